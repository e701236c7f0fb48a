// Sweet Home 3D catalogs on archives written here (libzip): the .properties reader, the zip
// wrapper, the catalog's keys and errors, the model's frame, size, materials, lights and cache,
// and the label table.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <zip.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "zip_fixture.h"
#include "assets/catalog_labels.h"
#include "assets/catalog_library.h"
#include "assets/catalog_model.h"
#include "assets/furniture_catalog.h"
#include "assets/java_properties.h"
#include "assets/zip_archive.h"
#include "core/atomic_file.h"
#include "core/image_io.h"
#include "scene/catalog_ref.h"
#include "scene/layout_json.h"
#include "scene/nyu40.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;
using test::TempDir;

/// Writes a zip archive of `files` (name -> bytes) to `path`.
using test::writeZip;

// ---- .properties --------------------------------------------------------------------------

TEST(JavaProperties, SeparatorsCommentsContinuationsAndEscapes) {
  const std::string text =
      "# comment\n"
      "! also a comment\n"
      "a=1\n"
      "b : 2\r\n"
      "c 3\n"
      "   d=  spaced value  \n"
      "long=first \\\n"
      "      second\n"
      "key\\ with\\:colon=x\\ty\n"
      "euro=10\\u20ac\n"
      "latin=caf\xe9\n"
      "empty=\n"
      "a=again\n";
  const JavaProperties p = parseJavaProperties(text, "t.properties");
  EXPECT_EQ(p.at("a"), "again");  // later keys replace earlier ones
  EXPECT_EQ(p.at("b"), "2");
  EXPECT_EQ(p.at("c"), "3");
  EXPECT_EQ(p.at("d"), "spaced value  ");
  EXPECT_EQ(p.at("long"), "first second");
  EXPECT_EQ(p.at("key with:colon"), "x\ty");
  EXPECT_EQ(p.at("euro"), "10\xe2\x82\xac");  // U+20AC in UTF-8
  EXPECT_EQ(p.at("latin"), "caf\xc3\xa9");    // ISO-8859-1 0xE9 in UTF-8
  EXPECT_EQ(p.at("empty"), "");
  EXPECT_EQ(p.count("# comment"), 0u);
  EXPECT_EQ(p.size(), 9u);
}

TEST(JavaProperties, MalformedUnicodeEscapeNamesTheLine) {
  const InputError e =
      expectInputError([] { parseJavaProperties("a=1\nb=\\u12G4\n", "t.properties"); });
  EXPECT_EQ(e.file(), "t.properties");
  EXPECT_EQ(e.field(), "line 2");
  expectInputError([] { parseJavaProperties("a=\\u12", "t.properties"); });
}

// ---- zip ----------------------------------------------------------------------------------

TEST(ZipArchive, ReadsEntriesAndTheChecksumFollowsTheContent) {
  TempDir dir("zip");
  writeZip(dir / "a.zip", {{"x/one.txt", "hello"}, {"two.bin", std::string("\0\1\2", 3)}});
  ZipArchive z((dir / "a.zip").string());
  ASSERT_EQ(z.entries().size(), 2u);
  EXPECT_EQ(z.read("x/one.txt"), "hello");
  EXPECT_EQ(z.read("/x/one.txt"), "hello");  // a leading '/' as catalogs write model paths
  EXPECT_EQ(z.read("two.bin").size(), 3u);
  const std::string sum = z.contentChecksum();
  EXPECT_EQ(sum.size(), 16u);
  writeZip(dir / "b.zip", {{"x/one.txt", "hellO"}, {"two.bin", std::string("\0\1\2", 3)}});
  EXPECT_NE(ZipArchive((dir / "b.zip").string()).contentChecksum(), sum);
  writeZip(dir / "c.zip", {{"x/one.txt", "hello"}, {"two.bin", std::string("\0\1\2", 3)}});
  EXPECT_EQ(ZipArchive((dir / "c.zip").string()).contentChecksum(), sum);
  EXPECT_EQ(expectInputError([&] { z.read("nope"); }).field(), "nope");
  EXPECT_EQ(expectInputError([&] { z.read("x/one.txt", 4); }).field(), "x/one.txt");
  expectInputError([&] { ZipArchive((dir / "missing.zip").string()); });
  const std::string text = dir.write("not.zip", "just text");
  EXPECT_EQ(expectInputError([&] { ZipArchive z2(text); }).file(), text);
}

// ---- a catalog written here ---------------------------------------------------------------

// A Z-up OBJ of a 2 x 1 x 0.5 box (x, y, z in file units) with a marker triangle on its front
// face (file y = -0.5, which modelRotation turns to Sweet Home 3D's front, +z, and so to our
// -y), and two materials: glossy red and a textured one whose map_Kd names a path of the
// modeller's machine.
std::string boxObj() {
  std::string s = "mtllib box.mtl\n";
  const double x[2] = {-1, 1}, y[2] = {-0.5, 0.5}, z[2] = {0, 0.5};
  for (int i = 0; i < 8; ++i)
    s += fmt::format("v {} {} {}\n", x[i & 1], y[(i >> 1) & 1], z[i >> 2]);
  s += "vt 0 0\nvt 1 0\nvt 1 1\n";
  s += "o body\nusemtl red\n";
  const int faces[12][3] = {{1, 3, 4}, {1, 4, 2}, {5, 6, 8}, {5, 8, 7}, {1, 2, 6}, {1, 6, 5},
                            {3, 7, 8}, {3, 8, 4}, {1, 5, 7}, {1, 7, 3}, {2, 4, 8}, {2, 8, 6}};
  for (const auto& f : faces) s += fmt::format("f {}/1 {}/2 {}/3\n", f[0], f[1], f[2]);
  s += "v -0.1 -0.5 0.2\nv 0.1 -0.5 0.2\nv 0 -0.5 0.3\n";  // marker, front face
  s += "o marker\nusemtl wood\nf 9/1 10/2 11/3\n";
  s += "f 9 10\n";  // an edge among the faces (Assimp would fail the whole file)
  return s;
}

std::string boxMtl() {
  return "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 100\nd 1\n"
         "newmtl wood\nKd 1 1 1\nmap_Kd C:\\Documents and Settings\\me\\My Textures\\wood.png\n"
         "newmtl glass\nKd 0.2 0.8 0.2\nd 0.25\n";
}

/// A 2x2 PNG, written with our own PNG writer and read back as bytes.
std::string tinyPng(const TempDir& dir) {
  const fs::path p = dir / "tiny.png";
  writePng(p, ImageU8(2, 2, 3, 200));
  return readTextFile(p);
}

const char* kProperties =
    "id=Test#Catalog\nname=Test catalog\nlicense=CC0\n"
    "id#1=Test#box\nname#1=Coffee table\ncategory#1=Living room\ncreator#1=Me\n"
    "model#1=/test/box/box.obj\nmultiPartModel#1=true\n"
    "width#1=200\ndepth#1=100\nheight#1=50\nmovable#1=true\ndoorOrWindow#1=false\n"
    "modelRotation#1=1 0 0 0 0 1 0 -1 0\ntags#1=Wood, Table\n"
    "id#2=Test#lamp\nname#2=Desk lamp\ncategory#2=Lights\nmodel#2=/test/box/box.obj\n"
    "multiPartModel#2=true\nwidth#2=20\ndepth#2=40\nheight#2=60\nelevation#2=75\n"
    "modelRotation#2=1 0 0 0 0 1 0 -1 0\n"
    "lightSourceX#2=10 0\nlightSourceY#2=0 40\nlightSourceZ#2=60 30\n"
    "lightSourceColor#2=#888888 #FF0000\nlightSourceDiameter#2=4 2\n"
    "id#3=Test#window\nname#3=Arched window\ncategory#3=Doors and windows\n"
    "model#3=/test/box/box.obj\nmultiPartModel#3=true\nwidth#3=100\ndepth#3=20\n"
    "height#3=150\ndoorOrWindow#3=true\nmovable#3=false\n"
    "doorOrWindowCutOutShape#3=M0,0.2 a0.5,0.2 0 0,1 1,0 v0.8 h-1 z\n"
    "doorOrWindowWallThickness#3=15\ndoorOrWindowWallDistance#3=2\n"
    "doorOrWindowSashXAxis#3=5 95\ndoorOrWindowSashYAxis#3=10 10\n"
    "doorOrWindowSashWidth#3=45 45\ndoorOrWindowSashStartAngle#3=0 180\n"
    "doorOrWindowSashEndAngle#3=90 90\n";

fs::path writeCatalog(const TempDir& dir, const std::string& properties = kProperties,
                      const std::string& name = "test.sh3f") {
  const fs::path path = dir / name;
  writeZip(path, {{"PluginFurnitureCatalog.properties", properties},
                  {"test/box/box.obj", boxObj()},
                  {"test/box/box.mtl", boxMtl()},
                  {"test/box/wood.png", tinyPng(dir)},
                  {"LICENSE.TXT", "CC0"}});
  return path;
}

TEST(FurnitureCatalog, ReadsThePiecesKeys) {
  TempDir dir("sh3f");
  const FurnitureCatalog c = readFurnitureCatalog(writeCatalog(dir).string());
  EXPECT_EQ(c.id, "Test#Catalog");
  EXPECT_EQ(c.name, "Test catalog");
  EXPECT_EQ(c.checksum.size(), 16u);
  ASSERT_EQ(c.pieces.size(), 3u);
  const CatalogPiece& box = c.pieces[0];
  EXPECT_EQ(box.id, "Test#box");
  EXPECT_EQ(box.model, "test/box/box.obj");
  EXPECT_EQ(box.license, "CC0");  // the catalog's
  EXPECT_EQ(box.creator, "Me");
  EXPECT_EQ(box.tags, (std::vector<std::string>{"Wood", "Table"}));
  EXPECT_DOUBLE_EQ(box.width_cm, 200);
  EXPECT_TRUE(box.multi_part);
  EXPECT_FALSE(box.door_or_window);
  EXPECT_EQ(box.model_rotation(1, 2), 1.0);
  EXPECT_EQ(box.model_rotation(2, 1), -1.0);
  const CatalogPiece& lamp = c.pieces[1];
  ASSERT_EQ(lamp.lights.size(), 2u);
  EXPECT_EQ(lamp.lights[1].position_cm, Eigen::Vector3d(0, 40, 30));
  EXPECT_NEAR(lamp.lights[0].color.x(), 0x88 / 255.0, 1e-6);
  EXPECT_EQ(lamp.lights[1].color, Vec3f(1, 0, 0));
  EXPECT_DOUBLE_EQ(lamp.lights[1].diameter_cm, 2);
  EXPECT_DOUBLE_EQ(lamp.elevation_cm, 75);
  const CatalogPiece& win = c.pieces[2];
  ASSERT_TRUE(win.door_or_window);
  EXPECT_FALSE(win.movable);
  EXPECT_EQ(win.door_or_window->cut_out_shape, "M0,0.2 a0.5,0.2 0 0,1 1,0 v0.8 h-1 z");
  EXPECT_DOUBLE_EQ(win.door_or_window->wall_thickness_cm, 15);
  ASSERT_EQ(win.door_or_window->sashes.size(), 2u);
  EXPECT_NEAR(win.door_or_window->sashes[1].start_angle, M_PI, 1e-12);
  EXPECT_TRUE(win.isInterior());
}

TEST(FurnitureCatalog, BadKeysAreNamed) {
  TempDir dir("sh3f_bad");
  auto fieldOf = [&](const std::string& from, const std::string& to) {
    std::string props = kProperties;
    const size_t at = props.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    props.replace(at, from.size(), to);
    const fs::path path = writeCatalog(dir, props, "bad.sh3f");
    const InputError e = expectInputError([&] { readFurnitureCatalog(path.string()); });
    EXPECT_EQ(e.file(), path.string());
    return e.field();
  };
  EXPECT_EQ(fieldOf("width#1=200\n", ""), "width#1");
  EXPECT_EQ(fieldOf("width#1=200", "width#1=wide"), "width#1");
  EXPECT_EQ(fieldOf("depth#1=100", "depth#1=-3"), "depth#1");
  EXPECT_EQ(fieldOf("modelRotation#1=1 0 0 0 0 1 0 -1 0", "modelRotation#1=1 0 0"),
            "modelRotation#1");
  EXPECT_EQ(fieldOf("modelRotation#1=1 0 0 0 0 1 0 -1 0", "modelRotation#1=2 0 0 0 2 0 0 0 2"),
            "modelRotation#1");
  EXPECT_EQ(fieldOf("model#1=/test/box/box.obj", "model#1=/test/none.obj"), "model#1");
  EXPECT_EQ(fieldOf("id#2=Test#lamp", "id#2=Test#box"), "id#2");
  EXPECT_EQ(fieldOf("lightSourceZ#2=60 30", "lightSourceZ#2=60"), "lightSourceX#2");
  EXPECT_EQ(fieldOf("#888888 #FF0000", "#888888 red"), "lightSourceColor#2");
  EXPECT_EQ(fieldOf("movable#1=true", "movable#1=yes"), "movable#1");
  EXPECT_EQ(fieldOf("doorOrWindowSashWidth#3=45 45", "doorOrWindowSashWidth#3=45"),
            "doorOrWindowSashXAxis#3");
  // not a catalog at all
  const fs::path empty = dir / "empty.sh3f";
  writeZip(empty, {{"README", "x"}});
  EXPECT_EQ(expectInputError([&] { readFurnitureCatalog(empty.string()); }).field(),
            "PluginFurnitureCatalog.properties");
  EXPECT_EQ(expectInputError([&] { readFurnitureCatalogs((dir / "nowhere").string()); }).file(),
            (dir / "nowhere").string());
}

TEST(FurnitureCatalog, ModelFrameSizeMaterialsAndCache) {
  TempDir dir("sh3f_model");
  const FurnitureCatalog c = readFurnitureCatalog(writeCatalog(dir).string());
  const fs::path cache = dir / "cache";
  const CatalogModel m = loadCatalogModel(c, c.pieces[0], cache);
  // the box is 2 x 1 x 0.5 file units; the catalog says 200 x 100 x 50 cm: 1 unit = 1 m
  Eigen::AlignedBox3d box;
  for (const auto& mesh : m.parts.meshes)
    for (const auto& v : mesh.positions) box.extend(v.cast<double>());
  EXPECT_TRUE(box.min().isApprox(Eigen::Vector3d(-1, -0.5, 0), 1e-6)) << box.min().transpose();
  EXPECT_TRUE(box.max().isApprox(Eigen::Vector3d(1, 0.5, 0.5), 1e-6)) << box.max().transpose();
  EXPECT_NEAR(m.stretch, 1.0, 1e-9);
  EXPECT_TRUE(m.size.isApprox(Eigen::Vector3d(2, 1, 0.5)));
  // the marker sits on the front face: ours -y
  int marker = -1;
  for (size_t i = 0; i < m.parts.objects.size(); ++i)
    if (m.parts.objects[i].part == "marker") marker = static_cast<int>(i);
  ASSERT_GE(marker, 0);
  for (const auto& v : m.parts.meshes[size_t(m.parts.objects[size_t(marker)].mesh)].positions)
    EXPECT_NEAR(v.y(), -0.5f, 1e-6f);
  // labels, physics
  EXPECT_EQ(m.label.category, "coffee_table");
  for (const auto& o : m.parts.objects) {
    EXPECT_EQ(o.nyu40, *nyu40FromName("table"));
    EXPECT_EQ(o.kind, "coffee_table");
    ASSERT_TRUE(o.physics);
    EXPECT_GT(o.physics->mass_kg, 0.05f);
  }
  EXPECT_EQ(m.hulls.size(), m.parts.objects.size());
  // materials: glossy red is a plastic, the texture was found beside the model by file name
  std::map<std::string, const Material*> mats;
  for (const auto& mat : m.parts.materials) {
    EXPECT_EQ(mat.catalog_piece, "Test#box");
    EXPECT_EQ(mat.id, "Test#box/" + mat.catalog_material);
    mats[mat.catalog_material] = &mat;
  }
  ASSERT_TRUE(mats.count("red"));
  EXPECT_EQ(mats["red"]->type, MaterialType::Plastic);
  EXPECT_NEAR(mats["red"]->roughness, std::pow(2.0 / 102.0, 0.25), 1e-6);
  ASSERT_TRUE(mats.count("wood"));
  ASSERT_FALSE(mats["wood"]->albedo_texture.empty());
  EXPECT_EQ(fs::path(mats["wood"]->albedo_texture.path).filename(), "wood.png");
  EXPECT_EQ(m.report.relocated_textures, 1u);
  EXPECT_EQ(m.report.skipped_textures, 0u);
  // extracted once into <cache>/<checksum>/: a second load reads the same files
  const fs::path obj = cache / c.checksum / "test/box/box.obj";
  ASSERT_TRUE(fs::exists(obj));
  const auto stamp = fs::last_write_time(obj);
  fs::permissions(cache / c.checksum / "test/box", fs::perms::owner_write,
                  fs::perm_options::remove);
  const CatalogModel again = loadCatalogModel(c, c.pieces[0], cache);  // no write needed
  fs::permissions(cache / c.checksum / "test/box", fs::perms::owner_write, fs::perm_options::add);
  EXPECT_EQ(fs::last_write_time(obj), stamp);
  EXPECT_EQ(again.parts.meshes[0].positions, m.parts.meshes[0].positions);
  for (const auto& e : fs::recursive_directory_iterator(cache))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(FurnitureCatalog, LampLightsAreInTheModelFrame) {
  TempDir dir("sh3f_lamp");
  const FurnitureCatalog c = readFurnitureCatalog(writeCatalog(dir).string());
  const CatalogModel m = loadCatalogModel(c, c.pieces[1], dir / "cache");
  EXPECT_EQ(m.label.category, "table_lamp");
  EXPECT_DOUBLE_EQ(m.elevation_m, 0.75);
  ASSERT_EQ(m.parts.lights.size(), 2u);
  // x from the left, y from the front (our -y), z from the bottom, as Sweet Home 3D's
  // HomeComponent3D and PhotoRenderer place them; 20 x 40 x 60 cm
  EXPECT_TRUE(m.parts.lights[0].position.isApprox(Vec3(0, -0.2, 0.6)));
  EXPECT_TRUE(m.parts.lights[1].position.isApprox(Vec3(-0.1, 0.2, 0.3)));
  EXPECT_EQ(m.parts.lights[0].temperature_k, 2700.f);  // grey: warm white
  EXPECT_EQ(m.parts.lights[1].temperature_k, 0.f);     // red: its own colour
  EXPECT_GT(m.parts.lights[1].color.x(), 1.f);
  EXPECT_NEAR(m.parts.lights[0].intensity + m.parts.lights[1].intensity, 2.5f, 1e-6f);
  const CatalogModel w = loadCatalogModel(c, c.pieces[2], dir / "cache");
  EXPECT_FALSE(w.movable);
  EXPECT_EQ(w.label.category, "window");
}

TEST(FurnitureCatalog, EntriesThatLeaveTheCacheAreRefused) {
  TempDir dir("sh3f_slip");
  std::string props = kProperties;
  const std::string from = "model#1=/test/box/box.obj";
  props.replace(props.find(from), from.size(), "model#1=../../evil/box.obj");
  const fs::path path = dir / "slip.sh3f";
  writeZip(path, {{"PluginFurnitureCatalog.properties", props},
                  {"../../evil/box.obj", boxObj()},
                  {"test/box/box.obj", boxObj()}});
  const FurnitureCatalog c = readFurnitureCatalog(path.string());
  const InputError e = expectInputError([&] { loadCatalogModel(c, c.pieces[0], dir / "cache"); });
  EXPECT_EQ(e.file(), path.string());
  EXPECT_FALSE(fs::exists(dir / "evil"));
}

TEST(FurnitureCatalog, LayoutsNameCatalogModelsAndLoadThemBack) {
  TempDir dir("sh3f_layout");
  fs::create_directories(dir / "catalogs");
  writeCatalog(dir, kProperties, "catalogs/test.sh3f");
  const std::string cat_dir = (dir / "catalogs").string();
  const auto lib = catalogLibrary(cat_dir);
  ASSERT_EQ(lib->byCategory("coffee_table").size(), 1u);
  EXPECT_EQ(lib->byCategory("coffee_table")[0]->id, "Test#box");
  const auto model = lib->model("Test#box", "", "");
  EXPECT_EQ(lib->model("Test#box", "", "").get(), model.get());  // loaded once
  EXPECT_EQ(expectInputError([&] { lib->model("Test#none", "f", "g"); }).field(), "g");
  // a scene of the model placed twice, written as a layout: meshes and materials by name
  Scene s = model->parts;
  s.name = "two_tables";
  const size_t n = s.objects.size();
  for (size_t i = 0; i < n; ++i) {
    Object o = s.objects[i];
    o.name = "table_2";
    o.instance = 2;
    o.T_world_object(0, 3) = 3.0;
    s.objects.push_back(o);
  }
  for (auto& o : s.objects)
    if (o.name.empty() || o.name == "body" || o.name == "marker") o.name = "table_1";
  const fs::path path = dir / "layout.json";
  saveLayout(s, path.string());
  const std::string text = readTextFile(path);
  EXPECT_NE(text.find("\"catalog\": \"Test#box\""), std::string::npos);
  EXPECT_EQ(text.find("vertices"), std::string::npos);  // nothing inlined
  EXPECT_EQ(text.find("wood.png"), std::string::npos);  // no cache paths
  installCatalogResolver(cat_dir);
  const Scene back = loadLayout(path.string());
  ASSERT_EQ(back.meshes.size(), s.meshes.size());
  for (size_t i = 0; i < s.meshes.size(); ++i)
    EXPECT_EQ(back.meshes[i].positions, s.meshes[i].positions);
  ASSERT_EQ(back.materials.size(), s.materials.size());
  for (size_t i = 0; i < s.materials.size(); ++i) {
    EXPECT_EQ(back.materials[i].id, s.materials[i].id);
    EXPECT_EQ(back.materials[i].type, s.materials[i].type);
    EXPECT_EQ(back.materials[i].albedo_texture, s.materials[i].albedo_texture);
  }
  EXPECT_EQ(layoutToJson(back), text);  // and writes back the same
  // a part or material the model lacks, and no catalogs at all, are located errors
  std::string bad = text;
  bad.replace(bad.find("\"part\": 0"), 10, "\"part\": 9");
  EXPECT_NE(expectInputError([&] { parseLayout(bad, path.string()); }).field().find("part"),
            std::string::npos);
  setCatalogResolver(nullptr);
  const InputError e = expectInputError([&] { loadLayout(path.string()); });
  EXPECT_NE(e.field().find("catalog"), std::string::npos);
  EXPECT_NE(e.problem().find("sweethome3d-furniture"), std::string::npos);
}

// ---- the label table ----------------------------------------------------------------------

CatalogPiece piece(const std::string& name, const std::string& category, double w, double d,
                   double h) {
  CatalogPiece p;
  p.name = name;
  p.category = category;
  p.width_cm = w, p.depth_cm = d, p.height_cm = h;
  return p;
}

TEST(CatalogLabels, NamesCategoriesAndSizes) {
  auto label = [](const CatalogPiece& p) { return labelCatalogPiece(p); };
  EXPECT_EQ(label(piece("Futon couch", "Living room", 196, 90, 88)).category, "sofa");
  EXPECT_EQ(label(piece("Futon", "Bedroom", 142, 211, 18)).category, "bed_double");
  EXPECT_EQ(label(piece("Island bath", "Bathroom", 170, 94, 108)).category, "bathtub");
  EXPECT_EQ(label(piece("Island", "Kitchen", 94, 70, 83)).category, "kitchen_counter");
  EXPECT_EQ(label(piece("Coffee table", "Living room", 120, 70, 45)).category, "coffee_table");
  EXPECT_EQ(label(piece("Table", "Living room", 66, 53, 64)).category, "side_table");
  EXPECT_EQ(label(piece("Table", "Living room", 107, 73, 54)).category, "coffee_table");
  EXPECT_EQ(label(piece("Table", "Living room", 150, 80, 75)).category, "dining_table");
  EXPECT_EQ(label(piece("Bed", "Bedroom", 100, 200, 80)).category, "bed_single");
  EXPECT_EQ(label(piece("Chair", "Office", 64, 64, 91)).category, "office_chair");
  EXPECT_EQ(label(piece("Chair with cushion", "Living room", 44, 44, 95)).category, "dining_chair");
  EXPECT_EQ(label(piece("Toilet paper dispenser", "Bathroom", 21, 17, 15)).nyu40, 40);
  EXPECT_EQ(label(piece("Toilets unit", "Bathroom", 35, 69, 77)).nyu40, 33);
  EXPECT_EQ(label(piece("Desk lamp", "Lights", 14, 34, 45)).category, "table_lamp");
  EXPECT_EQ(label(piece("Lamp", "Lights", 40, 58, 143)).category, "floor_lamp");
  CatalogPiece chandelier = piece("Lamp", "Lights", 53, 51, 63);
  chandelier.lights = {{{5, 20, 21}, {1, 1, 1}, 4}, {{40, 46, 21}, {1, 1, 1}, 4}};
  EXPECT_EQ(label(chandelier).category, "pendant_light");  // bulbs low: it hangs
  chandelier.lights[1].position_cm.z() = 50;
  EXPECT_EQ(label(chandelier).category, "table_lamp");
  const CatalogLabel teapot = label(piece("Teapot", "Kitchen", 22, 15, 21));
  EXPECT_EQ(teapot.category, "mug");  // takes a mug's place on a counter
  EXPECT_TRUE(teapot.slot);
  EXPECT_EQ(teapot.kind, "teapot");
  EXPECT_FALSE(label(piece("Sofa", "Living room", 200, 90, 80)).slot);
  const CatalogLabel female = label(piece("Female", "Characters", 47, 37, 170));
  EXPECT_EQ(female.nyu40, 31);  // person
  EXPECT_EQ(female.kind, "female");
  EXPECT_EQ(label(piece("Male", "Characters", 56, 41, 185)).nyu40, 31);
  EXPECT_EQ(label(piece("Cat", "Characters", 23, 34, 46)).nyu40, 40);
  EXPECT_EQ(label(piece("Bill 10\xe2\x82\xac", "Miscellaneous", 13, 7, 0.1)).nyu40, 40);
  const CatalogLabel big = label(piece("Fitness machine", "Miscellaneous", 220, 170, 200));
  EXPECT_EQ(big.nyu40, 39);  // otherfurniture: unknown and larger than 1 m
  EXPECT_EQ(big.kind, "fitness_machine");
  EXPECT_EQ(label(piece("Shelves", "Bedroom", 101, 42, 191)).category, "bookshelf");
  EXPECT_EQ(label(piece("Book", "Miscellaneous", 28, 18, 2)).category, "books");
  EXPECT_EQ(label(piece("Apple iBook", "Office", 28, 24, 2)).category, "laptop");
}

}  // namespace
}  // namespace inet
