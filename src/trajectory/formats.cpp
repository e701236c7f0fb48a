#include "trajectory/formats.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"

namespace inet {
namespace {

constexpr double kQuatNormTolerance = 1e-3;
constexpr const char* kTumComment =
    "interiornet trajectory: T_world_camera, OpenCV camera axes, world Z up";

// ---- conversions (derivations in formats.h) ----

/// ICL world -> ours (swap y and z); its own inverse.
Mat3 iclWorldToOurs() {
  Mat3 a;
  a << 1, 0, 0, 0, 0, 1, 0, 1, 0;
  return a;
}

/// ICL camera (y up) <-> OpenCV camera (y down); its own inverse.
Mat3 yFlip() {
  return Vec3(1, -1, 1).asDiagonal();
}

Pose iclToOurs(const Pose& T_icl) {
  const Mat3 a = iclWorldToOurs();
  return {Quat(a * T_icl.rotation() * yFlip()).normalized(), a * T_icl.t};
}

/// SceneNet world (y up) -> ours (z up): Rx(+90 deg).
Vec3 sceneNetToOurs(const Vec3& p) {
  return {p.x(), -p.z(), p.y()};
}
Vec3 oursToSceneNet(const Vec3& p) {
  return {p.x(), p.z(), -p.y()};
}

// ---- tokenising ----

constexpr char kByteOrderMark[] = "\xEF\xBB\xBF";

/// A line of column names ("timestamp tx ty ...", "timestamp,p_x,..."): it starts with a letter
/// and is not a SceneNet `time:`/`instance:` record.
bool isColumnNames(const std::string& line) {
  const size_t b = line.find_first_not_of(" \t");
  return b != std::string::npos && std::isalpha(static_cast<unsigned char>(line[b])) &&
         line.compare(b, 5, "time:") != 0 && line.compare(b, 9, "instance:") != 0;
}

/// Calls fn(line, line_no) for every line that is not blank and not a '#' comment, with a
/// leading UTF-8 byte-order mark (Windows editors) and a trailing '\r' removed. With `header`,
/// a first such line that starts with a letter is taken for column names written without '#'
/// (pandas.to_csv, spreadsheets) and skipped; a later one is the reader's error.
void forEachDataLine(const std::string& text, bool header, TrajectoryReadReport* report,
                     const std::function<void(const std::string&, int)>& fn) {
  size_t pos = text.rfind(kByteOrderMark, 0) == 0 ? 3 : 0;
  int line_no = 0;
  bool first = true;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t b = line.find_first_not_of(" \t");
    if (b == std::string::npos || line[b] == '#') continue;
    const bool was_first = std::exchange(first, false);
    if (header && was_first && isColumnNames(line)) {
      if (report) report->skipped_header = true;
      continue;
    }
    fn(line, line_no);
  }
}

/// Comma-separated fields with surrounding spaces removed (EuRoC writes ", " in its header).
std::vector<std::string> splitComma(const std::string& line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (true) {
    size_t j = line.find(',', i);
    std::string f = line.substr(i, j == std::string::npos ? std::string::npos : j - i);
    const size_t a = f.find_first_not_of(" \t"), b = f.find_last_not_of(" \t");
    out.push_back(a == std::string::npos ? std::string() : f.substr(a, b - a + 1));
    if (j == std::string::npos) break;
    i = j + 1;
  }
  return out;
}

/// splitComma without one empty field after a trailing comma (VINS ends its rows with ',').
std::vector<std::string> splitCsvRow(const std::string& line) {
  std::vector<std::string> tok = splitComma(line);
  if (tok.size() > 1 && tok.back().empty()) tok.pop_back();
  return tok;
}

/// A finite decimal number (optional sign, fraction, exponent). No hex, inf or nan.
bool parseNumber(const std::string& s, double& out) {
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  auto [ptr, ec] = std::from_chars(b, e, out, std::chars_format::general);
  return ec == std::errc() && ptr == e && std::isfinite(out);
}

bool isDigits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

/// A non-negative integer that fits int64, also in scientific notation as long as it is whole
/// ("1.403715529112143517e+18": numpy writes integer columns through '%.18e').
bool parseCount(const std::string& s, int64_t& out) {
  return !s.empty() && s[0] != '-' && s[0] != '+' && parseScaledDecimal(s, 0, true, out);
}

std::string lineRef(int line_no) {
  return fmt::format("line {}", line_no);
}

/// Parses tokens[first .. first+n) as numbers; InputError names the 1-based column.
void parseNumbers(const std::vector<std::string>& tok, size_t first, size_t n, double* out,
                  const std::string& path, int line_no) {
  for (size_t k = 0; k < n; ++k)
    if (!parseNumber(tok[first + k], out[k]))
      throw InputError(
          path, lineRef(line_no),
          fmt::format("column {} '{}' is not a finite number", first + k + 1, tok[first + k]));
}

/// A unit quaternion from (w, x, y, z), or InputError.
Quat unitQuat(double w, double x, double y, double z, const std::string& path, int line_no) {
  Quat q(w, x, y, z);
  if (std::abs(q.norm() - 1.0) > kQuatNormTolerance)
    throw InputError(path, lineRef(line_no),
                     fmt::format("quaternion norm {:.6f} is not 1", q.norm()));
  return q.normalized();
}

bool samePose(const Pose& a, const Pose& b) {
  return a.t == b.t && (a.q.coeffs() == b.q.coeffs() || a.q.coeffs() == -b.q.coeffs());
}

/// The poses of one file as a reader finds them: time must not go back; a repeated stamp keeps
/// the first pose (TrajectoryReadReport says why) and is counted.
class PoseCollector {
 public:
  PoseCollector(const std::string& path, TrajectoryReadReport* report)
      : path_(path), report_(report ? report : &own_) {
    *report_ = TrajectoryReadReport{};
  }
  TrajectoryReadReport* report() { return report_; }

  void add(TimeNs t_ns, const Pose& T_world_camera, int line_no) {
    if (!traj_.empty()) {
      const TimedPose& last = traj_.poses.back();
      if (t_ns == last.t_ns) {
        if (report_->repeated_stamps++ == 0) report_->first_repeat_line = line_no;
        report_->repeated_with_other_pose += !samePose(last.T_world_camera, T_world_camera);
        return;
      }
      if (t_ns < last.t_ns)
        throw InputError(path_, lineRef(line_no),
                         fmt::format("time goes back ({} s after {} s): stamps must increase "
                                     "(sort the file by time)",
                                     nsToSecondsString(t_ns), nsToSecondsString(last.t_ns)));
    }
    traj_.poses.push_back({t_ns, T_world_camera});
  }

  Trajectory finish() {
    if (traj_.empty()) throw InputError(path_, "", "trajectory has no poses");
    return std::move(traj_);
  }

 private:
  const std::string& path_;
  TrajectoryReadReport own_;
  TrajectoryReadReport* report_;
  Trajectory traj_;
};

// ---- readers ----

/// TUM: `t tx ty tz qx qy qz qw`; commas and tabs separate too (TUM's own tools accept them).
Trajectory parseTum(const std::string& text, const std::string& path,
                    TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  forEachDataLine(text, true, out.report(), [&](std::string line, int line_no) {
    std::replace(line.begin(), line.end(), ',', ' ');
    const std::vector<std::string> tok = splitWhitespace(line);
    // 20: OpenVINS' ov_eval writes the pose and its 12 covariance values
    if (tok.size() != 8 && tok.size() != 20)
      throw InputError(
          path, lineRef(line_no),
          fmt::format("expected 8 fields 'timestamp tx ty tz qx qy qz qw', found {}{}", tok.size(),
                      tok.size() == 12 ? " (12 numbers a line: KITTI poses? --format kitti)" : ""));
    if (tok.size() > 8) {
      double cov[12];
      parseNumbers(tok, 8, 12, cov, path, line_no);
      out.report()->ignored_columns = 12;
    }
    TimeNs t_ns = 0;
    const size_t digits = std::min(tok[0].find('.'), tok[0].size());
    if (digits >= 16 && isDigits(tok[0].substr(0, digits)) &&
        parseScaledDecimal(tok[0], 0, false, t_ns)) {
      out.report()->nanosecond_stamps = true;
    } else if (!parseSecondsToNs(tok[0], t_ns)) {
      throw InputError(path, lineRef(line_no),
                       "timestamp '" + tok[0] + "' is not a number of seconds");
    }
    double v[7];
    parseNumbers(tok, 1, 7, v, path, line_no);
    out.add(t_ns, {unitQuat(v[6], v[3], v[4], v[5], path, line_no), Vec3(v[0], v[1], v[2])},
            line_no);
  });
  return out.finish();
}

Trajectory parseEuroc(const std::string& text, const std::string& path,
                      TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  size_t columns = 0;
  forEachDataLine(text, true, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitCsvRow(line);
    // 11: VINS-Mono/Fusion write the pose and the velocity
    if (tok.size() != 8 && tok.size() != 11 && tok.size() != 17)
      throw InputError(path, lineRef(line_no),
                       fmt::format("expected 8, 11 or 17 comma-separated columns "
                                   "'t_ns,px,py,pz,qw,qx,qy,qz[,v[,bw,ba]]', found {}",
                                   tok.size()));
    if (columns == 0) columns = tok.size();
    if (tok.size() != columns)
      throw InputError(path, lineRef(line_no),
                       fmt::format("{} columns after rows of {}", tok.size(), columns));
    int64_t t_ns = 0;
    if (!parseCount(tok[0], t_ns))
      throw InputError(path, lineRef(line_no),
                       "timestamp '" + tok[0] + "' is not an integer number of nanoseconds");
    double v[16];
    parseNumbers(tok, 1, tok.size() - 1, v, path, line_no);
    if (tok.size() == 11) out.report()->ignored_columns = 3;  // VINS' velocity
    out.add(t_ns, {unitQuat(v[3], v[4], v[5], v[6], path, line_no), Vec3(v[0], v[1], v[2])},
            line_no);
  });
  return out.finish();
}

/// Frame number -> ns at `fps` (rounded to the nearest ns).
TimeNs frameToNs(int64_t frame, double fps) {
  return static_cast<TimeNs>(std::llround(static_cast<double>(frame) * 1e9 / fps));
}

Trajectory parseIcl(const std::string& text, const std::string& path, double fps,
                    TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  forEachDataLine(text, true, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitWhitespace(line);
    if (tok.size() != 8)
      throw InputError(
          path, lineRef(line_no),
          fmt::format("expected 8 fields 'frame tx ty tz qx qy qz qw', found {}", tok.size()));
    int64_t frame = 0;
    if (!parseCount(tok[0], frame) || static_cast<double>(frame) / fps > 9e9)
      throw InputError(path, lineRef(line_no),
                       "frame number '" + tok[0] + "' is not a non-negative integer");
    double v[7];
    parseNumbers(tok, 1, 7, v, path, line_no);
    const Pose T_icl{unitQuat(v[6], v[3], v[4], v[5], path, line_no), Vec3(v[0], v[1], v[2])};
    out.add(frameToNs(frame, fps), iclToOurs(T_icl), line_no);
  });
  return out.finish();
}

/// The TUM layout, checked against SLAMBench 2's RegexPattern (timestamp `([0-9]+)[.]([0-9]+)`,
/// decimal `([-0-9.]+)`): no header line, no exponent.
Trajectory parseSlamBench(const std::string& text, const std::string& path,
                          TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  forEachDataLine(text, false, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitWhitespace(line);
    if (tok.size() != 8)
      throw InputError(
          path, lineRef(line_no),
          fmt::format("expected 8 fields 'timestamp tx ty tz qx qy qz qw', found {}", tok.size()));
    const size_t dot = tok[0].find('.');
    TimeNs t_ns = 0;
    if (dot == std::string::npos || !isDigits(tok[0].substr(0, dot)) ||
        !isDigits(tok[0].substr(dot + 1)) || tok[0].size() - dot - 1 > 9 ||
        !parseSecondsToNs(tok[0], t_ns))
      throw InputError(path, lineRef(line_no),
                       "timestamp '" + tok[0] +
                           "' is not 'seconds.fraction' (at most 9 decimals), as SLAMBench needs");
    for (size_t k = 1; k < 8; ++k)
      if (tok[k].find_first_not_of("-0123456789.") != std::string::npos)
        throw InputError(path, lineRef(line_no),
                         fmt::format("column {} '{}' is not plain decimal notation, which "
                                     "SLAMBench's [-0-9.]+ requires",
                                     k + 1, tok[k]));
    double v[7];
    parseNumbers(tok, 1, 7, v, path, line_no);
    out.add(t_ns, {unitQuat(v[6], v[3], v[4], v[5], path, line_no), Vec3(v[0], v[1], v[2])},
            line_no);
  });
  return out.finish();
}

/// "key:x,y,z" -> the point, or InputError.
Vec3 sceneNetPoint(const std::string& tok, const std::string& key, const std::string& path,
                   int line_no) {
  if (tok.rfind(key, 0) != 0)
    throw InputError(path, lineRef(line_no), "expected '" + key + "x,y,z', found '" + tok + "'");
  const std::vector<std::string> xyz = splitComma(tok.substr(key.size()));
  if (xyz.size() != 3)
    throw InputError(path, lineRef(line_no),
                     fmt::format("'{}' needs 3 comma-separated values, found {}", key, xyz.size()));
  double v[3];
  parseNumbers(xyz, 0, 3, v, path, line_no);
  return {v[0], v[1], v[2]};
}

Trajectory parseSceneNet(const std::string& text, const std::string& path,
                         TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  forEachDataLine(text, false, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitWhitespace(line);
    if (tok[0].rfind("instance:", 0) == 0) return;  // render_info.log object list
    if (tok.size() != 3)
      throw InputError(
          path, lineRef(line_no),
          fmt::format("expected 'time:T pose:x,y,z lookat:x,y,z', found {} fields", tok.size()));
    TimeNs t_ns = 0;
    if (tok[0].rfind("time:", 0) != 0 || !parseSecondsToNs(tok[0].substr(5), t_ns))
      throw InputError(path, lineRef(line_no), "expected 'time:<seconds>', found '" + tok[0] + "'");
    const Vec3 eye = sceneNetToOurs(sceneNetPoint(tok[1], "pose:", path, line_no));
    const Vec3 target = sceneNetToOurs(sceneNetPoint(tok[2], "lookat:", path, line_no));
    const Vec3 dir = target - eye;
    if (dir.norm() < 1e-9 || dir.normalized().cross(Vec3::UnitZ()).norm() < 1e-6)
      throw InputError(path, lineRef(line_no),
                       "lookat equals the camera position or lies straight above/below it: "
                       "the view direction is undefined");
    out.add(t_ns, Pose::lookAt(eye, target, Vec3::UnitZ()), line_no);
  });
  return out.finish();
}

/// SceneNet v1 (ankurhanda/SceneNetv1.0 `*_trajectory_random_poses_SE3_3x4.txt`): one
/// camera-to-world [R|t] per pose as 3 lines of 4 numbers, blank lines between poses, no time
/// (pose k at k / fps). The world is the scene's OBJ frame (Y up) and the camera OpenGL's
/// (x right, y up, looking along -z): the shared room_89 file's camera y columns point up the
/// file's +Y, and its positions lie inside the room at 1.65-1.85 m. Hence
///   T_world_camera = [A 0; 0 1] [R t; 0 1] [F 0; 0 1],  A = Rx(+90 deg): (x, y, z) -> (x, -z, y),
///   F = diag(1, -1, -1) (OpenGL camera -> OpenCV camera).
Trajectory parseSceneNetV1(const std::string& text, const std::string& path, double fps,
                           TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  std::vector<double> rows;  // up to 12 numbers of the pose being read
  int first_line = 0;
  int64_t k = 0;  // poses read
  forEachDataLine(text, false, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitWhitespace(line);
    if (tok.size() != 4)
      throw InputError(path, lineRef(line_no),
                       fmt::format("expected a row of 4 numbers of a 3x4 [R|t] pose, found {} "
                                   "fields",
                                   tok.size()));
    if (rows.empty()) first_line = line_no;
    double v[4];
    parseNumbers(tok, 0, 4, v, path, line_no);
    rows.insert(rows.end(), v, v + 4);
    if (rows.size() < 12) return;
    Mat3 R;
    R << rows[0], rows[1], rows[2], rows[4], rows[5], rows[6], rows[8], rows[9], rows[10];
    const Vec3 t(rows[3], rows[7], rows[11]);
    rows.clear();
    if ((R.transpose() * R - Mat3::Identity()).norm() > 1e-3 || R.determinant() < 0)
      throw InputError(path, lineRef(first_line),
                       "the 3x3 part of this pose is not a rotation (orthonormal, det +1)");
    Mat3 A;
    A << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    const Mat3 R_cv = A * R * Vec3(1, -1, -1).asDiagonal();
    out.add(frameToNs(k++, fps), {Quat(R_cv).normalized(), A * t}, first_line);
  });
  if (!rows.empty())
    throw InputError(path, "", "the file ends inside a pose (a 3x4 [R|t] needs 3 rows of 4)");
  return out.finish();
}

// ---- writers ----

void requireNonNegativeTime(const Trajectory& traj, TrajectoryFormat fmt) {
  for (size_t k = 0; k < traj.size(); ++k)
    if (traj.poses[k].t_ns < 0)
      throw InputError(
          "", fmt::format("pose {}", k),
          fmt::format("time {} s is negative; {} needs times >= 0",
                      nsToSecondsString(traj.poses[k].t_ns), trajectoryFormatName(fmt)));
}

/// `tx ty tz qx qy qz qw` (TUM order), nm positions and 12-decimal quaternions.
std::string tumPoseFields(const Pose& T) {
  const Quat q = canonicalQuat(T.q);
  return fmt::format("{:.9f} {:.9f} {:.9f} {:.12f} {:.12f} {:.12f} {:.12f}", T.t.x(), T.t.y(),
                     T.t.z(), q.x(), q.y(), q.z(), q.w());
}

std::string formatEuroc(const Trajectory& traj) {
  std::string out =
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], "
      "b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], "
      "b_a_RS_S_z [m s^-2]\n";
  for (size_t k = 0; k < traj.size(); ++k) {
    const Pose& T = traj.poses[k].T_world_camera;
    const Quat q = canonicalQuat(T.q);
    const Vec3 v = traj.velocityWorld(k);
    // shortest decimals that read back to the same double: lossless, so TUM -> EuRoC -> TUM
    // gives the same file
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},0,0,0,0,0,0\n", traj.poses[k].t_ns,
                       T.t.x(), T.t.y(), T.t.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z());
  }
  return out;
}

std::string formatIcl(const Trajectory& traj, double fps) {
  std::string out;
  const double period_ns = 1e9 / fps;
  for (size_t k = 0; k < traj.size(); ++k) {
    const TimeNs t_ns = traj.poses[k].t_ns;
    const int64_t frame = std::llround(static_cast<double>(t_ns) / period_ns);
    if (std::abs(static_cast<double>(frameToNs(frame, fps) - t_ns)) > 0.01 * period_ns)
      throw InputError("", "--fps",
                       fmt::format("pose {} at {} s is not on the {} fps frame grid (nearest "
                                   "frame {}); resample the trajectory or give its frame rate",
                                   k, nsToSecondsString(t_ns), fps, frame));
    // iclToOurs is its own inverse (A and F are involutions)
    out += fmt::format("{} {}\n", frame, tumPoseFields(iclToOurs(traj.poses[k].T_world_camera)));
  }
  return out;
}

std::string formatSlamBench(const Trajectory& traj) {
  std::string out = std::string("# ") + kTumComment + "\n# timestamp tx ty tz qx qy qz qw\n";
  for (const TimedPose& p : traj.poses)
    out += fmt::format("{} {}\n", nsToSecondsString(p.t_ns), tumPoseFields(p.T_world_camera));
  return out;
}

std::string formatSceneNet(const Trajectory& traj) {
  std::string out;
  for (size_t k = 0; k < traj.size(); ++k) {
    const Pose& T = traj.poses[k].T_world_camera;
    const Vec3 forward = T.rotation().col(2);
    if (forward.cross(Vec3::UnitZ()).norm() < 1e-6)
      throw InputError("", fmt::format("pose {}", k),
                       "the camera looks straight up or down, which SceneNet's lookat form "
                       "(up = world up) cannot express");
    const Vec3 eye = oursToSceneNet(T.t), look = oursToSceneNet(T.t + forward);
    out += fmt::format("time:{} pose:{:.12f},{:.12f},{:.12f} lookat:{:.12f},{:.12f},{:.12f}\n",
                       nsToSecondsString(traj.poses[k].t_ns), eye.x(), eye.y(), eye.z(), look.x(),
                       look.y(), look.z());
  }
  return out;
}

/// KITTI odometry poses (`poses/XX.txt`, evo's `kitti` files): one camera-to-world 3x4 [R|t]
/// row-major per line, no time (pose k at k / fps, 10 Hz as KITTI's). The camera is OpenCV's
/// (x right, y down, z forward) and the world is the first camera's frame, so its up is -y:
/// ours is that frame turned by Rx(-90 deg), p_w = (x, z, -y), and the camera axes stay.
Mat3 kittiWorldToOurs() {
  Mat3 a;
  a << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return a;
}

Trajectory parseKitti(const std::string& text, const std::string& path, double fps,
                      TrajectoryReadReport* report) {
  PoseCollector out(path, report);
  int64_t k = 0;
  forEachDataLine(text, false, out.report(), [&](const std::string& line, int line_no) {
    const std::vector<std::string> tok = splitWhitespace(line);
    if (tok.size() != 12)
      throw InputError(path, lineRef(line_no),
                       fmt::format("expected the 12 numbers of a 3x4 [R|t] pose, found {}",
                                   tok.size()));
    double v[12];
    parseNumbers(tok, 0, 12, v, path, line_no);
    Mat3 R;
    R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    if ((R.transpose() * R - Mat3::Identity()).norm() > 1e-3 || R.determinant() < 0)
      throw InputError(path, lineRef(line_no),
                       "the 3x3 part is not a rotation (orthonormal, det +1)");
    const Mat3 A = kittiWorldToOurs();
    out.add(frameToNs(k++, fps), {Quat(A * R).normalized(), A * Vec3(v[3], v[7], v[11])},
            line_no);
  });
  return out.finish();
}

std::string formatKitti(const Trajectory& traj, double fps) {
  std::string out;
  const Mat3 At = kittiWorldToOurs().transpose();
  const double period_ns = 1e9 / fps;
  for (size_t k = 0; k < traj.size(); ++k) {
    if (std::abs(static_cast<double>(frameToNs(static_cast<int64_t>(k), fps) -
                                     traj.poses[k].t_ns)) > 0.01 * period_ns)
      throw InputError("", "--fps",
                       fmt::format("pose {} at {} s is not frame {} of a {} fps sequence starting "
                                   "at 0: kitti files hold no times; resample the trajectory or "
                                   "give its frame rate",
                                   k, nsToSecondsString(traj.poses[k].t_ns), k, fps));
    const Mat3 R = At * traj.poses[k].T_world_camera.rotation();
    const Vec3 t = At * traj.poses[k].T_world_camera.t;
    out += fmt::format("{:.12e} {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} {:.12e} "
                       "{:.12e} {:.12e} {:.12e}\n",
                       R(0, 0), R(0, 1), R(0, 2), t.x(), R(1, 0), R(1, 1), R(1, 2), t.y(), R(2, 0),
                       R(2, 1), R(2, 2), t.z());
  }
  return out;
}

/// 3x4 [R|t] blocks (parseSceneNetV1 has the frames), times on the fps grid.
std::string formatSceneNetV1(const Trajectory& traj, double fps) {
  std::string out;
  Mat3 A;
  A << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const double period_ns = 1e9 / fps;
  for (size_t k = 0; k < traj.size(); ++k) {
    const TimeNs t_ns = traj.poses[k].t_ns;
    if (std::abs(static_cast<double>(frameToNs(static_cast<int64_t>(k), fps) - t_ns)) >
        0.01 * period_ns)
      throw InputError("", "--fps",
                       fmt::format("pose {} at {} s is not frame {} of a {} fps sequence starting "
                                   "at 0: scenenet_v1 files hold no times; resample the "
                                   "trajectory or give its frame rate",
                                   k, nsToSecondsString(t_ns), k, fps));
    const Pose& T = traj.poses[k].T_world_camera;
    // A^-1 = A^T; F is its own inverse
    const Mat3 R = A.transpose() * T.rotation() * Vec3(1, -1, -1).asDiagonal();
    const Vec3 t = A.transpose() * T.t;
    for (int r = 0; r < 3; ++r)
      out += fmt::format("{:.12f} {:.12f} {:.12f} {:.12f}\n", R(r, 0), R(r, 1), R(r, 2), t[r]);
    out += "\n";
  }
  return out;
}

struct FormatName {
  TrajectoryFormat fmt;
  const char* name;
};
constexpr FormatName kFormats[] = {{TrajectoryFormat::Tum, "tum"},
                                   {TrajectoryFormat::Euroc, "euroc"},
                                   {TrajectoryFormat::Icl, "icl"},
                                   {TrajectoryFormat::SlamBench, "slambench"},
                                   {TrajectoryFormat::SceneNet, "scenenet"},
                                   {TrajectoryFormat::SceneNetV1, "scenenet_v1"},
                                   {TrajectoryFormat::Kitti, "kitti"}};

}  // namespace

TrajectoryFormat parseTrajectoryFormat(const std::string& name, const std::string& field) {
  for (const FormatName& f : kFormats)
    if (name == f.name) return f.fmt;
  std::string valid;
  for (const FormatName& f : kFormats) valid += std::string(valid.empty() ? "" : ", ") + f.name;
  throw InputError("", field, "unknown trajectory format '" + name + "' (valid: " + valid + ")");
}

const char* trajectoryFormatName(TrajectoryFormat f) {
  for (const FormatName& n : kFormats)
    if (n.fmt == f) return n.name;
  INET_CHECK_MSG(false, "unhandled TrajectoryFormat");
}

std::optional<TrajectoryFormat> trajectoryFormatFromExtension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return TrajectoryFormat::Euroc;
  if (ext == ".freiburg") return TrajectoryFormat::Icl;
  if (ext == ".log") return TrajectoryFormat::SceneNet;
  if (ext == ".txt") return TrajectoryFormat::Tum;
  return std::nullopt;
}

TrajectoryFormat detectTrajectoryFormat(const std::string& path, const std::string& text) {
  std::string first;
  int first_no = 0;
  bool seen = false;
  forEachDataLine(text, false, nullptr, [&](const std::string& line, int line_no) {
    if (!first.empty()) return;
    // a header of column names does not tell the format: the line after it does
    if (!std::exchange(seen, true) && isColumnNames(line)) return;
    first = line;
    first_no = line_no;
  });
  if (first.empty()) throw InputError(path, "", "trajectory has no poses");
  // when the content does not tell, the extension decides, so that the format's own parser
  // reports what is wrong with the line
  const std::optional<TrajectoryFormat> by_extension = trajectoryFormatFromExtension(path);
  const auto cannot = [&](const std::string& why) {
    if (by_extension) return *by_extension;
    throw InputError(path, lineRef(first_no),
                     "cannot tell the trajectory format (" + why +
                         "); name it (tum, euroc, icl, slambench, scenenet, scenenet_v1, kitti)");
  };
  const std::vector<std::string> tok = splitWhitespace(first);
  if (tok[0].rfind("time:", 0) == 0 || tok[0].rfind("instance:", 0) == 0)
    return TrajectoryFormat::SceneNet;
  if (first.find(',') != std::string::npos) {
    const std::vector<std::string> cols = splitCsvRow(first);
    // EuRoC stamps are whole nanoseconds: digits, or numpy's '%.18e' of them (a whole number
    // of at least 1e12 ns; as TUM seconds that would be the year 33,000)
    int64_t ns = 0;
    const bool ns_stamp = isDigits(cols[0]) || (parseCount(cols[0], ns) && ns >= 1'000'000'000'000);
    if (cols.size() == 17 || ((cols.size() == 8 || cols.size() == 11) && ns_stamp))
      return TrajectoryFormat::Euroc;
    if (cols.size() == 8) return TrajectoryFormat::Tum;  // TUM tools also write commas
    return cannot(fmt::format("{} comma-separated columns", cols.size()));
  }
  if (tok.size() == 4) return TrajectoryFormat::SceneNetV1;  // rows of 3x4 [R|t] blocks
  if (tok.size() == 12) return TrajectoryFormat::Kitti;      // a 3x4 [R|t] a line
  if (tok.size() != 8 && tok.size() != 20) return cannot(fmt::format("{} columns", tok.size()));
  // ICL-NUIM's frame numbers look like whole-second TUM stamps: only its extension tells
  if (by_extension == TrajectoryFormat::Icl) return TrajectoryFormat::Icl;
  return TrajectoryFormat::Tum;
}

Trajectory parseTrajectory(const std::string& text, const std::string& path, TrajectoryFormat fmt,
                           const TrajectoryFormatOptions& opt, TrajectoryReadReport* report) {
  auto checkFps = [&](double fps) {
    if (!(fps > 0) || !std::isfinite(fps))
      throw InputError(path, "--fps", "the frame rate must be > 0");
    return fps;
  };
  switch (fmt) {
    case TrajectoryFormat::Tum:
      return parseTum(text, path, report);
    case TrajectoryFormat::Euroc:
      return parseEuroc(text, path, report);
    case TrajectoryFormat::Icl:
      return parseIcl(text, path, checkFps(opt.icl_fps), report);
    case TrajectoryFormat::SlamBench:
      return parseSlamBench(text, path, report);
    case TrajectoryFormat::SceneNet:
      return parseSceneNet(text, path, report);
    case TrajectoryFormat::SceneNetV1:
      return parseSceneNetV1(text, path, checkFps(opt.pose_list_fps), report);
    case TrajectoryFormat::Kitti:
      return parseKitti(text, path, checkFps(opt.kitti_fps), report);
  }
  INET_CHECK_MSG(false, "unhandled TrajectoryFormat");
}

Trajectory readTrajectory(const std::string& path, std::optional<TrajectoryFormat> fmt,
                          const TrajectoryFormatOptions& opt, TrajectoryReadReport* report) {
  const std::string text = readTextFile(path);
  return parseTrajectory(text, path, fmt ? *fmt : detectTrajectoryFormat(path, text), opt, report);
}

std::string formatTrajectory(const Trajectory& traj, TrajectoryFormat fmt,
                             const TrajectoryFormatOptions& opt) {
  if (traj.empty()) throw InputError("", "trajectory", "no poses to write");
  switch (fmt) {
    case TrajectoryFormat::Tum:
      return formatTumTrajectory(traj, kTumComment);
    case TrajectoryFormat::Euroc:
      requireNonNegativeTime(traj, fmt);
      return formatEuroc(traj);
    case TrajectoryFormat::Icl:
      if (!(opt.icl_fps > 0) || !std::isfinite(opt.icl_fps))
        throw InputError("", "--fps", "the ICL frame rate must be > 0");
      requireNonNegativeTime(traj, fmt);
      return formatIcl(traj, opt.icl_fps);
    case TrajectoryFormat::SlamBench:
      requireNonNegativeTime(traj, fmt);
      return formatSlamBench(traj);
    case TrajectoryFormat::SceneNet:
      return formatSceneNet(traj);
    case TrajectoryFormat::SceneNetV1:
      if (!(opt.pose_list_fps > 0) || !std::isfinite(opt.pose_list_fps))
        throw InputError("", "--fps", "the frame rate must be > 0");
      return formatSceneNetV1(traj, opt.pose_list_fps);
    case TrajectoryFormat::Kitti:
      if (!(opt.kitti_fps > 0) || !std::isfinite(opt.kitti_fps))
        throw InputError("", "--fps", "the frame rate must be > 0");
      return formatKitti(traj, opt.kitti_fps);
  }
  INET_CHECK_MSG(false, "unhandled TrajectoryFormat");
}

void writeTrajectory(const std::string& path, const Trajectory& traj, TrajectoryFormat fmt,
                     const TrajectoryFormatOptions& opt) {
  writeTextAtomic(path, formatTrajectory(traj, fmt, opt));
}

Trajectory parseTumTrajectory(const std::string& text, const std::string& path,
                              TrajectoryReadReport* report) {
  return parseTum(text, path, report);
}

Trajectory offsetTrajectory(const Trajectory& traj, const Pose& T_cam0_cam1) {
  Trajectory out = traj;
  for (TimedPose& p : out.poses) p.T_world_camera = p.T_world_camera * T_cam0_cam1;
  return out;
}

}  // namespace inet
