// End to end: a generated apartment gets a random trajectory and renders labelled frames with no
// camera path given; `trajectory generate`, `convert`, `show` and `eval ate` work together on
// the files they write.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/atomic_file.h"
#include "trajectory/formats.h"

namespace inet::test {
namespace {

TEST(CliTrajectory, GenerateOnAGeneratedLayoutFindsItsOwnPath) {
  TempDir dir("cli_traj_layout");
  const std::string layout = (dir / "apt").string();
  ASSERT_EQ(runInterinet("layout generate --seed 4 --texture-size 64 --out " + layout).exit_code, 0);
  RunResult r = runInterinet("generate --layout " + layout +
                             "/layout.json --trajectory hand-held --frames 3 --spp 1 --width 64 "
                             "--height 48 --fx 60 --fy 60 --no-progress --seed 9 --imu 400 --out " +
                             (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // one sequence folder with 3 labelled frames
  auto tree = readTree(dir / "out");
  int labels = 0;
  std::string gt, meta;
  for (const auto& [name, text] : tree) {
    labels += name.find("_nyu.png") != std::string::npos;
    if (name.find("groundtruth.txt") != std::string::npos) gt = text;
    if (name.find("meta.json") != std::string::npos) meta = text;
  }
  EXPECT_EQ(labels, 3);
  Trajectory t = parseTrajectory(gt, "groundtruth.txt", TrajectoryFormat::Tum);
  ASSERT_EQ(t.size(), 3u);
  for (const auto& p : t.poses) {
    EXPECT_GE(p.T_world_camera.t.z(), 1.0);
    EXPECT_LE(p.T_world_camera.t.z(), 2.0);
    EXPECT_LT(p.T_world_camera.rotation().col(2).z(), 0.0) << "hand-held looks down";
  }
  EXPECT_NE(meta.find("hand-held random trajectory, seed 9"), std::string::npos) << meta;
  // --imu 400: 3 frames at 25 Hz span 80 ms, so 33 samples at 400 Hz, EuRoC header first
  std::string imu;
  for (const auto& [name, text] : tree)
    if (name.find("imu0/data.csv") != std::string::npos) imu = text;
  ASSERT_FALSE(imu.empty());
  EXPECT_EQ(imu.rfind("#timestamp [ns],w_RS_S_x [rad s^-1]", 0), 0u);
  EXPECT_EQ(std::count(imu.begin(), imu.end(), '\n'), 1 + 33);
  // Kinect-like depth for the same sequence, twice: same seed, same bytes
  std::string seq;
  for (const auto& [name, text] : tree)
    if (name.size() > 9 && name.compare(name.size() - 9, 9, "meta.json") == 0)
      seq = (dir / "out" / name.substr(0, name.size() - 10)).string();
  ASSERT_FALSE(seq.empty());
  const std::filesystem::path noisy_dir = std::filesystem::path(seq) / "depth0_noisy";
  const auto generated = readTree(noisy_dir);
  RunResult noisy = runInterinet("depth-noise --sequence " + seq + " --seed 4");
  ASSERT_EQ(noisy.exit_code, 0) << noisy.err;
  const auto first = readTree(noisy_dir);
  // generate wrote depth0_noisy/ already (a default pass); depth-noise redoes its frames with
  // another seed through the same writer: the same sensor.yaml and data.csv, plus noise.yaml
  EXPECT_EQ(first.size(), 3u + 3u) << "3 frames, data.csv, noise.yaml, sensor.yaml";
  EXPECT_EQ(first.at("sensor.yaml"), generated.at("sensor.yaml"));
  EXPECT_EQ(first.at("data.csv"), generated.at("data.csv"));
  EXPECT_EQ(generated.count("noise.yaml"), 0u);
  ASSERT_EQ(runInterinet("depth-noise --sequence " + seq + " --seed 4").exit_code, 0);
  EXPECT_EQ(readTree(noisy_dir), first);
  // a remake that fails half-way leaves the folder marked incomplete (no data.csv), and says
  // which file stopped it
  const auto last_depth = std::filesystem::path(seq) / "depth0" / "data" /
                          std::prev(first.end(), 3)->first.substr(5);  // data/<t>.png
  ASSERT_TRUE(std::filesystem::remove(last_depth)) << last_depth;
  noisy = runInterinet("depth-noise --sequence " + seq + " --seed 5");
  EXPECT_NE(noisy.exit_code, 0);
  EXPECT_NE(noisy.err.find(last_depth.string()), std::string::npos) << noisy.err;
  EXPECT_FALSE(std::filesystem::exists(noisy_dir / "data.csv"));
}

TEST(CliTrajectory, GenerateConvertShowAndScore) {
  TempDir dir("cli_traj_tools");
  const std::string tum = (dir / "a.txt").string(), csv = (dir / "a.csv").string();
  RunResult g = runInterinet("trajectory generate --type look-forward --frames 200 --seed 2 "
                             "--v-mult 1.5 --w-mult 1 --out " + tum + " --plot " +
                             (dir / "a.png").string());
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_NE(g.out.find("v_mult 1.50, w_mult 1.00"), std::string::npos) << g.out;
  EXPECT_GT(std::filesystem::file_size(dir / "a.png"), 10000u);
  // the same seed gives the same bytes
  ASSERT_EQ(runInterinet("trajectory generate --type look-forward --frames 200 --seed 2 "
                         "--v-mult 1.5 --w-mult 1 --out " + (dir / "b.txt").string())
                .exit_code,
            0);
  EXPECT_EQ(readTextFile(tum), readTextFile(dir / "b.txt"));

  RunResult c = runInterinet("trajectory convert " + tum + " " + csv);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(readTrajectory(csv).size(), 200u);
  RunResult s = runInterinet("trajectory show " + csv + " --out " + (dir / "s.png").string());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "s.png"));

  // a file against its own conversion scores zero; a shifted copy scores the shift after
  // --align none and zero after se3
  RunResult e = runInterinet("eval ate " + tum + " " + csv + " --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  auto j = nlohmann::json::parse(e.out);
  EXPECT_EQ(j["pairs"], 200);
  EXPECT_LT(j["translation_m"]["rmse"].get<double>(), 1e-6) << "EuRoC keeps every digit";
  Trajectory moved = readTrajectory(tum);
  for (auto& p : moved.poses) p.T_world_camera.t += Vec3(0.3, 0, 0.4);
  writeTrajectory((dir / "moved.txt").string(), moved, TrajectoryFormat::Tum);
  RunResult none =
      runInterinet("eval ate " + tum + " " + (dir / "moved.txt").string() + " --align none --json");
  ASSERT_EQ(none.exit_code, 0) << none.err;
  auto jn = nlohmann::json::parse(none.out);
  EXPECT_NEAR(jn["translation_m"]["min"].get<double>(), 0.5, 1e-6);  // |(0.3, 0, 0.4)|
  EXPECT_NEAR(jn["translation_m"]["max"].get<double>(), 0.5, 1e-6);
  RunResult se3 = runInterinet("eval ate " + tum + " " + (dir / "moved.txt").string() + " --json");
  ASSERT_EQ(se3.exit_code, 0) << se3.err;
  EXPECT_LT(nlohmann::json::parse(se3.out)["translation_m"]["rmse"].get<double>(), 1e-6);
  RunResult bad = runInterinet("trajectory generate --type jog --out " + (dir / "x.txt").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--type"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.txt"));
}

// train-style runs in its own LibTorch executable; interiornet hands over every argument to it
// (so interiornet itself starts without loading LibTorch)
TEST(CliTrajectory, TrainStyleHandsOverToItsOwnExecutable) {
  RunResult help = runInterinet("trajectory train-style --help");
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("--holdout"), std::string::npos) << help.out;
  RunResult bad = runInterinet("trajectory train-style --data /nonexistent/folder --out x.bin");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("/nonexistent/folder: --data"), std::string::npos) << bad.err;
  RunResult version = runInterinet("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_LT(version.peak_rss_kb, 60000) << "interiornet does not load LibTorch";
}

}  // namespace
}  // namespace inet::test
