#include "render/tonemap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/color.h"
#include "core/error.h"

namespace inet {
namespace {

constexpr double acesFitted(double x) {
  return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
}

constexpr double hableUncharted(double x) {
  constexpr double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
  return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
}

/// u(W) for the white point W = 11.2: the normaliser of the Hable curve.
constexpr double kHableWhiteValue = hableUncharted(11.2);

}  // namespace

std::string toneCurveName(ToneCurve c) {
  switch (c) {
    case ToneCurve::Clamp:
      return "clamp";
    case ToneCurve::Aces:
      return "aces";
    case ToneCurve::Hable:
      return "hable";
  }
  return "?";
}

ToneCurve parseToneCurve(const std::string& name, const std::string& where,
                         const std::string& field) {
  if (name == "clamp" || name == "none") return ToneCurve::Clamp;
  if (name == "aces") return ToneCurve::Aces;
  if (name == "hable") return ToneCurve::Hable;
  throw InputError(where, field,
                   "unknown tone curve '" + name + "' (valid: clamp, none, aces, hable)");
}

float CameraResponse::multiplier() const {
  return static_cast<float>(static_cast<double>(exposure_scale) *
                            std::exp2(static_cast<double>(exposure_ev)));
}

std::string CameraResponse::describe() const {
  std::ostringstream s;
  s << "exposure_ev=" << exposure_ev << " exposure_scale=" << exposure_scale
    << " curve=" << toneCurveName(curve);
  return s.str();
}

void validateCameraResponse(const CameraResponse& r, const std::string& where) {
  if (!std::isfinite(r.exposure_ev))
    throw InputError(where, "camera_response.exposure_ev", "must be finite");
  if (!(std::isfinite(r.exposure_scale) && r.exposure_scale > 0.f))
    throw InputError(where, "camera_response.exposure_scale",
                     "must be finite and > 0, got " + std::to_string(r.exposure_scale));
  if (!std::isfinite(r.multiplier()))
    throw InputError(where, "camera_response.exposure_ev", "exposure overflows a float");
}

float applyToneCurve(ToneCurve curve, float x) {
  if (!(x > 0.f)) return 0.f;  // also NaN
  if (std::isinf(x)) return 1.f;
  double v = x;
  switch (curve) {
    case ToneCurve::Clamp:
      break;
    case ToneCurve::Aces:
      v = acesFitted(v);
      break;
    case ToneCurve::Hable:
      v = hableUncharted(v) / kHableWhiteValue;
      break;
  }
  return static_cast<float>(std::clamp(v, 0.0, 1.0));
}

ImageF applyExposure(const ImageF& linear, float multiplier) {
  ImageF out = linear;
  for (float& v : out.data) v *= multiplier;
  return out;
}

ImageF applyExposureAndCurve(const ImageF& linear, const CameraResponse& response) {
  validateCameraResponse(response, "");
  ImageF out = applyExposure(linear, response.multiplier());
  for (float& v : out.data) v = applyToneCurve(response.curve, v);
  return out;
}

ImageU8 applyCameraResponse(const ImageF& linear, const CameraResponse& response) {
  return encodeSrgb8(applyExposureAndCurve(linear, response));
}

void ExposureMeter::add(const ImageF& rgb) {
  auto lum = [&](int x, int y) {
    return luminance(Eigen::Vector3f(rgb.at(x, y, 0), rgb.at(x, y, 1), rgb.at(x, y, 2)));
  };
  for (int y = 0; y + 1 < rgb.height; y += 2)
    for (int x = 0; x + 1 < rgb.width; x += 2) {
      const double block = 0.25 * (lum(x, y) + lum(x + 1, y) + lum(x, y + 1) + lum(x + 1, y + 1));
      log_sum_ += std::log(1e-4 + std::max(0.0, std::isfinite(block) ? block : 0.0));
      ++blocks_;
    }
}

float ExposureMeter::scale() const {
  const double log_average = std::exp(log_sum_ / static_cast<double>(std::max<size_t>(blocks_, 1)));
  const double ev =
      std::clamp(std::round(3.0 * std::log2(kMiddleGrey / log_average)) / 3.0, -kRangeEv, kRangeEv);
  return static_cast<float>(std::exp2(ev));
}

}  // namespace inet
