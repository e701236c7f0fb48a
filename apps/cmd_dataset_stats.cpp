// interiornet dataset stats DIR (issue 16, docs/dataset.md "Statistics"): stats.json and PNG
// charts of a build folder, complete or partial. Thin over src/builder/dataset_stats.h.
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "builder/dataset_stats.h"
#include "common.h"
#include "core/error.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct StatsArgs {
  std::string dir, out;
  int64_t max_frames = 2000;
  bool progress = true;
};

void runStats(const StatsArgs& a) {
  // checked here too, so that the message names the flag rather than the library's field
  if (a.max_frames < 1 || a.max_frames > 1000000000)
    throw InputError("", "--max-frames",
                     fmt::format("must be 1 .. 1000000000, got {}", a.max_frames));
  DatasetStatsOptions opt;
  opt.max_frames = a.max_frames;
  opt.progress = a.progress;
  const DatasetStats s = computeDatasetStats(a.dir, opt);
  const fs::path out = a.out.empty() ? fs::path(a.dir) / "stats" : fs::path(a.out);
  const std::vector<fs::path> files = writeDatasetStats(s, out);
  int64_t measured = 0;
  for (const SequenceMotion& q : s.sequences) measured += q.steps > 0;
  fmt::print(
      "{}: {} layouts, {} of {} frames built{}; NYU40 pixels of {} of {} labelled frames; "
      "speeds of {} of {} sequences\n",
      s.name, s.total.layouts, s.total.frames, s.total.frames_planned,
      s.complete ? "" : " (incomplete build)", s.sampled_frames, s.labelled_frames, measured,
      s.sequences.size());
  for (const fs::path& f : files) fmt::print("wrote {}\n", f.string());
}

}  // namespace

void registerDatasetStats(CLI::App& dataset_cmd) {
  auto args = std::make_shared<StatsArgs>();
  auto* c = dataset_cmd.add_subcommand(
      "stats",
      "Describe a build folder, complete or not (what is built so far): writes stats.json (every "
      "number) and PNG charts to DIR/stats: rooms_per_layout.png, splits.png (layouts and frames "
      "per split and per subset), nyu40_pixels.png (share of pixels per NYU40 class over a "
      "sample of the labelled frames) and speeds.png (per trajectory type, histograms of the "
      "linear speed and turn rate between consecutive ground-truth poses; the planned v_mult and "
      "w_mult). Reads plan.json, the manifest and the files; writes nothing else");
  c->add_option("DIR", args->dir, "the build folder (with plan.json)")->required();
  c->add_option("--out", args->out, "where to write stats.json and the charts (default DIR/stats)");
  c->add_option("--max-frames", args->max_frames,
                "label images decoded for the NYU40 shares: an evenly spaced sample of at most N "
                "labelled frames in manifest order, so that a large dataset stays fast "
                "(default 2000)");
  c->add_flag("--no-progress{false}", args->progress, "do not draw the progress bars");
  c->callback([args] { runStats(*args); });
}

}  // namespace inet::app
