#include "render/sky.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/color.h"
#include "core/error.h"
#include "render/texture.h"

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
                                               int n_phi, double theta_max)
    : n_theta_(n_theta), n_phi_(n_phi) {
  INET_CHECK(n_theta > 0 && n_phi > 0 && values.size() == size_t(n_theta) * n_phi);
  INET_CHECK(theta_max > 0.0 && theta_max <= kPi);
  const double dtheta = theta_max / n_theta, dphi = 2.0 * kPi / n_phi;
  // the last edge exactly 0 (horizon) or -1 (south pole): no sliver of the cap left out
  double last = std::cos(theta_max);
  if (std::abs(last) < 1e-12) last = 0.0;
  if (last < -1.0 + 1e-12) last = -1.0;
  std::vector<double> cos_edge(n_theta + 1);
  for (int i = 0; i <= n_theta; ++i) cos_edge[i] = i == n_theta ? last : std::cos(i * dtheta);
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
  if (pdf_.empty()) return -1;
  // a whole-sphere table also takes the south pole itself (and z a rounding below -1)
  const float lo = cos_edge_.back();
  if (!(lo <= -1.f ? d.z() == d.z() : d.z() > lo)) return -1;
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

namespace {

/// The table frame swaps x and y of the map frame, so that the table's phi = atan2(y, x) is the
/// map's phi = 2 pi u, and table column j is image column j.
Vec3f swapXY(const Vec3f& v) {
  return {v.y(), v.x(), v.z()};
}

/// Linear RGB, 3 channels, every value finite and >= 0 (an HDR file may hold NaN or negatives).
ImageF sanitizedRgb(const ImageF& in) {
  INET_CHECK(in.width > 0 && in.height > 0 && (in.channels == 1 || in.channels == 3));
  ImageF out(in.width, in.height, 3);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = in.at(x, y, in.channels == 1 ? 0 : c);
        out.at(x, y, c) = std::isfinite(v) && v > 0.f ? v : 0.f;
      }
  return out;
}

}  // namespace

EnvMapSkyLight::EnvMapSkyLight(const Light& light, const std::string& where)
    : EnvMapSkyLight(Texture::load(light.envmap.path, TextureEncoding::Srgb, where,
                                   "lights['" + light.name + "'].file")
                         .level(0),
                     light.envmap_rotation, light.intensity) {}

EnvMapSkyLight::EnvMapSkyLight(ImageF image, const Mat3& rotation, float scale)
    : image_(sanitizedRgb(image)), R_world_map_(rotation.cast<float>()), scale_(scale) {
  build();
}

Eigen::Vector2f EnvMapSkyLight::directionToUv(const Vec3f& d) {
  float u = std::atan2(d.x(), d.y()) / (2.f * static_cast<float>(kPi));
  if (u < 0.f) u += 1.f;
  const float v = std::acos(std::clamp(d.z(), -1.f, 1.f)) / static_cast<float>(kPi);
  return {u, v};
}

Vec3f EnvMapSkyLight::uvToDirection(const Eigen::Vector2f& uv) {
  const float phi = 2.f * static_cast<float>(kPi) * uv.x(), theta = static_cast<float>(kPi) * uv.y();
  const float s = std::sin(theta);
  return {std::sin(phi) * s, std::cos(phi) * s, std::cos(theta)};
}

Vec3f EnvMapSkyLight::texel(int x, int y) const {
  const float* p = image_.pixel(x, y);
  return {p[0], p[1], p[2]};
}

void EnvMapSkyLight::build() {
  const int W = image_.width, H = image_.height;
  std::vector<double> lum(size_t(W) * H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) lum[size_t(y) * W + x] = luminance(texel(x, y));
  std::vector<double> bound(lum.size(), 0.0);
  double integral = 0.0, peak = 0.0;
  const double dphi = 2.0 * kPi / W;
  for (int y = 0; y < H; ++y) {
    const double omega = (std::cos(y * kPi / H) - std::cos((y + 1) * kPi / H)) * dphi;
    for (int x = 0; x < W; ++x) {
      double m = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int yy = std::clamp(y + dy, 0, H - 1), xx = ((x + dx) % W + W) % W;
          m = std::max(m, lum[size_t(yy) * W + xx]);
        }
      bound[size_t(y) * W + x] = m;
      peak = std::max(peak, m);
      integral += lum[size_t(y) * W + x] * omega;
    }
  }
  luminance_integral_ = integral * scale_;
  if (peak > 0.0) table_ = HemisphereDistribution(bound, H, W, kPi);
}

Vec3f EnvMapSkyLight::radiance(const Vec3f& d) const {
  const Eigen::Vector2f uv = directionToUv(R_world_map_.transpose() * d);
  if (!uv.allFinite()) return Vec3f::Zero();
  const int W = image_.width, H = image_.height;
  // texel centres at ((x + 0.5) / W, (y + 0.5) / H): repeat in u, clamp in v
  const float fx = uv.x() * W - 0.5f, fy = uv.y() * H - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = ((static_cast<int>(x0f) % W) + W) % W, x1 = (x0 + 1) % W;
  const int y0 = std::clamp(static_cast<int>(y0f), 0, H - 1);
  const int y1 = std::clamp(static_cast<int>(y0f) + 1, 0, H - 1);
  const Vec3f top = (1.f - tx) * texel(x0, y0) + tx * texel(x1, y0);
  const Vec3f bottom = (1.f - tx) * texel(x0, y1) + tx * texel(x1, y1);
  return scale_ * ((1.f - ty) * top + ty * bottom);
}

float EnvMapSkyLight::pdf(const Vec3f& d) const {
  return table_.pdf(swapXY(R_world_map_.transpose() * d));
}

bool EnvMapSkyLight::sample(const Eigen::Vector2f& u, Vec3f& wi, Vec3f& radiance,
                            float& pdf) const {
  Vec3f t;
  if (!table_.sample(u, t, pdf)) return false;
  wi = (R_world_map_ * swapXY(t)).normalized();
  pdf = this->pdf(wi);  // of the world direction itself, so that it equals pdf(wi) exactly
  radiance = this->radiance(wi);
  return pdf > 0.f;
}

}  // namespace inet
