#pragma once
// Shared by tests/eval/fake_slam.cpp (a stand-in for the ORB-SLAM2/3 example programs) and
// tests/eval/slam_external_test.cpp: the settings keys each system reads, which the fake
// demands and the test looks for, and what the fake writes (ground truth moved into a world of
// its own, some frames lost).
#include <Eigen/Geometry>

#include <cstddef>
#include <string>
#include <vector>

namespace inet::test::fake_slam {

/// How the system reads a key: ORB-SLAM3's Settings.cc aborts on a wrong type (an int key must be
/// an int, a matrix must be dt f); ORB-SLAM2 converts any number.
enum class KeyType { Real, Int, Text, Matrix };
struct Key {
  const char* name;
  KeyType type;
};

// ---- ORB-SLAM2 (raulmur/ORB_SLAM2) ----
/// src/Tracking.cc (Tracking::Tracking), src/Viewer.cc and src/MapDrawer.cc (constructors): every
/// input. Camera.k3 is read too but used only when non-zero.
inline const std::vector<Key> kOrbSlam2Keys = {{"Camera.fx", KeyType::Real},
                                               {"Camera.fy", KeyType::Real},
                                               {"Camera.cx", KeyType::Real},
                                               {"Camera.cy", KeyType::Real},
                                               {"Camera.k1", KeyType::Real},
                                               {"Camera.k2", KeyType::Real},
                                               {"Camera.p1", KeyType::Real},
                                               {"Camera.p2", KeyType::Real},
                                               {"Camera.fps", KeyType::Real},
                                               {"Camera.RGB", KeyType::Int},
                                               {"Camera.width", KeyType::Int},
                                               {"Camera.height", KeyType::Int},
                                               {"ORBextractor.nFeatures", KeyType::Int},
                                               {"ORBextractor.scaleFactor", KeyType::Real},
                                               {"ORBextractor.nLevels", KeyType::Int},
                                               {"ORBextractor.iniThFAST", KeyType::Int},
                                               {"ORBextractor.minThFAST", KeyType::Int},
                                               {"Viewer.KeyFrameSize", KeyType::Real},
                                               {"Viewer.KeyFrameLineWidth", KeyType::Real},
                                               {"Viewer.GraphLineWidth", KeyType::Real},
                                               {"Viewer.PointSize", KeyType::Real},
                                               {"Viewer.CameraSize", KeyType::Real},
                                               {"Viewer.CameraLineWidth", KeyType::Real},
                                               {"Viewer.ViewpointX", KeyType::Real},
                                               {"Viewer.ViewpointY", KeyType::Real},
                                               {"Viewer.ViewpointZ", KeyType::Real},
                                               {"Viewer.ViewpointF", KeyType::Real}};
/// src/Tracking.cc: stereo and RGB-D (bf = baseline x fx, close/far threshold).
inline const std::vector<Key> kOrbSlam2DepthKeys = {{"Camera.bf", KeyType::Real},
                                                    {"ThDepth", KeyType::Real}};
/// src/Tracking.cc: RGB-D.
inline const std::vector<Key> kOrbSlam2RgbdKeys = {{"DepthMapFactor", KeyType::Real}};
/// Examples/Stereo/stereo_euroc.cc: the rectification it applies to every image (it stops with
/// "Calibration parameters to rectify stereo are missing!" without them).
inline const std::vector<Key> kOrbSlam2StereoKeys = {
    {"LEFT.K", KeyType::Matrix},  {"RIGHT.K", KeyType::Matrix},   {"LEFT.P", KeyType::Matrix},
    {"RIGHT.P", KeyType::Matrix}, {"LEFT.R", KeyType::Matrix},    {"RIGHT.R", KeyType::Matrix},
    {"LEFT.D", KeyType::Matrix},  {"RIGHT.D", KeyType::Matrix},   {"LEFT.height", KeyType::Int},
    {"LEFT.width", KeyType::Int}, {"RIGHT.height", KeyType::Int}, {"RIGHT.width", KeyType::Int}};

// ---- ORB-SLAM3 v1.0 (UZ-SLAMLab/ORB_SLAM3): src/System.cc hands a file whose File.version is
// "1.0" to src/Settings.cc, which aborts on a missing required key or a wrong type ----
/// Settings::readCamera1 (PinHole), readImageInfo, readORB, readViewer (the examples open the
/// viewer: then its keys are required): every input.
inline const std::vector<Key> kOrbSlam3Keys = {{"File.version", KeyType::Text},
                                               {"Camera.type", KeyType::Text},
                                               {"Camera1.fx", KeyType::Real},
                                               {"Camera1.fy", KeyType::Real},
                                               {"Camera1.cx", KeyType::Real},
                                               {"Camera1.cy", KeyType::Real},
                                               {"Camera.width", KeyType::Int},
                                               {"Camera.height", KeyType::Int},
                                               {"Camera.fps", KeyType::Int},
                                               {"Camera.RGB", KeyType::Int},
                                               {"ORBextractor.nFeatures", KeyType::Int},
                                               {"ORBextractor.scaleFactor", KeyType::Real},
                                               {"ORBextractor.nLevels", KeyType::Int},
                                               {"ORBextractor.iniThFAST", KeyType::Int},
                                               {"ORBextractor.minThFAST", KeyType::Int},
                                               {"Viewer.KeyFrameSize", KeyType::Real},
                                               {"Viewer.KeyFrameLineWidth", KeyType::Real},
                                               {"Viewer.GraphLineWidth", KeyType::Real},
                                               {"Viewer.PointSize", KeyType::Real},
                                               {"Viewer.CameraSize", KeyType::Real},
                                               {"Viewer.CameraLineWidth", KeyType::Real},
                                               {"Viewer.ViewpointX", KeyType::Real},
                                               {"Viewer.ViewpointY", KeyType::Real},
                                               {"Viewer.ViewpointZ", KeyType::Real},
                                               {"Viewer.ViewpointF", KeyType::Real}};
/// Settings::readCamera2 (PinHole, not rectified): stereo and stereo-inertial.
inline const std::vector<Key> kOrbSlam3StereoKeys = {
    {"Camera2.fx", KeyType::Real},       {"Camera2.fy", KeyType::Real},
    {"Camera2.cx", KeyType::Real},       {"Camera2.cy", KeyType::Real},
    {"Stereo.T_c1_c2", KeyType::Matrix}, {"Stereo.ThDepth", KeyType::Real}};
/// Settings::readRGBD.
inline const std::vector<Key> kOrbSlam3RgbdKeys = {{"RGBD.DepthMapFactor", KeyType::Real},
                                                   {"Stereo.ThDepth", KeyType::Real},
                                                   {"Stereo.b", KeyType::Real}};
/// Settings::readIMU: mono-inertial and stereo-inertial.
inline const std::vector<Key> kOrbSlam3ImuKeys = {
    {"IMU.NoiseGyro", KeyType::Real}, {"IMU.NoiseAcc", KeyType::Real},
    {"IMU.GyroWalk", KeyType::Real},  {"IMU.AccWalk", KeyType::Real},
    {"IMU.Frequency", KeyType::Real}, {"IMU.T_b_c1", KeyType::Matrix}};

/// The keys a run needs: `orbslam3` or not, `mode` the example program's name (rgbd_tum,
/// stereo_euroc, mono_euroc, mono_inertial_euroc, stereo_inertial_euroc).
inline std::vector<Key> requiredKeys(bool orbslam3, const std::string& mode) {
  const bool rgbd = mode == "rgbd_tum";
  const bool stereo = mode.rfind("stereo", 0) == 0;
  const bool imu = mode.find("inertial") != std::string::npos;
  std::vector<Key> keys = orbslam3 ? kOrbSlam3Keys : kOrbSlam2Keys;
  auto add = [&](const std::vector<Key>& more) {
    keys.insert(keys.end(), more.begin(), more.end());
  };
  if (!orbslam3) {
    if (rgbd || stereo) add(kOrbSlam2DepthKeys);
    if (rgbd) add(kOrbSlam2RgbdKeys);
    if (stereo) add(kOrbSlam2StereoKeys);
    return keys;
  }
  if (stereo) add(kOrbSlam3StereoKeys);
  if (rgbd) add(kOrbSlam3RgbdKeys);
  if (imu) add(kOrbSlam3ImuKeys);
  return keys;
}

// ---- what the fake writes ----
/// The fake's world: p_fake = s R p_world + t, with the scale s free (0.5) for monocular input
/// only (the others are metric).
inline Eigen::Quaterniond worldRotation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
}
inline Eigen::Vector3d worldTranslation() {
  return {0.5, -1.0, 2.0};
}
inline double worldScale(const std::string& mode) {
  return mode == "mono_euroc" ? 0.5 : 1.0;
}
/// Frame k (0-based, in list order) is lost when k % 4 == 2 (no pose written).
inline bool lostFrame(size_t k) {
  return k % 4 == 2;
}
/// Keyframes: frames with k % 4 == 0.
inline bool keyFrame(size_t k) {
  return k % 4 == 0;
}

}  // namespace inet::test::fake_slam
