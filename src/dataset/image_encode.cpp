#include "dataset/image_encode.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace inet {
namespace {

constexpr int kBuckets = 4096;  // power of two: v * kBuckets is exact in float

/// The reference code of a float, straight from the formula.
int srgbCodeReference(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<int>(std::floor(srgbOetf(v) * 255.0 + 0.5));
}

/// threshold[k] = smallest float whose reference code is >= k (k = 1..255); start[b] = code of
/// the first float of bucket b. Both come from the reference formula itself, so the fast path
/// agrees with it for every float as long as the formula is monotonic (it is).
struct SrgbTables {
  std::array<float, 256> threshold{};
  std::array<uint8_t, kBuckets> start{};

  SrgbTables() {
    threshold[0] = 0.0f;
    for (int k = 1; k < 256; ++k) {
      // Start from the analytic inverse of the code boundary, then walk ulp by ulp.
      double e = (k - 0.5) / 255.0;
      double lin = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
      float v = static_cast<float>(lin);
      while (v > 0.0f && srgbCodeReference(v) >= k) v = std::nextafter(v, 0.0f);
      while (srgbCodeReference(v) < k) v = std::nextafter(v, 2.0f);
      threshold[k] = v;
    }
    for (int b = 0; b < kBuckets; ++b)
      start[b] = static_cast<uint8_t>(srgbCodeReference(static_cast<float>(b) / kBuckets));
  }
};

const SrgbTables& srgbTables() {
  static const SrgbTables tables;
  return tables;
}

uint16_t normalComponent(float c) {
  double v = std::clamp(static_cast<double>(c), -1.0, 1.0);
  return static_cast<uint16_t>(std::floor((v + 1.0) * 0.5 * 65535.0 + 0.5));
}

}  // namespace

double srgbOetf(double v) {
  if (v <= 0.0031308) return 12.92 * v;
  return 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

uint8_t linearToSrgb8(float v) {
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  const SrgbTables& t = srgbTables();
  int code = t.start[static_cast<int>(v * kBuckets)];
  while (code < 255 && v >= t.threshold[code + 1]) ++code;
  return static_cast<uint8_t>(code);
}

ImageU8 encodeSrgb8(const ImageF& linear) {
  ImageU8 out(linear.width, linear.height, linear.channels);
  srgbTables();  // build once before the loop
  for (size_t i = 0; i < linear.data.size(); ++i) out.data[i] = linearToSrgb8(linear.data[i]);
  return out;
}

uint16_t depthToU16(float depth_m, double scale) {
  if (!(depth_m > 0.0f) || !std::isfinite(depth_m)) return 0;
  double code = std::floor(static_cast<double>(depth_m) * scale + 0.5);
  return code > 65535.0 ? 0 : static_cast<uint16_t>(code);
}

ImageU16 encodeDepth16(const ImageF& depth_m, double scale) {
  INET_CHECK(depth_m.channels == 1 && scale > 0.0);
  ImageU16 out(depth_m.width, depth_m.height, 1);
  for (size_t i = 0; i < depth_m.data.size(); ++i) out.data[i] = depthToU16(depth_m.data[i], scale);
  return out;
}

ImageF decodeDepth16(const ImageU16& depth, double scale) {
  INET_CHECK(depth.channels == 1 && scale > 0.0);
  ImageF out(depth.width, depth.height, 1);
  for (size_t i = 0; i < depth.data.size(); ++i)
    out.data[i] = static_cast<float>(depth.data[i] / scale);
  return out;
}

ImageU16 encodeNormal16(const ImageF& normal) {
  INET_CHECK(normal.channels == 3);
  ImageU16 out(normal.width, normal.height, 3);
  for (size_t p = 0; p < normal.pixelCount(); ++p) {
    const float* n = normal.data.data() + 3 * p;
    bool finite = std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]);
    bool zero = n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f;
    if (!finite || zero) continue;  // stays (0, 0, 0)
    for (int c = 0; c < 3; ++c) out.data[3 * p + c] = normalComponent(n[c]);
  }
  return out;
}

ImageF decodeNormal16(const ImageU16& normal) {
  INET_CHECK(normal.channels == 3);
  ImageF out(normal.width, normal.height, 3);
  for (size_t p = 0; p < normal.pixelCount(); ++p) {
    const uint16_t* c = normal.data.data() + 3 * p;
    if (c[0] == 0 && c[1] == 0 && c[2] == 0) continue;
    for (int k = 0; k < 3; ++k)
      out.data[3 * p + k] = static_cast<float>(c[k] / 65535.0 * 2.0 - 1.0);
  }
  return out;
}

}  // namespace inet
