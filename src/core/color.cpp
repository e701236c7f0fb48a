#include "core/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace inet {

double srgbOetf(double linear) {
  double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

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
      double lin = srgbEotf(e);
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

// Piecewise Gaussian lobe of the Wyman et al. fit: width s1 left of the mean, s2 right of it.
double lobe(double x, double mu, double s1, double s2) {
  double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
}  // namespace

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

Eigen::Vector3d cieXyzMatching(double nm) {
  double x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
             0.065 * lobe(nm, 501.1, 20.4, 26.2);
  double y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
  double z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
  return {x, y, z};
}

Eigen::Vector3f blackbodyRgb(double kelvin) {
  const double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  for (int nm = 380; nm <= 780; ++nm) {
    double lambda = nm * 1e-9;
    double radiance =
        2.0 * h * c * c / std::pow(lambda, 5) / std::expm1(h * c / (lambda * k * kelvin));
    xyz += radiance * cieXyzMatching(nm);
  }
  xyz /= xyz.y();
  Eigen::Matrix3d xyz_to_srgb;
  xyz_to_srgb << 3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570;
  Eigen::Vector3d rgb = (xyz_to_srgb * xyz).cwiseMax(0.0);
  // rescale to luminance 1 after clipping (Rec. 709 luminance weights)
  double y = luminance(rgb);
  return (rgb / y).cast<float>();
}

}  // namespace inet
