// glTF export: round trip through our own importer (Assimp) and tinygltf's reader, the unit
// conversions, motion as animations, and Blender's importer when Blender is installed.
#include "scene/gltf_export.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "../expect_input_error.h"
#include "procedural/apartment.h"
#include "render/fresnel.h"
#include "scene/assimp_importer.h"
#include "scene/primitives.h"
#include "../temp_dir.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

Apartment apartment(const fs::path& dir) {
  ApartmentOptions opt;
  opt.seed = 3;
  opt.texture_size = 64;
  return makeApartment(opt, dir, dir / "textures");
}

Scene reimport(const fs::path& file) {
  ImportOptions opt;
  opt.up = 'a';  // glTF is Y-up: detected from the extension
  return importMeshScene(file.string(), opt);
}

/// Per instance: its class and the sorted parts; the partition of objects into instances.
std::map<int, std::pair<int, std::multiset<std::string>>> instances(const Scene& s) {
  std::map<int, std::pair<int, std::multiset<std::string>>> out;
  for (const Object& o : s.objects) {
    out[o.instance].first = o.nyu40;
    out[o.instance].second.insert(o.part + "|" + o.kind);
  }
  return out;
}

void expectSameObjects(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    const Object &x = a.objects[i], &y = b.objects[i];
    SCOPED_TRACE(x.name);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.nyu40, y.nyu40);
    EXPECT_EQ(x.instance, y.instance);
    EXPECT_EQ(x.part, y.part);
    EXPECT_EQ(x.kind, y.kind);
    ASSERT_EQ(x.physics.has_value(), y.physics.has_value());
    if (x.physics) {
      EXPECT_EQ(*x.physics, *y.physics);
    }
    // every object's triangles and world-space bounds (spheres come back tessellated)
    const Mesh &mx = a.meshes[x.mesh], &my = b.meshes[y.mesh];
    if (mx.isSphere()) continue;
    ASSERT_EQ(mx.triangles.size(), my.triangles.size());
    Eigen::AlignedBox3d bx, by;
    for (const Vec3f& p : mx.positions)
      bx.extend((x.T_world_object * p.cast<double>().homogeneous()).head<3>());
    for (const Vec3f& p : my.positions)
      by.extend((y.T_world_object * p.cast<double>().homogeneous()).head<3>());
    EXPECT_LT((bx.min() - by.min()).norm(), 1e-5);
    EXPECT_LT((bx.max() - by.max()).norm(), 1e-5);
  }
  EXPECT_EQ(instances(a), instances(b));
  const auto [alo, ahi] = a.bounds();
  const auto [blo, bhi] = b.bounds();
  EXPECT_LT((alo - blo).norm(), 1e-5);
  EXPECT_LT((ahi - bhi).norm(), 1e-5);
}

/// The lights that are on (point, spot, sun; skies are not glTF lights) come back in order with
/// the same type, place, direction, RGB intensity and cone.
void expectSameLights(const Scene& a, const Scene& b) {
  std::vector<const Light*> on;
  for (const Light& l : a.lights)
    if (l.on && l.type != LightType::Sky) on.push_back(&l);
  ASSERT_EQ(on.size(), b.lights.size());
  for (size_t i = 0; i < on.size(); ++i) {
    const Light &x = *on[i], &y = b.lights[i];
    SCOPED_TRACE(x.name);
    EXPECT_EQ(x.type, y.type);
    EXPECT_LT(((x.rgbIntensity() - y.rgbIntensity()).cwiseAbs() / x.rgbIntensity().maxCoeff())
                  .maxCoeff(),
              1e-5);
    if (x.type != LightType::Sun) {
      EXPECT_LT((x.position - y.position).norm(), 1e-5);
    }
    if (x.type != LightType::Point) {
      EXPECT_LT((x.direction - y.direction).norm(), 1e-5);
    }
    if (x.type == LightType::Spot) {
      EXPECT_NEAR(x.cone_deg, y.cone_deg, 1e-3);
      EXPECT_NEAR(x.falloff_deg, y.falloff_deg, 1e-3);
    }
  }
}

TEST(GltfExport, ApartmentRoundTripsThroughOurImporter) {
  test::TempDir dir("gltf_apt");
  const Apartment apt = apartment(dir.path());
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    GltfExportOptions opt;
    opt.binary = binary;
    const fs::path out = dir / (binary ? "apt.glb" : "apt.gltf");
    const GltfExportReport r = exportGltf(apt.scene, out.string(), opt);
    EXPECT_GT(r.images, 10);
    EXPECT_GT(r.lights, 0);
    EXPECT_EQ(r.skipped_textures, 0);
    if (!binary) {
      EXPECT_TRUE(fs::exists(dir / "apt.bin"));
      EXPECT_TRUE(fs::is_directory(dir / "apt_textures"));
    }
    const Scene back = reimport(out);
    expectSameObjects(apt.scene, back);
    expectSameLights(apt.scene, back);
    // textures came along: as many textured materials after as before
    auto textured = [](const Scene& s) {
      int n = 0;
      for (const Material& m : s.materials) n += !m.albedo_texture.empty();
      return n;
    };
    EXPECT_EQ(textured(back), textured(apt.scene));
  }
}

/// Reads the file with tinygltf (the other direction of the library we write with).
tinygltf::Model load(const fs::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  const bool ok = path.extension() == ".glb"
                      ? loader.LoadBinaryFromFile(&m, &err, &warn, path.string())
                      : loader.LoadASCIIFromFile(&m, &err, &warn, path.string());
  EXPECT_TRUE(ok) << err;
  return m;
}

template <typename T>
std::vector<T> accessorData(const tinygltf::Model& m, int index) {
  const auto& a = m.accessors[index];
  const auto& v = m.bufferViews[a.bufferView];
  const int n = tinygltf::GetNumComponentsInType(a.type);
  std::vector<T> out(a.count * n);
  std::memcpy(out.data(), m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset,
              out.size() * sizeof(T));
  return out;
}

/// The one node `pick` accepts (the test fails when there is none or several).
template <class F>
const tinygltf::Node& node(const tinygltf::Model& m, F pick) {
  const tinygltf::Node* found = nullptr;
  for (const auto& n : m.nodes) {
    if (!pick(n)) continue;
    EXPECT_EQ(found, nullptr) << "two nodes match";
    found = &n;
  }
  if (!found) {
    ADD_FAILURE() << "no node matches";
    static const tinygltf::Node none;
    return none;
  }
  return *found;
}

Quat rotationOf(const tinygltf::Node& n) {
  EXPECT_EQ(n.rotation.size(), 4u) << n.name;
  if (n.rotation.size() != 4) return Quat::Identity();
  return Quat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
}

Scene smallScene() {
  Scene s;
  Mesh quad = makePrimitive("quad", {}, "test", "floor");
  quad.id = "floor_mesh";
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.meshes.push_back(quad);
  s.meshes.push_back(makePrimitive("sphere", {{"radius", 0.5}}, "test", "ball"));
  Material lam;
  lam.id = "lam";
  lam.uv_scale = {2.f, 3.f};
  Material gold;
  gold.id = "gold";
  gold.type = MaterialType::Conductor;
  gold.metal = "gold";
  gold.roughness = 0.3f;
  gold.albedo = {1.f, 1.f, 1.f};  // no tint: the base colour is the metal's own
  Material lamp;
  lamp.id = "lamp";
  lamp.emission = {20.f, 10.f, 5.f};
  s.materials = {lam, gold, lamp};
  s.objects.push_back(Object::make("floor", 0, 0, Mat4::Identity(), 2, 1));
  Mat4 T = Mat4::Identity();
  T.block<3, 1>(0, 3) = Vec3(1, 2, 0.5);
  s.objects.push_back(Object::make("ball", 1, 1, T, 40, 2));
  Object moving = Object::make("panel", 0, 2, T, 40, 3);
  Pose p;
  p.t = Vec3(0, 0, 1);
  moving.motion = {{0.0, Pose()}, {2.0, p}};
  s.objects.push_back(moving);
  Light point;
  point.name = "bulb";
  point.position = Vec3(0, 0, 2);
  point.intensity = 3.f;
  point.color = {1.f, 0.5f, 0.25f};
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0, 0.6, -0.8);
  sun.intensity = 100.f;
  Light off = point;
  off.name = "off";
  off.on = false;
  s.lights = {point, sun, off};
  return s;
}

TEST(GltfExport, UnitsAxesTexcoordsAndMotion) {
  test::TempDir dir("gltf_units");
  const Scene s = smallScene();
  GltfCamera cam;
  cam.T_world_camera = Pose::lookAt(Vec3(3, 0, 1.5), Vec3(0, 0, 1), Vec3::UnitZ()).matrix();
  GltfExportOptions opt;
  opt.camera = cam;
  const fs::path out = dir / "small.gltf";
  const GltfExportReport r = exportGltf(s, out.string(), opt);
  EXPECT_EQ(r.spheres_tessellated, 1);
  EXPECT_EQ(r.lights, 2);
  EXPECT_EQ(r.lights_off, 1);
  EXPECT_EQ(r.animations, 1);
  const tinygltf::Model m = load(out);

  // the root turns Z-up into Y-up: our +z becomes glTF's +y
  ASSERT_EQ(m.nodes[0].name, "interiornet_world");
  const Quat root = rotationOf(m.nodes[0]);
  EXPECT_LT((root * Vec3::UnitZ() - Vec3::UnitY()).norm(), 1e-12);

  // photometric lights: 683 lm/W; colour normalised to its largest channel
  ASSERT_EQ(m.lights.size(), 2u);
  EXPECT_EQ(m.lights[0].type, "point");
  EXPECT_NEAR(m.lights[0].intensity, 683.0 * 3.0, 1e-9);
  EXPECT_NEAR(m.lights[0].color[1], 0.5, 1e-7);
  EXPECT_EQ(m.lights[1].type, "directional");
  EXPECT_NEAR(m.lights[1].intensity, 683.0 * 100.0, 1e-6);
  // the sun's node -z is our direction
  const tinygltf::Node& sun_node = node(m, [](const tinygltf::Node& n) { return n.name == "sun"; });
  const Quat qs = rotationOf(sun_node);
  EXPECT_LT((qs * -Vec3::UnitZ() - Vec3(0, 0.6, -0.8)).norm(), 1e-9);

  // emission as radiance: factor x strength
  const auto& lamp = m.materials[2];
  ASSERT_EQ(lamp.name, "lamp");
  const double strength =
      lamp.extensions.at("KHR_materials_emissive_strength").Get("emissiveStrength").GetNumberAsDouble();
  EXPECT_NEAR(lamp.emissiveFactor[1] * strength, 10.0, 1e-5);

  // the gold conductor: metallic, base colour = F0 of render/fresnel.h's complex IOR
  const auto& gold = m.materials[1];
  EXPECT_EQ(gold.pbrMetallicRoughness.metallicFactor, 1.0);
  const ComplexIor ior = metalIor(Metal::Gold);
  for (int c = 0; c < 3; ++c) {
    const float e = ior.eta[c], k = ior.k[c];
    const float f0 = ((e - 1) * (e - 1) + k * k) / ((e + 1) * (e + 1) + k * k);
    EXPECT_NEAR(gold.pbrMetallicRoughness.baseColorFactor[c], f0, 0.01) << c;
  }

  // texture coordinates: scaled by the material's uv_scale, v flipped for glTF
  const auto& floor_prim = m.meshes[m.nodes[1].mesh].primitives[0];
  const std::vector<float> uv = accessorData<float>(m, floor_prim.attributes.at("TEXCOORD_0"));
  ASSERT_EQ(uv.size(), 8u);
  EXPECT_FLOAT_EQ(uv[2 * 2 + 0], 2.f);       // (1, 1) -> (2, 1 - 3)
  EXPECT_FLOAT_EQ(uv[2 * 2 + 1], 1.f - 3.f);
  EXPECT_FLOAT_EQ(uv[0 * 2 + 1], 1.f);       // (0, 0) -> (0, 1)

  // node extras
  EXPECT_EQ(m.nodes[1].extras.Get("nyu40").GetNumberAsInt(), 2);
  EXPECT_EQ(m.nodes[1].extras.Get("nyu40_name").Get<std::string>(), "floor");

  // the moving object: a parent with two LINEAR channels over the keyframe times
  ASSERT_EQ(m.animations.size(), 1u);
  const auto& anim = m.animations[0];
  ASSERT_EQ(anim.channels.size(), 2u);
  const std::vector<float> times = accessorData<float>(m, anim.samplers[0].input);
  EXPECT_EQ(times, (std::vector<float>{0.f, 2.f}));
  const std::vector<float> xyz = accessorData<float>(m, anim.samplers[0].output);
  EXPECT_EQ(xyz, (std::vector<float>{0, 0, 0, 0, 0, 1}));
  const auto& parent = m.nodes[anim.channels[0].target_node];
  ASSERT_EQ(parent.children.size(), 1u);
  EXPECT_EQ(m.nodes[parent.children[0]].name, "panel");

  // the camera looks along glTF -z = our look direction
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_NEAR(m.cameras[0].perspective.yfov, 2 * std::atan(240.0 / 600.0), 1e-12);
  const Quat qc = rotationOf(node(m, [](const tinygltf::Node& n) { return n.camera == 0; }));
  EXPECT_LT((qc * -Vec3::UnitZ() - Vec3(-3, 0, -0.5).normalized()).norm(), 1e-9);

  // Assimp (our importer) reads a file with a camera too
  const Scene back = reimport(out);
  EXPECT_EQ(back.objects.size(), s.objects.size());
  EXPECT_EQ(back.lights.size(), 2u);

  // extensions declared
  std::set<std::string> used(m.extensionsUsed.begin(), m.extensionsUsed.end());
  EXPECT_TRUE(used.count("KHR_lights_punctual"));
  EXPECT_TRUE(used.count("KHR_materials_emissive_strength"));
}

TEST(GltfExport, RefusesAWrongExtensionAndWritesNothing) {
  test::TempDir dir("gltf_bad");
  const Scene s = smallScene();
  GltfExportOptions opt;
  opt.binary = true;
  const InputError e = test::expectInputError([&] { exportGltf(s, (dir / "x.gltf").string(), opt); });
  EXPECT_NE(std::string(e.what()).find("x.gltf"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find(".glb"), std::string::npos) << e.what();
  EXPECT_FALSE(fs::exists(dir / "x.gltf"));
}

/// Blender's own importer (io_scene_gltf2) through bench/cycles_gltf.py --summary: the same
/// objects, instances, classes and bounds as our scene.
TEST(GltfExport, LoadsInBlender) {
  if (std::system("blender --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "Blender is not installed (Debian: apt install blender, or "
                    "scripts/setup.sh peers)";
  test::TempDir dir("gltf_blender");
  const Apartment apt = apartment(dir.path());
  const fs::path glb = dir / "apt.glb", summary = dir / "summary.json";
  GltfExportOptions opt;
  opt.binary = true;
  exportGltf(apt.scene, glb.string(), opt);
  const std::string cmd = "blender -b --factory-startup -P '" INET_SOURCE_DIR
                          "/bench/cycles_gltf.py' -- --gltf '" +
                          glb.string() + "' --summary '" + summary.string() + "' > '" +
                          (dir / "blender.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << cmd;
  std::ifstream in(summary);
  ASSERT_TRUE(in) << "Blender wrote no summary";
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["objects"].get<size_t>(), apt.scene.objects.size());
  std::map<int, int> parts;
  std::set<int> inst;
  for (const Object& o : apt.scene.objects) {
    ++parts[o.nyu40];
    inst.insert(o.instance);
  }
  EXPECT_EQ(j["instances"].get<size_t>(), inst.size());
  for (const auto& [cls, n] : parts) EXPECT_EQ(j["parts_per_class"][std::to_string(cls)], n) << cls;
  int on = 0;
  for (const Light& l : apt.scene.lights) on += l.on && l.type != LightType::Sky;
  EXPECT_EQ(j["lights"].get<int>(), on);
  const auto [lo, hi] = apt.scene.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["bounds_min"][k].get<double>(), lo[k], 1e-4);
    EXPECT_NEAR(j["bounds_max"][k].get<double>(), hi[k], 1e-4);
  }
}

}  // namespace
}  // namespace inet
