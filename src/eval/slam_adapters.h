#pragma once
// For the SlamAdapter implementations (eval/slam.h) and their tests only: the registry's
// factories and the pieces every external adapter needs (input lists, its settings-file syntax,
// trajectory readers that give back frame stamps). Not part of the eval API.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "eval/slam.h"

namespace inet {

/// The registry's entries (eval/slam_orbslam.cpp): ORB-SLAM2 and ORB-SLAM3 example executables.
std::unique_ptr<SlamAdapter> makeOrbSlam2Adapter();
std::unique_ptr<SlamAdapter> makeOrbSlam3Adapter();

/// InputError (field "--input") when `system` does not take `input` (the message lists those it
/// takes) or the sequence lacks it: rgbd needs depth0, stereo cam1, the inertial inputs imu0.
void requireSlamInput(const SlamAdapter& system, SlamInput input, const SlamCalibration& cal);

/// An absolute path to the vocabulary (InputError, field "--vocabulary", when it is empty).
std::filesystem::path requireVocabulary(const ExternalRun& run, const std::string& system);

/// A EuRoC-style times file: one cam0 stamp per line in integer nanoseconds, exactly as
/// cam0/data.csv writes it, so that `<image folder>/<line>.png` names the frame's image (what
/// the ORB-SLAM EuRoC examples open). InputError naming cam0/data.csv for a row whose file is
/// not `<stamp>.png`.
void writeSlamTimesFile(const std::filesystem::path& path, const SlamCalibration& cal);

/// A TUM association file, `t_rgb rgb_path t_depth depth_path` per frame, t in seconds (9
/// decimals: exact nanoseconds), paths relative to the sequence folder (cam0/data/<t>.png,
/// depth0/data/<t>.png).
void writeSlamAssociations(const std::filesystem::path& path, const SlamCalibration& cal);

/// Text of an OpenCV FileStorage YAML settings file (`%YAML:1.0` first), one key a line; keys
/// stay in the order written.
class OpenCvYaml {
 public:
  OpenCvYaml();
  void comment(const std::string& text);        ///< "# text" (a blank line before it)
  void real(const std::string& key, double v);  ///< always written as a real ("500.0")
  void integer(const std::string& key, long long v);
  void text(const std::string& key, const std::string& v);  ///< a quoted string
  /// `!!opencv-matrix`, rows x cols row-major, dt "d" (double) or "f" (float).
  void matrix(const std::string& key, int rows, int cols, const std::vector<double>& v,
              char dt = 'd');
  const std::string& str() const { return s_; }

 private:
  std::string s_;
};

/// Poses read from a system's output, snapped to the sequence's frames: each stamp becomes the
/// nearest cam0 stamp within 1 ms. Seconds in 6 decimals (TUM files) and float nanoseconds lose
/// nothing near a frame, while frames are at least a few ms apart, so the nearest frame within
/// 1 ms is the frame the system was given. InputError naming `file` for a stamp with no frame
/// that close, or two poses on one frame.
Trajectory snapToFrames(const Trajectory& traj, const SlamCalibration& cal,
                        const std::filesystem::path& file);

/// A trajectory file the system wrote, parsed by `parse(text, path)` and snapped to frames. A
/// file without pose lines (only blanks and '#' lines) is an empty trajectory: a system that lost
/// every frame still writes its file. A missing file is an InputError naming it and `log`.
Trajectory readSlamEstimate(
    const std::filesystem::path& file, const SlamCalibration& cal, const std::filesystem::path& log,
    const std::function<Trajectory(const std::string& text, const std::string& path)>& parse);
/// The same with the TUM reader (`t tx ty tz qx qy qz qw`, seconds: trajectory/trajectory.h).
Trajectory readTumEstimate(const std::filesystem::path& file, const SlamCalibration& cal,
                           const std::filesystem::path& log);

/// ORB-SLAM3's SaveTrajectoryEuRoC text: TUM column order, space separated, the stamp in
/// nanoseconds as a float with 6 decimals (`1e9 * t` printed fixed): `t_ns tx ty tz qx qy qz
/// qw`. Not snapped. InputError naming `path` and the line for a malformed row (column count,
/// a non-number, a quaternion off unit length by more than 1e-3, time going back).
Trajectory parseOrbSlam3EurocText(const std::string& text, const std::string& path);

}  // namespace inet
