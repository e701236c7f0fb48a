// A stand-in for the ORB-SLAM2 and ORB-SLAM3 example programs, for tests/eval/slam_external_test:
// called exactly as they are, it checks what they would (vocabulary file, settings keys and types
// through cv::FileStorage, every image and list the arguments name) and writes the trajectory
// files they write, in their formats, from the sequence's ground truth moved into a world of its
// own with some frames lost (tests/eval/fake_slam.h).
//
// Mode: argv[0]'s basename (rgbd_tum, stereo_euroc, mono_euroc, mono_inertial_euroc,
// stereo_inertial_euroc) or FAKE_SLAM_MODE. System: ORB-SLAM3 when the settings have
// File.version, else ORB-SLAM2. Misbehaviour on request (environment):
//   FAKE_SLAM_FAIL       print a message and exit with status 3
//   FAKE_SLAM_HANG       start a child (its pid in hang_child.pid) and sleep, both for 10 min
//   FAKE_SLAM_MALFORMED  the frame trajectory's second row has 3 columns
//   FAKE_SLAM_EMPTY      write the trajectory files without a pose
//   FAKE_SLAM_NO_OUTPUT  write no trajectory
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fake_slam.h"

namespace fs = std::filesystem;
using namespace inet::test::fake_slam;

namespace {

[[noreturn]] void fail(const std::string& message, int status = 1) {
  std::cerr << message << std::endl;
  std::exit(status);
}

bool env(const char* name) {
  return std::getenv(name) != nullptr;
}

/// The checks ORB-SLAM3's Settings::readParameter makes (ORB-SLAM2 takes any number: for it a
/// key only has to be there), with its message.
void checkSettings(const cv::FileStorage& fs, bool orbslam3, const std::string& mode) {
  for (const Key& k : requiredKeys(orbslam3, mode)) {
    const cv::FileNode node = fs[k.name];
    if (node.empty())
      fail(std::string(k.name) + " required parameter does not exist, aborting...", 255);
    bool ok = true;
    switch (k.type) {
      case KeyType::Real:
        ok = node.isReal() || node.isInt();
        break;
      case KeyType::Int:
        ok = node.isInt() || (!orbslam3 && node.isReal());
        break;
      case KeyType::Text:
        ok = node.isString();
        break;
      case KeyType::Matrix: {
        cv::Mat m;
        node >> m;
        ok = !m.empty() && (!orbslam3 || m.type() == CV_32F);
        break;
      }
    }
    if (!ok) fail(std::string(k.name) + " parameter has the wrong type, aborting...", 255);
  }
  if (orbslam3 && (fs["File.version"].string() != "1.0" || fs["Camera.type"].string() != "PinHole"))
    fail("File.version must be \"1.0\" and Camera.type \"PinHole\"", 255);
}

/// One frame the program was given: its time in seconds, as the program computes it.
struct Frame {
  double t_s = 0;
};

std::vector<std::string> lines(const fs::path& path) {
  std::ifstream in(path);
  if (!in) fail("cannot open " + path.string());
  std::vector<std::string> out;
  for (std::string s; std::getline(in, s);)
    if (!s.empty()) out.push_back(s);
  return out;
}

void requireFile(const fs::path& p) {
  if (!fs::is_regular_file(p)) fail("Failed to load image at: " + p.string());
}

/// rgbd_tum's association file: `t rgb t depth`, paths relative to the sequence folder.
std::vector<Frame> readAssociations(const fs::path& seq, const fs::path& assoc) {
  std::vector<Frame> frames;
  for (const std::string& line : lines(assoc)) {
    std::istringstream ss(line);
    double t, t_depth;
    std::string rgb, depth;
    if (!(ss >> t >> rgb >> t_depth >> depth)) fail("bad association line: " + line);
    requireFile(seq / rgb);
    requireFile(seq / depth);
    frames.push_back({t});
  }
  return frames;
}

/// The EuRoC examples' times file: `<folder>/<line>.png` in each folder, t = line / 1e9.
std::vector<Frame> readTimes(const std::vector<fs::path>& folders, const fs::path& times) {
  std::vector<Frame> frames;
  for (const std::string& line : lines(times)) {
    for (const fs::path& f : folders) requireFile(f / (line + ".png"));
    frames.push_back({std::stod(line) / 1e9});
  }
  return frames;
}

/// state_groundtruth_estimate0/data.csv: t_ns -> T_world_camera.
std::map<long long, Eigen::Isometry3d> readGroundTruth(const fs::path& seq) {
  std::map<long long, Eigen::Isometry3d> gt;
  for (const std::string& line : lines(seq / "state_groundtruth_estimate0" / "data.csv")) {
    if (line[0] == '#') continue;
    std::vector<double> v;
    std::stringstream ss(line);
    std::string c;
    long long t = 0;
    for (int i = 0; std::getline(ss, c, ','); ++i)
      if (i == 0)
        t = std::stoll(c);
      else
        v.push_back(std::stod(c));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Quaterniond(v[3], v[4], v[5], v[6]).normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    gt[t] = T;
  }
  return gt;
}

Eigen::Isometry3d matrixOf(const cv::FileStorage& fs, const char* key) {
  cv::Mat m;
  fs[key] >> m;
  m.convertTo(m, CV_64F);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = m.at<double>(r, c);
  return T;
}

/// `t tx ty tz qx qy qz qw` as ORB-SLAM writes it: fixed, stamp with 6 decimals (seconds for
/// TUM, 1e9 t for its EuRoC files), the rest with 9.
void writePose(std::ostream& f, double stamp, const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  f << std::fixed << std::setprecision(6) << stamp << " " << std::setprecision(9) << t.x() << " "
    << t.y() << " " << t.z() << " " << q.x() << " " << q.y() << " " << q.z() << " " << q.w()
    << "\n";
}

/// What the arguments name: the sequence folder (the one with state_groundtruth_estimate0/), the
/// frames in list order, and ORB-SLAM3's trajectory name ("" if none).
struct Run {
  fs::path seq;
  std::vector<Frame> frames;
  std::string name;
};

/// The argument shapes of each example program (their Examples/*/*.cc main and LoadImages).
Run readArguments(int argc, char** argv, const std::string& mode, bool orbslam3) {
  const bool stereo = mode.rfind("stereo", 0) == 0;
  const bool inertial = mode.find("inertial") != std::string::npos;
  Run run;
  if (mode == "rgbd_tum") {
    if (argc != 5)
      fail(
          "Usage: ./rgbd_tum path_to_vocabulary path_to_settings path_to_sequence "
          "path_to_association");
    run.seq = argv[3];
    run.frames = readAssociations(run.seq, argv[4]);
  } else if (!orbslam3) {
    if (inertial) fail("ORB-SLAM2 has no " + mode);
    if (argc != (stereo ? 6 : 5))
      fail("Usage: ./" + mode +
           " path_to_vocabulary path_to_settings path_to_image_folder(s) path_to_times_file");
    run.seq = fs::path(argv[3]).parent_path().parent_path();  // <seq>/cam0/data
    std::vector<fs::path> folders = {argv[3]};
    if (stereo) folders.push_back(argv[4]);
    run.frames = readTimes(folders, argv[argc - 1]);
  } else {
    if (argc != 5 && argc != 6)
      fail("Usage: ./" + mode +
           " path_to_vocabulary path_to_settings path_to_sequence_folder path_to_times_file "
           "(trajectory_file_name)");
    run.seq = fs::path(argv[3]) / "mav0";
    std::vector<fs::path> folders = {run.seq / "cam0" / "data"};
    if (stereo) folders.push_back(run.seq / "cam1" / "data");
    run.frames = readTimes(folders, argv[4]);
    if (argc == 6) run.name = argv[5];
    if (inertial) {
      const std::vector<std::string> imu = lines(run.seq / "imu0" / "data.csv");
      if (imu.size() < 2 || std::stod(imu[1]) / 1e9 > run.frames.front().t_s)
        fail("the IMU must start before the first image");
    }
  }
  return run;
}

/// The files each program writes after SLAM.Shutdown(): ground truth in the fake's world, lost
/// frames left out; returns the number of frames tracked.
size_t writeTrajectories(const Run& run, const std::string& mode, bool orbslam3,
                         const cv::FileStorage& settings) {
  const bool mono = mode == "mono_euroc", stereo = mode == "stereo_euroc";
  const std::map<long long, Eigen::Isometry3d> gt = readGroundTruth(run.seq);
  const double s = worldScale(mode);
  // ORB-SLAM3 gives the IMU body's pose with an IMU (System::SaveTrajectoryEuRoC)
  const Eigen::Isometry3d T_cam_body = mode.find("inertial") != std::string::npos
                                           ? matrixOf(settings, "IMU.T_b_c1").inverse()
                                           : Eigen::Isometry3d::Identity();
  const bool euroc = orbslam3 && mode != "rgbd_tum";
  std::string frames_file = "CameraTrajectory.txt", keys_file = "KeyFrameTrajectory.txt";
  if (euroc && !run.name.empty()) {
    frames_file = "f_" + run.name + ".txt";
    keys_file = "kf_" + run.name + ".txt";
  }
  const bool write_frames = orbslam3 || !mono;  // ORB-SLAM2 mono_euroc: keyframes only
  const bool write_keys = orbslam3 || !stereo;  // ORB-SLAM2 stereo_euroc: frames only
  std::ofstream f, kf;
  if (write_frames) f.open(frames_file);
  if (write_keys) kf.open(keys_file);
  size_t tracked = 0;
  for (size_t k = 0; k < run.frames.size() && !env("FAKE_SLAM_EMPTY"); ++k) {
    if (lostFrame(k)) continue;
    const auto it = gt.find(std::llround(run.frames[k].t_s * 1e9));
    if (it == gt.end()) fail("fake_slam: no ground truth at a frame");
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = worldRotation() * it->second.linear();
    T.translation() = s * (worldRotation() * it->second.translation()) + worldTranslation();
    T = T * T_cam_body;
    const double stamp = euroc ? 1e9 * run.frames[k].t_s : run.frames[k].t_s;
    if (write_frames && env("FAKE_SLAM_MALFORMED") && tracked == 1)
      f << "garbage row " << stamp << "\n";
    else if (write_frames)
      writePose(f, stamp, T);
    if (write_keys && keyFrame(k)) writePose(kf, stamp, T);
    ++tracked;
  }
  return tracked;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode =
      env("FAKE_SLAM_MODE") ? std::getenv("FAKE_SLAM_MODE") : fs::path(argv[0]).filename().string();
  if (mode != "rgbd_tum" && mode != "stereo_euroc" && mode != "mono_euroc" &&
      mode != "mono_inertial_euroc" && mode != "stereo_inertial_euroc")
    fail("fake_slam: unknown mode '" + mode + "'");
  if (argc < 5) fail("Usage: ./" + mode + " path_to_vocabulary path_to_settings ...");
  if (!fs::is_regular_file(argv[1]))
    fail(std::string("Wrong path to vocabulary. Failed to open at: ") + argv[1], 255);
  cv::FileStorage settings;
  try {
    settings.open(argv[2], cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    fail(std::string("Failed to parse settings file at: ") + argv[2] + ": " + e.what(), 255);
  }
  if (!settings.isOpened()) fail(std::string("Failed to open settings file at: ") + argv[2], 255);
  const bool orbslam3 = !settings["File.version"].empty();
  checkSettings(settings, orbslam3, mode);
  const Run run = readArguments(argc, argv, mode, orbslam3);
  std::cout << "fake_slam: " << mode << " (" << (orbslam3 ? "ORB-SLAM3" : "ORB-SLAM2") << "), "
            << run.frames.size() << " frames" << std::endl;

  if (env("FAKE_SLAM_FAIL")) fail("fake_slam: failing as asked (FAKE_SLAM_FAIL)", 3);
  if (env("FAKE_SLAM_HANG")) {
    const pid_t child = fork();
    if (child == 0) {
      sleep(600);
      _exit(0);
    }
    std::ofstream("hang_child.pid") << child << "\n";
    std::cout << "fake_slam: hanging as asked (FAKE_SLAM_HANG)" << std::endl;
    sleep(600);
    return 0;
  }
  if (env("FAKE_SLAM_NO_OUTPUT")) return 0;
  const size_t tracked = writeTrajectories(run, mode, orbslam3, settings);
  std::cout << "fake_slam: tracked " << tracked << " of " << run.frames.size() << " frames"
            << std::endl;
  return 0;
}
