// Camera response (exposure, tone curves, 8-bit sRGB) and the Poisson-Gaussian sensor noise.
// Expected values are derived here from the published formulas, not printed by the code.
#include "render/tonemap.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "render/sensor_noise.h"

namespace inet {
namespace {

TEST(Tonemap, ExposureDoublesPerStop) {
  CameraResponse r;
  r.exposure_ev = 1.f;
  EXPECT_EQ(r.multiplier(), 2.f);
  r.exposure_ev = -2.f;
  r.exposure_scale = 3.f;
  EXPECT_EQ(r.multiplier(), 0.75f);
  ImageF img(4, 2, 3);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = 0.01f * static_cast<float>(i);
  const ImageF original = img;
  ImageF twice = applyExposure(img, CameraResponse{1.f, 1.f, ToneCurve::Clamp}.multiplier());
  for (size_t i = 0; i < img.data.size(); ++i) EXPECT_EQ(twice.data[i], 2.f * img.data[i]);
  // The same through the whole response with the identity-like clamp curve, below 1.
  ImageF shown = applyExposureAndCurve(img, CameraResponse{1.f, 1.f, ToneCurve::Clamp});
  for (size_t i = 0; i < img.data.size(); ++i)
    EXPECT_EQ(shown.data[i], std::min(1.f, 2.f * img.data[i]));
  EXPECT_TRUE(img == original) << "the linear input must stay untouched";
}

TEST(Tonemap, FilmicCurvesAreMonotonicFromZeroAndSaturateAtOne) {
  for (ToneCurve c : {ToneCurve::Aces, ToneCurve::Hable}) {
    SCOPED_TRACE(toneCurveName(c));
    EXPECT_EQ(applyToneCurve(c, 0.f), 0.f);
    float prev = 0.f;
    for (double x = 1e-6; x < 1e6; x *= 1.01) {  // log sweep over 12 decades
      float y = applyToneCurve(c, static_cast<float>(x));
      ASSERT_GE(y, prev) << "not monotonic at x = " << x;
      ASSERT_LE(y, 1.f);
      prev = y;
    }
    EXPECT_LT(applyToneCurve(c, 1.f), 1.f) << "highlights are compressed below white";
    EXPECT_LT(applyToneCurve(c, 1.f), 0.85f);
    EXPECT_EQ(applyToneCurve(c, 1e6f), 1.f);
    EXPECT_EQ(applyToneCurve(c, std::numeric_limits<float>::infinity()), 1.f);
    EXPECT_EQ(applyToneCurve(c, std::numeric_limits<float>::quiet_NaN()), 0.f);
    EXPECT_EQ(applyToneCurve(c, -3.f), 0.f);
  }
  // ACES fit at x = 1: (2.51 + 0.03) / (2.43 + 0.59 + 0.14); saturates where
  // 0.08 x^2 - 0.56 x - 0.14 = 0, x = (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16.
  EXPECT_NEAR(applyToneCurve(ToneCurve::Aces, 1.f), 2.54 / 3.16, 1e-6);
  double x_sat = (0.56 + std::sqrt(0.56 * 0.56 + 4 * 0.08 * 0.14)) / 0.16;
  EXPECT_LT(applyToneCurve(ToneCurve::Aces, static_cast<float>(x_sat * 0.99)), 1.f);
  EXPECT_EQ(applyToneCurve(ToneCurve::Aces, static_cast<float>(x_sat * 1.01)), 1.f);
  // Hable: exactly white at the white point W = 11.2, just below it before.
  EXPECT_NEAR(applyToneCurve(ToneCurve::Hable, 11.2f), 1.f, 1e-6);
  EXPECT_LT(applyToneCurve(ToneCurve::Hable, 10.f), 1.f);
}

TEST(Tonemap, SrgbOfLinearHalfIs188) {
  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354, * 255 = 187.5 -> 188.
  ImageF img(3, 1, 1);
  img.data = {0.5f, 0.f, 4.f};
  ImageU8 out = applyCameraResponse(img, CameraResponse{});
  EXPECT_EQ(out.data[0], 188);
  EXPECT_EQ(out.data[1], 0);
  EXPECT_EQ(out.data[2], 255);
  EXPECT_EQ(out.width, 3);
  // Exposure -1 EV on 1.0 gives the same code as linear 0.5.
  img.data = {1.f, 1.f, 1.f};
  EXPECT_EQ(applyCameraResponse(img, CameraResponse{-1.f, 1.f, ToneCurve::Clamp}).data[0], 188);
}

TEST(Tonemap, NamesAndValidation) {
  for (ToneCurve c : {ToneCurve::Clamp, ToneCurve::Aces, ToneCurve::Hable})
    EXPECT_EQ(parseToneCurve(toneCurveName(c), "cfg", "curve"), c);
  EXPECT_EQ(parseToneCurve("none", "cfg", "curve"), ToneCurve::Clamp);
  try {
    parseToneCurve("reinhard", "cfg.json", "camera.curve");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "cfg.json");
    EXPECT_NE(e.problem().find("aces"), std::string::npos) << "lists the valid names";
  }
  EXPECT_THROW(validateCameraResponse(CameraResponse{0.f, 0.f, ToneCurve::Aces}, ""), InputError);
  EXPECT_THROW(validateCameraResponse(CameraResponse{NAN, 1.f, ToneCurve::Aces}, ""), InputError);
  EXPECT_EQ(CameraResponse{}.describe(), "exposure_ev=0 exposure_scale=1 curve=clamp");
}

// ---- sensor noise ---------------------------------------------------------------------------

struct Moments {
  double mean = 0, var = 0;
};

/// Mean and variance, in electrons, of a flat 256x256 patch of linear value v.
Moments flatPatchElectrons(const SensorNoise& m, float v, uint64_t seed = 11) {
  ImageF flat(256, 256, 1, v);
  ImageF noisy = applySensorNoise(flat, m, seed, 3);
  double s = 0, s2 = 0;
  for (float x : noisy.data) {
    double e = x * m.full_well_e;
    s += e;
    s2 += e * e;
  }
  double n = static_cast<double>(noisy.data.size());
  Moments mo;
  mo.mean = s / n;
  mo.var = (s2 - s * s / n) / (n - 1);
  return mo;
}

TEST(Tonemap, ExposureMeterPutsTheLogAverageAtMiddleGreyInThirdStops) {
  ExposureMeter grey;
  grey.add(ImageF(8, 8, 3, 0.18f));
  EXPECT_FLOAT_EQ(grey.scale(), 1.f);
  ExposureMeter dim;  // 2 stops under: +2 EV
  dim.add(ImageF(8, 8, 3, 0.045f));
  EXPECT_FLOAT_EQ(dim.scale(), 4.f);
  ExposureMeter half;  // half black, half 0.72: the log-average of blocks is what counts
  ImageF img(8, 8, 3, 0.f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = 0.72f;
  half.add(img);
  // black blocks count as 1e-4: log-average sqrt(0.7201e-4), +4.4 EV, rounded to a third
  const double ev = std::round(3 * std::log2(0.18 / std::sqrt(0.7201e-4))) / 3;
  EXPECT_NEAR(std::log2(half.scale()), ev, 1e-5);
  EXPECT_NEAR(ev, 4.0 + 1.0 / 3, 1e-9);
  ExposureMeter two;  // images add up: 0.045 and 0.72 average to 0.18 in the log
  two.add(ImageF(8, 8, 3, 0.045f));
  two.add(ImageF(8, 8, 3, 0.72f));
  EXPECT_NEAR(two.scale(), 1.f, 1e-3);
  ExposureMeter bad;  // non-finite blocks are black, not NaN
  bad.add(ImageF(8, 8, 3, std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(std::isfinite(bad.scale()));
  EXPECT_FLOAT_EQ(bad.scale(), 256.f);
}

TEST(SensorNoise, FlatPatchVarianceIsSignalPlusReadNoiseSquared) {
  SensorNoise m;
  m.adc_bits = 0;  // quantisation off: the bare Poisson-Gaussian model
  // In linear units with gain g = full_well_e: Var = v / g + (read / g)^2; times g^2 in e-.
  for (double signal_e : {5.0, 11.5, 40.0, 2675.0, 9000.0}) {
    float v = static_cast<float>(signal_e / m.full_well_e);
    Moments mo = flatPatchElectrons(m, v);
    double want = v * m.full_well_e + m.read_noise_e * m.read_noise_e;
    EXPECT_NEAR(mo.var / want, 1.0, 0.03) << "signal " << signal_e << " e-";
    EXPECT_NEAR(mo.mean, v * m.full_well_e, 5 * std::sqrt(want / 65536.0));
  }
}

TEST(SensorNoise, ZeroSignalGivesOnlyReadNoise) {
  SensorNoise m;
  m.adc_bits = 0;
  Moments mo = flatPatchElectrons(m, 0.f);
  EXPECT_NEAR(mo.var / (m.read_noise_e * m.read_noise_e), 1.0, 0.03);
  EXPECT_NEAR(mo.mean, 0.0, 5 * m.read_noise_e / 256.0);
  m.read_noise_e = 0.0;
  ImageF dark = applySensorNoise(ImageF(16, 16, 3), m, 1, 0);
  for (float x : dark.data) EXPECT_EQ(x, 0.f);
}

TEST(SensorNoise, QuantisationAddsStepSquaredOverTwelve) {
  SensorNoise m;  // defaults: 12-bit ADC
  double step = m.full_well_e / 4095.0;
  Moments mo = flatPatchElectrons(m, 0.3f);
  double want = 0.3f * m.full_well_e + m.read_noise_e * m.read_noise_e + step * step / 12;
  EXPECT_NEAR(mo.var / want, 1.0, 0.03);
  ImageF noisy = applySensorNoise(ImageF(32, 32, 1, 0.3f), m, 2, 0);
  for (float x : noisy.data) {
    double codes = x * m.full_well_e / step;
    ASSERT_NEAR(codes, std::round(codes), 1e-3) << "not on the ADC grid";
  }
}

TEST(SensorNoise, SaturationClipsAtFullWell) {
  SensorNoise m;
  m.saturate = true;
  ImageF noisy = applySensorNoise(ImageF(64, 64, 3, 2.5f), m, 4, 0);
  for (float x : noisy.data) ASSERT_LE(x, 1.f);
  m.saturate = false;  // HDR headroom kept
  noisy = applySensorNoise(ImageF(64, 64, 3, 2.5f), m, 4, 0);
  double mean = 0;
  for (float x : noisy.data) mean += x;
  EXPECT_NEAR(mean / noisy.data.size(), 2.5, 1e-3);
}

TEST(SensorNoise, DeterministicInSeedFrameAndThreads) {
  ImageF img(97, 61, 3);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = 0.001f * static_cast<float>(i % 997);
  SensorNoise m;
  ImageF a = applySensorNoise(img, m, 42, 7), b = applySensorNoise(img, m, 42, 7);
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == applySensorNoise(img, m, 43, 7));
  EXPECT_FALSE(a == applySensorNoise(img, m, 42, 8));
  ImageF one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = applySensorNoise(img, m, 42, 7);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = applySensorNoise(img, m, 42, 7);
  }
  EXPECT_TRUE(one == a);
  EXPECT_TRUE(two == a);
  img.data[5] = NAN;
  EXPECT_TRUE(std::isnan(applySensorNoise(img, m, 1, 1).data[5]));
}

TEST(SensorNoise, PoissonSamplerMatchesThePmf) {
  // Both branches (inversion below 12, PTRS above): frequencies of k against
  // P(k) = e^-mean mean^k / k!, each within 5 binomial standard deviations + a small slack.
  for (double mean : {0.7, 4.0, 11.9, 12.0, 20.0, 150.0}) {
    SCOPED_TRACE(mean);
    const int n = 200000;
    std::vector<int> hist(static_cast<size_t>(mean * 4 + 40), 0);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      CounterRng rng(77, RngStream::Sensor, 0, static_cast<uint32_t>(i), 9);
      double k = poisson(rng, mean);
      ASSERT_EQ(k, std::floor(k));
      ASSERT_GE(k, 0.0);
      sum += k;
      sum2 += k * k;
      if (k < hist.size()) ++hist[static_cast<size_t>(k)];
    }
    double m = sum / n, var = sum2 / n - m * m;
    EXPECT_NEAR(m, mean, 5 * std::sqrt(mean / n));
    EXPECT_NEAR(var / mean, 1.0, 0.03);
    for (size_t k = 0; k < hist.size(); ++k) {
      double p = std::exp(-mean + k * std::log(mean) - std::lgamma(k + 1.0));
      double sd = std::sqrt(n * p * (1 - p));
      EXPECT_NEAR(hist[k], n * p, 5 * sd + 3) << "k = " << k;
    }
  }
  CounterRng rng(1, RngStream::Sensor, 0, 0, 0);
  EXPECT_EQ(poisson(rng, 0.0), 0.0);
  double big = poisson(rng, 1e9);
  EXPECT_NEAR(big, 1e9, 6 * std::sqrt(1e9));
}

TEST(SensorNoise, StandardNormalMoments) {
  double s = 0, s2 = 0, s4 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    CounterRng rng(3, RngStream::Sensor, 1, static_cast<uint32_t>(i), 0);
    double z = standardNormal(rng);
    s += z, s2 += z * z, s4 += z * z * z * z;
  }
  EXPECT_NEAR(s / n, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(s2 / n, 1.0, 0.015);
  EXPECT_NEAR(s4 / n, 3.0, 0.08);  // Gaussian kurtosis
}

TEST(SensorNoise, Validation) {
  SensorNoise m;
  m.full_well_e = 0;
  EXPECT_THROW(validateSensorNoise(m, "cfg"), InputError);
  m = SensorNoise{};
  m.read_noise_e = -1;
  EXPECT_THROW(validateSensorNoise(m, "cfg"), InputError);
  m = SensorNoise{};
  m.adc_bits = 40;
  try {
    applySensorNoise(ImageF(2, 2, 1), m, 0, 0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "sensor_noise.adc_bits");
  }
  EXPECT_EQ(SensorNoise{}.describe(), "full_well_e=10700 read_noise_e=1.8 adc_bits=12 saturate=0");
}

}  // namespace
}  // namespace inet
