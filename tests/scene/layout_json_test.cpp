// layout.json: loading, canonical writing, exact round trips, relative mesh files, and a table
// of malformed layouts whose errors must name the file and the offending field.
#include "scene/layout_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/assimp_importer.h"
#include "scene/primitives.h"
#include "scene_test_util.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using test::expectScenesEqual;
using test::fixture;
using test::TempDir;

/// A copy of the fixture layout and the mesh files it references, in a temporary folder.
std::string copyFixtureLayout(const TempDir& dir, const std::string& sub = "") {
  for (const char* name : {"small_layout.json", "two_parts.obj", "two_parts.mtl"}) {
    fs::create_directories(dir.path() / sub);
    fs::copy_file(fixture(name), dir.path() / sub / name);
  }
  return (dir.path() / sub / "small_layout.json").string();
}

TEST(LayoutJson, LoadsTheFixture) {
  Scene s = loadLayout(fixture("small_layout.json").string());
  EXPECT_EQ(s.name, "small test room");
  ASSERT_EQ(s.meshes.size(), 7u);
  ASSERT_EQ(s.objects.size(), 8u);
  EXPECT_EQ(s.meshes[0].triangles.size(), 12u);  // box
  EXPECT_EQ(s.meshes[1].triangles.size(), 64u);  // cylinder, 16 segments
  EXPECT_EQ(s.meshes[2].sphere_radius, 0.25f);
  // file meshes: one named part, and the whole file scaled by 0.5 and turned Y up -> Z up
  EXPECT_EQ(s.meshes[4].source.kind, MeshSource::Kind::File);
  EXPECT_EQ(s.meshes[4].source.file, "two_parts.obj") << "kept as written";
  EXPECT_EQ(s.meshes[4].triangles.size(), 2u);
  EXPECT_EQ(s.meshes[5].triangles.size(), 3u);
  bool found = false;  // file vertex (0, 0, 2) -> scaled (0, 0, 1) -> z becomes -y: (0, -1, 0)
  for (const auto& p : s.meshes[5].positions) found |= (p == Vec3f(0.f, -1.f, 0.f));
  EXPECT_TRUE(found);
  EXPECT_EQ(s.meshes[6].positions[1], Vec3f(0.1f, 0.f, 0.f));
  // labels: id only, name only, both; the canonical name is implied
  EXPECT_EQ(s.objects[0].nyu40, 2);
  EXPECT_EQ(s.objects[1].nyu40, 7);
  EXPECT_EQ(s.objects[2].nyu40, 7);
  EXPECT_EQ(s.objects[6].nyu40, 0);
  EXPECT_EQ(s.objects[1].T_world_object(0, 0), 0.8660254037844387);
  EXPECT_EQ(s.objects[5].T_world_object(1, 3), 1e-9);
  EXPECT_EQ(s.objects[2].instance, 2);
  EXPECT_EQ(s.materials[2].emission, Vec3f(12.f, 11.5f, 10.5f));
  EXPECT_EQ(s.materials[0].emission, Vec3f::Zero()) << "emission defaults to 0";
  ASSERT_EQ(s.materials.size(), 8u);
  EXPECT_EQ(s.materials[3].type, MaterialType::Conductor);
  EXPECT_EQ(s.materials[3].metal, "gold");
  EXPECT_FLOAT_EQ(s.materials[3].roughness, 0.35f);
  EXPECT_EQ(s.materials[4].type, MaterialType::Plastic);
  EXPECT_FLOAT_EQ(s.materials[4].ior, 1.49f);
  EXPECT_EQ(s.materials[5].type, MaterialType::Dielectric);
  EXPECT_EQ(s.materials[6].type, MaterialType::ThinDielectric);
  EXPECT_EQ(s.materials[7].type, MaterialType::Translucent);
  EXPECT_EQ(s.materials[7].transmittance, Vec3f(0.3f, 0.3f, 0.25f));
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[3].type, LightType::Sky);
  EXPECT_EQ(s.lights[0].position, Vec3(2.5, 2.0, 2.4));
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_EQ(s.lights[1].type, LightType::Spot);
  EXPECT_FLOAT_EQ(s.lights[1].temperature_k, 2700.f);
  EXPECT_EQ(s.lights[2].type, LightType::Sun);
  EXPECT_FALSE(s.lights[2].on);
}

TEST(LayoutJson, LoadSaveLoadSaveIsStable) {
  TempDir dir;
  const std::string original = copyFixtureLayout(dir);
  Scene s1 = loadLayout(original);
  const std::string saved1 = (dir.path() / "saved1.json").string();
  saveLayout(s1, saved1);
  Scene s2 = loadLayout(saved1);
  const std::string saved2 = (dir.path() / "saved2.json").string();
  saveLayout(s2, saved2);
  EXPECT_EQ(readTextFile(saved1), readTextFile(saved2)) << "canonical text is a fixed point";
  expectScenesEqual(s1, s2);
  expectScenesEqual(s1, loadLayout(saved2));
  EXPECT_EQ(removeStaleTemporaries(dir.path()), 0) << "atomic save leaves no temporaries";
}

TEST(LayoutJson, CanonicalTextShape) {
  const std::string text = layoutToJson(loadLayout(fixture("small_layout.json").string()));
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text.find('\t'), std::string::npos);
  EXPECT_EQ(text.rfind("{\n  \"format\": \"interiornet-layout\",\n  \"version\": 1,\n", 0), 0u)
      << text.substr(0, 80);
  // floats in their shortest form, arrays of scalars on one line, both label fields written
  EXPECT_NE(text.find("\"albedo\": [0.42, 0.28, 0.16]"), std::string::npos);
  EXPECT_NE(text.find("\"transform\": [5, 0, 0, 2.5, 0, 4, 0, 2, 0, 0, 1, 0, 0, 0, 0, 1]"),
            std::string::npos);
  EXPECT_NE(text.find("\"nyu40\": 2,\n      \"category\": \"floor\""), std::string::npos);
  EXPECT_NE(text.find("\"nyu40\": 0,\n      \"category\": \"void\""), std::string::npos);
  EXPECT_NE(text.find("\"category\": \"table\""), std::string::npos) << "canonical spelling";
  EXPECT_NE(text.find("\"file\": \"two_parts.obj\",\n      \"scale\": 1,\n      \"up\": \"z\","),
            std::string::npos);
  EXPECT_NE(text.find("[0.1, 0, 0]"), std::string::npos);
  // and the text is plain JSON
  EXPECT_NO_THROW({
    auto parsed = nlohmann::json::parse(text);
    (void)parsed;
  });
}

TEST(LayoutJson, EveryDoubleAndFloatRoundTripsExactly) {
  // awkward values: shortest text of each must parse back to the same bits
  const double awkward[] = {0.1 + 0.2,
                            1.0 / 3.0,
                            -0.0,
                            1e-300,
                            5e-324,
                            123456789.123456789,
                            std::nextafter(1.0, 2.0),
                            -2.5e-7,
                            9007199254740993.0,
                            1e15 + 0.5};
  Scene s;
  s.name = "exactness";
  Mesh tri;
  tri.id = "tri";
  tri.positions = {Vec3f(0.1f, 1.0f / 3.0f, -0.0f), Vec3f(std::nextafter(1.f, 2.f), 7e-39f, 3e38f),
                   Vec3f(16777217.f, -1.17549435e-38f, 0.7f)};
  tri.triangles = {Tri(0, 1, 2)};
  s.meshes.push_back(tri);
  Material mat;
  mat.id = "m";
  mat.albedo = Vec3f(0.1f, 0.2f, 0.3f);
  mat.emission = Vec3f(1e-7f, 3.4f, 1234.5678f);
  s.materials.push_back(mat);
  for (size_t i = 0; i + 2 < std::size(awkward); ++i) {
    Object o;
    o.name = "object_";
    o.name += std::to_string(i);
    o.mesh = 0;
    o.material = 0;
    o.T_world_object(0, 3) = awkward[i];
    o.T_world_object(1, 3) = awkward[i + 1];
    o.T_world_object(2, 3) = awkward[i + 2];
    o.T_world_object(0, 1) = awkward[i] * 1e-3;  // keeps det > 0 (upper triangular)
    o.T_world_object(2, 2) = 1.0 + awkward[i + 1] * 1e-3 + 1e-9;
    o.instance = static_cast<int>(i) + 1;
    s.objects.push_back(o);
  }
  Light l;
  l.name = "p";
  l.position = Vec3(awkward[0], awkward[3], awkward[4]);
  l.color = Vec3f(0.3f, 0.f, 1e30f);
  l.intensity = 0.1f;
  l.radius = 0.1f + 0.2f;
  s.lights.push_back(l);
  const std::string text = layoutToJson(s);
  Scene back = parseLayout(text, "memory.json");
  expectScenesEqual(s, back);
  EXPECT_EQ(layoutToJson(back), text);
  EXPECT_NE(text.find("-0.0"), std::string::npos) << "negative zero keeps its sign";
}

TEST(LayoutJson, ImportedScenesRoundTripInline) {
  Scene small = importMeshScene(fixture("two_parts.obj").string(), {});
  expectScenesEqual(small, parseLayout(layoutToJson(small), "two_parts.json"));
  const auto room = test::sharedDir() / "bench" / "room.obj";
  if (!fs::exists(room)) GTEST_SKIP() << "needs ../shared/bench/room.obj (absent)";
  Scene s = importMeshScene(room.string(), {});
  const std::string text = layoutToJson(s);
  Scene back = parseLayout(text, "room.json");
  expectScenesEqual(s, back);
  EXPECT_EQ(back.triangleCount(), 183798u);
  EXPECT_EQ(layoutToJson(back), text);
}

TEST(LayoutJson, RelativeFileMeshResolvesAgainstTheLayoutFolder) {
  TempDir dir;
  fs::create_directories(dir.path() / "meshes");
  fs::copy_file(fixture("two_parts.obj"), dir.path() / "meshes" / "two_parts.obj");
  fs::copy_file(fixture("two_parts.mtl"), dir.path() / "meshes" / "two_parts.mtl");
  const std::string layout = dir.write("rooms/a/layout.json", R"({
    "format": "interiornet-layout", "version": 1,
    "meshes": [{"id": "parts", "file": "../../meshes/two_parts.obj", "mesh_name": "glow_panel"}],
    "materials": [{"id": "w", "type": "lambertian", "albedo": [1, 1, 1]}],
    "objects": [{"name": "panel", "mesh": "parts", "material": "w", "category": "lamp",
                 "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "instance": 9}]})");
  Scene s = loadLayout(layout);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangles.size(), 1u);
  EXPECT_EQ(s.meshes[0].source.file, "../../meshes/two_parts.obj");
  EXPECT_EQ(s.meshes[0].source.mesh_name, "glow_panel");
  EXPECT_EQ(s.name, "scene") << "name is optional";
  EXPECT_TRUE(s.lights.empty()) << "lights is optional";
  // written back with the path as written, so the copy beside it loads too
  const std::string copy = (dir.path() / "rooms" / "a" / "copy.json").string();
  saveLayout(s, copy);
  expectScenesEqual(s, loadLayout(copy));
}

TEST(LayoutJson, TexturesNormalsAndUvsRoundTrip) {
  TempDir dir;
  dir.write("tex/wood.png", "not read by the loader, only checked to exist");
  const std::string path = dir.write("room/layout.json", R"({
    "format": "interiornet-layout", "version": 1, "name": "textured",
    "meshes": [{"id": "tri", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                "triangles": [[0, 1, 2]], "normals": [[0, 0, 2], [0, 0, 1], [0, 0.6, 0.8]],
                "uvs": [[0, 0], [2, 0], [0, 0.5]]}],
    "materials": [{"id": "wood", "type": "plastic", "albedo": [1, 1, 1], "roughness": 0.5,
                   "albedo_texture": "../tex/wood.png", "roughness_texture": "../tex/wood.png",
                   "normal_texture": "../tex/wood.png", "uv_scale": [4, 0.5]}],
    "objects": [{"name": "floor", "mesh": "tri", "material": "wood", "nyu40": 2, "instance": 1,
                 "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]})");
  Scene s = loadLayout(path);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_EQ(m.normals[0], Vec3f(0, 0, 2)) << "kept as written (the renderer normalises)";
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_EQ(m.uvs[1], Vec2f(2, 0));
  const Material& mat = s.materials[0];
  EXPECT_EQ(mat.albedo_texture.file, "../tex/wood.png") << "as written";
  EXPECT_TRUE(std::filesystem::equivalent(mat.albedo_texture.path, dir.path() / "tex/wood.png"));
  EXPECT_EQ(mat.uv_scale, Vec2f(4, 0.5f));
  // saved next to the original, it reloads to the same scene and the same text
  const std::string text = layoutToJson(s);
  const std::string again = dir.write("room/again.json", text);
  Scene s2 = loadLayout(again);
  EXPECT_EQ(layoutToJson(s2), text);
  EXPECT_EQ(s2.meshes[0].uvs, m.uvs);
  EXPECT_EQ(s2.meshes[0].normals, m.normals);
  EXPECT_EQ(s2.materials[0].normal_texture, mat.normal_texture);
}

TEST(LayoutJson, WriterRefusesScenesItCannotReload) {
  Scene s;
  s.meshes.push_back(makePrimitive("box", {}, "t", "m"));
  s.meshes.push_back(makePrimitive("box", {}, "t", "m"));
  s.meshes[0].id = s.meshes[1].id = "box";
  s.materials.emplace_back().id = "w";
  try {
    (void)layoutToJson(s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("meshes[1].id"), std::string::npos) << e.what();
  }
  s.meshes[1].id = "box2";
  Object o;
  o.name = "flat";
  o.mesh = 0;
  o.material = 0;
  o.instance = 1;
  s.objects.push_back(o);
  EXPECT_NO_THROW((void)layoutToJson(s));
  s.objects[0].name = "";
  EXPECT_THROW((void)layoutToJson(s), InputError);
  s.objects[0].name = "flat";
  s.objects[0].T_world_object(2, 2) = 0.0;  // zero scale
  EXPECT_THROW((void)layoutToJson(s), InputError);
}

// ---- malformed layouts ----

using nlohmann::json;

/// A small valid layout; each malformed case edits a copy of it.
json baseLayout() {
  return json::parse(R"({
    "format": "interiornet-layout", "version": 1, "name": "base",
    "meshes": [{"id": "box", "primitive": "box"}],
    "materials": [{"id": "white", "type": "lambertian", "albedo": [0.5, 0.5, 0.5]}],
    "objects": [{"name": "crate", "mesh": "box", "material": "white", "nyu40": 29,
                 "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "instance": 1}],
    "lights": [{"name": "bulb", "type": "point", "position": [0, 0, 2], "intensity": 1}]})");
}

/// A Preetham sky light entry (valid).
json preethamSky() {
  return json::parse(
      R"({"name": "sky", "type": "sky", "model": "preetham", "sun_direction": [0, 0.6, -0.8],
          "turbidity": 4, "intensity": 90})");
}

template <class F>
std::string edited(F edit) {
  json j = baseLayout();
  edit(j);
  return j.dump(1);
}

struct BadLayout {
  std::string name;     ///< also the file name, which the message must contain
  std::string text;     ///< the layout.json contents
  std::string field;    ///< must appear in the message
  std::string problem;  ///< must appear in the message
};

/// Syntax, top-level keys, format and version.
std::vector<BadLayout> headerCases() {
  return {
      {"syntax", "{\"format\": \"interiornet-layout\",\n \"version\": 1,,}", "line 2, column 15",
       "invalid JSON"},
      {"not_an_object", "[1, 2]", "", "top level"},
      {"number_overflow", edited([](json& j) { j["name"] = "x"; }).replace(0, 1, "{\"v\": 1e400,"),
       "", "overflow"},
      {"duplicate_key", "{\"format\": \"interiornet-layout\", \"format\": \"x\"}", "format",
       "duplicate key"},
      {"wrong_format", edited([](json& j) { j["format"] = "mitsuba"; }), "format",
       "expected \"interiornet-layout\""},
      {"missing_format", edited([](json& j) { j.erase("format"); }), "format", "missing"},
      {"future_version", edited([](json& j) { j["version"] = 2; }), "version",
       "this build reads version 1"},
      {"version_as_string", edited([](json& j) { j["version"] = "1"; }), "version", "unsupported"},
      {"room_unknown_type", edited([](json& j) {
         j["rooms"] =
             json::parse(R"([{"id": "r", "type": "ballroom", "outline": [[0,0],[1,0],[1,1]]}])");
       }),
       "rooms[0].type", "unknown room type 'ballroom' (valid: living_room"},
      {"room_clockwise", edited([](json& j) {
         j["rooms"] =
             json::parse(R"([{"id": "r", "type": "kitchen", "outline": [[0,0],[0,1],[1,1]]}])");
       }),
       "rooms[0].outline", "counter-clockwise"},
      {"object_unknown_room", edited([](json& j) { j["objects"][0]["room"] = "attic"; }),
       "objects[0].room", "unknown room id 'attic'"},
      {"physics_zero_mass", edited([](json& j) {
         j["objects"][0]["physics"] = {{"mass_kg", 0}, {"friction", 0.2}, {"movable", true}};
       }),
       "objects[0].physics.mass_kg", "> 0"},
      {"light_unknown_object", edited([](json& j) { j["lights"][0]["object"] = "lamp_9"; }),
       "lights[0] ('bulb').object", "no object is named 'lamp_9'"},
      {"missing_objects", edited([](json& j) { j.erase("objects"); }), "objects",
       "missing required key"},
  };
}

/// Mesh entries of every kind, including referenced mesh files.
std::vector<BadLayout> meshCases() {
  const std::string fixture_dir = fixture("").string();
  return {
      {"mesh_unknown_key", edited([](json& j) { j["meshes"][0]["colour"] = 1; }),
       "meshes[0].colour", "unknown key"},
      {"mesh_two_kinds", edited([](json& j) { j["meshes"][0]["file"] = "a.obj"; }), "meshes[0]",
       "exactly one of"},
      {"unknown_primitive", edited([](json& j) { j["meshes"][0]["primitive"] = "torus"; }),
       "meshes[0].primitive", "box, cylinder, fold, quad, sphere"},
      {"bad_primitive_param", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"}, {"primitive", "cylinder"}, {"params", {{"segments", 2}}}};
       }),
       "meshes[0].params.segments", "[3, 256]"},
      {"duplicate_mesh_id", edited([](json& j) {
         j["meshes"].push_back({{"id", "box"}, {"primitive", "quad"}});
       }),
       "meshes[1].id", "duplicate id 'box'"},
      {"triangle_index_out_of_range", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"},
                           {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                           {"triangles", {{0, 1, 3}}}};
       }),
       "meshes[0].triangles[0][2]", "outside 0..2"},
      {"vertex_not_a_number", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"},
                           {"vertices", {{0, 0, 0}, {"one", 0, 0}, {0, 1, 0}}},
                           {"triangles", {{0, 1, 2}}}};
       }),
       "meshes[0].vertices[1][0]", "expected a number"},
      {"vertex_beyond_float", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"},
                           {"vertices", {{1e39, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                           {"triangles", {{0, 1, 2}}}};
       }),
       "meshes[0].vertices[0][0]", "single-precision"},
      {"missing_mesh_file", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"}, {"file", "absent.obj"}};
       }),
       "meshes[0].file", "absent.obj': file not found"},
      {"malformed_obj", edited([&](json& j) {
         j["meshes"][0] = {{"id", "box"}, {"file", fixture_dir + "malformed.obj"}};
       }),
       "meshes[0].file", "line 6: face vertex index 9"},
      {"mesh_name_not_in_file", edited([&](json& j) {
         j["meshes"][0] = {
             {"id", "box"}, {"file", fixture_dir + "two_parts.obj"}, {"mesh_name", "sofa"}};
       }),
       "meshes[0].file", "no node or mesh named 'sofa'"},
      {"bad_up_axis", edited([&](json& j) {
         j["meshes"][0] = {{"id", "box"}, {"file", fixture_dir + "two_parts.obj"}, {"up", "x"}};
       }),
       "meshes[0].up", "\"y\" or \"z\""},
      {"zero_file_scale", edited([&](json& j) {
         j["meshes"][0] = {{"id", "box"}, {"file", fixture_dir + "two_parts.obj"}, {"scale", 0}};
       }),
       "meshes[0].scale", "> 0"},
  };
}

/// Materials, objects (references, transforms, labels, instances) and point lights.
std::vector<BadLayout> objectCases() {
  return {
      {"albedo_above_one", edited([](json& j) {
         j["materials"][0]["albedo"] = {0.5, 1.5, 0.5};
       }),
       "materials[0].albedo", "[0, 1]"},
      {"unknown_material_type", edited([](json& j) { j["materials"][0]["type"] = "glass"; }),
       "materials[0].type", "valid: lambertian"},
      {"negative_emission", edited([](json& j) {
         j["materials"][0]["emission"] = {1, -1, 1};
       }),
       "materials[0].emission", ">= 0"},
      {"albedo_two_channels", edited([](json& j) {
         j["materials"][0]["albedo"] = {0.5, 0.5};
       }),
       "materials[0].albedo", "array of 3 numbers"},
      {"unknown_mesh_ref", edited([](json& j) { j["objects"][0]["mesh"] = "crate_mesh"; }),
       "objects[0].mesh", "unknown mesh id 'crate_mesh' (defined: box)"},
      {"unknown_material_ref", edited([](json& j) { j["objects"][0]["material"] = "black"; }),
       "objects[0].material", "unknown material id 'black'"},
      {"transform_15_numbers", edited([](json& j) { j["objects"][0]["transform"].erase(15); }),
       "objects[0].transform", "array of 16 numbers"},
      {"transform_string_element", edited([](json& j) { j["objects"][0]["transform"][3] = "2"; }),
       "objects[0].transform[3]", "expected a number"},
      {"mirror_transform", edited([](json& j) {
         j["objects"].push_back(j["objects"][0]);
         j["objects"][1]["transform"][0] = -1;
       }),
       "objects[1] ('crate').transform", "mirror"},
      {"zero_scale_transform", edited([](json& j) { j["objects"][0]["transform"][10] = 0; }),
       "objects[0] ('crate').transform", "zero"},
      {"unknown_category", edited([](json& j) {
         j["objects"][0].erase("nyu40");
         j["objects"][0]["category"] = "crate";
       }),
       "objects[0].category", "valid: void, wall, floor"},
      {"nyu40_out_of_range", edited([](json& j) { j["objects"][0]["nyu40"] = 41; }),
       "objects[0].nyu40", "outside 0..40"},
      {"label_disagreement", edited([](json& j) { j["objects"][0]["category"] = "bed"; }),
       "objects[0].category", "'bed' is NYU40 id 4, but \"nyu40\" says 29 ('box')"},
      {"no_label", edited([](json& j) { j["objects"][0].erase("nyu40"); }), "objects[0]",
       "needs \"nyu40\""},
      {"instance_zero", edited([](json& j) { j["objects"][0]["instance"] = 0; }),
       "objects[0].instance", "outside 1..65535"},
      {"instance_too_big", edited([](json& j) { j["objects"][0]["instance"] = 65536; }),
       "objects[0].instance", "outside 1..65535"},
      {"instance_fraction", edited([](json& j) { j["objects"][0]["instance"] = 1.5; }),
       "objects[0].instance", "expected an integer"},
      {"empty_object_name", edited([](json& j) { j["objects"][0]["name"] = ""; }),
       "objects[0].name", "must not be empty"},
      {"negative_light", edited([](json& j) { j["lights"][0]["intensity"] = -1; }),
       "lights[0].intensity", ">= 0"},
      {"light_unknown_key", edited([](json& j) { j["lights"][0]["wattage"] = 60; }),
       "lights[0].wattage", "valid keys here: name, type, position, intensity"},
      {"negative_bulb_radius", edited([](json& j) { j["lights"][0]["radius"] = -0.01; }),
       "('bulb').radius", ">= 0"},
      {"light_unknown_type", edited([](json& j) { j["lights"][0]["type"] = "laser"; }),
       "lights[0].type", "valid: point, spot, sun, sky"},
      {"light_cold_temperature", edited([](json& j) { j["lights"][0]["temperature_k"] = 10; }),
       "temperature_k", "1000..40000"},
      {"spot_without_cone", edited([](json& j) {
         j["lights"][0]["type"] = "spot";
         j["lights"][0]["direction"] = json::array({0, 0, -1});
       }),
       "lights[0].cone_deg", "missing required key"},
      {"unknown_metal", edited([](json& j) {
         j["materials"][0] =
             json::parse(R"({"id": "white", "type": "conductor", "metal": "unobtainium"})");
       }),
       "metal", "valid: gold, silver, copper, aluminium, chromium"},
      {"roughness_above_one", edited([](json& j) {
         j["materials"][0] = json::parse(
             R"({"id": "white", "type": "plastic", "albedo": [0.5, 0.5, 0.5], "roughness": 2})");
       }),
       "roughness", "[0, 1]"},
      {"albedo_on_glass", edited([](json& j) {
         j["materials"][0] =
             json::parse(R"({"id": "white", "type": "dielectric", "albedo": [0.5, 0.5, 0.5]})");
       }),
       "materials[0].albedo", "unknown key"},
      {"translucent_energy", edited([](json& j) {
         j["materials"][0] = json::parse(
             R"({"id": "white", "type": "translucent", "albedo": [0.8, 0.8, 0.8], "transmittance": [0.5, 0.5, 0.5]})");
       }),
       "materials", "<= 1"},
      {"light_on_not_bool", edited([](json& j) { j["lights"][0]["on"] = 1; }), "lights[0].on",
       "expected true or false"},
      {"objects_not_array", edited([](json& j) { j["objects"] = json::object(); }), "objects",
       "expected an array"},
      {"motion_times_fall", edited([](json& j) {
         j["objects"][0]["motion"] = json::parse(
             R"([{"t": 1, "translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
                 {"t": 0.5, "translation": [1, 0, 0], "rotation": [1, 0, 0, 0]}])");
       }),
       "objects[0].motion[1].t", "increase strictly"},
      {"motion_quaternion_not_unit", edited([](json& j) {
         j["objects"][0]["motion"] =
             json::parse(R"([{"t": 0, "translation": [0, 0, 0], "rotation": [1, 1, 0, 0]}])");
       }),
       "objects[0].motion[0].rotation", "unit quaternion"},
      {"motion_empty", edited([](json& j) { j["objects"][0]["motion"] = json::array(); }),
       "objects[0].motion", "at least one keyframe"},
      {"moving_light", edited([](json& j) {
         j["materials"][0]["emission"] = {1, 1, 1};
         j["objects"][0]["motion"] =
             json::parse(R"([{"t": 0, "translation": [0, 0, 1], "rotation": [1, 0, 0, 0]}])");
       }),
       "objects[0] ('crate').motion", "emissive object cannot move"},
      {"missing_texture", edited([](json& j) { j["materials"][0]["albedo_texture"] = "no.png"; }),
       "materials[0].albedo_texture", "no.png': file not found"},
      {"texture_is_a_folder", edited([](json& j) { j["materials"][0]["normal_texture"] = "."; }),
       "materials[0].normal_texture", "is not a file"},
      {"roughness_map_on_lambertian",
       edited([](json& j) { j["materials"][0]["roughness_texture"] = "r.png"; }),
       "materials[0].roughness_texture", "unknown key"},
      {"uv_scale_zero", edited([](json& j) {
         j["materials"][0]["uv_scale"] = {1, 0};
       }),
       "materials[0].uv_scale", "must not be 0"},
      {"uvs_count", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"},
                           {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                           {"triangles", {{0, 1, 2}}},
                           {"uvs", {{0, 0}, {1, 0}}}};
       }),
       "meshes[0].uvs", "2 entries for 3 vertices"},
      {"sky_turbidity_1", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["turbidity"] = 1;
       }),
       "lights[0] ('sky').turbidity", "1 is outside 2..10"},
      {"sky_turbidity_11", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["turbidity"] = 11;
       }),
       "lights[0] ('sky').turbidity", "11 is outside 2..10"},
      {"sky_without_sun", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0].erase("sun_direction");
       }),
       "lights[0].sun_direction", "missing required key"},
      {"sky_sun_not_unit", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["sun_direction"] = {0, 0.6, -0.9};
       }),
       "lights[0] ('sky').sun_direction", "must be a unit vector"},
      {"sky_sun_below_horizon", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["sun_direction"] = {0, 0.6, 0.8};
       }),
       "lights[0] ('sky').sun_direction", "above the horizon"},
      {"sky_model_hosek", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["model"] = "hosek";
       }),
       "lights[0].model", "unknown sky model 'hosek' (valid: uniform, preetham, envmap)"},
      {"sky_preetham_color", edited([](json& j) {
         j["lights"][0] = preethamSky();
         j["lights"][0]["color"] = {1, 1, 1};
       }),
       "lights[0].color", "unknown key"},
      {"sky_uniform_turbidity", edited([](json& j) {
         j["lights"][0] =
             json::parse(R"({"name": "sky", "type": "sky", "intensity": 1, "turbidity": 3})");
       }),
       "lights[0].turbidity", "unknown key"},
      {"zero_normal", edited([](json& j) {
         j["meshes"][0] = {{"id", "box"},
                           {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                           {"triangles", {{0, 1, 2}}},
                           {"normals", {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}}}};
       }),
       "meshes[0].normals[1]", "must not be zero"},
  };
}

std::vector<BadLayout> badLayouts() {
  std::vector<BadLayout> all = headerCases();
  for (auto more : {meshCases(), objectCases()}) all.insert(all.end(), more.begin(), more.end());
  return all;
}

TEST(LayoutJson, BaseLayoutOfTheErrorTableIsValid) {
  EXPECT_NO_THROW(parseLayout(baseLayout().dump(), "base.json"));
}

TEST(LayoutJson, MalformedLayoutsNameFileAndField) {
  TempDir dir;
  const auto cases = badLayouts();
  ASSERT_GE(cases.size(), 15u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = dir.write(c.name + ".json", c.text);
    try {
      (void)loadLayout(path);
      ADD_FAILURE() << "loaded without error";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << "starts with the file: " << msg;
      EXPECT_NE(msg.find(c.field), std::string::npos) << "field '" << c.field << "': " << msg;
      EXPECT_NE(msg.find(c.problem), std::string::npos) << "problem '" << c.problem << "': " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    }
  }
}

TEST(LayoutJson, MotionRoundTripsAndInterpolates) {
  json j = baseLayout();
  j["objects"][0]["motion"] = json::parse(R"([
      {"t": 0.5, "translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
      {"t": 2.5, "translation": [2, 0, 0.25], "rotation": [0.7071067811865476, 0, 0, 0.7071067811865476]}])");
  Scene s = parseLayout(j.dump(), "moving.json");
  const Object& o = s.objects[0];
  ASSERT_EQ(o.motion.size(), 2u);
  const std::string text = layoutToJson(s);
  EXPECT_EQ(layoutToJson(parseLayout(text, "again.json")), text);
  // before the first keyframe: held; halfway: half the translation and a 45 degree turn
  EXPECT_TRUE(o.transformAt(-1.0).isApprox(o.T_world_object));
  const Mat4 mid = o.transformAt(1.5);
  EXPECT_TRUE((mid.block<3, 1>(0, 3).isApprox(Vec3(1, 0, 0.125))));
  const Mat3 R = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).toRotationMatrix();
  EXPECT_TRUE((mid.block<3, 3>(0, 0).isApprox(R * o.T_world_object.block<3, 3>(0, 0), 1e-9)));
  EXPECT_TRUE((o.transformAt(9.0).block<3, 1>(0, 3).isApprox(Vec3(2, 0, 0.25))));
}

TEST(LayoutJson, PreethamSkyRoundTrips) {
  TempDir dir;
  json j = baseLayout();
  j["lights"].push_back(preethamSky());
  j["lights"].push_back(preethamSky());
  j["lights"][2]["name"] = "default_turbidity";
  j["lights"][2].erase("turbidity");
  j["lights"][2]["sun_direction"] = {0.48, 0.6, -0.64};
  j["lights"].push_back(
      json::parse(R"({"name": "grey", "type": "sky", "model": "uniform", "intensity": 0.5})"));
  const std::string path = dir.write("sky.json", j.dump(1));
  Scene s = loadLayout(path);
  ASSERT_EQ(s.lights.size(), 4u);
  const Light& sky = s.lights[1];
  EXPECT_EQ(sky.type, LightType::Sky);
  EXPECT_EQ(sky.sky_model, SkyModel::Preetham);
  EXPECT_EQ(sky.turbidity, 4.f);
  EXPECT_EQ(sky.direction, Vec3(0, 0.6, -0.8)) << "kept as written";
  EXPECT_EQ(sky.intensity, 90.f);
  EXPECT_EQ(s.lights[2].turbidity, 3.f) << "default";
  EXPECT_EQ(s.lights[3].sky_model, SkyModel::Uniform);
  // load -> save -> load -> save: the same bytes; a uniform sky writes no model
  const std::string saved1 = (dir.path() / "saved1.json").string();
  saveLayout(s, saved1);
  Scene s2 = loadLayout(saved1);
  const std::string saved2 = (dir.path() / "saved2.json").string();
  saveLayout(s2, saved2);
  const std::string text = readTextFile(saved1);
  EXPECT_EQ(text, readTextFile(saved2));
  expectScenesEqual(s, s2);
  EXPECT_NE(text.find("\"model\": \"preetham\",\n      \"sun_direction\": [0, 0.6, -0.8],\n      "
                      "\"turbidity\": 4,\n      \"intensity\": 90,\n      \"on\": true"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("\"model\": \"uniform\""), std::string::npos) << "the default is left out";
}

TEST(LayoutJson, RoomsKindsPartsPhysicsAndLightBindingRoundTrip) {
  json j = baseLayout();
  j["rooms"] = json::parse(
      R"([{"id": "lr", "type": "living_room", "outline": [[0, 0], [4, 0], [4, 3.5], [0, 3.5]],
           "floor_z": 0, "ceiling_z": 2.65}])");
  j["objects"][0]["kind"] = "storage_box";
  j["objects"][0]["part"] = "lid";
  j["objects"][0]["room"] = "lr";
  j["objects"][0]["physics"] = {{"mass_kg", 2.5}, {"friction", 0.15}, {"movable", true}};
  j["lights"][0]["object"] = "crate";
  Scene s = parseLayout(j.dump(), "rooms.json");
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_DOUBLE_EQ(s.rooms[0].area(), 14.0);
  EXPECT_TRUE(s.rooms[0].contains(1, 1));
  EXPECT_FALSE(s.rooms[0].contains(5, 1));
  const Object& o = s.objects[0];
  EXPECT_EQ(o.kind, "storage_box");
  EXPECT_EQ(o.part, "lid");
  EXPECT_EQ(o.room, 0);
  ASSERT_TRUE(o.physics.has_value());
  EXPECT_EQ(*o.physics, (PhysicsProps{2.5f, 0.15f, true}));
  EXPECT_EQ(s.lights[0].object, "crate");
  const std::string text = layoutToJson(s);
  EXPECT_EQ(layoutToJson(parseLayout(text, "again.json")), text);
  // a layout without these keys writes none of them (older files keep their bytes)
  const std::string plain = layoutToJson(parseLayout(baseLayout().dump(), "base.json"));
  for (const char* key : {"\"rooms\"", "\"kind\"", "\"physics\"", "\"object\""})
    EXPECT_EQ(plain.find(key), std::string::npos) << key;
}

TEST(LayoutJson, MissingLayoutFile) {
  TempDir dir;
  const std::string path = (dir.path() / "nowhere.json").string();
  try {
    (void)loadLayout(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.json"), std::string::npos);
  }
}

TEST(Room, ContainsWithinATolerance) {
  Room r;
  r.outline = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  EXPECT_TRUE(r.contains(2, 1, 0.01));         // inside
  EXPECT_TRUE(r.contains(4.009, 1, 0.01));     // 9 mm past an edge
  EXPECT_FALSE(r.contains(4.011, 1, 0.01));    // 11 mm past it
  EXPECT_TRUE(r.contains(4.006, 3.006, 0.01));   // 8.5 mm from a corner
  EXPECT_FALSE(r.contains(4.008, 3.008, 0.01));  // 11.3 mm from it
  EXPECT_FALSE(r.contains(4.009, 1, 0.0));
}

}  // namespace
}  // namespace inet
