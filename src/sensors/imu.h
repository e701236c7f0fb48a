#pragma once
// IMU simulation from the trajectory spline (SENSORS.md section 2).
//
// Frames: world W (Z up, gravity g_W = (0, 0, -9.81) m/s^2 by default); IMU frame S; camera C
// (OpenCV). T_cam_imu maps IMU coordinates into the camera (Kalibr's camchain name); identity
// by default, so the IMU frame is the camera frame. The spline is fitted to the IMU poses
// T_world_imu = T_world_camera * T_cam_imu (the lever arm is part of the motion).
//
// Ideal measurements (noise-free ground truth) at IMU time t:
//   gyro   w_S(t') = body angular velocity of the spline           [rad/s]
//   accel  a_S(t') = R_WS(t')^T (p''_W(t') - g_W)                  [m/s^2]  (specific force)
// with t' = t - time_offset the time on the camera's (trajectory's) clock: Kalibr's
// timeshift_cam_imu convention, t_imu = t_cam + time_offset. At rest a_S = R_WS^T (0, 0, +9.81):
// the specific force points up.
//
// Noise (Kalibr's discrete-time model, "IMU Noise Model" wiki; OpenVINS Simulator::get_next_imu
// draws in the same order), per axis and sample k, dt = 1 / rate_hz:
//   w_m[k] = w[k] + b_g[k] + sigma_g / sqrt(dt) n,   a_m[k] = a[k] + b_a[k] + sigma_a / sqrt(dt) n
//   b_g[k+1] = b_g[k] + sigma_bg sqrt(dt) n,         b_a[k+1] = b_a[k] + sigma_ba sqrt(dt) n
// n ~ N(0, 1) i.i.d. (Box-Muller on CounterRng(seed, RngStream::Sensor, kImuRngTag, k, 0): a
// pure function of seed and sample index, the same bytes on every platform and thread count).
// Kalibr's caveat: the sqrt(dt) scaling assumes an ideal anti-alias filter; noise is simulated
// at the output rate, never decimated.
#include <cstdint>
#include <string>
#include <vector>

#include "core/pose.h"
#include "sensors/bspline.h"
#include "trajectory/trajectory.h"

namespace inet {

/// Continuous-time noise densities (Kalibr / EuRoC sensor.yaml keys and units).
struct ImuNoise {
  double gyroscope_noise_density = 0.0;      ///< sigma_g  [rad / s / sqrt(Hz)]
  double gyroscope_random_walk = 0.0;        ///< sigma_bg [rad / s^2 / sqrt(Hz)]
  double accelerometer_noise_density = 0.0;  ///< sigma_a  [m / s^2 / sqrt(Hz)]
  double accelerometer_random_walk = 0.0;    ///< sigma_ba [m / s^3 / sqrt(Hz)]
  Vec3 gyro_bias0 = Vec3::Zero();            ///< b_g[0] [rad/s]
  Vec3 accel_bias0 = Vec3::Zero();           ///< b_a[0] [m/s^2]

  /// The EuRoC MAV dataset's ADIS16448 values (mav0/imu0/sensor.yaml; also OpenVINS' simulator
  /// defaults): 1.6968e-4, 1.9393e-5, 2.0e-3, 3.0e-3.
  static ImuNoise euroc();
  static ImuNoise none() { return {}; }
  bool isZero() const;
  std::string toString() const;
};

/// A measurement in the IMU frame at IMU time t_ns.
struct ImuSample {
  TimeNs t_ns = 0;
  Vec3 gyro = Vec3::Zero();   ///< rad/s
  Vec3 accel = Vec3::Zero();  ///< m/s^2
};

/// The true biases added to sample k (the ground truth next to the noisy stream).
struct ImuBias {
  Vec3 gyro = Vec3::Zero();   ///< rad/s
  Vec3 accel = Vec3::Zero();  ///< m/s^2
};

struct ImuOptions {
  double rate_hz = 800.0;             ///< any rate > 0; sample k at t0 + round(k * 1e9 / rate)
  Pose T_cam_imu;                     ///< IMU -> camera; identity: IMU frame = camera frame
  double time_offset_s = 0.0;         ///< t_imu = t_cam + offset (Kalibr timeshift_cam_imu)
  Vec3 gravity_world{0.0, 0.0, -9.81};  ///< m/s^2
  ImuNoise noise = ImuNoise::euroc();
  uint64_t seed = 0;
  /// Throws InputError(source, "--rate" / "--time-offset" / noise key, ...) for a rate <= 0 or
  /// not finite, a non-finite offset, a negative or non-finite noise value.
  void validate(const std::string& source = "") const;
};

/// The ideal and noisy streams of one run, one entry per sample in each.
struct ImuSequence {
  std::vector<ImuSample> ideal;     ///< noise-free ground truth
  std::vector<ImuSample> measured;  ///< ideal + bias + white noise (== ideal for no noise)
  std::vector<ImuBias> bias;        ///< b[k] used in measured[k]
};

/// Word `a` of the IMU's CounterRng counter (keeps IMU draws apart from other sensors).
constexpr uint32_t kImuRngTag = 0x494d55;  // "IMU"

/// Ideal measurement of `spline_world_imu` at spline time t_ns (frac_ns: sub-ns offset).
ImuSample idealImuAt(const PoseSpline& spline_world_imu, TimeNs t_ns, const Vec3& gravity_world,
                     double frac_ns = 0.0);

/// IMU stamps covering the spline: from startNs + offset while the matching spline time is
/// <= endNs. Sample k is at start + round(k * 1e9 / rate_hz) (no drift at any rate).
std::vector<TimeNs> imuStamps(const PoseSpline& spline, const ImuOptions& opt);

/// Ideal samples at imuStamps (spline time = stamp - time offset).
std::vector<ImuSample> sampleIdealImu(const PoseSpline& spline_world_imu, const ImuOptions& opt);

/// Adds white noise and the bias random walk of `noise` at rate_hz (see the header comment).
void addImuNoise(const std::vector<ImuSample>& ideal, const ImuNoise& noise, double rate_hz,
                 uint64_t seed, std::vector<ImuSample>& measured, std::vector<ImuBias>& bias);

/// Camera trajectory -> IMU poses -> spline -> ideal and noisy streams. `spline_out` and
/// `report` (optional) receive the fitted spline of T_world_imu and its fit report. Throws
/// InputError as ImuOptions::validate and PoseSpline::fit.
ImuSequence simulateImu(const Trajectory& traj_world_camera, const ImuOptions& opt,
                        const SplineFitOptions& fit = {}, PoseSpline* spline_out = nullptr,
                        SplineFitReport* report = nullptr, const std::string& source = "");

}  // namespace inet
