#pragma once
// The camera keys that sequence jobs (studio/sequence_api.h) and frame previews
// (studio/frame_preview.h) share, read with the command line's rules (pipeline/settings.h) and
// checked when the request arrives, each problem an InputError("", key, problem) naming the key:
//   "lens": pinhole | thin_lens | fisheye | panorama (pinhole), "aperture_m", "focus_m" (thin
//   lens only), "fisheye_fov_deg" (fisheye only), "distortion": [k1, k2, p1, p2] or
//   [k1, k2, p1, p2, k3] (Brown-Conrady in OpenCV's order, as generate --distortion; pinhole
//   and thin lens only);
//   the camera response: "exposure": auto | fixed (auto: metered to middle grey, as generate
//   --exposure), "exposure_ev": -30..30 stops (0), "tone": none | aces | hable (none),
//   "sensor_noise": true | false (false).
#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "core/error.h"
#include "pipeline/settings.h"
#include "render/lens.h"

namespace inet::studio {

/// The keys parseLensKeys reads.
const std::set<std::string>& lensKeys();

/// The lens keys of `body` as generate's LensSettings, checked (a setting the lens does not
/// use, values out of range, 4 or 5 distortion coefficients).
LensSettings parseLensKeys(const nlohmann::json& body);

/// The keys parseResponseKeys reads.
const std::set<std::string>& responseKeys();

/// The camera response of a request: generate's ResponseSettings and --exposure.
struct ResponseKeys {
  ResponseSettings response;
  std::string exposure = "auto";  ///< auto | fixed
};
ResponseKeys parseResponseKeys(const nlohmann::json& body);

/// The lens for an image of K's size: pinhole and thin lens with K as given; a fisheye's image
/// must be square and a panorama's 2:1 (the key "height" named), their focal length follows from
/// the size; distortion that folds over inside the image is refused ("distortion").
LensModel lensModelOf(const LensSettings& lens, const CameraIntrinsics& K);

/// An InputError of the pipeline's settings worded with the request's keys: "--aperture" ->
/// "aperture_m", "--focus" -> "focus_m", "--fisheye-fov" -> "fisheye_fov_deg", "--format" ->
/// "formats", other flags as flagToKey makes them ("--distortion" -> "distortion").
InputError asRequestError(const InputError& e);

}  // namespace inet::studio
