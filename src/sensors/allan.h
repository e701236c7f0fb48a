#pragma once
// Overlapping Allan deviation (IEEE Std 952-1997, annex C; the estimator Kalibr's allan_variance
// tools and imu_utils use) and the fit of the two noise terms the IMU model has.
//
// For samples y_k at rate f (tau0 = 1/f), theta_j = tau0 * sum_{k<j} y_k, cluster time
// tau = m tau0:
//   sigma^2(tau) = 1 / (2 tau^2 (N - 2m + 1))
//                  * sum_{j=0}^{N-2m} (theta_{j+2m} - 2 theta_{j+m} + theta_j)^2
// White noise of density N gives sigma(tau) = N / sqrt(tau) (slope -1/2, read at tau = 1 s);
// a bias random walk of density K gives sigma(tau) = K sqrt(tau / 3) (slope +1/2, read at
// tau = 3 s). Independent terms add in variance.
#include <cstddef>
#include <vector>

namespace inet {

struct AllanPoint {
  double tau_s = 0.0;
  double adev = 0.0;     ///< Allan deviation, units of y
  size_t clusters = 0;   ///< number of overlapping differences averaged
};

/// Allan deviation at cluster sizes spaced `per_decade` per decade of tau, from one sample up to
/// N / max_fraction samples (longer clusters have too few independent differences).
std::vector<AllanPoint> allanDeviation(const std::vector<double>& y, double rate_hz,
                                       int per_decade = 10, double max_fraction = 10.0);

/// The deviation at `tau_s`, interpolated linearly in log-log between the nearest points
/// (INET_CHECK: tau within the curve).
double allanAt(const std::vector<AllanPoint>& curve, double tau_s);

struct AllanNoiseFit {
  double noise_density = 0.0;  ///< N: value of the slope -1/2 line at tau = 1 s
  double random_walk = 0.0;    ///< K: value of the slope +1/2 line at tau = 3 s
};

/// Least-squares fit of sigma^2(tau) = N^2 / tau + K^2 tau / 3 to the points with tau in
/// [tau_min, tau_max], each residual relative to the measured variance (so every decade
/// weighs the same). Linear in (N^2, K^2); a negative solution is clamped to 0.
AllanNoiseFit fitAllanNoise(const std::vector<AllanPoint>& curve, double tau_min, double tau_max);

/// K from the slope +1/2 line alone: the geometric mean of sigma(tau) / sqrt(tau / 3) over the
/// points in [tau_min, tau_max] (valid where the random walk dominates).
double fitRandomWalkLine(const std::vector<AllanPoint>& curve, double tau_min, double tau_max);

}  // namespace inet
