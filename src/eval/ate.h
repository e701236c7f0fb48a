#pragma once
// Absolute trajectory error (Sturm et al., "A Benchmark for the Evaluation of RGB-D SLAM
// Systems", IROS 2012, section on ATE): associate estimate and ground-truth stamps, align the
// estimate's positions onto the ground truth (eval/align.h), and take per-pair errors
//
//     e_i = || p_gt,i - (s R p_est,i + t) ||                      (metres)
//     r_i = angle( R_gt,i^T R R_est,i )                             (degrees)
//
// The translational statistics are the ATE of the TUM benchmark and of evo's `ape` (translation
// part); the rotational ones are evo's `ape --pose_relation angle_deg`.
#include <string>
#include <vector>

#include "eval/align.h"
#include "eval/associate.h"
#include "eval/error_stats.h"
#include "trajectory/trajectory.h"

namespace inet {

struct AteOptions {
  AlignMode align = AlignMode::SE3;
  AssociationOptions association;  ///< offset is added to the estimate's stamps
};

struct AteResult {
  AlignMode align = AlignMode::SE3;
  Alignment alignment;       ///< estimate -> ground truth (scale 1 unless Sim3)
  ErrorStats translation_m;  ///< the ATE
  ErrorStats rotation_deg;
  std::vector<StampMatch> matches;           ///< a: ground-truth index, b: estimate index; by time
  std::vector<double> translation_errors_m;  ///< per match
  std::vector<double> rotation_errors_deg;   ///< per match
  size_t gt_poses = 0, est_poses = 0;
  /// Ground-truth poses that an estimate pose could match: stamps in
  /// [first est + offset - max_diff, last est + offset + max_diff].
  size_t gt_poses_in_est_span = 0;
  /// matches / gt_poses_in_est_span and matches / gt_poses: how much of the sequence the
  /// estimate tracked (relative to the ground-truth rate: a 30 Hz estimate against 100 Hz
  /// ground truth tops out near 0.3).
  double tracked_in_span = 0, tracked_overall = 0;
  std::string toString() const;
};

/// ATE of `est` against `gt`. InputError (file "") when a trajectory is empty, nothing
/// associates (the message gives both time spans and the offset), or the alignment is
/// impossible (eval/align.h).
AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& opt = {});

/// Stamps of a trajectory, in its order.
std::vector<TimeNs> trajectoryStamps(const Trajectory& traj);

/// Matches of gt and est stamps (InputError if there are none; see computeAte).
std::vector<StampMatch> associateTrajectories(const Trajectory& gt, const Trajectory& est,
                                              const AssociationOptions& opt);

/// Rotation angle of a unit quaternion in degrees, in [0, 180].
double rotationAngleDeg(const Quat& q);

}  // namespace inet
