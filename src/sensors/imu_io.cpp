#include "sensors/imu_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace inet {

const char* const kEurocImuCsvHeader =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
    "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]";
const char* const kImuBiasCsvHeader =
    "#timestamp [ns],b_w_RS_S_x [rad s^-1],b_w_RS_S_y [rad s^-1],b_w_RS_S_z [rad s^-1],"
    "b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],b_a_RS_S_z [m s^-2]";

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

/// A whole-string decimal number; false for anything else (trailing text, empty, nan, inf).
bool parseNumber(const std::string& text, double& out) {
  const std::string s = trim(text);
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && errno == 0 && std::isfinite(out);
}

/// Lines of `text` without comments ('#' at the start or after a blank) and trailing blanks.
std::vector<std::string> yamlLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    for (size_t i = 0; i < line.size(); ++i)
      if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
        line.resize(i);
        break;
      }
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r'))
      line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

size_t indentOf(const std::string& line) { return line.find_first_not_of(" \t"); }

/// Numbers inside [...] of `text`, separated by commas and blanks.
bool bracketNumbers(const std::string& text, std::vector<double>& out) {
  int depth = 0;
  std::string token;
  auto flush = [&]() {
    const std::string t = trim(token);
    token.clear();
    if (t.empty()) return true;
    double v;
    if (!parseNumber(t, v)) return false;
    out.push_back(v);
    return true;
  };
  for (char c : text) {
    if (c == '[') {
      ++depth;
    } else if (c == ']' || ((c == ',' || c == ' ' || c == '\n') && depth > 0)) {
      if (!flush()) return false;
      if (c == ']') --depth;
    } else if (depth > 0) {
      token += c;
    }
  }
  return true;
}

/// Numbers separated by commas and/or blanks (the whole string).
bool plainNumbers(const std::string& text, std::vector<double>& out) {
  std::string s = text;
  std::replace(s.begin(), s.end(), ',', ' ');
  std::istringstream in(s);
  std::string tok;
  while (in >> tok) {
    double v;
    if (!parseNumber(tok, v)) return false;
    out.push_back(v);
  }
  return true;
}

std::string num(double v) { return fmt::format("{}", v); }

}  // namespace

ImuNoise parseImuNoiseYaml(const std::string& text, const std::string& path) {
  static const std::set<std::string> kNoiseKeys = {
      "gyroscope_noise_density", "gyroscope_random_walk", "accelerometer_noise_density",
      "accelerometer_random_walk"};
  static const std::set<std::string> kBiasKeys = {"initial_gyro_bias", "initial_accel_bias"};
  // keys Kalibr, EuRoC and our own sensor.yaml carry that do not concern the noise
  static const std::set<std::string> kIgnored = {
      "sensor_type", "comment", "T_BS", "T_i_b", "rate_hz", "update_rate", "rostopic", "model",
      "time_offset_s", "time_offset", "timeshift_cam_imu", "gravity_world", "seed"};
  ImuNoise n;
  std::map<std::string, int> seen;  // key -> line
  const std::vector<std::string> lines = yamlLines(text);
  size_t skip_indent = std::string::npos;  // inside an ignored block deeper than this
  int bracket_depth = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const int line_no = static_cast<int>(i) + 1;
    if (trim(line).empty()) continue;
    const size_t indent = indentOf(line);
    const std::string content = line.substr(indent);
    if (bracket_depth > 0) {  // continuation of a multi-line [...] list
      bracket_depth += static_cast<int>(std::count(content.begin(), content.end(), '[')) -
                       static_cast<int>(std::count(content.begin(), content.end(), ']'));
      continue;
    }
    if (skip_indent != std::string::npos && (indent > skip_indent || content[0] == '-')) continue;
    skip_indent = std::string::npos;
    const size_t colon = content.find(':');
    if (content[0] == '-' || colon == std::string::npos)
      throw InputError(path, fmt::format("line {}", line_no),
                       fmt::format("expected 'key: value', got '{}'", content));
    const std::string key = trim(content.substr(0, colon));
    const std::string value = trim(content.substr(colon + 1));
    bracket_depth = static_cast<int>(std::count(value.begin(), value.end(), '[')) -
                    static_cast<int>(std::count(value.begin(), value.end(), ']'));
    const bool container = key.size() > 3 && key.rfind("imu", 0) == 0 &&
                           std::all_of(key.begin() + 3, key.end(), ::isdigit) && value.empty();
    if (container || key == "cols" || key == "rows" || key == "data") continue;
    if (kIgnored.count(key)) {
      if (value.empty()) skip_indent = indent;
      continue;
    }
    if (!kNoiseKeys.count(key) && !kBiasKeys.count(key)) {
      std::string known;
      for (const auto* set : {&kNoiseKeys, &kBiasKeys, &kIgnored})
        for (const std::string& k : *set) known += (known.empty() ? "" : ", ") + k;
      throw InputError(path, key, fmt::format("line {}: unknown key (known: {})", line_no, known));
    }
    if (seen.count(key))
      throw InputError(path, key,
                       fmt::format("line {}: given twice (first on line {}); one IMU per file",
                                   line_no, seen[key]));
    seen[key] = line_no;
    if (kBiasKeys.count(key)) {
      std::vector<double> v;
      if (!bracketNumbers(value, v) || v.size() != 3 || bracket_depth != 0)
        throw InputError(path, key, fmt::format("line {}: expected [x, y, z], got '{}'", line_no,
                                                value));
      (key == "initial_gyro_bias" ? n.gyro_bias0 : n.accel_bias0) = Vec3(v[0], v[1], v[2]);
      continue;
    }
    double v;
    if (!parseNumber(value, v))
      throw InputError(path, key, fmt::format("line {}: not a number: '{}'", line_no, value));
    if (v < 0) throw InputError(path, key, fmt::format("line {}: negative: {}", line_no, v));
    if (key == "gyroscope_noise_density") n.gyroscope_noise_density = v;
    if (key == "gyroscope_random_walk") n.gyroscope_random_walk = v;
    if (key == "accelerometer_noise_density") n.accelerometer_noise_density = v;
    if (key == "accelerometer_random_walk") n.accelerometer_random_walk = v;
  }
  for (const std::string& key : kNoiseKeys)
    if (!seen.count(key)) throw InputError(path, key, "missing (all four noise keys are needed)");
  return n;
}

ImuNoise readImuNoiseYaml(const std::string& path) {
  return parseImuNoiseYaml(readTextFile(path), path);
}

ImuNoise imuNoiseFromArg(const std::string& arg, const std::string& field) {
  if (arg == "none") return ImuNoise::none();
  if (arg == "euroc") return ImuNoise::euroc();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(arg, ec))
    throw InputError(arg, field, "neither 'none', 'euroc' nor a readable yaml file");
  return readImuNoiseYaml(arg);
}

Pose poseFromRowMajor16(const std::vector<double>& m, const std::string& source,
                        const std::string& field) {
  if (m.size() != 16)
    throw InputError(source, field,
                     fmt::format("expected 16 numbers (4x4 row-major), got {}", m.size()));
  Mat4 T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = m[static_cast<size_t>(r * 4 + c)];
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
    throw InputError(source, field, "the last row must be 0 0 0 1");
  const Mat3 R = T.block<3, 3>(0, 0);
  const double ortho = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (ortho > 1e-6 || R.determinant() < 0)
    throw InputError(source, field,
                     fmt::format("the rotation is not orthonormal with det +1 (|R^T R - I| = "
                                 "{:.2e})",
                                 ortho));
  return Pose::fromMatrix(T);
}

Pose parseExtrinsicsArg(const std::string& arg, const std::string& field) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(arg, ec)) {
    std::vector<double> v;
    if (!plainNumbers(arg, v))
      throw InputError("", field,
                       "expected 16 numbers (T_cam_imu row-major) or a yaml file, got '" + arg +
                           "'");
    return poseFromRowMajor16(v, "", field);
  }
  const std::vector<std::string> lines = yamlLines(readTextFile(arg));
  for (size_t i = 0; i < lines.size(); ++i) {
    const size_t indent = indentOf(lines[i]);
    if (indent == std::string::npos) continue;
    const std::string content = lines[i].substr(indent);
    const bool cam_imu = content.rfind("T_cam_imu:", 0) == 0;
    if (!cam_imu && content.rfind("T_BS:", 0) != 0) continue;
    // the matrix: the rest of the line, then deeper lines and '- [...]' rows
    std::string block = content.substr(content.find(':') + 1) + "\n";
    for (size_t j = i + 1; j < lines.size(); ++j) {
      const size_t ind = indentOf(lines[j]);
      if (ind == std::string::npos) continue;
      if (ind < indent || (ind == indent && lines[j][ind] != '-')) break;
      block += lines[j].substr(ind) + "\n";
    }
    std::vector<double> v;
    const std::string key = cam_imu ? "T_cam_imu" : "T_BS";
    if (!bracketNumbers(block, v))
      throw InputError(arg, key, fmt::format("line {}: a matrix entry is not a number", i + 1));
    const Pose T = poseFromRowMajor16(v, arg, key);
    return cam_imu ? T : T.inverse();  // a camera's T_BS maps the camera into the IMU body
  }
  throw InputError(arg, field, "no T_cam_imu (Kalibr camchain) or T_BS (EuRoC camera) key");
}

std::string formatImuCsv(const std::vector<ImuSample>& samples) {
  std::string s = std::string(kEurocImuCsvHeader) + "\n";
  s.reserve(samples.size() * 140);
  for (const ImuSample& m : samples)
    fmt::format_to(std::back_inserter(s), "{},{},{},{},{},{},{}\n", m.t_ns, m.gyro.x(),
                   m.gyro.y(), m.gyro.z(), m.accel.x(), m.accel.y(), m.accel.z());
  return s;
}

std::string formatImuBiasCsv(const std::vector<ImuSample>& samples,
                             const std::vector<ImuBias>& bias) {
  INET_CHECK(samples.size() == bias.size());
  std::string s = std::string(kImuBiasCsvHeader) + "\n";
  s.reserve(samples.size() * 140);
  for (size_t k = 0; k < samples.size(); ++k) {
    const ImuBias& b = bias[k];
    fmt::format_to(std::back_inserter(s), "{},{},{},{},{},{},{}\n", samples[k].t_ns, b.gyro.x(),
                   b.gyro.y(), b.gyro.z(), b.accel.x(), b.accel.y(), b.accel.z());
  }
  return s;
}

std::string formatImuSensorYaml(const ImuOptions& opt, const std::string& comment) {
  // the comment is written as a YAML plain scalar
  INET_CHECK_MSG(comment.find(": ") == std::string::npos && comment.find(" #") == std::string::npos,
                 "an IMU sensor.yaml comment must not contain ': ' or ' #': " + comment);
  const Mat4 T = opt.T_cam_imu.matrix();
  std::string rows;
  for (int r = 0; r < 4; ++r)
    rows += fmt::format("{}{}, {}, {}, {}{}", r == 0 ? "" : "         ", num(T(r, 0)),
                        num(T(r, 1)), num(T(r, 2)), num(T(r, 3)), r == 3 ? "]\n" : ",\n");
  const ImuNoise& n = opt.noise;
  return fmt::format(
      "# General sensor definitions.\nsensor_type: imu\ncomment: {}\n\n"
      "# Sensor extrinsics wrt. the body-frame (body = cam0, so this is T_cam_imu).\n"
      "T_BS:\n  cols: 4\n  rows: 4\n  data: [{}"
      "rate_hz: {}\n\n"
      "# inertial sensor noise model parameters (static)\n"
      "gyroscope_noise_density: {}     # [ rad / s / sqrt(Hz) ]   ( gyro \"white noise\" )\n"
      "gyroscope_random_walk: {}       # [ rad / s^2 / sqrt(Hz) ] ( gyro bias diffusion )\n"
      "accelerometer_noise_density: {}  # [ m / s^2 / sqrt(Hz) ]   ( accel \"white noise\" )\n"
      "accelerometer_random_walk: {}    # [ m / s^3 / sqrt(Hz) ].  ( accel bias diffusion )\n\n"
      "# interiornet: how the stream was made\n"
      "time_offset_s: {}  # t_imu = t_cam + time_offset_s (Kalibr timeshift_cam_imu)\n"
      "gravity_world: [{}, {}, {}]  # [ m / s^2 ]\n"
      "initial_gyro_bias: [{}, {}, {}]  # [ rad / s ]\n"
      "initial_accel_bias: [{}, {}, {}]  # [ m / s^2 ]\n"
      "seed: {}\n",
      comment, rows, num(opt.rate_hz), num(n.gyroscope_noise_density),
      num(n.gyroscope_random_walk), num(n.accelerometer_noise_density),
      num(n.accelerometer_random_walk), num(opt.time_offset_s), num(opt.gravity_world.x()),
      num(opt.gravity_world.y()), num(opt.gravity_world.z()), num(n.gyro_bias0.x()),
      num(n.gyro_bias0.y()), num(n.gyro_bias0.z()), num(n.accel_bias0.x()),
      num(n.accel_bias0.y()), num(n.accel_bias0.z()), opt.seed);
}

std::vector<ImuSample> parseImuCsv(const std::string& text, const std::string& path) {
  std::vector<ImuSample> out;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cols;
    std::istringstream ls(line);
    std::string col;
    while (std::getline(ls, col, ',')) cols.push_back(col);
    const std::string where = fmt::format("line {}", line_no);
    if (cols.size() != 7)
      throw InputError(path, where, fmt::format("expected 7 columns, got {}", cols.size()));
    ImuSample m;
    char* end = nullptr;
    errno = 0;
    m.t_ns = std::strtoll(cols[0].c_str(), &end, 10);
    if (cols[0].empty() || *end != '\0' || errno != 0)
      throw InputError(path, where, "timestamp is not an integer: '" + cols[0] + "'");
    double v[6];
    for (int j = 0; j < 6; ++j)
      if (!parseNumber(cols[static_cast<size_t>(j + 1)], v[j]))
        throw InputError(path, where, "not a number: '" + cols[static_cast<size_t>(j + 1)] + "'");
    m.gyro = Vec3(v[0], v[1], v[2]);
    m.accel = Vec3(v[3], v[4], v[5]);
    out.push_back(m);
  }
  return out;
}

}  // namespace inet
