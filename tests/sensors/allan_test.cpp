#include "sensors/allan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "sensors/imu.h"

namespace inet {
namespace {

/// Noisy static stream (ideal = 0) of `seconds` at `rate_hz`: addImuNoise on zero samples.
ImuSequence staticNoise(const ImuNoise& noise, double rate_hz, double seconds, uint64_t seed) {
  ImuSequence seq;
  seq.ideal.resize(static_cast<size_t>(seconds * rate_hz));
  for (size_t k = 0; k < seq.ideal.size(); ++k)
    seq.ideal[k].t_ns = static_cast<TimeNs>(std::llround(static_cast<double>(k) * 1e9 / rate_hz));
  addImuNoise(seq.ideal, noise, rate_hz, seed, seq.measured, seq.bias);
  return seq;
}

std::vector<double> axis(const ImuSequence& seq, int j) {
  std::vector<double> y(seq.measured.size());
  for (size_t k = 0; k < y.size(); ++k)
    y[k] = j < 3 ? seq.measured[k].gyro[j] : seq.measured[k].accel[j - 3];
  return y;
}

TEST(Allan, WhiteNoiseHasSlopeMinusHalfAndDensityAtOneSecond) {
  ImuNoise n = ImuNoise::euroc();
  n.gyroscope_random_walk = n.accelerometer_random_walk = 0;
  const ImuSequence seq = staticNoise(n, 800.0, 1200.0, 1);  // 20 min at the default rate
  for (int j = 0; j < 6; ++j) {
    const std::vector<AllanPoint> c = allanDeviation(axis(seq, j), 800.0);
    const double density = j < 3 ? n.gyroscope_noise_density : n.accelerometer_noise_density;
    EXPECT_NEAR(allanAt(c, 1.0) / density, 1.0, 0.1) << j;
    // slope between 0.01 s and 10 s in log-log
    const double slope = std::log(allanAt(c, 10.0) / allanAt(c, 0.01)) / std::log(1000.0);
    EXPECT_NEAR(slope, -0.5, 0.05) << j;
  }
}

TEST(Allan, PureRandomWalkHasSlopePlusHalf) {
  ImuNoise n;
  n.gyroscope_random_walk = 1e-3;
  const ImuSequence seq = staticNoise(n, 100.0, 36000.0, 2);
  const std::vector<AllanPoint> c = allanDeviation(axis(seq, 0), 100.0);
  const double slope = std::log(allanAt(c, 300.0) / allanAt(c, 3.0)) / std::log(100.0);
  EXPECT_NEAR(slope, 0.5, 0.05);
  EXPECT_NEAR(allanAt(c, 3.0) / 1e-3, 1.0, 0.1);  // sigma(3 s) = K
}

uint64_t testSeed(uint64_t fallback) {
  const char* env = std::getenv("INET_ALLAN_SEED");  // for checking other seeds by hand
  return env ? std::strtoull(env, nullptr, 10) : fallback;
}

/// Allan variance averaged over the three axes of one sensor (they share their parameters).
std::vector<AllanPoint> pooledAllan(const ImuSequence& seq, int sensor, double rate) {
  std::vector<AllanPoint> pooled;
  for (int j = 3 * sensor; j < 3 * sensor + 3; ++j) {
    const std::vector<AllanPoint> c = allanDeviation(axis(seq, j), rate);
    if (pooled.empty()) pooled.assign(c.size(), AllanPoint{});
    for (size_t i = 0; i < c.size(); ++i) {
      pooled[i].tau_s = c[i].tau_s;
      pooled[i].adev += c[i].adev * c[i].adev / 3.0;  // variance first, sqrt below
    }
  }
  for (AllanPoint& p : pooled) p.adev = std::sqrt(p.adev);
  return pooled;
}

TEST(Allan, RecoversTheEuRoCNoiseDensitiesAt800Hz) {
  // 20 min static at 800 Hz, EuRoC's four values. N: the slope -1/2 line at 1 s of the joint
  // fit sigma^2 = N^2/tau + K^2 tau/3 over tau in [0.01 s, T/10], per axis.
  const ImuNoise n = ImuNoise::euroc();
  const double rate = 800.0, seconds = 1200.0;
  const uint64_t seed = testSeed(5);
  const ImuSequence seq = staticNoise(n, rate, seconds, seed);
  for (int j = 0; j < 6; ++j) {
    const std::vector<AllanPoint> c = allanDeviation(axis(seq, j), rate);
    const AllanNoiseFit f = fitAllanNoise(c, 0.01, seconds / 10);
    const double N = j < 3 ? n.gyroscope_noise_density : n.accelerometer_noise_density;
    std::printf("axis %d (seed %llu): N %.4e vs configured %.4e (%+.1f %%), sigma(1 s) %.4e\n", j,
                static_cast<unsigned long long>(seed), f.noise_density, N,
                100 * (f.noise_density / N - 1), allanAt(c, 1.0));
    EXPECT_NEAR(f.noise_density / N, 1.0, 0.1) << j;
    // the gyro's random walk is negligible at 1 s (crossover ~15 s): sigma(1 s) itself is N.
    // The accelerometer's is not (crossover ~1.2 s): sigma(1 s)^2 = N^2 + K^2/3.
    if (j < 3) {
      EXPECT_NEAR(allanAt(c, 1.0) / N, 1.0, 0.1) << j;
    } else {
      const double K = n.accelerometer_random_walk;
      EXPECT_NEAR(allanAt(c, 1.0) / std::sqrt(N * N + K * K / 3), 1.0, 0.1) << j;
    }
  }
}

TEST(Allan, RecoversTheEuRoCRandomWalks) {
  // 72 h static at 5 Hz (the densities do not depend on the rate; 5 Hz keeps the run short and
  // small). K: the slope +1/2 line at 3 s of the joint fit over tau in [1 s, T/20], on the
  // Allan variance pooled over each sensor's three axes: a random-walk estimate from one axis
  // scatters by ~5-10 % even over three days (the per-axis check is looser).
  const ImuNoise n = ImuNoise::euroc();
  const double rate = 5.0, seconds = 72 * 3600.0;
  const uint64_t seed = testSeed(5);
  const ImuSequence seq = staticNoise(n, rate, seconds, seed);
  for (int sensor = 0; sensor < 2; ++sensor) {
    const double K = sensor == 0 ? n.gyroscope_random_walk : n.accelerometer_random_walk;
    for (int j = 3 * sensor; j < 3 * sensor + 3; ++j) {
      const AllanNoiseFit f = fitAllanNoise(allanDeviation(axis(seq, j), rate), 1.0, seconds / 20);
      EXPECT_NEAR(f.random_walk / K, 1.0, 0.25) << j;
    }
    const AllanNoiseFit fit = fitAllanNoise(pooledAllan(seq, sensor, rate), 1.0, seconds / 20);
    std::printf("%s (3 axes, seed %llu): K %.4e vs configured %.4e (%+.1f %%)\n",
                sensor == 0 ? "gyro " : "accel", static_cast<unsigned long long>(seed),
                fit.random_walk, K, 100 * (fit.random_walk / K - 1));
    EXPECT_NEAR(fit.random_walk / K, 1.0, 0.1);
  }
}

}  // namespace
}  // namespace inet
