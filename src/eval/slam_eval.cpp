#include "eval/slam_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "eval/eval_plot.h"
#include "eval/sequence_reader.h"
#include "trajectory/formats.h"

namespace inet {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct BuiltinSystem {
  const char* name;
  OdometryMethod method;
};

constexpr BuiltinSystem kBuiltin[] = {
    {"opencv-rgbd", OdometryMethod::Rgbd},
    {"opencv-icp", OdometryMethod::Icp},
    {"opencv-rgbd-icp", OdometryMethod::RgbdIcp},
};

const BuiltinSystem* findBuiltin(const std::string& name) {
  for (const BuiltinSystem& b : kBuiltin)
    if (name == b.name) return &b;
  return nullptr;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// The association window: 20 ms (the TUM tools'), but at most half the shortest frame
/// interval, so that a pose can never be taken for its neighbour frame's.
AssociationOptions associationFor(const Trajectory& gt) {
  AssociationOptions a;
  for (size_t k = 1; k < gt.size(); ++k)
    a.max_diff_ns = std::min(a.max_diff_ns, (gt.poses[k].t_ns - gt.poses[k - 1].t_ns) / 2);
  return a;
}

double pathLength(const Trajectory& traj) {
  double len = 0;
  for (size_t k = 1; k < traj.size(); ++k)
    len += (traj.poses[k].T_world_camera.t - traj.poses[k - 1].T_world_camera.t).norm();
  return len;
}

json statsJson(const ErrorStats& s) {
  return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std},
          {"min", s.min},   {"max", s.max},   {"count", s.count}};
}

json alignmentJson(const Alignment& al) {
  const Quat q = canonicalQuat(al.T_gt_est.q);
  return {{"scale", al.scale},
          {"rotation_xyzw", {q.x(), q.y(), q.z(), q.w()}},
          {"translation_m", {al.T_gt_est.t.x(), al.T_gt_est.t.y(), al.T_gt_est.t.z()}}};
}

/// A number, or null for NaN (JSON has no NaN).
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

std::vector<std::string> builtinSlamSystems() {
  std::vector<std::string> names;
  for (const BuiltinSystem& b : kBuiltin) names.push_back(b.name);
  return names;
}

std::vector<std::string> slamSystemNames() {
  std::vector<std::string> names = builtinSlamSystems();
  for (const SlamAdapter* a : slamAdapters()) names.push_back(a->name());
  return names;
}

void SlamEvalOptions::validate() const {
  if (system.empty() == estimate.empty())
    throw InputError("", "--system",
                     "give a system (" + joined(slamSystemNames()) + ") or --estimate FILE, "
                     "not both or neither");
  if (!estimate.empty()) return;
  if (findBuiltin(system)) {
    OdometryOptions o = odometry;
    o.reference = reference;
    o.validate();
    return;
  }
  const std::vector<std::string> names = slamSystemNames();
  if (std::find(names.begin(), names.end(), system) == names.end())
    throw InputError("", "--system",
                     fmt::format("unknown system '{}' (valid: {})", system, joined(names)));
  if (external.exe.empty())
    throw InputError("", "--exe",
                     fmt::format("the external system {} needs its executable (--exe)", system));
  if (!(external.time_limit_s > 0))
    throw InputError("", "--time-limit",
                     fmt::format("must be > 0 s, got {}", external.time_limit_s));
}

SlamScore scoreSlam(const Trajectory& gt, const SlamEstimate& est, std::optional<size_t> tracked) {
  INET_CHECK(!gt.poses.empty());
  SlamScore s;
  s.frames = gt.size();
  s.path_length_m = pathLength(gt);
  s.duration_s = 1e-9 * static_cast<double>(gt.poses.back().t_ns - gt.poses.front().t_ns);
  s.seconds = est.seconds;
  s.seconds_per_frame = est.seconds / static_cast<double>(gt.size());
  const AssociationOptions assoc = associationFor(gt);
  std::vector<StampMatch> matches;
  if (!est.camera.poses.empty())
    matches = associateStamps(trajectoryStamps(gt), trajectoryStamps(est.camera), assoc);
  s.poses = matches.size();
  s.tracked = tracked ? *tracked : s.poses;
  s.tracked_share = static_cast<double>(s.tracked) / static_cast<double>(s.frames);
  if (!matches.empty() && s.duration_s > 0) {
    const auto [lo, hi] = std::minmax_element(
        matches.begin(), matches.end(),
        [](const StampMatch& a, const StampMatch& b) { return a.a < b.a; });
    s.coverage =
        1e-9 * static_cast<double>(gt.poses[hi->a].t_ns - gt.poses[lo->a].t_ns) / s.duration_s;
  }
  s.scored = matches.size() >= 3;
  if (!s.scored) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (ErrorStats* e : {&s.ate_se3.translation_m, &s.ate_se3.rotation_deg,
                          &s.ate_sim3.translation_m, &s.ate_sim3.rotation_deg,
                          &s.rpe.translation_m, &s.rpe.rotation_deg})
      e->rmse = e->mean = e->median = e->std = e->min = e->max = nan;
    return s;
  }
  AteOptions ate;
  ate.association = assoc;
  ate.align = AlignMode::SE3;
  s.ate_se3 = computeAte(gt, est.camera, ate);
  ate.align = AlignMode::Sim3;
  s.ate_sim3 = computeAte(gt, est.camera, ate);
  RpeOptions rpe;
  rpe.association = assoc;
  s.rpe = computeRpe(gt, est.camera, rpe);
  return s;
}

SlamReport evalSlam(const fs::path& sequence, const SlamEvalOptions& opt) {
  opt.validate();
  const SequenceReader seq(sequence);
  SlamReport r;
  r.ground_truth = seq.groundTruth();
  std::optional<size_t> tracked;
  std::string input = "rgbd";
  if (!opt.estimate.empty()) {
    r.estimate.camera = readTrajectory(opt.estimate.string());
    input = "estimate";
  } else if (const BuiltinSystem* b = findBuiltin(opt.system)) {
    OdometryOptions o = opt.odometry;
    o.method = b->method;
    o.reference = opt.reference;
    OdometryResult odo = rgbdOdometry(sequence, o);
    r.estimate.camera = odo.estimate;
    for (size_t n = 0; n < odo.estimate.size(); ++n)
      if (n == 0 || odo.steps[n - 1].keyframe)
        r.estimate.keyframes.poses.push_back(odo.estimate.poses[n]);
    r.estimate.seconds = odo.odometry_seconds;
    tracked = 1 + odo.tracked;
    r.odometry = std::move(odo);
  } else {
    const SlamAdapter& adapter = findSlamAdapter(opt.system);
    const SlamCalibration cal = readSlamCalibration(sequence);
    r.estimate = runExternalSlam(adapter, opt.external, cal);
    input = slamInputName(opt.external.input);
  }
  r.score = scoreSlam(r.ground_truth, r.estimate, tracked);
  r.score.system = opt.estimate.empty() ? opt.system : "estimate";
  r.score.sequence = sequence.string();
  r.score.input = input;
  return r;
}

json slamScoreJson(const SlamScore& s) {
  json j = {{"system", s.system},
            {"sequence", s.sequence},
            {"input", s.input},
            {"frames", s.frames},
            {"poses", s.poses},
            {"tracked", s.tracked},
            {"tracked_share", s.tracked_share},
            {"coverage", s.coverage},
            {"path_length_m", s.path_length_m},
            {"duration_s", s.duration_s},
            {"seconds", s.seconds},
            {"seconds_per_frame", s.seconds_per_frame},
            {"scored", s.scored}};
  if (s.scored) {
    j["ate_se3"] = {{"translation_m", statsJson(s.ate_se3.translation_m)},
                    {"rotation_deg", statsJson(s.ate_se3.rotation_deg)},
                    {"alignment", alignmentJson(s.ate_se3.alignment)}};
    j["ate_sim3"] = {{"translation_m", statsJson(s.ate_sim3.translation_m)},
                     {"rotation_deg", statsJson(s.ate_sim3.rotation_deg)},
                     {"alignment", alignmentJson(s.ate_sim3.alignment)}};
    j["rpe"] = {{"delta", "1 frame"},
                {"translation_m", statsJson(s.rpe.translation_m)},
                {"rotation_deg", statsJson(s.rpe.rotation_deg)}};
  } else {
    j["ate_se3"] = j["ate_sim3"] = j["rpe"] = nullptr;
  }
  return j;
}

void writeSlamReport(const fs::path& out, const SlamReport& report) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw InputError(out.string(), "--out", "cannot create folder: " + ec.message());
  const SlamScore& s = report.score;
  json j = {{"format", "interiornet-slam-eval-1"}, {"score", slamScoreJson(s)}};
  if (report.odometry) j["odometry"] = report.odometry->options.toString();
  if (s.scored) {
    // per associated frame: its stamp and the SE(3)-aligned errors
    json frames = json::array();
    const AteResult& a = s.ate_se3;
    for (size_t i = 0; i < a.matches.size(); ++i)
      frames.push_back({{"t_ns", report.ground_truth.poses[a.matches[i].a].t_ns},
                        {"ate_m", number(a.translation_errors_m[i])},
                        {"ate_deg", number(a.rotation_errors_deg[i])}});
    j["frames"] = std::move(frames);
  }
  if (report.odometry) {
    json steps = json::array();
    for (const OdometryStep& st : report.odometry->steps)
      steps.push_back({{"frame", st.frame},
                       {"converged", st.converged},
                       {"tracked", st.tracked},
                       {"keyframe", st.keyframe},
                       {"seconds", st.seconds}});
    j["steps"] = std::move(steps);
  }
  if (!report.estimate.camera.poses.empty())
    writeTrajectory((out / "estimate.txt").string(), report.estimate.camera, TrajectoryFormat::Tum);
  if (!report.estimate.keyframes.poses.empty())
    writeTrajectory((out / "keyframes.txt").string(), report.estimate.keyframes,
                    TrajectoryFormat::Tum);
  if (s.scored)
    writeAtePlot(out / "slam.png", report.ground_truth, report.estimate.camera, s.ate_se3,
                 fmt::format("{} on {}: ATE {:.2f} cm, {:.0f} % tracked", s.system,
                             fs::path(s.sequence).filename().string(),
                             100 * s.ate_se3.translation_m.rmse, 100 * s.tracked_share));
  writeTextAtomic(out / "slam.json", j.dump(2) + "\n");  // last: the report is complete
}

std::string SlamScore::toString() const {
  return fmt::format(
      "SlamScore[{} {} input={} frames={} tracked={} ({:.1f} %) coverage={:.3f} ate_se3={:.6f} m "
      "ate_sim3={:.6f} m rpe={:.6f} m s/frame={:.4f}]",
      system, sequence, input, frames, tracked, 100 * tracked_share, coverage,
      ate_se3.translation_m.rmse, ate_sim3.translation_m.rmse, rpe.translation_m.rmse,
      seconds_per_frame);
}

}  // namespace inet
