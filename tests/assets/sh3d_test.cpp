// Sweet Home 3D homes (.sh3d): Home.xml parsing and its errors, the conversion to a Scene
// (walls with mitred joins, round and sloped walls, door and window cut-outs, rooms, furniture
// placed, mirrored and turned), on homes written here and on the 17 real homes and the refused
// files of ../shared/data/homes (skipped when absent).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "../expect_input_error.h"
#include "../scene/scene_test_util.h"
#include "../segment_hits.h"
#include "../temp_dir.h"
#include "assets/polygon_mesh.h"
#include "assets/sh3d_home.h"
#include "assets/sh3d_import.h"
#include "zip_fixture.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;
using test::segmentHits;
using test::TempDir;
using V2 = Eigen::Vector2d;

fs::path homesDir() {
  return test::sharedDir() / "data" / "homes";
}

#define SKIP_WITHOUT_HOMES() \
  if (!fs::is_directory(homesDir())) GTEST_SKIP() << "needs ../shared/data/homes (absent)"

std::string home(const std::string& body, const std::string& attrs = "") {
  return "<?xml version='1.0'?>\n<home version='6500' name='t.sh3d' wallHeight='250.0'" + attrs +
         ">\n" + body + "\n</home>\n";
}

/// The world box of the objects of one instance.
Eigen::AlignedBox3d instanceBox(const Scene& s, int instance) {
  Eigen::AlignedBox3d box;
  for (const Object& o : s.objects) {
    if (o.instance != instance) continue;
    for (const auto& p : s.meshes[size_t(o.mesh)].positions)
      box.extend((o.T_world_object * p.cast<double>().homogeneous()).head<3>());
  }
  return box;
}


// ---- parsing ------------------------------------------------------------------------------

TEST(Sh3dHome, ParsesLevelsWallsRoomsPiecesAndCameras) {
  const Sh3dHome h = parseHomeXml(
      home("<level id='L0' name='Ground' elevation='0' floorThickness='12' height='260' "
           "elevationIndex='0'/>\n"
           "<level id='L1' name='Up' elevation='272' floorThickness='12' height='250' "
           "elevationIndex='0' visible='false'/>\n"
           "<wall id='w0' level='L0' wallAtEnd='w1' xStart='0' yStart='0' xEnd='400' yEnd='0' "
           "height='260' thickness='20' leftSideColor='FFFF0000'/>\n"
           "<wall id='w1' level='L0' wallAtStart='w0' xStart='400' yStart='0' xEnd='400' "
           "yEnd='300' height='260' heightAtEnd='300' thickness='20' arcExtent='0.5'/>\n"
           "<room id='r' level='L0' name='Cuisine' floorColor='FF808080' ceilingVisible='false'>"
           "<point x='0' y='0'/><point x='400' y='0'/><point x='400' y='300'/></room>\n"
           "<furnitureGroup id='g' name='G' x='0' y='0' width='1' depth='1' height='1' "
           "level='L0'><pieceOfFurniture id='p' level='L0' name='Chair' model='1' x='10' y='20' "
           "elevation='5' angle='1.5' width='40' depth='50' height='90' modelMirrored='true'>"
           "<material name='seat' color='FF00FF00' shininess='0.5'/></pieceOfFurniture>"
           "</furnitureGroup>\n"
           "<light id='l' level='L0' name='Lamp' model='2' x='1' y='2' width='10' depth='10' "
           "height='10' power='0.25'><lightSource x='0.5' y='0.5' z='0.9' color='FFFFEECC' "
           "diameter='0.2'/></light>\n"
           "<doorOrWindow id='d' level='L0' name='Door' model='3' x='200' y='0' width='90' "
           "depth='20' height='210' cutOutShape='M0,0 v1 h1 v-1 z'><sash xAxis='0.1' yAxis='0.5' "
           "width='0.8' startAngle='0' endAngle='1.57'/></doorOrWindow>\n"
           "<observerCamera attribute='observerCamera' lens='PINHOLE' x='100' y='100' z='170' "
           "yaw='0' pitch='0.1' fieldOfView='1.1' time='1491480000000'/>\n"
           "<observerCamera attribute='storedCamera' name='Kitchen view' lens='PINHOLE' x='1' "
           "y='2' z='150' yaw='1' pitch='0' fieldOfView='1.0'/>\n"
           "<compass x='0' y='0' diameter='100' northDirection='0.5' longitude='0.04' "
           "latitude='0.85' timeZone='Europe/Paris'/>"),
      "t.sh3d");
  ASSERT_EQ(h.levels.size(), 2u);
  EXPECT_FALSE(h.levels[1].visible);
  ASSERT_EQ(h.walls.size(), 2u);
  EXPECT_EQ(h.walls[0].wall_at_end, 1);
  EXPECT_EQ(h.walls[1].wall_at_start, 0);
  EXPECT_NEAR(h.walls[1].arc_extent, 0.5, 1e-12);
  EXPECT_NEAR(*h.walls[1].height_at_end_cm, 300, 1e-12);
  EXPECT_NEAR(h.walls[0].left_color->x(), 1.0, 1e-6);
  ASSERT_EQ(h.rooms.size(), 1u);
  EXPECT_FALSE(h.rooms[0].ceiling_visible);
  EXPECT_EQ(h.rooms[0].points.size(), 3u);
  ASSERT_EQ(h.pieces.size(), 3u);
  EXPECT_EQ(h.pieces[0].group, "G");
  EXPECT_TRUE(h.pieces[0].mirrored);
  EXPECT_NEAR(h.pieces[0].angle, 1.5, 1e-12);
  ASSERT_EQ(h.pieces[0].materials.size(), 1u);
  EXPECT_EQ(h.pieces[0].materials[0].name, "seat");
  EXPECT_EQ(h.pieces[1].kind, Sh3dPieceKind::Light);
  EXPECT_NEAR(h.pieces[1].power, 0.25, 1e-12);
  ASSERT_EQ(h.pieces[1].light_sources.size(), 1u);
  EXPECT_EQ(h.pieces[2].kind, Sh3dPieceKind::DoorOrWindow);
  ASSERT_EQ(h.pieces[2].sashes.size(), 1u);
  ASSERT_TRUE(h.observer.has_value());
  EXPECT_EQ(h.observer->time_ms, 1491480000000);
  ASSERT_EQ(h.stored_cameras.size(), 1u);
  EXPECT_EQ(h.stored_cameras[0].name, "Kitchen view");
  EXPECT_NEAR(h.compass.north_direction, 0.5, 1e-12);
}

TEST(Sh3dHome, ErrorsNameTheElementAndAttribute) {
  const std::string room =
      "<room id='r'><point x='0' y='0'/><point x='1' y='0'/>"
      "<point x='1' y='1'/></room>";
  auto fieldOf = [](const std::string& xml) {
    return expectInputError([&] { parseHomeXml(xml, "h.sh3d"); }).field();
  };
  EXPECT_EQ(fieldOf(home("<wall id='w3' xStart='abc' yStart='0' xEnd='1' yEnd='0' "
                         "thickness='10'/>" +
                         room)),
            "Home.xml <wall id='w3'> xStart");
  EXPECT_EQ(fieldOf(home("<wall id='w3' xStart='0' yStart='0' xEnd='1' yEnd='0' "
                         "thickness='-1'/>" +
                         room)),
            "Home.xml <wall id='w3'> thickness");
  EXPECT_EQ(fieldOf(home("<wall id='w3' xStart='0' yStart='0' xEnd='1' yEnd='0' thickness='1' "
                         "wallAtEnd='nope'/>" +
                         room)),
            "Home.xml <wall id='w3'> wallAtEnd");
  EXPECT_EQ(fieldOf(home("<pieceOfFurniture id='p9' name='x' x='0' y='0' width='1' depth='1' "
                         "height='1'/>")),
            "Home.xml <pieceOfFurniture id='p9'> model");
  EXPECT_EQ(fieldOf(home("<pieceOfFurniture id='p9' name='x' model='1' x='0' y='0' width='1' "
                         "depth='1' height='1' color='red'/>")),
            "Home.xml <pieceOfFurniture id='p9'> color");
  EXPECT_EQ(fieldOf(home("<room id='r'><point x='0' y='0'/></room>")),
            "Home.xml <room id='r'> point");
  EXPECT_EQ(fieldOf("<?xml version='1.0'?>\n<home version='6500'>\n<room name='A & B'/></home>"),
            "Home.xml line 3");
  EXPECT_EQ(fieldOf("<home version='6500'><wall"), "Home.xml line 1");
  EXPECT_EQ(fieldOf("<house/>"), "Home.xml");
  // imitations of the format by other tools
  const InputError v = expectInputError([&] {
    parseHomeXml("<home version='7.2'><room><point x='0' y='0'/></room></home>", "h.sh3d");
  });
  EXPECT_EQ(v.field(), "Home.xml <home> version");
  EXPECT_NE(v.problem().find("another tool"), std::string::npos);
  EXPECT_EQ(fieldOf("<home version='7200' unit='CENTIMETER'>" + room + "</home>"),
            "Home.xml <home> unit");
  // walls and nothing else
  EXPECT_EQ(fieldOf(home("<wall id='w' xStart='0' yStart='0' xEnd='1' yEnd='0' thickness='1'/>")),
            "Home.xml");
  // a home with levels names the level of each element
  EXPECT_EQ(fieldOf(home("<level id='L' elevation='0' height='250'/>" + room)),
            "Home.xml <room id='r'> level");
}

// ---- homes written here -------------------------------------------------------------------

/// An OBJ box of 1 x 1 x 1 (Sweet Home 3D's axes: y up) with a post on its left (-x) half,
/// 2 high: an asymmetric model, to see mirroring and turning.
std::string postedBoxObj() {
  std::string obj = "mtllib m.mtl\nusemtl body\n";
  auto box = [&](double x0, double y0, double z0, double x1, double y1, double z1, int base) {
    for (int i = 0; i < 8; ++i)
      obj += fmt::format("v {} {} {}\n", i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
    const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : f)
      obj += fmt::format("f {} {} {} {}\n", base + q[0], base + q[1], base + q[2], base + q[3]);
  };
  box(-0.5, 0, -0.5, 0.5, 1, 0.5, 1);
  obj += "usemtl post\n";
  box(-0.5, 1, -0.5, -0.3, 2, 0.5, 9);
  return obj;
}

std::string mtl() {
  return "newmtl body\nKd 0.5 0.5 0.5\nnewmtl post\nKd 0.2 0.2 0.8\n";
}

/// The world x, y of the post's top centre (the highest vertices) of one instance.
V2 postTop(const Scene& s, int instance) {
  double top = -1e9;
  V2 sum = V2::Zero();
  int n = 0;
  for (const Object& o : s.objects) {
    if (o.instance != instance) continue;
    for (const auto& p : s.meshes[size_t(o.mesh)].positions) {
      const Vec3 w = (o.T_world_object * p.cast<double>().homogeneous()).head<3>();
      if (w.z() > top + 1e-6) top = w.z(), sum.setZero(), n = 0;
      if (std::abs(w.z() - top) < 1e-6) sum += w.head<2>(), ++n;
    }
  }
  return sum / std::max(n, 1);
}

/// The centre of the vertices of one instance's objects whose material id ends in `suffix`.
Vec3 partCentre(const Scene& s, int instance, const std::string& suffix) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const Object& o : s.objects) {
    const std::string& id = s.materials[size_t(o.material)].id;
    if (o.instance != instance || id.size() < suffix.size() ||
        id.compare(id.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    for (const auto& p : s.meshes[size_t(o.mesh)].positions)
      sum += (o.T_world_object * p.cast<double>().homogeneous()).head<3>(), ++n;
  }
  return sum / std::max(n, 1);
}

TEST(Sh3dImport, PiecesArePlacedMirroredAndTurnedAsInThePlan) {
  TempDir dir("sh3d");
  // piece a: as modelled; b: mirrored; c: turned a quarter clockwise on screen; d: raised 80 cm,
  // pitched a quarter (its top towards its back)
  const std::string pieces =
      "<pieceOfFurniture id='a' name='Shelf a' model='0/box.obj' x='100' y='100' width='100' "
      "depth='50' height='200'/>\n"
      "<pieceOfFurniture id='b' name='Shelf b' model='0/box.obj' x='300' y='100' width='100' "
      "depth='50' height='200' modelMirrored='true'/>\n"
      "<pieceOfFurniture id='c' name='Shelf c' model='0/box.obj' x='100' y='300' width='100' "
      "depth='50' height='200' angle='1.5707964'/>\n"
      "<pieceOfFurniture id='d' name='Shelf d' model='0/box.obj' x='300' y='300' width='100' "
      "depth='50' height='200' elevation='80' pitch='1.5707964'/>\n"
      // a mirrored lamp with its bulb on its left, and a light source drawn as lines only
      "<light id='e' name='Lamp e' model='0/box.obj' x='500' y='100' width='100' depth='50' "
      "height='200' modelMirrored='true' power='0.25'><lightSource x='0.2' y='0.5' z='0.9' "
      "color='FFFFFFFF'/></light>\n"
      "<light id='f' name='Light source f' model='1/lines.obj' x='500' y='300' width='20' "
      "depth='20' height='20' elevation='200' power='0.5'><lightSource x='0.5' y='0.5' z='0.5' "
      "color='FFFFFFFF'/></light>\n";
  const std::string room =
      "<room id='r' name='Living room'><point x='0' y='0'/>"
      "<point x='400' y='0'/><point x='400' y='400'/><point x='0' y='400'/>"
      "</room>";
  const fs::path path = dir.path() / "pieces.sh3d";
  test::writeZip(path, {{"Home.xml", home(pieces + room)},
                        {"0/box.obj", postedBoxObj()},
                        {"0/m.mtl", mtl()},
                        {"1/lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2\nl 2 3\n"}});
  Sh3dImportReport report;
  Sh3dImportOptions opt;
  opt.daylight = false;
  opt.room_lights = false;
  const Scene s = importSh3d(path.string(), opt, &report);
  ASSERT_EQ(report.piece_instances.size(), 5u);  // the line-only light has no objects
  EXPECT_EQ(report.pieces, 6u);
  EXPECT_EQ(report.empty_models, 0u);
  // the mirrored lamp's bulb moved to its right (x = 5 + 0.3), dimmed by its power (0.25 of
  // Sweet Home 3D's default 0.5: a quarter of a 2 m lamp's, a floor lamp's, 4.5 W/sr); the
  // line-only light keeps its bulb at its centre
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_NEAR(s.lights[0].position.x(), 5.3, 1e-6);
  EXPECT_NEAR(s.lights[0].position.y(), -1.0, 1e-6);
  EXPECT_NEAR(s.lights[0].position.z(), 1.8, 1e-6);
  EXPECT_NEAR(s.lights[0].intensity, 4.5 / 4, 1e-6);
  EXPECT_TRUE(s.lights[1].position.isApprox(Vec3(5, -3, 2.1), 1e-9));
  std::map<std::string, int> inst;
  const Sh3dHome h = readSh3dHome(path.string());
  for (const auto& [piece, instance] : report.piece_instances) inst[h.pieces[piece].id] = instance;

  // a: centred on (1, -1), 1 x 0.5 x 2, post on its left (-x): Sweet Home 3D's model x is ours
  const auto a = instanceBox(s, inst["a"]);
  EXPECT_TRUE(a.center().head<2>().isApprox(V2(1, -1), 1e-6)) << a.center().transpose();
  EXPECT_TRUE(a.sizes().isApprox(Vec3(1, 0.5, 2), 1e-6)) << a.sizes().transpose();
  EXPECT_NEAR(a.min().z(), 0, 1e-6);
  EXPECT_NEAR(postTop(s, inst["a"]).x(), 1 - 0.4, 1e-6);
  // b: mirrored: the post on the right
  EXPECT_NEAR(postTop(s, inst["b"]).x(), 3 + 0.4, 1e-6);
  // c: a quarter clockwise on screen is clockwise seen from above: the left (-x) turns to +y
  const auto c = instanceBox(s, inst["c"]);
  EXPECT_TRUE(c.sizes().isApprox(Vec3(0.5, 1, 2), 1e-6)) << c.sizes().transpose();
  const V2 pc = postTop(s, inst["c"]);
  EXPECT_NEAR(pc.x(), 1, 1e-6);
  EXPECT_NEAR(pc.y(), -3 + 0.4, 1e-6);
  // d: pitched: lies on its back, 2 m deep, 0.5 m high, bottom at 0.8 m, still centred
  const auto d = instanceBox(s, inst["d"]);
  EXPECT_TRUE(d.sizes().isApprox(Vec3(1, 2, 0.5), 1e-6)) << d.sizes().transpose();
  EXPECT_NEAR(d.min().z(), 0.8, 1e-6);
  EXPECT_TRUE(d.center().head<2>().isApprox(V2(3, -3), 1e-6)) << d.center().transpose();
  // its top (where the post is) went to its back (+y in ours, the plan's up)
  EXPECT_NEAR(partCentre(s, inst["d"], "/post").y(), -3 + 0.5, 1e-6);
  EXPECT_LT(partCentre(s, inst["a"], "/post").z(), 2.0);
  EXPECT_GT(partCentre(s, inst["a"], "/post").z(), 1.0);
  // the room is typed and the pieces are in it
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_EQ(s.rooms[0].type, "living_room");
  for (const Object& o : s.objects)
    if (o.instance == inst["a"]) {
      EXPECT_EQ(o.room, 0);
    }
}

TEST(Sh3dImport, RoundAndSlopedWallsAndMitredCorners) {
  // a round room: four quarter arcs of radius 2 m around (3, 3) in the plan, the first two
  // sloped from 2.5 to 3.5 m and back; and a square room of four straight walls joined at
  // their ends
  std::string walls;
  const double cx = 300, cy = 300, r = 200;
  const V2 pts[4] = {{cx - r, cy}, {cx, cy - r}, {cx + r, cy}, {cx, cy + r}};
  for (int i = 0; i < 4; ++i) {
    const V2 a = pts[i], b = pts[(i + 1) % 4];
    const std::string slope = i == 0   ? " height='250' heightAtEnd='350'"
                              : i == 1 ? " height='350' heightAtEnd='250'"
                                       : " height='250'";
    walls += fmt::format(
        "<wall id='a{}' wallAtStart='a{}' wallAtEnd='a{}' xStart='{}' yStart='{}' xEnd='{}' "
        "yEnd='{}'{} thickness='20' arcExtent='1.5707964' leftSideColor='FFFF0000' "
        "rightSideColor='FF00FF00'/>\n",
        i, (i + 3) % 4, (i + 1) % 4, a.x(), a.y(), b.x(), b.y(), slope);
  }
  const V2 sq[4] = {{600, 100}, {900, 100}, {900, 400}, {600, 400}};
  for (int i = 0; i < 4; ++i)
    walls += fmt::format(
        "<wall id='s{}' wallAtStart='s{}' wallAtEnd='s{}' xStart='{}' yStart='{}' xEnd='{}' "
        "yEnd='{}' height='250' thickness='20'/>\n",
        i, (i + 3) % 4, (i + 1) % 4, sq[i].x(), sq[i].y(), sq[(i + 1) % 4].x(),
        sq[(i + 1) % 4].y());
  const std::string rooms =
      "<room id='sq' name='Bedroom'><point x='610' y='110'/><point x='890' y='110'/>"
      "<point x='890' y='390'/><point x='610' y='390'/></room>";
  Sh3dImportOptions opt;
  opt.daylight = false;
  Sh3dImportReport report;
  // no furniture: the home needs no archive
  const Scene s = sh3dToScene(parseHomeXml(home(walls + rooms), "t.sh3d"), opt, &report);
  EXPECT_EQ(report.walls, 8u);
  // the square is a room; the round walls make none (rooms come from walls only on levels
  // without any)
  EXPECT_EQ(report.rooms, 1u);
  const Vec3 centre(3, -3, 0);
  double lo = 1e9, hi = 0, top_start = 0, top_mid = 0;
  size_t red_outside = 0, red_inside = 0;
  for (const Object& o : s.objects) {
    if (o.name.rfind("wall a", 0) != 0) continue;
    const Material& m = s.materials[size_t(o.material)];
    for (const auto& p : s.meshes[size_t(o.mesh)].positions) {
      const double d = (p.cast<double>() - centre).head<2>().norm();
      lo = std::min(lo, d);
      hi = std::max(hi, d);
      // the slope: 2.5 m at the start (x = 1 in ours), 3.5 m where wall a0 ends (y = -1)
      if (std::abs(p.x() - 1.0) < 0.11 && std::abs(p.y() + 3) < 0.05)
        top_start = std::max(top_start, double(p.z()));
      if (std::abs(p.x() - 3.0) < 0.05 && std::abs(p.y() + 1.0) < 0.11)
        top_mid = std::max(top_mid, double(p.z()));
      if (o.name.find("left") != std::string::npos && m.albedo.x() > 0.9)
        (d > 2.0 ? red_outside : red_inside) += 1;
    }
  }
  // every vertex of the round walls is within the ring of radius 2 m and thickness 0.2 m
  EXPECT_GT(lo, 1.9 - 1e-4);
  EXPECT_LT(hi, 2.1 + 1e-4);
  EXPECT_NEAR(lo, 1.9, 2e-3);
  EXPECT_NEAR(hi, 2.1, 2e-3);
  EXPECT_NEAR(top_start, 2.5, 1e-4);
  EXPECT_NEAR(top_mid, 3.5, 1e-4);
  // a positive arc extent bulges to the left of start -> end: the left side is outside
  EXPECT_GT(red_outside, 0u);
  EXPECT_EQ(red_inside, 0u);
  // mitred corners: the square's outer corner (9.1, -0.9) is a vertex of two walls' sides and
  // no wall vertex lies beyond the outer square
  int at_corner = 0;
  for (const Object& o : s.objects) {
    if (o.name.rfind("wall s", 0) != 0) continue;
    for (const auto& p : s.meshes[size_t(o.mesh)].positions) {
      EXPECT_LE(p.x(), 9.1 + 1e-5);
      EXPECT_GE(p.y(), -4.1 - 1e-5);
      at_corner += (p.head<2>().cast<double>() - V2(9.1, -0.9)).norm() < 1e-5;
    }
  }
  EXPECT_GT(at_corner, 0);
  // the floor and the ceiling of the square room
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_EQ(s.rooms[0].type, "second_bedroom");
  EXPECT_NEAR(s.rooms[0].area(), 2.8 * 2.8, 1e-6);
  EXPECT_NEAR(s.rooms[0].ceiling_z, 2.5, 1e-12);
}

TEST(Sh3dImport, DoorsAndArchedWindowsCutTheirWalls) {
  TempDir dir("sh3d");
  // one 4 m wall along the plan's x axis, 20 cm thick; a door of 90 x 210 cm and an arched
  // window (its top a half ellipse) of 100 x 120 cm at 100 cm
  const std::string xml = home(
      "<wall id='w' xStart='0' yStart='0' xEnd='600' yEnd='0' height='250' thickness='20'/>\n"
      "<doorOrWindow id='door' name='Door' model='0/box.obj' x='150' y='0' width='90' depth='20' "
      "height='210' cutOutShape='M0,0 v1 h1 v-1 z'/>\n"
      "<doorOrWindow id='win' name='Window' model='0/box.obj' x='400' y='0' elevation='100' "
      "width='100' depth='20' height='120' cutOutShape='M0,1 v-0.5 a0.5,0.5 0 1,1 1,0 v0.5 z'/>");
  const fs::path path = dir.path() / "door.sh3d";
  test::writeZip(path, {{"Home.xml", xml}, {"0/box.obj", postedBoxObj()}, {"0/m.mtl", mtl()}});
  Sh3dImportOptions opt;
  opt.daylight = false;
  Sh3dImportReport report;
  const Scene s = importSh3d(path.string(), opt, &report);
  EXPECT_EQ(report.holes, 2u);
  EXPECT_EQ(report.doors_windows, 2u);
  // a segment through the wall (y from -0.2 to 0.2 in ours) at (x, z)
  auto through = [&](double x, double z) {
    return segmentHits(s, Vec3(x, 0.2, z), Vec3(x, -0.2, z), 1);
  };
  EXPECT_FALSE(through(1.5, 1.0)) << "door centre";
  EXPECT_FALSE(through(1.1, 0.1)) << "door corner";
  EXPECT_TRUE(through(1.5, 2.2)) << "above the door";
  EXPECT_TRUE(through(0.5, 1.0)) << "beside the door";
  EXPECT_FALSE(through(4.0, 1.6)) << "window centre";
  EXPECT_FALSE(through(4.0, 2.15)) << "window arch top";
  EXPECT_TRUE(through(3.55, 2.15)) << "beside the arch: the cut follows its shape";
  EXPECT_TRUE(through(4.0, 0.9)) << "below the window";
  // the reveals close the hole's sides: a segment along the wall inside its thickness, across
  // the door's jamb, meets one
  EXPECT_TRUE(segmentHits(s, Vec3(1.5, 0, 1.0), Vec3(0.9, 0, 1.0), 1));
}

TEST(Sh3dImport, WallsWithoutRoomsCloseRooms) {
  std::string walls;
  const V2 sq[4] = {{0, 0}, {400, 0}, {400, 300}, {0, 300}};
  for (int i = 0; i < 4; ++i)
    walls += fmt::format(
        "<wall id='s{}' xStart='{}' yStart='{}' xEnd='{}' yEnd='{}' "
        "height='250' thickness='20'/>\n",
        i, sq[i].x(), sq[i].y(), sq[(i + 1) % 4].x(), sq[(i + 1) % 4].y());
  // and a piece, so the home is more than walls (never loaded: it is hidden)
  walls +=
      "<pieceOfFurniture id='p' name='x' model='1' x='1' y='1' width='1' depth='1' "
      "height='1' visible='false'/>";
  Sh3dImportReport report;
  Sh3dImportOptions opt;
  opt.daylight = false;
  const Scene s = sh3dToScene(parseHomeXml(home(walls), "t.sh3d"), opt, &report);
  EXPECT_EQ(report.rooms_from_walls, 1u);
  EXPECT_EQ(report.hidden, 1u);
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_NEAR(s.rooms[0].area(), 12.0, 1e-6);  // the centre lines' square
  EXPECT_TRUE(s.rooms[0].contains(2, -1.5));
}

TEST(Sh3dImport, RoomNamesToRoomTypes) {
  EXPECT_EQ(sh3dRoomType("Living room"), "living_room");
  EXPECT_EQ(sh3dRoomType("salone"), "living_room");
  EXPECT_EQ(sh3dRoomType("Bedroom #2"), "second_bedroom");
  EXPECT_EQ(sh3dRoomType("Master bedroom"), "master_bedroom");
  EXPECT_EQ(sh3dRoomType("Cuisine"), "kitchen");
  EXPECT_EQ(sh3dRoomType("Bathroom"), "bathroom");
  EXPECT_EQ(sh3dRoomType("Hall"), "corridor");
  EXPECT_EQ(sh3dRoomType("Balcony"), "balcony");
  EXPECT_EQ(sh3dRoomType("Garage"), "storage");
  EXPECT_EQ(sh3dRoomType("厨房"), "kitchen");
  EXPECT_EQ(sh3dRoomType("Room 7"), "");
}

TEST(Sh3dImport, ViewsFollowSweetHome3dsYawAndPitch) {
  Sh3dHome h;
  Sh3dCamera c;
  c.name = "v";
  c.x_cm = 100;
  c.y_cm = 200;
  c.z_cm = 150;
  c.yaw = 0;  // looks down the plan's y axis: our -y
  c.pitch = 0.2;
  h.stored_cameras.push_back(c);
  const auto views = sh3dViews(h);
  ASSERT_EQ(views.size(), 1u);
  const Pose& T = views[0].T_world_camera;
  EXPECT_TRUE(T.t.isApprox(Vec3(1, -2, 1.5)));
  const Vec3 forward = T.q * Vec3::UnitZ();  // OpenCV: +z forward
  EXPECT_NEAR(forward.y(), -std::cos(0.2), 1e-9);
  EXPECT_NEAR(forward.z(), -std::sin(0.2), 1e-9);  // positive pitch looks down
  EXPECT_NEAR(forward.x(), 0, 1e-9);
}

// ---- the real homes -----------------------------------------------------------------------

TEST(Sh3dRealHomes, EveryHomeImportsWithItsFurnitureWhereThePlanHasIt) {
  SKIP_WITHOUT_HOMES();
  size_t homes = 0, checked = 0;
  for (const auto& entry : fs::directory_iterator(homesDir())) {
    if (entry.path().extension() != ".sh3d") continue;
    ++homes;
    SCOPED_TRACE(entry.path().filename().string());
    const Sh3dHome h = readSh3dHome(entry.path().string());
    Sh3dImportReport report;
    const Scene s = sh3dToScene(h, {}, &report);
    EXPECT_NO_THROW(s.validate(entry.path().string()));
    EXPECT_GT(s.objects.size(), 0u);
    // every visible room is a Room, with a type
    size_t shown_rooms = 0;
    for (const Sh3dRoom& r : h.rooms)
      shown_rooms += r.level < 0 || h.levels[size_t(r.level)].visible;
    EXPECT_EQ(report.rooms, shown_rooms + report.rooms_from_walls);
    for (const Room& r : s.rooms) EXPECT_FALSE(r.type.empty());
    // furniture: each upright piece's box is centred where the plan puts it, has its size
    // turned by its angle, and stands at its elevation
    for (const auto& [index, instance] : report.piece_instances) {
      const Sh3dPiece& p = h.pieces[index];
      if (p.pitch != 0 || p.roll != 0) continue;
      SCOPED_TRACE(p.id + " '" + p.name + "'");
      const auto box = instanceBox(s, instance);
      const double c = std::abs(std::cos(p.angle)), sn = std::abs(std::sin(p.angle));
      const V2 half(c * p.width_cm / 2 + sn * p.depth_cm / 2,
                    sn * p.width_cm / 2 + c * p.depth_cm / 2);
      const double bottom = h.levelElevation(p.level) + p.elevation_cm;
      EXPECT_NEAR(box.min().z() * 100, bottom, 1.0);
      EXPECT_NEAR(box.sizes().z() * 100, p.height_cm, 1.0);
      // the model fills its box: turned by a multiple of 90 degrees, its box is the plan's;
      // turned otherwise, it lies within the turned footprint's box
      const bool square = std::min(c, sn) < 1e-3;
      for (int k = 0; k < 2; ++k) {
        const double centre = k == 0 ? p.x_cm : -p.y_cm;
        if (square) {
          EXPECT_NEAR(box.center()[k] * 100, centre, 1.0) << "axis " << k;
          EXPECT_NEAR(box.sizes()[k] * 100, 2 * half[k], 1.0) << "axis " << k;
        } else {
          EXPECT_GE(box.min()[k] * 100, centre - half[k] - 1.0) << "axis " << k;
          EXPECT_LE(box.max()[k] * 100, centre + half[k] + 1.0) << "axis " << k;
        }
      }
      ++checked;
    }
  }
  EXPECT_EQ(homes, 17u);
  EXPECT_GT(checked, 700u);
  std::printf("%zu homes, %zu pieces checked against Home.xml\n", homes, checked);
}

TEST(Sh3dRealHomes, DoorsAndWindowsAreCutThroughTheirWalls) {
  SKIP_WITHOUT_HOMES();
  // the eTeks apartment with a bow window: each door or window on a straight wall is open at
  // its centre (a segment across the wall there meets no wall)
  const fs::path path = homesDir() / "eteks_ApartmentWithBowWindow.sh3d";
  const Sh3dHome h = readSh3dHome(path.string());
  Sh3dImportOptions opt;
  opt.daylight = false;
  Sh3dImportReport report;
  const Scene s = sh3dToScene(h, opt, &report);
  EXPECT_EQ(report.doors_windows, 27u);
  EXPECT_GE(report.holes, 27u);
  size_t open = 0, tested = 0;
  for (const Sh3dPiece& p : h.pieces) {
    if (p.kind != Sh3dPieceKind::DoorOrWindow) continue;
    const V2 c(p.x_cm / 100, -p.y_cm / 100);
    const V2 depth(-std::sin(-p.angle), std::cos(-p.angle));
    const double z = (p.elevation_cm + p.height_cm / 2) / 100;
    const V2 a = c + depth * 0.4, b = c - depth * 0.4;
    ++tested;
    open += !segmentHits(s, Vec3(a.x(), a.y(), z), Vec3(b.x(), b.y(), z), 1);
  }
  EXPECT_EQ(open, tested);
}

TEST(Sh3dRealHomes, RefusedFilesGiveOneLineErrors) {
  SKIP_WITHOUT_HOMES();
  const std::map<std::string, std::string> expected = {
      {"legacy_rtreffer_flat.sh3d", "save it again"},
      {"legacy_sh3d_junit_home1.sh3d", "save it again"},
      {"neg_sh3d_damagedHome.sh3d", "zip"},
      {"neg_sh3d_damagedNoContent.sh3d", "save it again"},
      {"synth_beispielhaus_malformed.sh3d", "bare '&'"},
      {"synth_bowman_walls.sh3d", "nothing else"},
      {"synth_openhome_test.sh3d", "another tool"},
      {"synth_uk_4bed_semi_v72.sh3d", "another tool"}};
  size_t seen = 0;
  for (const auto& entry : fs::directory_iterator(homesDir() / "negative")) {
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const InputError e = expectInputError([&] { importSh3d(entry.path().string(), {}); });
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), entry.path().string());
    ASSERT_TRUE(expected.count(name)) << "a refused file this test does not know";
    EXPECT_NE(std::string(e.what()).find(expected.at(name)), std::string::npos) << e.what();
    ++seen;
  }
  EXPECT_EQ(seen, expected.size());
}

// ---- polygons (GEOS) ----------------------------------------------------------------------

TEST(PolygonMesh, DifferenceTriangulationCoversTheRightArea) {
  const Ring square = {V2(0, 0), V2(4, 0), V2(4, 3), V2(0, 3)};
  const Ring hole = {V2(1, 1), V2(2, 1), V2(2, 2), V2(1, 2)};
  const Ring crossing = {V2(3, -1), V2(5, -1), V2(5, 1), V2(3, 1)};  // a quarter inside
  double area = 0;
  for (const auto& t : triangulateDifference(square, {hole, crossing})) {
    const double a2 = signedArea2({t[0], t[1], t[2]});
    EXPECT_GT(a2, 0) << "counter-clockwise";
    area += a2 / 2;
  }
  EXPECT_NEAR(area, 12 - 1 - 1, 1e-9);
  // an L-shaped (concave) room, given clockwise
  const Ring l = {V2(0, 0), V2(0, 2), V2(1, 2), V2(1, 1), V2(2, 1), V2(2, 0)};
  area = 0;
  for (const auto& t : triangulatePolygon(l)) area += signedArea2({t[0], t[1], t[2]}) / 2;
  EXPECT_NEAR(area, 3, 1e-9);
  EXPECT_NEAR(intersectionArea(square, crossing), 1, 1e-9);
  EXPECT_TRUE(triangulatePolygon({V2(0, 0), V2(1, 1)}).empty());
}

}  // namespace
}  // namespace inet
