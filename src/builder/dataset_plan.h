#pragma once
// The dataset plan (issue 16, docs/dataset.md): the spec (dataset_spec.h) turned into the list of
// layouts with every random decision taken, and the work units a build executes.
//
//   DatasetSpec spec = parseDatasetSpec("dataset.yaml");
//   DatasetPlan plan = makePlan(spec);        // lists folders, reads room counts, draws
//   writePlan(plan, "out/plan.json");         // atomically; readPlan() gives it back
//   for (const WorkUnit& u : units(plan)) ... // what `dataset build` hands out
//
// Determinism and stability:
//  - the same spec (and the same layout files) gives the same plan and a byte-identical file;
//  - a layout's split is a function of its id alone (stableHash64 of the id against the split
//    shares), never of its position or of the dataset seed: adding layouts never moves one;
//  - every draw of a layout (room count, derived configuration seeds, view seed) and of its
//    sequences (trajectory type, v_mult, w_mult, trajectory seed) comes from a counter-based
//    stream keyed by (dataset seed, hash of the layout id, sequence index) (core/rng.h), so
//    adding layouts or sequences never changes the draws of the others.
//
// Units are not stored: they follow from the layouts and the spec (units()), which keeps the
// plan file at one line per layout (a 100,000-layout plan has a million 100-frame units).
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "builder/dataset_spec.h"

namespace inet {

enum class LayoutKind { Procedural, File, Front3d };
/// "procedural", "file", "front3d".
const char* layoutKindName(LayoutKind kind);

enum class Split { Train, Validation, Test };
/// "train", "validation", "test".
const char* splitName(Split split);

/// The split of the layout with this id under these shares: u = the top 53 bits of
/// stableHash64(id) as a number in [0, 1); train below `train`, validation below
/// `train + validation`, test above. A function of the id alone, so it never changes when the
/// dataset grows.
Split splitOf(const std::string& layout_id, const SplitShares& shares);

/// "rooms_03" for 3 rooms, "rooms_unknown" for 0 (a layout file that does not say).
std::string subsetName(int rooms);

/// One sequence of a layout with its draws.
struct PlannedSequence {
  std::string name;        ///< "seq_000", "seq_001", ...
  std::string trajectory;  ///< two-body, hand-held or look-forward
  double v_mult = 1.0, w_mult = 1.0;
  uint64_t seed = 0;  ///< the trajectory's seed (RandomTrajectoryOptions::seed)
  bool operator==(const PlannedSequence&) const = default;
};

struct PlannedLayout {
  std::string id;  ///< "procedural:<seed>", "file:<path as given>/<name>.json", "front3d:<path>"
  LayoutKind kind = LayoutKind::Procedural;
  uint64_t seed = 0;  ///< Procedural: the apartment seed (ApartmentOptions::seed)
  std::string path;   ///< File, Front3d: the file, absolute
  int rooms = 0;      ///< room count; 0 = unknown
  Split split = Split::Train;
  std::string subset;  ///< subsetName(rooms)
  /// Seeds of the configurations whose seed is derived ("lighting", "rearranged" without ":N"),
  /// 0..999999999, and of the sparse view's pose; 0 when the spec has no use for them.
  uint64_t lighting_seed = 0, rearranged_seed = 0, view_seed = 0;
  std::vector<PlannedSequence> sequences;
  bool operator==(const PlannedLayout&) const = default;
};

struct DatasetPlan {
  DatasetSpec spec;  ///< the effective spec (file = the spec file, checksum of its text)
  std::vector<PlannedLayout> layouts;  ///< procedural, then folders, then 3D-FRONT, spec order
};

/// The name of configuration `c` for `layout`, as `generate --config` reads it: "original",
/// "lighting:<n>", "rearranged:<n>" (a derived seed replaced by the layout's).
std::string configurationName(const SceneConfiguration& c, const PlannedLayout& layout);

enum class UnitKind { Sequence, Sparse };

/// One piece of work `dataset build` hands to a rank.
///  - Sequence: frames [frame_begin, frame_end) of sequence `sequence` of layout `layout` in
///    configuration `configuration` (an index into spec.sequences.configurations);
///  - Sparse: one view of each of the `layout_count` layouts from `layout` on, in every
///    configuration of spec.sparse.configurations (configuration = -1).
struct WorkUnit {
  /// Stable and unique: "seq/<layout id>/<sequence>/<configuration>/f0000-0099" (the last frame
  /// inclusive) or "sparse/<first layout id>..<last layout id>".
  std::string id;
  UnitKind kind = UnitKind::Sequence;
  int layout = 0;
  int layout_count = 1;
  int sequence = -1;
  int configuration = -1;
  int frame_begin = 0, frame_end = 0;
  int64_t frames = 0;  ///< frames (sparse: views) it renders: its weight for scheduling and ETA
};

/// Every work unit of the plan, in this order: for each layout (plan order), each sequence,
/// each configuration, the frame ranges [0, unit_frames), [unit_frames, 2 unit_frames), ...
/// (the last one shorter); then the sparse batches of spec.sparse.batch layouts in plan order.
/// Units all but a sequence's last have the same length, so a dynamic scheduler handing them
/// out in this order mixes long and short ones without sorting.
std::vector<WorkUnit> units(const DatasetPlan& plan);

struct PlanCounts {
  int64_t layouts = 0, sequences = 0;
  int64_t sequence_units = 0, sparse_units = 0;
  int64_t sequence_frames = 0;  ///< over every configuration
  int64_t sparse_views = 0;
  std::array<int64_t, 3> split_layouts{};  ///< by Split
  int64_t units() const { return sequence_units + sparse_units; }
  int64_t frames() const { return sequence_frames + sparse_views; }
};
/// The plan's totals (without expanding the units).
PlanCounts planCounts(const DatasetPlan& plan);

/// Layouts, sequences and frames of one split (or one subset of a split).
struct SplitCount {
  int64_t layouts = 0, sequences = 0;
  int64_t sequence_frames = 0;  ///< over every configuration
  int64_t sparse_views = 0;
  bool operator==(const SplitCount&) const = default;
};
struct SplitStats {
  std::array<SplitCount, 3> splits;  ///< by Split
  /// subset name -> counts by Split; subsets in name order (rooms_01, ..., rooms_unknown)
  std::map<std::string, std::array<SplitCount, 3>> subsets;
};
/// Counts per split and per subset and split.
SplitStats splitStats(const DatasetPlan& plan);
/// A small table of splitStats for the terminal: one row per subset and a total row, layouts
/// and frames per split with the shares of the layouts.
std::string formatSplitStats(const SplitStats& stats);

/// Makes the plan of `spec`: lists the layout folders (their *.json files in name order), reads
/// the room count of each layout file, assigns splits and subsets, draws every layout's and
/// sequence's random values. Throws InputError naming the spec file and field for a folder or
/// file that is missing, an empty folder, two layouts with the same id, and naming the layout
/// file for one that is not JSON.
DatasetPlan makePlan(const DatasetSpec& spec);

/// The plan file's text (what writePlan writes): a header (format, version, the spec file and
/// its checksum, the counts), the effective spec, and one line per layout. Deterministic.
std::string planText(const DatasetPlan& plan);
/// Writes planText(plan) to `path` atomically (a temporary renamed into place).
void writePlan(const DatasetPlan& plan, const std::filesystem::path& path);
/// Reads a plan file back. Throws InputError(path, field, problem) for a file that is not a
/// plan, of another version, or has a malformed or inconsistent entry (field e.g.
/// "layouts[12].rooms", or "line 4, column 2" for JSON syntax).
DatasetPlan readPlan(const std::filesystem::path& path);

}  // namespace inet
