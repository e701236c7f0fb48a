// The calibration of a sequence folder as SLAM systems take it, the adapter registry, the pieces
// every adapter shares (eval/slam_adapters.h), and runExternalSlam: one child process in its own
// process group, killed with the group at the time limit.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <system_error>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/format_writer.h"
#include "dataset/image_encode.h"
#include "eval/slam.h"
#include "eval/slam_adapters.h"
#include "render/lens.h"
#include "sensors/imu_io.h"
#include "trajectory/formats.h"

namespace inet {

namespace fs = std::filesystem;

namespace {

struct InputEntry {
  SlamInput input;
  const char* name;
};
constexpr InputEntry kInputs[] = {{SlamInput::Rgbd, "rgbd"},
                                  {SlamInput::Stereo, "stereo"},
                                  {SlamInput::Monocular, "mono"},
                                  {SlamInput::MonoInertial, "mono-inertial"},
                                  {SlamInput::StereoInertial, "stereo-inertial"}};

// The registry: one line per external system.
struct AdapterEntry {
  const char* name;
  std::unique_ptr<SlamAdapter> (*make)();
};
constexpr AdapterEntry kAdapters[] = {{"orbslam2", makeOrbSlam2Adapter},
                                      {"orbslam3", makeOrbSlam3Adapter}};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

/// A whole-string finite decimal number.
bool parseDouble(const std::string& text, double& out) {
  const std::string s = trim(text);
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && errno == 0 && std::isfinite(out);
}

/// The top-level keys of an EuRoC / Kalibr sensor.yaml, read with yaml-cpp (OpenCV's
/// FileStorage wants a %YAML line, which these files do not have). Errors name the key and the
/// line of its value.
class SensorYaml {
 public:
  explicit SensorYaml(const fs::path& path) : path_(path.string()) {
    try {
      root_ = YAML::Load(readTextFile(path));
    } catch (const YAML::Exception& e) {
      throw InputError(path_, fmt::format("line {}", e.mark.line + 1), e.msg);
    }
    if (!root_.IsMap()) throw InputError(path_, "", "expected 'key: value' lines");
  }

  bool has(const std::string& key) const { return static_cast<bool>(root_[key]); }

  std::string text(const std::string& key) const {
    const YAML::Node v = value(key);
    if (!v.IsScalar())
      throw InputError(path_, key, fmt::format("line {}: expected a single value", line(v)));
    return v.Scalar();
  }

  double number(const std::string& key) const {
    double v;
    if (!parseDouble(text(key), v))
      throw InputError(path_, key,
                       fmt::format("line {}: not a number: '{}'", line(value(key)), text(key)));
    return v;
  }

  /// The numbers of the [...] list of `key` (of its `data:` for a matrix block); exactly n.
  std::vector<double> numbers(const std::string& key, size_t n) const {
    YAML::Node v = value(key);
    if (v.IsMap() && v["data"]) v = v["data"];
    std::vector<double> out;
    bool ok = v.IsSequence() && v.size() == n;
    for (size_t i = 0; ok && i < n; ++i) {
      double x = 0;
      ok = v[i].IsScalar() && parseDouble(v[i].Scalar(), x);
      out.push_back(x);
    }
    if (!ok)
      throw InputError(path_, key,
                       fmt::format("line {}: expected a list of {} numbers", line(v), n));
    return out;
  }

 private:
  YAML::Node value(const std::string& key) const {
    const YAML::Node v = root_[key];
    if (!v) throw InputError(path_, key, "missing");
    return v;
  }
  static int line(const YAML::Node& v) { return v.Mark().line + 1; }

  std::string path_;
  YAML::Node root_;
};

bool nearlyEqual(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a));
}

/// meta.json: the lens (pinhole only), the image size and the OpenCV-convention intrinsics.
void readMeta(const fs::path& path, SlamCalibration& cal) {
  const std::string where = path.string();
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(readTextFile(path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "", std::string("not valid JSON: ") + e.what());
  }
  // one level at a time, so that the message names the field that is missing or wrong
  auto field = [&](const nlohmann::json& obj, const char* key, const std::string& name) {
    if (!obj.is_object() || !obj.contains(key)) throw InputError(where, name, "missing");
    return obj.at(key);
  };
  auto number = [&](const nlohmann::json& obj, const char* key, const std::string& name) {
    const nlohmann::json v = field(obj, key, name);
    if (!v.is_number()) throw InputError(where, name, "expected a number, got " + v.dump());
    return v.get<double>();
  };
  if (field(meta, "meta_format_version", "meta_format_version") != 1)
    throw InputError(where, "meta_format_version", "this reader knows version 1");
  const nlohmann::json cam = field(meta, "camera", "camera");
  const nlohmann::json lens = field(cam, "lens", "camera.lens");
  if (!lens.is_string()) throw InputError(where, "camera.lens", "expected a lens name");
  const LensType type = parseLensType(lens.get<std::string>(), where, "camera.lens");
  if (type != LensType::Pinhole && type != LensType::ThinLens)
    throw InputError(where, "camera.lens",
                     fmt::format("'{}': the SLAM systems take a pinhole camera (generate with "
                                 "--lens pinhole or thin_lens)",
                                 lens.get<std::string>()));
  const double width = number(cam, "width", "camera.width");
  const double height = number(cam, "height", "camera.height");
  if (!(width >= 1 && height >= 1 && width == std::floor(width) && height == std::floor(height)))
    throw InputError(where, "camera.width",
                     fmt::format("{}x{} is not an image size", width, height));
  cal.width = static_cast<int>(width);
  cal.height = static_cast<int>(height);
  const nlohmann::json cv = field(cam, "opencv", "camera.opencv");
  cal.fx = number(cv, "fx", "camera.opencv.fx");
  cal.fy = number(cv, "fy", "camera.opencv.fy");
  cal.cx = number(cv, "cx", "camera.opencv.cx");
  cal.cy = number(cv, "cy", "camera.opencv.cy");
  if (!(cal.fx > 0 && cal.fy > 0))
    throw InputError(where, "camera.opencv.fx", "focal lengths must be > 0");
  if (meta.contains("stereo"))
    cal.stereo_baseline_m = number(meta.at("stereo"), "baseline_m", "stereo.baseline_m");
}

/// cam0/sensor.yaml: rate, distortion; its size and intrinsics must be meta.json's.
void readCam0(const fs::path& path, SlamCalibration& cal) {
  const SensorYaml y(path);
  const std::string where = path.string();
  if (y.text("camera_model") != "pinhole" || y.text("distortion_model") != "radial-tangential")
    throw InputError(where, "camera_model",
                     fmt::format("'{}' with '{}': the SLAM systems take a pinhole with "
                                 "radial-tangential distortion",
                                 y.text("camera_model"), y.text("distortion_model")));
  const std::vector<double> size = y.numbers("resolution", 2);
  const std::vector<double> K = y.numbers("intrinsics", 4);
  if (size[0] != cal.width || size[1] != cal.height || !nearlyEqual(K[0], cal.fx) ||
      !nearlyEqual(K[1], cal.fy) || !nearlyEqual(K[2], cal.cx) || !nearlyEqual(K[3], cal.cy))
    throw InputError(where, "intrinsics",
                     "resolution or intrinsics differ from meta.json's camera.opencv: files of "
                     "two sequences in one folder?");
  const std::vector<double> d = y.numbers("distortion_coefficients", 4);
  cal.k1 = d[0];
  cal.k2 = d[1];
  cal.p1 = d[2];
  cal.p2 = d[3];
  cal.fps = y.number("rate_hz");
  if (!(cal.fps > 0))
    throw InputError(
        where, "rate_hz",
        fmt::format("{}: the systems need a frame rate (a sequence of one frame?)", cal.fps));
}

/// Rows of `folder`/data.csv, which must list cam0's stamps (the systems open every frame's
/// image in each folder they read).
std::vector<SequenceFrame> sameFrames(const fs::path& folder, const SlamCalibration& cal) {
  const fs::path csv = folder / "data.csv";
  const std::vector<SequenceFrame> rows = readAslFrameList(csv);
  for (size_t k = 0; k < std::max(rows.size(), cal.frames.size()); ++k)
    if (k >= rows.size() || k >= cal.frames.size() || rows[k].t_ns != cal.frames[k].t_ns)
      throw InputError(csv.string(), fmt::format("row {}", k + 1),
                       "its frames are not cam0's (cam0/data.csv): a partly written folder?");
  return rows;
}

/// cam1/sensor.yaml: T_BS = T_cam0_cam1 must be a pure shift along x (a rectified pair).
void readCam1(const fs::path& seq, SlamCalibration& cal) {
  const fs::path path = seq / "cam1" / "sensor.yaml";
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (cal.stereo_baseline_m > 0)
      throw InputError(path.string(), "", "missing, though meta.json has a stereo baseline");
    return;
  }
  const Mat4 T =
      poseFromRowMajor16(SensorYaml(path).numbers("T_BS", 16), path.string(), "T_BS").matrix();
  const double b = T(0, 3);
  const bool shift = (T.block<3, 3>(0, 0) - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-9 &&
                     std::abs(T(1, 3)) < 1e-9 && std::abs(T(2, 3)) < 1e-9 && b > 0;
  if (!shift)
    throw InputError(path.string(), "T_BS",
                     "cam1 is not cam0 shifted to the right (x) with the same orientation: not "
                     "a rectified stereo pair");
  if (cal.stereo_baseline_m > 0 && !nearlyEqual(b, cal.stereo_baseline_m))
    throw InputError(path.string(), "T_BS",
                     fmt::format("baseline {} m differs from meta.json's stereo.baseline_m {}", b,
                                 cal.stereo_baseline_m));
  cal.stereo_baseline_m = b;
  sameFrames(seq / "cam1", cal);
}

/// imu0/sensor.yaml: rate, the four noise figures, T_BS (= T_cam0_imu: body = cam0).
void readImu0(const fs::path& seq, SlamCalibration& cal) {
  const fs::path path = seq / "imu0" / "sensor.yaml";
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  const ImuNoise noise = readImuNoiseYaml(path.string());
  cal.gyro_noise_density = noise.gyroscope_noise_density;
  cal.gyro_random_walk = noise.gyroscope_random_walk;
  cal.accel_noise_density = noise.accelerometer_noise_density;
  cal.accel_random_walk = noise.accelerometer_random_walk;
  const SensorYaml y(path);
  cal.imu_rate_hz = y.number("rate_hz");
  if (!(cal.imu_rate_hz > 0))
    throw InputError(path.string(), "rate_hz", fmt::format("{}: must be > 0", cal.imu_rate_hz));
  cal.T_cam0_imu = poseFromRowMajor16(y.numbers("T_BS", 16), path.string(), "T_BS");
  const fs::path csv = seq / "imu0" / "data.csv";
  if (!fs::exists(csv, ec))
    throw InputError(csv.string(), "", "missing (imu0/sensor.yaml is there)");
  cal.has_imu = true;
}

}  // namespace

SlamInput parseSlamInput(const std::string& name, const std::string& field) {
  std::string known;
  for (const InputEntry& e : kInputs) {
    if (name == e.name) return e.input;
    known += (known.empty() ? "" : ", ") + std::string(e.name);
  }
  throw InputError("", field, fmt::format("unknown input '{}' (known: {})", name, known));
}

const char* slamInputName(SlamInput input) {
  for (const InputEntry& e : kInputs)
    if (e.input == input) return e.name;
  INET_CHECK_MSG(false, "a SlamInput without a name");
  return "";
}

SlamCalibration readSlamCalibration(const fs::path& sequence) {
  std::error_code ec;
  if (!fs::is_directory(sequence, ec))
    throw InputError(sequence.string(), "",
                     fs::exists(sequence, ec) ? "not a folder: expected a sequence folder"
                                              : "sequence folder not found");
  SlamCalibration cal;
  cal.sequence = sequence;
  readMeta(sequence / "meta.json", cal);
  readCam0(sequence / "cam0" / "sensor.yaml", cal);
  cal.frames = readAslFrameList(sequence / "cam0" / "data.csv");
  // depth0/<t>.png holds millimetres (docs/output.md section 3); a depth0 of EXRs only (the
  // ray_depth pass alone) has no PNG for the systems
  const fs::path depth_csv = sequence / "depth0" / "data.csv";
  if (fs::exists(depth_csv, ec)) {
    const std::vector<SequenceFrame> depth = sameFrames(sequence / "depth0", cal);
    if (std::all_of(depth.begin(), depth.end(),
                    [](const SequenceFrame& f) { return f.file == f.stamp + ".png"; }))
      cal.depth_png_scale = kDepthScaleMm;
  }
  readCam1(sequence, cal);
  readImu0(sequence, cal);
  return cal;
}

const SlamAdapter& findSlamAdapter(const std::string& name) {
  std::string known;
  for (const SlamAdapter* a : slamAdapters()) {
    if (a->name() == name) return *a;
    known += (known.empty() ? "" : ", ") + a->name();
  }
  throw InputError("", "--system", fmt::format("unknown system '{}' (external: {})", name, known));
}

std::vector<const SlamAdapter*> slamAdapters() {
  static const std::vector<std::unique_ptr<SlamAdapter>> all = [] {
    std::vector<std::unique_ptr<SlamAdapter>> v;
    for (const AdapterEntry& e : kAdapters) {
      v.push_back(e.make());
      INET_CHECK_MSG(v.back()->name() == e.name, "registry name differs from the adapter's");
    }
    return v;
  }();
  std::vector<const SlamAdapter*> out;
  for (const auto& a : all) out.push_back(a.get());
  return out;
}

// ---- shared by the adapters (eval/slam_adapters.h) ----

void requireSlamInput(const SlamAdapter& system, SlamInput input, const SlamCalibration& cal) {
  const std::vector<SlamInput> takes = system.inputs();
  if (std::find(takes.begin(), takes.end(), input) == takes.end()) {
    std::string known;
    for (SlamInput i : takes) known += (known.empty() ? "" : ", ") + std::string(slamInputName(i));
    throw InputError("", "--input",
                     fmt::format("{} does not take '{}' (it takes: {})", system.name(),
                                 slamInputName(input), known));
  }
  const std::string name = slamInputName(input);
  if (input == SlamInput::Rgbd && !(cal.depth_png_scale > 0))
    throw InputError((cal.sequence / "depth0" / "data.csv").string(), "--input",
                     "'rgbd' needs the depth PNGs of depth0/, which this sequence lacks "
                     "(generate with the depth pass)");
  if ((input == SlamInput::Stereo || input == SlamInput::StereoInertial) &&
      !(cal.stereo_baseline_m > 0))
    throw InputError((cal.sequence / "cam1" / "sensor.yaml").string(), "--input",
                     fmt::format("'{}' needs cam1/, and this sequence is mono (generate "
                                 "--stereo B)",
                                 name));
  if ((input == SlamInput::MonoInertial || input == SlamInput::StereoInertial) && !cal.has_imu)
    throw InputError((cal.sequence / "imu0" / "sensor.yaml").string(), "--input",
                     fmt::format("'{}' needs imu0/, which this sequence lacks (generate with "
                                 "the imu pass, or interiornet imu)",
                                 name));
}

fs::path requireVocabulary(const ExternalRun& run, const std::string& system) {
  if (run.vocabulary.empty())
    throw InputError("", "--vocabulary",
                     system +
                         " needs its ORB vocabulary (Vocabulary/ORBvoc.txt of its source "
                         "tree, unpacked)");
  return fs::absolute(run.vocabulary);
}

void writeSlamTimesFile(const fs::path& path, const SlamCalibration& cal) {
  std::string s;
  for (size_t k = 0; k < cal.frames.size(); ++k) {
    const SequenceFrame& f = cal.frames[k];
    if (f.file != f.stamp + ".png")
      throw InputError((cal.sequence / "cam0" / "data.csv").string(), fmt::format("row {}", k + 1),
                       fmt::format("the file is {}, not {}.png: the EuRoC examples open "
                                   "<stamp>.png",
                                   f.file, f.stamp));
    s += f.stamp + "\n";
  }
  writeTextAtomic(path, s);
}

void writeSlamAssociations(const fs::path& path, const SlamCalibration& cal) {
  std::string s;
  for (const SequenceFrame& f : cal.frames) {
    const std::string t = nsToSecondsString(f.t_ns, 9);
    s += fmt::format("{} cam0/data/{} {} depth0/data/{}.png\n", t, f.file, t, f.stamp);
  }
  writeTextAtomic(path, s);
}

OpenCvYaml::OpenCvYaml() : s_("%YAML:1.0\n") {}

void OpenCvYaml::comment(const std::string& text) {
  s_ += "\n# " + text + "\n";
}

void OpenCvYaml::real(const std::string& key, double v) {
  s_ += key + ": " + formatFloat(v) + "\n";
}

void OpenCvYaml::integer(const std::string& key, long long v) {
  s_ += fmt::format("{}: {}\n", key, v);
}

void OpenCvYaml::text(const std::string& key, const std::string& v) {
  s_ += fmt::format("{}: \"{}\"\n", key, v);
}

void OpenCvYaml::matrix(const std::string& key, int rows, int cols, const std::vector<double>& v,
                        char dt) {
  INET_CHECK(v.size() == static_cast<size_t>(rows * cols) && (dt == 'd' || dt == 'f'));
  std::string data;
  for (size_t i = 0; i < v.size(); ++i)
    data += (i == 0 ? "" : (i % static_cast<size_t>(cols) == 0 ? ",\n         " : ", ")) +
            formatFloat(v[i]);
  s_ += fmt::format("{}: !!opencv-matrix\n   rows: {}\n   cols: {}\n   dt: {}\n   data: [{}]\n",
                    key, rows, cols, dt, data);
}

Trajectory snapToFrames(const Trajectory& traj, const SlamCalibration& cal, const fs::path& file) {
  constexpr TimeNs kTolerance = 1'000'000;  // 1 ms
  Trajectory out;
  std::vector<bool> used(cal.frames.size(), false);
  for (const TimedPose& p : traj.poses) {
    const auto it = std::lower_bound(cal.frames.begin(), cal.frames.end(), p.t_ns,
                                     [](const SequenceFrame& f, TimeNs t) { return f.t_ns < t; });
    size_t k = static_cast<size_t>(it - cal.frames.begin());
    if (k == cal.frames.size() ||
        (k > 0 && p.t_ns - cal.frames[k - 1].t_ns < cal.frames[k].t_ns - p.t_ns))
      k = k == 0 ? 0 : k - 1;
    const std::string at = "t = " + nsToSecondsString(p.t_ns) + " s";
    if (cal.frames.empty() || std::abs(p.t_ns - cal.frames[k].t_ns) > kTolerance)
      throw InputError(file.string(), at,
                       "no cam0 frame within 1 ms: a trajectory of another sequence?");
    if (used[k])
      throw InputError(
          file.string(), at,
          "a second pose for the frame at " + nsToSecondsString(cal.frames[k].t_ns) + " s");
    used[k] = true;
    out.poses.push_back({cal.frames[k].t_ns, p.T_world_camera});
  }
  return out;
}

Trajectory readSlamEstimate(
    const fs::path& file, const SlamCalibration& cal, const fs::path& log,
    const std::function<Trajectory(const std::string& text, const std::string& path)>& parse) {
  std::error_code ec;
  if (!fs::exists(file, ec))
    throw InputError(
        file.string(), "",
        "missing: the system wrote no trajectory here (its output: " + log.string() + ")");
  const std::string text = readTextFile(file);
  std::istringstream in(text);
  std::string line;
  bool poses = false;
  while (!poses && std::getline(in, line)) poses = !trim(line).empty() && trim(line)[0] != '#';
  if (!poses) return {};
  return snapToFrames(parse(text, file.string()), cal, file);
}

Trajectory readTumEstimate(const fs::path& file, const SlamCalibration& cal, const fs::path& log) {
  return readSlamEstimate(file, cal, log, [](const std::string& text, const std::string& path) {
    return parseTumTrajectory(text, path);
  });
}

// ---- running the system ----

namespace {

void checkExecutable(const fs::path& exe) {
  std::error_code ec;
  if (exe.empty()) throw InputError("", "--exe", "no executable given");
  if (!fs::exists(exe, ec)) throw InputError(exe.string(), "--exe", "not found");
  if (!fs::is_regular_file(exe, ec)) throw InputError(exe.string(), "--exe", "not a file");
  if (access(exe.c_str(), X_OK) != 0)
    throw InputError(exe.string(), "--exe", "not executable (no x permission for this user)");
}

/// The last non-blank line of the log, cut to 300 characters ("" if none).
std::string lastLine(const fs::path& log) {
  std::string text;
  try {
    text = readTextFile(log);
  } catch (const InputError&) {
    return "";
  }
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line))
    if (!trim(line).empty()) last = trim(line);
  return last.size() > 300 ? last.substr(0, 300) + "..." : last;
}

std::string quoteLastLine(const fs::path& log) {
  const std::string last = lastLine(log);
  return last.empty() ? "its log is empty" : "its last line: '" + last + "'";
}

/// Starts argv (argv[0] an absolute path) in a process group of its own, working in `work`,
/// stdin from /dev/null, stdout and stderr to `log`. An exec failure comes back through a
/// close-on-exec pipe as InputError (field "--exe").
pid_t spawn(const std::vector<std::string>& argv, const fs::path& work, const fs::path& log) {
  // everything the child needs is made before fork: between fork and exec only
  // async-signal-safe calls (the parent may have other threads)
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string dir = work.string();
  const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0)
    throw InputError(log.string(), "", std::string("cannot be written: ") + std::strerror(errno));
  const int in = open("/dev/null", O_RDONLY | O_CLOEXEC);
  int report[2];
  if (in < 0 || pipe2(report, O_CLOEXEC) != 0) {
    const int e = errno;
    close(out);
    if (in >= 0) close(in);
    throw std::system_error(e, std::generic_category(), "runExternalSlam: pipe");
  }
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    if (chdir(dir.c_str()) == 0 && dup2(in, 0) >= 0 && dup2(out, 1) >= 0 && dup2(out, 2) >= 0)
      execv(args[0], args.data());
    const int e = errno;
    (void)!write(report[1], &e, sizeof e);
    _exit(127);
  }
  const int fork_errno = errno;
  close(out);
  close(in);
  close(report[1]);
  if (pid < 0) {
    close(report[0]);
    throw std::system_error(fork_errno, std::generic_category(), "runExternalSlam: fork");
  }
  // also here, so that the group exists before the parent may signal it (the loser of the race
  // gets EACCES or EPERM, harmlessly)
  setpgid(pid, pid);
  int child_errno = 0;
  ssize_t n;
  do {
    n = read(report[0], &child_errno, sizeof child_errno);
  } while (n < 0 && errno == EINTR);
  close(report[0]);
  if (n == static_cast<ssize_t>(sizeof child_errno)) {
    waitpid(pid, nullptr, 0);
    throw InputError(argv[0], "--exe", std::string("cannot be run: ") + std::strerror(child_errno));
  }
  return pid;
}

}  // namespace

SlamEstimate runExternalSlam(const SlamAdapter& adapter, const ExternalRun& run_in,
                             const SlamCalibration& cal) {
  checkExecutable(run_in.exe);
  std::error_code ec;
  if (!run_in.vocabulary.empty() && !fs::is_regular_file(run_in.vocabulary, ec))
    throw InputError(run_in.vocabulary.string(), "--vocabulary", "not found");
  if (!(run_in.time_limit_s > 0) || !std::isfinite(run_in.time_limit_s))
    throw InputError("", "--time-limit", fmt::format("{} s: must be > 0", run_in.time_limit_s));
  // the child works in run.work: every path it is given must be absolute
  ExternalRun run = run_in;
  run.exe = fs::absolute(run.exe);
  run.work = fs::absolute(run.work);
  if (!run.vocabulary.empty()) run.vocabulary = fs::absolute(run.vocabulary);
  std::vector<std::string> argv = adapter.prepare(run, cal);
  INET_CHECK_MSG(!argv.empty() && argv[0] == run.exe.string(), "prepare: argv[0] must be run.exe");

  const fs::path log = run.work / "log.txt";
  const std::string name = run.exe.filename().string();
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline = start + std::chrono::duration_cast<Clock::duration>(
                                                 std::chrono::duration<double>(run.time_limit_s));
  const pid_t pid = spawn(argv, run.work, log);
  int status = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR)
      throw std::system_error(errno, std::generic_category(), "runExternalSlam: waitpid");
    const Clock::time_point now = Clock::now();
    if (now >= deadline) {
      // the whole group: example programs start threads, and a wrapper script its children
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      throw InputError(log.string(), "--time-limit",
                       fmt::format("{} still ran after {} s and was killed; {}", name,
                                   run.time_limit_s, quoteLastLine(log)));
    }
    std::this_thread::sleep_for(
        std::min<Clock::duration>(std::chrono::milliseconds(10), deadline - now));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (WIFSIGNALED(status))
    throw InputError(log.string(), "exit status",
                     fmt::format("{} was killed by signal {} ({}); {}", name, WTERMSIG(status),
                                 strsignal(WTERMSIG(status)), quoteLastLine(log)));
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    throw InputError(
        log.string(), "exit status",
        fmt::format("{} exited with status {}; {}", name, WEXITSTATUS(status), quoteLastLine(log)));
  SlamEstimate est = adapter.collect(run, cal);
  est.seconds = seconds;
  est.log = log;
  return est;
}

}  // namespace inet
