// eval/slam.h's external side: the calibration read from a sequence folder, the ORB-SLAM2 and
// ORB-SLAM3 adapters and runExternalSlam, run against tests/eval/fake_slam.cpp, which is called
// as the real example programs are, checks their settings keys (fake_slam.h lists them with the
// source file each comes from), and writes trajectories in their formats. One tiny sequence of
// the built-in room from the real binary, stereo with an IMU whose extrinsics are not the
// identity, and an RGB-D copy of it without cam1 and imu0 (about 1.7 s to make).
#include <signal.h>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "../expect_input_error.h"
#include "core/atomic_file.h"
#include "eval/sequence_reader.h"
#include "eval/slam.h"
#include "eval/slam_adapters.h"
#include "fake_slam.h"
#include "generated_sequence.h"
#include "sensors/imu.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::fake_slam::KeyType;

/// T_cam_imu given to `interiornet imu --extrinsics`: the IMU turned 90 deg about z and shifted.
const char* const kExtrinsics = "0 -1 0 0.02  1 0 0 -0.05  0 0 1 0.01  0 0 0 1";
Pose extrinsics() {
  Mat4 T;
  T << 0, -1, 0, 0.02, 1, 0, 0, -0.05, 0, 0, 1, 0.01, 0, 0, 0, 1;
  return Pose::fromMatrix(T);
}
constexpr double kBaseline = 0.1;

/// Sets an environment variable for the life of the object (the fake reads it).
class EnvVar {
 public:
  explicit EnvVar(const char* name) : name_(name) { setenv(name, "1", 1); }
  ~EnvVar() { unsetenv(name_); }

 private:
  const char* name_;
};

class SlamExternal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir("slam_external");
    // 48x36 at 1 spp: the fake only opens the images' names (about 1.6 s)
    const test::RunResult r = test::runInterinet(
        "generate --layout builtin:room --frames " + std::to_string(test::kSeqFrames) +
        " --width 48 --height 36 --fx 45 --fy 45 --spp 1 --passes rgb,depth --stereo " +
        std::to_string(kBaseline) + " --format asl --exposure fixed --no-progress --out " +
        (*dir_ / "stereo").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    stereo_ = new fs::path(*dir_ / "stereo" / "default_room" / "seq_000");
    const test::RunResult imu = test::runInterinet(
        "imu --trajectory " + (*stereo_ / "state_groundtruth_estimate0" / "data.csv").string() +
        " --rate 200 --extrinsics '" + kExtrinsics + "' --out " + stereo_->string());
    ASSERT_EQ(imu.exit_code, 0) << imu.err;
    // the RGB-D sequence: the same without cam1 and imu0 (what generate writes without --stereo
    // and the imu pass)
    rgbd_ = new fs::path(*dir_ / "rgbd" / "seq_000");
    fs::create_directories(*rgbd_);
    for (const char* folder : {"cam0", "depth0", "state_groundtruth_estimate0"})
      fs::copy(*stereo_ / folder, *rgbd_ / folder, fs::copy_options::recursive);
    nlohmann::json meta = nlohmann::json::parse(readTextFile(*stereo_ / "meta.json"));
    meta.erase("stereo");
    test::writeFile(*rgbd_ / "meta.json", meta.dump(2) + "\n");
    // the example programs' names, as links to the fake
    fs::create_directories(*dir_ / "bin");
    for (const char* exe :
         {"rgbd_tum", "stereo_euroc", "mono_euroc", "mono_inertial_euroc", "stereo_inertial_euroc"})
      fs::create_symlink(INET_FAKE_SLAM, *dir_ / "bin" / exe);
    test::writeFile(*dir_ / "ORBvoc.txt", "a vocabulary\n");
  }
  static void TearDownTestSuite() {
    delete stereo_;
    delete rgbd_;
    delete dir_;
  }

  /// A run of `exe` (a name under bin/) in a work folder of its own.
  static ExternalRun run(const std::string& exe, SlamInput input, const std::string& work) {
    ExternalRun r;
    r.exe = *dir_ / "bin" / exe;
    r.vocabulary = *dir_ / "ORBvoc.txt";
    r.work = *dir_ / "work" / work;
    r.input = input;
    r.time_limit_s = 60;
    return r;
  }

  static test::TempDir* dir_;
  static fs::path *rgbd_, *stereo_;
};
test::TempDir* SlamExternal::dir_ = nullptr;
fs::path* SlamExternal::rgbd_ = nullptr;
fs::path* SlamExternal::stereo_ = nullptr;

double angleBetween(const Quat& a, const Quat& b) {
  return a.angularDistance(b);
}

/// What the fake writes for `mode`: ground truth in its world, lost frames left out (frames only
/// or keyframes only), as T_world_camera. Derived from the sequence's ground truth and
/// fake_slam.h, not from anything the adapters read.
Trajectory expectedPoses(const fs::path& seq, const std::string& mode, bool keyframes) {
  const Trajectory gt = SequenceReader(seq).groundTruth();
  const double s = test::fake_slam::worldScale(mode);
  const Quat R = test::fake_slam::worldRotation();
  Trajectory out;
  for (size_t k = 0; k < gt.size(); ++k) {
    if (test::fake_slam::lostFrame(k) || (keyframes && !test::fake_slam::keyFrame(k))) continue;
    const Pose& T = gt.poses[k].T_world_camera;
    out.poses.push_back(
        {gt.poses[k].t_ns, {R * T.q, s * (R * T.t) + test::fake_slam::worldTranslation()}});
  }
  return out;
}

void expectSamePoses(const Trajectory& got, const Trajectory& want, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got.poses[i].t_ns, want.poses[i].t_ns) << "pose " << i;
    EXPECT_LT((got.poses[i].T_world_camera.t - want.poses[i].T_world_camera.t).norm(), 1e-6)
        << "pose " << i;
    EXPECT_LT(angleBetween(got.poses[i].T_world_camera.q, want.poses[i].T_world_camera.q), 1e-6)
        << "pose " << i;
  }
}

double realOf(const cv::FileStorage& fs, const char* key) {
  return static_cast<double>(fs[key]);
}

/// settings.yaml has every key the system reads for `mode` (fake_slam.h lists them, with the
/// source file of each list), of the type it reads, and the sequence's calibration.
void expectSettings(const fs::path& file, bool orbslam3, const std::string& mode) {
  SCOPED_TRACE(file.string());
  cv::FileStorage fs(file.string(), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(readTextFile(file).rfind("%YAML:1.0\n", 0), 0u);
  for (const test::fake_slam::Key& k : test::fake_slam::requiredKeys(orbslam3, mode)) {
    const cv::FileNode n = fs[k.name];
    EXPECT_FALSE(n.empty()) << k.name;
    if (k.type == KeyType::Int) {
      EXPECT_TRUE(n.isInt()) << k.name;
    }
    if (k.type == KeyType::Real) {
      EXPECT_TRUE(n.isReal()) << k.name;  // written as reals ("500.0"), as the examples do
    }
  }
  const std::string cam = orbslam3 ? "Camera1." : "Camera.";
  EXPECT_DOUBLE_EQ(realOf(fs, (cam + "fx").c_str()), 45.0);
  EXPECT_DOUBLE_EQ(realOf(fs, (cam + "cx").c_str()), 23.5);  // (48 - 1) / 2: OpenCV centres
  EXPECT_DOUBLE_EQ(realOf(fs, (cam + "cy").c_str()), 17.5);
  EXPECT_EQ(static_cast<int>(fs["Camera.width"]), 48);
  EXPECT_EQ(static_cast<int>(fs["Camera.RGB"]), 0);  // cv::imread gives BGR
  EXPECT_DOUBLE_EQ(realOf(fs, "Camera.fps"), 25.0);
  if (mode == "rgbd_tum") {
    EXPECT_DOUBLE_EQ(realOf(fs, orbslam3 ? "RGBD.DepthMapFactor" : "DepthMapFactor"), 1000.0);
    EXPECT_GT(realOf(fs, orbslam3 ? "Stereo.b" : "Camera.bf"), 0.0);  // a virtual baseline
  }
  if (mode.rfind("stereo", 0) == 0) {
    if (!orbslam3) {
      EXPECT_NEAR(realOf(fs, "Camera.bf"), 45.0 * kBaseline, 1e-12);
      cv::Mat P;
      fs["RIGHT.P"] >> P;
      EXPECT_NEAR(P.at<double>(0, 3), -45.0 * kBaseline, 1e-12);
    } else {
      cv::Mat T;
      fs["Stereo.T_c1_c2"] >> T;
      EXPECT_NEAR(T.at<float>(0, 3), kBaseline, 1e-7);
      EXPECT_EQ(T.at<float>(0, 0), 1.0f);
    }
  }
  if (mode.find("inertial") != std::string::npos) {
    const ImuNoise euroc = ImuNoise::euroc();  // what generate / imu write by default
    EXPECT_DOUBLE_EQ(realOf(fs, "IMU.NoiseGyro"), euroc.gyroscope_noise_density);
    EXPECT_DOUBLE_EQ(realOf(fs, "IMU.NoiseAcc"), euroc.accelerometer_noise_density);
    EXPECT_DOUBLE_EQ(realOf(fs, "IMU.GyroWalk"), euroc.gyroscope_random_walk);
    EXPECT_DOUBLE_EQ(realOf(fs, "IMU.AccWalk"), euroc.accelerometer_random_walk);
    EXPECT_DOUBLE_EQ(realOf(fs, "IMU.Frequency"), 200.0);
    cv::Mat T;
    fs["IMU.T_b_c1"] >> T;
    const Mat4 want = extrinsics().inverse().matrix();  // T_imu_cam: cam0 into the body
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(T.at<float>(r, c), want(r, c), 1e-7) << r << c;
  }
}

TEST_F(SlamExternal, InputNamesAndRegistry) {
  for (const char* name : {"rgbd", "stereo", "mono", "mono-inertial", "stereo-inertial"})
    EXPECT_EQ(slamInputName(parseSlamInput(name)), std::string(name));
  const InputError e = test::expectInputError([] { parseSlamInput("lidar"); });
  EXPECT_EQ(e.field(), "--input");
  EXPECT_NE(e.problem().find("stereo-inertial"), std::string::npos) << e.what();

  ASSERT_EQ(slamAdapters().size(), 2u);
  EXPECT_EQ(findSlamAdapter("orbslam2").name(), "orbslam2");
  EXPECT_EQ(findSlamAdapter("orbslam3").inputs().size(), 5u);
  const InputError u = test::expectInputError([] { findSlamAdapter("vins"); });
  EXPECT_EQ(u.field(), "--system");
  EXPECT_NE(u.problem().find("orbslam2, orbslam3"), std::string::npos) << u.what();
}

TEST_F(SlamExternal, CalibrationFromTheFolderAlone) {
  const SlamCalibration a = readSlamCalibration(*rgbd_);
  EXPECT_EQ(a.width, 48);
  EXPECT_EQ(a.height, 36);
  EXPECT_DOUBLE_EQ(a.fx, 45.0);
  EXPECT_DOUBLE_EQ(a.fy, 45.0);
  EXPECT_DOUBLE_EQ(a.cx, 23.5);  // OpenCV convention: (48 - 1) / 2
  EXPECT_DOUBLE_EQ(a.cy, 17.5);
  EXPECT_EQ(a.k1, 0.0);
  EXPECT_DOUBLE_EQ(a.fps, 25.0);  // generate's default 25 Hz
  EXPECT_DOUBLE_EQ(a.depth_png_scale, 1000.0);
  EXPECT_EQ(a.stereo_baseline_m, 0.0);
  EXPECT_FALSE(a.has_imu);
  ASSERT_EQ(a.frames.size(), static_cast<size_t>(test::kSeqFrames));
  EXPECT_EQ(a.frames[1].t_ns, 40'000'000);

  const SlamCalibration b = readSlamCalibration(*stereo_);
  EXPECT_DOUBLE_EQ(b.stereo_baseline_m, kBaseline);
  EXPECT_TRUE(b.has_imu);
  EXPECT_DOUBLE_EQ(b.imu_rate_hz, 200.0);
  const ImuNoise euroc = ImuNoise::euroc();
  EXPECT_DOUBLE_EQ(b.gyro_noise_density, euroc.gyroscope_noise_density);
  EXPECT_DOUBLE_EQ(b.gyro_random_walk, euroc.gyroscope_random_walk);
  EXPECT_DOUBLE_EQ(b.accel_noise_density, euroc.accelerometer_noise_density);
  EXPECT_DOUBLE_EQ(b.accel_random_walk, euroc.accelerometer_random_walk);
  EXPECT_LT((b.T_cam0_imu.matrix() - extrinsics().matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_F(SlamExternal, CalibrationErrorsNameFileAndField) {
  // a copy of the calibration files only: the reader needs no image
  const fs::path copy = *dir_ / "broken";
  for (const char* f : {"meta.json", "cam0/sensor.yaml", "cam0/data.csv"})
    test::writeFile(copy / f, readTextFile(*rgbd_ / f));
  ASSERT_NO_THROW(readSlamCalibration(copy));
  const std::string meta = readTextFile(copy / "meta.json");
  const std::string yaml = readTextFile(copy / "cam0/sensor.yaml");

  std::string fisheye = meta;
  fisheye.replace(fisheye.find("\"lens\": \"pinhole\""), 17, "\"lens\": \"fisheye\"");
  test::writeFile(copy / "meta.json", fisheye);
  InputError e = test::expectInputError([&] { readSlamCalibration(copy); });
  EXPECT_EQ(e.file(), (copy / "meta.json").string());
  EXPECT_EQ(e.field(), "camera.lens");
  test::writeFile(copy / "meta.json", meta);

  std::string no_rate = yaml;
  no_rate.erase(no_rate.find("rate_hz: 25\n"), 12);
  test::writeFile(copy / "cam0/sensor.yaml", no_rate);
  e = test::expectInputError([&] { readSlamCalibration(copy); });
  EXPECT_EQ(e.file(), (copy / "cam0/sensor.yaml").string());
  EXPECT_EQ(e.field(), "rate_hz");

  std::string bad = yaml;
  bad.replace(bad.find("rate_hz: 25"), 11, "rate_hz: 2x");
  test::writeFile(copy / "cam0/sensor.yaml", bad);
  e = test::expectInputError([&] { readSlamCalibration(copy); });
  EXPECT_EQ(e.field(), "rate_hz");
  EXPECT_NE(e.problem().find("line "), std::string::npos) << e.what();
}

struct Case {
  const char* system;
  const char* exe;
  SlamInput input;
  bool stereo_sequence;
};

TEST_F(SlamExternal, EveryAdapterAndInputGivesBackWhatTheSystemWrote) {
  const Case cases[] = {
      {"orbslam2", "rgbd_tum", SlamInput::Rgbd, false},
      {"orbslam2", "stereo_euroc", SlamInput::Stereo, true},
      {"orbslam2", "mono_euroc", SlamInput::Monocular, false},
      {"orbslam3", "rgbd_tum", SlamInput::Rgbd, false},
      {"orbslam3", "stereo_euroc", SlamInput::Stereo, true},
      {"orbslam3", "mono_euroc", SlamInput::Monocular, false},
      {"orbslam3", "mono_inertial_euroc", SlamInput::MonoInertial, true},
      {"orbslam3", "stereo_inertial_euroc", SlamInput::StereoInertial, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.system) + " " + slamInputName(c.input));
    const fs::path& seq = c.stereo_sequence ? *stereo_ : *rgbd_;
    const SlamCalibration cal = readSlamCalibration(seq);
    const ExternalRun r = run(c.exe, c.input, std::string(c.system) + "_" + c.exe);
    const SlamEstimate est = runExternalSlam(findSlamAdapter(c.system), r, cal);
    EXPECT_GT(est.seconds, 0.0);
    EXPECT_EQ(est.log, fs::absolute(r.work) / "log.txt");
    EXPECT_NE(readTextFile(est.log).find("fake_slam: tracked"), std::string::npos);

    const bool orbslam3 = std::string(c.system) == "orbslam3";
    const Trajectory frames = expectedPoses(seq, c.exe, false);
    const Trajectory keys = expectedPoses(seq, c.exe, true);
    if (!orbslam3 && c.input == SlamInput::Monocular) {
      expectSamePoses(est.camera, keys, "camera = keyframes: mono_euroc saves nothing else");
    } else {
      expectSamePoses(est.camera, frames, "camera");
      EXPECT_EQ(est.camera.size(), static_cast<size_t>(test::kSeqFrames - 1));  // one lost
    }
    if (!orbslam3 && c.input == SlamInput::Stereo)
      EXPECT_TRUE(est.keyframes.empty());  // stereo_euroc saves the frames only
    else
      expectSamePoses(est.keyframes, keys, "keyframes");
    expectSettings(r.work / "settings.yaml", orbslam3, c.exe);
  }
}

TEST_F(SlamExternal, InputListsAreWhatTheExamplesRead) {
  const SlamCalibration cal = readSlamCalibration(*rgbd_);
  const ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "lists");
  findSlamAdapter("orbslam2").prepare(r, cal);
  std::ifstream assoc(r.work / "associations.txt");
  std::string t1, rgb, t2, depth;
  ASSERT_TRUE(assoc >> t1 >> rgb >> t2 >> depth);
  EXPECT_EQ(t1, "0.000000000");
  EXPECT_EQ(rgb, "cam0/data/" + cal.frames[0].stamp + ".png");
  EXPECT_EQ(depth, "depth0/data/" + cal.frames[0].stamp + ".png");
  EXPECT_TRUE(fs::exists(*rgbd_ / rgb) && fs::exists(*rgbd_ / depth));

  const ExternalRun m = run("mono_euroc", SlamInput::Monocular, "lists3");
  const std::vector<std::string> argv = findSlamAdapter("orbslam3").prepare(m, cal);
  ASSERT_EQ(argv.size(), 6u);
  EXPECT_EQ(argv[3], (fs::absolute(m.work) / "seq").string());
  EXPECT_TRUE(
      fs::exists(fs::path(argv[3]) / "mav0" / "cam0" / "data" / (cal.frames[5].stamp + ".png")));
  EXPECT_EQ(readTextFile(argv[4]).substr(0, 20), cal.frames[0].stamp + "\n");
  EXPECT_EQ(argv[5], "inet");
  // a second prepare replaces the link of the first
  EXPECT_NO_THROW(findSlamAdapter("orbslam3").prepare(m, cal));
}

TEST_F(SlamExternal, ExecutableAndVocabularyErrors) {
  const SlamCalibration cal = readSlamCalibration(*rgbd_);
  const SlamAdapter& orb = findSlamAdapter("orbslam2");
  ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "errors");

  r.exe = *dir_ / "bin" / "no_such_program";
  InputError e = test::expectInputError([&] { runExternalSlam(orb, r, cal); });
  EXPECT_EQ(e.field(), "--exe");
  EXPECT_EQ(e.file(), r.exe.string());
  EXPECT_EQ(e.problem(), "not found");

  r.exe = *dir_ / "not_executable";
  test::writeFile(r.exe, "#!/bin/sh\n");
  fs::permissions(r.exe, fs::perms::owner_read | fs::perms::owner_write);
  e = test::expectInputError([&] { runExternalSlam(orb, r, cal); });
  EXPECT_EQ(e.field(), "--exe");
  EXPECT_NE(e.problem().find("not executable"), std::string::npos) << e.what();

  r = run("rgbd_tum", SlamInput::Rgbd, "errors");
  r.vocabulary = *dir_ / "missing.txt";
  e = test::expectInputError([&] { runExternalSlam(orb, r, cal); });
  EXPECT_EQ(e.field(), "--vocabulary");
  EXPECT_EQ(e.file(), r.vocabulary.string());
  r.vocabulary.clear();
  e = test::expectInputError([&] { runExternalSlam(orb, r, cal); });
  EXPECT_EQ(e.field(), "--vocabulary");
  EXPECT_NE(e.problem().find("ORBvoc.txt"), std::string::npos) << e.what();
}

TEST_F(SlamExternal, NonZeroExitNamesTheLogAndQuotesItsLastLine) {
  const SlamCalibration cal = readSlamCalibration(*rgbd_);
  const ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "fail");
  const EnvVar fail("FAKE_SLAM_FAIL");
  const InputError e =
      test::expectInputError([&] { runExternalSlam(findSlamAdapter("orbslam3"), r, cal); });
  EXPECT_EQ(e.file(), (fs::absolute(r.work) / "log.txt").string());
  EXPECT_NE(e.problem().find("exited with status 3"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("'fake_slam: failing as asked (FAKE_SLAM_FAIL)'"), std::string::npos)
      << e.what();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
}

/// Whether process `pid` is gone (or a zombie nobody reaped yet: it runs no more).
bool gone(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const size_t paren = line.rfind(')');
  return paren != std::string::npos && line.size() > paren + 2 && line[paren + 2] == 'Z';
}

TEST_F(SlamExternal, TimeLimitKillsTheProcessGroup) {
  const SlamCalibration cal = readSlamCalibration(*rgbd_);
  ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "hang");
  r.time_limit_s = 1;
  const EnvVar hang("FAKE_SLAM_HANG");
  const auto start = std::chrono::steady_clock::now();
  const InputError e =
      test::expectInputError([&] { runExternalSlam(findSlamAdapter("orbslam2"), r, cal); });
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(e.field(), "--time-limit");
  EXPECT_EQ(e.file(), (fs::absolute(r.work) / "log.txt").string());
  EXPECT_NE(e.problem().find("hanging as asked"), std::string::npos) << e.what();
  EXPECT_GE(waited, 1.0);
  EXPECT_LT(waited, 5.0);
  // the program's own child went with it
  pid_t child = 0;
  std::ifstream(r.work / "hang_child.pid") >> child;
  ASSERT_GT(child, 0);
  for (int i = 0; i < 100 && !gone(child); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_TRUE(gone(child)) << "pid " << child;
  if (!gone(child)) kill(child, SIGKILL);
}

TEST_F(SlamExternal, TrajectoryFilesMalformedEmptyOrMissing) {
  const SlamCalibration rgbd = readSlamCalibration(*rgbd_);
  const SlamCalibration stereo = readSlamCalibration(*stereo_);
  {
    const EnvVar bad("FAKE_SLAM_MALFORMED");
    const ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "malformed2");
    InputError e =
        test::expectInputError([&] { runExternalSlam(findSlamAdapter("orbslam2"), r, rgbd); });
    EXPECT_EQ(e.file(), (fs::absolute(r.work) / "CameraTrajectory.txt").string());
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    const ExternalRun r3 = run("stereo_euroc", SlamInput::Stereo, "malformed3");
    e = test::expectInputError([&] { runExternalSlam(findSlamAdapter("orbslam3"), r3, stereo); });
    EXPECT_EQ(e.file(), (fs::absolute(r3.work) / "f_inet.txt").string());
    EXPECT_EQ(e.field(), "line 2");
  }
  {
    const EnvVar empty("FAKE_SLAM_EMPTY");
    const ExternalRun r = run("stereo_inertial_euroc", SlamInput::StereoInertial, "empty");
    const SlamEstimate est = runExternalSlam(findSlamAdapter("orbslam3"), r, stereo);
    EXPECT_TRUE(est.camera.empty());  // lost everything: no pose, no error
    EXPECT_TRUE(est.keyframes.empty());
  }
  {
    const EnvVar none("FAKE_SLAM_NO_OUTPUT");
    const ExternalRun r = run("rgbd_tum", SlamInput::Rgbd, "no_output");
    const InputError e =
        test::expectInputError([&] { runExternalSlam(findSlamAdapter("orbslam2"), r, rgbd); });
    EXPECT_EQ(e.file(), (fs::absolute(r.work) / "CameraTrajectory.txt").string());
    EXPECT_NE(e.problem().find("missing"), std::string::npos) << e.what();
  }
}

TEST_F(SlamExternal, InputTheSequenceOrSystemLacks) {
  const SlamCalibration rgbd = readSlamCalibration(*rgbd_);
  const SlamCalibration stereo = readSlamCalibration(*stereo_);
  const SlamAdapter& orb3 = findSlamAdapter("orbslam3");
  InputError e = test::expectInputError(
      [&] { orb3.prepare(run("stereo_euroc", SlamInput::Stereo, "lack1"), rgbd); });
  EXPECT_EQ(e.field(), "--input");
  EXPECT_EQ(e.file(), (*rgbd_ / "cam1" / "sensor.yaml").string());
  e = test::expectInputError(
      [&] { orb3.prepare(run("mono_inertial_euroc", SlamInput::MonoInertial, "lack2"), rgbd); });
  EXPECT_EQ(e.field(), "--input");
  EXPECT_EQ(e.file(), (*rgbd_ / "imu0" / "sensor.yaml").string());
  e = test::expectInputError([&] {
    findSlamAdapter("orbslam2")
        .prepare(run("mono_inertial_euroc", SlamInput::MonoInertial, "lack3"), stereo);
  });
  EXPECT_EQ(e.field(), "--input");
  EXPECT_NE(e.problem().find("it takes: rgbd, stereo, mono"), std::string::npos) << e.what();
}

TEST(SlamEstimateReaders, StampsSnapToFramesWithinOneMillisecond) {
  SlamCalibration cal;
  for (TimeNs t : {0, 40'000'000, 80'000'000}) cal.frames.push_back({t, "", ""});
  Trajectory t;
  t.poses.push_back({39'999'999, {}});  // float seconds of frame 1
  t.poses.push_back({80'000'400, {}});
  const Trajectory s = snapToFrames(t, cal, "est.txt");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.poses[0].t_ns, 40'000'000);
  EXPECT_EQ(s.poses[1].t_ns, 80'000'000);
  t.poses = {{20'000'000, {}}};
  InputError e = test::expectInputError([&] { snapToFrames(t, cal, "est.txt"); });
  EXPECT_EQ(e.file(), "est.txt");
  EXPECT_NE(e.problem().find("within 1 ms"), std::string::npos) << e.what();
  t.poses = {{40'000'000, {}}, {40'000'500, {}}};
  e = test::expectInputError([&] { snapToFrames(t, cal, "est.txt"); });
  EXPECT_NE(e.problem().find("second pose"), std::string::npos) << e.what();
}

TEST(SlamEstimateReaders, OrbSlam3EurocText) {
  const Trajectory t = parseOrbSlam3EurocText(
      "40000000.000000 1.0 2.0 3.0 0.0 0.0 0.0 1.0\n\n"
      "80000000.000001 1.5 2.0 3.0 0.0 0.0 0.707106781 0.707106781\n",
      "f.txt");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].t_ns, 40'000'000);
  EXPECT_EQ(t.poses[1].t_ns, 80'000'000);
  EXPECT_EQ(t.poses[1].T_world_camera.t, Vec3(1.5, 2.0, 3.0));
  EXPECT_NEAR(t.poses[1].T_world_camera.q.w(), std::sqrt(0.5), 1e-9);  // w is last in the file
  InputError e =
      test::expectInputError([] { parseOrbSlam3EurocText("1.0 2.0 3.0 4.0\n", "f.txt"); });
  EXPECT_EQ(e.file(), "f.txt");
  EXPECT_EQ(e.field(), "line 1");
  e = test::expectInputError(
      [] { parseOrbSlam3EurocText("0 0 0 0 0 0 0 1\n5 0 0 0 0 0 0 2\n", "f.txt"); });
  EXPECT_EQ(e.field(), "line 2");
  e = test::expectInputError(
      [] { parseOrbSlam3EurocText("0 0 0 0 0 0 0 1\n5 0 x 0 0 0 0 1\n", "f.txt"); });
  EXPECT_EQ(e.field(), "line 2");
}

}  // namespace
}  // namespace inet
