// The Preetham daylight sky (render/sky.h) and its importance sampling. Expectations are derived
// independently of the code under test:
//  - zenith luminance and chromaticity written out again here from the paper's appendix A.2;
//  - the shape of the Perez distribution: brighter toward the sun, brighter at the horizon than
//    at the zenith, bluer at the zenith; nothing below the horizon;
//  - intensity normalisation: the luminance of int L cos dw, by quadrature here, is `intensity`;
//  - sampling: a chi-square test of sampled directions against the integral of the pdf over bins,
//    the pdf integrating to 1, and SceneLights returning the same pdf for a sample and for an
//    escaped ray along it. The renderer's closed form is in lights_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "render/lights.h"
#include "render/sky.h"

namespace inet {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Unit direction at elevation el and azimuth az (radians; azimuth from +x toward +y).
Vec3 dirElAz(double el, double az) {
  return Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
}

/// A Preetham sky whose sun is at elevation `sun_el_deg`, azimuth 0.
Light preethamLight(double turbidity, double sun_el_deg, float intensity = 100.f) {
  Light l;
  l.name = "sky";
  l.type = LightType::Sky;
  l.sky_model = SkyModel::Preetham;
  l.turbidity = static_cast<float>(turbidity);
  l.direction = -dirElAz(sun_el_deg * kPi / 180.0, 0.0);
  l.intensity = intensity;
  return l;
}

double luminance(const Eigen::Vector3d& c) {
  return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}

/// Uniform float in [0, 1) from 24 bits.
struct Rng {
  explicit Rng(uint64_t seed) : gen(seed) {}
  float operator()() { return static_cast<float>(gen() >> 40) * 0x1p-24f; }
  std::mt19937_64 gen;
};

/// Integral of f(d) dw over the upper hemisphere: midpoint rule in (theta, phi) with each
/// sub-cell's exact solid angle (cos a - cos b) dphi.
template <class F>
auto hemisphereIntegral(F f, int n_theta = 400, int n_phi = 1600) {
  using R = decltype(f(Vec3::UnitZ()));  // double or Eigen::Vector3d
  R sum = f(Vec3::UnitZ()) * 0.0;
  const double dt = 0.5 * kPi / n_theta, dp = 2 * kPi / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double t = (i + 0.5) * dt, w = (std::cos(i * dt) - std::cos((i + 1) * dt)) * dp;
    for (int j = 0; j < n_phi; ++j) {
      const double p = (j + 0.5) * dp;
      sum += f(Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t))) * w;
    }
  }
  return sum;
}

TEST(PreethamSky, ZenithValuesFollowThePaper) {
  for (double T : {2.0, 3.0, 4.5, 7.0, 10.0}) {
    for (double el_deg : {5.0, 20.0, 45.0, 70.0, 89.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun elevation " << el_deg);
      const double ts = (90.0 - el_deg) * kPi / 180.0;
      // Preetham et al. 1999, appendix A.2, written out term by term
      const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * ts);
      const double Yz = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
      const double t2 = ts * ts, t3 = t2 * ts;
      const double xz = (0.00166 * t3 - 0.00375 * t2 + 0.00209 * ts) * T * T +
                        (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * ts + 0.00394) * T +
                        (0.11693 * t3 - 0.21196 * t2 + 0.06052 * ts + 0.25886);
      const double yz = (0.00275 * t3 - 0.00610 * t2 + 0.00317 * ts) * T * T +
                        (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * ts + 0.00516) * T +
                        (0.15346 * t3 - 0.26756 * t2 + 0.06670 * ts + 0.26688);
      EXPECT_NEAR(preethamZenithLuminance(T, ts), Yz, 1e-12 * Yz);
      EXPECT_NEAR(preethamZenithChromaticity(T, ts).x(), xz, 1e-12);
      EXPECT_NEAR(preethamZenithChromaticity(T, ts).y(), yz, 1e-12);
      // the Perez distribution is normalised to these values at the zenith
      const PreethamSky sky(T, -dirElAz(el_deg * kPi / 180.0, 0.3));
      const Eigen::Vector3d zenith = sky.xyY(Vec3::UnitZ());
      EXPECT_NEAR(zenith.z(), Yz, 1e-12 * Yz);
      EXPECT_NEAR(zenith.x(), xz, 1e-12);
      EXPECT_NEAR(zenith.y(), yz, 1e-12);
      // a daylight colour: near the white point, x and y in 0.2 .. 0.4, Y positive
      EXPECT_GT(Yz, 0.0);
      EXPECT_GT(xz, 0.2);
      EXPECT_LT(xz, 0.4);
      EXPECT_GT(yz, 0.2);
      EXPECT_LT(yz, 0.4);
    }
  }
  // the zenith brightens as the sun climbs
  EXPECT_LT(preethamZenithLuminance(3, 80 * kPi / 180), preethamZenithLuminance(3, 40 * kPi / 180));
}

TEST(PreethamSky, XyYToSrgbKeepsLuminanceAndWhite) {
  const Eigen::Vector3d d65 = xyYToLinearSrgb(0.3127, 0.3290, 2.0);  // D65 white point
  EXPECT_NEAR(d65.x(), 2.0, 2e-3);
  EXPECT_NEAR(d65.y(), 2.0, 2e-3);
  EXPECT_NEAR(d65.z(), 2.0, 2e-3);
  const Eigen::Vector3d sky = xyYToLinearSrgb(0.27, 0.29, 5.0);
  // Y survives the conversion (no clipping here), to the 4 digits of the Rec. 709 weights
  EXPECT_NEAR(luminance(sky), 5.0, 5e-4);
  EXPECT_GT(sky.z(), sky.x()) << "x, y below the white point: blue";
}

TEST(PreethamSky, PerezShape) {
  for (double T : {2.0, 3.0, 6.0}) {
    for (double sun_el : {15.0, 35.0, 60.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun elevation " << sun_el);
      const PreethamSky sky(T, -dirElAz(sun_el * kPi / 180.0, 0.0));
      auto Y = [&](double el, double az) { return sky.xyY(dirElAz(el, az)).z(); };
      const double el = sun_el * kPi / 180.0;
      // toward the sun against opposite it, at the sun's elevation
      EXPECT_GT(Y(el, 0.2), 1.5 * Y(el, kPi));
      // at the same angle from the sun (60 degrees), lower is brighter: the Perez gradation
      // 1 + A exp(B / cos theta) (A < 0, B < 0 for 2 <= T < 8) rises toward the horizon
      const Vec3 s = sky.toSun(), side = s.cross(Vec3::UnitZ()).normalized();
      const Vec3 up = side.cross(s).normalized();  // perpendicular to the sun, toward the zenith
      const Vec3 top = 0.5 * s + 0.8660254037844386 * up,
                 flank = 0.5 * s + 0.8660254037844386 * side;
      EXPECT_GT(top.z(), flank.z() + 0.3);
      EXPECT_GT(sky.xyY(flank).z(), sky.xyY(top).z());
      // bluer at the zenith than at the horizon (90 degrees from the sun)
      const Eigen::Vector3d zen = sky.rgb(Vec3::UnitZ()), hor = sky.rgb(dirElAz(0.03, 0.5 * kPi));
      EXPECT_GT(zen.z() / zen.x(), hor.z() / hor.x())
          << zen.transpose() << " | " << hor.transpose();
      EXPECT_GT(zen.z(), zen.x()) << "the zenith is blue";
      // nothing from below the horizon
      EXPECT_EQ(sky.rgb(dirElAz(-0.01, 1.0)), Eigen::Vector3d::Zero());
      EXPECT_EQ(sky.rgb(dirElAz(-1.2, 0.0)), Eigen::Vector3d::Zero());
    }
  }
  // Away from the sun, a clear sky with a low sun is brighter at the horizon than at the zenith
  // (Preetham's figure 7); a hazy sky or a high sun reverses that (the zenith is then close
  // enough to the sun, or the gradation weak: A exp(B) -> 0 as T grows).
  for (double T : {2.0, 3.0}) {
    for (double sun_el : {5.0, 15.0, 35.0}) {
      const PreethamSky sky(T, -dirElAz(sun_el * kPi / 180.0, 0.0));
      const double zenith = sky.xyY(Vec3::UnitZ()).z();
      EXPECT_GT(sky.xyY(dirElAz(0.035, 0.5 * kPi)).z(), 1.3 * zenith) << T << " " << sun_el;
      EXPECT_GT(sky.xyY(dirElAz(0.035, kPi)).z(), 1.3 * zenith) << T << " " << sun_el;
    }
  }
  const PreethamSky hazy_high(10, -dirElAz(60 * kPi / 180, 0.0));
  EXPECT_LT(hazy_high.xyY(dirElAz(0.035, 0.5 * kPi)).z(), hazy_high.xyY(Vec3::UnitZ()).z());
  // haze whitens the zenith: a clear sky is bluer than a hazy one at the same sun
  const PreethamSky clear(2, -dirElAz(0.6, 0)), hazy(9, -dirElAz(0.6, 0));
  const Eigen::Vector3d c = clear.rgb(Vec3::UnitZ()), h = hazy.rgb(Vec3::UnitZ());
  EXPECT_GT(c.z() / c.x(), h.z() / h.x());
}

TEST(PreethamSkyLight, IntensityIsTheHorizontalIrradiance) {
  for (double T : {2.0, 3.0, 8.0}) {
    for (double sun_el : {10.0, 45.0, 85.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun elevation " << sun_el);
      const PreethamSkyLight sky(preethamLight(T, sun_el, 120.f));
      const Eigen::Vector3d E = hemisphereIntegral([&](const Vec3& d) -> Eigen::Vector3d {
        return sky.radiance(d.cast<float>()).cast<double>() * d.z();
      });
      EXPECT_NEAR(luminance(E), 120.0, 0.12);
      const double S = hemisphereIntegral(
          [&](const Vec3& d) { return luminance(sky.radiance(d.cast<float>()).cast<double>()); });
      EXPECT_NEAR(sky.luminanceIntegral(), S, 1e-3 * S);
    }
  }
}

/// Chi-square statistic and p-value of n directions sampled from `sampler` against the
/// integral of `pdf` over a 16 x 32 (theta, phi) grid of the upper hemisphere, plus one bin for
/// failed samples and directions below the horizon (expected: 1 - integral of the pdf).
/// p from the Wilson-Hilferty normal approximation of the chi-square distribution.
template <class Sampler, class Pdf>
double chiSquareP(Sampler sampler, Pdf pdf, int n, uint64_t seed) {
  constexpr int kT = 16, kP = 32, kSub = 24;
  std::vector<double> obs(kT * kP + 1, 0.0), expd(kT * kP + 1, 0.0);
  Rng rng(seed);
  for (int k = 0; k < n; ++k) {
    Vec3f wi;
    if (!sampler(Eigen::Vector2f(rng(), rng()), wi) || wi.z() <= 0.f) {
      obs.back() += 1;
      continue;
    }
    const double th = std::acos(std::min(1.0, double(wi.z())));
    double ph = std::atan2(wi.y(), wi.x());
    if (ph < 0) ph += 2 * kPi;
    const int bt = std::min(int(th / (0.5 * kPi) * kT), kT - 1);
    const int bp = std::min(int(ph / (2 * kPi) * kP), kP - 1);
    obs[bt * kP + bp] += 1;
  }
  const double dt = 0.5 * kPi / (kT * kSub), dp = 2 * kPi / (kP * kSub);
  double total = 0;
  for (int a = 0; a < kT * kSub; ++a) {
    const double t = (a + 0.5) * dt, w = (std::cos(a * dt) - std::cos((a + 1) * dt)) * dp;
    for (int b = 0; b < kP * kSub; ++b) {
      const double p = (b + 0.5) * dp;
      const double v = pdf(Vec3f(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                                 float(std::cos(t)))) *
                       w;
      expd[(a / kSub) * kP + b / kSub] += v * n;
      total += v;
    }
  }
  expd.back() = std::max(0.0, 1.0 - total) * n;
  double stat = 0, pool_o = 0, pool_e = 0;
  int bins = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    if (expd[i] < 5.0) {  // pooled
      pool_o += obs[i];
      pool_e += expd[i];
      continue;
    }
    stat += (obs[i] - expd[i]) * (obs[i] - expd[i]) / expd[i];
    ++bins;
  }
  if (pool_e >= 5.0) {
    stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++bins;
  } else if (pool_o > 10) {
    return 0.0;  // samples where the pdf says there are none
  }
  const double k = bins - 1, h = 2.0 / (9.0 * k);
  const double z = (std::cbrt(stat / k) - (1.0 - h)) / std::sqrt(h);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

TEST(PreethamSkyLight, SamplingMatchesThePdf) {
  int seed = 0;
  double smallest_p = 1.0;
  for (double T : {2.0, 5.0, 10.0}) {
    for (double sun_el : {5.0, 40.0, 88.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun elevation " << sun_el);
      const PreethamSkyLight sky(preethamLight(T, sun_el));
      auto sampler = [&](const Eigen::Vector2f& u, Vec3f& wi) {
        Vec3f L;
        float pdf;
        if (!sky.sample(u, wi, L, pdf)) return false;
        // the sample's pdf and radiance are exactly those of its direction
        EXPECT_EQ(pdf, sky.pdf(wi));
        EXPECT_EQ(L, sky.radiance(wi));
        return true;
      };
      auto pdf = [&](const Vec3f& d) { return double(sky.pdf(d)); };
      // 9 tests: Sidak-corrected 1 % level
      const double p = chiSquareP(sampler, pdf, 200000, ++seed);
      smallest_p = std::min(smallest_p, p);
      EXPECT_GT(p, 1.0 - std::pow(0.99, 1.0 / 9.0));
      // the pdf integrates to 1 over the hemisphere and is 0 below it
      EXPECT_NEAR(hemisphereIntegral([&](const Vec3& d) { return pdf(d.cast<float>()); }), 1.0,
                  1e-3);
      EXPECT_EQ(sky.pdf(Vec3f(0.6f, 0.f, -0.8f)), 0.f);
      EXPECT_GT(sky.pdf(Vec3f(0.f, 0.999f, 0.0447f)), 0.f) << "every sky direction can be sampled";
    }
  }
  std::printf("9 chi-square tests, smallest p-value %.4f\n", smallest_p);
}

TEST(PreethamSkyLight, ChiSquareDetectsAWrongPdf) {
  // samples of a sky whose sun stands 10 degrees higher than the pdf's
  const PreethamSkyLight sky(preethamLight(3, 30)), other(preethamLight(3, 40));
  auto sampler = [&](const Eigen::Vector2f& u, Vec3f& wi) {
    Vec3f L;
    float pdf;
    return other.sample(u, wi, L, pdf);
  };
  EXPECT_LT(chiSquareP(
                sampler, [&](const Vec3f& d) { return double(sky.pdf(d)); }, 200000, 99),
            1e-6);
}

TEST(PreethamSkyLight, SceneLightsSampleAndEscapedRaysAgree) {
  Scene s;
  s.lights = {preethamLight(3, 25, 80.f)};
  const SceneLights lights(s, {});
  Rng rng(7);
  int checked = 0;
  const SceneLights::PickPoint at = lights.pickAt(Vec3f(0.5f, -1.f, 0.2f));
  for (int k = 0; k < 2000; ++k) {
    LightSample ls;
    if (!lights.sample(at, rng(), Eigen::Vector2f(rng(), rng()), ls)) continue;
    ++checked;
    EXPECT_FALSE(ls.delta);
    EXPECT_TRUE(std::isinf(ls.dist));
    float pdf = -1.f;
    const Vec3f L = lights.environmentRadiance(ls.wi, &at, pdf);
    ASSERT_EQ(ls.pdf, pdf) << "MIS needs the same pdf both ways";
    ASSERT_EQ(ls.radiance, L);
  }
  EXPECT_GT(checked, 1990);
  float pdf = -1.f;
  EXPECT_EQ(lights.environmentRadiance(Vec3f(0.f, 0.6f, -0.8f), &at, pdf), Vec3f::Zero());
  EXPECT_EQ(pdf, 0.f) << "below the horizon";
}

// The light-picking weight of a Preetham sky is int Y(L) dw, like a uniform sky's 4 pi Y(L): a
// uniform sky beside it is picked in that proportion, wherever the receiver is.
TEST(PreethamSkyLight, PickedInProportionToItsRadiance) {
  Scene s;
  Light uniform;
  uniform.name = "uniform";
  uniform.type = LightType::Sky;
  uniform.intensity = 3.f;
  s.lights = {uniform, preethamLight(4, 50, 200.f)};
  const SceneLights lights(s, {});
  const PreethamSkyLight sky(s.lights[1]);
  const double S = hemisphereIntegral(
      [&](const Vec3& d) { return luminance(sky.radiance(d.cast<float>()).cast<double>()); });
  const double expected_pmf = 4 * kPi * 3.0 / (4 * kPi * 3.0 + S);
  LightSample ls;  // u_pick 0 picks the first light: the uniform sky, pdf = pmf / (4 pi)
  ASSERT_TRUE(lights.sample(lights.pickAt(Vec3f::Zero()), 0.f, Eigen::Vector2f(0.3f, 0.3f), ls));
  EXPECT_NEAR(ls.pdf * 4 * kPi, expected_pmf, 1e-3 * expected_pmf);
}

}  // namespace
}  // namespace inet
