// interiornet dataset shards DIR (issue 16, docs/dataset.md "WebDataset shards"): WebDataset tar
// shards and wids indexes of a complete build folder, on demand. Thin over src/builder/shards.h.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "builder/dataset_build.h"
#include "builder/shards.h"
#include "common.h"
#include "core/error.h"
#include "core/text.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct ShardsArgs {
  std::string dir;
  double max_mb = 0;
  std::string passes;
  bool max_mb_given = false, passes_given = false;  ///< else the spec's shards settings
  bool progress = true;
};

void runShards(const ShardsArgs& a) {
  installStopHandlers();
  // the plan holds the effective spec: its name and shards settings are the defaults
  const BuildFolder folder(a.dir, StateAccess::None);
  ShardOptions opt = shardOptions(folder.plan().spec);
  opt.progress = a.progress;
  if (a.max_mb_given) {
    if (!(a.max_mb >= 0.001 && a.max_mb <= 1e7))
      throw InputError("", "--max-mb", fmt::format("must be 0.001 .. 10000000, got {}", a.max_mb));
    opt.max_bytes = std::llround(a.max_mb * 1e6);
  }
  if (a.passes_given) {
    opt.passes = splitCommaList(a.passes);
    if (opt.passes.empty()) throw InputError("", "--passes", "no pass key given");
  }
  ShardReport r;
  try {
    r = writeShards(a.dir, opt);
  } catch (const InputError& e) {
    if (e.field() != "passes" || !a.passes_given) throw;
    throw InputError(e.file(), "--passes", e.problem());  // name the flag the user gave
  }
  for (const auto& [split, shards] : r.splits) {
    int64_t samples = 0, bytes = 0, reused = 0;
    for (const ShardRecord& s : shards) samples += s.samples, bytes += s.bytes, reused += s.reused;
    fmt::print("{}: {} shard(s), {} samples, {:.1f} MB ({} unchanged); index {}\n", split,
               shards.size(), samples, bytes / 1e6, reused,
               (fs::path(a.dir) / "shards" / (split + ".json")).string());
  }
  fmt::print("{} samples, {:.1f} MB of shards, {:.1f} MB written in {:.1f} s ({:.0f} MB/s)\n",
             r.samples, r.bytes / 1e6, r.bytes_written / 1e6, r.seconds,
             r.seconds > 0 ? r.bytes_written / 1e6 / r.seconds : 0.0);
}

}  // namespace

void registerDatasetShards(CLI::App& dataset_cmd) {
  auto args = std::make_shared<ShardsArgs>();
  auto* c = dataset_cmd.add_subcommand(
      "shards",
      "Write WebDataset tar shards of a complete build folder (one sample per manifest row, key "
      "<layout>/<sequence>/<frame>, members key.json and key.<pass key>.png|exr|flo), per split "
      "in DIR/shards/<split>/<split>-NNNNNN.tar, each at most --max-mb, and the wids shard "
      "index DIR/shards/<split>.json; the same build gives the same bytes, and a rerun leaves "
      "unchanged shards alone. Defaults from the spec's shards key (docs/dataset.md)");
  c->add_option("DIR", args->dir, "the build folder (with plan.json and manifest.jsonl)")
      ->required();
  c->add_option("--max-mb", args->max_mb,
                "a shard's bound in MB (10^6 bytes) of tar, headers included; a larger sample is "
                "a shard alone (default: the spec's shards.max_mb, 1024)");
  c->add_option("--passes", args->passes,
                "pass keys of the manifest to include, comma-separated (cam0,depth0.exr,"
                "label0_nyu) or all (default: the spec's shards.passes, all)");
  c->add_flag("--no-progress{false}", args->progress, "do not draw the progress bar");
  c->callback([args, c] {
    args->max_mb_given = c->count("--max-mb") > 0;
    args->passes_given = c->count("--passes") > 0;
    runShards(*args);
  });
}

}  // namespace inet::app
