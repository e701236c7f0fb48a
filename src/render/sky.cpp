#include "render/sky.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/color.h"
#include "core/error.h"

namespace inet {
namespace {

constexpr double kPi = 3.14159265358979323846;


// The importance-sampling grid: 1.4 degrees square at the horizon, fine enough for the
// circumsolar peak (its Perez term falls as exp(D gamma), D about -2 per radian).
constexpr int kTheta = 64, kPhi = 256, kSub = 2;

}  // namespace

double preethamZenithLuminance(double turbidity, double theta_sun) {
  const double T = turbidity;
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * theta_sun);
  return (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
}

Eigen::Vector2d preethamZenithChromaticity(double turbidity, double theta_sun) {
  // Appendix A.2: x_z = [T^2 T 1] M_x [theta_s^3 theta_s^2 theta_s 1]^T, likewise y_z.
  const double T = turbidity, t = theta_sun;
  const Eigen::Vector3d tv(T * T, T, 1.0);
  const Eigen::Vector4d sv(t * t * t, t * t, t, 1.0);
  Eigen::Matrix<double, 3, 4> mx, my;
  mx << 0.00166, -0.00375, 0.00209, 0.0,  //
      -0.02903, 0.06377, -0.03202, 0.00394, 0.11693, -0.21196, 0.06052, 0.25886;
  my << 0.00275, -0.00610, 0.00317, 0.0,  //
      -0.04214, 0.08970, -0.04153, 0.00516, 0.15346, -0.26756, 0.06670, 0.26688;
  return {tv.dot(mx * sv), tv.dot(my * sv)};
}

Eigen::Vector3d xyYToLinearSrgb(double x, double y, double Y) {
  if (y <= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d xyz(x / y * Y, Y, (1.0 - x - y) / y * Y);
  // IEC 61966-2-1 (sRGB): XYZ (D65) -> linear RGB with Rec. 709 primaries
  Eigen::Matrix3d m;
  m << 3.2404542, -1.5371385, -0.4985314,  //
      -0.9692660, 1.8760108, 0.0415560,    //
      0.0556434, -0.2040259, 1.0572252;
  return (m * xyz).cwiseMax(0.0);
}

double PreethamSky::Perez::operator()(double cos_theta, double gamma, double cos_gamma) const {
  return (1.0 + A * std::exp(B / cos_theta)) *
         (1.0 + C * std::exp(D * gamma) + E * cos_gamma * cos_gamma);
}

PreethamSky::PreethamSky(double turbidity, const Vec3& sun_direction)
    : to_sun_(-sun_direction.normalized()) {
  INET_CHECK(turbidity >= 2.0 && turbidity <= 10.0);
  INET_CHECK(to_sun_.z() > 0.0);
  const double T = turbidity;
  // Appendix A.2: the Perez coefficients of Y, x and y, each linear in T
  perez_[0] = {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
               -0.0670 * T + 0.3703};
  perez_[1] = {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125,
               -0.0641 * T - 0.8989, -0.0033 * T + 0.0452};
  perez_[2] = {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102,
               -0.0441 * T - 1.6537, -0.0109 * T + 0.0529};
  const double theta_s = std::acos(std::min(to_sun_.z(), 1.0));
  const Eigen::Vector2d xy_z = preethamZenithChromaticity(T, theta_s);
  const double zenith[3] = {preethamZenithLuminance(T, theta_s), xy_z.x(), xy_z.y()};
  // the zenith itself: theta = 0, gamma = theta_s
  for (int k = 0; k < 3; ++k) scale_[k] = zenith[k] / perez_[k](1.0, theta_s, std::cos(theta_s));
}

Eigen::Vector3d PreethamSky::xyY(const Vec3& d) const {
  const double cos_gamma = std::clamp(d.dot(to_sun_), -1.0, 1.0);
  const double gamma = std::acos(cos_gamma);
  const double cos_theta = d.z();
  return {scale_[1] * perez_[1](cos_theta, gamma, cos_gamma),
          scale_[2] * perez_[2](cos_theta, gamma, cos_gamma),
          scale_[0] * perez_[0](cos_theta, gamma, cos_gamma)};
}

Eigen::Vector3d PreethamSky::rgb(const Vec3& d) const {
  if (!(d.z() > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d v = xyY(d);
  return xyYToLinearSrgb(v.x(), v.y(), v.z());
}

HemisphereDistribution::HemisphereDistribution(const std::vector<double>& values, int n_theta,
                                               int n_phi)
    : n_theta_(n_theta), n_phi_(n_phi) {
  INET_CHECK(n_theta > 0 && n_phi > 0 && values.size() == size_t(n_theta) * n_phi);
  const double dtheta = 0.5 * kPi / n_theta, dphi = 2.0 * kPi / n_phi;
  std::vector<double> cos_edge(n_theta + 1);
  for (int i = 0; i <= n_theta; ++i) cos_edge[i] = i == n_theta ? 0.0 : std::cos(i * dtheta);
  std::vector<double> row_mass(n_theta, 0.0);
  double total = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    double row = 0.0;
    for (int j = 0; j < n_phi; ++j) {
      INET_CHECK(values[i * n_phi + j] >= 0.0);
      row += values[i * n_phi + j];
    }
    row_mass[i] = row * (cos_edge[i] - cos_edge[i + 1]) * dphi;  // sum of f x solid angle
    total += row_mass[i];
  }
  INET_CHECK(total > 0.0);
  cos_edge_.assign(cos_edge.begin(), cos_edge.end());
  pdf_.resize(values.size());
  row_cdf_.resize(n_theta);
  column_cdf_.resize(values.size());
  double acc = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    acc += row_mass[i];
    row_cdf_[i] = static_cast<float>(acc / total);
    double row = 0.0, row_acc = 0.0;
    for (int j = 0; j < n_phi; ++j) row += values[i * n_phi + j];
    for (int j = 0; j < n_phi; ++j) {
      pdf_[i * n_phi + j] = static_cast<float>(values[i * n_phi + j] / total);
      row_acc += values[i * n_phi + j];
      column_cdf_[i * n_phi + j] = row > 0.0 ? static_cast<float>(row_acc / row) : 1.f;
    }
    column_cdf_[i * n_phi + n_phi - 1] = 1.f;
  }
  row_cdf_.back() = 1.f;
}

namespace {

/// Index of the interval of cdf (ascending, last = 1) holding u, and u's position in it, [0, 1].
int pickInterval(const float* cdf, int n, float u, float& t) {
  int i = static_cast<int>(std::upper_bound(cdf, cdf + n, u) - cdf);
  i = std::min(i, n - 1);
  while (i > 0 && cdf[i] == cdf[i - 1]) --i;  // never an empty interval
  const float lo = i > 0 ? cdf[i - 1] : 0.f, width = cdf[i] - lo;
  t = width > 0.f ? std::clamp((u - lo) / width, 0.f, 1.f) : 0.5f;
  return i;
}

}  // namespace

bool HemisphereDistribution::sample(const Eigen::Vector2f& u, Vec3f& wi, float& pdf) const {
  if (pdf_.empty()) return false;
  float t_row, t_col;
  const int i = pickInterval(row_cdf_.data(), n_theta_, u.x(), t_row);
  const int j = pickInterval(column_cdf_.data() + size_t(i) * n_phi_, n_phi_, u.y(), t_col);
  // uniform in solid angle inside the cell: cos theta linear in t_row, phi linear in t_col
  const float cos_t = cos_edge_[i] + t_row * (cos_edge_[i + 1] - cos_edge_[i]);
  const float sin_t = std::sqrt(std::max(0.f, 1.f - cos_t * cos_t));
  const float phi = (static_cast<float>(j) + t_col) * (2.f * static_cast<float>(kPi) / n_phi_);
  wi = Vec3f(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
  // the pdf of the cell the direction lands in, so that it equals pdf(wi) exactly (a direction
  // on a cell edge may round into the neighbour)
  pdf = this->pdf(wi);
  return pdf > 0.f;
}

int HemisphereDistribution::cell(const Vec3f& d) const {
  if (!(d.z() > 0.f) || pdf_.empty()) return -1;
  // row i holds cos_edge[i + 1] <= z < cos_edge[i] (the edges fall from 1 to 0)
  const auto first_below =
      std::lower_bound(cos_edge_.begin() + 1, cos_edge_.end(), d.z(), std::greater<float>());
  const int i = std::clamp(static_cast<int>(first_below - cos_edge_.begin()) - 1, 0, n_theta_ - 1);
  float phi = std::atan2(d.y(), d.x());
  if (phi < 0.f) phi += 2.f * static_cast<float>(kPi);
  const int j =
      std::clamp(static_cast<int>(phi * (n_phi_ / (2.f * static_cast<float>(kPi)))), 0, n_phi_ - 1);
  return i * n_phi_ + j;
}

float HemisphereDistribution::pdf(const Vec3f& d) const {
  const int c = cell(d);
  return c < 0 ? 0.f : pdf_[c];
}

PreethamSkyLight::PreethamSkyLight(const Light& light) : model_(light.turbidity, light.direction) {
  // Luminance on a kSub-times finer grid: the cells' mean for the table, and the integrals
  // E = int Y cos dw (normalisation) and int Y dw (power), with each point weighted by the exact
  // (cosine-weighted) solid angle of its sub-cell.
  const int nt = kTheta * kSub, np = kPhi * kSub;
  const double dtheta = 0.5 * kPi / nt, dphi = 2.0 * kPi / np;
  std::vector<double> cells(size_t(kTheta) * kPhi, 0.0);
  double irradiance = 0.0, radiance_integral = 0.0;
  for (int a = 0; a < nt; ++a) {
    const double t0 = a * dtheta, t1 = (a + 1) * dtheta, theta = 0.5 * (t0 + t1);
    const double c0 = std::cos(t0), c1 = a + 1 == nt ? 0.0 : std::cos(t1);
    const double omega = (c0 - c1) * dphi, omega_cos = 0.5 * (c0 * c0 - c1 * c1) * dphi;
    for (int b = 0; b < np; ++b) {
      const double phi = (b + 0.5) * dphi;
      const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      const double y = luminance(model_.rgb(d));
      cells[size_t(a / kSub) * kPhi + b / kSub] += y / (kSub * kSub);
      irradiance += y * omega_cos;
      radiance_integral += y * omega;
    }
  }
  INET_CHECK(irradiance > 0.0);
  const double floor = 1e-3 * radiance_integral / (2.0 * kPi);  // 0.1 % of the mean radiance
  for (double& c : cells) c += floor;
  table_ = HemisphereDistribution(cells, kTheta, kPhi);
  scale_ = light.intensity / irradiance;
  luminance_integral_ = radiance_integral * scale_;
}

Vec3f PreethamSkyLight::radiance(const Vec3f& d) const {
  return (model_.rgb(d.cast<double>()) * scale_).cast<float>();
}

bool PreethamSkyLight::sample(const Eigen::Vector2f& u, Vec3f& wi, Vec3f& radiance,
                              float& pdf) const {
  if (!table_.sample(u, wi, pdf)) return false;
  radiance = this->radiance(wi);
  return true;
}

}  // namespace inet
