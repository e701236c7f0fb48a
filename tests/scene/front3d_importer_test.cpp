// 3D-FRONT import: the shared house imports with its rooms, architecture labels and furniture
// placeholders (no 3D-FUTURE models here), and renders with labels; malformed files name the
// JSON field.
#include "scene/front3d_importer.h"

#include <gtest/gtest.h>

#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "scene/layout_json.h"
#include "scene/nyu40.h"
#include "scene_test_util.h"

namespace inet {
namespace {

using test::TempDir;

std::string house() {
  return (test::sharedDir() / "data" / "scenes" / "3d_front" /
          "0a8d471a-2587-458a-9214-586e003e9cf9.json")
      .string();
}

TEST(Front3d, SharedHouseImportsWithRoomsLabelsAndPlaceholders) {
  if (!std::filesystem::exists(house()))
    GTEST_SKIP() << "needs ../shared/data/scenes/3d_front (absent)";
  Front3dReport report;
  Scene s = importFront3d(house(), {}, &report);
  EXPECT_EQ(s.rooms.size(), 8u) << "the README's 8 rooms, each with a floor";
  std::set<std::string> types;
  for (const Room& r : s.rooms) types.insert(r.type);
  for (const char* t : {"living_room", "master_bedroom", "study", "kitchen", "master_bathroom"})
    EXPECT_TRUE(types.count(t)) << t;
  std::map<int, int> per_class;
  for (const Object& o : s.objects) ++per_class[o.nyu40];
  EXPECT_GT(per_class[1], 100) << "walls";
  EXPECT_EQ(per_class[2], 8) << "one floor per room";
  EXPECT_GT(per_class[8], 0) << "doors";
  EXPECT_GT(per_class[9], 0) << "windows";
  EXPECT_GT(per_class[*nyu40FromName("bed")], 0);
  EXPECT_GT(per_class[*nyu40FromName("chair")], 0);
  EXPECT_EQ(report.placeholders, 20u) << "every furniture piece with a size, as a box";
  EXPECT_NE(report.summary().find("labelled boxes"), std::string::npos) << "says so";
  // Z up, metres: the floor at 0 and ceilings at 2.8 (README: y in 0..2.8 in the file)
  auto [lo, hi] = s.bounds();
  EXPECT_NEAR(lo.z(), 0.0, 1e-3);
  EXPECT_NEAR(hi.z(), 2.8, 0.05);
  for (const Room& r : s.rooms) {
    EXPECT_NEAR(r.floor_z, 0.0, 1e-3);
    EXPECT_GT(r.area(), 1.0);
  }
  // placeholders lie between floor and ceiling (the box's height is its y axis in the
  // 3D-FUTURE frame, world z after the axis change); most stand on the floor
  int on_floor = 0, boxes = 0;
  for (const Object& o : s.objects) {
    if (o.part != "placeholder_box") continue;
    ++boxes;
    const double half = o.T_world_object.block<3, 3>(0, 0).col(1).norm() / 2;
    const double z = o.T_world_object(2, 3);
    EXPECT_GE(z - half, -0.01) << o.name;
    EXPECT_LE(z + half, 2.81) << o.name;
    on_floor += std::fabs(z - half) < 0.01;
  }
  EXPECT_GT(on_floor, boxes / 2);
  // and the result is a layout like any other
  TempDir dir;
  const std::string out = (dir.path() / "house.json").string();
  saveLayout(s, out);
  EXPECT_EQ(loadLayout(out).objects.size(), s.objects.size());
}

// With a 3D-FUTURE model folder, each piece's raw_model.obj replaces its box. Models made here
// as boxes of each piece's bbox (y up, origin at the bottom centre, as 3D-FUTURE's) must land
// exactly where the placeholder boxes do.
TEST(Front3d, FutureModelsReplaceThePlaceholdersInPlace) {
  if (!std::filesystem::exists(house()))
    GTEST_SKIP() << "needs ../shared/data/scenes/3d_front (absent)";
  TempDir dir;
  const auto models = dir.path() / "3D-FUTURE-model";
  Front3dReport boxes_report;
  const Scene boxes = importFront3d(house(), {}, &boxes_report);
  // write one model per placeholder's jid, from the house file's own bbox
  const nlohmann::json j = nlohmann::json::parse(readTextFile(house()));
  int written = 0;
  for (const auto& f : j["furniture"]) {
    if (!f.contains("jid") || !f.contains("bbox") || f["bbox"].empty()) continue;
    const auto& b = f["bbox"][0].is_array() ? f["bbox"][0] : f["bbox"];
    const double x = b[0].get<double>() / 2, y = b[1].get<double>(), z = b[2].get<double>() / 2;
    std::string obj;
    for (int c = 0; c < 8; ++c)
      obj += fmt::format("v {} {} {}\n", c & 1 ? x : -x, c & 2 ? y : 0.0, c & 4 ? z : -z);
    obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    const auto folder = models / f["jid"].get<std::string>();
    std::filesystem::create_directories(folder);
    writeTextAtomic(folder / "raw_model.obj", obj);
    ++written;
  }
  ASSERT_GT(written, 10);
  Front3dOptions opt;
  opt.models_dir = models.string();
  Front3dReport report;
  const Scene real = importFront3d(house(), opt, &report);
  EXPECT_EQ(report.placeholders, 0u) << "every piece found its model";
  EXPECT_EQ(report.furniture, boxes_report.furniture);
  // the same pieces in the same order: world bounds agree to 1e-5 m
  auto worldBox = [](const Scene& s, const Object& o) {
    Eigen::AlignedBox3d box;
    for (const Vec3f& p : s.meshes[o.mesh].positions)
      box.extend((o.T_world_object * Eigen::Vector4d(p.x(), p.y(), p.z(), 1)).head<3>());
    return box;
  };
  std::vector<const Object*> a, b;
  for (const Object& o : boxes.objects)
    if (o.part == "placeholder_box") a.push_back(&o);
  for (const Object& o : real.objects)
    if (o.mesh >= 0 && real.meshes[o.mesh].id.rfind("model_", 0) == 0) b.push_back(&o);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 20u);
  for (size_t i = 0; i < a.size(); ++i) {
    const auto ba = worldBox(boxes, *a[i]), bb = worldBox(real, *b[i]);
    EXPECT_LT((ba.min() - bb.min()).norm(), 1e-5) << a[i]->name;
    EXPECT_LT((ba.max() - bb.max()).norm(), 1e-5) << a[i]->name;
    EXPECT_EQ(a[i]->nyu40, b[i]->nyu40);
  }
}

TEST(Front3d, MalformedFilesNameTheField) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "malformed JSON"},
      {"[1, 2]", "scene"},
      {R"({"scene": {"room": []}, "mesh": [{"uid": "a", "xyz": [0, 0], "faces": [0, 1, 2]}]})",
       "mesh[0].xyz"},
      {R"({"scene": {"room": []}, "mesh": [{"uid": "a", "xyz": [0,0,0, 1,0,0, 0,1,0], "faces": [0, 1, 7]}]})",
       "mesh[0].faces[2]"},
      {R"({"scene": {"room": []}, "mesh": [{"uid": "a", "xyz": [0,0,0, "x",0,0, 0,1,0], "faces": [0, 1, 2]}]})",
       "mesh[0].xyz[3]"},
      {R"({"scene": {"room": [{"type": "Kitchen", "children": [{"ref": "a", "pos": [0, 0]}]}]},
           "mesh": [{"uid": "a", "xyz": [0,0,0, 1,0,0, 0,0,1], "faces": [0, 1, 2]}]})",
       "scene.room[0].children[0].pos"},
      {R"({"scene": {"room": []}})", "no geometry"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    const std::string path = dir.write("bad" + std::to_string(i) + ".json", cases[i].first);
    const std::string msg = test::errorOf([&] { (void)importFront3d(path, {}); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(cases[i].second), std::string::npos) << msg;
  }
  // numbers written as strings are accepted (a 3D-FRONT quirk)
  const std::string ok =
      dir.write("strings.json",
                R"({"scene": {"room": [{"type": "Bedroom", "children": [{"ref": "f"}]}]},
          "mesh": [{"uid": "f", "type": "Floor", "xyz": ["0","0","0", "2","0","0", "2","0","-2", "0","0","-2"],
                    "faces": [0, 1, 2, 0, 2, 3]}]})");
  Scene s = importFront3d(ok, {});
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_EQ(s.rooms[0].type, "second_bedroom");
  EXPECT_NEAR(s.rooms[0].area(), 4.0, 1e-9);
}

}  // namespace
}  // namespace inet
