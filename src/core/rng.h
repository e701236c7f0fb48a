#pragma once
// Counter-based random numbers (Random123's Philox4x32-10, Salmon et al. SC'11).
//
// Every random decision in the project is a pure function of a key and a counter, so the
// value does not depend on which thread, rank or order computes it (DESIGN.md section 5).
// The key holds the 64-bit global seed; the counter holds (stream, frame, pixel or item,
// sample) and a block index that advances as draws are consumed.
#include <Random123/philox.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string_view>

namespace inet {

/// Named stream ids so that two stages never draw the same numbers for the same seed.
enum class RngStream : uint32_t {
  PathTracer = 1,
  Trajectory = 2,
  Layout = 3,
  Sensor = 4,
  Variation = 5,  ///< scene variants: rearrangement, lighting
};

class CounterRng {
 public:
  /// seed: global seed; stream: which consumer; a, b, c: its indices (frame, pixel, sample).
  CounterRng(uint64_t seed, RngStream stream, uint32_t a, uint32_t b, uint32_t c)
      : key_{{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}},
        ctr_{{a, b, c, static_cast<uint32_t>(stream) << 24}} {}

  /// Next 32 uniformly distributed bits.
  uint32_t nextU32() {
    if (used_ == 4) refill();
    return out_.v[used_++];
  }
  /// Uniform float in [0, 1): the 24 high bits, so 1.0 is never returned.
  float uniform() { return static_cast<float>(nextU32() >> 8) * 0x1p-24f; }
  /// Uniform double in [0, 1) from 53 bits.
  double uniformDouble() {
    uint64_t hi = nextU32(), lo = nextU32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }
  /// Uniform double in [lo, hi).
  double uniformDouble(double lo, double hi) { return lo + (hi - lo) * uniformDouble(); }
  /// Two independent standard normal values from two uniforms (Box-Muller; 1 - U keeps the log
  /// finite).
  void normalPair(double& z0, double& z1) {
    const double u1 = 1.0 - uniformDouble();  // (0, 1]
    const double u2 = uniformDouble();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 2.0 * std::numbers::pi * u2;
    z0 = r * std::cos(a);
    z1 = r * std::sin(a);
  }
  /// One standard normal value (the first of a pair; uses two uniforms).
  double normal() {
    double z0, z1;
    normalPair(z0, z1);
    return z0;
  }

 private:
  void refill() {
    out_ = philox_(ctr_, key_);
    ++ctr_.v[3];  // the low 24 bits of word 3 count blocks within one stream
    used_ = 0;
  }
  r123::Philox4x32 philox_;
  r123::Philox4x32::key_type key_;
  r123::Philox4x32::ctr_type ctr_;
  r123::Philox4x32::ctr_type out_{};
  int used_ = 4;
};

/// 64-bit FNV-1a of a string: a hash that is the same on every run and platform (std::hash is
/// not), for seeds derived from names.
inline uint64_t stableHash(std::string_view s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace inet
