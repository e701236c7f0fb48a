#include "variation/lighting.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/color.h"
#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
/// Third counter word of the lighting draws (ASCII "LIT").
constexpr uint32_t kLightingRngTag = 0x4c4954u;

bool leapYear(int y) {
  return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int dayOfYear(int y, int m, int d) {
  static const int before[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  return before[m - 1] + d + (m > 2 && leapYear(y) ? 1 : 0);
}

/// Direct normal irradiance relative to the sun at 45 degrees: Meinel and Meinel's air-mass
/// model, 1.353 kW/m^2 x 0.7^(AM^0.678), AM = 1 / cos(zenith) (plane-parallel atmosphere,
/// capped at AM 38 near the horizon).
double sunFactor(double elevation) {
  if (elevation <= 0) return 0.0;
  auto dni = [](double el) {
    const double am = std::min(1.0 / std::sin(el), 38.0);
    return std::pow(0.7, std::pow(am, 0.678));
  };
  return dni(elevation) / dni(45 * kDeg);
}

/// The daylight sky's brightness relative to the sun at 45 degrees: sin(elevation).
double skyFactor(double elevation) {
  return elevation <= 0 ? 0.0 : std::sin(elevation) / std::sin(45 * kDeg);
}

}  // namespace

void SunTime::validate(const std::string& where) const {
  if (year < 1901 || year > 2099) throw InputError(where, "--date", "year must be in 1901..2099");
  if (month < 1 || month > 12) throw InputError(where, "--date", "month must be in 1..12");
  static const int days[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (day < 1 || day > days[month - 1] || (month == 2 && day == 29 && !leapYear(year)))
    throw InputError(where, "--date", fmt::format("{}-{:02d}-{:02d} is not a date", year, month, day));
  if (!(hour >= 0 && hour < 24)) throw InputError(where, "--time", "must be in 00:00..23:59");
  if (!(latitude_deg >= -90 && latitude_deg <= 90))
    throw InputError(where, "--latitude", "must be in -90..90 degrees");
  if (!(longitude_deg >= -180 && longitude_deg <= 180))
    throw InputError(where, "--longitude", "must be in -180..180 degrees");
  if (!(utc_offset_h >= -14 && utc_offset_h <= 14))
    throw InputError(where, "--utc-offset", "must be in -14..14 hours");
  if (!std::isfinite(north_deg)) throw InputError(where, "--north", "must be finite");
}

SunAngles sunPosition(const SunTime& w) {
  const int n = dayOfYear(w.year, w.month, w.day);
  const double year_days = leapYear(w.year) ? 366 : 365;
  // NOAA: fractional year (radians), equation of time (minutes), declination (radians)
  const double g = 2 * kPi / year_days * (n - 1 + (w.hour - 12) / 24);
  const double eqtime = 229.18 * (0.000075 + 0.001868 * std::cos(g) - 0.032077 * std::sin(g) -
                                  0.014615 * std::cos(2 * g) - 0.040849 * std::sin(2 * g));
  const double decl = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) -
                      0.006758 * std::cos(2 * g) + 0.000907 * std::sin(2 * g) -
                      0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  // true solar time (minutes) and hour angle (radians, 0 at solar noon, + in the afternoon)
  const double offset = eqtime + 4 * w.longitude_deg - 60 * w.utc_offset_h;
  const double tst = w.hour * 60 + offset;
  const double ha = (tst / 4 - 180) * kDeg;
  const double lat = w.latitude_deg * kDeg;
  const double cos_zen = std::clamp(
      std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(ha), -1.0, 1.0);
  const double zen = std::acos(cos_zen);
  SunAngles s;
  s.elevation = kPi / 2 - zen;
  // azimuth from north through east: atan2 of the east and north components of the direction
  const double east = -std::cos(decl) * std::sin(ha);
  const double north = std::sin(decl) * std::cos(lat) - std::cos(decl) * std::sin(lat) * std::cos(ha);
  s.azimuth = std::atan2(east, north);
  if (s.azimuth < 0) s.azimuth += 2 * kPi;
  return s;
}

Vec3 sunDirectionWorld(const SunAngles& sun, double north_deg) {
  // in a frame with +x east, +y north, +z up; then the layout's north turned by north_deg
  const Vec3 enu(std::cos(sun.elevation) * std::sin(sun.azimuth),
                 std::cos(sun.elevation) * std::cos(sun.azimuth), std::sin(sun.elevation));
  const double c = std::cos(north_deg * kDeg), s = std::sin(north_deg * kDeg);
  return Vec3(c * enu.x() - s * enu.y(), s * enu.x() + c * enu.y(), enu.z());
}

void RandomLightingOptions::validate(const std::string& where) const {
  if (!(on_probability >= 0 && on_probability <= 1))
    throw InputError(where, "--on-probability", "must be in 0..1");
  if (!(min_temperature_k >= 1000 && max_temperature_k <= 40000 &&
        min_temperature_k <= max_temperature_k))
    throw InputError(where, "--temperature", "must be a range within 1000..40000 K");
  if (!(min_brightness > 0 && max_brightness <= 100 && min_brightness <= max_brightness))
    throw InputError(where, "--brightness", "must be a range within (0, 100]");
  if (!(coloured_probability >= 0 && coloured_probability <= 1))
    throw InputError(where, "--coloured-probability", "must be in 0..1");
}

LightSetup randomLighting(const LightSetup& base, const RandomLightingOptions& opt) {
  opt.validate("random lighting");
  LightSetup out = base;
  // one stream per light (its index; area lights after the analytic ones): adding a light to a
  // layout does not change the draws of the others
  auto draw = [&](uint32_t index, bool& on, float& scale, Vec3f& color, float& temperature) {
    CounterRng rng(opt.seed, RngStream::Variation, index, 0, kLightingRngTag);
    on = rng.uniformDouble() < opt.on_probability;
    scale = static_cast<float>(rng.uniformDouble(opt.min_brightness, opt.max_brightness));
    if (rng.uniformDouble() < opt.coloured_probability) {
      // a saturated hue: one channel 1, one 0.15, the third in between
      const double h = rng.uniformDouble(0, 6);
      const int sector = static_cast<int>(h);
      const float f = static_cast<float>(h - sector);
      const float hi = 1.f, lo = 0.15f, mid = lo + (hi - lo) * (sector % 2 ? 1 - f : f);
      const Vec3f sectors[6] = {{hi, mid, lo}, {mid, hi, lo}, {lo, hi, mid},
                                {lo, mid, hi}, {mid, lo, hi}, {hi, lo, mid}};
      color = sectors[sector % 6];
      temperature = 0.f;
    } else {
      temperature =
          static_cast<float>(rng.uniformDouble(opt.min_temperature_k, opt.max_temperature_k));
    }
  };
  uint32_t index = 0;
  int on_count = 0, candidates = 0;
  for (Light& l : out.lights) {
    const uint32_t i = index++;
    if (l.type == LightType::Sun || l.type == LightType::Sky) continue;
    ++candidates;
    bool on;
    float scale, temperature = 0.f;
    Vec3f color = l.color;
    draw(i, on, scale, color, temperature);
    l.on = on;
    l.intensity *= scale;
    l.temperature_k = temperature;
    if (temperature == 0.f) l.color = color;
    on_count += on;
  }
  for (AreaLightEntry& a : out.areas) {
    const uint32_t i = index++;
    ++candidates;
    bool on;
    float scale, temperature = 0.f;
    Vec3f color = Vec3f::Ones();
    draw(i, on, scale, color, temperature);
    // an area light has a radiance, not a temperature: keep its luminance, take the colour
    const float lum = luminance(a.radiance);
    const Vec3f c = temperature > 0 ? Vec3f(blackbodyRgb(temperature)) : color;
    const float c_lum = luminance(c);
    if (c_lum > 0) a.radiance = c * (lum * scale / c_lum);
    a.on = on;
    on_count += on;
  }
  if (candidates > 0 && on_count == 0) {
    // at least one light stays on: the first candidate
    for (Light& l : out.lights)
      if (l.type != LightType::Sun && l.type != LightType::Sky) {
        l.on = true;
        return out;
      }
    out.areas.front().on = true;
  }
  return out;
}

LightSetup timeOfDayLighting(const LightSetup& base, const SunTime& when) {
  when.validate("time of day");
  LightSetup out = base;
  const SunAngles sun = sunPosition(when);
  const Vec3 to_sun = sunDirectionWorld(sun, when.north_deg);
  bool has_sun = false, has_sky = false;
  const bool day = sun.elevation > 0;
  for (Light& l : out.lights) {
    if (l.type == LightType::Sun || l.type == LightType::Sky) {
      (l.type == LightType::Sun ? has_sun : has_sky) = true;
      l.on = day;
      if (!day) continue;  // below the horizon: off, as it was otherwise
      if (l.type == LightType::Sun || l.sky_model == SkyModel::Preetham) l.direction = -to_sun;
      const double f = l.type == LightType::Sun ? sunFactor(sun.elevation) : skyFactor(sun.elevation);
      l.intensity = static_cast<float>(l.intensity * f);
    } else {
      l.on = sun.elevation < 6 * kDeg;
    }
  }
  for (AreaLightEntry& a : out.areas) a.on = sun.elevation < 6 * kDeg;
  // an added sun or sky below the horizon points straight down (off): a valid light either way
  const Vec3 travel = day ? Vec3(-to_sun) : Vec3(-Vec3::UnitZ());
  if (!has_sun) {
    Light s;
    s.name = "sun";
    s.type = LightType::Sun;
    s.direction = travel;
    s.temperature_k = 5500.f;
    s.intensity = static_cast<float>(350.0 * std::max(sunFactor(sun.elevation), 1e-3));
    s.on = sun.elevation > 0;
    out.lights.push_back(s);
  }
  if (!has_sky) {
    Light s;
    s.name = "sky";
    s.type = LightType::Sky;
    s.sky_model = SkyModel::Preetham;
    s.direction = travel;
    s.intensity = static_cast<float>(40.0 * std::max(skyFactor(sun.elevation), 1e-3));
    s.on = sun.elevation > 0;
    out.lights.push_back(s);
  }
  return out;
}

int moveBoundLights(const Scene& before, Scene& after) {
  INET_CHECK(before.objects.size() == after.objects.size());
  int moved = 0;
  for (Light& l : after.lights) {
    if (l.object.empty()) continue;
    for (size_t i = 0; i < before.objects.size(); ++i) {
      if (before.objects[i].name != l.object) continue;
      const Mat4 delta =
          after.objects[i].T_world_object * before.objects[i].T_world_object.inverse();
      if (!delta.isApprox(Mat4::Identity(), 1e-12)) {
        l.position = delta.topLeftCorner<3, 3>() * l.position + delta.block<3, 1>(0, 3);
        l.direction = (delta.topLeftCorner<3, 3>() * l.direction).normalized();
        ++moved;
      }
      break;  // the first part of the object
    }
  }
  return moved;
}

}  // namespace inet
