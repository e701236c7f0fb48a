// Mesh-file import: objects, labels, materials, axes, instancing, errors; plus the benchmark room
// and a SceneNet layout from ../shared when present.
#include "scene/assimp_importer.h"

#include "core/image_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/nyu40.h"
#include "scene_test_util.h"

namespace inet {
namespace {

using test::errorOf;
using test::fixture;
using test::TempDir;

int id(const char* name) {
  return *nyu40FromName(name);
}

int findObject(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.objects.size(); ++i)
    if (s.objects[i].name == name) return static_cast<int>(i);
  return -1;
}

/// World-space position of vertex `v` of object `o`.
Vec3 worldVertex(const Scene& s, const Object& o, int v) {
  Vec3 p = s.meshes[o.mesh].positions[v].cast<double>();
  return (o.T_world_object * p.homogeneous()).head<3>();
}

/// Geometric normal of triangle `t` of object `o`, in world space.
Vec3 worldNormal(const Scene& s, const Object& o, int t) {
  const Tri& tri = s.meshes[o.mesh].triangles[t];
  Vec3 a = worldVertex(s, o, tri[0]), b = worldVertex(s, o, tri[1]), c = worldVertex(s, o, tri[2]);
  return (b - a).cross(c - a).normalized();
}

TEST(AssimpImporter, ObjObjectsMaterialsAndLabels) {
  ImportReport report;
  Scene s = importMeshScene(fixture("two_parts.obj").string(), {}, &report);
  EXPECT_EQ(s.name, "two_parts");
  ASSERT_EQ(s.objects.size(), 2u);
  const Object& chair = s.objects[0];
  const Object& panel = s.objects[1];
  EXPECT_EQ(chair.name, "chair_01");
  EXPECT_EQ(panel.name, "glow_panel");
  EXPECT_EQ(chair.nyu40, id("chair"));
  EXPECT_EQ(panel.nyu40, id("otherprop"));  // default_category
  EXPECT_EQ(chair.instance, 1);
  EXPECT_EQ(panel.instance, 2);
  EXPECT_EQ(s.triangleCount(), 3u);
  EXPECT_TRUE(chair.T_world_object.isIdentity());
  // materials exactly as the MTL states them (Kd linear albedo, Ke radiance)
  const Material& red = s.materials[chair.material];
  const Material& glow = s.materials[panel.material];
  EXPECT_EQ(red.id, "red_fabric");
  EXPECT_EQ(red.albedo, Vec3f(0.55f, 0.1f, 0.1f));
  EXPECT_FALSE(red.isEmissive());
  EXPECT_EQ(glow.emission, Vec3f(12.f, 11.5f, 10.5f));
  EXPECT_EQ(glow.albedo, Vec3f(0.f, 0.f, 0.f));
  EXPECT_EQ(s.materials.size(), 2u) << "unused DefaultMaterial is not imported";
  // winding preserved: the panel at z = 2 faces down (f 5 7 6)
  EXPECT_NEAR(worldNormal(s, panel, 0).z(), -1.0, 1e-9);
  EXPECT_NEAR(worldNormal(s, chair, 0).z(), 1.0, 1e-9);
  // one summary for the unmatched name
  EXPECT_EQ(report.objects, 2u);
  EXPECT_EQ(report.unmatched_objects, 1u);
  EXPECT_EQ(report.unmatched_names, std::vector<std::string>{"glow_panel"});
  std::string summary = report.summary("otherprop");
  EXPECT_NE(summary.find("glow_panel"), std::string::npos) << summary;
  EXPECT_NE(summary.find("'otherprop'"), std::string::npos) << summary;
  EXPECT_EQ(summary.find('\n'), std::string::npos);
  EXPECT_EQ(ImportReport().summary("otherprop"), "");
}

TEST(AssimpImporter, LabelMapAndDefaultCategoryOptions) {
  TempDir dir;
  ImportOptions opt;
  opt.label_map = dir.write("labels.csv", "glow,lamp\n");
  ImportReport report;
  Scene s = importMeshScene(fixture("two_parts.obj").string(), opt, &report);
  EXPECT_EQ(s.objects[1].nyu40, id("lamp"));
  EXPECT_EQ(report.unmatched_objects, 0u);

  ImportOptions fallback;
  fallback.default_category = "otherfurniture";
  EXPECT_EQ(importMeshScene(fixture("two_parts.obj").string(), fallback).objects[1].nyu40,
            id("otherfurniture"));

  ImportOptions bad;
  bad.default_category = "gizmo";
  std::string e = errorOf([&] { importMeshScene(fixture("two_parts.obj").string(), bad); });
  EXPECT_NE(e.find("default_category"), std::string::npos) << e;
  EXPECT_NE(e.find("otherprop"), std::string::npos) << "lists the valid names: " << e;

  ImportOptions bad_map;
  bad_map.label_map = dir.write("bad.csv", "glow,lamp\nglow\n");
  e = errorOf([&] { importMeshScene(fixture("two_parts.obj").string(), bad_map); });
  EXPECT_NE(e.find("bad.csv: line 2"), std::string::npos) << e;
}

TEST(AssimpImporter, YUpAndScaleConversion) {
  TempDir dir;
  // one triangle in a Y-up file, in centimetres
  std::string path = dir.write("yup.obj", "o shelf\nv 0 0 0\nv 100 0 0\nv 0 200 -300\nf 1 2 3\n");
  ImportOptions opt;
  opt.up = 'y';
  opt.scale = 0.01;
  Scene s = importMeshScene(path, opt);
  ASSERT_EQ(s.objects.size(), 1u);
  // +Y -> +Z, +Z -> -Y: (0, 200, -300) cm -> (0, 3, 2) m
  EXPECT_TRUE(worldVertex(s, s.objects[0], 2).isApprox(Vec3(0, 3, 2), 1e-6));
  EXPECT_TRUE(worldVertex(s, s.objects[0], 1).isApprox(Vec3(1, 0, 0), 1e-6));
  // a proper rotation keeps the winding: file normal (100,0,0) x (0,200,-300) ~ (0,3,2),
  // rotated (x, y, z) -> (x, -z, y) gives (0, -2, 3)
  EXPECT_TRUE(worldNormal(s, s.objects[0], 0).isApprox(Vec3(0, -2, 3).normalized(), 1e-6));
  ImportOptions bad;
  bad.up = 'x';
  EXPECT_NE(errorOf([&] { importMeshScene(path, bad); }).find("up axis"), std::string::npos);
  bad.up = 'z';
  bad.scale = 0;
  EXPECT_NE(errorOf([&] { importMeshScene(path, bad); }).find("scale"), std::string::npos);
}

TEST(AssimpImporter, PlyFile) {
  TempDir dir;
  std::string path = dir.write("quad.ply",
                               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  Scene s = importMeshScene(path, {});
  EXPECT_EQ(s.triangleCount(), 2u);  // the quad is triangulated
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].instance, 1);
}

TEST(AssimpImporter, GltfNodeTransformsAndSharedMeshes) {
  Scene s = importMeshScene(fixture("instanced.gltf").string(), {});
  ASSERT_EQ(s.objects.size(), 3u);
  const Object& a = s.objects[findObject(s, "table_a")];
  const Object& b = s.objects[findObject(s, "table_b")];
  const Object& m = s.objects[findObject(s, "mirror_x")];
  EXPECT_EQ(a.mesh, b.mesh) << "nodes referencing one aiMesh share one Mesh";
  EXPECT_NE(m.mesh, a.mesh) << "a mirrored instance is baked into its own mesh";
  EXPECT_TRUE(m.T_world_object.isIdentity());
  EXPECT_EQ(s.meshes.size(), 2u);
  // the triangle is (0,0,0), (1,0,0), (0,1,0); node translations as written in the file
  EXPECT_TRUE(worldVertex(s, a, 1).isApprox(Vec3(2, 0, 0)));
  EXPECT_TRUE(worldVertex(s, b, 2).isApprox(Vec3(0, 1, 2)));
  // mirror_x: scale (-1, 1, 1) under the parent's translation (0, 5, 0)
  std::set<std::tuple<double, double, double>> got;
  for (int v = 0; v < 3; ++v) {
    Vec3 p = worldVertex(s, m, v);
    got.insert({p.x(), p.y(), p.z()});
  }
  std::set<std::tuple<double, double, double>> want = {{0, 5, 0}, {-1, 5, 0}, {0, 6, 0}};
  EXPECT_EQ(got, want);
  // a mirror must not turn the surface inside out: the normal still points to +z
  EXPECT_NEAR(worldNormal(s, m, 0).z(), 1.0, 1e-9);
  EXPECT_NEAR(worldNormal(s, a, 0).z(), 1.0, 1e-9);
  EXPECT_EQ(s.materials[a.material].albedo, Vec3f(0.5f, 0.25f, 0.125f));
  std::set<int> instances = {a.instance, b.instance, m.instance};
  EXPECT_EQ(instances, (std::set<int>{1, 2, 3}));
}

TEST(AssimpImporter, GltfYUpConjugatesNodeTransforms) {
  ImportOptions opt;
  opt.up = 'y';
  Scene s = importMeshScene(fixture("instanced.gltf").string(), opt);
  const Object& b = s.objects[findObject(s, "table_b")];
  // file point (0,1,0) + translation (0,0,2) = (0,1,2) (Y up) -> (0,-2,1) (Z up)
  EXPECT_TRUE(worldVertex(s, b, 2).isApprox(Vec3(0, -2, 1)));
  EXPECT_TRUE((b.T_world_object.block<3, 3>(0, 0).isIdentity())) << "still a pure translation";
}

TEST(AssimpImporter, ErrorsNameTheFile) {
  TempDir dir;
  std::string e = errorOf([&] { importMeshScene((dir.path() / "nope.obj").string(), {}); });
  EXPECT_NE(e.find("nope.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("not found"), std::string::npos) << e;

  e = errorOf([&] { importMeshScene(fixture("malformed.obj").string(), {}); });
  EXPECT_NE(e.find("malformed.obj"), std::string::npos) << e;
  // our OBJ pre-pass names the line (Assimp would only say "index out of range")
  EXPECT_NE(e.find("line 6"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex index 9 but only 3 vertices come before it"), std::string::npos) << e;
  // a file Assimp itself refuses: its reason is passed on
  e = errorOf([&] { importMeshScene(dir.write("garbage.ply", "ply\nformat nonsense\n"), {}); });
  EXPECT_NE(e.find("garbage.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot import"), std::string::npos) << e;

  e = errorOf([&] { importMeshScene(dir.write("empty.obj", ""), {}); });
  EXPECT_NE(e.find("empty.obj"), std::string::npos) << e;

  e = errorOf([&] { importMeshScene(dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"), {}); });
  EXPECT_NE(e.find("lines.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("no triangles"), std::string::npos) << e;

  e = errorOf([&] { importMeshScene(dir.path().string(), {}); });
  EXPECT_NE(e.find("folder"), std::string::npos) << e;
}

TEST(AssimpImporter, LoadMeshFileMergesOrPicksByName) {
  const std::string path = fixture("two_parts.obj").string();
  Mesh all = loadMeshFile(path, 1.0, 'z', "", "layout.json", "meshes[0].file");
  EXPECT_EQ(all.triangles.size(), 3u);
  EXPECT_EQ(all.positions.size(), 7u);
  EXPECT_EQ(all.source.kind, MeshSource::Kind::File);
  Mesh chair = loadMeshFile(path, 2.0, 'z', "chair_01", "layout.json", "meshes[0].file");
  EXPECT_EQ(chair.triangles.size(), 2u);
  EXPECT_EQ(chair.source.mesh_name, "chair_01");
  EXPECT_EQ(chair.source.scale, 2.0);
  float max_x = 0;
  for (const auto& p : chair.positions) max_x = std::max(max_x, p.x());
  EXPECT_EQ(max_x, 2.0f);

  std::string e =
      errorOf([&] { loadMeshFile(path, 1, 'z', "sofa", "layout.json", "meshes[4].file"); });
  EXPECT_NE(e.find("layout.json: meshes[4].file:"), std::string::npos) << e;
  EXPECT_NE(e.find("chair_01, glow_panel"), std::string::npos) << "lists the names: " << e;
  e = errorOf([&] {
    loadMeshFile(fixture("malformed.obj").string(), 1, 'z', "", "layout.json", "meshes[1].file");
  });
  EXPECT_NE(e.find("layout.json: meshes[1].file:"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed.obj"), std::string::npos) << e;
}

TEST(AssimpImporter, BenchmarkRoom) {
  const auto room = test::sharedDir() / "bench" / "room.obj";
  if (!std::filesystem::exists(room)) GTEST_SKIP() << "needs ../shared/bench/room.obj (absent)";
  ImportOptions opt;
  opt.label_map = fixture("room_labels.csv").string();
  ImportReport report;
  Scene s = importMeshScene(room.string(), opt, &report);
  EXPECT_EQ(s.triangleCount(), 183798u);
  std::set<std::string> names;
  std::set<int> instances;
  for (const auto& o : s.objects) {
    names.insert(o.name);
    instances.insert(o.instance);
  }
  EXPECT_EQ(names.size(), 28u);
  EXPECT_EQ(instances.size(), 28u);
  EXPECT_EQ(*instances.begin(), 1);
  EXPECT_EQ(*instances.rbegin(), 28);
  // exactly one emitter, with the MTL's Ke
  int emissive = 0;
  for (const auto& o : s.objects) {
    if (!s.materials[o.material].isEmissive()) continue;
    ++emissive;
    EXPECT_EQ(o.name, "ceiling_light");
    EXPECT_EQ(s.materials[o.material].emission, Vec3f(12.f, 11.5f, 10.5f));
    EXPECT_NEAR(worldNormal(s, o, 0).z(), -1.0, 1e-6) << "the light faces down";
  }
  EXPECT_EQ(emissive, 1);
  auto [lo, hi] = s.bounds();
  EXPECT_LT(lo.norm(), 1e-6);
  EXPECT_TRUE(hi.isApprox(Vec3(5, 4, 2.7), 1e-6));
  EXPECT_EQ(s.objects[findObject(s, "bed")].nyu40, id("bed"));
  EXPECT_EQ(s.objects[findObject(s, "nightstand_left")].nyu40, id("night_stand"));
  EXPECT_EQ(s.objects[findObject(s, "table_lamp_right")].nyu40, id("lamp"));
  EXPECT_EQ(s.objects[findObject(s, "desk_chair")].nyu40, id("chair"));
  EXPECT_EQ(s.objects[findObject(s, "room_walls")].nyu40, id("wall"));
  EXPECT_EQ(report.unmatched_names, (std::vector<std::string>{"decor_ball", "decor_ring"}));
}

TEST(AssimpImporter, TexturedObjKeepsUvsNormalsAndMaps) {
  TempDir tmp;
  ImageU8 texels(2, 2, 3, 128);
  writePng(tmp.path() / "maps" / "wood.png", texels);
  writePng(tmp.path() / "maps" / "wood_n.png", texels);
  tmp.write("quad.mtl",
            "newmtl wood\nKd 0.3 0.3 0.3\nmap_Kd maps/wood.png\nnorm maps/wood_n.png\n"
            "map_bump maps/wood_n.png\n"
            "newmtl plain\nKd 0.5 0.25 0.125\nmap_Kd maps/absent.png\n");
  const std::string obj =
      tmp.write("quad.obj",
                "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
                "vt 0 0\nvt 2 0\nvt 2 1\nvt 0 1\nvn 0 -1 0\nvn 0 -1 0\nvn 0 -0.9 0.43589\n"
                "o floor\nusemtl wood\nf 1/1/1 2/2/2 3/3/3 4/4/2\n"
                "o flat\nusemtl plain\nf 1 2 3\n");
  ImportOptions opt;
  opt.up = 'y';
  ImportReport report;
  Scene s = importMeshScene(obj, opt, &report);
  const Object& floor = s.objects[findObject(s, "floor")];
  const Mesh& m = s.meshes[floor.mesh];
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    // texture coordinates follow their vertex: u = 2 x, v = file z (before the y-up turn)
    const Vec3f& p = m.positions[i];
    EXPECT_NEAR(m.uvs[i].x(), 2 * p.x(), 1e-6);
    EXPECT_NEAR(m.uvs[i].y(), -p.y(), 1e-6);  // file z = -world y after the y-up conversion
    EXPECT_NEAR(m.normals[i].norm(), 1.f, 1e-6);
    EXPECT_LT(m.normals[i].z(), -0.5f) << "file -Y becomes world -Z";
  }
  // 26 degrees off the face: a smooth surface, kept (file +Z becomes world -Y)
  EXPECT_EQ(std::count_if(m.normals.begin(), m.normals.end(),
                          [](const Vec3f& n) { return n.y() < -0.4f; }),
            1);
  const Material& wood = s.materials[floor.material];
  EXPECT_TRUE(std::filesystem::equivalent(wood.albedo_texture.path, tmp.path() / "maps/wood.png"));
  EXPECT_TRUE(
      std::filesystem::equivalent(wood.normal_texture.path, tmp.path() / "maps/wood_n.png"));
  EXPECT_EQ(wood.albedo, Vec3f::Ones()) << "an OBJ's map_Kd replaces Kd";
  const Object& flat = s.objects[findObject(s, "flat")];
  EXPECT_TRUE(s.meshes[flat.mesh].normals.empty()) << "no vn: flat shading";
  EXPECT_TRUE(s.meshes[flat.mesh].uvs.empty());
  const Material& plain = s.materials[flat.material];
  EXPECT_TRUE(plain.albedo_texture.empty()) << "missing image: skipped";
  EXPECT_EQ(plain.albedo, Vec3f(0.5f, 0.25f, 0.125f));
  EXPECT_EQ(report.skipped_textures, 1u);
  EXPECT_EQ(report.ignored_bump_maps, 1u);
  EXPECT_NE(report.summary("otherprop").find("bump"), std::string::npos);
}

TEST(AssimpImporter, SceneNetTextureFoldersPickOneImageStably) {
  const auto dir = test::sharedDir() / "data" / "scenes" / "scenenet_rgbd_layouts";
  const auto bedroom = dir / "bedroom" / "bedroom3_layout.obj";
  if (!std::filesystem::exists(bedroom))
    GTEST_SKIP() << "needs ../shared/data/scenes/scenenet_rgbd_layouts (absent)";
  ImportOptions opt;
  opt.up = 'y';
  Scene a = importMeshScene(bedroom.string(), opt), b = importMeshScene(bedroom.string(), opt);
  size_t textured = 0;
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const TextureRef& t = a.materials[i].albedo_texture;
    EXPECT_EQ(t, b.materials[i].albedo_texture) << "the same image on every run";
    if (t.empty()) continue;
    ++textured;
    // map_Kd names a folder of texture_library; the image chosen lies in it
    EXPECT_NE(t.path.find("texture_library"), std::string::npos) << t.path;
    EXPECT_TRUE(std::filesystem::is_regular_file(t.path)) << t.path;
  }
  EXPECT_GE(textured, 10u);
  const Object& wall = a.objects[findObject(a, "wall.002")];
  EXPECT_FALSE(a.meshes[wall.mesh].uvs.empty());
  // SceneNet smooths its box-shaped walls and floors over their corners (vn at 55 degrees to
  // each face); those triangles come out flat: every vertex normal equals its face normal
  const Object& floor = a.objects[findObject(a, "floor.002")];
  const Mesh& fm = a.meshes[floor.mesh];
  ASSERT_FALSE(fm.normals.empty());
  for (const Tri& t : fm.triangles) {
    const Vec3f c =
        (fm.positions[t[1]] - fm.positions[t[0]]).cross(fm.positions[t[2]] - fm.positions[t[0]]);
    if (c.norm() < 1e-3f) continue;
    for (int k = 0; k < 3; ++k) EXPECT_GT(fm.normals[t[k]].dot(c.normalized()), 0.819f);
  }
}

TEST(AssimpImporter, SceneNetLayoutIsYUp) {
  const auto dir = test::sharedDir() / "data" / "scenes" / "scenenet_rgbd_layouts";
  const auto bedroom = dir / "bedroom" / "bedroom3_layout.obj";
  if (!std::filesystem::exists(bedroom))
    GTEST_SKIP() << "needs ../shared/data/scenes/scenenet_rgbd_layouts (absent)";
  TempDir tmp;
  ImportOptions opt;
  opt.up = 'y';
  opt.label_map = tmp.write("scenenet.csv", "painting,picture\nplate,otherprop\n");
  ImportReport report;
  Scene s = importMeshScene(bedroom.string(), opt, &report);
  // 15 objects in the file; the floor and ceiling faces of wall.002 become objects of their own
  // (room_shell.h), with no triangle lost
  EXPECT_EQ(s.objects.size(), 17u);
  EXPECT_EQ(report.split_shells, 1u);
  EXPECT_EQ(s.objects[findObject(s, "wall.002_floor")].nyu40, id("floor"));
  EXPECT_EQ(s.objects[findObject(s, "wall.002_ceiling")].nyu40, id("ceiling"));
  EXPECT_EQ(s.triangleCount(), 16968u);
  EXPECT_EQ(report.unmatched_objects, 0u) << report.summary(opt.default_category);
  EXPECT_EQ(s.objects[findObject(s, "painting.004")].nyu40, id("picture"));
  EXPECT_EQ(s.objects[findObject(s, "wall.002")].nyu40, id("wall"));
  EXPECT_EQ(s.objects[findObject(s, "curtain.002")].nyu40, id("curtain"));
  // README: extent 8.2 x 2.8 (Y, height) x 6.8; floor at y ~ 0 -> z ~ 0 after conversion
  auto [lo, hi] = s.bounds();
  EXPECT_NEAR(hi.z() - lo.z(), 2.8, 0.06);
  EXPECT_NEAR(lo.z(), 0.0, 0.05);
  EXPECT_NEAR(hi.x() - lo.x(), 8.2, 0.06);
  EXPECT_NEAR(hi.y() - lo.y(), 6.8, 0.06);
  // the floor is a 1 cm slab whose top (file y = 0) faces +Y; after conversion the large top
  // triangles (z = 0) face +z and the bottom ones (z = -0.0103) face -z
  const Object& floor = s.objects[findObject(s, "floor.002")];
  int top = 0, bottom = 0;
  for (size_t t = 0; t < s.meshes[floor.mesh].triangles.size(); ++t) {
    const Tri& tri = s.meshes[floor.mesh].triangles[t];
    Vec3 a = worldVertex(s, floor, tri[0]), b = worldVertex(s, floor, tri[1]),
         c = worldVertex(s, floor, tri[2]);
    if ((b - a).cross(c - a).norm() < 2.0) continue;  // area < 1 m^2
    const double z = (a.z() + b.z() + c.z()) / 3.0;
    const double nz = worldNormal(s, floor, static_cast<int>(t)).z();
    if (std::abs(z) < 1e-4) top += nz > 0.99;
    if (std::abs(z + 0.0103) < 1e-4) bottom += nz < -0.99;
  }
  EXPECT_EQ(top, 6);
  EXPECT_EQ(bottom, 6);
}

// Issue 13 defect 6: an OBJ whose light is given only as Ka (older Cornell-box files). The
// shared McGuire box with its `Ke 17 12 4` moved to `Ka 17 12 4`: the light still emits, and the
// report says why; a Ka of at most 1 (Blender writes Ka 1 1 1 everywhere) stays a non-emitter.
TEST(AssimpImporter, AmbientAboveOneWithoutKeIsEmission) {
  const auto box = test::sharedDir() / "data" / "scenes" / "cornell_box_mcguire";
  if (!std::filesystem::exists(box / "CornellBox-Original.obj"))
    GTEST_SKIP() << "needs ../shared/data/scenes/cornell_box_mcguire (absent)";
  std::string mtl = readTextFile((box / "CornellBox-Original.mtl").string());
  // the light's block: its own Ka 0.78 goes, its Ke 17 12 4 becomes Ka 17 12 4
  const size_t light = mtl.find("newmtl light");
  ASSERT_NE(light, std::string::npos);
  const size_t ka = mtl.find("Ka 0.78 0.78 0.78", light);
  ASSERT_NE(ka, std::string::npos);
  mtl.erase(ka, mtl.find('\n', ka) + 1 - ka);
  const size_t ke = mtl.find("Ke 17 12 4", light);
  ASSERT_NE(ke, std::string::npos);
  mtl.replace(ke, 2, "Ka");
  TempDir tmp;
  tmp.write("CornellBox-Original.mtl", mtl);
  const std::string obj =
      tmp.write("box.obj", readTextFile((box / "CornellBox-Original.obj").string()));
  ImportOptions opt;
  opt.up = 'y';
  ImportReport report;
  const Scene s = importMeshScene(obj, opt, &report);
  int emitters = 0;
  for (const Object& o : s.objects) {
    const Material& m = s.materials[o.material];
    if (!m.isEmissive()) continue;
    ++emitters;
    EXPECT_EQ(o.name, "light");
    EXPECT_EQ(m.emission, Vec3f(17, 12, 4));
  }
  EXPECT_EQ(emitters, 1);
  ASSERT_EQ(report.ka_emission_materials.size(), 1u);
  EXPECT_EQ(report.ka_emission_materials[0], "light");
  const std::string line = report.summary(opt.default_category);
  EXPECT_NE(line.find("Ka"), std::string::npos) << line;
  EXPECT_NE(line.find("light"), std::string::npos) << line;
  // Blender's Ka 1 1 1 with Kd and no Ke: not a light
  tmp.write("b.mtl", "newmtl m\nKa 1 1 1\nKd 0.5 0.5 0.5\n");
  const std::string b = tmp.write("b.obj", "mtllib b.mtl\no a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                           "usemtl m\nf 1 2 3\n");
  ImportReport rb;
  const Scene sb = importMeshScene(b, ImportOptions{}, &rb);
  EXPECT_FALSE(sb.materials[0].isEmissive());
  EXPECT_TRUE(rb.ka_emission_materials.empty());
}

// --up auto: glTF is Y up; otherwise where the floor and ceiling objects face, or failing labels,
// where most triangle area faces. Each file is also checked turned to the other axis.
TEST(AssimpImporter, UpAxisIsDetected) {
  ImportOptions opt;
  opt.up = 'a';
  ImportReport report;
  importMeshScene(fixture("instanced.gltf").string(), opt, &report);
  EXPECT_EQ(report.up, 'y');
  EXPECT_NE(report.up_reason.find("glTF"), std::string::npos) << report.up_reason;
  importMeshScene(fixture("two_parts.obj").string(), opt, &report);
  EXPECT_EQ(report.up, 'z') << report.up_reason;

  // a 6 x 4 m room, 2.6 m high, written Y up (y is height) and Z up, with and without labels
  auto roomObj = [](bool y_up, bool labelled) {
    auto v = [&](double x, double d, double h) {
      return y_up ? fmt::format("v {} {} {}\n", x, h, -d) : fmt::format("v {} {} {}\n", x, d, h);
    };
    std::string s;
    const char* names[3] = {labelled ? "floor" : "part_a", labelled ? "ceiling" : "part_b",
                            labelled ? "wall" : "part_c"};
    s += std::string("o ") + names[0] + "\n" + v(0, 0, 0) + v(6, 0, 0) + v(6, 4, 0) + v(0, 4, 0) +
         "f 1 2 3\nf 1 3 4\n";
    s += std::string("o ") + names[1] + "\n" + v(0, 0, 2.6) + v(6, 0, 2.6) + v(6, 4, 2.6) +
         v(0, 4, 2.6) + "f 5 7 6\nf 5 8 7\n";
    s += std::string("o ") + names[2] + "\n" + v(0, 0, 0) + v(6, 0, 0) + v(6, 0, 2.6) +
         v(0, 0, 2.6) + "f 9 10 11\nf 9 11 12\n";
    return s;
  };
  TempDir tmp;
  for (bool labelled : {true, false})
    for (bool y_up : {true, false}) {
      SCOPED_TRACE(fmt::format("labelled {} y_up {}", labelled, y_up));
      const std::string path = tmp.write(fmt::format("room_{}_{}.obj", labelled, y_up),
                                         roomObj(y_up, labelled));
      const Scene s = importMeshScene(path, opt, &report);
      EXPECT_EQ(report.up, y_up ? 'y' : 'z') << report.up_reason;
      EXPECT_NE(report.up_reason.find(labelled ? "floor and ceiling" : "triangles"),
                std::string::npos)
          << report.up_reason;
      auto [lo, hi] = s.bounds();
      EXPECT_NEAR(hi.z() - lo.z(), 2.6, 1e-5);  // the height is z after the import
    }
}

// OBJ files as other tools write them (tinyobjloader's test models): a 4th vertex value, numbers
// with a leading dot, missing material libraries, impossible face indices named by line.
TEST(AssimpImporter, ObjQuirksOfRealFiles) {
  TempDir tmp;
  ImportReport report;
  // v x y z w: Assimp would divide by w (a 2 m triangle would become 4 m)
  const Scene w = importMeshScene(
      tmp.write("w.obj", "v 0 0 0 1\nv 2 0 0 0.5\nv 0 2 0 0.5\nf 1 2 3\n"), {}, &report);
  auto [lo, hi] = w.bounds();
  EXPECT_NEAR(hi.x(), 2.0, 1e-6);
  EXPECT_NEAR(hi.y(), 2.0, 1e-6);
  EXPECT_EQ(report.obj_w_values, 3u);
  EXPECT_NE(report.summary("otherprop").find("(w) value"), std::string::npos);
  // .5 (Assimp: "vertex index out of range"), CRLF kept
  const Scene dot = importMeshScene(
      tmp.write("dot.obj", "v 0 0 0\r\nv .5 0 0\r\nv 0 -.5 0\r\nvt .25 .75\r\nf 1 2 3\r\n"), {},
      &report);
  std::tie(lo, hi) = dot.bounds();
  EXPECT_NEAR(hi.x(), 0.5, 1e-6);
  EXPECT_NEAR(lo.y(), -0.5, 1e-6);
  EXPECT_EQ(report.obj_leading_dots, 4u);
  // a missing library: its materials are grey, and said so
  importMeshScene(tmp.write("m.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                     "usemtl red\nf 1 2 3\nusemtl green\nf 1 3 2\n"),
                  {}, &report);
  ASSERT_EQ(report.missing_mtllibs.size(), 1u);
  EXPECT_EQ(report.missing_mtllibs[0], "missing.mtl");
  EXPECT_EQ(report.grey_materials, (std::vector<std::string>{"red", "green"}));
  EXPECT_NE(report.summary("otherprop").find("missing.mtl"), std::string::npos);
  // a library found (with a space in its name): nothing to say
  tmp.write("my mats.mtl", "newmtl red\nKd 1 0 0\n");
  importMeshScene(tmp.write("ok.obj", "mtllib my mats.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "usemtl red\nf 1 2 3\n"),
                  {}, &report);
  EXPECT_TRUE(report.missing_mtllibs.empty());
  EXPECT_TRUE(report.grey_materials.empty());
  // a normal index beyond the file's normals (Sweet Home 3D's window models: `81//125` with no
  // `vn` at all): that corner is shaded without it, the file still reads
  const Scene nn = importMeshScene(
      tmp.write("nn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3//7\nf 2 4 3\n"), {},
      &report);
  EXPECT_EQ(nn.triangleCount(), 2u);
  EXPECT_EQ(report.obj_missing_normals, 1u);
  EXPECT_NE(report.summary("otherprop").find("normal the file does not have"), std::string::npos);
  // face indices that cannot be right, named by line
  for (const auto& [text, expect] : std::vector<std::pair<std::string, std::string>>{
           {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: face vertex index 0"},
           {"v 0 0 0\nv 1 0 0\nf -4 -3 -2\n", "line 3: face vertex index -4 but only 2"},
           {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/2 2/1 3/1\n",
            "line 5: face texture coordinate index 2 but only 1 texture coordinate"}}) {
    const std::string e = errorOf([&] { importMeshScene(tmp.write("bad.obj", text), {}); });
    EXPECT_NE(e.find("bad.obj: " + expect), std::string::npos) << e;
  }
}

// McGuire's archive names each group after its faces (`usemtl shortBox`, the faces, then
// `g shortBox`): before, the short box's faces fell into the group before them and the short
// box was labelled wall. Files in the usual order are not touched.
TEST(AssimpImporter, GroupNamesWrittenAfterTheirFaces) {
  TempDir tmp;
  ImportReport report;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 0 1\n";  // upright: not a floor
  const Scene late = importMeshScene(
      tmp.write("late.obj", tri + "g leftWall\nusemtl leftWall\nf 1 2 3\n"
                                  "usemtl shortBox\nf 1 3 2\ng shortBox\nusemtl shortBox\n"
                                  "usemtl door\nf 1 2 3\ng door\nusemtl door\n"),
      {}, &report);
  EXPECT_EQ(report.obj_late_groups, 2u);
  EXPECT_NE(report.summary("otherprop").find("after their faces"), std::string::npos);
  ASSERT_GE(findObject(late, "shortBox"), 0);
  EXPECT_EQ(late.objects[findObject(late, "shortBox")].nyu40, id("box"));
  ASSERT_GE(findObject(late, "door"), 0);
  EXPECT_EQ(late.objects[findObject(late, "door")].nyu40, id("door"));
  for (const Object& o : late.objects) {
    if (o.name == "leftWall") {
      EXPECT_EQ(o.nyu40, id("wall"));
    }
  }
  // the same with CRLF line ends
  std::string crlf = tri + "g leftWall\nusemtl leftWall\nf 1 2 3\nusemtl shortBox\nf 1 3 2\n"
                           "g shortBox\nusemtl shortBox\n";
  for (size_t i = crlf.find('\n'); i != std::string::npos; i = crlf.find('\n', i + 2))
    crlf.replace(i, 1, "\r\n");
  const Scene late_crlf = importMeshScene(tmp.write("late_crlf.obj", crlf), {}, &report);
  EXPECT_EQ(report.obj_late_groups, 1u);
  ASSERT_GE(findObject(late_crlf, "shortBox"), 0);
  EXPECT_EQ(late_crlf.objects[findObject(late_crlf, "shortBox")].nyu40, id("box"));
  // the usual order, and a material named after no group: nothing moves
  importMeshScene(tmp.write("usual.obj", tri + "g leftWall\nusemtl leftWall\nf 1 2 3\n"
                                         "g shortBox\nusemtl shortBox\nf 1 3 2\n"
                                         "g chair\nusemtl wood\nf 1 2 3\n"),
                  {}, &report);
  EXPECT_EQ(report.obj_late_groups, 0u);
  // the real file, when ../shared is here: both boxes are boxes, five walls/floor/ceiling
  const auto cornell =
      test::sharedDir() / "data" / "scenes" / "cornell_box_mcguire" / "CornellBox-Original.obj";
  if (!std::filesystem::exists(cornell)) GTEST_SKIP() << cornell << " not found (../shared)";
  const Scene real = importMeshScene(cornell.string(), {}, &report);
  std::set<int> boxes;
  for (const Object& o : real.objects)
    if (o.nyu40 == id("box")) boxes.insert(o.instance);
    else EXPECT_NE(o.material >= 0 ? real.materials[o.material].id : "", "shortBox") << o.name;
  EXPECT_EQ(boxes.size(), 2u);
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = static_cast<uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 2]);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

// glTF files carry their images inside (data URIs, .glb): they are written once to the cache
// and used; before, the material lost its texture ("embedded ... skipped").
TEST(AssimpImporter, EmbeddedGltfImagesAreExtractedToTheCache) {
  TempDir tmp;
  ::setenv("XDG_CACHE_HOME", (tmp.path() / "cache").c_str(), 1);
  ImageU8 img(2, 2, 3, 0);
  img.at(0, 0, 0) = 255, img.at(1, 1, 2) = 255;
  writePng(tmp.path() / "tex.png", img);
  const std::string png = readTextFile((tmp.path() / "tex.png").string());
  std::string gltf = readTextFile(fixture("instanced.gltf").string());
  const std::string factor = R"("metallicFactor": 0.0)";
  gltf.replace(gltf.find(factor), factor.size(),
               R"("metallicFactor": 0.0, "baseColorTexture": {"index": 0})");
  const std::string buffers = R"( "buffers": [)";
  gltf.replace(gltf.find(buffers), buffers.size(),
               R"( "textures": [{"source": 0}],
 "images": [{"uri": "data:image/png;base64,)" + base64(png) + R"("}],
 "buffers": [)");
  ImportReport report;
  const Scene s = importMeshScene(tmp.write("textured.gltf", gltf), {}, &report);
  EXPECT_EQ(report.embedded_textures, 1u) << report.summary("otherprop");
  EXPECT_EQ(report.skipped_textures, 0u);
  const TextureRef& t = s.materials[0].albedo_texture;
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(std::filesystem::path(t.path).parent_path(), tmp.path() / "cache" / "interiornet" / "embedded");
  EXPECT_EQ(readTextFile(t.path), png);
  ::unsetenv("XDG_CACHE_HOME");
}

TEST(AssimpImporter, AFileInMillimetresSaysWhichScaleToGive) {
  TempDir tmp;
  ImportReport report;
  importMeshScene(tmp.write("mm.obj", "v 0 0 0\nv 556 0 0\nv 0 556 0\nf 1 2 3\n"), {}, &report);
  EXPECT_NE(report.summary("otherprop").find("556 m across"), std::string::npos)
      << report.summary("otherprop");
  EXPECT_NE(report.summary("otherprop").find("--scale"), std::string::npos);
}

}  // namespace
}  // namespace inet
