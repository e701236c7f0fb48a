#include "trajectory/trajectory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace inet {

Vec3 Trajectory::velocityWorld(size_t k) const {
  if (poses.size() < 2) return Vec3::Zero();
  size_t a = k == 0 ? 0 : k - 1;
  size_t b = k + 1 >= poses.size() ? poses.size() - 1 : k + 1;
  double dt = (poses[b].t_ns - poses[a].t_ns) * 1e-9;
  return (poses[b].T_world_camera.t - poses[a].T_world_camera.t) / dt;
}

Pose Trajectory::poseAt(TimeNs t_ns) const {
  INET_CHECK(!poses.empty());
  Pose out;
  interpolatePoseAt(poses, t_ns, out);
  return out;
}

bool parseScaledDecimal(const std::string& s, int scale_pow10, bool exact, int64_t& out) {
  size_t i = 0;
  bool neg = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
  std::string mantissa;  // every digit, the point removed
  int frac_digits = 0;
  bool point = false;
  for (; i < s.size(); ++i) {
    if (s[i] >= '0' && s[i] <= '9') {
      mantissa += s[i];
      frac_digits += point;
    } else if (s[i] == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (mantissa.empty()) return false;
  int64_t exponent = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool exp_neg = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) exp_neg = s[i++] == '-';
    if (i == s.size()) return false;
    for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) {
      exponent = exponent * 10 + (s[i] - '0');
      if (exponent > 100000) return false;
    }
    if (exp_neg) exponent = -exponent;
  }
  if (i != s.size()) return false;
  // value = mantissa * 10^p: shift the digit string, then cut at the point
  const int64_t p = exponent - frac_digits + scale_pow10;
  const size_t first = std::min(mantissa.find_first_not_of('0'), mantissa.size());
  mantissa.erase(0, first);
  std::string whole = mantissa;
  bool round_up = false;
  if (p >= 0) {
    if (!mantissa.empty()) whole.append(static_cast<size_t>(std::min<int64_t>(p, 40)), '0');
  } else {
    const size_t cut = static_cast<size_t>(std::min<int64_t>(-p, 100000));
    const std::string fraction = cut >= mantissa.size()
                                     ? std::string(cut - mantissa.size(), '0') + mantissa
                                     : mantissa.substr(mantissa.size() - cut);
    whole = cut >= mantissa.size() ? std::string() : mantissa.substr(0, mantissa.size() - cut);
    if (exact && fraction.find_first_not_of('0') != std::string::npos) return false;
    round_up = !fraction.empty() && fraction[0] >= '5';
  }
  if (whole.size() > 19) return false;
  uint64_t v = 0;
  for (char c : whole) v = v * 10 + static_cast<uint64_t>(c - '0');
  v += round_up;
  if (v > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) return false;
  out = neg ? -static_cast<int64_t>(v) : static_cast<int64_t>(v);
  return true;
}

bool parseSecondsToNs(const std::string& s, TimeNs& out) {
  return parseScaledDecimal(s, 9, false, out);
}

std::string TrajectoryReadReport::summary() const {
  std::vector<std::string> parts;
  if (repeated_stamps > 0)
    parts.push_back(fmt::format(
        "{} pose(s) repeat the stamp before them (first at line {}; {} with another pose) and "
        "were dropped: the first pose of each stamp is kept, as evo does",
        repeated_stamps, first_repeat_line, repeated_with_other_pose));
  if (nanosecond_stamps)
    parts.push_back("stamps of 16 or more digits were read as nanoseconds (as ORB-SLAM3 writes "
                    "EuRoC runs in TUM layout)");
  if (ignored_columns > 0)
    parts.push_back(fmt::format("{} column(s) after the pose on every line were ignored",
                                ignored_columns));
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

Trajectory readTumTrajectory(const std::string& path, TrajectoryReadReport* report) {
  return parseTumTrajectory(readTextFile(path), path, report);
}

std::string formatTumTrajectory(const Trajectory& traj, const std::string& comment) {
  std::string out = "# " + comment + "\n# timestamp tx ty tz qx qy qz qw\n";
  for (const auto& p : traj.poses) {
    Quat q = canonicalQuat(p.T_world_camera.q);
    const Vec3& t = p.T_world_camera.t;
    out += fmt::format("{} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f}\n",
                       nsToSecondsString(p.t_ns), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  }
  return out;
}

}  // namespace inet
