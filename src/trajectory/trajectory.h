#pragma once
// A camera trajectory: timestamped poses T_world_camera (OpenCV camera axes), strictly increasing
// int64 nanosecond timestamps.
#include <string>
#include <vector>

#include "core/pose.h"

namespace inet {

struct TimedPose {
  TimeNs t_ns = 0;
  Pose T_world_camera;
};

struct Trajectory {
  std::vector<TimedPose> poses;
  size_t size() const { return poses.size(); }
  bool empty() const { return poses.empty(); }
  /// Linear velocity of the camera centre in the world frame at pose k (central difference,
  /// one-sided at the ends; zero for a single pose), m/s.
  Vec3 velocityWorld(size_t k) const;
  /// The pose at t_ns (interpolatePoseAt: linear in position, shortest-arc slerp in rotation,
  /// held at the ends). Needs a non-empty trajectory.
  Pose poseAt(TimeNs t_ns) const;
};

/// Reads a TUM trajectory (`timestamp tx ty tz qx qy qz qw`, seconds, '#' comments; commas and
/// tabs count as spaces). Throws InputError naming the file and line for a malformed line, a
/// non-unit quaternion (|q| off by > 1e-3), non-increasing timestamps, or an empty file.
Trajectory readTumTrajectory(const std::string& path);
/// The same rules on text in memory; `path` only names the source in error messages.
Trajectory parseTumTrajectory(const std::string& text, const std::string& path);
/// Parses seconds text such as "1305031102.175304" to exact nanoseconds (no double rounding).
/// Returns false if `s` is not a plain decimal number.
bool parseSecondsToNs(const std::string& s, TimeNs& out);
/// TUM text with 9 decimals, `# timestamp tx ty tz qx qy qz qw` header.
std::string formatTumTrajectory(const Trajectory& traj, const std::string& comment);

}  // namespace inet
