#pragma once
// Frame-to-frame RGB-D odometry on a sequence folder with OpenCV's rgbd module (opencv_contrib
// 4.6, namespace cv::rgbd): how far a dense RGB-D tracker drifts on the sequence (issue 14's
// acceptance, and the baseline of issue 17).
//
// Methods, all with OpenCV's default parameters (depth used in (0, 4) m, 0.07 m largest depth
// difference of a correspondence, 7 % of the pixels sampled with OpenCV's fixed-seed RNG):
//   rgbd      cv::rgbd::RgbdOdometry: photometric, Steinbruecker, Sturm, Cremers, "Real-Time
//             Visual Odometry from Dense RGB-D Images", ICCV workshops 2011
//   icp       cv::rgbd::ICPOdometry: point-to-plane ICP on the depth alone
//   rgbd-icp  cv::rgbd::RgbdICPOdometry: the sum of both energies
//
// Inputs per frame: the grey image (CV_8UC1, RGB2GRAY of the sRGB codes), depth0 as float
// metres (CV_32FC1, pixels without depth as NaN, as OpenCV's odometry_evaluation sample), and
// the camera matrix of meta.json in OpenCV's convention (cx = renderer cx - 0.5).
//
// Chaining. compute(src = frame j, dst = frame i) returns Rt with p_i = Rt p_j, i.e. T_i_j
// (OpenCV's documentation of Odometry::compute; its odometry_evaluation sample chains the same
// way), so with i the previous used frame and j the next one
//
//     T_world_j = T_world_i * Rt,        T_world_0 = the ground truth's first pose.
//
// Tracked. A step is tracked when compute() returns true (OpenCV's own test: enough
// correspondences, a solvable system, and at most 0.15 m and 15 deg for rgbd/icp/rgbd-icp by
// default) and the step passes our plausibility gate: translation < max_step_m (0.5 m) and
// rotation < max_step_deg (30 deg). The gate catches a converged but absurd step; with OpenCV's
// defaults its own limits are the tighter ones. An untracked step is bridged with constant
// velocity: the previous frame-to-frame motion again (identity before the first one), so the
// trajectory keeps one pose per frame and the ATE sees the cost of the loss.
//
// Reference frame. frame-to-frame (OdometryReference::Previous) registers each frame to the
// one before it. frame-to-keyframe (Keyframe) registers it to the current keyframe, which
// stays until a tracked frame lies more than keyframe_m (0.1 m) or keyframe_deg (10 deg) from
// it, or a frame is lost; that frame (at its bridged pose, if lost) becomes the next keyframe.
// Drift then grows per keyframe instead of per frame.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "eval/ate.h"
#include "trajectory/trajectory.h"

namespace inet {

enum class OdometryMethod { Rgbd, Icp, RgbdIcp };
/// What each frame is registered to (see the header comment).
enum class OdometryReference { Previous, Keyframe };

/// "rgbd", "icp" or "rgbd-icp"; InputError naming `field` and listing them otherwise.
OdometryMethod parseOdometryMethod(const std::string& name, const std::string& field = "--method");
const char* odometryMethodName(OdometryMethod m);
/// "frame" (frame-to-frame) or "keyframe"; InputError naming `field` otherwise.
OdometryReference parseOdometryReference(const std::string& name,
                                         const std::string& field = "--reference-frame");
const char* odometryReferenceName(OdometryReference r);

struct OdometryOptions {
  OdometryMethod method = OdometryMethod::Rgbd;
  OdometryReference reference = OdometryReference::Previous;
  double keyframe_m = 0.1;     ///< Keyframe: a new keyframe beyond this distance, metres
  double keyframe_deg = 10.0;  ///< Keyframe: ... or beyond this rotation, degrees
  double max_step_m = 0.5;     ///< plausibility gate: translation per step, metres
  double max_step_deg = 30.0;  ///< plausibility gate: rotation per step, degrees
  size_t stride = 1;           ///< use frames 0, stride, 2 stride, ...
  size_t max_frames = 0;       ///< at most this many frames; 0 = all
  /// InputError naming the option (field "odometry.<name>") for a value out of range.
  void validate() const;
  std::string toString() const;
};

/// One step, from the previous used frame to `frame`.
struct OdometryStep {
  size_t frame = 0;                            ///< index in the sequence
  bool converged = false;                      ///< compute() returned true
  bool tracked = false;                        ///< converged and inside the plausibility gate
  double translation_m = 0, rotation_deg = 0;  ///< of compute()'s step (0 when not converged)
  double seconds = 0;                          ///< compute() wall time
  bool keyframe = false;                       ///< the frame became the reference
};

struct OdometryResult {
  std::string sequence;  ///< the folder
  OdometryOptions options;
  Trajectory estimate;              ///< T_world_camera of every used frame, frame stamps
  Trajectory ground_truth;          ///< the same frames' ground truth
  std::vector<OdometryStep> steps;  ///< one per used frame after the first
  size_t tracked = 0;               ///< steps tracked
  size_t keyframes = 1;             ///< reference frames used (the first frame is one)
  AteResult ate;                    ///< estimate vs ground truth, SE(3)-aligned (Umeyama)
  /// The same without alignment. The estimate starts at the ground truth's first pose, so this
  /// is the drift accumulated from there. Its rotation is the one to read: the alignment fits
  /// positions only, and a short, nearly straight path leaves the rotation about its direction
  /// free, so `ate`'s rotation error can be large while its translation error is small.
  AteResult drift;
  double odometry_seconds = 0;  ///< sum of compute() times
  double seconds = 0;           ///< wall time, reading included
  std::string toString() const;
};

/// Runs the odometry over the sequence folder (eval/sequence_reader.h; InputError naming the
/// file for a missing folder, meta.json field, image or ground truth; for a fisheye or panorama,
/// whose depth0 holds ray distance; for fewer than 3 used frames, which SE(3) alignment needs).
OdometryResult rgbdOdometry(const std::filesystem::path& sequence, const OdometryOptions& opt = {});

}  // namespace inet
