#pragma once
// Statistics of a built dataset (issue 16, docs/dataset.md "Statistics"): what `dataset stats
// DIR` measures in a build folder (unit_runner.h) and writes to DIR/stats/.
//
//   DatasetStats s = computeDatasetStats("ds", {});  // plan.json + manifest + the files
//   writeDatasetStats(s, "ds/stats");                  // stats.json and four PNG charts
//
// Sources, so that a partial build is described by what it holds:
//  - the plan (plan.json): layouts per room count, split and subset; sequences with their
//    trajectory type and v/w multipliers; the planned frames;
//  - the manifest (manifest.jsonl, or manifest/units/*.jsonl in unit order while the build is
//    incomplete): the frames built, per split and subset; which frames have an NYU40 image;
//    which folder holds each sequence;
//  - the files: NYU40 label images (an evenly spaced sample of them, so a 20M-frame dataset
//    takes seconds, not hours) and each sequence's ground-truth poses
//    (state_groundtruth_estimate0/data.csv, else the TUM groundtruth.txt), read once per
//    sequence from its original configuration (a relit or rearranged copy repeats the camera
//    path and would count it twice).
// Every count is deterministic: the same folder gives the same stats.json whatever the threads.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "scene/nyu40.h"
#include "trajectory/trajectory.h"

namespace inet {

struct DatasetStatsOptions {
  /// Labelled frames decoded for the NYU40 pixel counts: an evenly spaced sample (evenSample)
  /// of at most this many, in manifest order. 1 .. 10^9.
  int64_t max_frames = 2000;
  bool progress = false;  ///< progress bars on stderr
};

/// Indices of min(k, n) of the items 0..n-1 spread evenly: item floor((2i + 1) n / 2k) for
/// i = 0..k-1, the middle of k equal slices (all items when k >= n). Strictly increasing.
/// Needs 0 <= n, 1 <= k <= 10^9.
std::vector<int64_t> evenSample(int64_t n, int64_t k);

/// The camera's motion between consecutive poses k and k+1, dt = t_{k+1} - t_k in seconds.
struct MotionStep {
  double speed_m_s = 0;   ///< |p_{k+1} - p_k| / dt, camera centre
  double turn_deg_s = 0;  ///< angle of R_k^T R_{k+1} / dt, in [0, 180] degrees per dt
};
/// The size() - 1 steps of a trajectory (none for fewer than two poses). Finite differences
/// over one frame interval: at 25 fps they follow the motion closely, and they are what a
/// tracker sees between two frames.
std::vector<MotionStep> motionSteps(const Trajectory& traj);

/// Counts of non-negative values in fixed bins [k w, (k+1) w), k = 0..bins-1; values at or
/// beyond bins * w land in `overflow`. Count, sum and maximum are exact, so the mean is too;
/// quantiles are good to one bin. Fixed bins keep memory flat however many frames are added.
struct FixedHistogram {
  double bin_width = 1.0;
  std::vector<int64_t> counts;
  int64_t overflow = 0;
  int64_t n = 0;
  double sum = 0, max = 0;

  FixedHistogram(double bin_width, int bins);
  void add(double v);
  double mean() const { return n > 0 ? sum / static_cast<double>(n) : 0.0; }
  /// The upper edge of the bin holding the value of rank ceil(p n) (p in [0, 1]); the maximum
  /// when that rank is in the overflow; 0 for no values.
  double quantile(double p) const;
};

/// Layouts, sequences and frames of one split (or one subset of a split).
struct SplitTally {
  int64_t layouts = 0, sequences = 0;  ///< planned
  int64_t frames_planned = 0;          ///< sequence frames over every configuration + sparse views
  int64_t layouts_built = 0;           ///< with at least one frame in the manifest
  int64_t frames = 0;                  ///< built: manifest rows (sequence_frames + sparse_views)
  int64_t sequence_frames = 0, sparse_views = 0;
};

/// The motion of every sequence of one trajectory type.
struct TrajectoryTypeStats {
  int64_t sequences = 0;                  ///< planned sequences of this type
  int64_t sequences_measured = 0;         ///< of those, with ground-truth poses read
  FixedHistogram speed_m_s{0.005, 4000};  ///< per step, 0 .. 20 m/s
  FixedHistogram turn_deg_s{0.25, 4000};  ///< per step, 0 .. 1000 deg/s
};

/// One planned sequence: its draws and, once built, its measured motion.
struct SequenceMotion {
  std::string layout, sequence, trajectory;
  double v_mult = 1.0, w_mult = 1.0;
  std::string folder;  ///< relative to the build folder; "" = no frame built yet
  int64_t steps = 0;   ///< measured steps; 0 = no ground truth (sequence not finished)
  double mean_speed_m_s = 0, mean_turn_deg_s = 0;
};

struct DatasetStats {
  std::string name;                          ///< the spec's name
  std::filesystem::path root;                ///< the build folder
  bool complete = false;                     ///< manifest.jsonl exists (every unit done)
  int64_t max_frames = 0;                    ///< the option used
  std::map<int, int64_t> layouts_per_rooms;  ///< room count -> layouts; 0 = unknown
  std::array<SplitTally, 3> splits{};        ///< by Split
  std::map<std::string, std::array<SplitTally, 3>> subsets;  ///< subset -> by Split
  SplitTally total;
  /// NYU40: labelled frames (manifest rows with a label0_nyu file), those decoded, and their
  /// pixels per class id; values above 40 (a corrupt file) are counted apart.
  int64_t labelled_frames = 0, sampled_frames = 0;
  std::array<int64_t, kNyu40Count> nyu40_pixels{};
  int64_t invalid_label_pixels = 0;
  int label_width = 0, label_height = 0;                    ///< of the first sampled image
  std::map<std::string, TrajectoryTypeStats> trajectories;  ///< by trajectory type
  std::vector<SequenceMotion> sequences;                    ///< plan order
  /// The spec's ranges the multipliers are drawn from (SequencesSpec), and its frame rate.
  std::array<double, 2> v_mult_range{}, w_mult_range{};
  double fps = 0;
};

/// Measures the build folder `root` (see the top of this file). Throws InputError naming the
/// folder when it has no plan.json, or the file (and line) for a malformed manifest row, a
/// label image that is missing or not 8-bit grey, or unreadable ground truth.
DatasetStats computeDatasetStats(const std::filesystem::path& root,
                                 const DatasetStatsOptions& options);

/// Every number of `stats` as JSON (stats.json): totals, rooms per layout, splits, subsets,
/// NYU40 pixels and shares of all 41 ids (the shares sum to 1), per trajectory type the speed
/// and turn-rate summaries with their histograms, and every sequence.
std::string datasetStatsJson(const DatasetStats& stats);

/// Writes `out`/stats.json and the charts rooms_per_layout.png, splits.png, nyu40_pixels.png
/// and speeds.png, each atomically. Returns the files written, in that order (a chart with
/// nothing to show, e.g. NYU40 before any label is built, is left out).
std::vector<std::filesystem::path> writeDatasetStats(const DatasetStats& stats,
                                                     const std::filesystem::path& out);

}  // namespace inet
