// Bad input, table-driven: every case must exit non-zero with a one-line message naming the
// file (or flag) and the problem, and must write nothing under the output folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <vector>

#include "cli_util.h"
#include "core/atomic_file.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

std::string layoutWith(
    const std::string& object_json, const std::string& mesh_json = "",
    const std::string& head = R"("format": "interiornet-layout", "version": 1)") {
  return "{" + head + R"(, "name": "room",
  "meshes": [{"id": "box", "primitive": "box"})" +
         mesh_json + R"(],
  "materials": [{"id": "white", "type": "lambertian", "albedo": [0.8, 0.8, 0.8]}],
  "lights": [{"name": "bulb", "type": "point", "position": [0, 0, 2], "intensity": 3}],
  "objects": [)" +
         object_json + "]}\n";
}

const std::string kGoodObject =
    R"({"name": "cube", "mesh": "box", "material": "white", "nyu40": 29, "instance": 1,
        "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})";

const std::string kGoodTrajectory =
    "# t tx ty tz qx qy qz qw\n1.0 0 -3 0 0 0 0 1\n1.04 0 -3 0 0 0 0 1\n";

struct Case {
  std::string name;
  std::map<std::string, std::string> files;  // written into the case folder
  std::string args;                          // {D} is replaced by the case folder
  std::vector<std::string> expect;           // substrings of stderr
};

std::vector<Case> cases() {
  const std::string traj_args = " --trajectory {D}/traj.txt";
  std::string obj = kGoodObject;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = kGoodObject;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  return {
      {"malformed_json",
       {{"l.json", "{\"format\": \"interiornet-layout\", \"version\": 1,,}"},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "JSON"}},
      {"missing_field",
       {{"l.json", layoutWith(replaced(R"("mesh": "box", )", ""))}, {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "mesh"}},
      {"wrong_type",
       {{"l.json", layoutWith(replaced(R"("instance": 1)", R"("instance": "one")"))},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "instance"}},
      {"negative_scale",
       {{"l.json", layoutWith(replaced("[1,0,0,0,", "[-1,0,0,0,"))}, {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "transform"}},
      {"unknown_label",
       {{"l.json", layoutWith(replaced(R"("nyu40": 29)", R"("category": "spaceship")"))},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "spaceship"}},
      {"label_out_of_range",
       {{"l.json", layoutWith(replaced(R"("nyu40": 29)", R"("nyu40": 41)"))},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "nyu40"}},
      {"unknown_key",
       {{"l.json", layoutWith(replaced(R"("instance": 1)", R"("instance": 1, "colour": 3)"))},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "colour"}},
      {"wrong_version",
       {{"l.json", layoutWith(kGoodObject, "", R"("format": "interiornet-layout", "version": 99)")},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"l.json", "version"}},
      {"missing_mesh_file",
       {{"l.json", layoutWith(kGoodObject, R"(, {"id": "chair", "file": "no_such_chair.obj"})")},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json" + traj_args,
       {"no_such_chair.obj"}},
      {"malformed_obj",
       {{"scene.obj", "o broken\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
        {"traj.txt", kGoodTrajectory}},
       "--layout {D}/scene.obj" + traj_args,
       {"scene.obj"}},
      {"missing_layout",
       {{"traj.txt", kGoodTrajectory}},
       "--layout {D}/nothing.json" + traj_args,
       {"nothing.json", "not found"}},
      {"empty_trajectory",
       {{"l.json", layoutWith(kGoodObject)}, {"traj.txt", "# only a comment\n"}},
       "--layout {D}/l.json" + traj_args,
       {"traj.txt", "no poses"}},
      {"non_monotonic_time",
       {{"l.json", layoutWith(kGoodObject)},
        {"traj.txt", "2.0 0 -3 0 0 0 0 1\n1.0 0 -3 0 0 0 0 1\n"}},
       "--layout {D}/l.json" + traj_args,
       {"traj.txt", "line 2", "increase"}},
      {"short_trajectory_line",
       {{"l.json", layoutWith(kGoodObject)}, {"traj.txt", "1.0 0 -3 0 0 0 1\n"}},
       "--layout {D}/l.json" + traj_args,
       {"traj.txt", "line 1", "8 fields"}},
      {"bad_quaternion",
       {{"l.json", layoutWith(kGoodObject)}, {"traj.txt", "1.0 0 -3 0 0 0 0 2\n"}},
       "--layout {D}/l.json" + traj_args,
       {"traj.txt", "quaternion"}},
      {"layout_without_room_for_a_camera",  // a 0.3 m cube: no place 0.25 m from it in its box
       {{"l.json", layoutWith(R"({"name": "cube", "mesh": "box", "material": "white",
            "nyu40": 29, "instance": 1,
            "transform": [0.3,0,0,0, 0,0.3,0,0, 0,0,0.3,0, 0,0,0,1]})")}},
       "--layout {D}/l.json",
       {"l.json", "free space", "--trajectory"}},
      {"too_many_frames",
       {{"l.json", layoutWith(kGoodObject)}, {"traj.txt", kGoodTrajectory}},
       "--layout {D}/l.json --frames 5" + traj_args,
       {"traj.txt", "--frames"}},
      {"unknown_pass", {}, "--passes depth,colour", {"--passes", "colour"}},
      {"unknown_format", {}, "--format asl,rosbag", {"--format", "rosbag"}},
      {"zero_frames", {}, "--frames 0", {"--frames"}},
      {"zero_spp", {}, "--spp 0", {"--spp"}},
      {"negative_threads", {}, "--threads -1", {"--threads"}},
      {"bad_width", {}, "--width 0", {"width"}},
      {"unknown_tone_curve", {}, "--tone sepia", {"--tone", "sepia"}},
      {"absurd_exposure", {}, "--exposure-ev 99", {"--exposure-ev"}},
      {"unwritable_output",
       {{"out", "I am a file, not a folder\n"}},
       "--frames 1 --out {D}/out",
       {"out"}},
  };
}

// Readable names in test listings instead of a byte dump.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, FailsWithOneLineMessageAndWritesNothing) {
  const Case& c = GetParam();
  TempDir dir("bad_" + c.name);
  for (const auto& [name, text] : c.files) writeFile(dir / name, text);
  auto before = readTree(dir.path());
  std::string args = c.args;
  for (size_t p; (p = args.find("{D}")) != std::string::npos;)
    args.replace(p, 3, dir.path().string());
  if (args.find("--out") == std::string::npos) args += " --out " + (dir / "out").string();
  // the built-in room unless the case names a layout (errors are found before any apartment)
  if (args.find("--layout") == std::string::npos) args = "--layout builtin:room " + args;
  RunResult r = runInterinet("generate --width 32 --height 24 --spp 1 --no-progress " + args);
  EXPECT_NE(r.exit_code, 0) << c.name;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
  for (const auto& s : c.expect)
    EXPECT_NE(r.err.find(s), std::string::npos) << "'" << s << "' not in: " << r.err;
  EXPECT_EQ(readTree(dir.path()), before) << "the failed run changed files";
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

TEST(BadInputTable, HasAtLeastFifteenCases) {
  EXPECT_GE(cases().size(), 15u);
}

TEST(Cli, HelpExplainsEverySubcommand) {
  RunResult r = runInterinet("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"generate", "render", "layout", "bench"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  RunResult g = runInterinet("generate --help");
  for (const char* s : {"--layout", "--trajectory", "--frames", "--seed", "--threads", "--spp",
                        "--format", "--out", "--passes"})
    EXPECT_NE(g.out.find(s), std::string::npos) << s;
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

TEST(Cli, LayoutImportWritesALoadableLayout) {
  TempDir dir("layout_import");
  const std::string obj = std::string(INET_SOURCE_DIR) + "/tests/data/scene/two_parts.obj";
  const std::string out = (dir / "imported.json").string();
  RunResult r = runInterinet("layout import --scene " + obj + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  RunResult show = runInterinet("layout show --scene " + out);
  ASSERT_EQ(show.exit_code, 0) << show.err;
  RunResult orig = runInterinet("layout show --scene " + obj);
  // the same objects, classes and bounds whether read from the OBJ or from the written layout
  auto tail = [](const std::string& s) { return s.substr(s.find("meshes")); };
  EXPECT_EQ(tail(show.out), tail(orig.out));
  // an --out in a folder that does not exist yet: made, as generate --out makes its folder
  RunResult nested = runInterinet("layout import --scene " + obj + " --out " +
                                  (dir / "new" / "sub" / "x.json").string());
  EXPECT_EQ(nested.exit_code, 0) << nested.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "new" / "sub" / "x.json"));
  // an --out under a file, which cannot be a folder: a one-line error, nothing written
  writeFile(dir / "plain", "a file\n");
  RunResult bad = runInterinet("layout import --scene " + obj + " --out " +
                               (dir / "plain" / "x.json").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--out"), std::string::npos) << bad.err;
  EXPECT_EQ(readTextFile((dir / "plain").string()), "a file\n");
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

TEST(Cli, LayoutGenerateIsDeterministicResumesAndFeedsStats) {
  TempDir dir("layout_generate");
  const std::string a = (dir / "a").string(), b = (dir / "b").string();
  ASSERT_EQ(runInterinet("layout generate --seed 11 --texture-size 64 --out " + a).exit_code, 0);
  ASSERT_EQ(runInterinet("layout generate --seed 11 --texture-size 64 --out " + b).exit_code, 0);
  EXPECT_EQ(readTree(a), readTree(b)) << "same seed, same bytes (layout, light.xml, textures)";
  RunResult show = runInterinet("layout show --layout " + a + "/layout.json");
  EXPECT_EQ(show.exit_code, 0) << show.err;
  // --count: one folder per seed, shared textures; a rerun leaves finished ones alone
  const std::string many = (dir / "many").string();
  ASSERT_EQ(
      runInterinet("layout generate --seed 3 --count 3 --texture-size 64 --out " + many).exit_code,
      0);
  const auto before = readTree(many);
  EXPECT_TRUE(before.count("seed_000004/layout.json"));
  EXPECT_TRUE(before.count("seed_000005/light.xml"));
  std::filesystem::remove(dir / "many" / "seed_000004" / "layout.json");
  ASSERT_EQ(
      runInterinet("layout generate --seed 3 --count 3 --texture-size 64 --out " + many).exit_code,
      0);
  EXPECT_EQ(readTree(many), before) << "the missing one is made again, identical";
  RunResult stats = runInterinet("layout stats " + many + " --out " + (dir / "stats").string());
  EXPECT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("3 layouts"), std::string::npos) << stats.out;
  // bad input: one line naming the flag, nothing written
  for (const char* bad : {"--rooms 17", "--rooms -1", "--texture-size 100", "--count 0"}) {
    const std::string out = (dir / "bad").string();
    RunResult r = runInterinet(std::string("layout generate ") + bad + " --out " + out);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad" / "layout.json")) << bad;
  }
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

TEST(Cli, LayoutExportWritesGltfThatReadsBackTheSame) {
  TempDir dir("layout_export");
  const std::string gltf = (dir / "room.gltf").string(), glb = (dir / "room.glb").string();
  RunResult r = runInterinet("layout export --out " + gltf);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("nodes"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "room.bin"));
  ASSERT_EQ(runInterinet("layout export --format glb --out " + glb).exit_code, 0);
  // the same classes per instance and the same bounds as the built-in room itself
  auto from = [](const std::string& s, const char* key) { return s.substr(s.find(key)); };
  const RunResult orig = runInterinet("layout show");
  for (const std::string& f : {gltf, glb}) {
    const RunResult back = runInterinet("layout show --scene " + f);
    ASSERT_EQ(back.exit_code, 0) << back.err;
    EXPECT_EQ(from(back.out, "bounds"), from(orig.out, "bounds")) << f;
  }
  // a .gltf name with --format glb: one line naming the flag, nothing written
  const auto before = readTree(dir.path());
  RunResult bad = runInterinet("layout export --format glb --out " + (dir / "x.gltf").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("--out"), std::string::npos) << bad.err;
  EXPECT_EQ(readTree(dir.path()), before);
}

// A layout with daylight: its sky is baked into <stem>_sky.exr beside the file, named in the
// scene's extras.
TEST(Cli, LayoutExportBakesTheSky) {
  TempDir dir("layout_export_sky");
  ASSERT_EQ(runInterinet("layout generate --seed 1 --rooms 1 --texture-size 64 --out " +
                         (dir / "apt").string())
                .exit_code,
            0);
  const RunResult r =
      runInterinet("layout export " + (dir / "apt" / "layout.json").string() + " --sky-width 64 "
                   "--out " + (dir / "a.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("the sky baked into a_sky.exr"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "a_sky.exr"));
  const std::string glb = readTextFile((dir / "a.glb").string());
  EXPECT_NE(glb.find("\"sky_image\":\"a_sky.exr\""), std::string::npos);
}

}  // namespace
}  // namespace inet::test
