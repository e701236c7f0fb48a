#pragma once
// Lights for scenes that come without any (issue 13, defect 4). SceneNet's layouts, SUNCG-style
// OBJ exports and many glTF files model lamps as plain geometry: rendered as they are, every
// frame is black. SceneNet RGB-D itself added lights at render time; this does the same, in a
// documented, deterministic way (docs/import.md):
//
//  1. Luminaires glow. An object whose name (or material name) has a token light, lamp,
//     lampshade, lightbulb, bulb, chandelier, sconce, luminaire, lighting, downlight or
//     spotlight (singular or plural; not "switch"), or whose class is NYU40 lamp, gets an
//     emissive copy of its material: warm white (3500 K), radiance chosen so that its flux
//     pi L A (A: its one-sided world area) is its share of the space it lights (below).
//  2. Every enclosed space gets ceiling lights where no luminaire lights it. A space is a
//     connected set of voxel columns (0.1 m) with a free run from a floor to a ceiling at least
//     1.9 m high, neighbours' ceilings within 0.2 m (a door's lintel separates two rooms), in
//     a connected free volume of at least 5 m^3 (not the inside of a closed wardrobe). Its
//     flux is `flux_per_m2` times its floor area; without luminaires it gets one 0.5 x 0.5 m
//     downward emitting panel (class lamp, an instance of its own) per `area_per_light_m2`,
//     placed by k-means over its columns, 5 mm under the ceiling found by a ray cast.
//  3. Daylight: a scene with glass (dielectric or thin dielectric materials) gets the Preetham
//     sky and sun of the procedural apartments; a scene without any enclosed space (open to the
//     sky: a glTF model, furniture on a plate) the same at 1/100 (3.5 W/m^2 of sun, 0.4 of
//     sky), as it stands in them unshaded.
// The figures: flux_per_m2 = 5 W/m^2 (of floor) is what the procedural apartments' lamps give
// their rooms (3-8 W/sr per lamp, one to three per 12-20 m^2 room), so imported scenes expose
// like generated ones. Light bounces: a room of albedo rho is 1 / (1 - rho) times as bright as
// its direct light, so the flux is scaled by (1 - rho) / 0.5 (0.2 .. 2), rho the scene's
// area-weighted albedo luminance with textures at their mean: an all-white 3D-FRONT house
// (0.9) gets a fifth of it.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// When to add lights: only to a scene without any (auto), always (on), never (off).
enum class AutoLightMode { Auto, On, Off };
/// "auto", "on", "off"; InputError naming `field` otherwise.
AutoLightMode parseAutoLightMode(const std::string& name, const std::string& field);

struct AutoLightOptions {
  AutoLightMode mode = AutoLightMode::Auto;
  double flux_per_m2 = 5.0;         ///< W per m^2 of floor, spread over a space's lights
  double area_per_light_m2 = 9.0;   ///< a ceiling panel per this much floor
  double panel_m = 0.5;             ///< side of a ceiling panel
  double min_room_height_m = 1.9;   ///< floor-to-ceiling run that makes a space
  double min_space_volume_m3 = 5.0; ///< free volume a space's air must be part of
  double temperature_k = 3500.0;    ///< colour of every added light
  double voxel_m = 0.1;             ///< grid of the space analysis
};

/// What addAutoLights did, for one warning line.
struct AutoLightReport {
  bool had_light = false;               ///< the scene already had a light (auto: untouched)
  std::vector<std::string> luminaires;  ///< objects made to glow
  size_t spaces = 0;                    ///< enclosed spaces found
  double space_area_m2 = 0.0;           ///< their floor area
  size_t ceiling_panels = 0;            ///< panels added
  bool daylight = false;                ///< sky and sun added
  bool no_room = false;  ///< every object wider than 50 m: nowhere to put a light
  double mean_albedo = 0.0;  ///< area-weighted albedo luminance, which scales the flux
  /// "" when nothing was added, otherwise one line saying what and how to turn it off.
  std::string summary() const;
};

/// Does the scene light itself: an analytic light that is on with intensity > 0, or an
/// emissive material on some object?
bool sceneHasLight(const Scene& scene);

/// Adds lights as the header comment says (nothing in Off mode, or in Auto mode when the scene
/// has a light). Deterministic: the same scene gives the same lights.
AutoLightReport addAutoLights(Scene& scene, const AutoLightOptions& opt = {});

/// Is `name` a luminaire's name (see the header comment)?
bool isLuminaireName(const std::string& name);

}  // namespace inet
