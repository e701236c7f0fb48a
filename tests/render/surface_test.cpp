// Shading points (EmbreeScene::surface) through the whole renderer: texture coordinates and the
// v-up convention, mip level selection from the pixel footprint, smooth vertex normals, normal
// maps, and textured albedo in the path tracer. The scenes are a textured quad seen straight from
// above, so every pixel's texture coordinate is known in closed form:
//   camera at (0, 0, 1) looking down, image up = world +Y, K = 64x64 px, f = 32 px: the image
//   spans exactly the quad [-1, 1]^2 at z = 0, and pixel (x, y) sees
//   u = (x + 0.5) / 64, v = 1 - (y + 0.5) / 64.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "../temp_dir.h"
#include "core/image_io.h"
#include "render/renderer.h"
#include "render/texture.h"
#include "scene/primitives.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
constexpr int kSize = 64;

using test::TempDir;

double srgbDecode(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// A 2 x 2 m quad at z = 0 with one material (ids "quad"), optionally textured.
Scene quadScene(const Material& m) {
  Scene s;
  Mesh quad = makePrimitive("quad", {}, "t", "quad");
  quad.id = "quad";
  s.meshes = {quad};
  s.materials = {m};
  Mat4 T = Mat4::Identity();
  T.diagonal() << 2, 2, 1, 1;
  s.objects = {Object::make("quad", 0, 0, T, 2, 1)};
  return s;
}

Material textured(const std::string& albedo_png) {
  Material m;
  m.id = "quad";
  m.albedo = Vec3f::Ones();
  m.albedo_texture = TextureRef{albedo_png, albedo_png};
  return m;
}

CameraIntrinsics topCamera() {
  CameraIntrinsics K;
  K.width = K.height = kSize;
  K.fx = K.fy = kSize / 2.0;
  K.cx = K.cy = kSize / 2.0;
  return K;
}

Pose topPose() {
  return Pose::lookAt(Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3::UnitY());
}

Frame renderPasses(const Scene& s, PassMask passes, int spp = 1, int bounces = 8) {
  Renderer r(s);
  RenderOptions opt;
  opt.spp = spp;
  opt.max_bounces = bounces;
  opt.passes = passes;
  Frame f;
  r.render(topCamera(), topPose(), opt, 0, f);
  return f;
}

/// 4 x 4 texels, each a distinct colour, as an 8-bit sRGB PNG.
ImageU8 colourTexels() {
  ImageU8 img(4, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      img.at(x, y, 0) = static_cast<uint8_t>(30 + 60 * x);
      img.at(x, y, 1) = static_cast<uint8_t>(20 + 70 * y);
      img.at(x, y, 2) = static_cast<uint8_t>((x + y) % 2 ? 200 : 40);
    }
  return img;
}

TEST(Surface, AlbedoPassReadsTheTextureAtEachPixelsCoordinate) {
  TempDir dir;
  const std::string png = (dir / "texels.png").string();
  writePng(png, colourTexels());
  Frame f = renderPasses(quadScene(textured(png)), static_cast<PassMask>(Pass::Albedo));
  TextureCache cache;
  const Texture* tex = cache.get(png, TextureEncoding::Srgb, "", "test");
  double worst = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const Eigen::Vector2f uv((x + 0.5f) / kSize, 1.f - (y + 0.5f) / kSize);
      const Vec3f want = tex->rgb(uv, 0.f);  // footprint 1/64 uv: far below one texel
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::fabs(double(f.albedo.at(x, y, c)) - want[c]));
    }
  }
  EXPECT_LT(worst, 2e-4);
  // orientation: texel (1, 2) of the file is image block (1, 2) (v points up the image)
  const ImageU8 texels = colourTexels();
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(f.albedo.at(16 + 8, 32 + 8, c), srgbDecode(texels.at(1, 2, c) / 255.0), 0.04);
}

/// 8 x 8 texels: a checkerboard of 2 x 2-texel squares, black and white.
std::string writeChecker(const TempDir& dir) {
  ImageU8 img(8, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) img.at(x, y) = ((x / 2 + y / 2) % 2) ? 255 : 0;
  const std::string png = (dir / "checker.png").string();
  writePng(png, img);
  return png;
}

TEST(Surface, MipLevelFollowsThePixelFootprint) {
  TempDir dir;
  const std::string png = writeChecker(dir);
  // A pixel covers 1/64 of the quad's uv range. uv_scale 32: 32 x 8 = 256 texels across 64 px,
  // 4 texels per pixel: the footprint selects level 2 (2 x 2 texels, all grey 0.5). A renderer
  // that ignored the footprint would alias to black and white.
  Material m = textured(png);
  m.uv_scale = Vec2f(32, 32);
  Frame far = renderPasses(quadScene(m), static_cast<PassMask>(Pass::Albedo));
  for (size_t i = 0; i < far.albedo.data.size(); ++i)
    ASSERT_NEAR(far.albedo.data[i], 0.5f, 0.02f) << "pixel " << i / 3;
  // uv_scale 2: 16 texels across 64 px, 4 px per texel: level 0, the checker itself, keeps
  // its contrast (level 1 would already halve it).
  m.uv_scale = Vec2f(2, 2);
  Frame near = renderPasses(quadScene(m), static_cast<PassMask>(Pass::Albedo));
  double sum = 0, sum2 = 0;
  const size_t n = near.albedo.pixelCount();
  for (size_t i = 0; i < n; ++i) {
    sum += near.albedo.data[3 * i];
    sum2 += near.albedo.data[3 * i] * near.albedo.data[3 * i];
  }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
  EXPECT_GT(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.3) << "standard deviation";
}

TEST(Surface, VertexNormalsAreInterpolatedInTheNormalPass) {
  // vertex normals tilted along x: n(x) ~ (a x, 0, 1) at the quad's corners x = -0.5, 0.5.
  // Barycentric interpolation on either triangle is then linear in x:
  // n = (0.5 - x) n(-0.5) + (0.5 + x) n(0.5), normalised.
  Material m;
  m.id = "quad";
  Scene s = quadScene(m);
  const float a = 1.2f;
  for (const Vec3f& p : s.meshes[0].positions)
    s.meshes[0].normals.push_back(Vec3f(a * p.x(), 0.f, 1.f).normalized());
  Frame f = renderPasses(s, static_cast<PassMask>(Pass::Normal));
  const Vec3f nl = Vec3f(-0.5f * a, 0, 1).normalized(), nr = Vec3f(0.5f * a, 0, 1).normalized();
  double worst = 0;
  for (int y = 0; y < kSize; y += 3) {
    for (int x = 0; x < kSize; x += 3) {
      const float xo = ((x + 0.5f) / kSize - 0.5f);  // object-space x of the pixel's hit
      // object-space interpolation, then the object's inverse transpose diag(1/2, 1/2, 1)
      Vec3f n = ((0.5f - xo) * nl + (0.5f + xo) * nr).cwiseProduct(Vec3f(0.5f, 0.5f, 1.f));
      n.normalize();
      const Vec3f n_cam(n.x(), -n.y(), -n.z());  // camera: x = +X, y = -Y, z = -Z
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::fabs(double(f.normal.at(x, y, c)) - n_cam[c]));
    }
  }
  EXPECT_LT(worst, 1e-4);
}

TEST(Surface, CylinderNormalsAreSmooth) {
  // An 8-sided cylinder seen from the side: flat facets would make the normal jump by 45
  // degrees between neighbouring pixels; smooth normals change by a few degrees at most.
  Scene s;
  Mesh cyl = makePrimitive("cylinder", {{"segments", 8}}, "t", "cyl");
  cyl.id = "cyl";
  s.meshes = {cyl};
  Material m;
  m.id = "grey";
  s.materials = {m};
  s.objects = {Object::make("cyl", 0, 0, Mat4::Identity(), 2, 1)};
  Renderer r(s);
  RenderOptions opt;
  opt.passes = static_cast<PassMask>(Pass::Normal);
  Frame f;
  CameraIntrinsics K = topCamera();
  K.fx = K.fy = 64;
  r.render(K, Pose::lookAt(Vec3(3, 0, 0), Vec3(0, 0, 0), Vec3::UnitZ()), opt, 0, f);
  double max_step = 0;
  int on_object = 0, changed = 0;
  const int y = kSize / 2;
  for (int x = 1; x < kSize; ++x) {
    Vec3f a(f.normal.pixel(x - 1, y)), b(f.normal.pixel(x, y));
    if (a.norm() < 0.5f || b.norm() < 0.5f) continue;  // background
    ++on_object;
    const double step = std::acos(std::clamp(a.dot(b), -1.f, 1.f));
    max_step = std::max(max_step, step);
    changed += step > 1e-3;
  }
  EXPECT_GT(on_object, 15);
  EXPECT_EQ(changed, on_object) << "flat facets repeat one normal across many pixels";
  EXPECT_LT(max_step, 0.5) << "radians between neighbouring pixels (a facet edge: 0.785)";
}

/// A 200 x 200 m Lambertian floor lit by a sun straight overhead; radiance of the floor point
/// under the camera (the mean of a tiny image), one bounce.
double sunlitFloor(const Material& m) {
  Scene s = quadScene(m);
  s.objects[0].T_world_object.diagonal() << 200, 200, 1, 1;
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = -Vec3::UnitZ();
  sun.intensity = 3.f;
  s.lights = {sun};
  Renderer r(s);
  CameraIntrinsics K;
  K.width = K.height = 4;
  K.fx = K.fy = 40000;
  K.cx = K.cy = 2;
  RenderOptions opt;
  opt.spp = 64;
  opt.max_bounces = 1;
  opt.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Normal);
  Frame f;
  r.render(K, Pose::lookAt(Vec3(0.3, 0.2, 1.0), Vec3(0.3, 0.2, 0), Vec3::UnitY()), opt, 0, f);
  // the normal pass leaves normal maps out: it is the geometric +Z (camera -z)
  for (size_t i = 0; i < f.normal.pixelCount(); ++i)
    EXPECT_NEAR(f.normal.data[3 * i + 2], -1.f, 1e-6);
  double sum = 0;
  for (size_t i = 0; i < f.rgb.pixelCount(); ++i) sum += f.rgb.data[3 * i + 1];
  return sum / f.rgb.pixelCount();
}

TEST(Surface, NormalMapTiltsTheShadingNormal) {
  // A constant normal map (sin 40, 0, cos 40) in tangent space. The quad's tangent (dp/du) is
  // +X and bitangent (dp/dv) +Y, so the shading normal leans 40 degrees towards +X and the
  // sunlit floor's radiance drops from a/pi E to a/pi E cos 40.
  TempDir dir;
  const double tilt = 40.0 * M_PI / 180.0;
  ImageF map(2, 2, 3);
  for (size_t i = 0; i < map.pixelCount(); ++i) {
    map.data[3 * i] = static_cast<float>(0.5 * (std::sin(tilt) + 1));
    map.data[3 * i + 1] = 0.5f;
    map.data[3 * i + 2] = static_cast<float>(0.5 * (std::cos(tilt) + 1));
  }
  const std::string exr = (dir / "normal.exr").string();
  writeExr(exr, map, {"R", "G", "B"});
  Material m;
  m.id = "quad";
  m.albedo = Vec3f::Constant(0.6f);
  const double flat = sunlitFloor(m);
  EXPECT_NEAR(flat, 0.6 / M_PI * 3.0, 2e-3);
  m.normal_texture = TextureRef{exr, exr};
  EXPECT_NEAR(sunlitFloor(m), 0.6 / M_PI * 3.0 * std::cos(tilt), 2e-3);
}

TEST(Surface, PathTracerShadesWithTheTexturedAlbedo) {
  // Sun overhead, one bounce: every pixel's radiance is albedo(pixel) / pi * E, so rgb and the
  // albedo pass must agree: the bilinear texture is linear across each pixel (its kinks lie on
  // pixel edges), so the pixel's area average equals the centre sample; the samples estimate
  // that average (256 samples) to within 1e-3, 4% of the largest change across one pixel.
  TempDir dir;
  const std::string png = (dir / "texels.png").string();
  writePng(png, colourTexels());
  Scene s = quadScene(textured(png));
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = -Vec3::UnitZ();
  sun.intensity = 2.f;
  s.lights = {sun};
  Frame f = renderPasses(s, static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Albedo),
                         256, 1);
  double worst = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double want = f.albedo.at(x, y, c) / M_PI * 2.0;
        worst = std::max(worst, std::fabs(f.rgb.at(x, y, c) - want));
      }
    }
  }
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace inet
