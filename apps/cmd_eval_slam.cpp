// interiornet eval slam: run a SLAM system on a sequence folder (or take an estimate file) and
// score it against the folder's ground truth (eval/slam_eval.h); eval experiment paper: the
// paper's Section 7 in one command (eval/paper_experiment.h). docs/evaluation.md.
//
// Declared for the `eval` subcommand (common.h; registerEval calls it):
//   void addSlamEvalCommand(CLI::App* eval_cmd);
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/error.h"
#include "eval/paper_experiment.h"
#include "eval/slam_eval.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct SlamArgs {
  std::string system, sequence, estimate, out;
  std::string reference = "keyframe";
  std::string exe, vocabulary, input = "rgbd";
  double time_limit_s = 3600;
  std::string config;
  SlamEvalOptions opt;
  bool json = false;
};

/// --config: CLI11 2.1 reads a config file for the top-level command only, so a subcommand's is
/// applied here, with CLI11's own TOML/INI reader: every `key = value` sets the option --key
/// unless the command line gave it (InputError naming the file and key otherwise).
void applyConfigFile(CLI::App& cmd, const std::string& path) {
  std::vector<CLI::ConfigItem> items;
  try {
    items = CLI::ConfigTOML().from_file(path);
  } catch (const CLI::Error& e) {
    throw InputError(path, "", e.what());
  }
  for (const CLI::ConfigItem& item : items) {
    if (item.name == "++" || item.name == "--") continue;  // section markers
    CLI::Option* op = cmd.get_option_no_throw("--" + item.name);
    if (!op || !item.parents.empty() || item.name == "config")
      throw InputError(path, item.fullname(), "not an option of eval slam");
    if (op->count() > 0) continue;  // the command line wins
    try {
      op->add_result(item.inputs);
      op->run_callback();
    } catch (const CLI::Error& e) {
      throw InputError(path, item.name, e.what());
    }
  }
}

std::string cellOf(double v, const char* unit, double scale) {
  return std::isfinite(v) ? fmt::format("{:.3f} {}", scale * v, unit) : "-";
}

void runSlam(SlamArgs a) {
  SlamEvalOptions& o = a.opt;
  o.system = a.system;
  o.estimate = a.estimate;
  o.reference = parseOdometryReference(a.reference);
  o.external.exe = a.exe;
  o.external.vocabulary = a.vocabulary;
  o.external.input = parseSlamInput(a.input);
  o.external.time_limit_s = a.time_limit_s;
  const fs::path seq = a.sequence;
  const std::string who = a.system.empty() ? "estimate" : a.system;
  fs::path name = seq.lexically_normal();  // "SEQ/" names SEQ too
  if (name.filename().empty()) name = name.parent_path();
  const fs::path out =
      a.out.empty() ? fs::path("slam") / name.filename() / who : fs::path(a.out);
  o.external.work = out / "run";
  o.validate();
  const SlamReport r = evalSlam(seq, o);
  writeSlamReport(out, r);
  const SlamScore& s = r.score;
  if (a.json) {
    fmt::print("{}\n", slamScoreJson(s).dump(2));
    return;
  }
  fmt::print("{} on {} ({})\n", s.system, s.sequence, s.input);
  fmt::print("  frames        {} ({:.2f} s, {:.3f} m of path)\n", s.frames, s.duration_s,
             s.path_length_m);
  fmt::print("  tracked       {} ({:.1f} %), coverage {:.1f} %\n", s.tracked,
             100 * s.tracked_share, 100 * s.coverage);
  fmt::print("  ATE SE(3)     {} RMSE, {}\n", cellOf(s.ate_se3.translation_m.rmse, "cm", 100),
             cellOf(s.ate_se3.rotation_deg.rmse, "deg", 1));
  fmt::print("  ATE Sim(3)    {} RMSE (scale {:.4f})\n",
             cellOf(s.ate_sim3.translation_m.rmse, "cm", 100), s.ate_sim3.alignment.scale);
  fmt::print("  RPE 1 frame   {} RMSE, {}\n", cellOf(s.rpe.translation_m.rmse, "cm", 100),
             cellOf(s.rpe.rotation_deg.rmse, "deg", 1));
  fmt::print("  runtime       {:.3f} s ({:.1f} ms per frame)\n", s.seconds,
             1000 * s.seconds_per_frame);
  fmt::print("wrote {}/ (slam.json, estimate.txt{})\n", out.string(),
             s.scored ? ", slam.png" : "");
}

struct ExperimentArgs {
  PaperExperimentOptions opt;
  std::string reference = "keyframe";
};

void runExperiment(ExperimentArgs a) {
  a.opt.reference = parseOdometryReference(a.reference);
  const PaperExperimentResult r = runPaperExperiment(a.opt);
  fmt::print("\n{}\n", experimentTableMarkdown(r, a.opt.systems));
  fmt::print("{} runs; making the sequences {:.0f} s, running the systems {:.0f} s\n",
             r.rows.size(), r.render_s, r.eval_s);
  fmt::print("wrote {}/ (table.md, results.csv, experiment.json, plots, sequences/, runs/)\n",
             a.opt.out.string());
}

}  // namespace

void addSlamEvalCommand(CLI::App* eval) {
  std::string systems;
  for (const std::string& n : slamSystemNames()) systems += (systems.empty() ? "" : ", ") + n;
  auto* cmd = eval->add_subcommand(
      "slam",
      "Run a SLAM system on a sequence folder and score it (ATE SE(3) and Sim(3), RPE, frames "
      "tracked, coverage, runtime): the built-in OpenCV RGB-D odometry, or an external system "
      "(ORB-SLAM2, ORB-SLAM3) given its executable, whose settings are written from the "
      "sequence's own calibration; or score an estimate file from anywhere. Writes "
      "OUT/slam.json, estimate.txt (TUM), keyframes.txt and slam.png (docs/evaluation.md)");
  auto a = std::make_shared<SlamArgs>();
  cmd->add_option("--sequence", a->sequence, "sequence folder (OUT/<layout>/<sequence>, ASL)")
      ->required();
  cmd->add_option("--system", a->system, "the system: " + systems);
  cmd->add_option("--estimate", a->estimate,
                  "score this trajectory file instead of running a system (tum, euroc, icl, "
                  "... detected)");
  cmd->add_option("--out", a->out, "report folder (default slam/<sequence>/<system>)");
  cmd->add_option("--reference-frame", a->reference,
                  "built-in systems: register each frame to the last keyframe (keyframe, "
                  "default) or to the previous frame (frame)");
  cmd->add_option("--keyframe-m", a->opt.odometry.keyframe_m,
                  "built-in, keyframe: new keyframe beyond this distance, m (default 0.1)");
  cmd->add_option("--keyframe-deg", a->opt.odometry.keyframe_deg,
                  "built-in, keyframe: new keyframe beyond this rotation, deg (default 10)");
  cmd->add_option("--max-step-m", a->opt.odometry.max_step_m,
                  "built-in: plausibility gate, largest tracked step, m (default 0.5)");
  cmd->add_option("--max-step-deg", a->opt.odometry.max_step_deg,
                  "built-in: plausibility gate, largest tracked rotation, deg (default 30)");
  cmd->add_option("--stride", a->opt.odometry.stride, "built-in: frames 0, N, 2N, ... (default 1)");
  cmd->add_option("--max-frames", a->opt.odometry.max_frames,
                  "built-in: at most N frames (default 0 = all)");
  cmd->add_option("--exe", a->exe,
                  "external: the system's example executable (e.g. ORB_SLAM2/Examples/RGB-D/"
                  "rgbd_tum, ORB_SLAM3/Examples/Monocular-Inertial/mono_inertial_euroc)");
  cmd->add_option("--vocabulary", a->vocabulary, "external: ORB vocabulary (ORBvoc.txt)");
  cmd->add_option("--input", a->input,
                  "external: rgbd (default), stereo, mono, mono-inertial or stereo-inertial");
  cmd->add_option("--time-limit", a->time_limit_s,
                  "external: kill the system after this many seconds (default 3600)");
  cmd->add_option("--config", a->config,
                  "read these options from a TOML or INI file (e.g. exe = \"...\", "
                  "vocabulary = \"...\"); options on the command line win");
  cmd->add_flag("--json", a->json, "print the score as one JSON object");
  cmd->callback([a, cmd] {
    if (!a->config.empty()) applyConfigFile(*cmd, a->config);
    runSlam(*a);
  });

  auto* exp = eval->add_subcommand("experiment", "Reproduce an evaluation of the paper");
  exp->require_subcommand(1);
  auto* paper = exp->add_subcommand(
      "paper",
      "The paper's Section 7 on our data: (a) a two-body (1, 1) trajectory through an apartment, "
      "original, relit and rearranged; (b) a grid of v and w multipliers (frames tracked and "
      "ATE against speed); (c) the three trajectory types; (d) one trajectory type and seed "
      "through several layouts. Makes every sequence (resumable), runs the built-in systems, "
      "writes OUT/table.md (Table 1's shape), results.csv, experiment.json, speed_tracked.png, "
      "speed_ate.png, layouts.png");
  auto e = std::make_shared<ExperimentArgs>();
  PaperExperimentOptions& o = e->opt;
  paper->add_option("--out", o.out, "experiment folder (default experiment)");
  paper->add_option("--parts", o.parts, "any of a, b, c, d (default abcd)");
  paper->add_option("--apartment", o.apartment,
                    "layout of parts a-c: procedural:<seed>, a layout.json, any scene "
                    "(default procedural:3)");
  paper->add_option("--rooms", o.rooms, "rooms of procedural apartments (default 0 = drawn)");
  paper->add_option("--layouts", o.layouts,
                    "layouts of part d (default procedural:1 procedural:2 procedural:4 "
                    "procedural:5)");
  paper->add_option("--v-mult", o.v_grid, "part b: v multipliers (default 1 3 5 9)");
  paper->add_option("--w-mult", o.w_grid, "part b: w multipliers (default 1 3 5 9)");
  paper->add_option("--lighting", o.lighting,
                    "part a: the relit configuration lighting:N (default 1)");
  paper->add_option("--rearranged", o.rearranged,
                    "part a: the rearranged configuration rearranged:N (default 5: 6 of the "
                    "default apartment's 15 movable objects pushed)");
  paper->add_option("--systems", o.systems,
                    "built-in systems (default opencv-rgbd opencv-icp)");
  paper->add_option("--reference-frame", e->reference,
                    "keyframe (default) or frame: what the built-in systems register to");
  paper->add_option("--frames", o.frames, "frames per sequence (default 100)");
  paper->add_option("--fps", o.fps, "frame rate (default 25)");
  paper->add_option("--width", o.width, "image width (default 320)");
  paper->add_option("--height", o.height, "image height (default 240)");
  paper->add_option("--fx", o.fx, "focal length, px (default 600 x width / 640)");
  paper->add_option("--spp", o.spp, "samples per pixel (default 4; the denoiser is on)");
  paper->add_option("--seed", o.seed, "seed of every trajectory and render (default 1)");
  paper->callback([e] { runExperiment(*e); });
}

}  // namespace inet::app
