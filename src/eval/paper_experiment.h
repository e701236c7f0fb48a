#pragma once
// `interiornet eval experiment paper`: the paper's Section 7 (Li et al., BMVC 2018) on our own
// data in one command. Every sequence is made with the sequence pipeline (pipeline/
// sequence_job.h, what `generate` runs) and every system is run and scored by eval/slam_eval.h.
//
// Parts (each selectable; docs/evaluation.md):
//   a  one two-body (type-1) trajectory at (v, w) = (1, 1) through the apartment, in its
//      original, relit (lighting:N) and rearranged (rearranged:M) configurations: Table 1
//      rows 1-3;
//   b  two-body trajectories over a grid of v and w multipliers through the apartment: share
//      of frames tracked and ATE against difficulty (Table 1 rows 4-5, Fig. 6 right);
//   c  the three trajectory types (two-body, hand-held, look-forward) at (1, 1): rows 6-8;
//   d  a two-body (1, 1) trajectory with the same seed through several layouts: mean and
//      spread of the ATE over layouts (the paper's closing paragraph). A random trajectory is
//      drawn in each layout's own free space, so "the same trajectory" is the same type,
//      multipliers and seed, not the same poses.
// A sequence several parts need is made once (its folder name says what it is). Runs resume:
// runSequenceJob skips the frames that are complete, and each system is run again (seconds).
//
// Outputs under `out`: sequences/<layout>/<name>/ (ASL), runs/<layout>/<name>/<system>/ (each
// eval slam report), results.csv (one row per sequence and system), table.md (Table 1's shape),
// speed_tracked.png and speed_ate.png (part b), layouts.png (part d), experiment.json (options
// and every row).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "eval/slam_eval.h"

namespace inet {

struct PaperExperimentOptions {
  std::filesystem::path out = "experiment";
  std::string parts = "abcd";                 ///< any of a, b, c, d
  std::string apartment = "procedural:3";     ///< parts a-c
  int rooms = 0;                              ///< procedural apartments: 0 = drawn
  std::vector<std::string> layouts = {"procedural:1", "procedural:2", "procedural:4",
                                      "procedural:5"};  ///< part d
  std::vector<double> v_grid = {1, 3, 5, 9};  ///< part b
  std::vector<double> w_grid = {1, 3, 5, 9};  ///< part b
  /// Part a's configurations: lighting:<lighting> and rearranged:<rearranged> (the seeds of
  /// `vary relight` and `vary rearrange`). Rearrangement pushes a random 5-45 % of the movable
  /// objects; seed 5 pushes 6 of the default apartment's 15 (seed 1 pushes one, out of view of
  /// the path, which leaves every frame as it was).
  int lighting = 1, rearranged = 5;
  std::vector<std::string> systems = {"opencv-rgbd", "opencv-icp"};  ///< built-in systems
  OdometryReference reference = OdometryReference::Keyframe;
  int frames = 100;
  double fps = 25;
  int width = 320, height = 240;
  double fx = 0;  ///< 0 = the pipeline's default for the width
  int spp = 4;
  uint64_t seed = 1;      ///< trajectory and render seed of every sequence
  bool progress = true;  ///< a line per sequence and per run on stdout
  /// InputError naming the option ("--parts", "--v-mult", "--w-mult", "--systems", "--frames", ...).
  void validate() const;
};

/// One system on one sequence.
struct ExperimentRow {
  std::string part;           ///< a, b, c or d (a sequence used by several parts has a row each)
  std::string layout;         ///< the scene source ("procedural:3")
  std::string sequence;       ///< folder
  std::string configuration;  ///< original, lighting:1, rearranged:1
  std::string type;           ///< two-body, hand-held, look-forward
  double v = 1, w = 1;
  SlamScore score;            ///< its system, ATE, tracked share, runtime
};

struct PaperExperimentResult {
  std::vector<ExperimentRow> rows;
  double render_s = 0, eval_s = 0;  ///< wall time making sequences and running systems
};

/// Runs the experiment (InputError for bad options; a failed sequence or run stops it, and a
/// rerun resumes). Writes every output listed above.
PaperExperimentResult runPaperExperiment(const PaperExperimentOptions& opt);

/// The markdown table (Table 1's shape: No, length, (v, w, type), configuration, then ATE and
/// tracked share per system), with part d's mean and spread under it.
std::string experimentTableMarkdown(const PaperExperimentResult& r,
                                    const std::vector<std::string>& systems);

}  // namespace inet
