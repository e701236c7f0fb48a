// Path tracer checks: a closed furnace with a known analytic radiance, the direct-lighting term
// against a closed-form irradiance, bit-identical images for 1 and 2 threads, and the split of
// the colour into emission, diffuse and the rest (IntegratorOutputs).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "core/image_io.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "scene/primitives.h"
#include "../temp_dir.h"

namespace inet {
namespace {

// The unit box with its faces turned inward (emission is one-sided along the geometric normal).
Mesh inwardBox() {
  Mesh m = makePrimitive("box", {}, "test", "box");
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  m.source.kind = MeshSource::Kind::Inline;
  m.id = "inward_box";
  return m;
}

Scene furnace(float albedo, float emission) {
  Scene s;
  s.meshes = {inwardBox()};
  Material m;
  m.id = "wall";
  m.albedo = Vec3f::Constant(albedo);
  m.emission = Vec3f::Constant(emission);
  s.materials = {m};
  Object o;
  o.name = "room";
  o.mesh = 0;
  o.material = 0;
  o.nyu40 = 1;
  o.instance = 1;
  o.T_world_object = (Eigen::Translation3d(0, 0, 1) * Eigen::Scaling(Vec3(4, 3, 2))).matrix();
  s.objects = {o};
  return s;
}

RenderOptions rgbOnly(int spp, int max_bounces) {
  RenderOptions opt;
  opt.spp = spp;
  opt.max_bounces = max_bounces;
  opt.passes = static_cast<PassMask>(Pass::Rgb);
  return opt;
}

double meanOf(const ImageF& img) {
  double sum = 0;
  for (float v : img.data) sum += v;
  return sum / img.data.size();
}

// Every surface emits Le and reflects with albedo a: radiance everywhere is Le / (1 - a).
TEST(PathTracer, FurnaceConvergesToAnalyticRadiance) {
  Scene s = furnace(0.5f, 1.0f);
  Renderer r(s);
  CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 60);
  RenderOptions opt = rgbOnly(64, 64);
  Frame f;
  r.render(K, Pose::lookAt(Vec3(0.3, -0.2, 1.1), Vec3(1, 1, 0.8), Vec3::UnitZ()), opt, 0, f);
  EXPECT_NEAR(meanOf(f.rgb), 2.0, 0.02);
}

// The white furnace as usually stated: a closed sphere of albedo 0.8 under a uniform
// environment of radiance 1. Every direction above any point of a convex object sees the
// environment, so the sphere shows exactly 0.8 and the background 1. Checked for the analytic
// sphere and for a tessellated one with smooth vertex normals (whose shading frames differ from
// its facets: no energy may appear or vanish through them).
TEST(PathTracer, WhiteFurnaceSphere) {
  for (bool tessellated : {false, true}) {
    SCOPED_TRACE(tessellated ? "tessellated, smooth normals" : "analytic sphere");
    Scene s;
    Mesh ball;
    if (!tessellated) {
      ball = makePrimitive("sphere", {{"radius", 0.5}}, "t", "ball");
    } else {  // UV sphere, 48 x 24, normals = positions / radius
      const int nu = 48, nv = 24;
      for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
          const double th = M_PI * j / nv, ph = 2 * M_PI * i / nu;
          Vec3f n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
          ball.positions.push_back(0.5f * n);
          ball.normals.push_back(n.normalized());
        }
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
          const uint32_t a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
          if (j > 0) ball.triangles.push_back(Tri(a, c, b));  // outward winding
          if (j < nv - 1) ball.triangles.push_back(Tri(b, c, d));
        }
    }
    ball.id = "ball";
    s.meshes = {ball};
    Material m;
    m.id = "white";
    m.albedo = Vec3f::Constant(0.8f);
    s.materials = {m};
    s.objects = {Object::make("ball", 0, 0, Mat4::Identity(), 40, 1)};
    Light sky;
    sky.name = "sky";
    sky.type = LightType::Sky;
    sky.intensity = 1.f;
    s.lights = {sky};
    s.validate("furnace");
    Renderer r(s);
    CameraIntrinsics K = CameraIntrinsics::centred(48, 48, 60);  // the ball fills the middle of the image
    RenderOptions opt = rgbOnly(256, 64);
    opt.passes |= static_cast<PassMask>(Pass::Instance);
    Frame f;
    r.render(K, Pose::lookAt(Vec3(0, -2, 0.3), Vec3(0, 0, 0), Vec3::UnitZ()), opt, 0, f);
    double on = 0, off = 0;
    int n_on = 0, n_off = 0;
    for (int y = 0; y < K.height; ++y)
      for (int x = 0; x < K.width; ++x) {
        const double v = f.rgb.at(x, y, 1);
        // whole pixels only: edge pixels mix ball and background
        bool edge = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = std::clamp(x + dx, 0, K.width - 1),
                      yy = std::clamp(y + dy, 0, K.height - 1);
            edge = edge || f.instance.at(xx, yy) != f.instance.at(x, y);
          }
        if (edge) continue;
        (f.instance.at(x, y) ? on : off) += v;
        ++(f.instance.at(x, y) ? n_on : n_off);
      }
    ASSERT_GT(n_on, 200);
    EXPECT_NEAR(on / n_on, 0.8, 0.008);
    EXPECT_NEAR(off / n_off, 1.0, 1e-5);
  }
}

// With max_bounces = 1 the image is emission + one bounce: Le (1 + a).
TEST(PathTracer, SingleBounceFurnace) {
  Scene s = furnace(0.8f, 0.5f);
  Renderer r(s);
  CameraIntrinsics K = CameraIntrinsics::centred(48, 32, 40);
  RenderOptions opt = rgbOnly(64, 1);
  Frame f;
  r.render(K, Pose::lookAt(Vec3(-0.5, 0.2, 0.9), Vec3(1, 0, 1.2), Vec3::UnitZ()), opt, 0, f);
  EXPECT_NEAR(meanOf(f.rgb), 0.5 * 1.8, 0.009);
}

// A large Lambertian floor under a small downward-facing emitter: the radiance of the floor
// point under the light follows from the emitter's solid angle, L = a/pi * Le * E-factor.
TEST(PathTracer, DirectLightMatchesClosedForm) {
  Scene s;
  Mesh quad = makePrimitive("quad", {}, "t", "quad");
  quad.id = "quad";
  s.meshes = {quad};
  Material floor_m, light_m;
  floor_m.id = "floor";
  floor_m.albedo = Vec3f::Constant(0.6f);
  light_m.id = "light";
  light_m.albedo = Vec3f::Zero();
  light_m.emission = Vec3f::Constant(10.f);
  s.materials = {floor_m, light_m};
  Mat4 floor_T = Mat4::Identity();
  floor_T.diagonal() << 100, 100, 1, 1;
  Object fl = Object::make("floor", 0, 0, floor_T, 2, 1);
  const double h = 2.0, w = 0.2;  // square light of side w at height h, facing down
  Object li = Object::make("light", 0, 1,
                           (Eigen::Translation3d(0, 0, h) * Eigen::AngleAxisd(M_PI, Vec3::UnitX()) *
                            Eigen::Scaling(Vec3(w, w, 1)))
                               .matrix(),
                           35, 2);
  s.objects = {fl, li};
  Renderer r(s);
  // tiny field of view: every pixel sees the floor right under the light
  CameraIntrinsics K = CameraIntrinsics::centred(8, 8, 4000);
  RenderOptions opt = rgbOnly(4096, 1);
  Frame f;
  // camera beside the light, looking straight down at the origin
  Pose pose = Pose::lookAt(Vec3(0, 0.0001, 1.0), Vec3(0, 0, 0), Vec3::UnitY());
  r.render(K, pose, opt, 0, f);
  // irradiance from a small square source: E = Le * A * cos^2 / d^2 (exact form for a square
  // above the point: integrate numerically in double)
  double E = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double x = (i + 0.5) / n * w - w / 2, y = (j + 0.5) / n * w - w / 2;
      double d2 = x * x + y * y + h * h;
      E += 10.0 * (h * h / (d2 * d2)) * (w * w / (n * n));
    }
  double expected = 0.6 / M_PI * E;
  EXPECT_NEAR(meanOf(f.rgb), expected, 0.01 * expected);
}

// A lossless dielectric inside an enclosure of uniform radiance is invisible: every pixel, through
// the glass or not, sees Le. This checks refraction, Fresnel splitting, total internal reflection
// and the delta-lobe handling of MIS at once. A thin pane must be invisible too.
Scene glassInFurnace(MaterialType glass_type, float roughness) {
  Scene s = furnace(0.f, 1.f);  // black walls emitting Le = 1
  Mesh ball = makePrimitive("sphere", {{"radius", 1.0}}, "t", "ball");
  ball.id = "ball";
  Mesh pane = makePrimitive("box", {}, "t", "pane");
  pane.id = "pane";
  s.meshes.push_back(ball);
  s.meshes.push_back(pane);
  Material glass;
  glass.id = "glass";
  glass.type = glass_type;
  glass.roughness = roughness;
  glass.ior = 1.5f;
  s.materials.push_back(glass);
  Object o = Object::make(
      "ball", 1, 1, (Eigen::Translation3d(1.0, 0.5, 1.0) * Eigen::Scaling(0.4)).matrix(), 40, 2);
  s.objects.push_back(o);
  return s;
}

TEST(PathTracer, SmoothGlassInAFurnaceIsInvisible) {
  Scene s = glassInFurnace(MaterialType::Dielectric, 0.f);
  Renderer r(s);
  RenderOptions opt = rgbOnly(64, 64);
  Frame f;
  r.render(CameraIntrinsics::centred(48, 32, 40),
           Pose::lookAt(Vec3(-0.5, 0.0, 1.0), Vec3(1.0, 0.5, 1.0), Vec3::UnitZ()), opt, 0, f);
  // every pixel, not just the mean: a lost or doubled lobe shows as a dark or bright disk or
  // ring. Per-pixel noise comes only from Russian roulette on paths with internal reflections.
  EXPECT_NEAR(meanOf(f.rgb), 1.0, 0.005);
  for (size_t i = 0; i < f.rgb.pixelCount(); ++i)
    ASSERT_NEAR(f.rgb.data[3 * i + 1], 1.0, 0.08) << "pixel " << i;
}

TEST(PathTracer, ThinPaneAndConductorInAFurnace) {
  Scene s = glassInFurnace(MaterialType::ThinDielectric, 0.f);
  Renderer r(s);
  Frame f;
  Pose pose = Pose::lookAt(Vec3(-0.5, 0.0, 1.0), Vec3(1.0, 0.5, 1.0), Vec3::UnitZ());
  r.render(CameraIntrinsics::centred(48, 32, 40), pose, rgbOnly(64, 64), 0, f);
  EXPECT_NEAR(meanOf(f.rgb), 1.0, 0.01);
  // a gold ball reflects less than it receives, more in red than in blue, never more than Le
  s.materials.back().type = MaterialType::Conductor;
  s.materials.back().metal = "gold";
  s.materials.back().albedo = Vec3f::Ones();
  s.materials.back().roughness = 0.3f;
  Renderer gold(s);
  Frame g;
  CameraIntrinsics K = CameraIntrinsics::centred(16, 16, 400);  // narrow: the ball fills the view
  gold.render(K, pose, rgbOnly(64, 16), 0, g);
  double red = 0, blue = 0;
  for (size_t i = 0; i < g.rgb.pixelCount(); ++i)
    red += g.rgb.data[3 * i], blue += g.rgb.data[3 * i + 2];
  red /= g.rgb.pixelCount();
  blue /= g.rgb.pixelCount();
  EXPECT_GT(red, 0.85);
  EXPECT_LE(red, 1.01);
  EXPECT_LT(blue, 0.6);
  EXPECT_GT(blue, 0.25);
}

// Shading is rgb / albedo, and may be asked for alone: the renderer then traces the rgb and the
// albedo it needs without reporting them as passes.
TEST(PathTracer, ShadingIsRgbOverAlbedoAndStandsAlone) {
  Scene s = furnace(0.5f, 1.0f);
  Renderer r(s);
  CameraIntrinsics K = CameraIntrinsics::centred(24, 16, 20);
  Pose pose = Pose::lookAt(Vec3(0.3, -0.2, 1.1), Vec3(1, 1, 0.8), Vec3::UnitZ());
  RenderOptions only = rgbOnly(4, 8);
  only.passes = static_cast<PassMask>(Pass::Shading);
  Frame a;
  r.render(K, pose, only, 0, a);
  EXPECT_EQ(a.passes, static_cast<PassMask>(Pass::Shading));
  ASSERT_EQ(a.shading.pixelCount(), K.width * static_cast<size_t>(K.height));
  RenderOptions both = rgbOnly(4, 8);
  both.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Albedo);
  Frame b;
  r.render(K, pose, both, 0, b);
  for (size_t i = 0; i < a.shading.data.size(); ++i)
    ASSERT_FLOAT_EQ(a.shading.data[i] * b.albedo.data[i], b.rgb.data[i]) << i;
}

TEST(PathTracer, SameBytesForOneAndTwoThreads) {
  Scene s = furnace(0.7f, 0.3f);
  Renderer r(s);
  CameraIntrinsics K = CameraIntrinsics::centred(40, 30, 30);
  RenderOptions opt = rgbOnly(4, 8);
  opt.passes = kRenderPasses;
  opt.seed = 1234;
  Pose pose = Pose::lookAt(Vec3(0.1, 0.1, 1.0), Vec3(1, 1, 1.0), Vec3::UnitZ());
  Frame a, b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    r.render(K, pose, opt, 7, a);
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    r.render(K, pose, opt, 7, b);
  }
  EXPECT_EQ(a.rgb.data, b.rgb.data);
  // a different frame index or seed gives different noise
  Frame c;
  r.render(K, pose, opt, 8, c);
  EXPECT_NE(a.rgb.data, c.rgb.data);
}

// RenderOptions::spp_multiplier: a pixel rendered at spp x m is the pixel a plain render at that
// spp gives, bit for bit (the same samples), with its layers; the sample count adds up.
TEST(PathTracer, APixelsSamplesMultiplierDrawsTheSamplesOfAPlainRenderAtThatSpp) {
  Scene s = furnace(0.7f, 0.3f);
  Renderer r(s);
  const CameraIntrinsics K = CameraIntrinsics::centred(40, 30, 30);
  const LensModel lens = LensModel::pinhole(K);
  const Pose pose = Pose::lookAt(Vec3(0.1, 0.1, 1.0), Vec3(1, 1, 1.0), Vec3::UnitZ());
  RenderOptions opt = rgbOnly(2, 8);
  opt.seed = 99;
  ImageU8 m(40, 30, 1, 1);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) m.at(x, y) = static_cast<uint8_t>(1 + (x / 7 + y / 5) % 4);
  m.at(3, 3) = 0;  // 0 counts as 1
  RenderOptions boosted = opt;
  boosted.spp_multiplier = &m;
  RenderStats stats;
  r.setStats(&stats);
  Frame f;
  RgbLayers layers;
  r.render(lens, CameraExposure::fixed(pose), boosted, 5, f, &layers);
  r.setStats(nullptr);
  uint64_t expected_samples = 0;
  for (uint8_t v : m.data) expected_samples += 2u * std::max<uint8_t>(v, 1);
  EXPECT_EQ(stats.samples.load(), expected_samples);
  int checked = 0;
  for (int mult = 1; mult <= 4; ++mult) {
    RenderOptions plain = opt;
    plain.spp = 2 * mult;
    Frame g;
    RgbLayers gl;
    r.render(lens, CameraExposure::fixed(pose), plain, 5, g, &gl);
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        if (std::max<int>(m.at(x, y), 1) != mult) continue;
        ++checked;
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(f.rgb.at(x, y, c), g.rgb.at(x, y, c)) << x << "," << y << " x" << mult;
          ASSERT_EQ(layers.variance.at(x, y, c), gl.variance.at(x, y, c)) << x << "," << y;
          ASSERT_EQ(layers.diffuse.at(x, y, c), gl.diffuse.at(x, y, c)) << x << "," << y;
        }
      }
  }
  EXPECT_EQ(checked, 40 * 30);
}

// Textures seen by indirect rays are read through a cone that a rough bounce widens
// (kIndirectConeSpread): the furnace's floor carries a millimetre checkerboard of albedo 0 and 1,
// and a narrow camera looks at the plain ceiling, so the checker reaches the image only through
// bounces. The ceiling's mean must equal the one with a flat floor of the checker's mean albedo
// (filtering keeps the mean), and so must its noise: a path reading single checker texels would
// carry throughput 0 or 1 instead of 0.5. Measured: mean 1.9905 and variance 0.00792 for both
// floors; with the cone's spread set to 0 (the camera's pixel spread only), the checker's
// variance was 0.0119, 1.5x, and the test failed.
TEST(PathTracer, IndirectRaysReadTexturesThroughAWidenedConeWithTheSameMean) {
  test::TempDir dir("cone");
  ImageF checker(64, 64, 3), flat(64, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        checker.data[(y * 64 + x) * 3 + c] = ((x + y) & 1) ? 1.f : 0.f;
        flat.data[(y * 64 + x) * 3 + c] = 0.5f;
      }
  writeExr(dir.path() / "checker.exr", checker, {"R", "G", "B"});
  writeExr(dir.path() / "flat.exr", flat, {"R", "G", "B"});
  auto ceiling = [&](const char* texture) {
    Scene s = furnace(0.5f, 1.0f);
    s.meshes.push_back(makePrimitive("quad", {}, "test", "floor"));
    Material m;
    m.id = "floor";
    m.albedo = Vec3f::Ones();
    m.emission = Vec3f::Ones();
    m.albedo_texture = TextureRef{texture, (dir.path() / texture).string()};
    m.uv_scale = Vec2f(60.f, 60.f);  // a 6.7 cm tile of 64 checks: one check is 1 mm
    s.materials.push_back(m);
    s.objects.push_back(Object::make(
        "floor", 1, 1, (Eigen::Translation3d(0, 0, 0.001) * Eigen::Scaling(Vec3(4, 4, 1))).matrix(),
        2, 2));
    Renderer r(s);
    Frame f;
    // fx 4000: a pixel spreads 0.25 mrad, a footprint under 1 mm everywhere in the box
    r.render(CameraIntrinsics::centred(48, 48, 4000),
             Pose::lookAt(Vec3(0.2, 0.1, 1.0), Vec3(0.2, 0.1, 2.0), Vec3::UnitX()), rgbOnly(4, 6),
             3, f);
    double sum = 0, sq = 0;
    const size_t n = f.rgb.data.size() / 3;
    for (size_t i = 0; i < n; ++i) {
      const double v = f.rgb.data[3 * i + 1];
      sum += v;
      sq += v * v;
    }
    const double mean = sum / n;
    return std::make_pair(mean, sq / n - mean * mean);
  };
  const auto [mean_checker, var_checker] = ceiling("checker.exr");
  const auto [mean_flat, var_flat] = ceiling("flat.exr");
  EXPECT_NEAR(mean_flat, 2.0, 0.03);  // the furnace: Le / (1 - a) everywhere
  EXPECT_NEAR(mean_checker / mean_flat, 1.0, 0.015);
  EXPECT_LT(var_checker, 1.15 * var_flat) << "checker " << var_checker << ", flat " << var_flat;
}

/// The built-in room with every material made `type` (emitters keep their emission), rendered
/// with layers: the raw colour and its parts.
struct Split {
  Frame frame;
  RgbLayers layers;
};
Split renderSplit(MaterialType type, float roughness) {
  Scene scene = makeDefaultScene();
  for (Material& m : scene.materials) {
    m.type = type;
    m.roughness = roughness;
  }
  Renderer r(scene);
  Split s;
  RenderOptions o;
  o.spp = 4;
  o.passes = static_cast<PassMask>(Pass::Rgb);
  const Pose T = Pose::lookAt(Vec3(0.6, 0.6, 1.5), Vec3(3.5, 3, 1.0), Vec3::UnitZ());
  r.render(LensModel::pinhole(CameraIntrinsics::centred(64, 48, 50.0)), CameraExposure::fixed(T),
           o, 0, s.frame, &s.layers);
  return s;
}

/// A glass slab 1 m square and 1 cm thick (NYU40 window) at x = 1.5, facing a camera at the
/// origin looking down +x, with a grey wall (albedo 0.5) 40 m square at x = 4 behind it, under a
/// uniform sky of radiance 1.
Scene paneBeforeAWall() {
  Scene s;
  Mesh box = makePrimitive("box", {}, "t", "box");
  box.id = "box";
  s.meshes = {box};
  Material glass;
  glass.id = "glass";
  glass.type = MaterialType::ThinDielectric;
  glass.ior = 1.5f;
  Material grey;
  grey.id = "grey";
  grey.albedo = Vec3f::Constant(0.5f);
  s.materials = {glass, grey};
  auto slab = [](double x, double half) {
    return (Eigen::Translation3d(x, 0, 0) * Eigen::Scaling(Vec3(0.01, 2 * half, 2 * half))).matrix();
  };
  s.objects = {Object::make("window", 0, 0, slab(1.5, 0.5), 9, 1),
               Object::make("outside", 0, 1, slab(4.0, 20.0), 1, 2)};
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.intensity = 1.f;
  s.lights = {sky};
  return s;
}

// What the camera sees straight through a window pane is kept out of the filters (returned with
// the emission): the pane's guides say nothing about the view behind it. Only the pane's
// reflection is filtered. Here a grey wall lit by a uniform sky stands behind a pane.
TEST(PathTracer, TheViewThroughAPaneIsKeptOutOfTheFiltersAndItsReflectionIsNot) {
  const Scene s = paneBeforeAWall();
  Renderer r(s);
  RenderOptions o;
  o.spp = 64;
  o.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Label);
  Frame f;
  RgbLayers layers;
  r.render(LensModel::pinhole(CameraIntrinsics::centred(32, 32, 16.0)),
           CameraExposure::fixed(Pose::lookAt(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ())), o, 0, f,
           &layers);
  double kept = 0, filtered = 0, through = 0, wall = 0, wall_rgb = 0;
  for (size_t i = 0; i < f.rgb.pixelCount(); ++i) {
    const float rgb = f.rgb.data[3 * i + 1], le = layers.emission.data[3 * i + 1];
    const int x = static_cast<int>(i % 32), y = static_cast<int>(i / 32);
    if (f.label.data[i] == 9) {
      ++through;
      kept += le;
      filtered += rgb - le;
      ASSERT_EQ(layers.diffuse.data[3 * i + 1], 0.f) << "a pane has no diffuse lobe";
    } else if (std::abs(x - 16) > 8 || std::abs(y - 16) > 8) {  // away from the pane's edge
      ++wall;
      wall_rgb += rgb;
      ASSERT_EQ(le, 0.f) << "pixel " << i << ": the wall seen directly is filtered";
    }
  }
  ASSERT_GT(through, 50);
  ASSERT_GT(wall, 50);
  kept /= through;
  filtered /= through;
  wall_rgb /= wall;
  // the wall: albedo x sky = 0.5 (its front half-space sees only sky). Clear glass at
  // near-normal incidence: a thin pane passes T = 2n / (n^2 + 1) = 0.923 and reflects
  // R = 1 - T = 0.077 (interreflections included); the slab's front and back faces are two
  // panes. Kept: the view through both, the wall, T^2 x 0.5. Filtered: the room's reflections
  // on the pane (the sky behind the camera), off the front face, R x 1, and off the back face
  // back out through the front, T R T x 1 (higher orders < 0.001)
  const double T = 2 * 1.5 / (1.5 * 1.5 + 1), R = 1 - T;
  std::printf("wall %.4f; through the pane: kept %.4f, filtered %.4f\n", wall_rgb, kept, filtered);
  EXPECT_NEAR(wall_rgb, 0.5, 0.02);
  EXPECT_NEAR(kept, T * T * 0.5, 0.01);
  EXPECT_NEAR(filtered, R + T * R * T, 0.01);
}

// The same window at 1 and 2 spp. The camera's line of sight through the slab is split at both
// faces (path_tracer.cpp PaneSplit): every pixel of the window gets the reflection and the view
// through, each with its weight, instead of one picked by its share (a pixel then had either
// the whole reflection or none, and each face sent 7.7 % of the paths away from the view).
// With the denoiser on, the view through is filtered on the guides of what lies behind the glass
// (denoise.h WindowViewLayers), its mean kept.
TEST(PathTracer, APanesTwoLobesAreBothFollowedAndTheViewThroughItIsFilteredOnItsOwnGuides) {
  const Scene s = paneBeforeAWall();
  Renderer r(s);
  const double T = 2 * 1.5 / (1.5 * 1.5 + 1), R = 1 - T;
  struct Window {
    std::vector<double> reflection, through;  // rgb - emission and emission, green, per pixel
  };
  auto render = [&](int spp, bool denoise, uint64_t seed) {
    RenderOptions o;
    o.spp = spp;
    o.seed = seed;
    o.denoise = denoise;
    o.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Label);
    Frame f;
    RgbLayers layers;
    r.render(LensModel::pinhole(CameraIntrinsics::centred(64, 64, 32.0)),
             CameraExposure::fixed(Pose::lookAt(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ())), o,
             0, f, &layers);
    Window w;
    for (size_t i = 0; i < f.rgb.pixelCount(); ++i) {
      const int x = static_cast<int>(i % 64), y = static_cast<int>(i / 64);
      if (f.label.data[i] != 9 || std::abs(x - 32) > 8 || std::abs(y - 32) > 8) continue;
      const float rgb = f.rgb.data[3 * i + 1], le = layers.emission.data[3 * i + 1];
      w.reflection.push_back(rgb - le);
      w.through.push_back(le);
    }
    return w;
  };
  auto mean = [](const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m += x;
    return m / static_cast<double>(v.size());
  };
  auto rms = [](const std::vector<double>& v, double about) {
    double e = 0;
    for (double x : v) e += (x - about) * (x - about);
    return std::sqrt(e / static_cast<double>(v.size()));
  };
  const Window one = render(1, false, 1);
  ASSERT_GT(one.through.size(), 250u);
  // the reflections of the uniform sky, R + T R T, in every pixel at 1 spp: one path stands for
  // both faces' (PaneSplit kEitherFace), R (1 + T) whichever it took, unless it reflected
  // again inside the glass (under a tenth of them)
  // (picking one lobe instead, nine pixels in ten had none)
  int off = 0;
  for (double reflection : one.reflection) off += std::abs(reflection - R * (1 + T)) > 0.005;
  EXPECT_LT(off, static_cast<int>(one.reflection.size()) / 6);
  EXPECT_NEAR(mean(one.reflection), R + T * R * T, 0.01);
  // the view through, the wall's T^2 x 0.5: no pixel without it
  const double expected = T * T * 0.5;
  for (size_t i = 0; i < one.through.size(); ++i)
    ASSERT_GT(one.through[i], 0.02 * expected) << "window pixel " << i;
  // filtered on the outside wall's guides: less noise, the same mean
  const Window raw = render(2, false, 2), filtered = render(2, true, 2);
  const double raw_error = rms(raw.through, expected);
  const double filtered_error = rms(filtered.through, expected);
  std::printf("through the pane at 2 spp: rms error %.4f raw, %.4f filtered; mean %.4f, %.4f "
              "(expected %.4f)\n",
              raw_error, filtered_error, mean(raw.through), mean(filtered.through), expected);
  EXPECT_LT(filtered_error, 0.5 * raw_error);
  EXPECT_NEAR(mean(filtered.through), expected, 0.02 * expected);
  EXPECT_NEAR(mean(filtered.reflection), R + T * R * T, 0.01);
}

TEST(PathTracer, TheDiffuseLayerIsAllOfLambertianLightSomeOfPlasticsAndNoneOfAMirrors) {
  // Lambertian: everything reflected is diffuse (same samples, up to rounding); the colour is
  // the same as without layers
  const Split lambert = renderSplit(MaterialType::Lambertian, 0.f);
  double reflected = 0, diffuse = 0;
  for (size_t i = 0; i < lambert.frame.rgb.data.size(); ++i) {
    const float r = lambert.frame.rgb.data[i] - lambert.layers.emission.data[i];
    ASSERT_NEAR(lambert.layers.diffuse.data[i], r, 1e-5f * (1.f + std::abs(r))) << i;
    ASSERT_NEAR(lambert.layers.rest_variance.data[i], 0.f, 1e-6f * (1.f + r * r)) << i;
    reflected += r;
  }
  EXPECT_GT(reflected, 0.0);
  // Plastic: the coating's reflection is not diffuse; the base is (0 <= diffuse <= reflected
  // per pixel on average, strictly less in total)
  const Split plastic = renderSplit(MaterialType::Plastic, 0.3f);
  reflected = 0;
  for (size_t i = 0; i < plastic.frame.rgb.data.size(); ++i) {
    ASSERT_GE(plastic.layers.diffuse.data[i], 0.f);
    reflected += plastic.frame.rgb.data[i] - plastic.layers.emission.data[i];
    diffuse += plastic.layers.diffuse.data[i];
  }
  std::printf("plastic room: diffuse layer %.1f %% of the reflected light\n",
              100 * diffuse / reflected);
  EXPECT_GT(diffuse, 0.5 * reflected);
  EXPECT_LT(diffuse, 0.99 * reflected);
  // a smooth mirror has no diffuse lobe
  const Split mirror = renderSplit(MaterialType::Conductor, 0.f);
  for (float d : mirror.layers.diffuse.data) ASSERT_EQ(d, 0.f);
  // the footprint albedo matches the albedo pass where the pixel sees one albedo (the albedo
  // pass is the same over the centre's 3x3 neighbourhood): exactly at most pixels, off where a
  // jittered sample catches something thinner than a pixel
  int compared = 0, exact = 0;
  double off = 0;
  for (int y = 1; y < 47; ++y)
    for (int x = 1; x < 63; ++x) {
      bool one = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          for (int c = 0; c < 3; ++c)
            one = one && lambert.frame.albedo.at(x + dx, y + dy, c) == lambert.frame.albedo.at(x, y, c);
      if (!one) continue;
      ++compared;
      double d = 0;
      for (int c = 0; c < 3; ++c)
        d += std::abs(lambert.layers.albedo.at(x, y, c) - lambert.frame.albedo.at(x, y, c));
      exact += d < 1e-5;
      off += d;
    }
  std::printf("footprint albedo = albedo pass at %d of %d one-albedo pixels, mean |diff| %.2e\n",
              exact, compared, off / compared);
  EXPECT_GT(exact, compared * 95 / 100);
  EXPECT_LT(off / compared, 3e-3);
  EXPECT_GT(compared, 64 * 48 / 2);
}

}  // namespace
}  // namespace inet
