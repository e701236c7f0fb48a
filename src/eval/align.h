#pragma once
// Closed-form alignment of an estimated trajectory to ground truth (Umeyama, "Least-squares
// estimation of transformation parameters between two point patterns", PAMI 1991; Horn 1987
// for the rotation-only case). Given matched positions p_est,i and p_gt,i it finds
//
//     (s, R, t) = argmin  sum_i || p_gt,i - (s R p_est,i + t) ||^2
//
// with s = 1 for SE(3) (stereo / RGB-D / visual-inertial estimates) and s free for Sim(3)
// (monocular estimates, whose scale is unobservable). Eigen::umeyama implements exactly this,
// including the reflection guard (det(R) = +1), so it is used directly.
#include <string>
#include <vector>

#include "core/pose.h"

namespace inet {

enum class AlignMode { None, SE3, Sim3 };

/// "none", "se3" or "sim3" (case-sensitive); InputError naming `field` and listing the valid
/// names otherwise.
AlignMode parseAlignMode(const std::string& name, const std::string& field = "--align");
const char* alignModeName(AlignMode mode);

/// A similarity transform taking estimate coordinates into ground-truth coordinates:
/// p_gt = scale * (R p_est) + t, with R and t in T_gt_est.
struct Alignment {
  Pose T_gt_est;
  double scale = 1.0;

  Vec3 apply(const Vec3& p_est) const { return scale * (T_gt_est.q * p_est) + T_gt_est.t; }
  /// A camera pose T_est_camera moved into the ground-truth frame: rotation R * R_c, position
  /// apply(t_c).
  Pose apply(const Pose& T_est_camera) const {
    return {T_gt_est.q * T_est_camera.q, apply(T_est_camera.t)};
  }
};

/// The least-squares alignment of `est` onto `gt` (same length, matched by index). None gives
/// the identity. SE3/Sim3 need at least 3 pairs, and Sim3 an estimate that is not a single
/// point; otherwise InputError (field "alignment"). Fewer than 3 non-collinear points leave the
/// rotation about their line undetermined; the result is still a least-squares optimum.
Alignment alignPositions(const std::vector<Vec3>& est, const std::vector<Vec3>& gt, AlignMode mode);

}  // namespace inet
