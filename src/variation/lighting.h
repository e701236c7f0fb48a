#pragma once
// Lighting configurations of one layout (issue 7; the paper's "lighting variations"): new
// light setups (scene/light_xml.h) drawn at random within documented ranges, or for a time of
// day, where the sun and the daylight sky take the position the date, time and latitude give
// (sunPosition) and lamps come on after dusk. Nothing else about the scene changes.
#include <cstdint>
#include <string>

#include "core/pose.h"
#include "scene/light_xml.h"
#include "scene/scene.h"

namespace inet {

/// The sun seen from a place on Earth: elevation above the horizon and azimuth from north
/// through east, radians.
struct SunAngles {
  double elevation = 0.0;
  double azimuth = 0.0;
};

/// Where a layout is and when. Local standard time at the given UTC offset; the layout's north
/// is `north_deg` counter-clockwise from world +y (0: +y is north, +x east).
struct SunTime {
  int year = 2026, month = 6, day = 21;
  double hour = 12.0;       ///< local clock time, hours (e.g. 15.5 = 15:30)
  double latitude_deg = 51.5;   ///< + north
  double longitude_deg = 0.0;   ///< + east
  double utc_offset_h = 0.0;    ///< the clock's offset from UTC, hours
  double north_deg = 0.0;
  /// Throws InputError(where, "--date" / "--time" / "--latitude" / ...) for impossible values.
  void validate(const std::string& where) const;
};

/// Solar elevation and azimuth by NOAA's general solar position formulas (Global Monitoring
/// Laboratory, "General Solar Position Calculations": fractional year, equation of time and
/// declination as Fourier series, hour angle from the true solar time). Accurate to about
/// 0.2 degrees between latitudes +-60; no atmospheric refraction.
SunAngles sunPosition(const SunTime& when);

/// The unit direction in the world frame (z up) from the scene towards the sun.
Vec3 sunDirectionWorld(const SunAngles& sun, double north_deg);

/// Ranges of a random lighting configuration (every value drawn uniformly).
struct RandomLightingOptions {
  double on_probability = 0.7;  ///< each lamp, ceiling light and area light is on with this
  double min_temperature_k = 2700, max_temperature_k = 6500;  ///< warm white .. daylight
  double min_brightness = 0.5, max_brightness = 1.5;          ///< factor on the layout's energy
  double coloured_probability = 0.1;  ///< a light gets a random saturated hue instead
  uint64_t seed = 0;
  void validate(const std::string& where) const;
};

/// A random configuration of `base` (the layout's own setup): every light and area light
/// switched on with on_probability (at least one stays on), its energy scaled by a brightness
/// drawn in range, its colour a blackbody temperature in range or, rarely, a saturated hue.
/// The sun and sky are kept as they are. Deterministic in the seed.
LightSetup randomLighting(const LightSetup& base, const RandomLightingOptions& opt);

/// The configuration of `base` at a time of day: every sun and Preetham sky takes the sun's
/// direction for `when`; the sun's irradiance follows its elevation through the atmosphere
/// (Meinel's air-mass model, 1353 W/m^2 x 0.7^(AM^0.678)), the sky's with sin(elevation), both
/// relative to the layout's values, taken as those of a sun 45 degrees high; below the horizon
/// both are off (and otherwise as they were). Lamps and area lights are on when the sun is below 6 degrees
/// (dusk, night) and off in daylight. With no sun in the layout one is added (and a sky when
/// it has none), so that windows light the rooms.
LightSetup timeOfDayLighting(const LightSetup& base, const SunTime& when);

/// After objects moved (`before` -> `after`, same objects in the same order): every analytic
/// light bound to an object (Light::object = the object's name) moves rigidly with that object's
/// first part, position and direction. Returns how many lights moved.
int moveBoundLights(const Scene& before, Scene& after);

}  // namespace inet
