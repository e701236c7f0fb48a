#include "dataset/image_encode.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace inet {
namespace {

uint16_t normalComponent(float c) {
  double v = std::clamp(static_cast<double>(c), -1.0, 1.0);
  return static_cast<uint16_t>(std::floor((v + 1.0) * 0.5 * 65535.0 + 0.5));
}

}  // namespace

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
