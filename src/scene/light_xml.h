#pragma once
// light.xml: a layout's lighting setup in the spirit of the InteriorNet paper's per-layout file
// (light type, energy, maximum distance as in PBRT-v3, position, direction, colour or
// temperature, on/off, and the object each light belongs to, e.g. a lamp). Analytic lights are
// <light type="PointLight|SpotLight|SunLight|SkyLight">; emissive objects (area lights) are
// <light type="AreaLight" object="..." radiance="r g b">. Switching lights or recolouring them is
// editing this file; `applyLightXml` puts a setup onto a scene. A SkyLight's model is uniform,
// preetham (sun_direction, turbidity) or envmap (file: the image, relative to the light.xml's
// folder; rotation: 9 numbers, map frame -> world row by row; as layout.json's envmap sky).
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// An emissive object's entry: its radiance and whether it is on.
struct AreaLightEntry {
  std::string object;
  /// The part of the object that glows (a lamp's lens, not its housing); "" = the object's
  /// emissive parts, or all of its parts when none is emissive yet.
  std::string part;
  Vec3f radiance = Vec3f::Zero();
  bool on = true;
  bool operator==(const AreaLightEntry&) const = default;
};

struct LightSetup {
  std::vector<Light> lights;
  std::vector<AreaLightEntry> areas;
};

/// The scene's lights plus one AreaLight per emissive part of an object (named by the object
/// and the part).
LightSetup lightSetupOf(const Scene& scene);
/// The setup as light.xml text (fixed attribute order and number format); `path` is where it
/// will be written (an envmap sky's image is given relative to its folder).
std::string lightXmlText(const Scene& scene, const std::string& path);
/// Writes lightXmlText atomically.
void saveLightXml(const Scene& scene, const std::string& path);
/// Reads light.xml; throws InputError(path, "light[i].attribute", problem) for bad input.
LightSetup loadLightXml(const std::string& path);
/// Parses light.xml text read from `path` (relative envmap images are found from its folder).
LightSetup parseLightXml(const std::string& text, const std::string& path);
/// Replaces the scene's analytic lights and sets the emission of each listed object's parts (0
/// when off; objects sharing a material get their own copy): the named part, or without one the
/// parts that were emissive, or all parts when none was. Throws InputError(where, ...) when an
/// entry names an object or part the scene does not have.
void applyLightSetup(Scene& scene, const LightSetup& setup, const std::string& where);

}  // namespace inet
