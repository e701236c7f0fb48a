#pragma once
// Analytic test motion shared by the spline and IMU tests: a camera that wanders in position and
// turns in yaw at 1.3 rad/s (so it looks level along world -Y, a rotation by exactly pi where a
// rotation-vector spline is singular, every 4.8 s) while rolling and pitching, so the rotation
// axis is never fixed and w_body differs from any single-axis derivative.
#include <cmath>
#include <filesystem>
#include <string>

#include "core/pose.h"
#include "trajectory/trajectory.h"

namespace inet::test {

inline Pose analyticPose(double t) {
  const Vec3 p(0.5 * std::sin(1.1 * t), 0.4 * std::cos(0.7 * t), 1.5 + 0.1 * std::sin(2.0 * t));
  // level OpenCV camera looking along world +X (z forward, y down), then yaw, pitch, roll wobble
  Mat3 base;
  base.col(0) = Vec3(0, -1, 0);
  base.col(1) = Vec3(0, 0, -1);
  base.col(2) = Vec3(1, 0, 0);
  const Quat q = Quat(Eigen::AngleAxisd(1.3 * t, Vec3::UnitZ())) *
                 Quat(Eigen::AngleAxisd(0.2 * std::sin(1.7 * t), Vec3::UnitY())) *
                 Quat(base) * Quat(Eigen::AngleAxisd(0.15 * std::cos(2.3 * t), Vec3::UnitZ()));
  return {q.normalized(), p};
}

/// Poses of analyticPose at t0 + k * dt, k = 0..n-1 (time in seconds from 0).
inline Trajectory analyticTrajectory(TimeNs dt_ns, int n) {
  Trajectory traj;
  for (int k = 0; k < n; ++k) {
    const TimeNs t = static_cast<TimeNs>(k) * dt_ns;
    traj.poses.push_back({t, analyticPose(static_cast<double>(t) * 1e-9)});
  }
  return traj;
}

/// The shared data folder (../shared), or "" when it is not there.
inline std::string sharedDir() {
  std::error_code ec;
  return std::filesystem::is_directory(INET_SHARED_DIR "/data", ec) ? INET_SHARED_DIR : "";
}

}  // namespace inet::test
