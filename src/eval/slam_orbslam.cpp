// ORB-SLAM2 and ORB-SLAM3 behind the SlamAdapter contract, driving the example executables their
// READMEs document, with the settings keys their sources read (each block below names the file):
//
//   ORB-SLAM2 (raulmur/ORB_SLAM2)
//     rgbd_tum     VOCAB SETTINGS SEQUENCE ASSOCIATIONS   -> CameraTrajectory.txt,
//                                                            KeyFrameTrajectory.txt (TUM)
//     stereo_euroc VOCAB SETTINGS LEFT RIGHT TIMES        -> CameraTrajectory.txt (TUM)
//     mono_euroc   VOCAB SETTINGS IMAGES TIMES            -> KeyFrameTrajectory.txt (TUM) only
//   ORB-SLAM3 v1.0 (UZ-SLAMLab/ORB_SLAM3; settings "File.version 1.0", read by src/Settings.cc)
//     rgbd_tum     VOCAB SETTINGS SEQUENCE ASSOCIATIONS   -> CameraTrajectory.txt,
//                                                            KeyFrameTrajectory.txt (TUM)
//     stereo_euroc, mono_euroc, mono_inertial_euroc, stereo_inertial_euroc
//                  VOCAB SETTINGS SEQ TIMES NAME          -> f_NAME.txt, kf_NAME.txt (EuRoC style:
//                  SEQ/mav0/{cam0,cam1,imu0}                 float ns, TUM column order; the
//                                                            inertial ones give the IMU's pose)
//
// Every image is read by cv::imread, which hands colour over as BGR whatever the file's order:
// so Camera.RGB is 0 (the examples' TUM1.yaml says 1 for RGB files, which swaps red and blue in
// the grey conversion).
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "eval/slam.h"
#include "eval/slam_adapters.h"
#include "trajectory/trajectory.h"

namespace inet {

namespace fs = std::filesystem;

namespace {

/// Close/far threshold in baselines (ThDepth; ORB-SLAM2 Examples/RGB-D/TUM1.yaml): points
/// nearer than ThDepth * baseline are triangulated from one frame.
constexpr double kThDepth = 40.0;
/// RGB-D has no second camera; ORB-SLAM uses a virtual one (bf) for the close/far split. 8 cm,
/// about a Kinect's projector-camera baseline (TUM1.yaml: bf 40 / fx 517 = 7.7 cm): points up to
/// 40 x 0.08 = 3.2 m count as close, the size of a room.
constexpr double kRgbdVirtualBaselineM = 0.08;
/// ORB-SLAM3's NAME argument: it writes f_inet.txt and kf_inet.txt.
constexpr const char* kRunName = "inet";

bool inertial(SlamInput input) {
  return input == SlamInput::MonoInertial || input == SlamInput::StereoInertial;
}
bool stereo(SlamInput input) {
  return input == SlamInput::Stereo || input == SlamInput::StereoInertial;
}
bool hasDistortion(const SlamCalibration& cal) {
  return cal.k1 != 0 || cal.k2 != 0 || cal.p1 != 0 || cal.p2 != 0;
}

std::vector<double> rowMajor(const Mat4& T) {
  std::vector<double> v;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) v.push_back(T(r, c));
  return v;
}

/// ORB extractor (both systems: ORB-SLAM2 src/Tracking.cc constructor, ORB-SLAM3
/// src/Settings.cc readORB; values of their TUM1.yaml) and viewer (ORB-SLAM2 src/Viewer.cc and
/// src/MapDrawer.cc constructors, ORB-SLAM3 Settings::readViewer: required when the example
/// opens its viewer). Viewer values only place the map view.
void orbAndViewer(OpenCvYaml& y) {
  y.comment("ORB extractor");
  y.integer("ORBextractor.nFeatures", 1000);
  y.real("ORBextractor.scaleFactor", 1.2);
  y.integer("ORBextractor.nLevels", 8);
  y.integer("ORBextractor.iniThFAST", 20);
  y.integer("ORBextractor.minThFAST", 7);
  y.comment("Viewer");
  for (const auto& [key, v] : {std::pair{"KeyFrameSize", 0.05}, std::pair{"KeyFrameLineWidth", 1.0},
                               std::pair{"GraphLineWidth", 0.9}, std::pair{"PointSize", 2.0},
                               std::pair{"CameraSize", 0.08}, std::pair{"CameraLineWidth", 3.0},
                               std::pair{"ViewpointX", 0.0}, std::pair{"ViewpointY", -0.7},
                               std::pair{"ViewpointZ", -1.8}, std::pair{"ViewpointF", 500.0}})
    y.real(std::string("Viewer.") + key, v);
}

std::string orbSlam2Settings(SlamInput input, const SlamCalibration& cal) {
  OpenCvYaml y;
  y.comment(
      fmt::format("ORB-SLAM2 settings for '{}' input, written by interiornet eval slam "
                  "from {}",
                  slamInputName(input), cal.sequence.string()));
  // stereo_euroc rectifies (and undistorts) every image with LEFT/RIGHT below; Tracking then
  // sees ideal images, so its own distortion is zero (as in ORB-SLAM2's Stereo/EuRoC.yaml)
  const bool rectify = input == SlamInput::Stereo;
  y.comment(
      "src/Tracking.cc (Tracking::Tracking): pinhole, OpenCV convention; k3 is read only "
      "when non-zero");
  y.real("Camera.fx", cal.fx);
  y.real("Camera.fy", cal.fy);
  y.real("Camera.cx", cal.cx);
  y.real("Camera.cy", cal.cy);
  y.real("Camera.k1", rectify ? 0.0 : cal.k1);
  y.real("Camera.k2", rectify ? 0.0 : cal.k2);
  y.real("Camera.p1", rectify ? 0.0 : cal.p1);
  y.real("Camera.p2", rectify ? 0.0 : cal.p2);
  y.real("Camera.fps", cal.fps);
  y.integer("Camera.RGB", 0);  // cv::imread gives BGR (file header)
  y.comment("src/Viewer.cc: the frame view's size");
  y.integer("Camera.width", cal.width);
  y.integer("Camera.height", cal.height);
  if (input == SlamInput::Rgbd || input == SlamInput::Stereo) {
    const double b = input == SlamInput::Stereo ? cal.stereo_baseline_m : kRgbdVirtualBaselineM;
    y.comment(
        fmt::format("src/Tracking.cc: bf = baseline x fx ({} m: {}), close/far threshold "
                    "ThDepth in baselines",
                    b, rectify ? "cam1 right of cam0" : "virtual, RGB-D"));
    y.real("Camera.bf", b * cal.fx);
    y.real("ThDepth", kThDepth);
  }
  if (input == SlamInput::Rgbd) {
    y.comment("src/Tracking.cc: depth = PNG value / DepthMapFactor (depth0 PNGs are mm)");
    y.real("DepthMapFactor", cal.depth_png_scale);
  }
  if (rectify) {
    y.comment(
        "Examples/Stereo/stereo_euroc.cc: rectification maps (initUndistortRectifyMap). The "
        "pair is already rectified: R = I, P = [K | 0] and [K | (-bf, 0, 0)]");
    const std::vector<double> K = {cal.fx, 0, cal.cx, 0, cal.fy, cal.cy, 0, 0, 1};
    const std::vector<double> D = {cal.k1, cal.k2, cal.p1, cal.p2, 0};
    const std::vector<double> R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (const char* side : {"LEFT", "RIGHT"}) {
      const double tx = std::string(side) == "RIGHT" ? -cal.fx * cal.stereo_baseline_m : 0.0;
      y.integer(std::string(side) + ".height", cal.height);
      y.integer(std::string(side) + ".width", cal.width);
      y.matrix(std::string(side) + ".D", 1, 5, D);
      y.matrix(std::string(side) + ".K", 3, 3, K);
      y.matrix(std::string(side) + ".R", 3, 3, R);
      y.matrix(std::string(side) + ".P", 3, 4,
               {cal.fx, 0, cal.cx, tx, 0, cal.fy, cal.cy, 0, 0, 0, 1, 0});
    }
  }
  orbAndViewer(y);
  return y.str();
}

std::string orbSlam3Settings(SlamInput input, const SlamCalibration& cal) {
  OpenCvYaml y;
  y.comment(
      fmt::format("ORB-SLAM3 v1.0 settings for '{}' input, written by interiornet eval "
                  "slam from {}",
                  slamInputName(input), cal.sequence.string()));
  // System.cc hands a file with File.version "1.0" to src/Settings.cc, which aborts on a missing
  // required key or a wrong type (ints must be written as ints, matrices as dt f)
  y.text("File.version", "1.0");
  y.comment(
      "src/Settings.cc readCamera1: a pinhole; distortion keys only when there is "
      "distortion (their absence means none; monocular undistorts, stereo rectifies)");
  y.text("Camera.type", "PinHole");
  for (int c = 1; c <= (stereo(input) ? 2 : 1); ++c) {
    if (c == 2)
      y.comment(
          "readCamera2: cam1 has cam0's intrinsics; Stereo.T_c1_c2 maps cam1 into cam0 "
          "(identity rotation, baseline along x: the rectification maps are identities)");
    const std::string cam = fmt::format("Camera{}.", c);
    y.real(cam + "fx", cal.fx);
    y.real(cam + "fy", cal.fy);
    y.real(cam + "cx", cal.cx);
    y.real(cam + "cy", cal.cy);
    if (hasDistortion(cal)) {
      y.real(cam + "k1", cal.k1);
      y.real(cam + "k2", cal.k2);
      y.real(cam + "p1", cal.p1);
      y.real(cam + "p2", cal.p2);
    }
  }
  if (stereo(input)) {
    Mat4 T_c1_c2 = Mat4::Identity();
    T_c1_c2(0, 3) = cal.stereo_baseline_m;
    y.matrix("Stereo.T_c1_c2", 4, 4, rowMajor(T_c1_c2), 'f');
    y.real("Stereo.ThDepth", kThDepth);
  }
  y.comment(fmt::format("readImageInfo: Camera.fps is an integer there ({} Hz)", cal.fps));
  y.integer("Camera.width", cal.width);
  y.integer("Camera.height", cal.height);
  y.integer("Camera.fps", std::llround(cal.fps));
  y.integer("Camera.RGB", 0);  // cv::imread gives BGR (file header)
  if (input == SlamInput::Rgbd) {
    y.comment(
        fmt::format("readRGBD: depth = PNG value / DepthMapFactor (depth0 PNGs are mm); "
                    "Stereo.b a virtual baseline ({} m) for bf and the close/far split",
                    kRgbdVirtualBaselineM));
    y.real("RGBD.DepthMapFactor", cal.depth_png_scale);
    y.real("Stereo.ThDepth", kThDepth);
    y.real("Stereo.b", kRgbdVirtualBaselineM);
  }
  if (inertial(input)) {
    y.comment(
        "readIMU: continuous-time noise densities and random walks (Kalibr units, as "
        "imu0/sensor.yaml), T_b_c1 maps cam0 into the IMU body frame");
    y.real("IMU.NoiseGyro", cal.gyro_noise_density);
    y.real("IMU.NoiseAcc", cal.accel_noise_density);
    y.real("IMU.GyroWalk", cal.gyro_random_walk);
    y.real("IMU.AccWalk", cal.accel_random_walk);
    y.real("IMU.Frequency", cal.imu_rate_hz);
    y.matrix("IMU.T_b_c1", 4, 4, rowMajor(cal.T_cam0_imu.inverse().matrix()), 'f');
  }
  orbAndViewer(y);
  return y.str();
}

/// What both adapters share: the work folder, stale outputs, the settings file.
class OrbSlamAdapter : public SlamAdapter {
 protected:
  struct Started {
    fs::path settings, vocabulary;  ///< absolute
  };
  /// Checks the input and the vocabulary, makes run.work (removing the outputs of an earlier
  /// run, so that a failed run is never read as this one's) and writes settings.yaml there.
  Started begin(const ExternalRun& run, const SlamCalibration& cal, const std::string& system,
                const std::string& settings, const std::vector<std::string>& outputs) const {
    requireSlamInput(*this, run.input, cal);
    Started s;
    s.vocabulary = requireVocabulary(run, system);
    const fs::path work = fs::absolute(run.work);
    fs::create_directories(work);
    for (const std::string& o : outputs) fs::remove(work / o);
    s.settings = work / "settings.yaml";
    writeTextAtomic(s.settings, settings);
    return s;
  }

  /// rgbd_tum VOCAB SETTINGS SEQUENCE ASSOCIATIONS (both systems' Examples/RGB-D/rgbd_tum.cc).
  static std::vector<std::string> rgbdTum(const ExternalRun& run, const fs::path& vocab,
                                          const fs::path& settings, const SlamCalibration& cal) {
    const fs::path assoc = fs::absolute(run.work) / "associations.txt";
    writeSlamAssociations(assoc, cal);
    return {run.exe.string(), vocab.string(), settings.string(),
            fs::absolute(cal.sequence).string(), assoc.string()};
  }

  static fs::path log(const ExternalRun& run) { return fs::absolute(run.work) / "log.txt"; }
};

class OrbSlam2 final : public OrbSlamAdapter {
 public:
  std::string name() const override { return "orbslam2"; }
  std::string description() const override {
    return "ORB-SLAM2 example programs: --exe rgbd_tum (rgbd), stereo_euroc (stereo) or "
           "mono_euroc (mono; it saves keyframes only), --vocabulary ORBvoc.txt";
  }
  std::vector<SlamInput> inputs() const override {
    return {SlamInput::Rgbd, SlamInput::Stereo, SlamInput::Monocular};
  }

  std::vector<std::string> prepare(const ExternalRun& run,
                                   const SlamCalibration& cal) const override {
    const Started s = begin(run, cal, "ORB-SLAM2", orbSlam2Settings(run.input, cal),
                            {"CameraTrajectory.txt", "KeyFrameTrajectory.txt"});
    const fs::path &settings = s.settings, &vocab = s.vocabulary;
    if (run.input == SlamInput::Rgbd) return rgbdTum(run, vocab, settings, cal);
    // Examples/Stereo/stereo_euroc.cc, Examples/Monocular/mono_euroc.cc: image folders and a
    // times file whose lines name <folder>/<line>.png
    const fs::path times = fs::absolute(run.work) / "times.txt";
    writeSlamTimesFile(times, cal);
    const fs::path seq = fs::absolute(cal.sequence);
    std::vector<std::string> argv = {run.exe.string(), vocab.string(), settings.string(),
                                     (seq / "cam0" / "data").string()};
    if (run.input == SlamInput::Stereo) argv.push_back((seq / "cam1" / "data").string());
    argv.push_back(times.string());
    return argv;
  }

  SlamEstimate collect(const ExternalRun& run, const SlamCalibration& cal) const override {
    const fs::path work = fs::absolute(run.work);
    SlamEstimate est;
    // stereo_euroc saves the frames only, mono_euroc the keyframes only (SaveTrajectoryTUM
    // refuses monocular): for mono the keyframes are all the camera poses there are
    if (run.input != SlamInput::Monocular)
      est.camera = readTumEstimate(work / "CameraTrajectory.txt", cal, log(run));
    if (run.input != SlamInput::Stereo)
      est.keyframes = readTumEstimate(work / "KeyFrameTrajectory.txt", cal, log(run));
    if (run.input == SlamInput::Monocular) est.camera = est.keyframes;
    return est;
  }
};

class OrbSlam3 final : public OrbSlamAdapter {
 public:
  std::string name() const override { return "orbslam3"; }
  std::string description() const override {
    return "ORB-SLAM3 v1.0 example programs: --exe rgbd_tum, stereo_euroc, mono_euroc, "
           "mono_inertial_euroc or stereo_inertial_euroc (as --input), --vocabulary ORBvoc.txt";
  }
  std::vector<SlamInput> inputs() const override {
    return {SlamInput::Rgbd, SlamInput::Stereo, SlamInput::Monocular, SlamInput::MonoInertial,
            SlamInput::StereoInertial};
  }

  std::vector<std::string> prepare(const ExternalRun& run,
                                   const SlamCalibration& cal) const override {
    if (run.input == SlamInput::Rgbd && hasDistortion(cal))
      throw InputError((cal.sequence / "cam0" / "sensor.yaml").string(), "--input",
                       "ORB-SLAM3 v1.0 ignores the distortion of RGB-D images (Settings.cc "
                       "undistorts monocular input only): use a sequence without distortion");
    const std::string f = fmt::format("f_{}.txt", kRunName),
                      kf = fmt::format("kf_{}.txt", kRunName);
    const Started s = begin(run, cal, "ORB-SLAM3", orbSlam3Settings(run.input, cal),
                            {"CameraTrajectory.txt", "KeyFrameTrajectory.txt", f, kf});
    const fs::path &settings = s.settings, &vocab = s.vocabulary;
    if (run.input == SlamInput::Rgbd) return rgbdTum(run, vocab, settings, cal);
    // Examples/*/..._euroc.cc open SEQ/mav0/cam0/data (cam1, imu0/data.csv): the sequence
    // folder plays mav0 (docs/output.md), so SEQ is a folder holding a link to it
    const fs::path work = fs::absolute(run.work);
    const fs::path mav0 = work / "seq" / "mav0";
    fs::create_directories(mav0.parent_path());
    fs::remove(mav0);  // the link of an earlier run (remove never follows it)
    fs::create_directory_symlink(fs::absolute(cal.sequence), mav0);
    const fs::path times = work / "times.txt";
    writeSlamTimesFile(times, cal);
    return {run.exe.string(),        vocab.string(), settings.string(),
            (work / "seq").string(), times.string(), kRunName};
  }

  SlamEstimate collect(const ExternalRun& run, const SlamCalibration& cal) const override {
    const fs::path work = fs::absolute(run.work);
    SlamEstimate est;
    if (run.input == SlamInput::Rgbd) {
      est.camera = readTumEstimate(work / "CameraTrajectory.txt", cal, log(run));
      est.keyframes = readTumEstimate(work / "KeyFrameTrajectory.txt", cal, log(run));
      return est;
    }
    est.camera = readSlamEstimate(work / fmt::format("f_{}.txt", kRunName), cal, log(run),
                                  parseOrbSlam3EurocText);
    est.keyframes = readSlamEstimate(work / fmt::format("kf_{}.txt", kRunName), cal, log(run),
                                     parseOrbSlam3EurocText);
    if (inertial(run.input)) {
      // System::SaveTrajectoryEuRoC writes the IMU body's pose with an IMU: T_w_cam0 = T_w_imu
      // T_imu_cam0
      const Pose T_imu_cam0 = cal.T_cam0_imu.inverse();
      for (Trajectory* t : {&est.camera, &est.keyframes})
        for (TimedPose& p : t->poses) p.T_world_camera = p.T_world_camera * T_imu_cam0;
    }
    return est;
  }
};

}  // namespace

Trajectory parseOrbSlam3EurocText(const std::string& text, const std::string& path) {
  Trajectory traj;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::vector<std::string> col;
    for (std::string c; fields >> c;) col.push_back(c);
    if (col.empty() || col[0][0] == '#') continue;
    const std::string where = fmt::format("line {}", n);
    if (col.size() != 8)
      throw InputError(path, where,
                       fmt::format("expected 8 columns 't_ns tx ty tz qx qy qz qw', got {}: '{}'",
                                   col.size(), line));
    TimedPose p;
    if (!parseScaledDecimal(col[0], 0, false, p.t_ns) || p.t_ns < 0)
      throw InputError(path, where, "not a time in nanoseconds: '" + col[0] + "'");
    double v[7];
    for (size_t j = 0; j < 7; ++j) {
      char* end = nullptr;
      v[j] = std::strtod(col[j + 1].c_str(), &end);
      if (*end != '\0' || !std::isfinite(v[j]))
        throw InputError(path, where,
                         fmt::format("column {} is not a number: '{}'", j + 2, col[j + 1]));
    }
    Quat q(v[6], v[3], v[4], v[5]);  // the file's order is x y z w
    if (std::abs(q.norm() - 1) > 1e-3)
      throw InputError(path, where,
                       fmt::format("quaternion of norm {} (not a rotation)", q.norm()));
    if (!traj.empty() && p.t_ns <= traj.poses.back().t_ns)
      throw InputError(path, where, "time does not increase");
    p.T_world_camera = {q.normalized(), Vec3(v[0], v[1], v[2])};
    traj.poses.push_back(p);
  }
  return traj;
}

std::unique_ptr<SlamAdapter> makeOrbSlam2Adapter() {
  return std::make_unique<OrbSlam2>();
}
std::unique_ptr<SlamAdapter> makeOrbSlam3Adapter() {
  return std::make_unique<OrbSlam3>();
}

}  // namespace inet
