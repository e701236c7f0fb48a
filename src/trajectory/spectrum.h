#pragma once
// Motion analysis for the trajectory style model (docs/style.md): uniform resampling of a pose
// sequence through a smooth interpolant, velocities and accelerations by central differences,
// Welch power spectra and the log-spectral distance.
//
// Resampling ("sampled from the spline"): positions follow the Catmull-Rom cubic through the
// samples (C1, interpolating; tangents are central differences over the non-uniform time steps),
// rotations the same cubic on the quaternion components after making consecutive quaternions
// sign-consistent, then normalised. For the dense (>= 100 Hz) mocap and simulated poses we use,
// its error is far below the motion of interest.
//
// From poses T_k at the uniform rate r (dt = 1/r), in the world frame:
//   v_k = (p_{k+1} - p_{k-1}) / (2 dt)              linear velocity (m/s)
//   a_k = (p_{k+1} - 2 p_k + p_{k-1}) / dt^2        linear acceleration, without gravity (m/s^2)
//   w_k = Log(R_{k+1} R_{k-1}^T) / (2 dt)           angular velocity (rad/s)
// World-frame angular velocity is the same whichever frame is attached to the rigid body (the
// camera of TUM RGB-D, the IMU of TUM-VI), which is why the style model works in the world frame.
//
// Spectra: Welch's method (Hann window, 50 % overlap, one-sided, density scaling, so that the
// sum of P(f) df over f equals the mean square of the series). A 3-vector series' spectrum is
// the trace, the sum of its three per-axis spectra (invariant to a rotation of the world).
// Log-spectral distance in dB between spectra P and Q over the bins f_lo <= f <= f_hi:
//   LSD(P, Q) = sqrt( mean_f ( 10 log10(P(f) / Q(f)) )^2 ).
#include <vector>

#include "trajectory/trajectory.h"

namespace inet {

/// Poses at t0 + k / rate_hz (t0 = first pose's time) up to the last pose's time, interpolated
/// as described above. Needs >= 2 poses (returns a copy otherwise).
Trajectory resampleUniform(const Trajectory& traj, double rate_hz);

/// World-frame velocity, angular velocity and acceleration of a uniformly sampled trajectory
/// (at its interior samples 1 .. n-2; n-2 entries each).
struct MotionSeries {
  double rate_hz = 0;
  std::vector<Vec3> v_world, w_world, a_world;
};
MotionSeries motionSeries(const Trajectory& uniform, double rate_hz);

/// A one-sided power spectral density: psd[i] at freq_hz[i] (units^2 / Hz).
struct Spectrum {
  std::vector<double> freq_hz, psd;
};

/// Welch's PSD pooled over many series: add any number of series (each at least one segment
/// long; shorter ones are ignored); the result averages all their segments, so longer series
/// weigh more. Vector series add the trace of their per-axis spectra.
class WelchPsd {
 public:
  WelchPsd(double rate_hz, int segment);
  void add(const std::vector<double>& x);
  void add(const std::vector<Vec3>& x);
  int segments() const { return count_; }
  /// The averaged spectrum (bins 0 .. segment/2). InputError-free: CHECKs that segments() > 0.
  Spectrum result() const;

 private:
  void addSegment(const double* x, size_t stride, std::vector<double>& acc) const;
  double rate_hz_;
  int segment_;
  std::vector<double> window_, acc_;
  double window_power_ = 0;
  int count_ = 0;
};

/// LSD in dB between two spectra on the same bins, over f_lo <= f <= f_hi.
double logSpectralDistanceDb(const Spectrum& p, const Spectrum& q, double f_lo, double f_hi);

}  // namespace inet
