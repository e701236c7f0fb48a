#pragma once
// SO(3) helpers for the splines and the IMU: hat, Exp and Log (Rodrigues), with the small-angle
// series where the closed forms lose precision. Hat [x]x is the skew matrix, theta = |phi|.
#include <cmath>

#include "core/pose.h"

namespace inet::so3 {

inline Mat3 hat(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// Exp(phi) = I + sin(theta)/theta [phi]x + (1 - cos(theta))/theta^2 [phi]x^2, as a quaternion
/// (cos(theta/2), sin(theta/2) phi/theta).
inline Quat expQuat(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double w, s;  // s = sin(theta/2) / theta
  if (theta < 1e-4) {
    w = 1.0 - theta2 / 8.0;
    s = 0.5 - theta2 / 48.0;
  } else {
    w = std::cos(0.5 * theta);
    s = std::sin(0.5 * theta) / theta;
  }
  return Quat(w, s * phi.x(), s * phi.y(), s * phi.z());
}

/// Log(q): the rotation vector with theta in [0, pi] (q and -q give the same result).
inline Vec3 logQuat(const Quat& q_in) {
  Quat q = q_in;
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-8) return 2.0 * v / q.w();  // theta/sin(theta/2) -> 2/w for small angles
  // atan2 keeps full precision near 0 and near pi (acos does not)
  const double theta = 2.0 * std::atan2(s, q.w());
  return (theta / s) * v;
}

/// Rotation angle (rad, in [0, pi]) between two rotations.
inline double angleBetween(const Quat& a, const Quat& b) {
  return logQuat(a.conjugate() * b).norm();
}

}  // namespace inet::so3
