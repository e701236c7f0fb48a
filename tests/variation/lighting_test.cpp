// Lighting configurations (variation/lighting.h): the sun's position against an independent
// textbook formula and known geometry, random configurations within their ranges, times of day,
// and the linearity of light (issue 7): image(all) = image(all but A) + image(only A).
#include "variation/lighting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/color.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

/// An independent, coarser formula (Cooper 1969 declination, no equation of time) for solar
/// elevation at local solar time `solar_hour`: agreement within a degree checks the sign
/// conventions and the NOAA series.
double cooperElevation(int day_of_year, double solar_hour, double lat_deg) {
  const double decl = 23.45 * kDeg * std::sin(2 * kPi * (284 + day_of_year) / 365.0);
  const double ha = (solar_hour - 12) * 15 * kDeg;
  const double lat = lat_deg * kDeg;
  return std::asin(std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(ha));
}

TEST(SunPosition, KnownGeometry) {
  SunTime t;
  // June solstice, London, noon UTC (solar noon is at 12:02): 90 - 51.5 + 23.44 = 61.9 degrees,
  // due south
  t.year = 2026, t.month = 6, t.day = 21, t.hour = 12.0 + 1.8 / 60;
  t.latitude_deg = 51.5;
  SunAngles s = sunPosition(t);
  EXPECT_NEAR(s.elevation / kDeg, 61.94, 0.3);
  EXPECT_NEAR(s.azimuth / kDeg, 180.0, 1.0);
  // morning sun in the east half, afternoon in the west half; below the horizon at midnight
  t.hour = 8;
  EXPECT_LT(sunPosition(t).azimuth / kDeg, 180);
  EXPECT_GT(sunPosition(t).azimuth / kDeg, 45);
  t.hour = 16;
  EXPECT_GT(sunPosition(t).azimuth / kDeg, 180);
  t.hour = 0;
  EXPECT_LT(sunPosition(t).elevation, 0);
  // equator at the March equinox, solar noon (12:07 at longitude 0): nearly overhead
  t = SunTime{};
  t.year = 2026, t.month = 3, t.day = 20, t.hour = 12 + 7.5 / 60, t.latitude_deg = 0;
  EXPECT_GT(sunPosition(t).elevation / kDeg, 89.0);
  // the southern hemisphere sees the noon sun in the north
  t.latitude_deg = -34;
  t.month = 6, t.day = 21;
  const double az = sunPosition(t).azimuth / kDeg;
  EXPECT_TRUE(az < 2 || az > 358) << az;
  // longitude and UTC offset: 15 degrees east at UTC+1 is the same solar time as 0 at UTC
  SunTime a;
  a.hour = 10;
  SunTime b = a;
  b.longitude_deg = 15;
  b.utc_offset_h = 1;
  EXPECT_NEAR(sunPosition(a).elevation, sunPosition(b).elevation, 1e-12);
}

TEST(SunPosition, AgreesWithAnIndependentFormula) {
  // over a year and a day at three latitudes; the NOAA time includes the equation of time (up
  // to 16 min), so compare at the true solar time it implies: set longitude so that the clock
  // offset is zero and allow the equation-of-time shift (16 min = 4 deg of hour angle)
  for (double lat : {-35.0, 0.0, 48.0})
    for (int month = 1; month <= 12; month += 1)
      for (double hour = 7; hour <= 17; hour += 2) {
        SunTime t;
        t.month = month, t.day = 15, t.hour = hour, t.latitude_deg = lat;
        static const int before[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
        const double e_noaa = sunPosition(t).elevation;
        const double e_cooper = cooperElevation(before[month - 1] + 15, hour, lat);
        // 4 degrees of hour angle move the elevation by at most 4 degrees
        EXPECT_NEAR(e_noaa / kDeg, e_cooper / kDeg, 4.5)
            << "lat " << lat << " month " << month << " hour " << hour;
      }
}

TEST(SunPosition, WorldDirection) {
  SunAngles east{0.0, 90 * kDeg};
  EXPECT_NEAR((sunDirectionWorld(east, 0) - Vec3(1, 0, 0)).norm(), 0, 1e-12);
  SunAngles up{90 * kDeg, 0};
  EXPECT_NEAR((sunDirectionWorld(up, 30) - Vec3(0, 0, 1)).norm(), 0, 1e-12);
  // north turned 90 degrees counter-clockwise: north is world -x
  SunAngles north{0.0, 0.0};
  EXPECT_NEAR((sunDirectionWorld(north, 90) - Vec3(-1, 0, 0)).norm(), 0, 1e-12);
}

// Light colours from temperatures (core/color.h blackbodyRgb, used by light.xml's
// temperature): the chromaticity of our linear Rec. 709 colour, taken back to CIE xy, against the
// Planckian locus in the CIE 1931 2-degree observer (docs/variation.md lists the table):
// CIE standard illuminant A (a Planckian radiator at 2856 K), and the locus at 3000, 5000 and
// 6500 K.
TEST(Blackbody, ChromaticityFollowsThePlanckianLocusTable) {
  struct Row {
    double kelvin, x, y;
  };
  const Row table[] = {{2856, 0.44757, 0.40745}, {3000, 0.4369, 0.4041},
                       {5000, 0.3451, 0.3516},   {6500, 0.3135, 0.3236}};
  for (const Row& r : table) {
    const Eigen::Vector3f rgb = blackbodyRgb(r.kelvin);
    // linear Rec. 709 / sRGB (D65) -> XYZ (IEC 61966-2-1)
    const double X = 0.4124 * rgb.x() + 0.3576 * rgb.y() + 0.1805 * rgb.z();
    const double Y = 0.2126 * rgb.x() + 0.7152 * rgb.y() + 0.0722 * rgb.z();
    const double Z = 0.0193 * rgb.x() + 0.1192 * rgb.y() + 0.9505 * rgb.z();
    EXPECT_NEAR(X / (X + Y + Z), r.x, 0.002) << r.kelvin << " K";
    EXPECT_NEAR(Y / (X + Y + Z), r.y, 0.002) << r.kelvin << " K";
    EXPECT_NEAR(Y, 1.0, 1e-4) << "luminance 1";
  }
}

LightSetup manyLamps(int n) {
  LightSetup s;
  for (int i = 0; i < n; ++i) {
    Light l;
    l.name = "lamp_" + std::to_string(i);
    l.intensity = 10.f;
    s.lights.push_back(l);
  }
  Light sun;
  sun.type = LightType::Sun;
  sun.intensity = 350.f;
  s.lights.push_back(sun);
  return s;
}

TEST(RandomLighting, DrawsWithinTheConfiguredRanges) {
  const LightSetup base = manyLamps(2000);
  RandomLightingOptions opt;
  opt.seed = 3;
  const LightSetup a = randomLighting(base, opt);
  EXPECT_EQ(a.lights.size(), base.lights.size());
  int on = 0, coloured = 0;
  for (size_t i = 0; i + 1 < a.lights.size(); ++i) {
    const Light& l = a.lights[i];
    on += l.on;
    EXPECT_GE(l.intensity, 10.f * opt.min_brightness - 1e-4f);
    EXPECT_LE(l.intensity, 10.f * opt.max_brightness + 1e-4f);
    if (l.temperature_k == 0.f) {
      ++coloured;
    } else {
      EXPECT_GE(l.temperature_k, opt.min_temperature_k);
      EXPECT_LE(l.temperature_k, opt.max_temperature_k);
    }
  }
  EXPECT_NEAR(on / 2000.0, opt.on_probability, 0.03);
  EXPECT_NEAR(coloured / 2000.0, opt.coloured_probability, 0.02);
  // the sun is untouched; the same seed gives the same setup, another seed another
  EXPECT_EQ(a.lights.back().intensity, 350.f);
  const LightSetup b = randomLighting(base, opt);
  for (size_t i = 0; i < a.lights.size(); ++i) EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity);
  opt.seed = 4;
  EXPECT_NE(randomLighting(base, opt).lights[0].intensity, a.lights[0].intensity);
  // never all off
  opt.on_probability = 0;
  const LightSetup dark = randomLighting(manyLamps(5), opt);
  int lit = 0;
  for (const Light& l : dark.lights) lit += l.on && l.type != LightType::Sun;
  EXPECT_EQ(lit, 1);
  opt.on_probability = 2;
  EXPECT_THROW(randomLighting(base, opt), InputError);
}

TEST(TimeOfDay, SunFollowsTheClockAndLampsComeOnAtDusk) {
  const LightSetup base = manyLamps(3);
  SunTime noon;
  noon.hour = 13;
  const LightSetup day = timeOfDayLighting(base, noon);
  const Light& sun = day.lights[3];  // after the three lamps; a sky was appended
  EXPECT_TRUE(sun.on);
  EXPECT_NEAR((-sun.direction - sunDirectionWorld(sunPosition(noon), 0)).norm(), 0, 1e-12);
  EXPECT_FALSE(day.lights[0].on) << "lamps off in daylight";
  // a lower sun is dimmer (more air); night: sun off, lamps on; a sky was added
  SunTime evening = noon;
  evening.hour = 19;
  EXPECT_LT(timeOfDayLighting(base, evening).lights[3].intensity, sun.intensity);
  SunTime night = noon;
  night.hour = 23.5;
  const LightSetup dark = timeOfDayLighting(base, night);
  EXPECT_FALSE(dark.lights[3].on);
  EXPECT_TRUE(dark.lights[0].on);
  ASSERT_EQ(dark.lights.size(), base.lights.size() + 1);
  EXPECT_EQ(dark.lights.back().type, LightType::Sky);
  night.month = 13;
  EXPECT_THROW(timeOfDayLighting(base, night), InputError);
}

/// Mean radiance per 8x8 block of a render of the built-in room under `setup`.
std::vector<double> blocks(const Scene& base_scene, const LightSetup& setup) {
  Scene scene = base_scene;
  applyLightSetup(scene, setup, "test");
  Renderer r(scene);
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 40);
  RenderOptions opt;
  opt.spp = 256;
  opt.seed = 11;
  opt.passes = static_cast<PassMask>(Pass::Rgb);
  Frame f;
  r.render(LensModel::pinhole(K), builtinTrajectory(1, 25.0).poses[0].T_world_camera, opt, 0, f);
  std::vector<double> out;
  for (int by = 0; by < 6; ++by)
    for (int bx = 0; bx < 8; ++bx) {
      double sum = 0;
      for (int y = 8 * by; y < 8 * by + 8; ++y)
        for (int x = 8 * bx; x < 8 * bx + 8; ++x)
          for (int c = 0; c < 3; ++c) sum += f.rgb.at(x, y, c);
      out.push_back(sum / 192);
    }
  return out;
}

TEST(LightingLinearity, AllEqualsAllButOnePlusOnlyThatOne) {
  const Scene scene = makeDefaultScene();
  const LightSetup all = lightSetupOf(scene);
  const size_t n = all.lights.size() + all.areas.size();
  ASSERT_GE(n, 2u) << "the built-in room needs two lights for this test";
  // A = the first light (analytic or area)
  LightSetup without = all, only = all;
  auto set = [](LightSetup& s, size_t i, bool on) {
    if (i < s.lights.size()) s.lights[i].on = on;
    else s.areas[i - s.lights.size()].on = on;
  };
  for (size_t i = 0; i < n; ++i) set(only, i, i == 0);
  set(without, 0, false);
  const auto a = blocks(scene, all), b = blocks(scene, without), c = blocks(scene, only);
  double total = 0, diff = 0, part_b = 0, part_c = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    total += a[i];
    diff += std::abs(a[i] - (b[i] + c[i]));
    part_b += b[i];
    part_c += c[i];
  }
  // each part carries real light (else the test proves nothing)
  EXPECT_GT(part_b, 0.05 * total);
  EXPECT_GT(part_c, 0.05 * total);
  std::printf("%zu lights; A carries %.1f %% of the light; |all - (without A + only A)| = %.2f %%\n", n,
              100 * part_c / total, 100 * diff / total);
  // sum of block differences within Monte Carlo error (measured 0.29 %; 64 px x 256 spp a block)
  EXPECT_LT(diff / total, 0.03);
  // and a wrong decomposition is far off: twice A's part
  double wrong = 0;
  for (size_t i = 0; i < a.size(); ++i) wrong += std::abs(a[i] - (b[i] + 2 * c[i]));
  EXPECT_GT(wrong / total, 0.1);
}

}  // namespace
}  // namespace inet
