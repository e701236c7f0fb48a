#include "studio/camera_keys.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>

#include "studio/json_fields.h"

namespace inet::studio {

using nlohmann::json;

namespace {

/// "--aperture" -> "aperture_m", ...; the other flags by flagToKey.
std::string requestKeys(std::string text) {
  static const std::pair<const char*, const char*> keys[] = {{"--aperture", "aperture_m"},
                                                             {"--focus", "focus_m"},
                                                             {"--fisheye-fov", "fisheye_fov_deg"},
                                                             {"--format", "formats"}};
  for (const auto& [flag, key] : keys)
    for (size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at)) {
      // whole flags only: "--format" is not the start of "--formats"
      const char next = at + std::strlen(flag) < text.size() ? text[at + std::strlen(flag)] : ' ';
      if (std::isalnum(static_cast<unsigned char>(next)) || next == '-') {
        at += std::strlen(flag);
        continue;
      }
      text.replace(at, std::strlen(flag), key);
    }
  return flagToKey(text);
}

}  // namespace

InputError asRequestError(const InputError& e) {
  return InputError(e.file(), requestKeys(e.field()), requestKeys(e.problem()));
}

const std::set<std::string>& lensKeys() {
  static const std::set<std::string> keys = {"lens", "aperture_m", "focus_m", "fisheye_fov_deg",
                                             "distortion"};
  return keys;
}

LensSettings parseLensKeys(const json& body) {
  LensSettings lens;
  lens.lens = text(body, "lens", "pinhole");
  lens.aperture_m = number(body, "aperture_m", 0.0);
  lens.focus_set = body.contains("focus_m");
  lens.focus_m = number(body, "focus_m", lens.focus_m);
  lens.fisheye_fov_set = body.contains("fisheye_fov_deg");
  lens.fisheye_fov_deg = number(body, "fisheye_fov_deg", lens.fisheye_fov_deg);
  if (body.contains("distortion")) {
    const json& d = body.at("distortion");
    if (!d.is_array() ||
        !std::all_of(d.begin(), d.end(), [](const json& v) { return v.is_number(); }))
      throw InputError("", "distortion",
                       "must be [k1, k2, p1, p2] or [k1, k2, p1, p2, k3], not " + d.dump());
    for (const json& v : d) lens.distortion.push_back(v.get<double>());
  }
  // LensSettings::type() refuses an unknown lens, values out of range, a setting the chosen
  // lens does not use and a distortion of other than 4 or 5 values
  try {
    lens.type();
  } catch (const InputError& e) {
    throw asRequestError(e);
  }
  return lens;
}

const std::set<std::string>& responseKeys() {
  static const std::set<std::string> keys = {"exposure", "exposure_ev", "tone", "sensor_noise"};
  return keys;
}

ResponseKeys parseResponseKeys(const json& body) {
  ResponseKeys r;
  r.exposure = text(body, "exposure", r.exposure);
  if (r.exposure != "auto" && r.exposure != "fixed")
    throw InputError("", "exposure", "must be auto or fixed, not '" + r.exposure + "'");
  r.response.exposure_ev = static_cast<float>(number(body, "exposure_ev", 0.0));
  r.response.tone = text(body, "tone", r.response.tone);
  if (body.contains("sensor_noise")) {
    if (!body.at("sensor_noise").is_boolean())
      throw InputError("", "sensor_noise",
                       "must be true or false, not " + body.at("sensor_noise").dump());
    r.response.sensor_noise = body.at("sensor_noise").get<bool>();
  }
  try {
    r.response.validate();
  } catch (const InputError& e) {
    throw asRequestError(e);
  }
  return r;
}

LensModel lensModelOf(const LensSettings& lens, const CameraIntrinsics& K) {
  const LensType type = lens.type();
  if (type == LensType::Fisheye && K.width != K.height)
    throw InputError("", "height",
                     fmt::format("a fisheye image is square: width {} needs height {}, not {}",
                                 K.width, K.width, K.height));
  if (type == LensType::Panorama && K.width != 2 * K.height)
    throw InputError("", "height",
                     fmt::format("a panorama image is 2:1: width {} needs height {}, not {}",
                                 K.width, K.width / 2.0, K.height));
  try {
    return lens.make(K, "");
  } catch (const InputError& e) {
    throw asRequestError(e);
  }
}

}  // namespace inet::studio
