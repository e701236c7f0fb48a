#pragma once
// Colour helpers shared by the renderer and the writers.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "core/image.h"

namespace inet {

/// Luminance Y of a linear Rec. 709 / sRGB colour (the Y row of the RGB -> XYZ matrix, IEC
/// 61966-2-1), computed in the colour's own scalar type.
template <class V>
typename V::Scalar luminance(const V& c) {
  using S = typename V::Scalar;
  return S(0.2126) * c.x() + S(0.7152) * c.y() + S(0.0722) * c.z();
}

/// sRGB opto-electronic transfer function (IEC 61966-2-1) of a linear value in [0, 1].
double srgbOetf(double linear);
/// Its inverse, the sRGB EOTF: an encoded value in [0, 1] -> linear.
inline double srgbEotf(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

/// One linear value -> 8-bit sRGB code, exactly floor(255 * srgbOetf(clamp(v, 0, 1)) + 0.5) for
/// every float v (NaN and negatives give 0, +inf gives 255). Implemented with a 4096-bucket table
/// plus the 255 exact float thresholds between codes, so it is fast and bit-exact.
uint8_t linearToSrgb8(float linear);

/// Linear RGB (or any channel count) -> 8-bit sRGB, per channel as linearToSrgb8. Used for the
/// colour image and for albedo.
ImageU8 encodeSrgb8(const ImageF& linear);

/// Linear sRGB (Rec. 709 primaries, D65) colour of a blackbody at `kelvin`, scaled to luminance
/// Y = 1. Planck's law integrated against the CIE 1931 2-degree colour matching functions (the
/// analytic multi-lobe fit of Wyman, Sloan and Shirley, JCGT 2013) over 380-780 nm in 1 nm steps;
/// negative components (very low temperatures lie outside the sRGB gamut) are clipped to 0.
/// Valid for 1000 K .. 40000 K.
Eigen::Vector3f blackbodyRgb(double kelvin);

/// CIE 1931 colour matching functions at wavelength `nm` (Wyman et al. 2013 fit): (x, y, z).
Eigen::Vector3d cieXyzMatching(double nm);

}  // namespace inet
