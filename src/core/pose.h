#pragma once
// Rigid poses and time. Names carry frames (STYLE.md 1.8): T_a_b maps b-coordinates into a.
// World: right-handed, Z up, metres. Camera: OpenCV (x right, y down, z forward).
// Time is int64 nanoseconds everywhere; seconds only appear when a text format asks for them.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

namespace inet {

using TimeNs = int64_t;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Quat = Eigen::Quaterniond;

/// A rigid transform T_a_b: p_a = R * p_b + t.
struct Pose {
  Quat q = Quat::Identity();
  Vec3 t = Vec3::Zero();

  Mat3 rotation() const { return q.toRotationMatrix(); }
  Mat4 matrix() const;
  Vec3 operator*(const Vec3& p) const { return q * p + t; }
  Pose operator*(const Pose& o) const { return {q * o.q, q * o.t + t}; }
  Pose inverse() const;
  static Pose fromMatrix(const Mat4& m);
  /// Camera pose T_world_camera (OpenCV axes) looking from `eye` at `target` with `up` roughly
  /// opposite to the image's y axis.
  static Pose lookAt(const Vec3& eye, const Vec3& target, const Vec3& up);
  std::string toString() const;
};

/// Quaternion with w >= 0 (consumers treat q and -q alike; a fixed sign keeps files diffable).
Quat canonicalQuat(const Quat& q);

/// Seconds with 9 decimals from nanoseconds, exact (no floating point round trip).
std::string nsToSecondsString(TimeNs t_ns, int decimals = 9);

}  // namespace inet
