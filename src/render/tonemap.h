#pragma once
// Camera response: scene-linear RGB -> display 8-bit sRGB, in three steps.
//   1. Exposure: v * m, m = exposure_scale * 2^exposure_ev (EV stops; +1 EV doubles).
//   2. Tone curve, per channel, output clamped to [0, 1]:
//      - Clamp:  f(x) = clamp(x, 0, 1) (what the 8-bit encode does anyway; also named "none").
//      - Aces:   K. Narkowicz, "ACES Filmic Tone Mapping Curve", blog post, 6 Jan 2016
//                (knarkowicz.wordpress.com), a fit of the ACES RRT + Rec.709 ODT without gamma:
//                f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14). Pre-exposed: f(1) ~ 0.80;
//                the original ACES level is f(0.6 x). Reaches 1 at x ~ 7.24 (then clamps).
//      - Hable:  J. Hable, "Uncharted 2: HDR Lighting", GDC 2010 / "Filmic Tonemapping
//                Operators" (filmicworlds.com, 2010): u(x) = (x (A x + C B) + D E) /
//                (x (A x + B) + D F) - E / F with A = 0.15 (shoulder strength), B = 0.50 (linear
//                strength), C = 0.10 (linear angle), D = 0.20 (toe strength), E = 0.02 (toe
//                numerator), F = 0.30 (toe denominator); f(x) = u(x) / u(W), white point
//                W = 11.2, so f(W) = 1 and f(1) ~ 0.30 (Hable pairs it with an exposure
//                bias of 2, i.e. exposure_ev = +1).
//      Both filmic curves are 0 at 0, increase monotonically, and compress highlights so that
//      f(1) < 1. Per-channel application desaturates and shifts hue in bright colours (as both
//      authors note); that is accepted here.
//   3. sRGB OETF to 8 bits: core/color.h (linearToSrgb8), the project's one exact encoder.
// The linear HDR image itself is never modified: EXR outputs take the radiance as rendered.
// Physical order when sensor noise is simulated: exposure (applyExposure) -> sensor noise ->
// applyCameraResponse with exposure 0 EV.
#include <string>

#include "core/image.h"

namespace inet {

enum class ToneCurve { Clamp, Aces, Hable };

/// "clamp", "aces" or "hable".
std::string toneCurveName(ToneCurve c);
/// Parses a curve name ("none" is accepted as "clamp"); throws InputError(where, field, ...)
/// naming the valid choices.
ToneCurve parseToneCurve(const std::string& name, const std::string& where,
                         const std::string& field);

struct CameraResponse {
  float exposure_ev = 0.f;     ///< exposure compensation in stops
  float exposure_scale = 1.f;  ///< extra linear multiplier (e.g. 1 / auto-exposure key)
  ToneCurve curve = ToneCurve::Clamp;

  /// Total linear multiplier exposure_scale * 2^exposure_ev.
  float multiplier() const;
  /// "exposure_ev=0 exposure_scale=1 curve=clamp".
  std::string describe() const;
};

/// Throws InputError(where, "camera_response.<field>", ...) unless exposure_ev is finite and
/// exposure_scale finite and > 0.
void validateCameraResponse(const CameraResponse& r, const std::string& where);

/// The tone curve alone, one value. NaN and negative inputs give 0, +inf gives 1.
float applyToneCurve(ToneCurve curve, float x);

/// Linear image (any channel count) times `multiplier`.
ImageF applyExposure(const ImageF& linear, float multiplier);

/// Steps 1 and 2: exposure and tone curve, display-linear values in [0, 1].
ImageF applyExposureAndCurve(const ImageF& linear, const CameraResponse& response);

/// All three steps: scene-linear -> 8-bit sRGB, same size and channel count.
ImageU8 applyCameraResponse(const ImageF& linear, const CameraResponse& response);

/// Auto exposure, as a camera meters before it records: the exposure multiplier that puts the
/// log-average luminance of the images added at middle grey (0.18, Reinhard et al. 2002's key),
/// in third stops, within +-8 stops. The log-average is taken over 2x2 blocks (a single noisy
/// pixel's log meters darker than the scene is); non-finite blocks count as black.
class ExposureMeter {
 public:
  static constexpr double kMiddleGrey = 0.18;
  static constexpr double kRangeEv = 8.0;
  /// Adds the 2x2 blocks of a linear RGB image.
  void add(const ImageF& rgb);
  /// The multiplier: exp2 of the EV, rounded to a third and clamped to the range.
  float scale() const;

 private:
  double log_sum_ = 0.0;
  size_t blocks_ = 0;
};

}  // namespace inet
