#pragma once
// SLAM systems run on a sequence folder that `interiornet generate` wrote (ASL layout,
// docs/output.md), with nothing but the folder: intrinsics, depth scale, stereo baseline, frame
// rate and the IMU's rate and noise come from its meta.json and sensor.yaml files
// (readSlamCalibration). docs/evaluation.md documents the systems and the adapter contract.
//
// Two kinds of system:
//   built-in   OpenCV's RGB-D odometry (eval/rgbd_odometry.h), run in this process;
//   external   an executable given by the user (ORB-SLAM2, ORB-SLAM3, ...), driven through a
//              SlamAdapter: one small class per system that writes the settings and input lists
//              the system expects into a work folder, names its command line, and reads back
//              the trajectories it wrote. runExternalSlam runs it with a time limit.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/pose.h"
#include "dataset/asl_writer.h"
#include "trajectory/trajectory.h"

namespace inet {

/// What a system consumes from the sequence folder.
enum class SlamInput { Rgbd, Stereo, Monocular, MonoInertial, StereoInertial };

/// "rgbd", "stereo", "mono", "mono-inertial", "stereo-inertial"; InputError naming `field` and
/// listing them otherwise.
SlamInput parseSlamInput(const std::string& name, const std::string& field = "--input");
const char* slamInputName(SlamInput input);

/// The sequence's calibration in the form SLAM systems take it (OpenCV convention: pixel
/// centres at integers), read from the folder's own files.
struct SlamCalibration {
  std::filesystem::path sequence;
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;  ///< cam0, OpenCV convention (meta.json camera.opencv)
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0;  ///< radial-tangential (cam0/sensor.yaml)
  double fps = 0;                         ///< cam0/sensor.yaml rate_hz
  /// depth0/<t>.png value per metre (1000: millimetres); 0 when the sequence has no depth0.
  double depth_png_scale = 0;
  bool rgb = true;  ///< colour images are RGB (8-bit sRGB), not BGR
  /// cam1 (rectified, same intrinsics) this far right of cam0, metres; 0 = no cam1.
  double stereo_baseline_m = 0;
  /// imu0/: present, rate (Hz) and its sensor.yaml noise figures (continuous-time densities and
  /// random walks, EuRoC/Kalibr units), and T_body_imu (body = cam0).
  bool has_imu = false;
  double imu_rate_hz = 0;
  double gyro_noise_density = 0, gyro_random_walk = 0;    ///< rad/s/sqrt(Hz), rad/s^2/sqrt(Hz)
  double accel_noise_density = 0, accel_random_walk = 0;  ///< m/s^2/sqrt(Hz), m/s^3/sqrt(Hz)
  Pose T_cam0_imu;                                        ///< imu0's T_BS (cam0 = body)
  std::vector<SequenceFrame> frames;                      ///< cam0/data.csv
};

/// Reads the calibration of a sequence folder (InputError naming the file and field when one is
/// missing or malformed; a fisheye or panorama sequence is refused: the systems take pinhole).
SlamCalibration readSlamCalibration(const std::filesystem::path& sequence);

/// An external system's run.
struct ExternalRun {
  std::filesystem::path exe;         ///< the system's executable (e.g. ORB-SLAM2's rgbd_tum)
  std::filesystem::path vocabulary;  ///< ORB vocabulary (ORBvoc.txt) or "" if the system has none
  std::filesystem::path work;        ///< folder for settings, input lists, log and outputs
  SlamInput input = SlamInput::Rgbd;
  double time_limit_s = 3600;  ///< the process is killed after this long (InputError)
};

/// What a system leaves: its trajectories, in its own world frame.
struct SlamEstimate {
  Trajectory camera;     ///< one pose per frame it tracked (T_world_camera, cam0), frame stamps
  Trajectory keyframes;  ///< its keyframes (may be empty)
  double seconds = 0;    ///< wall time of the system (process or odometry)
  std::filesystem::path log;  ///< its stdout and stderr ("" for built-in systems)
};

/// The adapter contract (docs/evaluation.md, "Adding a system"): everything that differs
/// between external systems. An adapter must not touch the sequence folder; it writes below
/// run.work only (symbolic links into the sequence are fine).
class SlamAdapter {
 public:
  virtual ~SlamAdapter() = default;
  /// Registry name ("orbslam2", "orbslam3").
  virtual std::string name() const = 0;
  /// One line for --help.
  virtual std::string description() const = 0;
  /// The inputs it supports.
  virtual std::vector<SlamInput> inputs() const = 0;
  /// Writes the settings file and input lists into run.work (created) and returns the command
  /// line, argv[0] = run.exe. InputError (field "--input") for an input the sequence lacks.
  virtual std::vector<std::string> prepare(const ExternalRun& run,
                                           const SlamCalibration& cal) const = 0;
  /// Reads the trajectories the system wrote below run.work (InputError naming the file when
  /// it is missing or malformed); `seconds` and `log` are filled by runExternalSlam.
  virtual SlamEstimate collect(const ExternalRun& run, const SlamCalibration& cal) const = 0;
};

/// The adapter registered under `name`, or InputError (field "--system") listing the systems.
const SlamAdapter& findSlamAdapter(const std::string& name);
std::vector<const SlamAdapter*> slamAdapters();

/// prepare, run with the time limit (working directory run.work, stdout and stderr to
/// run.work/log.txt), collect. InputError: executable or vocabulary missing or not executable
/// (fields "--exe", "--vocabulary"), a non-zero exit or a signal (naming the log and quoting its
/// last line), the time limit exceeded.
SlamEstimate runExternalSlam(const SlamAdapter& adapter, const ExternalRun& run,
                             const SlamCalibration& cal);

}  // namespace inet
