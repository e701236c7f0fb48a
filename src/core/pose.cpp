#include "core/pose.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace inet {
namespace {

/// Spherical linear interpolation along the shorter arc. The angle comes from atan2 of the
/// chord lengths, accurate for tiny and for near-opposite rotations alike (acos of the dot
/// product loses half the digits near 1).
Quat slerpShortest(const Quat& a, Quat b, double alpha) {
  if (a.coeffs().dot(b.coeffs()) < 0) b.coeffs() = -b.coeffs();
  const double phi =
      2 * std::atan2((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
  double wa, wb;
  if (phi < 1e-9) {  // sin(k phi) / sin(phi) -> k; the normalisation below absorbs the rest
    wa = 1 - alpha;
    wb = alpha;
  } else {
    const double s = std::sin(phi);
    wa = std::sin((1 - alpha) * phi) / s;
    wb = std::sin(alpha * phi) / s;
  }
  Quat q;
  q.coeffs() = wa * a.coeffs() + wb * b.coeffs();
  return q.normalized();
}

}  // namespace

Pose interpolatePose(const Pose& a, TimeNs ta, const Pose& b, TimeNs tb, TimeNs t) {
  INET_CHECK_MSG(tb >= ta, fmt::format("interpolatePose: tb {} < ta {}", tb, ta));
  if (t == ta || tb == ta) return a;
  if (t == tb) return b;
  const double alpha = static_cast<double>(t - ta) / static_cast<double>(tb - ta);
  Pose p;
  p.t = (1 - alpha) * a.t + alpha * b.t;
  p.q = slerpShortest(a.q.normalized(), b.q.normalized(), alpha);
  return p;
}

Mat4 Pose::matrix() const {
  Mat4 m = Mat4::Identity();
  m.block<3, 3>(0, 0) = rotation();
  m.block<3, 1>(0, 3) = t;
  return m;
}

Pose Pose::inverse() const {
  Quat qi = q.conjugate();
  return {qi, -(qi * t)};
}

Pose Pose::fromMatrix(const Mat4& m) {
  Pose p;
  p.q = Quat(Mat3(m.block<3, 3>(0, 0))).normalized();
  p.t = m.block<3, 1>(0, 3);
  return p;
}

Pose Pose::lookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  Vec3 z = (target - eye).normalized();
  Vec3 x = z.cross(up);
  INET_CHECK_MSG(x.norm() > 1e-9, "lookAt: view direction parallel to up");
  x.normalize();
  Vec3 y = z.cross(x);  // image y points down, away from `up`
  Mat3 r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = z;
  return {Quat(r).normalized(), eye};
}

std::string Pose::toString() const {
  return fmt::format("Pose[t=({:.6f}, {:.6f}, {:.6f}) q(xyzw)=({:.6f}, {:.6f}, {:.6f}, {:.6f})]",
                     t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
}

Quat canonicalQuat(const Quat& q) {
  Quat n = q.normalized();
  if (n.w() < 0) n.coeffs() = -n.coeffs();
  return n;
}

std::string nsToSecondsString(TimeNs t_ns, int decimals) {
  INET_CHECK(decimals >= 0 && decimals <= 9);
  bool neg = t_ns < 0;
  uint64_t a = neg ? static_cast<uint64_t>(-(t_ns + 1)) + 1 : static_cast<uint64_t>(t_ns);
  uint64_t div = 1;
  for (int i = 0; i < 9 - decimals; ++i) div *= 10;
  // round half up at the requested precision
  uint64_t scaled = (a + div / 2) / div;
  uint64_t unit = 1;
  for (int i = 0; i < decimals; ++i) unit *= 10;
  std::string s = fmt::format("{}{}", neg ? "-" : "", scaled / unit);
  if (decimals > 0) s += fmt::format(".{:0{}}", scaled % unit, decimals);
  return s;
}

}  // namespace inet
