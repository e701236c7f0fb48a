// Mitsuba scene import (scene/mitsuba_importer.h): every supported plugin on small fixtures
// written here into a temporary folder, the XML conventions (versions, parameters, includes,
// references, both spellings, transforms), every kind of error, and Bitterli's living room from
// ../shared when present. Expectations are derived from Mitsuba's documented conventions, not
// printed by the importer: e.g. a Y-up point (x, y, z) must land at (x, -z, y).
#include "scene/mitsuba_importer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "core/image_io.h"
#include "render/camera.h"
#include "render/fresnel.h"
#include "scene/layout_json.h"
#include "scene/nyu40.h"
#include "scene_test_util.h"

namespace inet {
namespace {

using test::errorOf;
using test::TempDir;

constexpr double kPi = 3.14159265358979323846;

/// A folder with a unit quad OBJ (y = 0 plane, normal +y, uvs), a 2x2 PNG and a 4x2 EXR.
class MitsubaFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_.write("models/quad.obj",
               "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
               "vn 0 1 0\nf 1/1/1 4/4/1 3/3/1 2/2/1\n");
    dir_.write("models/tri.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nproperty float u\nproperty float v\nelement face 1\n"
               "property list uchar int vertex_indices\nend_header\n0 0 0 0 0.25\n1 0 0 1 0.25\n"
               "0 1 0 0 1\n3 0 1 2\n");
    writePng(dir_ / "tex.png", ImageU8(2, 2, 3, 200));
    ImageF sky(4, 2, 3, 0.5f);
    writeExr(dir_ / "sky.exr", sky, {"R", "G", "B"});
  }
  /// Writes `body` inside <scene version=...> as scene.xml and returns its path.
  std::string xml(const std::string& body, const std::string& version = "3.0.0") {
    return dir_.write("scene.xml", "<scene version=\"" + version + "\">\n" + body + "\n</scene>\n");
  }
  MitsubaScene read(const std::string& body, MitsubaOptions opt = {}) {
    return readMitsubaScene(xml(body), opt);
  }
  std::string error(const std::string& body, const std::string& version = "3.0.0") {
    const std::string path = xml(body, version);
    return errorOf([&] { readMitsubaScene(path, {}); });
  }
  TempDir dir_{"mitsuba"};
};

const Material& materialOf(const Scene& s, size_t object) {
  return s.materials[s.objects.at(object).material];
}

Vec3 world(const Scene& s, size_t object, const Vec3& p) {
  return (s.objects.at(object).T_world_object * p.homogeneous()).head<3>();
}

std::string approximations(const MitsubaScene& m) {
  std::string all;
  for (const auto& a : m.report.approximations) all += a + "\n";
  return all;
}

const char* kQuad = R"(<shape type="rectangle"><bsdf type="diffuse"/></shape>)";

TEST_F(MitsubaFixture, ObjAndPlyShapesWithUpAxisAndTransform) {
  const MitsubaScene m = read(R"(
    <shape type="obj" id="floor_quad"><string name="filename" value="models/quad.obj"/>
      <transform name="to_world"><translate x="0" y="2" z="-3"/></transform></shape>
    <shape type="ply"><string name="filename" value="models/tri.ply"/></shape>)");
  const Scene& s = m.scene;
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].name, "floor_quad");
  EXPECT_EQ(s.objects[0].nyu40, *nyu40FromName("floor"));  // the shape id matches a class
  EXPECT_EQ(s.objects[0].instance, 1);
  EXPECT_EQ(s.objects[1].instance, 2);
  // Y up: the file's (x, y, z) is our (x, -z, y); the quad's corner (1, 0, 1) moved by (0, 2, -3)
  const Mesh& quad = s.meshes[s.objects[0].mesh];
  EXPECT_EQ(quad.source.kind, MeshSource::Kind::File);  // nothing changed: kept by reference
  EXPECT_EQ(quad.source.up, 'y');
  bool found = false;
  for (const Vec3f& p : quad.positions)
    if ((world(s, 0, p.cast<double>()) - Vec3(1, 2, 2)).norm() < 1e-6) found = true;
  EXPECT_TRUE(found) << "corner (1, 0, 1) + (0, 2, -3) should be at (1, 2, 2)";
  // PLY texture coordinates are in Mitsuba's image convention (v down): flipped into ours
  const Mesh& tri = s.meshes[s.objects[1].mesh];
  ASSERT_EQ(tri.uvs.size(), 3u);
  EXPECT_FLOAT_EQ(tri.uvs[0].y(), 0.75f);
  EXPECT_EQ(tri.source.kind, MeshSource::Kind::Inline);
  EXPECT_EQ(materialOf(s, 0).albedo, Vec3f::Constant(0.5f));  // Mitsuba's default BSDF
}

TEST_F(MitsubaFixture, FaceNormalsAndFlipNormals) {
  const Scene s = read(R"(
    <shape type="obj"><string name="filename" value="models/quad.obj"/>
      <boolean name="faceNormals" value="true"/></shape>
    <shape type="obj"><string name="filename" value="models/quad.obj"/>
      <boolean name="flip_normals" value="true"/></shape>)").scene;
  const Mesh& flat = s.meshes[s.objects[0].mesh];
  EXPECT_TRUE(flat.normals.empty());
  EXPECT_EQ(flat.source.kind, MeshSource::Kind::Inline);
  const Mesh& flipped = s.meshes[s.objects[1].mesh];
  const Tri& t = flipped.triangles[0];
  const Vec3f n = (flipped.positions[t[1]] - flipped.positions[t[0]])
                      .cross(flipped.positions[t[2]] - flipped.positions[t[0]]);
  EXPECT_LT(n.z(), 0.f);  // the file's +y normal is our +z; flipped it points down
  EXPECT_LT(flipped.normals[0].z(), 0.f);
}

TEST_F(MitsubaFixture, PrimitivesHaveMitsubasSizes) {
  const Scene s = read(R"(
    <shape type="rectangle"/>
    <shape type="cube"><transform name="to_world"><scale value="0.5"/></transform></shape>
    <shape type="sphere"><point name="center" x="0" y="1" z="0"/><float name="radius" value="2"/></shape>
    <shape type="disk"/>
    <shape type="cylinder"><float name="radius" value="0.25"/></shape>)").scene;
  ASSERT_EQ(s.objects.size(), 5u);
  auto bounds = [&](size_t i) {
    Scene one;
    one.meshes = s.meshes;
    one.objects = {s.objects[i]};
    return one.bounds();
  };
  // rectangle [-1, 1]^2 in the file's z = 0 plane: our y = 0 plane
  EXPECT_TRUE(bounds(0).first.isApprox(Vec3(-1, 0, -1), 1e-9));
  EXPECT_TRUE(bounds(0).second.isApprox(Vec3(1, 0, 1), 1e-9));
  EXPECT_TRUE(bounds(1).second.isApprox(Vec3(0.5, 0.5, 0.5), 1e-9));  // cube [-1, 1]^3 x 0.5
  const Mesh& sphere = s.meshes[s.objects[2].mesh];
  EXPECT_TRUE(sphere.isSphere());
  EXPECT_TRUE(world(s, 2, Vec3::Zero()).isApprox(Vec3(0, 0, 1), 1e-12));  // centre (0, 1, 0)
  EXPECT_NEAR((world(s, 2, Vec3(sphere.sphere_radius, 0, 0)) - Vec3(0, 0, 1)).norm(), 2.0, 1e-9);
  EXPECT_NEAR(bounds(3).second.x(), 1.0, 1e-6);  // disk of radius 1
  // cylinder from (0, 0, 0) to (0, 0, 1) in the file: our -y direction, radius 0.25
  EXPECT_NEAR(bounds(4).first.y(), -1.0, 1e-6);
  EXPECT_NEAR(bounds(4).second.x(), 0.25, 1e-6);
}

TEST_F(MitsubaFixture, DiffuseColoursAndTextures) {
  const Scene s = read(R"(
    <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.2, 0.3"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"><srgb name="reflectance" value="#808080"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"><spectrum name="reflectance" value="0.25"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"><spectrum name="reflectance"
        value="400:0.6, 500:0.6, 600:0.6, 700:0.6"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"><texture name="reflectance" type="bitmap">
        <string name="filename" value="tex.png"/><float name="uscale" value="4"/></texture></bsdf></shape>)").scene;
  EXPECT_TRUE(materialOf(s, 0).albedo.isApprox(Vec3f(0.1f, 0.2f, 0.3f)));
  EXPECT_NEAR(materialOf(s, 1).albedo.x(), std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
  EXPECT_EQ(materialOf(s, 2).albedo, Vec3f::Constant(0.25f));
  EXPECT_TRUE(materialOf(s, 3).albedo.isApprox(Vec3f::Constant(0.6f), 1e-4));  // flat spectrum
  const Material& textured = materialOf(s, 4);
  EXPECT_EQ(textured.albedo, Vec3f::Ones());
  EXPECT_EQ(std::filesystem::path(textured.albedo_texture.path).filename(), "tex.png");
  EXPECT_EQ(textured.uv_scale, Vec2f(4.f, 1.f));
}

TEST_F(MitsubaFixture, PlasticConductorDielectricFamilies) {
  const MitsubaScene m = read(R"(
    <shape type="rectangle"><bsdf type="roughplastic"><float name="alpha" value="0.09"/>
      <string name="distribution" value="ggx"/><string name="int_ior" value="bk7"/>
      <rgb name="diffuse_reflectance" value="0.5, 0.4, 0.3"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="conductor"><string name="material" value="Au"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughconductor"><float name="alpha" value="0.04"/>
      <string name="distribution" value="ggx"/>
      <rgb name="eta" value="1.65746, 0.880369, 0.521229"/><rgb name="k" value="9.22387, 6.26952, 4.837"/>
      <rgb name="specular_reflectance" value="0.5, 0.5, 0.5"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="conductor"><rgb name="eta" value="0.3, 0.9, 1.2"/>
      <rgb name="k" value="3.0, 2.0, 1.8"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="dielectric"><float name="intIOR" value="1.33"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughdielectric"><float name="alpha" value="0.25"/>
      <string name="distribution" value="ggx"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="thindielectric"/></shape>)");
  const Scene& s = m.scene;
  const Material& plastic = materialOf(s, 0);
  EXPECT_EQ(plastic.type, MaterialType::Plastic);
  EXPECT_FLOAT_EQ(plastic.roughness, 0.3f);  // alpha = roughness^2
  EXPECT_NEAR(plastic.ior, 1.5046 / 1.000277, 1e-5);
  EXPECT_TRUE(plastic.albedo.isApprox(Vec3f(0.5f, 0.4f, 0.3f)));
  EXPECT_EQ(materialOf(s, 1).type, MaterialType::Conductor);
  EXPECT_EQ(materialOf(s, 1).metal, "gold");
  const Material& steel = materialOf(s, 2);
  EXPECT_EQ(steel.metal, "aluminium");  // Mitsuba's Al eta/k: our preset exactly
  EXPECT_TRUE(steel.albedo.isApprox(Vec3f::Constant(0.5f)));
  EXPECT_FLOAT_EQ(steel.roughness, 0.2f);
  EXPECT_EQ(materialOf(s, 3).metal, "copper");  // nearest by normal-incidence reflectance
  EXPECT_NE(approximations(m).find("nearest preset 'copper'"), std::string::npos);
  EXPECT_EQ(materialOf(s, 4).type, MaterialType::Dielectric);
  EXPECT_NEAR(materialOf(s, 4).ior, 1.33 / 1.000277, 1e-5);  // 0.6 spelling intIOR
  EXPECT_FLOAT_EQ(materialOf(s, 5).roughness, 0.5f);
  EXPECT_EQ(materialOf(s, 6).type, MaterialType::ThinDielectric);
  EXPECT_EQ(approximations(m).find("microfacets"), std::string::npos);  // all were ggx
}

TEST_F(MitsubaFixture, WrappersAndApproximationsAreListed) {
  const MitsubaScene m = read(R"(
    <bsdf type="twosided" id="Walls"><bsdf type="diffuse"><rgb name="reflectance" value="0.1"/></bsdf></bsdf>
    <shape type="rectangle"><ref id="Walls"/></shape>
    <shape type="rectangle"><bsdf type="mask" id="Leaves"><float name="opacity" value="0.5"/>
      <bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="bumpmap"><texture type="bitmap">
      <string name="filename" value="tex.png"/></texture><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="normalmap"><texture name="normalmap" type="bitmap">
      <string name="filename" value="tex.png"/></texture><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="coating"><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughplastic"><boolean name="nonlinear" value="true"/>
      <rgb name="diffuse_reflectance" value="0.3"/><float name="int_ior" value="1.5"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="hair"/></shape>
    <shape type="rectangle"><bsdf type="null"/></shape>)");
  const Scene& s = m.scene;
  ASSERT_EQ(s.objects.size(), 7u);  // the null BSDF's shape is left out
  EXPECT_EQ(materialOf(s, 0).id, "Walls");
  EXPECT_EQ(materialOf(s, 0).albedo, Vec3f::Constant(0.1f));
  EXPECT_EQ(s.objects[0].nyu40, *nyu40FromName("wall"));  // the BSDF id names the class
  EXPECT_EQ(materialOf(s, 2).type, MaterialType::Lambertian);
  EXPECT_FALSE(materialOf(s, 3).normal_texture.empty());
  EXPECT_EQ(materialOf(s, 4).type, MaterialType::Plastic);  // coated diffuse
  // nonlinear: R (1 - Fdr) / (1 - R Fdr), Fdr = 0.596 for ior 1.5 (Mitsuba's fdr_int)
  EXPECT_NEAR(materialOf(s, 5).albedo.x(), 0.3 * (1 - 0.5963) / (1 - 0.3 * 0.5963), 2e-3);
  EXPECT_EQ(materialOf(s, 6).albedo, Vec3f::Constant(0.5f));
  const std::string a = approximations(m);
  for (const char* what : {"mask (opacity cut-out) not supported", "bump map ignored",
                           "unsupported BSDF type 'hair'", "null BSDF", "nonlinear=true",
                           "one-sided BSDF rendered two-sided"})
    EXPECT_NE(a.find(what), std::string::npos) << what << " missing from:\n" << a;
  EXPECT_NE(m.report.summary("otherprop").find("Leaves"), std::string::npos);
}

TEST_F(MitsubaFixture, MoreBsdfsAndTextures) {
  const MitsubaScene m = read(R"(
    <shape type="rectangle"><bsdf type="difftrans"><rgb name="transmittance" value="0.4"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="principled"><float name="metallic" value="1"/>
      <rgb name="base_color" value="0.95, 0.64, 0.54"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="principled"><float name="spec_trans" value="1"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="principled"><float name="roughness" value="0.3"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="phong"><float name="exponent" value="98"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="blendbsdf"><float name="weight" value="0.8"/>
      <bsdf type="diffuse"/><bsdf type="conductor"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughdiffuse"><texture name="reflectance" type="checkerboard"/>
      </bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"><texture name="reflectance" type="scale">
      <float name="scale" value="0.5"/><texture type="bitmap"><string name="filename" value="tex.png"/>
      </texture></texture></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughcoating"><float name="alpha" value="0.16"/>
      <string name="distribution" value="ggx"/><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"/>
      <emitter type="area"><blackbody name="radiance" temperature="6500K"/></emitter></shape>)");
  const Scene& s = m.scene;
  EXPECT_EQ(materialOf(s, 0).type, MaterialType::Translucent);
  EXPECT_EQ(materialOf(s, 0).transmittance, Vec3f::Constant(0.4f));
  EXPECT_EQ(materialOf(s, 1).type, MaterialType::Conductor);
  EXPECT_EQ(materialOf(s, 1).metal, "copper");
  EXPECT_EQ(materialOf(s, 2).type, MaterialType::Dielectric);
  EXPECT_EQ(materialOf(s, 3).type, MaterialType::Plastic);
  EXPECT_FLOAT_EQ(materialOf(s, 3).roughness, 0.3f);  // principled roughness is perceptual
  EXPECT_NEAR(materialOf(s, 4).roughness, std::sqrt(std::sqrt(2.0 / 100.0)), 1e-6);
  EXPECT_EQ(materialOf(s, 5).type, MaterialType::Conductor);  // the heavier component
  EXPECT_TRUE(materialOf(s, 6).albedo.isApprox(Vec3f::Constant(0.3f)));  // checkerboard mean
  EXPECT_EQ(materialOf(s, 7).albedo, Vec3f::Constant(0.5f));  // scale x bitmap
  EXPECT_FALSE(materialOf(s, 7).albedo_texture.empty());
  EXPECT_EQ(materialOf(s, 8).type, MaterialType::Plastic);
  EXPECT_FLOAT_EQ(materialOf(s, 8).roughness, 0.4f);
  EXPECT_NEAR(luminance(materialOf(s, 9).emission), 1.0, 1e-3);  // blackbody: luminance 1
  const std::string a = approximations(m);
  for (const char* what : {"principled BSDF", "phong BSDF", "blendbsdf", "roughdiffuse",
                           "texture type 'checkerboard'"})
    EXPECT_NE(a.find(what), std::string::npos) << what << " missing from:\n" << a;
}

TEST_F(MitsubaFixture, ShapeGroupsInstancesAndFovAxes) {
  const MitsubaScene m = read(R"(
    <shape type="shapegroup" id="pair"><shape type="rectangle"/><shape type="cube"/></shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><translate x="3"/></transform></shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><translate x="6"/></transform></shape>
    <sensor type="thinlens"><float name="fov" value="90"/><string name="fov_axis" value="diagonal"/>
      <film type="hdrfilm"><integer name="width" value="300"/><integer name="height" value="400"/></film>
    </sensor>)");
  ASSERT_EQ(m.scene.objects.size(), 4u);
  EXPECT_EQ(m.scene.objects[0].mesh, m.scene.objects[2].mesh);  // instances share meshes
  EXPECT_TRUE(world(m.scene, 3, Vec3::Zero()).isApprox(Vec3(6, 0, 0)));
  EXPECT_NEAR(m.sensor->fx, 150.0 / (std::tan(kPi / 4) * 300.0 / 500.0), 1e-9);
  EXPECT_NE(approximations(m).find("no depth of field"), std::string::npos);
  for (const char* axis : {"smaller", "larger"}) {
    const MitsubaScene c = read(std::string(kQuad) + R"(<sensor type="perspective">
        <float name="fov" value="90"/><string name="fov_axis" value=")" + axis + R"("/>
        <film type="hdrfilm"><integer name="width" value="300"/><integer name="height" value="400"/>
        </film></sensor>)");
    // 90 degrees across the smaller side (300 px): f = 150; across the larger (400 px): 200
    EXPECT_NEAR(c.sensor->fx, std::string(axis) == "smaller" ? 150.0 : 200.0, 1e-9) << axis;
  }
}

TEST_F(MitsubaFixture, ParametersIncludesRefsAndBothSpellings) {
  dir_.write("part.xml", R"(<scene version="0.6.0"><bsdf type="diffuse" id="Grey">
    <rgb name="reflectance" value="$grey"/></bsdf></scene>)");
  MitsubaOptions opt;
  opt.parameters["grey"] = "0.25";
  const MitsubaScene m = read(R"(
    <default name="grey" value="0.75"/><default name="spp" value="16"/>
    <include filename="part.xml"/>
    <shape type="rectangle"><ref name="bsdf" id="Grey"/></shape>
    <sensor type="perspective"><sampler type="independent"><integer name="sampleCount" value="$spp"/>
      </sampler></sensor>)", opt);
  EXPECT_EQ(materialOf(m.scene, 0).albedo, Vec3f::Constant(0.25f));  // the option wins
  ASSERT_TRUE(m.sensor);
  EXPECT_EQ(m.sensor->spp, 16);
  // Mitsuba 0.6 and Mitsuba 3 spellings give the same scene
  const Scene old_names = readMitsubaScene(xml(R"(<shape type="rectangle">
      <transform name="toWorld"><translate x="1"/></transform><bsdf type="plastic">
      <float name="intIOR" value="1.4"/><rgb name="diffuseReflectance" value="0.2"/></bsdf>
      </shape>)", "0.6.0"), {}).scene;
  const Scene new_names = read(R"(<shape type="rectangle"><transform name="to_world">
      <translate value="1 0 0"/></transform><bsdf type="plastic"><float name="int_ior" value="1.4"/>
      <rgb name="diffuse_reflectance" value="0.2"/></bsdf></shape>)").scene;
  EXPECT_EQ(old_names.objects[0].T_world_object, new_names.objects[0].T_world_object);
  EXPECT_EQ(materialOf(old_names, 0).ior, materialOf(new_names, 0).ior);
  EXPECT_EQ(materialOf(old_names, 0).albedo, materialOf(new_names, 0).albedo);
}

TEST_F(MitsubaFixture, TransformsComposeInFileOrder) {
  const Scene s = read(R"(<shape type="rectangle"><transform name="to_world">
      <scale x="2" y="3" z="1"/><rotate x="0" y="0" z="1" angle="90"/>
      <translate x="10" y="0" z="0"/></transform></shape>
    <shape type="rectangle"><transform name="to_world">
      <matrix value="1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1"/></transform></shape>)").scene;
  // file point (1, 1, 0) of the unit-sized rectangle corner: scale -> (2, 3, 0), rotate 90 deg
  // about z -> (-3, 2, 0), translate -> (7, 2, 0); in our axes (7, 0, 2). Our quad's corner
  // (0.5, 0.5, 0) is the file's (1, 1, 0).
  EXPECT_TRUE(world(s, 0, Vec3(0.5, 0.5, 0)).isApprox(Vec3(7, 0, 2), 1e-9));
  EXPECT_TRUE(world(s, 1, Vec3::Zero()).isApprox(Vec3(5, -7, 6), 1e-12));
}

TEST_F(MitsubaFixture, EmittersBecomeOurLights) {
  const MitsubaScene m = read(R"(
    <shape type="rectangle" id="lamp"><bsdf type="diffuse"/>
      <emitter type="area"><rgb name="radiance" value="10, 8, 6"/></emitter></shape>
    <shape type="sphere"><emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
    <emitter type="point" id="bulb"><point name="position" x="0" y="2" z="0"/>
      <rgb name="intensity" value="5, 10, 5"/></emitter>
    <emitter type="spot"><transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0"/>
      </transform><float name="cutoff_angle" value="30"/><float name="beam_width" value="20"/></emitter>
    <emitter type="directional"><vector name="direction" x="0" y="-1" z="0"/>
      <rgb name="irradiance" value="3"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
    <emitter type="sunsky"><vector name="sun_direction" x="0" y="1" z="1"/></emitter>
    <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="2"/>
      <transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>)");
  const Scene& s = m.scene;
  const Material& lamp = materialOf(s, 0);
  EXPECT_EQ(lamp.emission, Vec3f(10, 8, 6));
  EXPECT_EQ(lamp.id, "lamp_bsdf@lamp");  // the shape's own emissive copy of its BSDF
  const Mesh& ball = s.meshes[s.objects[1].mesh];
  EXPECT_FALSE(ball.isSphere());  // emissive spheres are tessellated so lights sample them
  ASSERT_EQ(s.lights.size(), 7u);
  const Light& bulb = s.lights[0];
  EXPECT_EQ(bulb.type, LightType::Point);
  EXPECT_TRUE(bulb.position.isApprox(Vec3(0, 0, 2)));
  EXPECT_FLOAT_EQ(bulb.intensity, 10.f);
  EXPECT_EQ(bulb.color, Vec3f(0.5f, 1.f, 0.5f));
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_TRUE(spot.direction.isApprox(-Vec3::UnitZ(), 1e-9));
  EXPECT_FLOAT_EQ(spot.cone_deg, 30.f);
  EXPECT_FLOAT_EQ(spot.falloff_deg, 10.f);
  EXPECT_EQ(s.lights[2].type, LightType::Sun);
  EXPECT_TRUE(s.lights[2].direction.isApprox(-Vec3::UnitZ(), 1e-9));
  EXPECT_EQ(s.lights[3].type, LightType::Sky);
  EXPECT_EQ(s.lights[3].sky_model, SkyModel::Uniform);
  EXPECT_FLOAT_EQ(s.lights[3].intensity, 0.5f);
  EXPECT_EQ(s.lights[4].sky_model, SkyModel::Preetham);  // sunsky: sky, then sun
  EXPECT_TRUE(s.lights[4].direction.isApprox(-Vec3(0, -1, 1).normalized(), 1e-9));
  EXPECT_EQ(s.lights[5].type, LightType::Sun);
  const Light& env = s.lights[6];
  EXPECT_EQ(env.sky_model, SkyModel::EnvMap);
  EXPECT_FLOAT_EQ(env.intensity, 2.f);
  // to_world turns Mitsuba's map about its +y (our +z) by 90 degrees: the map's u = 0 direction
  // (Mitsuba -z, our +y in the map frame) goes to Mitsuba R_y(90) (0, 0, -1) = (-1, 0, 0)
  EXPECT_TRUE((env.envmap_rotation * Vec3::UnitY()).isApprox(Vec3(-1, 0, 0), 1e-9));
  EXPECT_TRUE((env.envmap_rotation * Vec3::UnitZ()).isApprox(Vec3::UnitZ(), 1e-9));
}

TEST_F(MitsubaFixture, SensorIsAnOpenCvCamera) {
  const MitsubaScene m = read(std::string(kQuad) + R"(
    <sensor type="perspective"><float name="fov" value="60"/><string name="fov_axis" value="y"/>
      <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="400"/><integer name="height" value="200"/></film>
    </sensor>)");
  ASSERT_TRUE(m.sensor);
  const MitsubaSensor& cam = *m.sensor;
  EXPECT_EQ(cam.width, 400);
  EXPECT_NEAR(cam.fy, 100.0 / std::tan(30.0 * kPi / 180.0), 1e-9);  // fov along y
  EXPECT_EQ(cam.fx, cam.fy);
  EXPECT_EQ(cam.cx, 200.0);
  // round trip through camera.json, then project Mitsuba points: +x is right of the centre
  // (Mitsuba's image x runs opposite its camera x), +y is above it
  const CameraFile f = parseCameraJson(mitsubaCameraJson(cam, "test"), "camera.json");
  EXPECT_TRUE(f.T_world_camera.t.isApprox(Vec3(0, -5, 0)));
  auto project = [&](const Vec3& p_world) {
    return f.intrinsics.project(f.T_world_camera.inverse() * p_world);
  };
  EXPECT_GT(project(Vec3(1, 0, 0)).x(), 200.0);  // Mitsuba (1, 0, 0)
  EXPECT_LT(project(Vec3(0, 0, 1)).y(), 100.0);  // Mitsuba (0, 1, 0)
  EXPECT_NEAR(project(Vec3::Zero()).x(), 200.0, 1e-9);
  // a horizontal fov of 90 degrees on a 1280-wide film (the living room's): fx = 640
  const MitsubaScene wide = read(std::string(kQuad) + R"(<sensor type="perspective">
      <float name="fov" value="90"/><film type="hdrfilm"><integer name="width" value="1280"/>
      <integer name="height" value="720"/></film></sensor>)");
  EXPECT_NEAR(wide.sensor->fx, 640.0, 1e-9);
}

TEST_F(MitsubaFixture, LabelMapAndUnmatchedNames) {
  dir_.write("labels.csv", "paneling,wall\n");
  MitsubaOptions opt;
  opt.label_map = (dir_ / "labels.csv").string();
  const MitsubaScene m = read(R"(
    <shape type="rectangle"><bsdf type="diffuse" id="Paneling"/></shape>
    <shape type="rectangle"><bsdf type="diffuse" id="Sofa"/></shape>
    <shape type="rectangle"><bsdf type="diffuse" id="Dirt"/></shape>)", opt);
  EXPECT_EQ(m.scene.objects[0].nyu40, *nyu40FromName("wall"));
  EXPECT_EQ(m.scene.objects[1].nyu40, *nyu40FromName("sofa"));
  EXPECT_EQ(m.scene.objects[2].nyu40, *nyu40FromName("otherprop"));
  EXPECT_EQ(m.report.unmatched_names, std::vector<std::string>{"Dirt"});
}

TEST_F(MitsubaFixture, LayoutRoundTripKeepsTheEnvMap) {
  const Scene s = read(std::string(kQuad) + R"(<emitter type="envmap">
      <string name="filename" value="sky.exr"/></emitter>)").scene;
  const std::string text = layoutToJson(s);
  const Scene back = parseLayout(text, (dir_ / "layout.json").string());
  ASSERT_EQ(back.lights.size(), 1u);
  EXPECT_EQ(back.lights[0].sky_model, SkyModel::EnvMap);
  EXPECT_EQ(back.lights[0].envmap.path, s.lights[0].envmap.path);
  EXPECT_EQ(back.lights[0].envmap_rotation, s.lights[0].envmap_rotation);
  EXPECT_EQ(layoutToJson(back), text);
}

TEST_F(MitsubaFixture, FromMemoryWithoutFiles) {
  MitsubaOptions opt;
  opt.read_files = false;
  const MitsubaScene m = parseMitsubaScene(R"(<scene version="3.0.0">
      <shape type="obj"><string name="filename" value="nowhere.obj"/></shape>)" +
                                               std::string(kQuad) + "</scene>",
                                           "/nonexistent/scene.xml", opt);
  EXPECT_EQ(m.scene.objects.size(), 1u);
  EXPECT_NE(approximations(m).find("nowhere.obj"), std::string::npos);
}

TEST_F(MitsubaFixture, ErrorsNameTheFileAndTheElement) {
  auto expectError = [&](const std::string& body, const std::string& want,
                         const std::string& version = "3.0.0") {
    const std::string e = error(body, version);
    EXPECT_NE(e.find("scene.xml"), std::string::npos) << e;
    EXPECT_NE(e.find(want), std::string::npos) << "want '" << want << "' in: " << e;
  };
  expectError("<shape type='rectangle'", "malformed XML");
  expectError(kQuad, "unsupported Mitsuba version '1.2'", "1.2");
  expectError(R"(<shape type="obj"><string name="filename" value="gone.obj"/></shape>)",
              "line 2 <shape type=\"obj\">");
  expectError(R"(<shape type="obj"><string name="filename" value="gone.obj"/></shape>)",
              "file not found");
  expectError(R"(<shape type="rectangle"><bsdf type="roughplastic">
      <float name="alpha" value="0.1x"/></bsdf></shape>)", "line 3 <float name=\"alpha\">: value=\"0.1x\": expected a finite number");
  expectError(R"(<shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance"
      value="0.1, 0.2"/></bsdf></shape>)", "expected 'r, g, b'");
  expectError(R"(<shape type="rectangle"><ref id="nothing"/></shape>)", "no element has id 'nothing'");
  expectError(R"(<bsdf type="diffuse" id="a"/><bsdf type="diffuse" id="a"/>)" + std::string(kQuad),
              "duplicate id 'a'");
  expectError(R"(<shape type="rectangle"><float name="x" value="$undefined"/></shape>)",
              "undefined parameter '$undefined'");
  expectError(R"(<include filename="missing.xml"/>)" + std::string(kQuad), "file not found");
  expectError(R"(<shape type="rectangle"><transform name="to_world"><shear/></transform></shape>)",
              "unknown transform operation");
  expectError(R"(<shape type="serialized"/>)", "the scene has no shape we can render");
  expectError(R"(<emitter type="envmap"><string name="filename" value="sky.hdr"/></emitter>)",
              "file not found");
  expectError(R"(<shape type="rectangle"><bsdf type="dielectric"><string name="int_ior"
      value="unobtainium"/></bsdf></shape>)", "unknown int_ior 'unobtainium'");
  expectError(R"(<shape type="shapegroup" id="g"><shape type="instance"><ref id="g"/></shape>
      </shape><shape type="instance"><ref id="g"/></shape>)", "instance inside a shapegroup");
  expectError(R"(<texture type="scale" id="t"><ref id="t"/></texture><shape type="rectangle">
      <bsdf type="diffuse"><ref name="reflectance" id="t"/></bsdf></shape>)", "nest too deeply");
  expectError(R"(<bsdf type="twosided" id="b"><ref id="b"/></bsdf><shape type="rectangle">
      <ref id="b"/></shape>)", "nest too deeply");
  const std::string no_version = dir_.write("scene.xml", std::string("<scene>") + kQuad + "</scene>");
  EXPECT_NE(errorOf([&] { readMitsubaScene(no_version, {}); }).find("missing the version"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readMitsubaScene((dir_ / "absent.xml").string(), {}); })
                .find("file not found"),
            std::string::npos);
}

TEST(MitsubaMetals, PresetReflectanceMatchesTheRenderersFresnel) {
  for (size_t i = 0; i < metalNames().size(); ++i) {
    const ComplexIor ior = metalIor(static_cast<Metal>(i));
    ASSERT_EQ(metalName(static_cast<Metal>(i)), metalNames()[i]);
    const Vec3f f0 = fresnelConductor(1.f, ior.eta, ior.k);
    EXPECT_TRUE(f0.isApprox(metalPresetF0()[i], 2e-4)) << metalNames()[i];
    Vec3f tint;
    EXPECT_EQ(nearestMetal(f0, &tint), metalNames()[i]);
    EXPECT_TRUE(tint.isApprox(Vec3f::Ones(), 1e-3));
  }
}

TEST(MitsubaLivingRoom, ImportsBitterlisScene) {
  const auto dir = test::sharedDir() / "data" / "scenes" / "bitterli_living_room_mitsuba";
  if (!std::filesystem::exists(dir / "scene.xml"))
    GTEST_SKIP() << "needs ../shared/data/scenes/bitterli_living_room_mitsuba (absent)";
  const MitsubaScene m = readMitsubaScene((dir / "scene.xml").string(), {});
  const Scene& s = m.scene;
  EXPECT_EQ(s.objects.size(), 65u);
  auto material = [&](const std::string& id) -> const Material& {
    const int i = s.findMaterial(id);
    EXPECT_GE(i, 0) << id;
    return s.materials.at(static_cast<size_t>(std::max(i, 0)));
  };
  EXPECT_EQ(material("Walls").type, MaterialType::Lambertian);
  EXPECT_EQ(material("Walls").albedo, Vec3f::Constant(0.1f));
  EXPECT_EQ(material("Floor").type, MaterialType::Plastic);
  EXPECT_NEAR(material("Floor").roughness, std::sqrt(0.15), 1e-6);
  EXPECT_EQ(std::filesystem::path(material("Floor").albedo_texture.path).filename(), "wood.jpg");
  EXPECT_EQ(material("Mirror").metal, "silver");
  EXPECT_EQ(material("BrushedStainlessSteel").metal, "aluminium");
  EXPECT_NEAR(material("BrushedStainlessSteel").albedo.x(), 0.578596, 1e-5);
  EXPECT_EQ(material("Glass").type, MaterialType::Dielectric);
  EXPECT_EQ(material("Sofa").albedo, Vec3f::Ones());
  EXPECT_GT(material("Leaves").albedo.y(), material("Leaves").albedo.z());  // green, opaque
  const std::map<std::string, std::string> classes = {
      {"Walls", "wall"}, {"Floor", "floor"}, {"Sofa", "sofa"}, {"TableWood", "table"}};
  for (const Object& o : s.objects) {
    auto it = classes.find(s.materials[o.material].id);
    if (it != classes.end()) {
      EXPECT_EQ(o.nyu40, *nyu40FromName(it->second)) << o.name;
    }
  }
  // the only light: the sky map, Mitsuba's to_world (a 90 degree turn about its y) in our axes
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& sky = s.lights[0];
  EXPECT_EQ(sky.sky_model, SkyModel::EnvMap);
  EXPECT_EQ(std::filesystem::path(sky.envmap.path).filename(), "Sky 19.exr");
  EXPECT_TRUE((sky.envmap_rotation * Vec3::UnitY()).isApprox(Vec3(-1, 0, 0), 1e-6));
  // the camera: Mitsuba's to_world of the scene file, written out here in our axes
  ASSERT_TRUE(m.sensor);
  EXPECT_EQ(m.sensor->width, 1280);
  EXPECT_EQ(m.sensor->height, 720);
  EXPECT_NEAR(m.sensor->fx, 640.0, 1e-9);
  const Pose& T = m.sensor->T_world_camera;
  EXPECT_TRUE(T.t.isApprox(Vec3(5.10518, 2.31789, 0.731065), 1e-9));
  const Vec3 forward = T.rotation().col(2);  // Mitsuba's column (-0.961792, 0.074407, 0.263476)
  EXPECT_TRUE(forward.isApprox(Vec3(-0.961792, -0.263476, 0.074407), 1e-5));
  EXPECT_LT(T.rotation().col(1).z(), -0.99);  // image down is world down: no roll
}

}  // namespace
}  // namespace inet
