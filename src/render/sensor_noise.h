#pragma once
// Optional image-sensor noise on a linear (exposed) image: the Poisson-Gaussian model
// (A. Foi, M. Trimeche, V. Katkovnik, K. Egiazarian, "Practical Poissonian-Gaussian noise
// modeling and fitting for single-image raw-data", IEEE TIP 17(10), 2008; EMVA 1288 uses the
// same linear camera model). Per pixel and channel, with v the linear value (1.0 = full well):
//     n_e  ~ Poisson(max(v, 0) * full_well_e)             photo-electrons (shot noise)
//     n_e  = min(n_e, full_well_e)                         if saturate
//     s_e  = n_e + read_noise_e * N(0, 1)                  read noise, electrons rms
//     s_e  = step * round(s_e / step), step = full_well_e / (2^adc_bits - 1)   if adc_bits > 0
//     out  = s_e / full_well_e
// so, in linear units with gain g = full_well_e (electrons per unit),
//     E[out] = v,  Var[out] = v / g + (read_noise_e / g)^2  (+ step^2 / 12 g^2 when quantised).
// Negative outputs are kept (a real sensor's black-level offset keeps them before subtraction),
// so the read noise stays zero-mean at zero signal.
//
// Defaults: Sony IMX250 (3.45 um global-shutter Pregius, a common machine-vision and SLAM camera
// sensor) as characterised in the Teledyne DALSA Genie Nano Series manual, model M2450 (12-bit
// "standard design"): full well 10.7 ke-, output dynamic range 75.46 dB, hence read noise
// 10 700 / 10^(75.46 / 20) = 1.8 e-. ADC 12 bit.
//
// Random numbers: CounterRng(seed, RngStream::Sensor, frame, pixel index y * width + x,
// kSensorNoiseTag), channels drawn in order from that pixel's stream, so the result is a pure
// function of (seed, frame, pixel) whatever the thread count.
#include <cstdint>
#include <string>

#include "core/image.h"
#include "core/rng.h"

namespace inet {

/// Third counter word of the image-noise streams, to keep them apart from other consumers of
/// RngStream::Sensor (ASCII "IMNS").
constexpr uint32_t kSensorNoiseTag = 0x494d4e53u;

struct SensorNoise {
  double full_well_e = 10700.0;  ///< electrons at linear value 1.0 (saturation capacity), e-
  double read_noise_e = 1.8;     ///< temporal dark (read) noise, e- rms
  int adc_bits = 12;             ///< quantisation step full_well_e / (2^bits - 1); 0 = none
  bool saturate = false;         ///< clip electrons at the full well (true for a real sensor;
                                 ///< false keeps HDR headroom for a filmic tone curve)

  /// "full_well_e=10700 read_noise_e=1.8 adc_bits=12 saturate=0".
  std::string describe() const;
};

/// Throws InputError(where, "sensor_noise.<field>", ...): full_well_e finite and >= 1,
/// read_noise_e finite and >= 0, adc_bits in 0..24.
void validateSensorNoise(const SensorNoise& model, const std::string& where);

/// The noisy image (same size and channels). Non-finite input values pass through unchanged.
/// Parallel over rows; deterministic in (seed, frame, pixel).
ImageF applySensorNoise(const ImageF& linear, const SensorNoise& model, uint64_t seed,
                        uint32_t frame);

/// Standard normal deviate (Box-Muller from two 53-bit uniforms; no std::normal_distribution,
/// whose output differs between standard libraries).
double standardNormal(CounterRng& rng);

/// Poisson deviate with mean `mean` >= 0: inversion by sequential search below 12, else the
/// PTRS transformed-rejection method of W. Hörmann, "The transformed rejection method for
/// generating Poisson random variables", Insurance: Mathematics and Economics 12, 1993.
double poisson(CounterRng& rng, double mean);

}  // namespace inet
