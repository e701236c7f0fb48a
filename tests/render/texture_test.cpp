// Mip-mapped textures: pyramid means, filtering, wrapping and the v-up convention against
// hand-computed texels; sRGB decoding of 8- and 16-bit files against the exact EOTF; loader
// errors and the cache.
#include "render/texture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "../core/jpeg_test_util.h"
#include "../temp_dir.h"
#include "core/error.h"
#include "core/image_io.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2f;

using test::TempDir;

double srgbEotf(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// Message of the InputError thrown by `f`, or "" when nothing was thrown.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

ImageF randomImage(int w, int h, int c, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  ImageF img(w, h, c);
  for (auto& v : img.data) v = U(rng);
  return img;
}

/// Texel (x, y) holds 10 y + x + 100 c: every texel and channel distinct.
ImageF indexImage(int w, int h, int c) {
  ImageF img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y, k) = static_cast<float>(10 * y + x + 100 * k);
  return img;
}

/// uv of the centre of texel (x, y) of a W x H level (v up, row 0 at the top).
Vector2f centre(int x, int y, int W, int H) {
  return {(x + 0.5f) / static_cast<float>(W), 1.0f - (y + 0.5f) / static_cast<float>(H)};
}

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(Texture, ConstantTextureIsConstantAtAnyUvAndFootprint) {
  ImageF img(13, 7, 3);
  for (size_t p = 0; p < img.pixelCount(); ++p) {
    img.data[3 * p] = 0.3f;
    img.data[3 * p + 1] = 0.6f;
    img.data[3 * p + 2] = 0.9f;
  }
  const Texture t = Texture::fromImage(img);
  for (Vector2f uv : {Vector2f(0, 0), Vector2f(0.37f, 0.81f), Vector2f(-5.2f, 17.9f),
                      Vector2f(0.999f, 0.001f), Vector2f(kNaN, kInf)})
    for (float fp : {0.0f, 1e-4f, 0.03f, 0.2f, 1.0f, 1e6f, kInf, kNaN}) {
      const Eigen::Vector3f c = t.rgb(uv, fp);
      EXPECT_FLOAT_EQ(c.x(), 0.3f) << uv.transpose() << " fp " << fp;
      EXPECT_FLOAT_EQ(c.y(), 0.6f) << uv.transpose() << " fp " << fp;
      EXPECT_FLOAT_EQ(c.z(), 0.9f) << uv.transpose() << " fp " << fp;
    }
}

TEST(Texture, EveryMipLevelKeepsTheMean) {
  struct Size {
    int w, h, levels;
  };
  for (Size s : {Size{64, 32, 7}, Size{37, 19, 6}, Size{1, 9, 4}, Size{5, 1, 3}, Size{3, 3, 2},
                 Size{255, 129, 8}})
    for (int c : {1, 3}) {
      const Texture t = Texture::fromImage(randomImage(s.w, s.h, c, 7u * s.w + s.h));
      ASSERT_EQ(t.levels(), s.levels) << s.w << "x" << s.h;
      ASSERT_EQ(t.channels(), c);
      std::vector<double> mean0;
      for (int l = 0; l < t.levels(); ++l) {
        const ImageF lv = t.level(l);
        EXPECT_EQ(lv.width, std::max(1, s.w >> l));
        EXPECT_EQ(lv.height, std::max(1, s.h >> l));
        for (int k = 0; k < c; ++k) {
          double sum = 0.0;
          for (size_t p = 0; p < lv.pixelCount(); ++p) sum += lv.data[p * c + k];
          const double mean = sum / static_cast<double>(lv.pixelCount());
          if (l == 0) mean0.push_back(mean);
          EXPECT_NEAR(mean, mean0[k], 1e-5 * mean0[k])
              << s.w << "x" << s.h << " level " << l << " channel " << k;
        }
      }
      EXPECT_EQ(t.level(t.levels() - 1).pixelCount(), 1u);
    }
}

TEST(Texture, OddSizeFilterCoversTheSourceExactly) {
  // 3 -> 1 texel: weights 1/3 each (a [1/4, 1/2, 1/4] filter would give 2.0 here).
  ImageF row(3, 1, 1);
  row.data = {0.0f, 3.0f, 9.0f};
  EXPECT_FLOAT_EQ(Texture::fromImage(row).level(1).data[0], 4.0f);
  // 5 -> 2: [1, 1, 1/2] / 2.5 and [1/2, 1, 1] / 2.5.
  ImageF five(5, 1, 1);
  five.data = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  const ImageF l1 = Texture::fromImage(five).level(1);
  EXPECT_FLOAT_EQ(l1.data[0], (1.0f + 2.0f + 1.5f) / 2.5f);
  EXPECT_FLOAT_EQ(l1.data[1], (1.5f + 4.0f + 5.0f) / 2.5f);
}

TEST(Texture, CheckerboardAveragesToHalfWithHugeFootprintAndIsExactAtTexelCentres) {
  const int W = 16, H = 8;
  ImageF img(W, H, 1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) img.at(x, y) = static_cast<float>((x + y) % 2);
  const Texture t = Texture::fromImage(img);
  for (Vector2f uv : {Vector2f(0.1f, 0.2f), Vector2f(0.77f, 0.5f), Vector2f(-3.3f, 2.01f)}) {
    EXPECT_NEAR(t.channel(uv, 1e3f, 0), 0.5f, 1e-4f);
    EXPECT_NEAR(t.channel(uv, kInf, 0), 0.5f, 1e-4f);
    // One level down every 2x2 block already averages to 1/2.
    EXPECT_NEAR(t.channel(uv, 2.0f / std::sqrt(static_cast<float>(W * H)), 0), 0.5f, 1e-6f);
  }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      EXPECT_EQ(t.channel(centre(x, y, W, H), 0.0f, 0), img.at(x, y)) << x << "," << y;
      // Grey textures replicate into every channel.
      EXPECT_EQ(t.rgb(centre(x, y, W, H), 0.0f), Eigen::Vector3f::Constant(img.at(x, y)));
    }
}

TEST(Texture, BilinearHalfwayGivesTheAverage) {
  const int W = 8, H = 4;
  const ImageF img = indexImage(W, H, 3);
  const Texture t = Texture::fromImage(img);
  float out[3];
  // Horizontally between (2, 1) and (3, 1).
  t.lookup(Vector2f(3.0f / W, 1.0f - 1.5f / H), 0.0f, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], 0.5f * (img.at(2, 1, c) + img.at(3, 1, c)));
  // Vertically between (5, 1) and (5, 2).
  t.lookup(Vector2f(5.5f / W, 1.0f - 2.0f / H), 0.0f, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], 0.5f * (img.at(5, 1, c) + img.at(5, 2, c)));
  // At u = 0 the left and right columns meet (repeat wrapping at the seam).
  t.lookup(Vector2f(0.0f, 1.0f - 2.5f / H), 0.0f, out);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[c], 0.5f * (img.at(0, 2, c) + img.at(7, 2, c)));
  // Quarter of the way: 3/4 of (2,1) + 1/4 of (3,1).
  EXPECT_FLOAT_EQ(t.channel(Vector2f(2.75f / W, 1.0f - 1.5f / H), 0.0f, 1),
                  0.75f * img.at(2, 1, 1) + 0.25f * img.at(3, 1, 1));
}

TEST(Texture, RepeatWrappingAndVUp) {
  const int W = 8, H = 4;
  const ImageF img = indexImage(W, H, 1);
  const Texture t = Texture::fromImage(img);
  for (float fp : {0.0f, 0.1f, 0.3f}) {
    const Vector2f uv(0.3125f, 0.6875f);  // exact in float, so uv + integers is exact too
    const float a = t.channel(uv, fp, 0);
    EXPECT_EQ(t.channel(uv + Vector2f(1, 0), fp, 0), a) << fp;
    EXPECT_EQ(t.channel(uv + Vector2f(0, -3), fp, 0), a) << fp;
    EXPECT_EQ(t.channel(uv + Vector2f(-7, 5), fp, 0), a) << fp;
  }
  // v is up: (0.5/W, 1 - 0.5/H) is the top-left texel of the image, (0.5/W, 0.5/H) bottom-left.
  EXPECT_EQ(t.channel(Vector2f(0.5f / W, 1.0f - 0.5f / H), 0.0f, 0), img.at(0, 0));
  EXPECT_EQ(t.channel(Vector2f(0.5f / W, 0.5f / H), 0.0f, 0), img.at(0, H - 1));
  EXPECT_EQ(t.channel(Vector2f(6.5f / W, 1.0f - 1.5f / H), 0.0f, 0), img.at(6, 1));
}

TEST(Texture, FootprintSelectsAndBlendsLevels) {
  const int W = 16, H = 16;
  const Texture t = Texture::fromImage(randomImage(W, H, 1, 3));
  const Vector2f uv = centre(1, 1, 2, 2);  // texel (1,1) of level 3, also a centre in level 4
  const float l3 = t.level(3).at(1, 1);
  const float l4 = t.level(4).at(0, 0);
  // Level = log2(footprint * 16): footprint 0.5 -> level 3 (a texel centre there: exact value).
  EXPECT_FLOAT_EQ(t.channel(uv, 0.5f, 0), l3);
  // Halfway between levels 3 and 4 (log2 = 3.5) blends them equally.
  EXPECT_NEAR(t.channel(uv, 0.5f * std::sqrt(2.0f), 0), 0.5f * (l3 + l4), 1e-5f);
}

TEST(Texture, AlphaIsDroppedAndMemoryIsFourThirds) {
  ImageF rgba(4, 2, 4);
  for (size_t i = 0; i < rgba.data.size(); ++i) rgba.data[i] = static_cast<float>(i);
  const Texture t = Texture::fromImage(rgba);
  EXPECT_EQ(t.channels(), 3);
  EXPECT_EQ(t.rgb(centre(1, 0, 4, 2), 0.0f), Eigen::Vector3f(4, 5, 6));
  ImageF ga(4, 2, 2, 0.25f);
  EXPECT_EQ(Texture::fromImage(ga).channels(), 1);

  const Texture big = Texture::fromImage(ImageF(64, 64, 3));
  EXPECT_EQ(big.bytes(), 3u * (4096 + 1024 + 256 + 64 + 16 + 4 + 1) * sizeof(float));
  EXPECT_LE(big.bytes(), 64u * 64 * 3 * 4 * 4 / 3 + 16);
}

TEST(Texture, LoadDecodesSrgbExactlyFor8And16BitPng) {
  TempDir dir;
  ImageU8 p8(3, 2, 3);
  for (size_t p = 0; p < p8.pixelCount(); ++p) {
    p8.data[3 * p] = 188;
    p8.data[3 * p + 1] = 0;
    p8.data[3 * p + 2] = 10;  // below the 0.04045 knee: c / 12.92
  }
  writePng(dir / "a8.png", p8);
  const Vector2f uv(0.4f, 0.3f);
  const Texture s8 = Texture::load(dir / "a8.png", TextureEncoding::Srgb, "scene.json", "albedo");
  ASSERT_EQ(s8.channels(), 3);
  ASSERT_EQ(s8.width(), 3);
  ASSERT_EQ(s8.height(), 2);
  const Eigen::Vector3f c = s8.rgb(uv, 0.0f);
  EXPECT_NEAR(c.x(), srgbEotf(188.0 / 255.0), 1e-7);
  EXPECT_NEAR(c.x(), 0.5029, 1e-4);
  EXPECT_EQ(c.y(), 0.0f);
  EXPECT_NEAR(c.z(), 10.0 / 255.0 / 12.92, 1e-9);
  const Texture l8 = Texture::load(dir / "a8.png", TextureEncoding::Linear, "scene.json", "rough");
  EXPECT_NEAR(l8.rgb(uv, 0.0f).x(), 188.0 / 255.0, 1e-7);

  ImageU16 p16(2, 2, 1, 48316);
  writePng(dir / "a16.png", p16);
  const Texture s16 = Texture::load(dir / "a16.png", TextureEncoding::Srgb, "scene.json", "a");
  ASSERT_EQ(s16.channels(), 1);
  EXPECT_NEAR(s16.channel(uv, 0.0f, 0), srgbEotf(48316.0 / 65535.0), 1e-7);
  const Texture l16 = Texture::load(dir / "a16.png", TextureEncoding::Linear, "scene.json", "a");
  EXPECT_NEAR(l16.channel(uv, 0.0f, 0), 48316.0 / 65535.0, 1e-7);
}

TEST(Texture, LoadsJpegAndExr) {
  TempDir dir;
  test::writeJpegForTest(dir / "grey.jpg", ImageU8(16, 8, 1, 188), 95);
  const Texture g = Texture::load(dir / "grey.jpg", TextureEncoding::Srgb, "scene.json", "a");
  EXPECT_EQ(g.width(), 16);
  EXPECT_EQ(g.height(), 8);
  EXPECT_EQ(g.channels(), 1);
  // A flat JPEG decodes to within a code of its value.
  EXPECT_GT(g.channel(Vector2f(0.3f, 0.6f), 0.0f, 0), srgbEotf(187.0 / 255.0) - 1e-6);
  EXPECT_LT(g.channel(Vector2f(0.3f, 0.6f), 0.0f, 0), srgbEotf(189.0 / 255.0) + 1e-6);
  test::writeJpegForTest(dir / "rgb.jpg", ImageU8(8, 8, 3, 90), 95);
  EXPECT_EQ(Texture::load(dir / "rgb.jpg", TextureEncoding::Srgb, "s", "f").channels(), 3);

  // EXR is linear whatever the encoding; Y-only files give one channel.
  ImageF rgb(4, 4, 3, 0.25f);
  writeExr(dir / "rgb.exr", rgb, {"R", "G", "B"});
  const Texture e = Texture::load(dir / "rgb.exr", TextureEncoding::Srgb, "scene.json", "a");
  EXPECT_EQ(e.rgb(Vector2f(0.5f, 0.5f), 0.0f), Eigen::Vector3f::Constant(0.25f));
  writeExr(dir / "y.exr", ImageF(4, 4, 1, 2.5f), {"Y"});
  const Texture y = Texture::load(dir / "y.exr", TextureEncoding::Linear, "scene.json", "a");
  EXPECT_EQ(y.channels(), 1);
  EXPECT_EQ(y.channel(Vector2f(0.1f, 0.1f), 0.0f, 0), 2.5f);
  writeExr(dir / "z.exr", ImageF(4, 4, 1, 1.0f), {"Z"});
  const std::string msg =
      errorOf([&] { Texture::load(dir / "z.exr", TextureEncoding::Linear, "scene.json", "a"); });
  EXPECT_NE(msg.find("it has: Z"), std::string::npos) << msg;
}

TEST(Texture, LoadErrorsNameTheSceneFileAndThePath) {
  TempDir dir;
  std::ofstream(dir / "junk.png") << "not an image at all";
  writePng(dir / "ok.png", ImageU8(32, 32, 3, 7));
  std::ifstream in(dir / "ok.png", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() - 30);
  std::ofstream(dir / "cut.jpg", std::ios::binary) << "\xff\xd8\xff\xe0";
  fs::create_directories(dir / "folder.png");
  for (const std::string name : {"missing.png", "folder.png", "junk.png", "cut.png", "cut.jpg"}) {
    const std::string path = dir / name;
    const std::string msg = errorOf(
        [&] { Texture::load(path, TextureEncoding::Srgb, "layout.json", "materials[2].albedo"); });
    EXPECT_NE(msg.find("layout.json"), std::string::npos) << name << ": " << msg;
    EXPECT_NE(msg.find("materials[2].albedo"), std::string::npos) << name << ": " << msg;
    EXPECT_NE(msg.find("'" + path + "'"), std::string::npos) << name << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

TEST(Texture, CacheReturnsOneTexturePerPathAndEncoding) {
  TempDir dir;
  writePng(dir / "a.png", ImageU8(8, 8, 3, 188));
  TextureCache cache;
  const Texture* s = cache.get(dir / "a.png", TextureEncoding::Srgb, "scene.json", "a");
  EXPECT_EQ(cache.get(dir / "a.png", TextureEncoding::Srgb, "other.json", "b"), s);
  EXPECT_EQ(cache.get(dir / "./a.png", TextureEncoding::Srgb, "scene.json", "a"), s);
  const Texture* l = cache.get(dir / "a.png", TextureEncoding::Linear, "scene.json", "a");
  EXPECT_NE(l, s);
  EXPECT_NE(s->channel(Vector2f(0.5f, 0.5f), 0.0f, 0), l->channel(Vector2f(0.5f, 0.5f), 0.0f, 0));
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.bytes(), s->bytes() + l->bytes());
  EXPECT_THROW(cache.get(dir / "nope.png", TextureEncoding::Srgb, "scene.json", "a"), InputError);
  EXPECT_EQ(cache.size(), 2u) << "a failed load caches nothing";
}

}  // namespace
}  // namespace inet
