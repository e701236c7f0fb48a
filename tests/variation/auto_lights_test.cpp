// variation/auto_lights.h: lights for scenes without any. Where the lights go (spaces, panels
// under the ceiling, lamps that glow), how much light (the emitted power, pi L A, equals the
// flux asked for), when nothing is added, and that a rendered room is lit afterwards.
#include "variation/auto_lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/color.h"
#include "render/renderer.h"
#include "scene/nyu40.h"
#include "../box_mesh.h"
#include "scene/primitives.h"

namespace inet {
namespace {

int id(const char* name) {
  return *nyu40FromName(name);
}

using test::appendBox;

/// A room [0, w] x [0, d], floor at 0, ceiling at h, 0.2 m walls and slabs; `partition` adds a
/// wall at x = w / 2 with a 0.9 x 2.0 m doorway; `ceiling` false leaves it open to the sky.
Scene room(double w, double d, double h, bool partition = false, bool ceiling = true) {
  Scene s;
  Mesh m;
  const double t = 0.2;
  appendBox(m, {w / 2, d / 2, -t / 2}, {w + 2 * t, d + 2 * t, t});
  if (ceiling) appendBox(m, {w / 2, d / 2, h + t / 2}, {w + 2 * t, d + 2 * t, t});
  appendBox(m, {-t / 2, d / 2, h / 2}, {t, d, h});
  appendBox(m, {w + t / 2, d / 2, h / 2}, {t, d, h});
  appendBox(m, {w / 2, -t / 2, h / 2}, {w, t, h});
  appendBox(m, {w / 2, d + t / 2, h / 2}, {w, t, h});
  if (partition) {
    const double door = d / 2;
    appendBox(m, {w / 2, (door - 0.45) / 2, h / 2}, {t, door - 0.45, h});
    appendBox(m, {w / 2, (d + door + 0.45) / 2, h / 2}, {t, d - door - 0.45, h});
    appendBox(m, {w / 2, door, (2.0 + h) / 2}, {t, 0.9, h - 2.0});  // lintel
  }
  m.id = "shell";
  s.meshes.push_back(m);
  s.materials.push_back(Material{});
  s.materials[0].id = "plaster";
  s.objects.push_back(Object::make("walls", 0, 0, Mat4::Identity(), id("wall"), 1));
  return s;
}

/// Emitted power of every emissive object: pi L A, L the luminance of the emission.
double emittedPower(const Scene& s) {
  double p = 0;
  for (const Object& o : s.objects) {
    const Material& m = s.materials[o.material];
    if (!m.isEmissive()) continue;
    const Mesh& mesh = s.meshes[o.mesh];
    for (const Tri& t : mesh.triangles) {
      Vec3 a = (o.T_world_object * mesh.positions[t[0]].cast<double>().homogeneous()).head<3>();
      Vec3 b = (o.T_world_object * mesh.positions[t[1]].cast<double>().homogeneous()).head<3>();
      Vec3 c = (o.T_world_object * mesh.positions[t[2]].cast<double>().homogeneous()).head<3>();
      p += M_PI * luminance(m.emission) * 0.5 * (b - a).cross(c - a).norm();
    }
  }
  return p;
}

TEST(AutoLights, LuminaireNames) {
  for (const char* yes : {"light.011", "Lamp", "CeilingLight_2", "lightbulb.100", "Lights.111",
                          "lampshade", "Chandelier", "wall_sconce", "Lighting", "downlight_3"})
    EXPECT_TRUE(isLuminaireName(yes)) << yes;
  for (const char* no : {"light_switch", "LightSwitch", "flight_case", "highlight", "wall.002",
                         "plate", "motion_sensor_light"})
    EXPECT_FALSE(isLuminaireName(no)) << no;
}

TEST(AutoLights, AClosedRoomGetsCeilingPanelsWithTheFluxItsFloorNeeds) {
  Scene s = room(6, 4, 2.7);
  ASSERT_FALSE(sceneHasLight(s));
  AutoLightOptions opt;
  const AutoLightReport r = addAutoLights(s, opt);
  EXPECT_TRUE(sceneHasLight(s));
  EXPECT_EQ(r.spaces, 1u);
  EXPECT_NEAR(r.space_area_m2, 24.0, 1.5);  // the free floor, to a voxel at the walls
  EXPECT_EQ(r.ceiling_panels, 3u);          // round(24 / 9)
  EXPECT_FALSE(r.daylight);
  // the room is of albedo 0.8 everywhere: its light bounces 1 / (1 - 0.8) times, so the flux
  // is (1 - 0.8) / 0.5 = 0.4 of 5 W per m^2 of floor
  EXPECT_NEAR(r.mean_albedo, 0.8, 1e-6);
  EXPECT_NEAR(emittedPower(s), opt.flux_per_m2 * 0.4 * r.space_area_m2, 1e-3 * emittedPower(s));
  std::set<int> instances;
  for (const Object& o : s.objects) EXPECT_TRUE(instances.insert(o.instance).second);
  for (size_t k = 1; k < s.objects.size(); ++k) {
    const Object& o = s.objects[k];
    EXPECT_EQ(o.nyu40, id("lamp"));
    EXPECT_NEAR(o.T_world_object(2, 3), 2.695, 1e-6) << "5 mm under the ceiling";
    EXPECT_LT(o.T_world_object(2, 2), 0.0) << "facing down";
    EXPECT_GT(o.T_world_object(0, 3), 0.3);
    EXPECT_LT(o.T_world_object(0, 3), 5.7);
  }
  EXPECT_NE(r.summary().find("3 ceiling light(s)"), std::string::npos) << r.summary();
  s.validate("auto lights");
  // deterministic
  Scene again = room(6, 4, 2.7);
  addAutoLights(again, opt);
  ASSERT_EQ(again.objects.size(), s.objects.size());
  for (size_t k = 0; k < s.objects.size(); ++k)
    EXPECT_EQ(again.objects[k].T_world_object, s.objects[k].T_world_object);
}

TEST(AutoLights, ADoorwaysLintelSeparatesTwoRooms) {
  Scene s = room(8, 4, 2.7, true);
  const AutoLightReport r = addAutoLights(s);
  EXPECT_EQ(r.spaces, 2u);
  EXPECT_EQ(r.ceiling_panels, 4u);  // 2 per 15 m^2 room
  int left = 0;
  for (const Object& o : s.objects) left += o.nyu40 == id("lamp") && o.T_world_object(0, 3) < 4;
  EXPECT_EQ(left, 2);
}

TEST(AutoLights, NoLightInsideAClosedWardrobe) {
  // a closed 1.2 x 1.2 x 2.1 m box in a 4 x 4 x 2.5 m room: its inside has floor-to-top runs
  // of 2 m, but it is 3 m^3 shut off from the room
  Scene s = room(4, 4, 2.5);
  Mesh wardrobe;
  appendBox(wardrobe, {0.8, 0.8, 1.05}, {1.2, 1.2, 2.1});
  wardrobe.id = "wardrobe";
  s.meshes.push_back(wardrobe);
  s.objects.push_back(Object::make("wardrobe", 1, 0, Mat4::Identity(), id("cabinet"), 2));
  const AutoLightReport r = addAutoLights(s);
  EXPECT_EQ(r.spaces, 1u);
  for (const Object& o : s.objects) {
    if (o.nyu40 == id("lamp")) {
      EXPECT_FALSE(o.T_world_object(0, 3) < 1.4 && o.T_world_object(1, 3) < 1.4 &&
                   o.T_world_object(2, 3) < 2.2)
          << "a panel inside the wardrobe";
    }
  }
}

TEST(AutoLights, LampObjectsGlowInsteadOfPanels) {
  Scene s = room(6, 4, 2.7);
  Mesh fixture;
  appendBox(fixture, {3, 2, 2.6}, {0.6, 0.6, 0.1});  // a ceiling fixture
  fixture.id = "fixture";
  s.meshes.push_back(fixture);
  s.objects.push_back(Object::make("light.011", 1, 0, Mat4::Identity(), id("otherprop"), 2));
  const AutoLightReport r = addAutoLights(s);
  ASSERT_EQ(r.luminaires.size(), 1u);
  EXPECT_EQ(r.ceiling_panels, 0u);
  const Material& glow = s.materials[s.objects[1].material];
  EXPECT_TRUE(glow.isEmissive());
  EXPECT_EQ(s.materials[s.objects[0].material].emission, Vec3f::Zero()) << "walls stay dark";
  EXPECT_NEAR(emittedPower(s), 5.0 * 0.4 * r.space_area_m2, 1e-3 * emittedPower(s));
  // the colour is 3500 K white
  const Vec3f c = glow.emission / luminance(glow.emission);
  EXPECT_LT((c - blackbodyRgb(3500)).norm(), 1e-4);
}

TEST(AutoLights, AnOpenSceneGetsDaylight) {
  Scene s = room(6, 4, 2.7, false, false);  // no ceiling: no enclosed space
  const AutoLightReport r = addAutoLights(s);
  EXPECT_EQ(r.spaces, 0u);
  EXPECT_TRUE(r.daylight);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, LightType::Sky);
  EXPECT_EQ(s.lights[1].type, LightType::Sun);
}

TEST(AutoLights, ADarkerRoomGetsMoreLight) {
  // albedo 0.3: bounces 1 / 0.7 times, so 1.4 times 5 W/m^2 (and 0.9 would get the floor of 0.2)
  Scene dark = room(6, 4, 2.7);
  dark.materials[0].albedo = Vec3f::Constant(0.3f);
  const AutoLightReport r = addAutoLights(dark);
  EXPECT_NEAR(emittedPower(dark), 5.0 * 1.4 * r.space_area_m2, 1e-3 * emittedPower(dark));
  Scene white = room(6, 4, 2.7);
  white.materials[0].albedo = Vec3f::Constant(0.95f);
  const AutoLightReport w = addAutoLights(white);
  EXPECT_NEAR(emittedPower(white), 5.0 * 0.2 * w.space_area_m2, 1e-3 * emittedPower(white));
}

TEST(AutoLights, ModesDecideWhenToAdd) {
  Scene lit = room(6, 4, 2.7);
  Light bulb;
  bulb.position = Vec3(3, 2, 2);
  lit.lights.push_back(bulb);
  EXPECT_TRUE(addAutoLights(lit).had_light);
  EXPECT_EQ(lit.objects.size(), 1u) << "auto: a lit scene is left alone";
  AutoLightOptions on;
  on.mode = AutoLightMode::On;
  EXPECT_EQ(addAutoLights(lit, on).ceiling_panels, 3u);
  Scene dark = room(6, 4, 2.7);
  AutoLightOptions off;
  off.mode = AutoLightMode::Off;
  EXPECT_TRUE(addAutoLights(dark, off).summary().empty());
  EXPECT_FALSE(sceneHasLight(dark));
  EXPECT_EQ(parseAutoLightMode("on", "--auto-lights"), AutoLightMode::On);
  EXPECT_THROW(parseAutoLightMode("yes", "--auto-lights"), InputError);
}

// Rendered: before, every pixel of the room is black; after, a view of the room from its
// middle is lit, with the floor under a panel brighter than the floor in a corner.
TEST(AutoLights, TheRoomRendersLitAfterwards) {
  Scene s = room(6, 4, 2.7);
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 40);
  const Pose T = Pose::lookAt({1.0, 2.0, 1.5}, {5.0, 2.0, 0.8}, Vec3::UnitZ());
  RenderOptions ro;
  ro.spp = 16;
  ro.passes = static_cast<PassMask>(Pass::Rgb);
  auto meanLuminance = [&](const Scene& scene) {
    Renderer r(scene);
    Frame f;
    r.render(K, T, ro, 0, f);
    double sum = 0;
    for (int y = 0; y < f.rgb.height; ++y)
      for (int x = 0; x < f.rgb.width; ++x)
        sum += luminance(Eigen::Vector3f(f.rgb.at(x, y, 0), f.rgb.at(x, y, 1), f.rgb.at(x, y, 2)));
    return sum / (f.rgb.width * f.rgb.height);
  };
  EXPECT_EQ(meanLuminance(s), 0.0);
  addAutoLights(s);
  // 5 W/m^2 on a 0.8-albedo room: direct floor irradiance of order 2-5 W/m^2, radiance
  // 0.8 E / pi of order 0.5-1.3; the mean over walls, floor and ceiling lies well inside
  const double lit = meanLuminance(s);
  EXPECT_GT(lit, 0.1);
  EXPECT_LT(lit, 3.0);
}

}  // namespace
}  // namespace inet
