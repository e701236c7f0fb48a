// The padded Sobol sampler: every 2D pair of one pixel's spp samples is a (0,2)-net (one point in
// each elementary interval), pairs are decorrelated, and values depend only on their key.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "render/sampler.h"

namespace inet {
namespace {

std::vector<Eigen::Vector2f> pairOf(uint32_t spp, uint32_t pixel, int pair, uint64_t seed = 3) {
  std::vector<Eigen::Vector2f> pts;
  for (uint32_t s = 0; s < spp; ++s) {
    PixelSampler smp(seed, 0, pixel, s, spp);
    Eigen::Vector2f p;
    for (int k = 0; k <= pair; ++k) p = smp.get2D();
    pts.push_back(p);
  }
  return pts;
}

// Every elementary interval of area 1/spp (2^a x 2^b cells, a + b = log2 spp) holds one point.
bool isZeroTwoNet(const std::vector<Eigen::Vector2f>& pts) {
  int m = 0;
  while ((1u << m) < pts.size()) ++m;
  for (int a = 0; a <= m; ++a) {
    int nx = 1 << a, ny = 1 << (m - a);
    std::set<int> cells;
    for (const auto& p : pts) {
      int cx = static_cast<int>(p.x() * nx), cy = static_cast<int>(p.y() * ny);
      if (!cells.insert(cx * ny + cy).second) return false;
    }
  }
  return true;
}

TEST(PixelSampler, EveryPairIsAZeroTwoNet) {
  for (uint32_t spp : {4u, 16u, 64u, 256u})
    for (uint32_t pixel : {0u, 17u, 123456u})
      for (int pair : {0, 1, 2, 7, 20})
        EXPECT_TRUE(isZeroTwoNet(pairOf(spp, pixel, pair))) << spp << " " << pixel << " " << pair;
}

TEST(PixelSampler, PairsAndPixelsAreDecorrelated) {
  // correlation between the x coordinates of two pairs over many pixels and samples ~ 0
  double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  int n = 0;
  for (uint32_t pixel = 0; pixel < 500; ++pixel)
    for (uint32_t s = 0; s < 16; ++s) {
      PixelSampler smp(9, 2, pixel, s, 16);
      float a = smp.get2D().x(), b = smp.get2D().x();
      sxy += a * b, sx += a, sy += b, sxx += a * a, syy += b * b, ++n;
    }
  double cov = sxy / n - sx / n * sy / n;
  double corr = cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  EXPECT_LT(std::abs(corr), 0.03);
  EXPECT_NE(pairOf(16, 1, 0), pairOf(16, 2, 0));
  EXPECT_NE(pairOf(16, 1, 0, 3), pairOf(16, 1, 0, 4));
}

// One sample per pixel (spp 1, or any one sample index) over many pixels: each sample must be
// uniform jointly in its two coordinates and across pairs, not only over a pixel's whole net.
// An earlier scramble tied a sample's x and y leading digits (chi-square 786,432 on 15 degrees
// of freedom) and correlated neighbouring pairs (57): sun photons drawn one per index came out
// 4 % dark. Chi-square over 4 x 4 cells, 262,144 pixels; 40 is p ~ 0.0005.
TEST(PixelSampler, SingleSamplesAreJointlyUniform) {
  for (uint64_t seed : {1u, 777u})
    for (uint32_t index : {0u, 5u}) {
      const int n = 1 << 18;
      double within[4][4] = {}, across[4][4] = {};
      for (int pixel = 0; pixel < n; ++pixel) {
        PixelSampler s(seed, 0, static_cast<uint32_t>(pixel), index, index + 1);
        const Eigen::Vector2f a = s.get2D(), b = s.get2D(), c = s.get2D();
        within[int(a.x() * 4)][int(a.y() * 4)] += 1;
        across[int(b.x() * 4)][int(c.x() * 4)] += 1;
      }
      double chi_within = 0, chi_across = 0;
      const double e = n / 16.0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          chi_within += (within[i][j] - e) * (within[i][j] - e) / e;
          chi_across += (across[i][j] - e) * (across[i][j] - e) / e;
        }
      EXPECT_LT(chi_within, 40.0) << "seed " << seed << " index " << index;
      EXPECT_LT(chi_across, 40.0) << "seed " << seed << " index " << index;
    }
}

TEST(PixelSampler, TableSobolEqualsBitwise) {
  for (uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 65535u, 123456789u, 0xffffffffu}) {
    EXPECT_EQ(sobol_detail::sobol1(i), sobol_detail::sobol1Slow(i)) << i;
    EXPECT_EQ(sobol_detail::sobol1(i, true),
              sobol_detail::reverseBits(sobol_detail::sobol1Slow(i)));
  }
  // the first points of Sobol dimension 1 are 0, 1/2, 3/4, 1/4
  EXPECT_EQ(sobol_detail::sobol1(1), 0x80000000u);
  EXPECT_EQ(sobol_detail::sobol1(2), 0xc0000000u);
  EXPECT_EQ(sobol_detail::sobol1(3), 0x40000000u);
}

TEST(PixelSampler, InUnitSquareAndReproducible) {
  for (uint32_t s = 0; s < 64; ++s) {
    PixelSampler a(1, 5, 77, s, 64), b(1, 5, 77, s, 64);
    for (int k = 0; k < 40; ++k) {  // past kMaxPairs the counter RNG takes over
      Eigen::Vector2f p = a.get2D(), q = b.get2D();
      ASSERT_EQ(p, q);
      ASSERT_GE(p.minCoeff(), 0.f);
      ASSERT_LT(p.maxCoeff(), 1.f);
    }
  }
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

TEST(PixelSampler, PrecomputedPairHashesGiveTheSameSamples) {
  for (uint32_t pixel : {0u, 7u, 307199u}) {
    uint32_t hashes[PixelSampler::kMaxPairs];
    PixelSampler::pairHashes(5, 3, pixel, hashes);
    for (uint32_t s = 0; s < 8; ++s) {
      PixelSampler a(5, 3, pixel, s, 8), b(5, 3, pixel, s, 8, hashes);
      for (uint32_t d = 0; d < PixelSampler::kMaxPairs + 3; ++d) {  // past kMaxPairs: the RNG
        const Eigen::Vector2f pa = a.get2D(), pb = b.get2D();
        ASSERT_EQ(pa, pb) << "pixel " << pixel << " sample " << s << " pair " << d;
      }
    }
  }
}

}  // namespace
}  // namespace inet
