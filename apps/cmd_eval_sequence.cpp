// interiornet eval features | odometry: how "SLAM-worthy" a generated sequence is, measured on
// its images (docs/eval.md). `features` checks ORB matches between consecutive frames against
// the exact forward flow (eval/feature_consistency.h); `odometry` runs OpenCV's frame-to-frame
// RGB-D odometry and scores it with the ATE (eval/rgbd_odometry.h). With --reference, the same
// figures for a second sequence and the ratios SEQ / REFSEQ.
//
// Declared for the `eval` subcommand (common.h; registerEval calls it):
//   void addSequenceEvalCommands(CLI::App* eval_cmd);
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/error.h"
#include "eval/feature_consistency.h"
#include "eval/rgbd_odometry.h"
#include "scene/nyu40.h"
#include "trajectory/formats.h"

namespace inet::app {
namespace {

/// One row of the comparison table: its JSON key and label, the value of each sequence, how to
/// print it, and whether a ratio SEQ / REFSEQ means something for it.
struct Row {
  std::string key, name;
  std::function<double(size_t)> value;  ///< by column: 0 = SEQ, 1 = REFSEQ
  std::string format = "{:.4f}";
  bool ratio = true;
};

/// A row reading `f` of results[0] and results[1]; `results` must outlive the row.
template <class Result>
Row row(const std::vector<Result>& results, std::string key, std::string name,
        std::type_identity_t<double (*)(const Result&)> f, std::string format = "{:.4f}",
        bool ratio = true) {
  return {std::move(key), std::move(name), [&results, f](size_t i) { return f(results.at(i)); },
          std::move(format), ratio};
}

std::optional<double> ratioOf(double a, double b) {
  if (b == 0 || !std::isfinite(a) || !std::isfinite(b)) return std::nullopt;
  return a / b;
}

/// correctShare(), or NaN (printed "-", JSON null) when no match could be checked.
double shareOrNan(const MatchCounts& c) {
  return c.checked() ? c.correctShare() : std::nan("");
}

/// A value, or "-" for NaN (a share of nothing).
std::string cell(const Row& r, size_t column) {
  const double v = r.value(column);
  return std::isnan(v) ? "-" : fmt::format(fmt::runtime(r.format), v);
}

/// Rows as a table with a column per sequence and, with a reference, the ratio column.
void printRows(const std::vector<Row>& rows, bool reference) {
  fmt::print("{:<28}{:>12}", "", "SEQ");
  if (reference) fmt::print("{:>12}{:>12}", "REFSEQ", "SEQ/REFSEQ");
  fmt::print("\n");
  for (const Row& r : rows) {
    fmt::print("{:<28}{:>12}", r.name, cell(r, 0));
    if (reference) {
      fmt::print("{:>12}", cell(r, 1));
      const std::optional<double> q = r.ratio ? ratioOf(r.value(0), r.value(1)) : std::nullopt;
      fmt::print("{:>12}", q ? fmt::format("{:.3f}", *q) : "-");
    }
    fmt::print("\n");
  }
}

/// The rows as {"sequence": ..., "reference": ..., "ratio": ...} objects keyed by Row::key.
nlohmann::json rowsJson(const std::vector<Row>& rows, bool reference) {
  nlohmann::json seq, ref, ratio;
  for (const Row& r : rows) {
    seq[r.key] = r.value(0);
    if (!reference) continue;
    ref[r.key] = r.value(1);
    if (!r.ratio) continue;
    const std::optional<double> q = ratioOf(r.value(0), r.value(1));
    ratio[r.key] = q ? nlohmann::json(*q) : nlohmann::json(nullptr);
  }
  nlohmann::json j = {{"sequence", seq}};
  if (reference) {
    j["reference"] = ref;
    j["ratio"] = ratio;
  }
  return j;
}

std::string flatClassNames(const std::vector<int>& ids) {
  std::string s;
  for (int id : ids) s += (s.empty() ? "" : ", ") + std::string(nyu40Name(id));
  return s;
}

// ---- features ---------------------------------------------------------------------------------

struct FeaturesArgs {
  std::string seq, reference, sampling = "nearest";
  FeatureOptions opt;
  bool json = false, per_pair = false;
};

nlohmann::json countsJson(const MatchCounts& c) {
  return {{"matches", c.matches},
          {"correct", c.correct},
          {"wrong", c.wrong},
          {"occluded", c.occluded},
          {"no_flow", c.no_flow},
          {"correct_share", shareOrNan(c)},
          {"occluded_share", c.occludedShare()}};
}

nlohmann::json featuresJson(const FeatureConsistencyResult& r) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const FramePairFeatures& p : r.pairs)
    pairs.push_back({{"frame", p.frame},
                     {"t_ns", p.t_ns},
                     {"keypoints", p.keypoints},
                     {"keypoints_next", p.keypoints_next},
                     {"keypoints_flat", p.keypoints_flat},
                     {"all", countsJson(p.all)},
                     {"flat", countsJson(p.flat)}});
  return {{"sequence", r.sequence},
          {"frames", r.frames},
          {"labels", r.labels},
          {"keypoints_per_frame", r.keypoints_per_frame},
          {"matches_per_pair", r.matches_per_pair},
          {"flat_keypoint_share", r.flat_keypoint_share},
          {"all", countsJson(r.all)},
          {"flat", countsJson(r.flat)},
          {"other", countsJson(r.all - r.flat)},
          {"seconds", r.seconds},
          {"pairs", pairs}};
}

std::string shareText(const MatchCounts& c) {
  return c.checked() ? fmt::format("{:.4f}", c.correctShare()) : "-";
}

void printPairs(const FeatureConsistencyResult& r) {
  fmt::print("\n{}: per pair (k, k+1)\n", r.sequence);
  fmt::print("{:>6} {:>14} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>8}\n", "k", "t (s)", "kp k",
             "kp k+1", "matches", "correct", "occluded", "kp flat", "flat ok");
  for (const FramePairFeatures& p : r.pairs)
    fmt::print("{:>6} {:>14} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>8}\n", p.frame,
               nsToSecondsString(p.t_ns, 6), p.keypoints, p.keypoints_next, p.all.matches,
               shareText(p.all), p.all.occluded, p.keypoints_flat, shareText(p.flat));
}

std::vector<Row> featureRows(const std::vector<FeatureConsistencyResult>& res) {
  using R = const FeatureConsistencyResult&;
  return {
      row(
          res, "pairs", "pairs evaluated", [](R r) { return double(r.pairs.size()); }, "{:.0f}",
          false),
      row(
          res, "keypoints_per_frame", "keypoints / frame",
          [](R r) { return r.keypoints_per_frame; }, "{:.1f}"),
      row(
          res, "matches_per_pair", "matches / pair", [](R r) { return r.matches_per_pair; },
          "{:.1f}"),
      row(res, "correct_share", "correct share", [](R r) { return shareOrNan(r.all); }),
      row(res, "occluded_share", "occluded share", [](R r) { return r.all.occludedShare(); }),
      row(
          res, "no_flow", "matches without flow", [](R r) { return double(r.all.no_flow); },
          "{:.0f}"),
      row(res, "flat_keypoint_share", "keypoints on flat",
          [](R r) { return r.flat_keypoint_share; }),
      row(res, "flat_correct_share", "correct share, flat", [](R r) { return shareOrNan(r.flat); }),
      row(res, "other_correct_share", "correct share, elsewhere",
          [](R r) { return shareOrNan(r.all - r.flat); }),
      row(
          res, "seconds", "time (s)", [](R r) { return r.seconds; }, "{:.2f}", false),
  };
}

void runFeatures(FeaturesArgs a) {
  a.opt.sampling = parseFlowSampling(a.sampling, "--sampling");
  a.opt.validate();
  std::vector<FeatureConsistencyResult> res{featureConsistency(a.seq, a.opt)};
  if (!a.reference.empty()) res.push_back(featureConsistency(a.reference, a.opt));
  const bool ref = res.size() == 2;
  const std::vector<Row> rows = featureRows(res);
  if (a.json) {
    nlohmann::json j = rowsJson(rows, ref);
    j = {{"metric", "features"},
         {"options",
          {{"orb_features", a.opt.orb_features},
           {"max_error_px", a.opt.max_error_px},
           {"sampling", flowSamplingName(a.opt.sampling)},
           {"flat_classes", a.opt.flat_classes},
           {"stride", a.opt.stride},
           {"max_pairs", a.opt.max_pairs}}},
         {"summary", j},
         {"sequence", featuresJson(res[0])}};
    if (ref) j["reference"] = featuresJson(res[1]);
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("SEQ           {} ({} frames)\n", res[0].sequence, res[0].frames);
  if (ref) fmt::print("REFSEQ        {} ({} frames)\n", res[1].sequence, res[1].frames);
  fmt::print(
      "measured      ORB ({} features) on each frame pair (k, k+1), cross-checked Hamming "
      "matches;\n              correct: within {} px of where the exact forward flow ({}) "
      "moves the keypoint,\n              share of the matches that are not occluded and have "
      "flow; flat: NYU40 {}\n\n",
      a.opt.orb_features, a.opt.max_error_px, flowSamplingName(a.opt.sampling),
      flatClassNames(a.opt.flat_classes));
  printRows(rows, ref);
  for (const FeatureConsistencyResult& r : res)
    if (!r.labels) fmt::print("\nnote: {} has no label0/: the flat figures are 0\n", r.sequence);
  if (a.per_pair)
    for (const FeatureConsistencyResult& r : res) printPairs(r);
}

// ---- odometry ---------------------------------------------------------------------------------

struct OdometryArgs {
  std::string seq, reference, method = "rgbd", out;
  OdometryOptions opt;
  bool json = false;
};

nlohmann::json odometryJson(const OdometryResult& r) {
  nlohmann::json steps = nlohmann::json::array();
  for (const OdometryStep& s : r.steps)
    steps.push_back({{"frame", s.frame},
                     {"converged", s.converged},
                     {"tracked", s.tracked},
                     {"translation_m", s.translation_m},
                     {"rotation_deg", s.rotation_deg},
                     {"seconds", s.seconds}});
  const ErrorStats& t = r.ate.translation_m;
  return {{"sequence", r.sequence},
          {"frames", r.estimate.size()},
          {"steps", r.steps.size()},
          {"tracked", r.tracked},
          {"ate_translation_m",
           {{"rmse", t.rmse}, {"mean", t.mean}, {"median", t.median}, {"max", t.max}}},
          {"ate_rotation_deg_rmse", r.ate.rotation_deg.rmse},
          {"unaligned_translation_m",
           {{"rmse", r.drift.translation_m.rmse}, {"max", r.drift.translation_m.max}}},
          {"unaligned_rotation_deg_rmse", r.drift.rotation_deg.rmse},
          {"odometry_seconds", r.odometry_seconds},
          {"seconds", r.seconds},
          {"per_step", steps}};
}

std::vector<Row> odometryRows(const std::vector<OdometryResult>& res) {
  using R = const OdometryResult&;
  return {
      row(
          res, "frames", "frames", [](R r) { return double(r.estimate.size()); }, "{:.0f}", false),
      row(res, "tracked_share", "tracked share",
          [](R r) { return double(r.tracked) / double(r.steps.size()); }),
      row(
          res, "ate_rmse_m", "ATE rmse (m)", [](R r) { return r.ate.translation_m.rmse; },
          "{:.5f}"),
      row(
          res, "ate_max_m", "ATE max (m)", [](R r) { return r.ate.translation_m.max; }, "{:.5f}"),
      row(
          res, "drift_rmse_m", "unaligned rmse (m)", [](R r) { return r.drift.translation_m.rmse; },
          "{:.5f}"),
      row(
          res, "drift_rotation_rmse_deg", "unaligned rot. rmse (deg)",
          [](R r) { return r.drift.rotation_deg.rmse; }, "{:.4f}"),
      row(
          res, "ms_per_step", "odometry ms / step",
          [](R r) { return 1000 * r.odometry_seconds / double(r.steps.size()); }, "{:.1f}"),
      row(
          res, "seconds", "time (s)", [](R r) { return r.seconds; }, "{:.2f}", false),
  };
}

void runOdometry(OdometryArgs a) {
  a.opt.method = parseOdometryMethod(a.method, "--method");
  a.opt.validate();
  if (!a.out.empty() && std::filesystem::is_directory(a.out))
    throw InputError(a.out, "--out", "is a folder; name the TUM trajectory file to write");
  std::vector<OdometryResult> res{rgbdOdometry(a.seq, a.opt)};
  if (!a.reference.empty()) res.push_back(rgbdOdometry(a.reference, a.opt));
  const bool ref = res.size() == 2;
  if (!a.out.empty()) writeTrajectory(a.out, res[0].estimate, TrajectoryFormat::Tum);
  const std::vector<Row> rows = odometryRows(res);
  if (a.json) {
    nlohmann::json j = {{"metric", "odometry"},
                        {"options",
                         {{"method", odometryMethodName(a.opt.method)},
                          {"max_step_m", a.opt.max_step_m},
                          {"max_step_deg", a.opt.max_step_deg},
                          {"stride", a.opt.stride},
                          {"max_frames", a.opt.max_frames},
                          {"align", "se3"}}},
                        {"summary", rowsJson(rows, ref)},
                        {"sequence", odometryJson(res[0])}};
    if (ref) j["reference"] = odometryJson(res[1]);
    if (!a.out.empty()) j["estimate_file"] = a.out;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("SEQ           {} ({} frames used)\n", res[0].sequence, res[0].estimate.size());
  if (ref)
    fmt::print("REFSEQ        {} ({} frames used)\n", res[1].sequence, res[1].estimate.size());
  fmt::print(
      "measured      OpenCV {} odometry frame to frame (default parameters), chained from the\n"
      "              ground-truth first pose; ATE after SE(3) alignment (Umeyama), and\n"
      "              unaligned (the drift from the shared first pose)\n",
      odometryMethodName(a.opt.method));
  for (const OdometryResult& r : res)
    fmt::print("tracked       {} of {} steps{}\n", r.tracked, r.steps.size(),
               ref ? " (" + r.sequence + ")" : std::string());
  fmt::print(
      "              tracked = compute() succeeds and the step is under {} m and {} deg;\n"
      "              other steps repeat the previous one (constant velocity)\n\n",
      a.opt.max_step_m, a.opt.max_step_deg);
  printRows(rows, ref);
  if (!a.out.empty()) fmt::print("\nwrote {} (TUM, T_world_camera)\n", a.out);
}

}  // namespace

void addSequenceEvalCommands(CLI::App* eval) {
  auto* feat = eval->add_subcommand(
      "features",
      "How well ORB features track on a sequence: per frame pair (k, k+1), cv::ORB (1000 "
      "features) on both grey images, brute-force Hamming matches with cross-check, each "
      "match checked against the exact forward flow of frame k (flow0/, its occlusion mask): "
      "correct when the match lands within --max-error px of where the flow moves the "
      "keypoint. Reports keypoints per frame, matches, the correct share (of the matches "
      "that are not occluded and have flow), the occluded share, and the share of keypoints "
      "on flat surfaces (NYU40 wall, floor, ceiling from label0/) with their own correct "
      "share. Needs the rgb, flow and (for the flat figures) label passes in the ASL layout");
  auto fa = std::make_shared<FeaturesArgs>();
  feat->add_option("SEQ", fa->seq, "sequence folder (OUT/<layout>/<sequence>)")->required();
  feat->add_option("--reference", fa->reference,
                   "a second sequence folder: the same figures for it and the ratios SEQ / "
                   "REFSEQ (e.g. a default sequence against a high-spp or raw one)");
  feat->add_option("--max-error", fa->opt.max_error_px,
                   "largest endpoint error of a correct match, pixels (default 3)");
  feat->add_option("--sampling", fa->sampling,
                   "flow at a keypoint: nearest pixel (default) or bilinear");
  feat->add_option("--orb-features", fa->opt.orb_features, "cv::ORB::create(N), N (default 1000)");
  feat->add_option("--stride", fa->opt.stride,
                   "evaluate the pairs (k, k+1) for k = 0, N, 2N, ... (default 1)");
  feat->add_option("--max-pairs", fa->opt.max_pairs, "at most N pairs (default 0 = all)");
  feat->add_flag("--per-pair", fa->per_pair, "also print one row per frame pair");
  feat->add_flag("--json", fa->json, "print one JSON object (summary, totals, every pair)");
  feat->callback([fa] { runFeatures(*fa); });

  auto* odo = eval->add_subcommand(
      "odometry",
      "Frame-to-frame RGB-D odometry with OpenCV's rgbd module (default parameters) on a "
      "sequence's cam0 (grey) and depth0 (metres), chained from the ground-truth first pose "
      "and scored by the ATE (SE(3)-aligned RMSE, m). A step is tracked when OpenCV's "
      "compute() succeeds and the step is under 0.5 m and 30 deg; an untracked step repeats "
      "the previous one (constant velocity). Reports frames tracked, ATE and runtime; pinhole "
      "or thin-lens sequences in the ASL layout");
  auto oa = std::make_shared<OdometryArgs>();
  odo->add_option("SEQ", oa->seq, "sequence folder (OUT/<layout>/<sequence>)")->required();
  odo->add_option("--method", oa->method,
                  "rgbd (photometric, cv::rgbd::RgbdOdometry; default), icp (depth only, "
                  "ICPOdometry) or rgbd-icp (both energies, RgbdICPOdometry)");
  odo->add_option("--out", oa->out, "write SEQ's estimated trajectory here (TUM format)");
  odo->add_option("--reference", oa->reference,
                  "a second sequence folder: the same figures for it and the ratios SEQ / "
                  "REFSEQ");
  odo->add_option("--stride", oa->opt.stride, "use frames 0, N, 2N, ... (default 1)");
  odo->add_option("--max-frames", oa->opt.max_frames, "at most N frames (default 0 = all)");
  odo->add_option("--max-step-m", oa->opt.max_step_m,
                  "plausibility gate: largest translation of a tracked step, m (default 0.5)");
  odo->add_option("--max-step-deg", oa->opt.max_step_deg,
                  "plausibility gate: largest rotation of a tracked step, deg (default 30)");
  odo->add_flag("--json", oa->json, "print one JSON object (summary and every step)");
  odo->callback([oa] { runOdometry(*oa); });
}

}  // namespace inet::app
