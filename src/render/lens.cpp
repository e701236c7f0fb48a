#include "render/lens.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "core/error.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;
// Angles at the edge of a model's range may overshoot it by rounding (e.g. u = 0 of the default
// panorama gives lon = -pi (1 + 1e-16)); such points still count as inside.
constexpr double kAngleSlack = 1e-12;

struct LensTypeEntry {
  LensType type;
  const char* name;
};
constexpr LensTypeEntry kLensTypes[] = {{LensType::Pinhole, "pinhole"},
                                        {LensType::ThinLens, "thin_lens"},
                                        {LensType::Fisheye, "fisheye"},
                                        {LensType::Panorama, "panorama"}};

/// Brown-Conrady forward model on normalised coordinates (OpenCV's projectPoints), with the
/// Jacobian d(distorted)/d(undistorted); it is symmetric, so J01 == J10.
struct Distorted {
  Eigen::Vector2d m;
  double j00, j01, j11;
};
Distorted distort(const LensModel& L, double x, double y) {
  const double r2 = x * x + y * y;
  const double g = 1 + r2 * (L.k1 + r2 * (L.k2 + r2 * L.k3));
  const double dg = L.k1 + r2 * (2 * L.k2 + 3 * r2 * L.k3);  // dg / d(r2)
  Distorted d;
  d.m.x() = x * g + 2 * L.p1 * x * y + L.p2 * (r2 + 2 * x * x);
  d.m.y() = y * g + L.p1 * (r2 + 2 * y * y) + 2 * L.p2 * x * y;
  d.j00 = g + 2 * x * x * dg + 2 * L.p1 * y + 6 * L.p2 * x;
  d.j01 = 2 * x * y * dg + 2 * L.p1 * x + 2 * L.p2 * y;
  d.j11 = g + 2 * y * y * dg + 6 * L.p1 * y + 2 * L.p2 * x;
  return d;
}

/// True if the radial image radius r g(r^2) strictly increases on [0, sqrt(s_max)], i.e.
/// q(s) = d(r g)/dr = 1 + 3 k1 s + 5 k2 s^2 + 7 k3 s^3 > 0 on [0, s_max] (s = r^2). A cubic is
/// positive on an interval iff it is at both ends and at its interior critical points.
bool radialMonotonic(const LensModel& L, double s_max) {
  auto q = [&](double s) { return 1 + s * (3 * L.k1 + s * (5 * L.k2 + s * 7 * L.k3)); };
  if (!(q(s_max) > 0)) return false;
  // q'(s) = a s^2 + b s + c
  const double a = 21 * L.k3, b = 10 * L.k2, c = 3 * L.k1;
  auto inside = [&](double s) { return s > 0 && s < s_max; };
  if (a == 0) {
    if (b != 0 && inside(-c / b) && !(q(-c / b) > 0)) return false;
    return true;
  }
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return true;
  // numerically stable roots of a s^2 + b s + c
  const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  for (double s : {h / a, h != 0 ? c / h : 0.0})
    if (inside(s) && !(q(s) > 0)) return false;
  return true;
}

/// Shirley & Chiu (1997) concentric map of [0,1)^2 onto the unit disk: squares to rings, so it
/// preserves area (uniform in, uniform out) and stratification.
Eigen::Vector2d concentricDisk(const Eigen::Vector2d& s) {
  const double a = 2 * s.x() - 1, b = 2 * s.y() - 1;
  if (a == 0 && b == 0) return {0, 0};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = (kPi / 4) * (b / a);
  } else {
    r = b;
    phi = kPi / 2 - (kPi / 4) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

/// Undistorted pinhole direction (x, y, 1) through (u, v).
bool pinholeDir(const LensModel& L, double u, double v, Eigen::Vector3d& dir) {
  // same expression as CameraIntrinsics::rayCamera, so the undistorted case matches it exactly
  const double mx = (u - L.K.cx) / L.K.fx, my = (v - L.K.cy) / L.K.fy;
  if (!L.hasDistortion()) {
    dir = {mx, my, 1.0};
    return true;
  }
  Eigen::Vector2d xy;
  if (!undistortNormalised(L, {mx, my}, xy)) return false;
  dir = {xy.x(), xy.y(), 1.0};
  return true;
}

double halfFovRad(const LensModel& L) {
  return L.fisheye_fov_deg * (kPi / 360);
}

}  // namespace

bool undistortNormalised(const LensModel& L, const Eigen::Vector2d& m, Eigen::Vector2d& xy) {
  const double tol = 1e-14 * (1 + m.norm());
  Eigen::Vector2d p = m;
  Distorted d = distort(L, p.x(), p.y());
  double err = (d.m - m).norm();
  for (int it = 0; it < 100 && err > tol; ++it) {
    const double det = d.j00 * d.j11 - d.j01 * d.j01;
    if (!(std::abs(det) > 1e-300)) return false;
    const Eigen::Vector2d r = m - d.m;
    const Eigen::Vector2d step((d.j11 * r.x() - d.j01 * r.y()) / det,
                               (d.j00 * r.y() - d.j01 * r.x()) / det);
    // backtrack until the residual decreases: keeps Newton from jumping across a fold
    double scale = 1;
    for (int k = 0; k < 40; ++k, scale *= 0.5) {
      Distorted trial = distort(L, p.x() + scale * step.x(), p.y() + scale * step.y());
      double trial_err = (trial.m - m).norm();
      if (trial_err < err) {
        p += scale * step;
        d = trial;
        err = trial_err;
        break;
      }
      if (k == 39) return false;  // no descent: stuck at a local minimum of the residual
    }
  }
  if (!(err <= tol)) return false;
  if (!(d.j00 * d.j11 - d.j01 * d.j01 > 0)) return false;
  if (!radialMonotonic(L, p.squaredNorm())) return false;
  xy = p;
  return true;
}

Eigen::Vector2d distortNormalised(const LensModel& L, const Eigen::Vector2d& xy,
                                  Eigen::Matrix2d* J) {
  Distorted d = distort(L, xy.x(), xy.y());
  if (J) *J << d.j00, d.j01, d.j01, d.j11;
  return d.m;
}

const char* lensTypeName(LensType type) {
  for (const auto& e : kLensTypes)
    if (e.type == type) return e.name;
  return "unknown";
}

LensType parseLensType(const std::string& name, const std::string& where,
                       const std::string& field) {
  std::string valid;
  for (const auto& e : kLensTypes) {
    if (name == e.name) return e.type;
    valid += valid.empty() ? e.name : std::string(", ") + e.name;
  }
  throw InputError(where, field, fmt::format("unknown lens '{}' (valid: {})", name, valid));
}

LensModel LensModel::fisheye(int size, double fov_deg) {
  LensModel L;
  L.type = LensType::Fisheye;
  L.fisheye_fov_deg = fov_deg;
  L.K.width = L.K.height = size;
  L.K.fx = L.K.fy = size / (fov_deg * kPi / 180);
  L.K.cx = L.K.cy = size / 2.0;
  return L;
}

LensModel LensModel::panorama(int width, int height) {
  LensModel L;
  L.type = LensType::Panorama;
  L.K.width = width;
  L.K.height = height;
  L.K.fx = width / (2 * kPi);
  L.K.fy = height / kPi;
  L.K.cx = width / 2.0;
  L.K.cy = height / 2.0;
  return L;
}

LensModel LensModel::pinhole(const CameraIntrinsics& K) {
  LensModel L;
  L.K = K;
  return L;
}

LensModel LensModel::thinLens(const CameraIntrinsics& K, double aperture_radius_m,
                              double focus_distance_m) {
  LensModel L;
  L.type = LensType::ThinLens;
  L.K = K;
  L.aperture_radius_m = aperture_radius_m;
  L.focus_distance_m = focus_distance_m;
  return L;
}

void LensModel::validate(const std::string& where) const {
  if (std::string(lensTypeName(type)) == "unknown")
    throw InputError(where, "type", fmt::format("invalid value {}", static_cast<int>(type)));
  if (type == LensType::Fisheye && !(fisheye_fov_deg > 0 && fisheye_fov_deg <= 360))
    throw InputError(where, "fisheye_fov_deg",
                     fmt::format("{} is outside (0, 360]", fisheye_fov_deg));
  K.validate(where);
  auto finite = [&](double value, const char* field) {
    if (!std::isfinite(value)) throw InputError(where, field, "must be finite");
  };
  const bool perspective = type == LensType::Pinhole || type == LensType::ThinLens;
  const std::pair<double, const char*> coeffs[] = {
      {k1, "k1"}, {k2, "k2"}, {p1, "p1"}, {p2, "p2"}, {k3, "k3"}};
  for (const auto& [value, field] : coeffs) {
    finite(value, field);
    if (value != 0 && !perspective)
      throw InputError(where, field,
                       fmt::format("distortion is only used by pinhole and thin_lens, not {}",
                                   lensTypeName(type)));
  }
  finite(aperture_radius_m, "aperture_radius_m");
  if (aperture_radius_m < 0) throw InputError(where, "aperture_radius_m", "must be >= 0");
  if (aperture_radius_m != 0 && type != LensType::ThinLens)
    throw InputError(where, "aperture_radius_m",
                     fmt::format("only used by thin_lens, not {}", lensTypeName(type)));
  if (type == LensType::ThinLens && !(focus_distance_m > 0 && std::isfinite(focus_distance_m)))
    throw InputError(where, "focus_distance_m", "must be > 0 and finite");
  if (perspective && hasDistortion()) {
    // For radial distortion the invertible region is a disk around the principal point (nearly
    // so with small tangential terms), so checking the border at every pixel edge covers the
    // whole image; a fold shows up first at the corners.
    const int w = K.width, h = K.height;
    Eigen::Vector3d d;
    auto check = [&](double u, double v) {
      if (!pinholeDir(*this, u, v, d))
        throw InputError(where, "k1..k3, p1, p2",
                         fmt::format("distortion cannot be inverted at image point ({}, {}): the "
                                     "polynomial folds over inside the image",
                                     u, v));
    };
    for (int i = 0; i <= w; ++i) {
      check(i, 0);
      check(i, h);
    }
    for (int j = 0; j <= h; ++j) {
      check(0, j);
      check(w, j);
    }
  }
}

std::string LensModel::toString() const {
  std::string s = fmt::format("Lens[{} {}", lensTypeName(type), K.toString());
  if (hasDistortion()) s += fmt::format(" k1={} k2={} p1={} p2={} k3={}", k1, k2, p1, p2, k3);
  if (type == LensType::ThinLens)
    s += fmt::format(" aperture_radius_m={} focus_distance_m={}", aperture_radius_m,
                     focus_distance_m);
  if (type == LensType::Fisheye) s += fmt::format(" fov_deg={}", fisheye_fov_deg);
  return s + "]";
}

bool generateRay(const LensModel& L, double u, double v, const Eigen::Vector2d& lens_uv,
                 CameraRay& out) {
  switch (L.type) {
    case LensType::Pinhole:
      out.origin.setZero();
      return pinholeDir(L, u, v, out.dir);
    case LensType::ThinLens: {
      Eigen::Vector3d d;
      if (!pinholeDir(L, u, v, d)) return false;
      if (L.aperture_radius_m == 0) {  // exactly the pinhole ray
        out.origin.setZero();
        out.dir = d;
        return true;
      }
      // P = F d lies on the focus plane; o + F (d - o/F) = P, and dir.z stays 1
      const Eigen::Vector2d o = L.aperture_radius_m * concentricDisk(lens_uv);
      out.origin = {o.x(), o.y(), 0.0};
      out.dir = {d.x() - o.x() / L.focus_distance_m, d.y() - o.y() / L.focus_distance_m, 1.0};
      return true;
    }
    case LensType::Fisheye: {
      const double mx = (u - L.K.cx) / L.K.fx, my = (v - L.K.cy) / L.K.fy;
      const double theta = std::hypot(mx, my);
      if (theta > halfFovRad(L) + kAngleSlack) return false;
      // sin(theta)/theta, with its series where the quotient loses precision
      const double s = theta < 1e-4 ? 1 - theta * theta / 6 : std::sin(theta) / theta;
      out.origin.setZero();
      out.dir = {s * mx, s * my, std::cos(theta)};
      return true;
    }
    case LensType::Panorama: {
      const double lon = (u - L.K.cx) / L.K.fx, lat = (v - L.K.cy) / L.K.fy;
      if (std::abs(lon) > kPi + kAngleSlack || std::abs(lat) > kPi / 2 + kAngleSlack) return false;
      const double c = std::cos(lat);
      out.origin.setZero();
      out.dir = {c * std::sin(lon), std::sin(lat), c * std::cos(lon)};
      return true;
    }
  }
  return false;
}

bool project(const LensModel& L, const Vec3& p, Eigen::Vector2d& uv) {
  switch (L.type) {
    case LensType::Pinhole:
    case LensType::ThinLens: {
      if (!(p.z() > 0)) return false;
      const double x = p.x() / p.z(), y = p.y() / p.z();
      Eigen::Vector2d m(x, y);
      if (L.hasDistortion()) {
        if (!radialMonotonic(L, x * x + y * y)) return false;
        m = distort(L, x, y).m;
      }
      uv = {L.K.fx * m.x() + L.K.cx, L.K.fy * m.y() + L.K.cy};
      return true;
    }
    case LensType::Fisheye: {
      const double r = std::hypot(p.x(), p.y());
      if (r == 0 && !(p.z() > 0)) return false;
      const double theta = std::atan2(r, p.z());
      if (theta > halfFovRad(L) + kAngleSlack) return false;
      const double s = r > 0 ? theta / r : 0;
      uv = {L.K.fx * s * p.x() + L.K.cx, L.K.fy * s * p.y() + L.K.cy};
      return true;
    }
    case LensType::Panorama: {
      if (p.isZero(0)) return false;
      double lon = std::atan2(p.x(), p.z());
      if (lon == kPi) lon = -kPi;  // keep the seam on the left edge: lon in [-pi, pi)
      const double lat = std::atan2(p.y(), std::hypot(p.x(), p.z()));
      uv = {L.K.fx * lon + L.K.cx, L.K.fy * lat + L.K.cy};
      return true;
    }
  }
  return false;
}

DepthKind groundTruthDepthKind(LensType type) {
  return (type == LensType::Pinhole || type == LensType::ThinLens) ? DepthKind::ZDepth
                                                                   : DepthKind::RayDistance;
}

double groundTruthDepth(const LensModel& L, const Vec3& p_cam) {
  return groundTruthDepthKind(L.type) == DepthKind::ZDepth ? p_cam.z() : p_cam.norm();
}

double blurRadiusPx(const LensModel& L, double depth_m) {
  if (L.type != LensType::ThinLens) return 0;
  return L.K.fx * L.aperture_radius_m * std::abs(1 / depth_m - 1 / L.focus_distance_m);
}

OpenCvCamera toOpenCv(const LensModel& L) {
  OpenCvCamera c;
  c.width = L.K.width;
  c.height = L.K.height;
  c.fx = L.K.fx;
  c.fy = L.K.fy;
  c.cx = L.K.cxOpenCV();
  c.cy = L.K.cyOpenCV();
  switch (L.type) {
    case LensType::Pinhole:
    case LensType::ThinLens:
      c.model = "radtan";
      c.distortion = {L.k1, L.k2, L.p1, L.p2, L.k3};
      break;
    case LensType::Fisheye:
      c.model = "equidistant";
      c.distortion = {0, 0, 0, 0};
      break;
    case LensType::Panorama:
      c.model = "equirectangular";
      break;
  }
  return c;
}

}  // namespace inet
