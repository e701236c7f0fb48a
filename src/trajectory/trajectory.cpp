#include "trajectory/trajectory.h"

#include <cmath>
#include <sstream>

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

bool parseSecondsToNs(const std::string& s, TimeNs& out) {
  if (s.empty()) return false;
  size_t i = 0;
  bool neg = false;
  if (s[0] == '-' || s[0] == '+') {
    neg = s[0] == '-';
    i = 1;
  }
  int64_t whole = 0, frac = 0;
  int frac_digits = 0, int_digits = 0;
  for (; i < s.size() && s[i] != '.'; ++i) {
    if (s[i] < '0' || s[i] > '9' || int_digits > 10) return false;
    whole = whole * 10 + (s[i] - '0');
    ++int_digits;
  }
  if (i < s.size()) {
    for (++i; i < s.size(); ++i) {
      if (s[i] < '0' || s[i] > '9') return false;
      if (frac_digits < 9) {
        frac = frac * 10 + (s[i] - '0');
        ++frac_digits;
      }
    }
  }
  if (int_digits == 0 && frac_digits == 0) return false;
  for (int d = frac_digits; d < 9; ++d) frac *= 10;
  out = whole * 1000000000LL + frac;
  if (neg) out = -out;
  return true;
}

Trajectory readTumTrajectory(const std::string& path) {
  return parseTumTrajectory(readTextFile(path), path);
}

Trajectory parseTumTrajectory(const std::string& text, const std::string& path) {
  Trajectory traj;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::vector<std::string> tok;
    std::string t;
    while (fields >> t) tok.push_back(t);
    std::string where = fmt::format("line {}", line_no);
    if (tok.size() != 8)
      throw InputError(
          path, where,
          fmt::format("expected 8 fields 'timestamp tx ty tz qx qy qz qw', found {}", tok.size()));
    TimedPose p;
    if (!parseSecondsToNs(tok[0], p.t_ns))
      throw InputError(path, where, "timestamp '" + tok[0] + "' is not a number of seconds");
    double v[7];
    for (int k = 0; k < 7; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(tok[k + 1].c_str(), &end);
      if (end == tok[k + 1].c_str() || *end != '\0' || !std::isfinite(v[k]))
        throw InputError(
            path, where,
            "field " + std::to_string(k + 2) + " '" + tok[k + 1] + "' is not a finite number");
    }
    p.T_world_camera.t = Vec3(v[0], v[1], v[2]);
    Quat q(v[6], v[3], v[4], v[5]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw InputError(path, where, fmt::format("quaternion norm {:.6f} is not 1", q.norm()));
    p.T_world_camera.q = q.normalized();
    if (!traj.poses.empty() && p.t_ns <= traj.poses.back().t_ns)
      throw InputError(path, where,
                       "timestamps must increase strictly (" + tok[0] + " after " +
                           nsToSecondsString(traj.poses.back().t_ns) + ")");
    traj.poses.push_back(p);
  }
  if (traj.empty()) throw InputError(path, "", "trajectory has no poses");
  return traj;
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
