#pragma once
// `interiornet eval slam`: run a SLAM system (or take an estimate file) on a sequence folder
// and score it against the folder's own ground truth (docs/evaluation.md).
//
// Systems:
//   opencv-rgbd, opencv-icp, opencv-rgbd-icp   built in: OpenCV's RGB-D odometry
//                (eval/rgbd_odometry.h), frame-to-keyframe by default, frame-to-frame on request
//   orbslam2, orbslam3, ...                     external, through their adapters (eval/slam.h)
//   --estimate FILE                              a trajectory from anywhere (TUM, EuRoC, ...)
//
// Scores (SlamScore):
//   tracked    frames the system tracked by its own account (built in: the first frame and
//              every tracked step; external and estimate files: frames with a pose within the
//              association window), and their share of the sequence's frames;
//   coverage   share of the sequence's duration between the first and last such pose;
//   ATE        over the frames with a pose, SE(3)- and Sim(3)-aligned (a monocular system's
//              scale is free: read Sim(3)); for a built-in system the poses it bridged over lost
//              frames (constant velocity) are scored too, so a loss costs what it costs;
//   RPE        frame to frame (delta 1 frame over the associated poses), unaligned;
//   runtime    the system's wall time, and per frame.
// Fewer than 3 associated poses leave ATE and RPE unscored (NaN in the JSON as null): the
// run is still reported, tracked 0-2 frames.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "eval/ate.h"
#include "eval/rgbd_odometry.h"
#include "eval/rpe.h"
#include "eval/slam.h"
#include "trajectory/trajectory.h"

namespace inet {

/// The built-in systems' names ("opencv-rgbd", "opencv-icp", "opencv-rgbd-icp").
std::vector<std::string> builtinSlamSystems();
/// Built-in and external systems, for --help and errors.
std::vector<std::string> slamSystemNames();

struct SlamEvalOptions {
  std::string system;  ///< a built-in or adapter name; "" with `estimate`
  std::filesystem::path estimate;  ///< score this file instead of running a system
  OdometryReference reference = OdometryReference::Keyframe;  ///< built-in systems
  OdometryOptions odometry;  ///< built-in systems: gate, keyframe thresholds (method, reference
                             ///< are set from `system` and `reference`)
  ExternalRun external;      ///< external systems: exe, vocabulary, input, time limit, work
  /// InputError naming the option for an unknown system, both or neither of system and
  /// estimate, or an external system without --exe.
  void validate() const;
};

struct SlamScore {
  std::string system;    ///< the system's name, or "estimate"
  std::string sequence;  ///< the folder
  std::string input;     ///< what it consumed ("rgbd", ...)
  size_t frames = 0;     ///< cam0 frames of the sequence
  size_t poses = 0;      ///< estimate poses associated with a frame
  size_t tracked = 0;    ///< frames tracked (see the header)
  double tracked_share = 0, coverage = 0;
  double path_length_m = 0;  ///< of the ground truth
  double duration_s = 0;     ///< of the sequence
  bool scored = false;       ///< at least 3 associated poses: ATE and RPE below are set
  AteResult ate_se3, ate_sim3;
  RpeResult rpe;
  double seconds = 0, seconds_per_frame = 0;  ///< the system's wall time
  std::string toString() const;
};

/// A run's result: the estimate, the ground truth and the score.
struct SlamReport {
  SlamScore score;
  Trajectory ground_truth;  ///< every frame
  SlamEstimate estimate;
  std::optional<OdometryResult> odometry;  ///< built-in systems: every step
};

/// Scores `est` against the ground truth `gt` (one pose per frame, frame stamps). `tracked`:
/// the system's own count, or nullopt to count the associated poses.
SlamScore scoreSlam(const Trajectory& gt, const SlamEstimate& est,
                    std::optional<size_t> tracked = std::nullopt);

/// Runs the system of `opt` on `sequence` (or reads opt.estimate) and scores it. InputError for
/// bad options, a sequence the system cannot take, a failed external run or a bad estimate.
SlamReport evalSlam(const std::filesystem::path& sequence, const SlamEvalOptions& opt);

/// slam.json (options, score, per-frame errors), estimate.txt (TUM, the system's frame as it
/// reported it), keyframes.txt (TUM) when there are any, and slam.png (top view of the ground
/// truth and the SE(3)-aligned estimate, ATE over time), atomically, into `out` (created).
void writeSlamReport(const std::filesystem::path& out, const SlamReport& report);

/// The score as JSON (what slam.json holds under "score").
nlohmann::json slamScoreJson(const SlamScore& s);

}  // namespace inet
