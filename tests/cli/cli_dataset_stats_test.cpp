// Issue 16: interiornet dataset stats on a small real build (two procedural apartments with
// parametric furniture, a 4-frame sequence each in 2-frame units, their sparse views, 48x36 at
// 1 spp), first cut short and then complete: the counts agree with the plan file and the
// manifest, the NYU40 shares sum to 1, each sequence's speed agrees with its ground-truth file
// read here, the charts are PNGs of the documented sizes; bad input is a one-line error.
// One build serves the whole first test (ctest runs each test in its own process).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

const std::string kSpec = kTinyDatasetSpec;

nlohmann::json readJson(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

/// Width and height from a PNG's IHDR, after checking the signature.
std::pair<int, int> pngSize(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), 24);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(sig, sig + 8, h)) return {-1, -1};
  auto be32 = [&](int at) {
    return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3];
  };
  return {be32(16), be32(20)};
}

/// Mean camera speed (m/s) of an EuRoC ground-truth csv, computed here from its positions.
double meanSpeedOfCsv(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::vector<std::array<double, 4>> rows;  // t_s, x, y, z
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string f[4];
    for (auto& x : f) std::getline(ss, x, ',');
    rows.push_back({std::stoll(f[0]) * 1e-9, std::stod(f[1]), std::stod(f[2]), std::stod(f[3])});
  }
  double sum = 0;
  for (size_t k = 1; k < rows.size(); ++k)
    sum += std::hypot(rows[k][1] - rows[k - 1][1], rows[k][2] - rows[k - 1][2],
                      rows[k][3] - rows[k - 1][3]) /
           (rows[k][0] - rows[k - 1][0]);
  return rows.size() > 1 ? sum / double(rows.size() - 1) : -1;
}

TEST(CliDatasetStats, PartialThenCompleteBuild) {
  TempDir dir("dataset_stats");
  writeFile(dir / "tiny.yaml", kSpec);
  const std::string ds = (dir / "ds").string();
  ASSERT_EQ(runInterinet("dataset plan " + (dir / "tiny.yaml").string() + " --out " + ds).exit_code,
            0);
  const nlohmann::json plan = readJson(dir / "ds" / "plan.json");

  // cut short after the first layout's sequence (units 0 and 1: frames 0-1 and 2-3)
  ASSERT_EQ(
      runInterinet("dataset build " + ds + " --max-units 2 --no-progress --threads 2").exit_code,
      0);
  const RunResult part = runInterinet("dataset stats " + ds + " --no-progress");
  ASSERT_EQ(part.exit_code, 0) << part.err;
  EXPECT_NE(part.out.find("incomplete build"), std::string::npos) << part.out;
  const nlohmann::json p = readJson(dir / "ds" / "stats" / "stats.json");
  EXPECT_FALSE(p["complete"]);
  EXPECT_EQ(p["totals"]["frames"], 4);
  EXPECT_EQ(p["totals"]["layouts_built"], 1);
  EXPECT_EQ(p["totals"]["frames_planned"], plan["counts"]["frames"]);
  int measured = 0;
  for (const auto& q : p["motion"]["sequences"]) measured += q["steps"].get<int>() > 0;
  EXPECT_EQ(measured, 1);

  ASSERT_EQ(runInterinet("dataset build " + ds + " --no-progress --threads 2").exit_code, 0);
  const std::string out = (dir / "charts").string();
  const RunResult full = runInterinet("dataset stats " + ds + " --out " + out + " --max-frames 5");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const nlohmann::json s = readJson(dir / "charts" / "stats.json");
  EXPECT_TRUE(s["complete"]);

  // counts: the plan's layouts per split, rooms and frames; frames = manifest rows
  size_t rows = 0, labelled = 0;
  {
    std::ifstream in(dir / "ds" / "manifest.jsonl");
    std::string line;
    while (std::getline(in, line))
      if (!line.empty())
        ++rows, labelled += nlohmann::json::parse(line)["files"].contains("label0_nyu");
  }
  EXPECT_EQ(s["totals"]["layouts"], plan["counts"]["layouts"]);
  EXPECT_EQ(s["totals"]["frames"], plan["counts"]["frames"]);
  EXPECT_EQ(s["totals"]["frames"], rows);
  EXPECT_EQ(s["totals"]["sequence_frames"], plan["counts"]["sequence_frames"]);
  EXPECT_EQ(s["totals"]["sparse_views"], plan["counts"]["sparse_views"]);
  for (const char* split : {"train", "validation", "test"})
    EXPECT_EQ(s["splits"][split]["layouts"], plan["counts"][split]) << split;
  std::map<std::string, int> rooms;
  for (const auto& L : plan["layouts"]) ++rooms[std::to_string(L["rooms"].get<int>())];
  for (const auto& [r, n] : rooms) EXPECT_EQ(s["rooms_per_layout"][r], n) << r;

  // NYU40: 5 of the labelled frames, shares summing to 1, walls present
  EXPECT_EQ(s["nyu40"]["labelled_frames"], labelled);
  EXPECT_EQ(s["nyu40"]["sampled_frames"], 5);
  EXPECT_EQ(s["nyu40"]["pixels"], 5 * 48 * 36);
  double share = 0;
  int drawn = 0;
  for (const auto& c : s["nyu40"]["classes"]) {
    share += c["share"].get<double>();
    drawn += c["pixels"].get<int64_t>() > 0;
  }
  EXPECT_NEAR(share, 1.0, 1e-9);
  EXPECT_GT(s["nyu40"]["classes"][1]["pixels"].get<int64_t>(), 0);  // wall

  // motion: every sequence measured, its mean speed as its ground truth says, plausible
  for (const auto& q : s["motion"]["sequences"]) {
    ASSERT_EQ(q["steps"], 3) << q;
    const double v = q["mean_speed_m_s"].get<double>();
    EXPECT_GT(v, 0.0) << q;
    EXPECT_LT(v, 10.0) << q;
    EXPECT_NEAR(v,
                meanSpeedOfCsv(dir / "ds" / q["folder"].get<std::string>() /
                               "state_groundtruth_estimate0" / "data.csv"),
                1e-6)
        << q;
    EXPECT_LT(q["mean_turn_rate_deg_s"].get<double>(), 720.0) << q;
  }
  for (const auto& [type, t] : s["motion"]["trajectories"].items()) {
    if (t["sequences_measured"] == 0) continue;
    EXPECT_GT(t["speed_m_s"]["mean"].get<double>(), 0.0) << type;
    EXPECT_LT(t["speed_m_s"]["max"].get<double>(), 10.0) << type;
  }

  // the charts: PNGs of their documented sizes
  EXPECT_EQ(pngSize(dir / "charts" / "rooms_per_layout.png"), std::make_pair(900, 600));
  EXPECT_EQ(pngSize(dir / "charts" / "speeds.png"), std::make_pair(1600, 960));
  EXPECT_EQ(pngSize(dir / "charts" / "nyu40_pixels.png"),
            std::make_pair(900, std::max(300, 120 + 22 * drawn)));
  const auto [sw, sh] = pngSize(dir / "charts" / "splits.png");
  EXPECT_EQ(sw, 1300);
  EXPECT_GE(sh, 840);
  for (const char* f :
       {"stats.json", "rooms_per_layout.png", "splits.png", "nyu40_pixels.png", "speeds.png"})
    EXPECT_NE(full.out.find(f), std::string::npos) << full.out;
}

TEST(CliDatasetStats, BadInputIsAOneLineError) {
  TempDir dir("dataset_stats_bad");
  auto oneLine = [](const RunResult& r, const std::string& want) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(want), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  };
  oneLine(runInterinet("dataset stats " + (dir / "nowhere").string()), "no such folder");
  oneLine(runInterinet("dataset stats " + dir.path().string()), "no plan.json");
  oneLine(runInterinet("dataset stats " + dir.path().string() + " --max-frames 0"), "--max-frames");
  EXPECT_FALSE(fs::exists(dir / "stats"));
}

}  // namespace
}  // namespace inet::test
