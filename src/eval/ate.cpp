#include "eval/ate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {

std::vector<TimeNs> trajectoryStamps(const Trajectory& traj) {
  std::vector<TimeNs> t;
  t.reserve(traj.size());
  for (const auto& p : traj.poses) t.push_back(p.t_ns);
  return t;
}

double rotationAngleDeg(const Quat& q) {
  // 2 atan2(|v|, |w|) is accurate near 0 and 180 degrees, unlike 2 acos(w)
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) * 180.0 / M_PI;
}

std::vector<StampMatch> associateTrajectories(const Trajectory& gt, const Trajectory& est,
                                              const AssociationOptions& opt) {
  if (gt.empty()) throw InputError("", "ground truth", "the trajectory has no poses");
  if (est.empty()) throw InputError("", "estimate", "the trajectory has no poses");
  std::vector<StampMatch> m = associateStamps(trajectoryStamps(gt), trajectoryStamps(est), opt);
  if (m.empty()) {
    auto span = [](const Trajectory& t) {
      auto [lo, hi] = std::minmax_element(t.poses.begin(), t.poses.end(),
                                          [](auto& a, auto& b) { return a.t_ns < b.t_ns; });
      return fmt::format("[{}, {}] s", nsToSecondsString(lo->t_ns, 6),
                         nsToSecondsString(hi->t_ns, 6));
    };
    throw InputError("", "association",
                     fmt::format("no estimate stamp is within {} s of a ground-truth stamp "
                                 "(ground truth {}, estimate {}, offset {} s); check --offset "
                                 "and --max-diff, and that both files use the same clock",
                                 nsToSecondsString(opt.max_diff_ns, 6), span(gt), span(est),
                                 nsToSecondsString(opt.offset_ns, 6)));
  }
  return m;
}

AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& opt) {
  AteResult r;
  r.align = opt.align;
  r.matches = associateTrajectories(gt, est, opt.association);
  r.gt_poses = gt.size();
  r.est_poses = est.size();
  std::vector<Vec3> p_gt, p_est;
  for (const StampMatch& m : r.matches) {
    p_gt.push_back(gt.poses[m.a].T_world_camera.t);
    p_est.push_back(est.poses[m.b].T_world_camera.t);
  }
  r.alignment = alignPositions(p_est, p_gt, opt.align);
  for (const StampMatch& m : r.matches) {
    const Pose& G = gt.poses[m.a].T_world_camera;
    const Pose A = r.alignment.apply(est.poses[m.b].T_world_camera);
    r.translation_errors_m.push_back((G.t - A.t).norm());
    r.rotation_errors_deg.push_back(rotationAngleDeg(G.q.conjugate() * A.q));
  }
  r.translation_m = computeErrorStats(r.translation_errors_m);
  r.rotation_deg = computeErrorStats(r.rotation_errors_deg);

  TimeNs est_lo = est.poses.front().t_ns, est_hi = est_lo;
  for (const auto& p : est.poses)
    est_lo = std::min(est_lo, p.t_ns), est_hi = std::max(est_hi, p.t_ns);
  const TimeNs lo = est_lo + opt.association.offset_ns - opt.association.max_diff_ns;
  const TimeNs hi = est_hi + opt.association.offset_ns + opt.association.max_diff_ns;
  for (const auto& p : gt.poses) r.gt_poses_in_est_span += p.t_ns >= lo && p.t_ns <= hi;
  const double n = static_cast<double>(r.matches.size());
  r.tracked_in_span = r.gt_poses_in_est_span ? n / r.gt_poses_in_est_span : 0.0;
  r.tracked_overall = n / r.gt_poses;
  return r;
}

std::string AteResult::toString() const {
  return fmt::format("AteResult[align={} scale={:.6g} matches={} translation {} rotation {}]",
                     alignModeName(align), alignment.scale, matches.size(),
                     translation_m.toString(), rotation_deg.toString());
}

}  // namespace inet
