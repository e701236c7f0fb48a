// Encodings of dataset/image_encode against expectations derived independently of the code.
#include "dataset/image_encode.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace inet {
namespace {

/// The sRGB code by the textbook formula, written out here again on purpose.
int srgbByFormula(float v) {
  double x = std::isnan(v) ? 0.0 : std::min(1.0, std::max(0.0, static_cast<double>(v)));
  double e = x <= 0.0031308 ? x * 12.92 : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
  return static_cast<int>(std::floor(e * 255.0 + 0.5));
}

TEST(ImageEncode, SrgbMatchesFormulaAroundEveryCodeBoundary) {
  // Boundary between code k-1 and k: encoded value (k - 0.5) / 255, mapped back to linear by the
  // inverse transfer function. Check 200 floats on each side of it.
  int checked = 0;
  for (int k = 1; k <= 255; ++k) {
    double e = (k - 0.5) / 255.0;
    double lin = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
    float v = static_cast<float>(lin);
    for (int i = 0; i < 100; ++i) v = std::nextafter(v, 0.0f);
    bool saw_low = false, saw_high = false;
    for (int i = 0; i < 200; ++i, v = std::nextafter(v, 2.0f)) {
      int want = srgbByFormula(v);
      ASSERT_EQ(linearToSrgb8(v), want) << "v = " << v << " near boundary " << k;
      saw_low = saw_low || want == k - 1;
      saw_high = saw_high || want == k;
      ++checked;
    }
    EXPECT_TRUE(saw_low && saw_high) << "window missed boundary " << k;
  }
  EXPECT_EQ(checked, 255 * 200);
}

TEST(ImageEncode, SrgbMatchesFormulaOnRandomAndSpecialValues) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  for (int i = 0; i < 200000; ++i) {
    float v = u(rng);
    ASSERT_EQ(linearToSrgb8(v), srgbByFormula(v)) << v;
  }
  for (int b = 0; b <= 4096; ++b) {  // every table bucket start and its neighbours
    float v = static_cast<float>(b) / 4096.0f;
    for (float w : {std::nextafter(v, 0.0f), v, std::nextafter(v, 2.0f)})
      ASSERT_EQ(linearToSrgb8(w), srgbByFormula(w)) << w;
  }
  EXPECT_EQ(linearToSrgb8(0.0f), 0);
  EXPECT_EQ(linearToSrgb8(1.0f), 255);
  EXPECT_EQ(linearToSrgb8(-3.0f), 0);
  EXPECT_EQ(linearToSrgb8(7.0f), 255);
  EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(linearToSrgb8(0.5f), 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.52
  EXPECT_EQ(linearToSrgb8(0.18f), 118);  // middle grey: 0.4614 -> 117.66
}

TEST(ImageEncode, SrgbImageKeepsShapeAndChannels) {
  ImageF img(5, 3, 3, 0.5f);
  ImageU8 out = encodeSrgb8(img);
  EXPECT_EQ(out.width, 5);
  EXPECT_EQ(out.height, 3);
  EXPECT_EQ(out.channels, 3);
  for (uint8_t v : out.data) EXPECT_EQ(v, 188);
}

TEST(ImageEncode, TumDepthIsRoundedTimes5000) {
  // Depths built from integer codes n: z = n / 5000 must store n exactly; a depth half a step
  // above n * 0.2 mm stores n + 1 (half up), just below stores n.
  ImageF z(200, 3, 1);
  for (int x = 0; x < 200; ++x) {
    int n = 1 + 327 * x;  // up to 65074
    z.at(x, 0) = static_cast<float>(n / 5000.0);
    z.at(x, 1) = static_cast<float>((n + 0.5) / 5000.0 * (1 + 1e-6));
    z.at(x, 2) = static_cast<float>((n + 0.5) / 5000.0 * (1 - 1e-6));
  }
  ImageU16 d = encodeDepth16(z, kDepthScaleTum);
  for (int x = 0; x < 200; ++x) {
    int n = 1 + 327 * x;
    EXPECT_EQ(d.at(x, 0), n);
    EXPECT_EQ(d.at(x, 1), n + 1);
    EXPECT_EQ(d.at(x, 2), n);
  }
}

TEST(ImageEncode, DepthInvalidAndOutOfRangeBecomeZero) {
  EXPECT_EQ(depthToU16(0.0f, 5000), 0);
  EXPECT_EQ(depthToU16(-1.0f, 5000), 0);
  EXPECT_EQ(depthToU16(std::numeric_limits<float>::quiet_NaN(), 5000), 0);
  EXPECT_EQ(depthToU16(std::numeric_limits<float>::infinity(), 5000), 0);
  EXPECT_EQ(depthToU16(13.107f, 5000), 65535);  // 65535 itself is a valid depth
  EXPECT_EQ(depthToU16(13.2f, 5000), 0) << "beyond the range: invalid, not clamped";
  EXPECT_EQ(depthToU16(65.535f, 1000), 65535);
  EXPECT_EQ(depthToU16(70.0f, 1000), 0);
  EXPECT_EQ(depthToU16(1.2345f, 1000), 1235);  // 1234.5 (in float: 1234.50005) rounds up
  EXPECT_EQ(depthToU16(2.0f, 1000), 2000);
  ImageU16 code(3, 1, 1);
  code.data = {0, 5000, 65535};
  ImageF back = decodeDepth16(code, 5000);
  EXPECT_EQ(back.data, (std::vector<float>{0.0f, 1.0f, 13.107f}));
}

TEST(ImageEncode, NormalsMapMinusOneToZeroAndOneToMax) {
  ImageF n(4, 1, 3);
  float px[4][3] = {{0, 0, 1}, {0, 0, -1}, {0, 0, 0}, {0.6f, -0.8f, 0}};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) n.at(x, 0, c) = px[x][c];
  ImageU16 e = encodeNormal16(n);
  // (0 + 1) / 2 * 65535 = 32767.5 rounds half up to 32768.
  EXPECT_EQ(e.at(0, 0, 0), 32768);
  EXPECT_EQ(e.at(0, 0, 2), 65535);
  EXPECT_EQ(e.at(1, 0, 2), 0);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(e.at(2, 0, c), 0) << "no surface stays zero";
  for (int c = 0; c < 2; ++c) {
    double v = static_cast<double>(px[3][c]);  // the float value, widened exactly
    EXPECT_EQ(e.at(3, 0, c), static_cast<int>(std::floor((v + 1) / 2 * 65535 + 0.5)));
  }
  ImageF d = decodeNormal16(e);
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.at(x, 0, c), n.at(x, 0, c), 1.0 / 65535 + 1e-7) << x;
}

}  // namespace
}  // namespace inet
