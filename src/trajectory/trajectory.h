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

/// What a reader did about the quirks of real files, for one warning line (not one per pose).
///
/// Repeated stamps: motion-capture ground truth repeats a stamp now and then, sometimes with a
/// different pose (TUM fr2/desk, lines 10862-10863). Every reader keeps the FIRST pose of a
/// repeated stamp and drops the others, as evo does (its association takes the first of equal
/// candidates, numpy.argmin); TUM's associate.py reads a file into a dict and so keeps the
/// last. Time that goes back is still an error: that file is out of order, not merely repeating.
struct TrajectoryReadReport {
  size_t repeated_stamps = 0;           ///< poses dropped: their stamp equals the one before
  size_t repeated_with_other_pose = 0;  ///< of those, how many had a different pose
  int first_repeat_line = 0;            ///< file line of the first dropped pose
  bool skipped_header = false;          ///< a first line of column names without '#'
  /// tum: stamps of 16 or more integer digits read as nanoseconds (ORB-SLAM3 writes EuRoC
  /// runs' nanosecond stamps into TUM-layout files: as seconds they would be 44 million years)
  bool nanosecond_stamps = false;
  size_t ignored_columns = 0;           ///< per line: columns after the pose (VINS, ov_eval)
  /// "" or one line, e.g. "2 poses repeat the stamp before them (first at line 10863; 1 with
  /// another pose) ...: the first pose of each stamp is kept"; findings joined by "; ".
  std::string summary() const;
};

/// Reads a TUM trajectory (`timestamp tx ty tz qx qy qz qw`, seconds, '#' comments; commas and
/// tabs count as spaces). Throws InputError naming the file and line for a malformed line, a
/// non-unit quaternion (|q| off by > 1e-3), time going back, or an empty file; repeated stamps
/// go to `report` (see TrajectoryReadReport).
Trajectory readTumTrajectory(const std::string& path, TrajectoryReadReport* report = nullptr);
/// The same rules on text in memory; `path` only names the source in error messages.
Trajectory parseTumTrajectory(const std::string& text, const std::string& path,
                              TrajectoryReadReport* report = nullptr);
/// A decimal number (optional sign; digits with an optional point; optional exponent
/// `e[+-]digits`, as C's printf %e and numpy.savetxt write) times 10^scale_pow10, as an
/// integer computed from the digits, never through a double, so every digit counts.
/// `exact`: a result with a fraction is refused; otherwise it is rounded half away from zero.
/// False for anything else (hex, inf, nan, stray characters) or a result outside int64.
bool parseScaledDecimal(const std::string& s, int scale_pow10, bool exact, int64_t& out);
/// Seconds text such as "1305031102.175304" or "1.403715529112143517e+09" to nanoseconds
/// (parseScaledDecimal with scale 9, rounded to the nearest ns).
bool parseSecondsToNs(const std::string& s, TimeNs& out);
/// TUM text with 9 decimals, `# timestamp tx ty tz qx qy qz qw` header.
std::string formatTumTrajectory(const Trajectory& traj, const std::string& comment);

}  // namespace inet
