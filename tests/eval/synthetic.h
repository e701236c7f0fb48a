#pragma once
// Test trajectories for the eval tests: a closed-form camera path and helpers to transform and
// perturb it, so expected errors are known without running the code under test.
#include <cmath>
#include <random>

#include "trajectory/trajectory.h"

namespace inet::test {

/// n poses at `rate_hz` from t0_ns: a helix (radius 2 m, 0.5 m rise per turn) with the camera
/// yawing along the path and nodding in pitch, so positions span 3D and rotations all axes.
inline Trajectory helixTrajectory(int n, double rate_hz = 30, TimeNs t0_ns = 1'000'000'000) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    const double s = k / rate_hz;
    const double a = 0.4 * s;
    TimedPose p;
    p.t_ns = t0_ns + static_cast<TimeNs>(std::llround(k * 1e9 / rate_hz));
    p.T_world_camera.t = Vec3(2 * std::cos(a), 2 * std::sin(a), 1.2 + 0.08 * a);
    p.T_world_camera.q = Quat(Eigen::AngleAxisd(a + M_PI / 2, Vec3::UnitZ())) *
                         Quat(Eigen::AngleAxisd(0.2 * std::sin(1.3 * s), Vec3::UnitX()));
    t.poses.push_back(p);
  }
  return t;
}

/// Every pose moved by T (p -> T p, orientation R_T R), stamps unchanged.
inline Trajectory transformed(const Trajectory& in, const Pose& T, double scale = 1.0) {
  Trajectory out = in;
  for (auto& p : out.poses) {
    p.T_world_camera.t = scale * (T.q * p.T_world_camera.t) + T.t;
    p.T_world_camera.q = T.q * p.T_world_camera.q;
  }
  return out;
}

inline Pose somePose() {
  Pose T;
  T.q = Quat(Eigen::AngleAxisd(0.7, Vec3(0.3, -0.5, 0.8).normalized()));
  T.t = Vec3(4.0, -1.5, 0.25);
  return T;
}

}  // namespace inet::test
