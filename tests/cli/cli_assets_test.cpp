// `interiornet assets`: bad catalog folders fail with one line naming the file; on the installed
// Sweet Home 3D catalogs (skipped without them) `list` and `sheet` give what they promise.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <set>

#include "cli_util.h"
#include "core/atomic_file.h"
#include "core/image_io.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

int lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(CliAssets, BadCatalogFoldersGiveOneLineErrors) {
  TempDir dir("assets_bad");
  RunResult r = runInterinet("assets list --catalog " + (dir / "nowhere").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
  fs::create_directories(dir / "empty");
  r = runInterinet("assets list --catalog " + (dir / "empty").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no .sh3f"), std::string::npos) << r.err;
  writeFile(dir / "cat" / "broken.sh3f", "not a zip archive");
  r = runInterinet("assets list --catalog " + (dir / "cat").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("broken.sh3f"), std::string::npos) << r.err;
  r = runInterinet("assets sheet --catalog " + (dir / "cat").string() + " --size 4 --out " +
                   (dir / "s.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "s.png"));
}

TEST(CliAssets, ListAndSheetOnTheInstalledCatalogs) {
  if (!fs::is_directory("/usr/share/sweethome3d/furniture"))
    GTEST_SKIP() << "sweethome3d-furniture is not installed (bash scripts/setup.sh)";
  TempDir dir("assets");
  RunResult r = runInterinet("assets list --json --match \"futon couch\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["furniture_category"], "sofa");
  EXPECT_EQ(j[0]["nyu40"], 6);
  EXPECT_EQ(j[0]["creator"], "Kator Legaz");
  EXPECT_NE(j[0]["license"].get<std::string>().find("Creative Commons"), std::string::npos);
  r = runInterinet("assets list --category Lights");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("lamp"), std::string::npos);
  const fs::path png = dir / "sheet.png";
  r = runInterinet("assets sheet --match \"futon\" --size 48 --spp 2 --columns 2 --out " +
                   png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageU8 im = readPng8(png);
  EXPECT_EQ(im.width, 2 * (48 + 4) + 4);  // "Futon" and "Futon couch": one row of two
  // the model is darker than the white margin somewhere: something was rendered
  int dark = 0;
  for (int y = 4; y < 52; ++y)
    for (int x = 4; x < 52; ++x) dark += im.at(x, y, 0) < 150;
  EXPECT_GT(dark, 20);
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

// generate without --layout shows the catalog-furnished apartment (builtin:apartment), and
// --contact-sheet gathers a few of its frames; builtin:room stays the old furnished room.
TEST(CliAssets, GenerateDefaultsToTheCatalogApartment) {
  if (!fs::is_directory("/usr/share/sweethome3d/furniture"))
    GTEST_SKIP() << "sweethome3d-furniture is not installed (bash scripts/setup.sh)";
  TempDir dir("gen_default");
  const RunResult r = runInterinet(
      "generate --trajectory look-forward --frames 4 --fps 2 --width 96 --height 72 --fx 75 "
      "--fy 75 --spp 2 --imu 0 --passes rgb,depth,label --no-progress --out " +
      (dir / "out").string() + " --contact-sheet " + (dir / "sheet.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path seq = dir / "out" / "apartment" / "seq_000";
  const auto meta = nlohmann::json::parse(readTextFile(seq / "meta.json"));
  EXPECT_NE(meta["layout"]["source"].get<std::string>().find("built-in apartment"),
            std::string::npos);
  // furniture in view: some class beyond wall, floor, ceiling, door, window
  std::set<int> classes;
  for (const auto& e : fs::directory_iterator(seq / "label0" / "data"))
    if (e.path().string().find("_nyu.png") != std::string::npos)
      for (uint8_t v : readPng8(e.path()).data) classes.insert(v);
  EXPECT_TRUE(std::any_of(classes.begin(), classes.end(), [](int c) {
    return c != 0 && c != 1 && c != 2 && c != 8 && c != 9 && c != 22;
  })) << classes.size() << " classes";
  const ImageU8 sheet = readPng8(dir / "sheet.png");
  EXPECT_GE(sheet.width, 3 * 48);  // 4 frames at half size, three to a row
  EXPECT_GE(sheet.height, 2 * 36);
  // the old default, by name
  const RunResult room = runInterinet(
      "generate --layout builtin:room --frames 2 --width 32 --height 24 --fx 30 --fy 30 --spp 1 "
      "--imu 0 --no-progress --out " + (dir / "room").string());
  ASSERT_EQ(room.exit_code, 0) << room.err;
  EXPECT_TRUE(fs::exists(dir / "room" / "default_room" / "seq_000"));
}

}  // namespace
}  // namespace inet::test
