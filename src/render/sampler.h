#pragma once
// Low-discrepancy samples for the path tracer: a "padded" scrambled Sobol sampler.
//
// Every 2D sample of a path (pixel position, light sample, BSDF sample, ...) comes from the first
// two dimensions of the Sobol sequence, a (0,2)-sequence, so the spp points of one pixel are
// stratified in every pair of dimensions. Pairs are decorrelated from each other by shuffling the
// sample index per pair and Owen-scrambling each coordinate, both by hashing (Burley, "Practical
// Hash-based Owen Scrambling", JCGT 2020; the same scheme as pbrt-v4's PaddedSobolSampler).
// Hand-written because the generator is a dozen lines of bit operations and no Debian package
// offers random access to scrambled Sobol points by (pixel, sample, dimension).
//
// All state is a pure function of (seed, frame, pixel, sample index), so the image does not depend
// on thread count or tile order. Past kMaxPairs pairs (deep bounces) it continues with the
// counter-based RNG, where stratification no longer pays.
#include <Eigen/Core>
#include <cstdint>

#include "core/rng.h"

namespace inet {

namespace sobol_detail {

inline uint32_t reverseBits(uint32_t x) {
  x = __builtin_bswap32(x);  // bytes in reverse order, then the bits inside each byte
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
}

/// Laine-Karras style permutation: each output bit depends only on the same and lower input bits.
inline uint32_t laineKarras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

/// Nested uniform (Owen) scrambling of a 32-bit fixed-point value in [0, 1).
inline uint32_t owenScramble(uint32_t x, uint32_t seed) {
  return reverseBits(laineKarras(reverseBits(x), seed));
}

/// Sobol dimension 0 (van der Corput in base 2) at index i, as 32-bit fixed point.
inline uint32_t sobol0(uint32_t i) {
  return reverseBits(i);
}

/// Sobol dimension 1 at index i (primitive polynomial x + 1, direction numbers all 1), bit by bit.
inline uint32_t sobol1Slow(uint32_t i) {
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) r ^= v;
  return r;
}

/// The same, by table: the generator is linear over GF(2), so the index is taken a byte at a time.
/// With `reversed`, the result comes bit-reversed (bit reversal is linear too), which is the form
/// Owen scrambling works on. The table is built at compile time (no run-time initialisation
/// guard on this hot path).
struct Sobol1Tables {
  uint32_t t[2][4][256];
};
constexpr uint32_t sobol1Constexpr(uint32_t i) {
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) r ^= v;
  return r;
}
constexpr uint32_t reverseBitsConstexpr(uint32_t x) {
  uint32_t r = 0;
  for (int b = 0; b < 32; ++b) r |= ((x >> b) & 1u) << (31 - b);
  return r;
}
constexpr Sobol1Tables makeSobol1Tables() {
  Sobol1Tables tables{};
  for (int b = 0; b < 4; ++b)
    for (uint32_t v = 0; v < 256; ++v) {
      tables.t[0][b][v] = sobol1Constexpr(v << (8 * b));
      tables.t[1][b][v] = reverseBitsConstexpr(tables.t[0][b][v]);
    }
  return tables;
}
inline constexpr Sobol1Tables kSobol1Tables = makeSobol1Tables();

inline uint32_t sobol1(uint32_t i, bool reversed = false) {
  const auto& t = kSobol1Tables.t[reversed ? 1 : 0];
  return t[0][i & 0xff] ^ t[1][(i >> 8) & 0xff] ^ t[2][(i >> 16) & 0xff] ^ t[3][i >> 24];
}

/// splitmix64's finaliser: every input bit flips each output bit with probability about 1/2.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// murmur3's 32-bit finaliser, the same for 32 bits.
inline uint32_t mix32(uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}

/// 32-bit hash of four words, each folded in through a full avalanche. The scrambles of
/// different sample dimensions must be independent: an earlier hash left the low bits of
/// neighbouring dimensions' seeds correlated, and Owen scrambling turns a seed's low bits into
/// a sample's leading digits (sampler_test checks the joint distribution).
inline uint32_t hash4(uint64_t a, uint32_t b, uint32_t c, uint32_t d) {
  uint64_t h = mix64(a + 0x9e3779b97f4a7c15ull);
  h = mix64(h ^ (static_cast<uint64_t>(b) << 32 | c));
  h = mix64(h + (static_cast<uint64_t>(d) + 1u) * 0x632be59bd9b4e019ull);
  return static_cast<uint32_t>(h >> 32);
}

}  // namespace sobol_detail

class PixelSampler {
 public:
  static constexpr uint32_t kMaxPairs = 32;

  /// spp: samples per pixel of the image (sample_index < spp); sets the size of the power-of-two
  /// block within which sample indices are shuffled.
  /// `pair_hashes`, when given, holds pairHashes(seed, frame, pixel) (kMaxPairs values, alive as
  /// long as the sampler): they depend on the pixel only, so a renderer computes them once per
  /// pixel instead of once per sample and pair. The samples are the same either way.
  PixelSampler(uint64_t seed, uint32_t frame, uint32_t pixel, uint32_t sample_index, uint32_t spp,
               const uint32_t* pair_hashes = nullptr)
      : seed_(seed),
        frame_(frame),
        pixel_(pixel),
        index_(sample_index),
        index_mask_(blockMask(spp)),
        index_reversed_(sobol_detail::reverseBits(sample_index)),
        pair_hashes_(pair_hashes),
        rng_(seed, RngStream::PathTracer, frame, pixel, sample_index) {}

  /// The next 2D sample in [0,1)^2.
  Eigen::Vector2f get2D() {
    if (pair_ >= kMaxPairs) return {rng_.uniform(), rng_.uniform()};
    using namespace sobol_detail;
    uint32_t h = pair_hashes_ ? pair_hashes_[pair_] : hash4(seed_, frame_, pixel_, pair_);
    ++pair_;
    // Shuffle the sample index within its power-of-two block. Owen scrambling maps a block with
    // fixed high bits onto a block with fixed high bits, so only the low bits matter; dropping
    // the constant high part is a digital shift of the net, absorbed by the scrambles below.
    // (owenScramble(index_, h), with the index's reversal done once in the constructor)
    uint32_t i = reverseBits(laineKarras(index_reversed_, h)) & index_mask_;
    // owenScramble(sobol0(i)) == reverseBits(laineKarras(i)): dimension 0 is i bit-reversed
    // (the two coordinates' scrambles from independent hashes of h: a linear map of h, as
    // before, fixed their leading digits' relation, so that one sample's x and y were correlated)
    uint32_t x = reverseBits(laineKarras(i, mix32(h ^ 0x68bc21ebu)));
    // owenScramble(sobol1(i)) with sobol1's table already bit-reversed
    uint32_t y = reverseBits(laineKarras(sobol1(i, true), mix32(h ^ 0x02e5be93u)));
    return {toUnit(x), toUnit(y)};
  }
  /// The next 1D sample in [0, 1) (stratified: the first coordinate of a fresh pair).
  float get1D() { return get2D().x(); }

  /// The scramble seed of every pair of one pixel, for the constructor's `pair_hashes`.
  static void pairHashes(uint64_t seed, uint32_t frame, uint32_t pixel, uint32_t* out) {
    for (uint32_t p = 0; p < kMaxPairs; ++p) out[p] = sobol_detail::hash4(seed, frame, pixel, p);
  }

 private:
  static uint32_t blockMask(uint32_t spp) {
    uint32_t m = 0;
    while (m < spp - 1) m = (m << 1) | 1u;
    return spp <= 1 ? 0u : m;
  }
  static float toUnit(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

  uint64_t seed_;
  uint32_t frame_, pixel_, index_, index_mask_, index_reversed_;
  const uint32_t* pair_hashes_;
  uint32_t pair_ = 0;
  CounterRng rng_;
};

}  // namespace inet
