#pragma once
// Rigid poses and time. Names carry frames (STYLE.md 1.8): T_a_b maps b-coordinates into a.
// World: right-handed, Z up, metres. Camera: OpenCV (x right, y down, z forward).
// Time is int64 nanoseconds everywhere; seconds only appear when a text format asks for them.
#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <iterator>
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

/// Pose at time t between a (at ta) and b (at tb), ta < tb (or ta == tb, which returns a):
/// position linear in t, rotation by slerp along the shorter arc (q and -q are the same
/// rotation, so b is flipped when a.q . b.q < 0). Returns a exactly at ta and b exactly at tb;
/// extrapolates outside [ta, tb].
Pose interpolatePose(const Pose& a, TimeNs ta, const Pose& b, TimeNs tb, TimeNs t);

/// Pose at time t in a list sorted by strictly increasing time: any random-access container whose
/// elements have members t_ns and T_world_camera (e.g. Trajectory::poses). Interpolates between
/// the two neighbours of t (exact at a stored time). Returns false if the list is empty or t lies
/// outside [front, back]; out then holds the nearest end pose (held constant), if any.
template <class PoseList>
bool interpolatePoseAt(const PoseList& poses, TimeNs t, Pose& out) {
  if (poses.empty()) return false;
  const auto first = std::begin(poses), last = std::prev(std::end(poses));
  if (t <= first->t_ns || t >= last->t_ns) {
    out = t <= first->t_ns ? first->T_world_camera : last->T_world_camera;
    return t == first->t_ns || t == last->t_ns;
  }
  // first element with time > t; it exists and is not `first`, because front < t < back
  auto hi = std::upper_bound(first, last, t, [](TimeNs x, const auto& p) { return x < p.t_ns; });
  auto lo = std::prev(hi);
  out = interpolatePose(lo->T_world_camera, lo->t_ns, hi->T_world_camera, hi->t_ns, t);
  return true;
}

}  // namespace inet
