// interiornet eval ate | rpe: evaluate an estimated trajectory (a SLAM or odometry result)
// against ground truth, as TUM's evaluate_ate.py / evaluate_rpe.py and evo's ape / rpe do.
// (eval features | odometry, which measure a sequence folder itself, are in
// cmd_eval_sequence.cpp.)
// Input files in any format trajectory/formats.h reads (TUM, EuRoC csv, ...); text output is a
// small table, --json one JSON object with every statistic, --plot a PNG.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/error.h"
#include "eval/ate.h"
#include "eval/eval_plot.h"
#include "eval/rpe.h"
#include "trajectory/formats.h"

namespace inet::app {
namespace {

struct EvalArgs {
  std::string gt, est, gt_format, est_format;
  std::string align;
  double max_diff_s = 0.02, offset_s = 0.0;
  bool json = false;
  std::string plot;
  // rpe only
  double delta = 1;
  std::string delta_unit = "frames";
  bool all_pairs = false;

  void addTo(CLI::App& cmd, const char* default_align) {
    align = default_align;
    cmd.add_option("GT", gt, "ground-truth trajectory file")->required();
    cmd.add_option("EST", est, "estimated trajectory file")->required();
    cmd.add_option("--gt-format", gt_format,
                   "tum, euroc, icl, slambench, scenenet, scenenet_v1 or kitti (default: detected)");
    cmd.add_option("--est-format", est_format, "as --gt-format, for EST");
    cmd.add_option("--align", align,
                   std::string("none, se3 (rigid) or sim3 (rigid + scale, for monocular "
                               "estimates); default ") +
                       default_align);
    cmd.add_option("--max-diff", max_diff_s,
                   "largest time difference of an associated pose pair, seconds (default 0.02)");
    cmd.add_option("--offset", offset_s,
                   "seconds added to EST's timestamps before association (default 0)");
    cmd.add_flag("--json", json, "print one JSON object with every statistic");
    cmd.add_option("--plot", plot, "also write a PNG figure to this file");
  }

  AssociationOptions association() const {
    if (!std::isfinite(max_diff_s) || max_diff_s <= 0 || max_diff_s > 3600)
      throw InputError("", "--max-diff", fmt::format("must be in (0, 3600] s, got {}", max_diff_s));
    if (!std::isfinite(offset_s) || std::abs(offset_s) > 1e9)
      throw InputError("", "--offset", fmt::format("not a usable number of seconds: {}", offset_s));
    return {static_cast<TimeNs>(std::llround(offset_s * 1e9)),
            static_cast<TimeNs>(std::llround(max_diff_s * 1e9))};
  }

  /// Validates every flag, then reads both files (InputError naming the file and line).
  std::pair<Trajectory, Trajectory> load() const {
    std::optional<TrajectoryFormat> fg, fe;
    if (!gt_format.empty()) fg = parseTrajectoryFormat(gt_format, "--gt-format");
    if (!est_format.empty()) fe = parseTrajectoryFormat(est_format, "--est-format");
    if (!plot.empty()) {
      std::string ext = std::filesystem::path(plot).extension().string();
      for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (ext != ".png") throw InputError(plot, "--plot", "the figure is a PNG: name it *.png");
    }
    return {readTrajectoryFile(gt, fg), readTrajectoryFile(est, fe)};
  }

  /// An error of the evaluation itself (file "": association, alignment) names both files.
  [[noreturn]] void rethrow(const InputError& e) const {
    if (e.file().empty() && e.field().rfind("--", 0) != 0)
      throw InputError(gt + " vs " + est, e.field(), e.problem());
    throw e;
  }
};

nlohmann::json statsJson(const ErrorStats& s) {
  return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std},
          {"min", s.min},   {"max", s.max},   {"sse", s.sse},       {"count", s.count}};
}

nlohmann::json commonJson(const EvalArgs& a, const char* metric, const Alignment& al,
                          AlignMode mode) {
  const Quat q = canonicalQuat(al.T_gt_est.q);
  return {{"metric", metric},
          {"ground_truth", a.gt},
          {"estimate", a.est},
          {"align", alignModeName(mode)},
          {"max_diff_s", a.max_diff_s},
          {"offset_s", a.offset_s},
          {"alignment",
           {{"scale", al.scale},
            {"rotation_xyzw", {q.x(), q.y(), q.z(), q.w()}},
            {"translation_m", {al.T_gt_est.t.x(), al.T_gt_est.t.y(), al.T_gt_est.t.z()}}}}};
}

/// evo-like table: one row per statistic, translation and rotation side by side.
void printTable(const ErrorStats& t, const ErrorStats& r) {
  fmt::print("{:>10}  {:>16}  {:>16}\n", "", "translation (m)", "rotation (deg)");
  const std::pair<const char*, double ErrorStats::*> rows[] = {
      {"rmse", &ErrorStats::rmse}, {"mean", &ErrorStats::mean}, {"median", &ErrorStats::median},
      {"std", &ErrorStats::std},   {"min", &ErrorStats::min},   {"max", &ErrorStats::max},
      {"sse", &ErrorStats::sse}};
  for (const auto& [name, field] : rows)
    fmt::print("{:>10}  {:>16.6f}  {:>16.6f}\n", name, t.*field, r.*field);
}

void printHeader(const EvalArgs& a, const Trajectory& gt, const Trajectory& est,
                 const Alignment& al, AlignMode mode) {
  fmt::print("ground truth  {} ({} poses)\n", a.gt, gt.size());
  fmt::print("estimate      {} ({} poses)\n", a.est, est.size());
  if (mode == AlignMode::None) {
    fmt::print("alignment     none\n");
    return;
  }
  fmt::print(
      "alignment     {} (Umeyama): scale {:.6f}, rotation {:.4f} deg, translation "
      "({:.6f}, {:.6f}, {:.6f}) m\n",
      mode == AlignMode::Sim3 ? "Sim(3)" : "SE(3)", al.scale, rotationAngleDeg(al.T_gt_est.q),
      al.T_gt_est.t.x(), al.T_gt_est.t.y(), al.T_gt_est.t.z());
}

void runAte(const EvalArgs& a) {
  AteOptions opt;
  opt.align = parseAlignMode(a.align);
  opt.association = a.association();
  auto [gt, est] = a.load();
  AteResult r;
  try {
    r = computeAte(gt, est, opt);
  } catch (const InputError& e) {
    a.rethrow(e);
  }
  if (!a.plot.empty())
    writeAtePlot(a.plot, gt, est, r, "ATE: " + std::filesystem::path(a.est).filename().string());
  if (a.json) {
    nlohmann::json j = commonJson(a, "ate", r.alignment, r.align);
    j["pairs"] = r.matches.size();
    j["gt_poses"] = r.gt_poses;
    j["est_poses"] = r.est_poses;
    j["gt_poses_in_est_span"] = r.gt_poses_in_est_span;
    j["tracked_in_span"] = r.tracked_in_span;
    j["tracked_overall"] = r.tracked_overall;
    j["translation_m"] = statsJson(r.translation_m);
    j["rotation_deg"] = statsJson(r.rotation_deg);
    if (!a.plot.empty()) j["plot"] = a.plot;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  printHeader(a, gt, est, r.alignment, r.align);
  fmt::print("matched       {} pose pairs (max diff {} s, offset {} s)\n", r.matches.size(),
             a.max_diff_s, a.offset_s);
  fmt::print(
      "tracked       {:.1f} % of the ground-truth poses in the estimate's time span "
      "({} of {}), {:.1f} % of all\n\n",
      100 * r.tracked_in_span, r.matches.size(), r.gt_poses_in_est_span, 100 * r.tracked_overall);
  fmt::print("ATE (absolute trajectory error), {} pairs\n", r.matches.size());
  printTable(r.translation_m, r.rotation_deg);
  if (!a.plot.empty()) fmt::print("\nwrote {}\n", a.plot);
}

void runRpe(const EvalArgs& a) {
  RpeOptions opt;
  opt.align = parseAlignMode(a.align);
  opt.association = a.association();
  opt.unit = parseDeltaUnit(a.delta_unit);
  opt.delta = a.delta;
  opt.all_pairs = a.all_pairs;
  auto [gt, est] = a.load();
  RpeResult r;
  try {
    r = computeRpe(gt, est, opt);
  } catch (const InputError& e) {
    a.rethrow(e);
  }
  if (!a.plot.empty())
    writeRpePlot(a.plot, gt, r, "RPE " + std::filesystem::path(a.est).filename().string());
  if (a.json) {
    nlohmann::json j = commonJson(a, "rpe", r.alignment, opt.align);
    j["delta"] = opt.delta;
    j["delta_unit"] = deltaUnitName(opt.unit);
    j["all_pairs"] = opt.all_pairs;
    j["matched"] = r.matched;
    j["pairs"] = r.pairs.size();
    j["translation_m"] = statsJson(r.translation_m);
    j["rotation_deg"] = statsJson(r.rotation_deg);
    if (!a.plot.empty()) j["plot"] = a.plot;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  printHeader(a, gt, est, r.alignment, opt.align);
  fmt::print("matched       {} poses (max diff {} s, offset {} s)\n\n", r.matched, a.max_diff_s,
             a.offset_s);
  fmt::print("RPE (relative pose error), delta {} {}, {} pairs{}\n", opt.delta,
             deltaUnitName(opt.unit), r.pairs.size(), opt.all_pairs ? " (all pairs)" : "");
  printTable(r.translation_m, r.rotation_deg);
  if (!a.plot.empty()) fmt::print("\nwrote {}\n", a.plot);
}

}  // namespace

void registerEval(CLI::App& app) {
  auto* eval = app.add_subcommand(
      "eval",
      "Evaluate an estimated trajectory against ground truth (ATE, RPE), or how SLAM-worthy a "
      "sequence is (ORB matches against the exact flow, RGB-D odometry)");
  eval->require_subcommand(1);

  auto* ate = eval->add_subcommand(
      "ate",
      "Absolute trajectory error: associate stamps (TUM associate.py rules), align the estimate "
      "(Umeyama), then translational and rotational error statistics");
  auto ate_args = std::make_shared<EvalArgs>();
  ate_args->addTo(*ate, "se3");
  ate->callback([ate_args] { runAte(*ate_args); });

  auto* rpe = eval->add_subcommand(
      "rpe",
      "Relative pose error over a fixed delta (drift per frame, metre or second): "
      "translational (m) and rotational (deg) statistics");
  auto rpe_args = std::make_shared<EvalArgs>();
  rpe_args->addTo(*rpe, "none");
  rpe->add_option("--delta", rpe_args->delta, "pose pair distance, in --delta-unit (default 1)");
  rpe->add_option("--delta-unit", rpe_args->delta_unit,
                  "frames (associated poses), m (ground-truth path) or s (default frames)");
  rpe->add_flag("--all-pairs", rpe_args->all_pairs,
                "a pair starting at every pose, not consecutive disjoint pairs");
  rpe->callback([rpe_args] { runRpe(*rpe_args); });

  addSequenceEvalCommands(eval);
  addSlamEvalCommand(eval);
}

}  // namespace inet::app
