// interiornet vary lighting | rearrange on a generated apartment: outputs that load back, the
// same seed gives the same bytes, bad input names its flag and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "assets/catalog_library.h"
#include "cli_util.h"
#include "core/atomic_file.h"
#include "scene/layout_json.h"
#include "scene/light_xml.h"

namespace inet::test {
namespace {

namespace fs = std::filesystem;

TEST(CliVary, LightingAndRearrangementOfAGeneratedApartment) {
  // layouts furnished from the Sweet Home 3D catalogs (the default where they are installed)
  // name catalog models: a program loading them installs the resolver, as interiornet does
  installCatalogResolver();
  TempDir dir("cli_vary");
  ASSERT_EQ(runInterinet("layout generate --seed 3 --out " + (dir / "apt").string()).exit_code, 0);
  const std::string layout = (dir / "apt" / "layout.json").string();
  // lighting: a night configuration has the lamps on and the sun off
  RunResult night = runInterinet("vary lighting --layout " + layout +
                                 " --mode time-of-day --time 23:00 --out " +
                                 (dir / "night.xml").string());
  ASSERT_EQ(night.exit_code, 0) << night.err;
  const LightSetup dark = loadLightXml((dir / "night.xml").string());
  int lamps_on = 0;
  for (const Light& l : dark.lights) {
    if (l.type == LightType::Sun) {
      EXPECT_FALSE(l.on);
    }
    if (l.type == LightType::Point || l.type == LightType::Spot) lamps_on += l.on;
  }
  EXPECT_GT(lamps_on, 0);
  // random: same seed, same bytes
  const std::string random = "vary lighting --layout " + layout + " --mode random --seed 5 --out ";
  ASSERT_EQ(runInterinet(random + (dir / "r1.xml").string()).exit_code, 0);
  ASSERT_EQ(runInterinet(random + (dir / "r2.xml").string()).exit_code, 0);
  EXPECT_EQ(readTextFile(dir / "r1.xml"), readTextFile(dir / "r2.xml"));
  // rearrangement: a layout that loads, a log within the ranges, the same bytes twice
  const std::string re = "vary rearrange --layout " + layout + " --seed 2 --out ";
  const RunResult r = runInterinet(re + (dir / "re1").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(runInterinet(re + (dir / "re2").string()).exit_code, 0);
  EXPECT_EQ(readTree(dir / "re1"), readTree(dir / "re2"));
  const Scene moved = loadLayout((dir / "re1" / "layout.json").string());
  const Scene original = loadLayout(layout);
  ASSERT_EQ(moved.objects.size(), original.objects.size());
  const auto log = nlohmann::json::parse(readTextFile(dir / "re1" / "rearrange_log.json"));
  EXPECT_GE(log["share"].get<double>(), 0.05 - 1e-9);
  EXPECT_LE(log["share"].get<double>(), 0.45 + 1e-9);
  int changed = 0;
  for (size_t i = 0; i < moved.objects.size(); ++i)
    changed += !moved.objects[i].T_world_object.isApprox(original.objects[i].T_world_object, 0);
  EXPECT_GT(changed, 0) << "something moved";
  // bad input: the flag named, nothing written
  for (auto [args, flag] : std::vector<std::pair<std::string, std::string>>{
           {"vary lighting --layout " + layout + " --mode dusk", "--mode"},
           {"vary lighting --layout " + layout + " --mode time-of-day --date 2026-13-01", "--date"},
           {"vary rearrange --layout " + layout + " --min-share 0.9", "--max-share"},
           {"vary rearrange --layout " + layout + " --min-share -0.1", "--min-share"},
           {"vary rearrange --layout " + layout + " --max-accel -1", "--max-accel"}}) {
    const RunResult bad = runInterinet(args + " --out " + (dir / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << args;
    EXPECT_NE(bad.err.find(flag), std::string::npos) << args << ": " << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad")) << args;
  }
}

TEST(CliVary, ThreeWaySequenceIsOneCommand) {
  // the paper's SLAM-under-change experiment: one layout, one camera path, three scenes
  TempDir dir("cli_threeway");
  ASSERT_EQ(runInterinet("layout generate --seed 5 --out " + (dir / "apt").string()).exit_code, 0);
  const RunResult r = runInterinet(
      "generate --layout " + (dir / "apt" / "layout.json").string() +
      " --trajectory hand-held --seed 7 --frames 2 --width 48 --height 36 --spp 2 "
      "--passes rgb,depth,instance,boxes --config original,lighting:2,rearranged:3 "
      "--no-progress --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path root = dir / "out" / "apartment_5";
  const fs::path o = root / "seq_000", l = root / "seq_000_lighting_2",
                 m = root / "seq_000_rearranged_3";
  for (const fs::path& p : {o, l, m}) ASSERT_TRUE(fs::exists(p / "meta.json")) << p;
  // one camera path through all three (the EuRoC ground truth names no sequence)
  const fs::path gt = "state_groundtruth_estimate0/data.csv";
  EXPECT_EQ(readTextFile(o / gt), readTextFile(l / gt));
  EXPECT_EQ(readTextFile(o / gt), readTextFile(m / gt));
  // relit: the same geometry (depth bytes), other colours
  EXPECT_EQ(readTree(o / "depth0"), readTree(l / "depth0"));
  EXPECT_NE(readTree(o / "cam0"), readTree(l / "cam0"));
  // rearranged: objects moved (their boxes), the building did not
  EXPECT_NE(readTextFile(o / "boxes.json"), readTextFile(m / "boxes.json"));
  const auto meta = nlohmann::json::parse(readTextFile(m / "meta.json"));
  EXPECT_EQ(meta["configuration"], "rearranged:3");
  // a bad configuration names the flag and writes nothing
  const RunResult bad = runInterinet("generate --config lighting:x --out " + (dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--config"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

}  // namespace
}  // namespace inet::test
