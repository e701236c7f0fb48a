// Analytic lights against closed forms: a large Lambertian floor (albedo a) seen from above, lit by
// one light. The floor's radiance toward the camera is a/pi * E, where E is the irradiance the
// light gives the floor point, so every pixel's expected value follows from the light alone.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/color.h"
#include "render/fresnel.h"
#include "render/embree_scene.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "render/sky.h"
#include "scene/primitives.h"
#include "emissive_quad.h"
#include "../box_mesh.h"

namespace inet {
namespace {

constexpr double kAlbedo = 0.6;

Scene floorScene() {
  Scene s;
  Mesh quad = makePrimitive("quad", {}, "t", "quad");
  quad.id = "quad";
  s.meshes = {quad};
  Material m;
  m.id = "floor";
  m.albedo = Vec3f::Constant(static_cast<float>(kAlbedo));
  s.materials = {m};
  Mat4 T = Mat4::Identity();
  T.diagonal() << 200, 200, 1, 1;
  s.objects = {Object::make("floor", 0, 0, T, 2, 1)};
  return s;
}

/// Mean floor radiance seen in a tiny field of view around the floor point (px, py, 0).
double floorRadiance(const Scene& s, double px, double py, int spp = 256) {
  Renderer r(s);
  CameraIntrinsics K;
  K.width = K.height = 4;
  K.fx = K.fy = 40000;
  K.cx = K.cy = 2;
  RenderOptions opt;
  opt.spp = spp;
  opt.max_bounces = 1;
  opt.passes = static_cast<PassMask>(Pass::Rgb);
  Frame f;
  r.render(K, Pose::lookAt(Vec3(px, py, 1.0), Vec3(px, py, 0), Vec3::UnitY()), opt, 0, f);
  double sum = 0;
  for (size_t i = 0; i < f.rgb.pixelCount(); ++i) sum += f.rgb.data[3 * i + 1];  // green
  return sum / f.rgb.pixelCount();
}

Light pointLight(Vec3 p, float intensity) {
  Light l;
  l.name = "bulb";
  l.type = LightType::Point;
  l.position = p;
  l.intensity = intensity;
  return l;
}

TEST(Lights, PointLightInverseSquareAndCosine) {
  Scene s = floorScene();
  s.lights = {pointLight(Vec3(0, 0, 2), 5.f)};
  // under the light: E = I / h^2; beside it at x: E = I cos / d^2 = I h / d^3
  EXPECT_NEAR(floorRadiance(s, 0, 0), kAlbedo / M_PI * 5.0 / 4.0, 1e-3);
  double d = std::sqrt(1.5 * 1.5 + 4.0);
  EXPECT_NEAR(floorRadiance(s, 1.5, 0), kAlbedo / M_PI * 5.0 * 2.0 / (d * d * d), 1e-3);
}

// A bulb of radius r: I / (d^2 + r^2), a disk facing the receiver (as Cycles draws a point light
// with a radius); far away the same as a point. 5 cm under it the plain point's light would be
// 5x as bright.
TEST(Lights, ABulbsRadiusBoundsItsLightNearby) {
  Scene s = floorScene();
  Light l = pointLight(Vec3(0, 0, 0.05), 5.f);
  l.radius = 0.1f;
  s.lights = {l};
  const double near = kAlbedo / M_PI * 5.0 / (0.05 * 0.05 + 0.01);
  EXPECT_NEAR(floorRadiance(s, 0, 0), near, 1e-3 * near);
  s.lights[0].position = Vec3(0, 0, 4);
  EXPECT_NEAR(floorRadiance(s, 0, 0), kAlbedo / M_PI * 5.0 / (16.0 + 0.01), 1e-5);
}

TEST(Lights, RangeAndOnOff) {
  Scene s = floorScene();
  Light l = pointLight(Vec3(0, 0, 2), 5.f);
  l.max_distance = 2.5f;
  s.lights = {l};
  EXPECT_GT(floorRadiance(s, 0, 0), 0.0);
  EXPECT_EQ(floorRadiance(s, 3, 0), 0.0) << "beyond max_distance";
  s.lights[0].on = false;
  EXPECT_EQ(floorRadiance(s, 0, 0), 0.0) << "switched off";
}

TEST(Lights, SpotConeAndFalloff) {
  Scene s = floorScene();
  Light l = pointLight(Vec3(0, 0, 2), 5.f);
  l.type = LightType::Spot;
  l.direction = -Vec3::UnitZ();
  l.cone_deg = 30.f;
  l.falloff_deg = 10.f;
  s.lights = {l};
  // on the axis: like a point light; inside the inner cone (< 20 deg): unchanged
  EXPECT_NEAR(floorRadiance(s, 0, 0), kAlbedo / M_PI * 5.0 / 4.0, 1e-3);
  double x_in = 2.0 * std::tan(15.0 * M_PI / 180.0), d = std::sqrt(x_in * x_in + 4.0);
  EXPECT_NEAR(floorRadiance(s, x_in, 0), kAlbedo / M_PI * 5.0 * 2.0 / (d * d * d), 1e-3);
  // in the smooth edge: strictly between; outside the cone: dark
  double x_edge = 2.0 * std::tan(25.0 * M_PI / 180.0), de = std::sqrt(x_edge * x_edge + 4.0);
  double full = kAlbedo / M_PI * 5.0 * 2.0 / (de * de * de), got = floorRadiance(s, x_edge, 0);
  EXPECT_GT(got, 0.05 * full);
  EXPECT_LT(got, 0.95 * full);
  EXPECT_EQ(floorRadiance(s, 2.0 * std::tan(35.0 * M_PI / 180.0), 0), 0.0);
}

TEST(Lights, SunIrradianceTimesCosine) {
  Scene s = floorScene();
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  double elevation = 40.0 * M_PI / 180.0;
  sun.direction = -Vec3(std::cos(elevation), 0, std::sin(elevation));
  sun.intensity = 3.f;  // W/m^2 normal to the rays
  s.lights = {sun};
  // E on the floor = E_normal * sin(elevation); the camera's own floor point is unoccluded
  EXPECT_NEAR(floorRadiance(s, 0, 0, 1024), kAlbedo / M_PI * 3.0 * std::sin(elevation), 2e-3);
}

// 60 point lights of random power: picking one per sample in proportion to power must converge
// to the sum of their contributions.
TEST(Lights, SixtyLightsConvergeToTheSum) {
  Scene s = floorScene();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  double expected_E = 0;
  for (int i = 0; i < 60; ++i) {
    Vec3 p(-3 + 6 * u(rng), -3 + 6 * u(rng), 0.5 + 2.5 * u(rng));
    float I = static_cast<float>(0.05 + 2 * u(rng));
    s.lights.push_back(pointLight(p, I));
    double d2 = p.squaredNorm();
    expected_E += I * p.z() / (d2 * std::sqrt(d2));
  }
  EXPECT_NEAR(floorRadiance(s, 0, 0, 8192), kAlbedo / M_PI * expected_E,
              0.01 * kAlbedo / M_PI * expected_E);
}

TEST(Blackbody, WhitePointAndWarmLight) {
  Eigen::Vector3f d65 = blackbodyRgb(6504);
  EXPECT_LT(d65.maxCoeff() / d65.minCoeff(), 1.1) << d65.transpose();
  Eigen::Vector3f warm = blackbodyRgb(2700);
  EXPECT_GT(warm.x(), warm.y());
  EXPECT_GT(warm.y(), warm.z());
  Eigen::Vector3f cold = blackbodyRgb(12000);
  EXPECT_GT(cold.z(), cold.x());
  for (float k : {1500.f, 2700.f, 6504.f, 20000.f}) {
    Eigen::Vector3f c = blackbodyRgb(k);
    EXPECT_NEAR(0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z(), 1.0, 1e-5);
  }
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

// A uniform sky of radiance L over an unoccluded Lambertian floor: E = pi L from the upper
// hemisphere, so the floor's radiance is a L (the lower hemisphere is hidden by the floor).
TEST(Lights, UniformSkyOverAFloor) {
  Scene s = floorScene();
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.intensity = 0.7f;
  s.lights = {sky};
  EXPECT_NEAR(floorRadiance(s, 0, 0, 4096), kAlbedo * 0.7, 0.01 * kAlbedo * 0.7);
}

// A Preetham sky (sun at 35 degrees) over the floor: the floor's radiance is a/pi E with
// E = int L cos dw over the upper hemisphere, integrated here from the model's radiance.
TEST(Lights, PreethamSkyOverAFloor) {
  Scene s = floorScene();
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.sky_model = SkyModel::Preetham;
  sky.turbidity = 3.f;
  const double el = 35.0 * M_PI / 180.0;
  sky.direction = -Vec3(std::cos(el) * std::cos(0.7), std::cos(el) * std::sin(0.7), std::sin(el));
  sky.intensity = 2.f;  // W/m^2 on the floor, in luminance
  s.lights = {sky};
  const PreethamSkyLight model(sky);
  double E_green = 0;  // midpoint rule in (theta, phi), exact solid angle per cell
  const int nt = 300, np = 1200;
  const double dt = 0.5 * M_PI / nt, dp = 2 * M_PI / np;
  for (int i = 0; i < nt; ++i) {
    const double t = (i + 0.5) * dt, w = (std::cos(i * dt) - std::cos((i + 1) * dt)) * dp;
    for (int j = 0; j < np; ++j) {
      const double p = (j + 0.5) * dp;
      const Vec3f d(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
      E_green += model.radiance(d).y() * std::cos(t) * w;
    }
  }
  const double expected = kAlbedo / M_PI * E_green;
  EXPECT_NEAR(floorRadiance(s, 0, 0, 256), expected, 0.01 * expected);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

/// floorScene() under a horizontal window pane (ior 1.5) at z = 1.5, above the camera.
Scene paneOverFloor() {
  Scene s = floorScene();
  Material glass;
  glass.id = "pane";
  glass.type = MaterialType::ThinDielectric;
  glass.ior = 1.5f;
  s.materials.push_back(glass);
  Mat4 T = Mat4::Identity();
  T.diagonal() << 200, 200, 1, 1;
  T(2, 3) = 1.5;
  s.objects.push_back(Object::make("pane", 0, 1, T, 9, 2));
  return s;
}

/// Expected straight-through transmission of the pane at incidence cosine c: 1 - 2F/(1+F).
double paneTransmission(double c) {
  const double f = fresnelDielectric(static_cast<float>(c), 1.5f);
  return 1.0 - 2.0 * f / (1.0 + f);
}

// Sunlight through a window: next-event estimation looks through the pane, so the floor gets
// E sin(el) T(el) at once (without it, only BSDF samples that happen to hit the 0.53-degree sun
// would carry the light: a firefly here and there, and almost always zero at 16 spp).
TEST(Lights, SunThroughAWindowPane) {
  Scene s = paneOverFloor();
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  const double elevation = 50.0 * M_PI / 180.0;
  sun.direction = -Vec3(std::cos(elevation), 0, std::sin(elevation));
  sun.intensity = 3.f;
  s.lights = {sun};
  const double expected =
      kAlbedo / M_PI * 3.0 * std::sin(elevation) * paneTransmission(std::sin(elevation));
  EXPECT_NEAR(floorRadiance(s, 0, 0, 16), expected, 0.01 * expected) << "16 spp suffice";
  EXPECT_NEAR(floorRadiance(s, 0, 0, 1024), expected, 0.003 * expected);
}

// An area light behind a pane: light sampling (through the pane) and BSDF sampling (through it
// as a pass, not a bounce) must combine to the same value as without the pane times its
// transmission; a small emitter straight above keeps the incidence near normal.
TEST(Lights, AreaLightThroughAPaneMatchesMisWithoutIt) {
  auto withLamp = [](Scene s) {
    Mesh quad = makePrimitive("quad", {}, "t", "quad");
    quad.id = "lamp_quad";
    s.meshes.push_back(quad);
    Material lamp;
    lamp.id = "lamp";
    lamp.emission = Vec3f::Constant(50.f);
    s.materials.push_back(lamp);
    Mat4 T = Mat4::Identity();
    T.diagonal() << 0.2, -0.2, -1, 1;  // turned over (x stays, y and z flip): faces down
    T(2, 3) = 3.0;
    s.objects.push_back(Object::make("lamp", static_cast<int>(s.meshes.size()) - 1,
                                     static_cast<int>(s.materials.size()) - 1, T, 39, 9));
    return s;
  };
  const double open = floorRadiance(withLamp(floorScene()), 0, 0, 4096);
  const double behind = floorRadiance(withLamp(paneOverFloor()), 0, 0, 4096);
  // the lamp subtends ~0.4 degrees from the floor point: T at normal incidence
  EXPECT_GT(open, 0.0);
  EXPECT_NEAR(behind, open * paneTransmission(1.0), 0.01 * open);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

// The pick depends on the receiver: a lamp's light dominates next to it and the sun far from
// it; a spot is never picked outside its cone; and the pdf that MIS computes for an emissive
// triangle or the sky from the receiver is the one `sample` used there.
TEST(LightPick, NearLightsWinNearbyAndPdfsAgreeWithSample) {
  Scene s;
  Light spot;
  spot.name = "spot";
  spot.type = LightType::Spot;
  spot.position = Vec3(0, 0, 2.5);
  spot.intensity = 8.f;
  spot.cone_deg = 30.f;
  spot.falloff_deg = 5.f;
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0, 0.6, -0.8);
  sun.intensity = 350.f;
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.intensity = 5.f;
  s.lights = {spot, sun, sky};
  // one emissive quad (two triangles) of radiance 20 at z = 2.7, facing down
  const SceneLights lights(s, test::emissiveQuad(7));
  ASSERT_EQ(lights.pickCount(), 4u);  // the quad, spot, sun, sky
  // 10 cm under the spot the spot is picked most of the time (a global pick by power would give
  // its 8 W a chance of 1e-5 next to the sun's 350 W/m^2 over the scene); outside its cone never
  EXPECT_GT(lights.pickProbability(Vec3f(0, 0, 2.4f), 1), 0.6f);
  EXPECT_EQ(lights.pickProbability(Vec3f(3, 0, 2.4f), 1), 0.f);
  // far away the sun and the sky take over
  const Vec3f far(30, 30, 0);
  EXPECT_GT(lights.pickProbability(far, 2) + lights.pickProbability(far, 3), 0.99f);
  float sum = 0.f;
  for (size_t k = 0; k < lights.pickCount(); ++k) sum += lights.pickProbability(far, k);
  EXPECT_NEAR(sum, 1.f, 1e-6f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.f, 1.f);
  int triangles = 0, skies = 0;
  for (const Vec3f& p : {Vec3f(2.1f, 2.2f, 2.4f), Vec3f(0.2f, 0.f, 0.5f), far}) {
    for (int i = 0; i < 4000; ++i) {
      LightSample ls;
      const SceneLights::PickPoint at = lights.pickAt(p);
      if (!lights.sample(at, U(rng), {U(rng), U(rng)}, ls) || ls.delta) continue;
      float pdf = 0.f;
      if (std::isinf(ls.dist)) {
        const Vec3f L = lights.environmentRadiance(ls.wi, &at, pdf);
        EXPECT_TRUE(L.isApprox(ls.radiance, 1e-5f));
        ++skies;
      } else {
        const size_t t = test::emissiveQuadTriangle(p, ls.wi);
        pdf = lights.trianglePdf(t, at, ls.dist, ls.wi.z());  // -normal . wi
        ++triangles;
      }
      ASSERT_NEAR(pdf, ls.pdf, 1e-4f * ls.pdf) << p.transpose();
    }
  }
  EXPECT_GT(triangles, 100);
  EXPECT_GT(skies, 100);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

/// A 0.5 x 0.5 m window (two triangles) at z = 1.5 centred above the origin, normal -z.
std::vector<PortalTriangle> squareWindow(float side = 0.5f, float height = 1.5f) {
  const float h = side / 2;
  PortalTriangle a, b;
  a.p0 = Vec3f(-h, -h, height), a.e1 = Vec3f(side, 0, 0), a.e2 = Vec3f(0, side, 0);
  b.p0 = Vec3f(h, h, height), b.e1 = Vec3f(-side, 0, 0), b.e2 = Vec3f(0, -side, 0);
  for (PortalTriangle* t : {&a, &b}) {
    t->area = side * side / 2;
    t->normal = Vec3f(0, 0, -1);
  }
  return {a, b};
}

// Sky portals (lights.h): with a window, a sky's pdf is the mixture of its own table and the
// portal; it must integrate to 1 over the sphere, be what `sample` reports and what MIS computes
// for an escaped ray, and send about half the samples (plus the table's share) through the
// window.
TEST(SkyPortal, MixturePdfIntegratesToOneAndAgreesWithSample) {
  for (SkyModel model : {SkyModel::Uniform, SkyModel::Preetham}) {
    Scene s;
    Light sky;
    sky.name = "sky";
    sky.type = LightType::Sky;
    sky.sky_model = model;
    sky.direction = Vec3(0.3, 0.2, -0.9).normalized();
    sky.intensity = 3.f;
    s.lights = {sky};
    const SceneLights lights(s, {}, squareWindow());
    ASSERT_EQ(lights.portalCount(), 2u);
    const Vec3f p(0.2f, -0.1f, 0.f);
    // the integral of the pdf over the sphere, by stratified uniform directions
    double integral = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const float z = 1.f - 2.f * (i + 0.5f) / n, phi = 2.f * float(M_PI) * (j + 0.5f) / n;
        const float r = std::sqrt(1.f - z * z);
        integral += lights.skyPdf(0, p, Vec3f(r * std::cos(phi), r * std::sin(phi), z));
      }
    integral *= 4 * M_PI / (double(n) * n);
    EXPECT_NEAR(integral, 1.0, 0.01) << "sky model " << int(model);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.f, 1.f);
    int through = 0, taken = 0;
    const SceneLights::PickPoint at = lights.pickAt(p);
    for (int i = 0; i < 20000; ++i) {
      LightSample ls;
      if (!lights.sample(at, U(rng), {U(rng), U(rng)}, ls)) continue;
      ++taken;
      float pdf = 0.f;
      const Vec3f L = lights.environmentRadiance(ls.wi, &at, pdf);
      ASSERT_TRUE(L.isApprox(ls.radiance, 1e-5f));
      ASSERT_NEAR(pdf, ls.pdf, 1e-4f * ls.pdf);
      ASSERT_NEAR(ls.pdf, lights.skyPdf(0, p, ls.wi), 1e-4f * ls.pdf);
      const float t = (1.5f - p.z()) / ls.wi.z();
      const Vec3f q = p + t * ls.wi;
      through += t > 0 && std::abs(q.x()) < 0.25f && std::abs(q.y()) < 0.25f;
    }
    EXPECT_GT(taken, 19000);
    EXPECT_GT(through, taken / 2) << "half the samples go through the window, and some more";
  }
}

/// floorScene() under an opaque black ceiling at z = 1.5 with a 0.5 m square hole above the
/// origin, closed by a window pane, under a uniform sky of radiance L. The pane is a quad, or
/// with `thin_box` a glass sheet modelled as a 1 mm box (as Sweet Home 3D's windows are) on the
/// ceiling's plane.
Scene windowedCeiling(float L, bool thin_box = false) {
  Scene s = floorScene();
  Mesh box = makePrimitive("box", {}, "t", "box");
  box.id = "box";
  s.meshes.push_back(box);
  Material black;
  black.id = "ceiling";
  black.albedo = Vec3f::Zero();
  Material glass;
  glass.id = "pane";
  glass.type = MaterialType::ThinDielectric;
  glass.ior = 1.5f;
  s.materials.push_back(black);
  s.materials.push_back(glass);
  auto quad = [&](const char* name, double x0, double x1, double y0, double y1, int material,
                  double thickness = 0) {
    Mat4 T = Mat4::Identity();
    T.diagonal() << x1 - x0, y1 - y0, thickness > 0 ? thickness : 1, 1;
    T.block<3, 1>(0, 3) = Vec3(0.5 * (x0 + x1), 0.5 * (y0 + y1), 1.5);
    s.objects.push_back(Object::make(name, thickness > 0 ? 1 : 0, material, T, 22,
                                     int(s.objects.size()) + 1));
  };
  quad("left", -100, -0.25, -100, 100, 1);
  quad("right", 0.25, 100, -100, 100, 1);
  quad("front", -0.25, 0.25, 0.25, 100, 1);
  quad("back", -0.25, 0.25, -100, -0.25, 1);
  quad("pane", -0.25, 0.25, -0.25, 0.25, 2, thin_box ? 0.001 : 0);
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.intensity = L;
  s.lights = {sky};
  return s;
}

// The floor under the window: its radiance is a/pi int_window L T(cos) cos dw, integrated here
// over the window's area (dw = cos / r^2 dA). Sky samples through the portal make this converge
// at a few hundred samples; the sky's own samples alone would need the window's 1/40 of the
// sphere to be hit.
TEST(SkyPortal, FloorUnderAWindowGetsTheSkyThroughItUnbiased) {
  const float L = 2.f;
  // E[k]: the integral with the glass crossed k times (a pane: once; a thin box: twice)
  double E[3] = {0, 0, 0};
  const int n = 400;
  const double side = 0.5, h = 1.5;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -side / 2 + side * (i + 0.5) / n, y = -side / 2 + side * (j + 0.5) / n;
      const double r2 = x * x + y * y + h * h, c = h / std::sqrt(r2);
      const double dE = L * c * c / r2 * (side * side / (double(n) * n));
      E[1] += dE * paneTransmission(c);
      E[2] += dE * paneTransmission(c) * paneTransmission(c);
    }
  for (bool thin_box : {false, true}) {
    const Scene s = windowedCeiling(L, thin_box);
    EXPECT_EQ(EmbreeScene(s).lights().portalCount(), 2u)
        << (thin_box ? "the box's upper face" : "the quad") << " is the portal";
    const double expected = kAlbedo / M_PI * E[thin_box ? 2 : 1];
    const double got = floorRadiance(s, 0, 0, 1024);
    std::printf("floor under a window (%s): %.6f, expected %.6f\n", thin_box ? "thin box" : "pane",
                got, expected);
    EXPECT_NEAR(got, expected, 0.01 * expected) << (thin_box ? "thin box" : "pane");
  }
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

// Only simple glass that sees the sky is a way to it: a window quad is a portal, a glass box
// under it (a table top) is not, however it is labelled.
TEST(SkyPortal, OnlyGlassThatSeesTheSkyIsAPortal) {
  Scene s = paneOverFloor();  // a window quad (2 triangles) at z = 1.5
  const int glass = static_cast<int>(s.materials.size()) - 1;
  s.meshes.push_back(makePrimitive("box", {}, "test", "mesh"));
  s.meshes.back().id = "glass_box";
  Mat4 T = Mat4::Identity();
  T.diagonal() << 1.2, 0.8, 0.02, 1;
  T(2, 3) = 0.75;
  s.objects.push_back(Object::make("glass_table_top", int(s.meshes.size()) - 1, glass, T, 9, 3));
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  s.lights = {sky};
  const EmbreeScene es(s);
  EXPECT_EQ(es.lights().portalCount(), 2u);
  // a flat glass object of too many triangles (a finely tessellated sheet) is no pane either,
  // even above the pane, in the open
  Mesh fine;
  fine.id = "fine";
  for (int i = 0; i <= 100; ++i) fine.positions.push_back(Vec3f(float(i) / 100, 0, 0));
  for (int i = 0; i <= 100; ++i) fine.positions.push_back(Vec3f(float(i) / 100, 1, 0));
  for (uint32_t i = 0; i < 100; ++i) fine.triangles.push_back(Tri(i, i + 1, i + 102));
  s.meshes.push_back(fine);
  Mat4 above = Mat4::Identity();
  above(2, 3) = 2.0;
  s.objects.push_back(Object::make("fine_glass", int(s.meshes.size()) - 1, glass, above, 40, 4));
  const EmbreeScene es2(s);
  EXPECT_EQ(es2.lights().portalCount(), 2u);
}

// A closed room 4 x 3 x 2.5 m with a 1 x 1 m window in its east wall (x from 2 to 2.1), glazed
// twice as Sweet Home 3D's windows are: two glass sheets, each a 1 mm box, 6 cm apart. Of all
// the glass only the outer sheet's outer face sees the sky: it is the portal (2 triangles on
// the plane x = 2.0805); the sheets' other faces, a glass cabinet door and a glass table top
// inside see walls or glass. The same window glazed once with a flat quad has that quad.
TEST(SkyPortal, AWindowsPortalIsItsOuterGlassFace) {
  auto room = [](bool thin_boxes) {
    Scene s;
    Mesh walls;
    walls.id = "walls";
    const double t = 0.1;
    auto slab = [&](Vec3 lo, Vec3 hi) { test::appendBox(walls, 0.5 * (lo + hi), hi - lo); };
    slab(Vec3(-2 - t, -1.5 - t, -t), Vec3(2 + t, 1.5 + t, 0));       // floor
    slab(Vec3(-2 - t, -1.5 - t, 2.5), Vec3(2 + t, 1.5 + t, 2.5 + t));  // ceiling
    slab(Vec3(-2 - t, -1.5, 0), Vec3(-2, 1.5, 2.5));
    slab(Vec3(-2, -1.5 - t, 0), Vec3(2, -1.5, 2.5));
    slab(Vec3(-2, 1.5, 0), Vec3(2, 1.5 + t, 2.5));
    slab(Vec3(2, -1.5, 0), Vec3(2 + t, 1.5, 0.75));  // the east wall round the window
    slab(Vec3(2, -1.5, 1.75), Vec3(2 + t, 1.5, 2.5));
    slab(Vec3(2, -1.5, 0.75), Vec3(2 + t, -0.5, 1.75));
    slab(Vec3(2, 0.5, 0.75), Vec3(2 + t, 1.5, 1.75));
    Mesh glass_box = makePrimitive("box", {}, "t", "box");
    glass_box.id = "glass_box";
    Mesh quad = makePrimitive("quad", {}, "t", "quad");
    quad.id = "quad";
    s.meshes = {walls, glass_box, quad};
    Material plaster, glass;
    plaster.id = "plaster";
    plaster.albedo = Vec3f::Constant(0.6f);
    glass.id = "glass";
    glass.type = MaterialType::ThinDielectric;
    glass.ior = 1.5f;
    s.materials = {plaster, glass};
    s.objects.push_back(Object::make("walls", 0, 0, Mat4::Identity(), 1, 1));
    auto glassBox = [&](const char* name, Vec3 centre, Vec3 size, int nyu40) {
      const Mat4 T = (Eigen::Translation3d(centre) * Eigen::Scaling(size)).matrix();
      s.objects.push_back(Object::make(name, 1, 1, T, nyu40, int(s.objects.size()) + 1));
    };
    if (thin_boxes) {
      glassBox("outer_sheet", Vec3(2.08, 0, 1.25), Vec3(0.001, 1, 1), 9);
      glassBox("inner_sheet", Vec3(2.02, 0, 1.25), Vec3(0.001, 1, 1), 9);
    } else {
      Mat4 P = Mat4::Identity();  // the unit quad (normal +z) turned to face +x
      P.block<3, 3>(0, 0) << 0, 0, 1, 1, 0, 0, 0, 1, 0;
      P.block<3, 1>(0, 3) = Vec3(2.0805, 0, 1.25);
      s.objects.push_back(Object::make("pane", 2, 1, P, 9, int(s.objects.size()) + 1));
    }
    glassBox("cabinet_door", Vec3(-1.5, 1.2, 1.0), Vec3(0.6, 0.002, 0.8), 3);
    glassBox("table_top", Vec3(0, 0, 0.75), Vec3(1.2, 0.8, 0.01), 7);
    Light sky;
    sky.name = "sky";
    sky.type = LightType::Sky;
    s.lights = {sky};
    return s;
  };
  for (bool thin_boxes : {true, false}) {
    const EmbreeScene es(room(thin_boxes));
    const SceneLights& lights = es.lights();
    ASSERT_EQ(lights.portalCount(), 2u) << (thin_boxes ? "two thin boxes" : "a quad");
    float area = 0.f;
    for (size_t i = 0; i < lights.portalCount(); ++i) {
      const PortalTriangle& p = lights.portal(i);
      area += p.area;
      for (const Vec3f& q : {p.p0, Vec3f(p.p0 + p.e1), Vec3f(p.p0 + p.e2)})
        EXPECT_NEAR(q.x(), 2.0805f, 1e-4f) << "the outer sheet's outer face";
      EXPECT_LT(p.normal.x(), -0.999f) << "facing the inside";
    }
    EXPECT_NEAR(area, 1.f, 1e-4f);
    // a receiver inside samples the sky through the window as well (the mixture's pdf toward
    // it is well above the uniform sky's own), one outside does not
    const float own = 1.f / (4.f * float(M_PI));
    EXPECT_GT(lights.skyPdf(0, Vec3f(1.0f, 0.f, 1.25f), Vec3f::UnitX()), 2.f * own);
    EXPECT_FLOAT_EQ(lights.skyPdf(0, Vec3f(4.0f, 0.f, 1.25f), -Vec3f::UnitX()), own);
  }
  // the same sheets standing in the open before a wall the whole sky lights: no window
  Scene open = room(true);
  open.objects[0] = Object::make(
      "wall", 1, 0,
      (Eigen::Translation3d(3.0, 0, 1.25) * Eigen::Scaling(Vec3(0.1, 40, 40))).matrix(), 1, 1);
  EXPECT_EQ(EmbreeScene(open).lights().portalCount(), 0u) << "glass in the open";
}

}  // namespace
}  // namespace inet
