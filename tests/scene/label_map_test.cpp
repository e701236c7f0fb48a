// Label map CSV parsing and object-name matching.
#include "scene/label_map.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/nyu40.h"
#include "scene_test_util.h"

namespace inet {
namespace {

int id(const char* name) {
  return *nyu40FromName(name);
}

/// Message of the InputError thrown while parsing `csv`, or "" when it parsed.
std::string parseError(const std::string& csv) {
  try {
    LabelMap::parse(csv, "labels.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

TEST(LabelMap, ParsesHeaderCommentsIdsAndNames) {
  LabelMap map = LabelMap::parse(
      "# object name -> NYU40\n"
      "name,nyu40\n"
      "\n"
      "  Painting , picture   # trailing comment\n"
      "nightstand,32\r\n"
      "dining chair,Chair\n"
      "tv_unit,otherfurniture\n",
      "labels.csv");
  ASSERT_EQ(map.size(), 4u);
  EXPECT_EQ(map.entries()[0].key, "painting");
  EXPECT_EQ(map.entries()[0].nyu40, id("picture"));
  EXPECT_EQ(map.entries()[0].line, 4);
  EXPECT_EQ(map.entries()[1].nyu40, 32);
  EXPECT_EQ(map.entries()[2].key, "dining chair");
  EXPECT_EQ(map.entries()[3].nyu40, id("otherfurniture"));
}

TEST(LabelMap, HeaderIsOptional) {
  LabelMap map = LabelMap::parse("sofa_bed,bed\n", "x.csv");
  ASSERT_EQ(map.size(), 1u);
  EXPECT_EQ(map.lookup("sofa_bed"), id("bed"));
}

TEST(LabelMap, ExactMatchIgnoresCaseAndSeparators) {
  LabelMap map = LabelMap::parse("painting,picture\nnight stand,night_stand\n", "m.csv");
  EXPECT_EQ(map.lookup("painting"), id("picture"));
  EXPECT_EQ(map.lookup("PAINTING"), id("picture"));
  EXPECT_EQ(map.lookup("Night_Stand"), 32);
}

TEST(LabelMap, PrefixAndTokenMatches) {
  LabelMap map = LabelMap::parse("chair,chair\npainting,picture\nspeaker,otherprop\n", "m.csv");
  EXPECT_EQ(map.lookup("chair_01"), id("chair"));
  EXPECT_EQ(map.lookup("Chair.003"), id("chair"));
  EXPECT_EQ(map.lookup("chairs"), id("chair"));                // prefix
  EXPECT_EQ(map.lookup("painting.002"), id("picture"));        // SceneNet style
  EXPECT_EQ(map.lookup("top_painting_inner"), id("picture"));  // whole token
  EXPECT_EQ(map.lookup("left-speaker-2"), id("otherprop"));
  // a whole token in the plural matches too; a longer word containing the key does not
  EXPECT_EQ(map.lookup("big_speakers"), id("otherprop"));
  EXPECT_EQ(map.lookup("big_speakerbox"), std::nullopt);
  // built-in names and aliases: plural walls, camelCase, dataset names
  const LabelMap none;
  EXPECT_EQ(none.lookup("room_walls"), id("wall"));
  EXPECT_EQ(none.lookup("backWall"), id("wall"));
  EXPECT_EQ(none.lookup("painting.004"), id("picture"));
  EXPECT_EQ(none.lookup("Couch_2"), id("sofa"));
  EXPECT_EQ(none.lookup("curtains"), id("curtain"));
}

TEST(LabelMap, LongestKeyWins) {
  LabelMap map = LabelMap::parse("table,table\ntable_lamp,lamp\nlamp,lamp\n", "m.csv");
  EXPECT_EQ(map.lookup("table_lamp_right"), id("lamp"));  // "tablelamp" beats "table"
  EXPECT_EQ(map.lookup("coffee_table"), id("table"));
  EXPECT_EQ(map.matchedKey("table_lamp_right"), "table_lamp");
}

TEST(LabelMap, Nyu40NamesMatchWithoutAMap) {
  LabelMap empty;
  EXPECT_EQ(empty.lookup("bed_2"), id("bed"));
  EXPECT_EQ(empty.lookup("Wall.034"), id("wall"));
  EXPECT_EQ(empty.lookup("Walls"), id("wall"));
  EXPECT_EQ(empty.lookup("nightstand_left"), id("night_stand"));
  EXPECT_EQ(empty.lookup("floor_mat_1"), id("floor_mat"));  // longer than "floor"
  EXPECT_EQ(empty.lookup("fridge"), id("refridgerator"));
  EXPECT_EQ(empty.lookup("spaceship"), std::nullopt);
  EXPECT_EQ(empty.matchedKey("spaceship"), "");
}

TEST(LabelMap, MapEntriesTakePrecedenceOverNyu40Names) {
  // Without the map "ceiling_light" would be a ceiling (NYU40 name prefix).
  LabelMap map = LabelMap::parse("ceiling_light,lamp\nlight,lamp\n", "m.csv");
  EXPECT_EQ(LabelMap().lookup("ceiling_light"), id("ceiling"));
  EXPECT_EQ(map.lookup("ceiling_light"), id("lamp"));
  EXPECT_EQ(map.lookup("wall_light.002"), id("lamp"));  // token "light" from the map wins
  EXPECT_EQ(map.lookup("wall.002"), id("wall"));        // falls back to NYU40 names
}

TEST(LabelMap, BadLinesNameFileAndLine) {
  std::string e = parseError("name,nyu40\nchair,chair\nsofa,sofa,extra\n");
  EXPECT_NE(e.find("labels.csv: line 3:"), std::string::npos) << e;
  EXPECT_NE(e.find("name,nyu40"), std::string::npos) << e;

  e = parseError("chair\n");
  EXPECT_NE(e.find("labels.csv: line 1:"), std::string::npos) << e;

  e = parseError("# c\nchair,spaceship\n");
  EXPECT_NE(e.find("line 2"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown NYU40 class 'spaceship'"), std::string::npos) << e;
  EXPECT_NE(e.find("otherprop"), std::string::npos) << "valid names listed: " << e;

  e = parseError("chair,41\n");
  EXPECT_NE(e.find("line 1"), std::string::npos) << e;
  EXPECT_NE(e.find("0..40"), std::string::npos) << e;

  e = parseError("chair,-3\n");
  EXPECT_NE(e.find("line 1"), std::string::npos) << e;

  e = parseError(",chair\n");
  EXPECT_NE(e.find("line 1: empty object name"), std::string::npos) << e;

  e = parseError("chair,chair\nsofa,sofa\nChair,table\n");
  EXPECT_NE(e.find("line 3"), std::string::npos) << e;
  EXPECT_NE(e.find("already mapped to chair on line 1"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";

  EXPECT_EQ(parseError("chair,chair\nCHAIR,5\n"), "") << "same class twice is harmless";
}

TEST(LabelMap, LoadReadsAFileAndReportsMissingOnes) {
  test::TempDir dir;
  std::string path = dir.write("labels.csv", "painting,picture\n");
  EXPECT_EQ(LabelMap::load(path).lookup("painting.001"), id("picture"));
  try {
    LabelMap::load((dir.path() / "missing.csv").string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace inet
