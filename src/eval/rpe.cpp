#include "eval/rpe.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "eval/ate.h"

namespace inet {

DeltaUnit parseDeltaUnit(const std::string& name, const std::string& field) {
  if (name == "frames" || name == "f") return DeltaUnit::Frames;
  if (name == "m") return DeltaUnit::Metres;
  if (name == "s") return DeltaUnit::Seconds;
  throw InputError("", field, "unknown unit '" + name + "'; valid: frames (or f), m, s");
}

const char* deltaUnitName(DeltaUnit unit) {
  switch (unit) {
    case DeltaUnit::Frames:
      return "frames";
    case DeltaUnit::Metres:
      return "m";
    case DeltaUnit::Seconds:
      return "s";
  }
  return "?";
}

namespace {

/// Pairs of indices into the n matched poses. For metres and seconds, reached(i, j) says
/// whether pose j is at least delta (path length or time) after pose i; it is monotone in j.
template <typename Reached>
std::vector<std::pair<size_t, size_t>> selectPairs(size_t n, const RpeOptions& opt,
                                                   Reached reached) {
  std::vector<std::pair<size_t, size_t>> pairs;
  if (opt.unit == DeltaUnit::Frames) {
    const auto d = static_cast<size_t>(opt.delta);
    for (size_t i = 0; i + d < n; i += opt.all_pairs ? 1 : d) pairs.emplace_back(i, i + d);
    return pairs;
  }
  size_t j = 0;
  for (size_t i = 0; i < n;) {
    j = std::max(j, i + 1);  // the first j reaching delta only moves forward with i
    while (j < n && !reached(i, j)) ++j;
    if (j >= n) break;
    pairs.emplace_back(i, j);
    i = opt.all_pairs ? i + 1 : j;
  }
  return pairs;
}

void validate(const RpeOptions& opt) {
  if (!(opt.delta > 0) || !std::isfinite(opt.delta))
    throw InputError("", "--delta", fmt::format("must be > 0, got {}", opt.delta));
  if (opt.unit == DeltaUnit::Frames && opt.delta != std::floor(opt.delta))
    throw InputError("", "--delta",
                     fmt::format("a whole number of frames is needed, got {}", opt.delta));
}

}  // namespace

RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& opt) {
  validate(opt);
  RpeResult r;
  r.matches = associateTrajectories(gt, est, opt.association);
  r.matched = r.matches.size();
  std::vector<Pose> Q, P;
  std::vector<Vec3> p_gt, p_est;
  for (const StampMatch& m : r.matches) {
    Q.push_back(gt.poses[m.a].T_world_camera);
    P.push_back(est.poses[m.b].T_world_camera);
    p_gt.push_back(Q.back().t), p_est.push_back(P.back().t);
  }
  r.alignment = alignPositions(p_est, p_gt, opt.align);
  for (Pose& p : P) p = r.alignment.apply(p);

  // metres: cumulative ground-truth path; seconds: exact integer ground-truth stamps
  std::vector<double> path_m(Q.size(), 0.0);
  for (size_t k = 1; k < Q.size(); ++k) path_m[k] = path_m[k - 1] + (Q[k].t - Q[k - 1].t).norm();
  const auto delta_ns = static_cast<TimeNs>(std::llround(opt.delta * 1e9));
  auto stamp = [&](size_t k) { return gt.poses[r.matches[k].a].t_ns; };
  r.pairs = selectPairs(Q.size(), opt, [&](size_t i, size_t j) {
    return opt.unit == DeltaUnit::Metres ? path_m[j] - path_m[i] >= opt.delta
                                         : stamp(j) - stamp(i) >= delta_ns;
  });
  if (r.pairs.empty()) {
    const TimeNs span_ns = stamp(Q.size() - 1) - stamp(0);
    throw InputError("", "--delta",
                     fmt::format("no pose pair is {} {} apart: {} matched poses spanning {:.3f} "
                                 "m of path and {} s",
                                 opt.delta, deltaUnitName(opt.unit), Q.size(), path_m.back(),
                                 nsToSecondsString(span_ns, 3)));
  }
  for (auto [i, j] : r.pairs) {
    const Pose E = (Q[i].inverse() * Q[j]).inverse() * (P[i].inverse() * P[j]);
    r.translation_errors_m.push_back(E.t.norm());
    r.rotation_errors_deg.push_back(rotationAngleDeg(E.q));
  }
  r.translation_m = computeErrorStats(r.translation_errors_m);
  r.rotation_deg = computeErrorStats(r.rotation_errors_deg);
  return r;
}

std::string RpeResult::toString() const {
  return fmt::format("RpeResult[matched={} pairs={} translation {} rotation {}]", matched,
                     pairs.size(), translation_m.toString(), rotation_deg.toString());
}

}  // namespace inet
