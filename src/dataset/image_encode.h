#pragma once
// Conversions from the renderer's float passes to the integer encodings stored in PNG files.
// Every rounding is "half up" (floor(x + 0.5)), done in double precision, so results do not
// depend on the platform's float rounding mode or on std::lround's half-away-from-zero rule.
#include <cstdint>

#include "core/color.h"
#include "core/image.h"

namespace inet {

// srgbOetf, linearToSrgb8 and encodeSrgb8 (exact sRGB encoding) live in core/color.h, so the
// renderer's camera response can use them too.

/// Depth scales: stored value per metre.
constexpr double kDepthScaleMm = 1000.0;   ///< ASL depth0 PNG: millimetres
constexpr double kDepthScaleTum = 5000.0;  ///< TUM RGB-D / ICL-NUIM PNG: 0.2 mm steps

/// One depth in metres -> stored uint16: floor(z * scale + 0.5). 0 means "no depth": z <= 0,
/// NaN, inf, and any depth whose code would exceed 65535 (beyond 65.535 m at scale 1000,
/// 13.107 m at scale 5000) become 0, never a clamped 65535 that would look like a real surface.
uint16_t depthToU16(float depth_m, double scale);
/// A 1-channel depth image (metres, 0 = none) -> 1-channel uint16 image, per pixel depthToU16.
ImageU16 encodeDepth16(const ImageF& depth_m, double scale);
/// Inverse for readers and tests: code / scale metres, 0 stays 0.
ImageF decodeDepth16(const ImageU16& depth, double scale);

/// Camera-frame unit normals (3 channels, (0,0,0) = no surface) -> 16-bit RGB:
/// code = floor((clamp(n, -1, 1) + 1) / 2 * 65535 + 0.5) per component. A zero (or non-finite)
/// normal is stored as (0, 0, 0); a real unit normal can never encode to all zeros.
ImageU16 encodeNormal16(const ImageF& normal);
/// Inverse: n = code / 65535 * 2 - 1, and (0,0,0) for an all-zero pixel.
ImageF decodeNormal16(const ImageU16& normal);

}  // namespace inet
