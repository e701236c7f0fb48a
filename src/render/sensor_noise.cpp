#include "render/sensor_noise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.h"

namespace inet {
namespace {

constexpr double kInversionLimit = 12.0;  // below: inversion; above: PTRS (valid from 10)

/// ln(k!) exactly from a product for small k, else Stirling's series for ln Gamma(k + 1)
/// (absolute error below 1e-12 from k = 10 with three correction terms).
double logFactorial(double k) {
  if (k < 10.0) {
    double f = 1.0;
    for (int i = 2; i <= static_cast<int>(k); ++i) f *= i;
    return std::log(f);
  }
  const double n = k + 1.0, n2 = n * n;
  return (n - 0.5) * std::log(n) - n + 0.5 * std::log(2.0 * std::numbers::pi) +
         (1.0 / 12.0 - (1.0 / 360.0 - 1.0 / (1260.0 * n2)) / n2) / n;
}

double poissonInversion(CounterRng& rng, double mean) {
  double u = rng.uniformDouble();
  double p = std::exp(-mean), cdf = p;
  double k = 0.0;
  // The cap only guards against rounding of the cdf; P(k > 200 | mean < 12) is ~1e-200.
  while (u > cdf && k < 200.0) {
    k += 1.0;
    p *= mean / k;
    cdf += p;
  }
  return k;
}

double poissonPtrs(CounterRng& rng, double mean) {
  const double smu = std::sqrt(mean);
  const double b = 0.931 + 2.53 * smu;
  const double a = -0.059 + 0.02483 * b;
  const double log_inv_alpha = std::log(1.1239 + 1.1328 / (b - 3.4));
  const double v_r = 0.9277 - 3.6224 / (b - 2.0);
  const double log_mean = std::log(mean);
  for (;;) {
    double u = rng.uniformDouble() - 0.5;
    double v = rng.uniformDouble();
    double us = 0.5 - std::fabs(u);
    if (us <= 0.0) continue;
    double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= v_r) return k;
    if (k < 0.0 || (us < 0.013 && v > us)) continue;
    if (std::log(v) + log_inv_alpha - std::log(a / (us * us) + b) <=
        -mean + k * log_mean - logFactorial(k))
      return k;
  }
}

/// One noisy value in linear units.
float noisyValue(CounterRng& rng, float v, const SensorNoise& m, double step_e) {
  if (!std::isfinite(v)) return v;
  double electrons = poisson(rng, std::max(0.0, static_cast<double>(v)) * m.full_well_e);
  if (m.saturate) electrons = std::min(electrons, m.full_well_e);
  double signal = electrons + m.read_noise_e * standardNormal(rng);
  if (step_e > 0.0) {
    signal = step_e * std::floor(signal / step_e + 0.5);
    if (m.saturate) signal = std::min(signal, m.full_well_e);
  }
  return static_cast<float>(signal / m.full_well_e);
}

}  // namespace

std::string SensorNoise::describe() const {
  std::ostringstream s;
  s << "full_well_e=" << full_well_e << " read_noise_e=" << read_noise_e << " adc_bits=" << adc_bits
    << " saturate=" << (saturate ? 1 : 0);
  return s.str();
}

void validateSensorNoise(const SensorNoise& m, const std::string& where) {
  if (!(std::isfinite(m.full_well_e) && m.full_well_e >= 1.0))
    throw InputError(where, "sensor_noise.full_well_e",
                     "must be finite and >= 1 electron, got " + std::to_string(m.full_well_e));
  if (!(std::isfinite(m.read_noise_e) && m.read_noise_e >= 0.0))
    throw InputError(where, "sensor_noise.read_noise_e",
                     "must be finite and >= 0 electrons, got " + std::to_string(m.read_noise_e));
  if (m.adc_bits < 0 || m.adc_bits > 24)
    throw InputError(where, "sensor_noise.adc_bits",
                     "must be in 0..24 (0 = no quantisation), got " + std::to_string(m.adc_bits));
}

double standardNormal(CounterRng& rng) {
  double u1 = 1.0 - rng.uniformDouble();  // (0, 1]: log stays finite
  double u2 = rng.uniformDouble();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double poisson(CounterRng& rng, double mean) {
  if (!(mean > 0.0)) return 0.0;
  return mean < kInversionLimit ? poissonInversion(rng, mean) : poissonPtrs(rng, mean);
}

ImageF applySensorNoise(const ImageF& linear, const SensorNoise& model, uint64_t seed,
                        uint32_t frame) {
  validateSensorNoise(model, "");
  const double step_e =
      model.adc_bits > 0 ? model.full_well_e / (std::exp2(model.adc_bits) - 1.0) : 0.0;
  ImageF out = linear;
  tbb::parallel_for(tbb::blocked_range<int>(0, linear.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < linear.width; ++x) {
        uint32_t pixel = static_cast<uint32_t>(y) * static_cast<uint32_t>(linear.width) +
                         static_cast<uint32_t>(x);
        CounterRng rng(seed, RngStream::Sensor, frame, pixel, kSensorNoiseTag);
        float* px = out.pixel(x, y);
        for (int c = 0; c < linear.channels; ++c) px[c] = noisyValue(rng, px[c], model, step_e);
      }
    }
  });
  return out;
}

}  // namespace inet
