// Dataset statistics (dataset_stats.h): the even sample, speeds and turn rates from known poses,
// the fixed histogram, and a hand-made partial build folder (plan, unit manifests, label images,
// ground truth) whose every count is known: splits, NYU40 pixels of exactly the sampled frames,
// the original configuration's motion only, the charts, and the errors.
#include "builder/dataset_stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "builder/dataset_plan.h"
#include "builder/unit_runner.h"
#include "core/atomic_file.h"
#include "core/image_io.h"
#include "trajectory/formats.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;
using test::TempDir;

TEST(DatasetStats, EvenSampleTakesTheMiddleOfEqualSlices) {
  EXPECT_EQ(evenSample(5, 10), (std::vector<int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(evenSample(5, 5), (std::vector<int64_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(evenSample(0, 3).empty());
  // 2 of 10: slices [0, 5) and [5, 10), middles 2.5 and 7.5
  EXPECT_EQ(evenSample(10, 2), (std::vector<int64_t>{2, 7}));
  EXPECT_EQ(evenSample(100, 4), (std::vector<int64_t>{12, 37, 62, 87}));
  EXPECT_EQ(evenSample(7, 1), (std::vector<int64_t>{3}));
  // far past int64 for a naive (2i + 1) n: still exact, increasing and inside [0, n)
  const int64_t n = 4'000'000'000'000'000'000;
  const std::vector<int64_t> big = evenSample(n, 1000);
  ASSERT_EQ(big.size(), 1000u);
  for (size_t i = 0; i < big.size(); ++i)  // n / 2000 = 2e15 exactly, so (2i+1) * 2e15
    EXPECT_EQ(big[i], static_cast<int64_t>(2 * i + 1) * 2'000'000'000'000'000) << i;
  // with a remainder: n = 2000 q + 1999, so item i is (2i+1) q + floor((2i+1) 1999 / 2000)
  // = (2i+1) q + 2i (as (2i+1) / 2000 < 1)
  const std::vector<int64_t> odd = evenSample(n + 1999, 1000);
  for (size_t i = 0; i < odd.size(); ++i)
    EXPECT_EQ(odd[i],
              static_cast<int64_t>(2 * i + 1) * 2'000'000'000'000'000 + static_cast<int64_t>(2 * i))
        << i;
}

TEST(DatasetStats, EvenSampleIsEvenlySpaced) {
  for (const auto& [n, k] : {std::pair<int64_t, int64_t>{1000, 7}, {999, 333}, {12345, 2000}}) {
    const std::vector<int64_t> s = evenSample(n, k);
    ASSERT_EQ(static_cast<int64_t>(s.size()), k);
    const int64_t gap = n / k;
    for (size_t i = 1; i < s.size(); ++i) {
      EXPECT_GE(s[i] - s[i - 1], gap) << n << " " << k;
      EXPECT_LE(s[i] - s[i - 1], gap + 1) << n << " " << k;
    }
  }
}

Pose poseAt(const Vec3& p, const Vec3& axis, double angle_deg) {
  Pose T;
  T.q = Quat(Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()));
  T.t = p;
  return T;
}

TEST(DatasetStats, MotionStepsFromKnownPoses) {
  // 25 fps, 2 cm and 2 degrees about z per frame: 0.5 m/s and 50 deg/s
  Trajectory traj;
  for (int k = 0; k < 4; ++k)
    traj.poses.push_back(
        {k * 40'000'000LL, poseAt(Vec3(0.02 * k, 1, 1.5), Vec3::UnitZ(), 2.0 * k)});
  const std::vector<MotionStep> steps = motionSteps(traj);
  ASSERT_EQ(steps.size(), 3u);
  for (const MotionStep& s : steps) {
    EXPECT_NEAR(s.speed_m_s, 0.5, 1e-9);
    EXPECT_NEAR(s.turn_deg_s, 50.0, 1e-7);
  }
  // uneven times, a diagonal move and a tilted axis: |(3, 4, 0)| cm in 0.1 s = 0.5 m/s,
  // 9 degrees in 0.1 s = 90 deg/s whatever the axis and start orientation
  const Vec3 axis(1, -2, 0.5);
  Trajectory t2;
  t2.poses.push_back({0, poseAt(Vec3(0, 0, 0), axis, 30.0)});
  t2.poses.push_back({100'000'000, poseAt(Vec3(0.03, 0.04, 0), axis, 39.0)});
  // the same rotation as -q (quaternions cover rotations twice): still 9 degrees, not 351
  Pose flipped = poseAt(Vec3(0.03, 0.04, 0), axis, 48.0);
  flipped.q.coeffs() *= -1.0;
  t2.poses.push_back({300'000'000, flipped});
  const std::vector<MotionStep> s2 = motionSteps(t2);
  ASSERT_EQ(s2.size(), 2u);
  EXPECT_NEAR(s2[0].speed_m_s, 0.5, 1e-9);
  EXPECT_NEAR(s2[0].turn_deg_s, 90.0, 1e-7);
  EXPECT_NEAR(s2[1].speed_m_s, 0.0, 1e-12);
  EXPECT_NEAR(s2[1].turn_deg_s, 45.0, 1e-7);  // 9 degrees in 0.2 s
  Trajectory one;
  one.poses.push_back({0, Pose{}});
  EXPECT_TRUE(motionSteps(one).empty());
}

TEST(DatasetStats, FixedHistogramCountsMeanAndQuantiles) {
  FixedHistogram h(0.5, 4);  // [0, 0.5) [0.5, 1) [1, 1.5) [1.5, 2), then overflow
  for (double v : {0.1, 0.2, 0.7, 1.2, 1.4, 1.6, 3.0}) h.add(v);
  EXPECT_EQ(h.counts, (std::vector<int64_t>{2, 1, 2, 1}));
  EXPECT_EQ(h.overflow, 1);
  EXPECT_EQ(h.n, 7);
  EXPECT_NEAR(h.mean(), 8.2 / 7, 1e-12);
  EXPECT_DOUBLE_EQ(h.max, 3.0);
  EXPECT_DOUBLE_EQ(h.quantile(0.0), 0.5);   // rank 1: first bin's upper edge
  EXPECT_DOUBLE_EQ(h.quantile(0.5), 1.5);   // rank 4 lies in [1, 1.5)
  EXPECT_DOUBLE_EQ(h.quantile(0.95), 3.0);  // rank 7 is the overflow: the maximum
  EXPECT_DOUBLE_EQ(FixedHistogram(1, 3).quantile(0.5), 0.0);
}

// ---- a hand-made partial build ----------------------------------------------------------------

/// Two procedural layouts, one 3-frame sequence each in two configurations, sparse views.
DatasetPlan tinyPlan() {
  return makePlan(
      parseDatasetSpecText("version: 1\nname: handmade\nseed: 5\n"
                           "layouts: {procedural: {count: 2, rooms: [2, 3]}}\n"
                           "sequences: {per_layout: 1, frames: 3, unit_frames: 3, "
                           "configurations: [original, \"lighting:1\"]}\n",
                           "/specs/handmade.yaml"));
}

/// A label image of 4 x 2 pixels: frame k has class (k % 40) + 1 in pixels 0..k%7, wall (1)
/// elsewhere, and void in the last pixel.
ImageU8 labelImage(int k) {
  ImageU8 img(4, 2, 1, 1);
  for (int i = 0; i <= k % 7; ++i) img.data[size_t(i)] = uint8_t(k % 40 + 1);
  img.data[7] = 0;
  return img;
}

/// Writes a 3-pose ground truth moving `step_m` per 40 ms along x (EuRoC csv).
void writeGroundTruth(const fs::path& seq_dir, double step_m) {
  Trajectory t;
  for (int k = 0; k < 3; ++k)
    t.poses.push_back({k * 40'000'000LL, poseAt(Vec3(step_m * k, 0, 1.4), Vec3::UnitZ(), 4.0 * k)});
  fs::create_directories(seq_dir / "state_groundtruth_estimate0");
  writeTrajectory((seq_dir / "state_groundtruth_estimate0" / "data.csv").string(), t,
                  TrajectoryFormat::Euroc);
}

struct Handmade {
  DatasetPlan plan;
  std::vector<ImageU8> labels;  ///< in manifest order
};

/// Layout 0's sequence in both configurations (6 labelled rows) and one sparse view of layout 0
/// without a label; layout 1 nothing: a build cut short. The lighting copy moves 5x faster, so
/// counting it would show.
Handmade writeHandmade(const fs::path& root) {
  Handmade h{tinyPlan(), {}};
  writePlan(h.plan, root / "plan.json");
  const PlannedLayout& L = h.plan.layouts[0];
  std::string rows[2];
  int k = 0;
  for (int c = 0; c < 2; ++c) {
    const std::string seq = c == 0 ? "seq_000" : "seq_000_lighting_1";
    const fs::path folder = fs::path("data") / layoutFolder(L) / seq;
    writeGroundTruth(root / folder, c == 0 ? 0.04 : 0.2);
    for (int f = 0; f < 3; ++f, ++k) {
      const std::string label =
          (folder / fmt::format("label0/data/{:019d}_nyu.png", f * 40'000'000LL)).generic_string();
      h.labels.push_back(labelImage(k));
      writePng(root / label, h.labels.back());
      nlohmann::ordered_json row = {{"split", splitName(L.split)},
                                    {"subset", L.subset},
                                    {"layout", L.id},
                                    {"configuration", c == 0 ? "original" : "lighting:1"},
                                    {"sequence", "seq_000"},
                                    {"folder", folder.generic_string()},
                                    {"trajectory", L.sequences[0].trajectory},
                                    {"v_mult", L.sequences[0].v_mult},
                                    {"w_mult", L.sequences[0].w_mult},
                                    {"frame", f},
                                    {"t_ns", f * 40'000'000LL},
                                    {"files", {{"cam0", "x.png"}, {"label0_nyu", label}}}};
      rows[0] += row.dump() + "\n";
    }
  }
  nlohmann::ordered_json sparse = {
      {"split", splitName(L.split)},
      {"subset", L.subset},
      {"layout", L.id},
      {"configuration", "original"},
      {"sequence", "sparse"},
      {"folder", (fs::path("data") / layoutFolder(L) / "sparse").generic_string()},
      {"trajectory", "two-body"},
      {"frame", 0},
      {"t_ns", 0},
      {"files", {{"cam0", "y.png"}}}};
  rows[1] = sparse.dump() + "\n";
  writeTextAtomic(unitManifestPath(root, 0), rows[0]);
  writeTextAtomic(unitManifestPath(root, 2), rows[1]);  // unit 1 not done yet
  return h;
}

TEST(DatasetStats, PartialBuildCountsWhatIsBuilt) {
  TempDir dir("dataset_stats");
  const Handmade h = writeHandmade(dir.path());
  const DatasetStats s = computeDatasetStats(dir.path(), {});
  EXPECT_EQ(s.name, "handmade");
  EXPECT_FALSE(s.complete);
  const PlannedLayout& L = h.plan.layouts[0];
  const int split = static_cast<int>(L.split);
  EXPECT_EQ(s.total.layouts, 2);
  EXPECT_EQ(s.total.sequences, 2);
  EXPECT_EQ(s.total.frames_planned, 2 * (2 * 3 + 3));  // 2 configurations x 3 frames + 3 views
  EXPECT_EQ(s.total.frames, 7);
  EXPECT_EQ(s.total.sequence_frames, 6);
  EXPECT_EQ(s.total.sparse_views, 1);
  EXPECT_EQ(s.total.layouts_built, 1);
  EXPECT_EQ(s.splits[split].frames, 7);
  EXPECT_EQ(s.subsets.at(L.subset)[split].frames, 7);
  EXPECT_EQ(s.subsets.at(L.subset)[split].layouts_built, 1);
  int64_t rooms = 0;
  for (const auto& [r, n] : s.layouts_per_rooms) {
    EXPECT_TRUE(r == 2 || r == 3) << r;
    rooms += n;
  }
  EXPECT_EQ(rooms, 2);

  // NYU40: every labelled frame, pixel by pixel
  EXPECT_EQ(s.labelled_frames, 6);
  EXPECT_EQ(s.sampled_frames, 6);
  std::array<int64_t, kNyu40Count> want{};
  for (const ImageU8& img : h.labels)
    for (uint8_t v : img.data) ++want[v];
  EXPECT_EQ(s.nyu40_pixels, want);
  EXPECT_EQ(s.label_width, 4);
  EXPECT_EQ(s.label_height, 2);

  // motion: the original's 1 m/s (4 cm per 40 ms), never the lighting copy's 5 m/s
  const std::string type = L.sequences[0].trajectory;
  ASSERT_EQ(s.sequences.size(), 2u);
  EXPECT_EQ(s.sequences[0].steps, 2);
  EXPECT_NEAR(s.sequences[0].mean_speed_m_s, 1.0, 1e-9);
  EXPECT_NEAR(s.sequences[0].mean_turn_deg_s, 100.0, 1e-6);
  EXPECT_EQ(s.sequences[0].folder,
            (fs::path("data") / layoutFolder(L) / "seq_000").generic_string());
  EXPECT_EQ(s.sequences[1].steps, 0);  // layout 1: nothing built
  EXPECT_EQ(s.trajectories.at(type).sequences_measured, 1);
  EXPECT_EQ(s.trajectories.at(type).speed_m_s.n, 2);
  EXPECT_NEAR(s.trajectories.at(type).speed_m_s.max, 1.0, 1e-9);
}

TEST(DatasetStats, NyuCountsOnlyTheEvenSample) {
  TempDir dir("dataset_stats");
  const Handmade h = writeHandmade(dir.path());
  DatasetStatsOptions opt;
  opt.max_frames = 2;
  const DatasetStats s = computeDatasetStats(dir.path(), opt);
  EXPECT_EQ(s.labelled_frames, 6);
  EXPECT_EQ(s.sampled_frames, 2);
  std::array<int64_t, kNyu40Count> want{};
  for (int64_t k : evenSample(6, 2))  // frames 1 and 4
    for (uint8_t v : h.labels[size_t(k)].data) ++want[v];
  EXPECT_EQ(s.nyu40_pixels, want);
}

TEST(DatasetStats, CompleteManifestIsPreferred) {
  TempDir dir("dataset_stats");
  writeHandmade(dir.path());
  // manifest.jsonl holds only the first row: the unit files must then be ignored
  const std::string first = readTextFile(unitManifestPath(dir.path(), 0));
  writeTextAtomic(dir / "manifest.jsonl", first.substr(0, first.find('\n') + 1));
  const DatasetStats s = computeDatasetStats(dir.path(), {});
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.total.frames, 1);
  EXPECT_EQ(s.labelled_frames, 1);
}

TEST(DatasetStats, WritesJsonAndCharts) {
  TempDir dir("dataset_stats");
  writeHandmade(dir.path());
  const DatasetStats s = computeDatasetStats(dir.path(), {});
  const std::vector<fs::path> files = writeDatasetStats(s, dir / "stats");
  const std::vector<std::string> names = {"stats.json", "rooms_per_layout.png", "splits.png",
                                          "nyu40_pixels.png", "speeds.png"};
  ASSERT_EQ(files.size(), names.size());
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(files[i], dir / "stats" / names[i]);
  const ImageU8 rooms = readPng8(dir / "stats" / "rooms_per_layout.png");
  EXPECT_EQ(rooms.width, 900);
  EXPECT_EQ(rooms.height, 600);
  const ImageU8 speeds = readPng8(dir / "stats" / "speeds.png");  // 2 x 2 panels
  EXPECT_EQ(speeds.width, 2 * 800);
  EXPECT_EQ(speeds.height, 2 * 480);
  for (const auto& e : fs::directory_iterator(dir / "stats"))  // no scratch panels left
    EXPECT_FALSE(isTemporaryName(e.path().filename().string())) << e.path();

  const auto j = nlohmann::json::parse(readTextFile(dir / "stats" / "stats.json"));
  EXPECT_EQ(j["totals"]["frames"], 7);
  EXPECT_EQ(j["nyu40"]["classes"].size(), 41u);
  double share = 0;
  for (const auto& c : j["nyu40"]["classes"]) share += c["share"].get<double>();
  EXPECT_NEAR(share, 1.0, 1e-12);
  EXPECT_EQ(j["nyu40"]["classes"][1]["name"], "wall");
  const std::string type = s.sequences[0].trajectory;
  EXPECT_NEAR(j["motion"]["trajectories"][type]["speed_m_s"]["mean"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(j["motion"]["sequences"].size(), 2u);

  // nothing labelled: no NYU40 chart, and the earlier one is removed rather than left stale
  DatasetStats bare = s;
  bare.nyu40_pixels.fill(0);
  writeDatasetStats(bare, dir / "stats");
  EXPECT_FALSE(fs::exists(dir / "stats" / "nyu40_pixels.png"));
}

TEST(DatasetStats, ErrorsNameTheFolderFileAndLine) {
  TempDir dir("dataset_stats");
  const InputError none = expectInputError([&] { computeDatasetStats(dir / "absent", {}); });
  EXPECT_NE(std::string(none.what()).find("no such folder"), std::string::npos) << none.what();
  const InputError no_plan = expectInputError([&] { computeDatasetStats(dir.path(), {}); });
  EXPECT_NE(std::string(no_plan.what()).find("no plan.json"), std::string::npos) << no_plan.what();
  DatasetStatsOptions zero;
  zero.max_frames = 0;
  EXPECT_EQ(expectInputError([&] { computeDatasetStats(dir.path(), zero); }).field(), "max_frames");

  const Handmade h = writeHandmade(dir.path());
  const fs::path rows = unitManifestPath(dir.path(), 0);
  std::string text = readTextFile(rows);
  // a missing label image names itself
  const fs::path label =
      dir.path() / nlohmann::json::parse(text.substr(0, text.find('\n')))["files"]["label0_nyu"]
                       .get<std::string>();
  fs::remove(label);
  const InputError missing = expectInputError([&] { computeDatasetStats(dir.path(), {}); });
  EXPECT_NE(std::string(missing.what()).find(label.filename().string()), std::string::npos)
      << missing.what();
  // a broken second row names the file and line 2
  const size_t second = text.find('\n') + 1;
  writeTextAtomic(rows, text.substr(0, second) + "{\"split\": \"train\"\n");
  const InputError bad = expectInputError([&] { computeDatasetStats(dir.path(), {}); });
  EXPECT_EQ(bad.file(), rows.string());
  EXPECT_EQ(bad.field(), "line 2");
  writeTextAtomic(rows, text.substr(0, second) + "{\"split\": \"holdout\"}\n");
  EXPECT_NE(
      expectInputError([&] { computeDatasetStats(dir.path(), {}); }).problem().find("holdout"),
      std::string::npos);
}

}  // namespace
}  // namespace inet
