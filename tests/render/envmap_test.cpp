// The environment-map sky (render/sky.h EnvMapSkyLight, SkyModel::EnvMap). Expectations come
// from elsewhere than the code under test:
//  - the direction convention: Mitsuba's envmap formula u = atan2(x, -z) / 2 pi,
//    v = acos(y) / pi (its Y-up frame), written out here, against our Z-up map frame;
//  - a constant map against the uniform sky of the same radiance (both rendered);
//  - importance sampling of a map with one bright texel against uniform sphere sampling and a
//    quadrature of the radiance itself;
//  - the sampler's pdf against the pdf of escaped rays, and its integral (1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../temp_dir.h"
#include "core/color.h"
#include "core/image_io.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "render/sky.h"
#include "scene/primitives.h"

namespace inet {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Rng {
  explicit Rng(uint64_t seed) : gen(seed) {}
  float operator()() { return static_cast<float>(gen() >> 40) * 0x1p-24f; }
  std::mt19937_64 gen;
};

/// Our map frame is Mitsuba's (Y up) turned so that its +Y is +Z: (x, y, z) -> (x, -z, y).
Vec3f fromMitsuba(const Vec3f& d) {
  return {d.x(), -d.z(), d.y()};
}

/// Mitsuba's envmap lookup coordinates of a direction in its own (Y-up) emitter frame.
Eigen::Vector2f mitsubaUv(const Vec3f& d) {
  float u = std::atan2(d.x(), -d.z()) / (2.f * static_cast<float>(kPi));
  if (u < 0.f) u += 1.f;
  return {u, std::acos(std::clamp(d.y(), -1.f, 1.f)) / static_cast<float>(kPi)};
}

TEST(EnvMap, MitsubaDirectionConvention) {
  // known directions in Mitsuba's frame: -z is the image's left edge (u = 0), +x a quarter in,
  // +y the top row
  const std::vector<std::pair<Vec3f, Eigen::Vector2f>> known = {
      {{0, 0, -1}, {0.f, 0.5f}},  {{1, 0, 0}, {0.25f, 0.5f}}, {{0, 0, 1}, {0.5f, 0.5f}},
      {{-1, 0, 0}, {0.75f, 0.5f}}, {{0, 1, 0}, {0.f, 0.f}},  {{0, -1, 0}, {0.f, 1.f}}};
  for (const auto& [d, uv] : known) {
    EXPECT_TRUE(mitsubaUv(d).isApprox(uv, 1e-6) || d.y() != 0.f) << d.transpose();
    const Eigen::Vector2f ours = EnvMapSkyLight::directionToUv(fromMitsuba(d));
    EXPECT_NEAR(ours.y(), uv.y(), 1e-6) << d.transpose();
    if (d.y() == 0.f) {
      EXPECT_NEAR(ours.x(), uv.x(), 1e-6) << d.transpose();
    }
  }
  Rng rng(1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f d = Vec3f(rng() - 0.5f, rng() - 0.5f, rng() - 0.5f).normalized();
    EXPECT_TRUE(EnvMapSkyLight::directionToUv(fromMitsuba(d)).isApprox(mitsubaUv(d), 1e-4));
    const Vec3f back = EnvMapSkyLight::uvToDirection(EnvMapSkyLight::directionToUv(d));
    EXPECT_TRUE(back.isApprox(d, 1e-4)) << d.transpose();
  }
}

TEST(EnvMap, TexelCentresAndRotation) {
  ImageF img(8, 4, 3, 0.f);
  img.at(3, 1, 0) = 5.f;  // a red texel: centre at u = 3.5 / 8, v = 1.5 / 4
  const Eigen::Vector2f centre(3.5f / 8, 1.5f / 4);
  const EnvMapSkyLight map(img, Mat3::Identity(), 2.f);
  EXPECT_NEAR(map.radiance(EnvMapSkyLight::uvToDirection(centre)).x(), 10.f, 1e-4);
  EXPECT_EQ(map.radiance(EnvMapSkyLight::uvToDirection({7.5f / 8, 3.5f / 4})), Vec3f::Zero());
  // turned 90 degrees about z: the texel is seen along the turned direction
  const Mat3 R = Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()).toRotationMatrix();
  const EnvMapSkyLight turned(img, R, 2.f);
  const Vec3f d = EnvMapSkyLight::uvToDirection(centre);
  EXPECT_NEAR(turned.radiance(R.cast<float>() * d).x(), 10.f, 1e-4);
}

/// A large Lambertian floor (albedo 0.6) under `sky`, seen straight down in a tiny field of view:
/// its radiance is albedo / pi * E (lights_test.cpp does the same for the other lights).
double floorRadiance(const Light& sky, int spp) {
  Scene s;
  Mesh quad = makePrimitive("quad", {}, "t", "quad");
  quad.id = "quad";
  s.meshes = {quad};
  Material m;
  m.id = "floor";
  m.albedo = Vec3f::Constant(0.6f);
  s.materials = {m};
  Mat4 T = Mat4::Identity();
  T.diagonal() << 200, 200, 1, 1;
  s.objects = {Object::make("floor", 0, 0, T, 2, 1)};
  s.lights = {sky};
  Renderer r(s);
  CameraIntrinsics K = CameraIntrinsics::centred(4, 4, 40000);
  RenderOptions opt;
  opt.spp = spp;
  opt.max_bounces = 1;
  opt.passes = static_cast<PassMask>(Pass::Rgb);
  Frame f;
  r.render(K, Pose::lookAt(Vec3(0, 0, 1), Vec3::Zero(), Vec3::UnitY()), opt, 0, f);
  double sum = 0;
  for (size_t i = 0; i < f.rgb.pixelCount(); ++i) sum += f.rgb.data[3 * i + 1];
  return sum / f.rgb.pixelCount();
}

Light envMapLight(const test::TempDir& dir, const ImageF& img, float scale = 1.f) {
  const auto path = dir / "map.exr";
  writeExr(path, img, {"R", "G", "B"});
  Light l;
  l.name = "map";
  l.type = LightType::Sky;
  l.sky_model = SkyModel::EnvMap;
  l.envmap.file = l.envmap.path = path.string();
  l.intensity = scale;
  return l;
}

TEST(EnvMap, ConstantMapEqualsUniformSky) {
  test::TempDir dir("envmap");
  Light uniform;
  uniform.name = "sky";
  uniform.type = LightType::Sky;
  uniform.intensity = 0.7f;
  const Light map = envMapLight(dir, ImageF(16, 8, 3, 0.35f), 2.f);
  const double a = floorRadiance(uniform, 1024), b = floorRadiance(map, 1024);
  EXPECT_NEAR(a, 0.6 * 0.7, 0.01 * 0.42);  // the closed form: albedo x L
  EXPECT_NEAR(b, a, 0.01 * a);
}

/// A 32 x 16 map, dim everywhere (0.02) but one texel (500) at 30 degrees above the horizon.
ImageF oneBrightTexel() {
  ImageF img(32, 16, 3, 0.02f);
  for (int c = 0; c < 3; ++c) img.at(5, 5, c) = 500.f;  // theta = 5.5 / 16 pi = 62 degrees
  return img;
}

/// E = int L(w) max(cos, 0) dw over the sphere by quadrature of the map's own radiance.
double irradianceQuadrature(const EnvMapSkyLight& map) {
  const int nt = 800, np = 1600;
  double E = 0;
  for (int i = 0; i < nt / 2; ++i) {
    const double t0 = kPi * i / nt, t1 = kPi * (i + 1) / nt, t = 0.5 * (t0 + t1);
    const double w = (std::cos(t0) - std::cos(t1)) * 2 * kPi / np;
    for (int j = 0; j < np; ++j) {
      const double p = 2 * kPi * (j + 0.5) / np;
      const Vec3f d(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
      E += map.radiance(d).y() * std::cos(t) * w;
    }
  }
  return E;
}

TEST(EnvMap, ImportanceSamplingAgreesWithUniformSampling) {
  const EnvMapSkyLight map(oneBrightTexel(), Mat3::Identity(), 1.f);
  const double exact = irradianceQuadrature(map);
  Rng rng(7);
  const int n = 200000;
  double sum_is = 0, sq_is = 0, sum_u = 0, sq_u = 0;
  for (int i = 0; i < n; ++i) {
    Vec3f wi, L;
    float pdf;
    ASSERT_TRUE(map.sample({rng(), rng()}, wi, L, pdf));
    ASSERT_NEAR(pdf, map.pdf(wi), 1e-6f * pdf);
    const double x = wi.z() > 0 ? L.y() * wi.z() / pdf : 0.0;
    sum_is += x;
    sq_is += x * x;
    // uniform on the sphere: pdf 1 / (4 pi)
    const float z = 1.f - 2.f * rng(), r = std::sqrt(std::max(0.f, 1.f - z * z)), ph = 2 * kPi * rng();
    const Vec3f d(r * std::cos(ph), r * std::sin(ph), z);
    const double y = z > 0 ? map.radiance(d).y() * z * 4 * kPi : 0.0;
    sum_u += y;
    sq_u += y * y;
  }
  const double mean_is = sum_is / n, mean_u = sum_u / n;
  const double se_is = std::sqrt((sq_is / n - mean_is * mean_is) / n);
  const double se_u = std::sqrt((sq_u / n - mean_u * mean_u) / n);
  EXPECT_NEAR(mean_is, exact, 4 * se_is + 1e-3 * exact);
  EXPECT_NEAR(mean_u, exact, 4 * se_u + 1e-3 * exact);
  EXPECT_LT(se_is, 0.2 * se_u);  // the point of importance sampling
}

TEST(EnvMap, PdfIntegratesToOneAndMatchesSceneLights) {
  test::TempDir dir("envmap");
  Scene s;
  s.lights = {envMapLight(dir, oneBrightTexel())};
  const SceneLights lights(s, {});
  const EnvMapSkyLight map(oneBrightTexel(), Mat3::Identity(), 1.f);
  double total = 0;  // int pdf dw over the sphere
  const int nt = 400, np = 800;
  for (int i = 0; i < nt; ++i) {
    const double t0 = kPi * i / nt, t1 = kPi * (i + 1) / nt, t = 0.5 * (t0 + t1);
    for (int j = 0; j < np; ++j) {
      const double p = 2 * kPi * (j + 0.5) / np;
      const Vec3f d(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
      total += map.pdf(d) * (std::cos(t0) - std::cos(t1)) * 2 * kPi / np;
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-3);
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    LightSample ls;
    const SceneLights::PickPoint at = lights.pickAt(Vec3f::Zero());
    if (!lights.sample(at, rng(), {rng(), rng()}, ls)) continue;
    float pdf;
    const Vec3f L = lights.environmentRadiance(ls.wi, &at, pdf);
    EXPECT_NEAR(pdf, ls.pdf, 1e-5f * ls.pdf);
    EXPECT_TRUE(L.isApprox(ls.radiance, 1e-5f));
  }
}

TEST(EnvMap, RenderedFloorMatchesQuadrature) {
  test::TempDir dir("envmap");
  const Light light = envMapLight(dir, oneBrightTexel());
  const double expected = 0.6 / kPi * irradianceQuadrature(EnvMapSkyLight(light, "t"));
  EXPECT_NEAR(floorRadiance(light, 256), expected, 0.02 * expected);
}

}  // namespace
}  // namespace inet
