// The dataset plan: determinism, splits and their stability, draws that do not move when the
// dataset grows, work units that tile every sequence, the plan file's round trip.
#include "builder/dataset_plan.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "trajectory/random_trajectory.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;
using test::TempDir;

/// A spec of `count` procedural layouts plus `extra` YAML lines.
DatasetSpec procedural(int64_t count, const std::string& extra = "",
                       const std::string& file = "/specs/spec.yaml") {
  return parseDatasetSpecText(
      fmt::format("version: 1\nname: t\nseed: 11\nlayouts:\n  procedural: {{count: {}}}\n{}", count,
                  extra),
      file);
}

std::string layoutJson(int rooms) {
  std::string s = R"({"format": "interiornet-layout", "version": 1, "meshes": [], )"
                  R"("materials": [], "objects": [], "rooms": [)";
  for (int i = 0; i < rooms; ++i)
    s += fmt::format(R"({}{{"id": "r{}", "type": "bedroom", "outline": [[0,0],[1,0],[1,1]]}})",
                     i ? ", " : "", i);
  return s + "]}";
}

TEST(DatasetPlan, SameSpecSamePlanByteForByte) {
  const DatasetSpec spec = procedural(200, "sequences: {per_layout: 2, frames: 120}\n");
  const std::string a = planText(makePlan(spec));
  const std::string b = planText(makePlan(procedural(200,
                                                     "sequences: {per_layout: 2, "
                                                     "frames: 120}\n")));
  EXPECT_EQ(a, b);
  TempDir dir("dataset_plan");
  writePlan(makePlan(spec), dir / "a.json");
  writePlan(makePlan(spec), dir / "b.json");
  EXPECT_EQ(readTextFile(dir / "a.json"), readTextFile(dir / "b.json"));
  EXPECT_EQ(readTextFile(dir / "a.json"), a);
  // a different dataset seed changes the draws (and so the plan), never the splits
  const DatasetPlan p0 = makePlan(spec);
  DatasetSpec other = spec;
  other.seed = 12;
  const DatasetPlan q = makePlan(other);
  int moved_draws = 0;
  for (size_t i = 0; i < p0.layouts.size(); ++i) {
    EXPECT_EQ(q.layouts[i].split, p0.layouts[i].split) << p0.layouts[i].id;
    moved_draws += q.layouts[i].sequences[0].seed != p0.layouts[i].sequences[0].seed;
  }
  EXPECT_EQ(moved_draws, 200);
}

TEST(DatasetPlan, SplitsOf1000LayoutsAreWithin2PercentOf801010) {
  const DatasetPlan plan = makePlan(procedural(1000));
  const SplitStats st = splitStats(plan);
  const double n = 1000.0;
  const double train = st.splits[0].layouts / n, val = st.splits[1].layouts / n,
               test = st.splits[2].layouts / n;
  std::printf(
      "splits of 1,000 procedural layouts: train %.1f %%, validation %.1f %%, "
      "test %.1f %%\n",
      100 * train, 100 * val, 100 * test);
  EXPECT_NEAR(train, 0.8, 0.02);
  EXPECT_NEAR(val, 0.1, 0.02);
  EXPECT_NEAR(test, 0.1, 0.02);
  EXPECT_EQ(st.splits[0].layouts + st.splits[1].layouts + st.splits[2].layouts, 1000);
  std::printf("%s", formatSplitStats(st).c_str());
  // A hash gives binomial shares: for 1,000 layouts the train share's standard deviation is
  // 1.3 %, so +-2 % holds for these ids but not for every set of 1,000. Other ids: within 3
  // standard deviations; 100,000 ids: within 0.4 % (3 standard deviations of 0.13 %).
  for (const int count : {1000, 100'000}) {
    int counts[3] = {};
    for (int i = 0; i < count; ++i)
      ++counts[static_cast<int>(
          splitOf(fmt::format("file:layouts/house_{:04d}.json", i), SplitShares{}))];
    const double m = count;
    std::printf("splits of %d file ids: %.2f %% / %.2f %% / %.2f %%\n", count, 100 * counts[0] / m,
                100 * counts[1] / m, 100 * counts[2] / m);
    const double sd_train = std::sqrt(0.8 * 0.2 / m), sd_other = std::sqrt(0.1 * 0.9 / m);
    EXPECT_NEAR(counts[0] / m, 0.8, 3 * sd_train);
    EXPECT_NEAR(counts[1] / m, 0.1, 3 * sd_other);
    EXPECT_NEAR(counts[2] / m, 0.1, 3 * sd_other);
  }
}

TEST(DatasetPlan, NoLayoutIsInTwoSplits) {
  // a layout's split is a function of its id alone: not of its position, not of the seed
  const DatasetPlan a = makePlan(procedural(500));
  DatasetSpec reseeded = procedural(500);
  reseeded.seed = 99;
  const DatasetPlan b = makePlan(reseeded);
  const DatasetPlan c = makePlan(parseDatasetSpecText(
      "version: 1\nname: t\nlayouts: {procedural: {count: 500, first_seed: 250}}\n", "s.yaml"));
  std::map<std::string, Split> split;
  for (const DatasetPlan* p : {&a, &b, &c})
    for (const PlannedLayout& L : p->layouts) {
      const auto [it, inserted] = split.emplace(L.id, L.split);
      EXPECT_EQ(it->second, L.split) << L.id << " is in two splits";
      EXPECT_EQ(L.split, splitOf(L.id, SplitShares{}));
    }
  EXPECT_EQ(split.size(), 750u);  // ids 0..749
  // every unit of a layout is in its layout's split: units carry the layout, not a split
  std::set<std::string> ids;
  for (const PlannedLayout& L : a.layouts) EXPECT_TRUE(ids.insert(L.id).second) << L.id;
  // a share of 0 gets no layout at all
  const DatasetPlan none = makePlan(procedural(300,
                                               "splits: {train: 0.9, validation: 0.1, "
                                               "test: 0}\n"));
  EXPECT_EQ(splitStats(none).splits[2].layouts, 0);
  EXPECT_GT(splitStats(none).splits[1].layouts, 0);
}

TEST(DatasetPlan, GrowingTheDatasetKeepsEveryLayoutsSplitRoomsAndDraws) {
  TempDir dir("dataset_plan_grow");
  dir.write("layouts/b.json", layoutJson(2));
  dir.write("layouts/a.json", layoutJson(5));
  const std::string extra =
      "  folders: [layouts]\nsequences: {per_layout: 3, configurations: "
      "[original, lighting, rearranged]}\n";
  auto spec = [&](int n) {
    return parseDatasetSpecText(
        fmt::format("version: 1\nname: g\nseed: 3\nlayouts:\n  procedural: {{count: {}}}\n{}", n,
                    extra),
        (dir / "spec.yaml").string());
  };
  const DatasetPlan small = makePlan(spec(1000));
  const DatasetPlan big = makePlan(spec(1500));
  ASSERT_EQ(small.layouts.size(), 1002u);
  ASSERT_EQ(big.layouts.size(), 1502u);
  std::map<std::string, const PlannedLayout*> by_id;
  for (const PlannedLayout& L : big.layouts) by_id[L.id] = &L;
  for (const PlannedLayout& L : small.layouts) {
    ASSERT_TRUE(by_id.count(L.id)) << L.id;
    // everything: split, rooms, subset, derived seeds, every sequence's draws
    EXPECT_EQ(*by_id[L.id], L) << L.id;
  }
  // the folder layouts moved in the list (after 1,500 procedural ones now) and kept everything
  EXPECT_EQ(big.layouts[1500].id, "file:layouts/a.json");
  EXPECT_EQ(small.layouts[1000], big.layouts[1500]);
  // more sequences per layout keep the first ones' draws
  const DatasetPlan more = makePlan(procedural(50, "sequences: {per_layout: 5}\n"));
  const DatasetPlan fewer = makePlan(procedural(50, "sequences: {per_layout: 2}\n"));
  for (size_t i = 0; i < 50; ++i)
    for (size_t k = 0; k < 2; ++k)
      EXPECT_EQ(more.layouts[i].sequences[k], fewer.layouts[i].sequences[k]);
}

TEST(DatasetPlan, DrawsFollowTheSpec) {
  const DatasetPlan p = makePlan(parseDatasetSpecText(R"(version: 1
name: d
layouts:
  procedural: {count: 1000, rooms: [2, 6]}
sequences:
  per_layout: 2
  v_mult: [0.8, 1.2]
  w_mult: [2, 2]
  trajectory: {two-body: 1, hand-held: 2, look-forward: 1}
)",
                                                      "d.yaml"));
  std::map<std::string, int> types;
  std::map<int, int> rooms;
  std::set<uint64_t> seeds;
  for (const PlannedLayout& L : p.layouts) {
    ++rooms[L.rooms];
    EXPECT_EQ(L.subset, fmt::format("rooms_{:02d}", L.rooms));
    for (const PlannedSequence& s : L.sequences) {
      ++types[s.trajectory];
      EXPECT_GE(s.v_mult, 0.8);
      EXPECT_LT(s.v_mult, 1.2);
      EXPECT_EQ(s.w_mult, 2.0);
      seeds.insert(s.seed);
      // names the generator reads
      EXPECT_NO_THROW(parseMotionType(s.trajectory));
    }
    EXPECT_EQ(L.sequences[0].name, "seq_000");
    EXPECT_EQ(L.sequences[1].name, "seq_001");
  }
  EXPECT_EQ(seeds.size(), 2000u);
  // weights 1:2:1 over 2,000 sequences: 500 / 1000 / 500 give or take a few %
  std::printf("trajectory types: two-body %d, hand-held %d, look-forward %d\n", types["two-body"],
              types["hand-held"], types["look-forward"]);
  EXPECT_NEAR(types["hand-held"], 1000, 100);
  EXPECT_NEAR(types["two-body"], 500, 80);
  EXPECT_NEAR(types["look-forward"], 500, 80);
  // rooms 2..6, each about 200 of 1,000
  ASSERT_EQ(rooms.size(), 5u);
  EXPECT_EQ(rooms.begin()->first, 2);
  EXPECT_EQ(rooms.rbegin()->first, 6);
  for (const auto& [r, n] : rooms) EXPECT_NEAR(n, 200, 60) << r << " rooms";
  // a zero weight is never drawn
  const DatasetPlan only = makePlan(
      procedural(100, "sequences: {trajectory: {two-body: 0, hand-held: 0, look-forward: 3}}\n"));
  for (const PlannedLayout& L : only.layouts) EXPECT_EQ(L.sequences[0].trajectory, "look-forward");
}

TEST(DatasetPlan, UnitsCoverEachSequenceExactlyOnce) {
  const DatasetPlan plan = makePlan(procedural(
      7,
      "sequences: {per_layout: 2, frames: 250, unit_frames: 100, configurations: [original, "
      "\"lighting:4\", rearranged]}\nsparse: {per_layout: 0}\n"));
  const std::vector<WorkUnit> us = units(plan);
  const PlanCounts c = planCounts(plan);
  EXPECT_EQ(c.units(), 7 * 2 * 3 * 3);
  ASSERT_EQ(static_cast<int64_t>(us.size()), c.units());
  EXPECT_EQ(c.frames(), 7 * 2 * 3 * 250);
  // (layout, sequence, configuration) -> the frames each unit covers
  std::map<std::tuple<int, int, int>, std::vector<int>> covered;
  std::set<std::string> ids;
  int64_t frames = 0;
  for (const WorkUnit& u : us) {
    EXPECT_EQ(u.kind, UnitKind::Sequence);
    EXPECT_TRUE(ids.insert(u.id).second) << u.id;
    EXPECT_EQ(u.frames, u.frame_end - u.frame_begin);
    EXPECT_LE(u.frames, 100);
    frames += u.frames;
    auto& f = covered[{u.layout, u.sequence, u.configuration}];
    for (int k = u.frame_begin; k < u.frame_end; ++k) f.push_back(k);
  }
  EXPECT_EQ(frames, c.frames());
  EXPECT_EQ(covered.size(), 7u * 2 * 3);
  for (auto& [key, f] : covered) {
    std::sort(f.begin(), f.end());
    ASSERT_EQ(f.size(), 250u);                         // no frame twice ...
    for (int k = 0; k < 250; ++k) ASSERT_EQ(f[k], k);  // ... and none missing
  }
  const PlannedLayout& L0 = plan.layouts[0];
  EXPECT_EQ(us[0].id, "seq/procedural:0/seq_000/original/f0000-0099");
  EXPECT_EQ(us[2].id, "seq/procedural:0/seq_000/original/f0200-0249");
  EXPECT_EQ(us[3].id, "seq/procedural:0/seq_000/lighting:4/f0000-0099");
  EXPECT_EQ(us[6].id,
            fmt::format("seq/procedural:0/seq_000/rearranged:{}/f0000-0099", L0.rearranged_seed));
  // a derived seed reads as `generate --config`
  const SceneConfiguration back =
      parseSceneConfiguration(configurationName(plan.spec.sequences.configurations[2], L0), "", "");
  EXPECT_EQ(back.seed, L0.rearranged_seed);
  EXPECT_FALSE(back.derived);
}

TEST(DatasetPlan, SparseViewsAreBatchedByLayout) {
  const DatasetPlan plan =
      makePlan(procedural(130, "sequences: {per_layout: 0}\nsparse: {batch: 64}\n"));
  const std::vector<WorkUnit> us = units(plan);
  ASSERT_EQ(us.size(), 3u);
  std::vector<int> seen(130, 0);
  for (const WorkUnit& u : us) {
    EXPECT_EQ(u.kind, UnitKind::Sparse);
    EXPECT_EQ(u.frames, u.layout_count * 3);
    for (int i = u.layout; i < u.layout + u.layout_count; ++i) ++seen[i];
  }
  for (int n : seen) EXPECT_EQ(n, 1);
  EXPECT_EQ(us[2].layout_count, 2);
  EXPECT_EQ(us[0].id, "sparse/procedural:0..procedural:63");
  const PlanCounts c = planCounts(plan);
  EXPECT_EQ(c.sparse_views, 390);
  EXPECT_EQ(c.sequences, 0);
  for (const PlannedLayout& L : plan.layouts) {
    EXPECT_TRUE(L.sequences.empty());
    EXPECT_LT(L.lighting_seed, 1'000'000'000u);
  }
  // without a derived configuration or sparse views, those seeds are not drawn into the plan
  const DatasetPlan plain = makePlan(procedural(5, "sparse: {per_layout: 0}\n"));
  EXPECT_EQ(plain.layouts[0].lighting_seed, 0u);
  EXPECT_EQ(plain.layouts[0].view_seed, 0u);
  EXPECT_EQ(planText(plain).find("view_seed"), std::string::npos);
}

TEST(DatasetPlan, FileLayoutsFoldersAndFront3d) {
  TempDir dir("dataset_plan_files");
  dir.write("layouts/zeta.json", layoutJson(3));
  dir.write("layouts/alpha.json", layoutJson(0));
  dir.write("layouts/no_rooms.json", R"({"format": "interiornet-layout", "version": 1})");
  dir.write("layouts/readme.txt", "not a layout");
  dir.write("houses/h1.json",
            R"({"mesh": [], "scene": {"room": [{"type": "Bedroom", "children": []}, )"
            R"({"type": "Kitchen"}, {"type": "Hallway", "children": [{"ref": "x"}]}]}})");
  const std::string spec_file = dir.write("spec.yaml", R"(version: 1
name: files
layouts:
  folders: [./layouts]
  front3d: [houses/h1.json]
)");
  const DatasetPlan plan = makePlan(parseDatasetSpec(spec_file));
  ASSERT_EQ(plan.layouts.size(), 4u);
  EXPECT_EQ(plan.layouts[0].id, "file:layouts/alpha.json");  // names in byte order
  EXPECT_EQ(plan.layouts[1].id, "file:layouts/no_rooms.json");
  EXPECT_EQ(plan.layouts[2].id, "file:layouts/zeta.json");
  EXPECT_EQ(plan.layouts[3].id, "front3d:houses/h1.json");
  EXPECT_EQ(plan.layouts[0].rooms, 0);
  EXPECT_EQ(plan.layouts[0].subset, "rooms_unknown");
  EXPECT_EQ(plan.layouts[1].subset, "rooms_unknown");
  EXPECT_EQ(plan.layouts[2].rooms, 3);
  EXPECT_EQ(plan.layouts[2].subset, "rooms_03");
  EXPECT_EQ(plan.layouts[3].rooms, 3);
  EXPECT_EQ(plan.layouts[2].kind, LayoutKind::File);
  EXPECT_EQ(plan.layouts[3].kind, LayoutKind::Front3d);
  EXPECT_EQ(fs::path(plan.layouts[2].path), dir.path() / "layouts" / "zeta.json");

  // errors point into the spec, or at the layout file
  const std::string missing =
      dir.write("missing.yaml", "version: 1\nname: m\nlayouts:\n  folders: [nowhere]\n");
  InputError e = expectInputError([&] { makePlan(parseDatasetSpec(missing)); });
  EXPECT_EQ(e.file(), missing);
  EXPECT_EQ(e.field(), "layouts.folders[0] (line 4)");
  EXPECT_NE(e.problem().find("no such folder"), std::string::npos) << e.what();
  dir.write("empty/readme.txt", "");
  const std::string empty = dir.write("empty.yaml",
                                      "version: 1\nname: m\nlayouts:\n  front3d: [houses/h1.json]\n"
                                      "  folders: [empty]\n");
  e = expectInputError([&] { makePlan(parseDatasetSpec(empty)); });
  EXPECT_EQ(e.field(), "layouts.folders[0] (line 5)");
  dir.write("bad/broken.json", "{\"rooms\": [1, 2,, 3]}");
  const std::string bad =
      dir.write("bad.yaml", "version: 1\nname: m\nlayouts:\n  folders: [bad]\n");
  e = expectInputError([&] { makePlan(parseDatasetSpec(bad)); });
  EXPECT_EQ(fs::path(e.file()), dir.path() / "bad" / "broken.json");
  EXPECT_NE(e.problem().find("line 1"), std::string::npos) << e.what();
  dir.write("odd/\xff.json", "{}");  // a name that is not UTF-8 cannot be a JSON id
  const std::string odd =
      dir.write("odd.yaml", "version: 1\nname: m\nlayouts:\n  folders: [odd]\n");
  e = expectInputError([&] { makePlan(parseDatasetSpec(odd)); });
  EXPECT_EQ(e.field(), "layouts.folders[0] (line 4)");
  EXPECT_NE(e.problem().find("UTF-8"), std::string::npos) << e.what();
  const std::string twice = dir.write(
      "twice.yaml", "version: 1\nname: m\nlayouts:\n  folders: [layouts, ./layouts/../layouts/]\n");
  e = expectInputError([&] { makePlan(parseDatasetSpec(twice)); });
  EXPECT_NE(e.problem().find("twice"), std::string::npos) << e.what();
}

TEST(DatasetPlan, PlanFileRoundTrip) {
  TempDir dir("dataset_plan_io");
  dir.write("layouts/a.json", layoutJson(4));
  const std::string spec_file = dir.write("spec.yaml", R"(version: 1
name: io
seed: 18446744073709551615
layouts:
  procedural: {count: 40, first_seed: 7}
  folders: [layouts]
sequences:
  per_layout: 2
  frames: 33
  unit_frames: 10
  configurations: [original, lighting]
sparse: {configurations: [original, rearranged], batch: 16}
)");
  const DatasetPlan plan = makePlan(parseDatasetSpec(spec_file));
  writePlan(plan, dir / "plan.json");
  const std::string text = readTextFile(dir / "plan.json");
  const DatasetPlan back = readPlan(dir / "plan.json");
  EXPECT_EQ(back.spec, plan.spec);
  EXPECT_EQ(back.spec.checksum, plan.spec.checksum);
  EXPECT_EQ(back.layouts, plan.layouts);
  writePlan(back, dir / "again.json");
  EXPECT_EQ(readTextFile(dir / "again.json"), text);
  // the units of the read plan are the same
  const std::vector<WorkUnit> a = units(plan), b = units(back);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].id, b[i].id);
  EXPECT_EQ(a.size(), 41u * 2 * 2 * 4 + 3);
  // the header says what the plan holds
  EXPECT_NE(text.find("\"format\": \"interiornet-dataset-plan\""), std::string::npos);
  EXPECT_NE(text.find(fmt::format("\"units\": {}", a.size())), std::string::npos);
  EXPECT_NE(text.find("\"spec_checksum\": \"" + plan.spec.checksum + "\""), std::string::npos);
}

TEST(DatasetPlan, ReadPlanErrorsAreLocated) {
  TempDir dir("dataset_plan_bad");
  writePlan(makePlan(procedural(3)), dir / "plan.json");
  const std::string good = readTextFile(dir / "plan.json");
  // replaces the first `from` at or after `after`
  auto broken = [&](std::string from, std::string to, const std::string& after = "") {
    std::string text = good;
    const size_t p = text.find(from, text.find(after));
    EXPECT_NE(p, std::string::npos) << from;
    text.replace(p, from.size(), to);
    const std::string file = dir.write("bad.json", text);
    return expectInputError([&] { readPlan(file); });
  };
  InputError e = broken("\"rooms\":", "\"rooms\":\"x\",\"r\":", "\"layouts\": [");
  EXPECT_EQ(e.file(), (dir / "bad.json").string());
  EXPECT_EQ(e.field(), "layouts[0].rooms");
  e = broken("\"split\":\"", "\"split\":\"x");
  EXPECT_NE(e.field().find(".split"), std::string::npos) << e.what();
  e = broken("\"version\": 1", "\"version\": 2");
  EXPECT_EQ(e.field(), "version");
  e = broken("interiornet-dataset-plan", "interiornet-layout");
  EXPECT_EQ(e.field(), "format");
  e = broken("\"frames\": 1000", "\"frames\": 0");
  EXPECT_EQ(e.field(), "spec.sequences.frames");
  e = broken("\"layouts\": 3", "\"layouts\": 4");
  EXPECT_EQ(e.field(), "counts.layouts");
  e = broken("\"layouts\": [", "\"layouts\": [[");
  EXPECT_EQ(e.field().rfind("line ", 0), 0u) << e.what();
}

TEST(DatasetPlan, SplitStatsAddUp) {
  const DatasetPlan plan = makePlan(procedural(
      300, "sequences: {per_layout: 2, frames: 10, configurations: [original, lighting:1]}\n"));
  const SplitStats st = splitStats(plan);
  const PlanCounts c = planCounts(plan);
  int64_t layouts = 0, frames = 0, views = 0;
  for (int s = 0; s < 3; ++s) {
    SplitCount sum;
    for (const auto& [name, per] : st.subsets) {
      sum.layouts += per[s].layouts;
      sum.sequences += per[s].sequences;
      sum.sequence_frames += per[s].sequence_frames;
      sum.sparse_views += per[s].sparse_views;
    }
    EXPECT_EQ(sum, st.splits[s]);
    EXPECT_EQ(st.splits[s].layouts, c.split_layouts[s]);
    layouts += st.splits[s].layouts;
    frames += st.splits[s].sequence_frames;
    views += st.splits[s].sparse_views;
  }
  EXPECT_EQ(layouts, 300);
  EXPECT_EQ(frames, c.sequence_frames);
  EXPECT_EQ(frames, 300 * 2 * 2 * 10);
  EXPECT_EQ(views, 900);
  EXPECT_EQ(st.subsets.size(), 8u);  // rooms_01 .. rooms_08
  EXPECT_EQ(st.subsets.begin()->first, "rooms_01");
}

// Not a timed test: run by hand for the figure (issue 16 asks for under 10 s), with
//   build/tests/builder/builder_dataset_plan_test --gtest_also_run_disabled_tests
//   --gtest_filter='*PlanTime100k*'
TEST(DatasetPlan, DISABLED_PlanTime100kLayouts) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  TempDir dir("dataset_plan_time");
  const auto t0 = Clock::now();
  const DatasetSpec spec = procedural(100'000,
                                      "sequences: {per_layout: 1, frames: 1000, "
                                      "unit_frames: 100}\nsparse: {per_layout: 0}\n");
  const DatasetPlan plan = makePlan(spec);
  const auto t1 = Clock::now();
  writePlan(plan, dir / "plan.json");
  const auto t2 = Clock::now();
  const std::vector<WorkUnit> us = units(plan);
  const auto t3 = Clock::now();
  const DatasetPlan back = readPlan(dir / "plan.json");
  const auto t4 = Clock::now();
  std::printf(
      "100,000 layouts, %zu units: plan %.3f s, write %.3f s (%.1f MB), plan + write "
      "%.3f s; expand units %.3f s; read back %.3f s\n",
      us.size(), seconds(t0, t1), seconds(t1, t2), fs::file_size(dir / "plan.json") / 1e6,
      seconds(t0, t2), seconds(t2, t3), seconds(t3, t4));
  EXPECT_EQ(us.size(), 1'000'000u);
  EXPECT_EQ(back.layouts.size(), 100'000u);
}

}  // namespace
}  // namespace inet
