#include "sensors/imu.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

TimeNs secondsToNs(double s) { return static_cast<TimeNs>(std::llround(s * 1e9)); }

}  // namespace

ImuNoise ImuNoise::euroc() {
  ImuNoise n;
  n.gyroscope_noise_density = 1.6968e-04;
  n.gyroscope_random_walk = 1.9393e-05;
  n.accelerometer_noise_density = 2.0000e-3;
  n.accelerometer_random_walk = 3.0000e-3;
  return n;
}

bool ImuNoise::isZero() const {
  return gyroscope_noise_density == 0 && gyroscope_random_walk == 0 &&
         accelerometer_noise_density == 0 && accelerometer_random_walk == 0 &&
         gyro_bias0.isZero(0) && accel_bias0.isZero(0);
}

std::string ImuNoise::toString() const {
  return fmt::format(
      "ImuNoise[gyro {:.4e} rad/s/sqrt(Hz), rw {:.4e} rad/s^2/sqrt(Hz); accel {:.4e} "
      "m/s^2/sqrt(Hz), rw {:.4e} m/s^3/sqrt(Hz); b_g0 ({}, {}, {}), b_a0 ({}, {}, {})]",
      gyroscope_noise_density, gyroscope_random_walk, accelerometer_noise_density,
      accelerometer_random_walk, gyro_bias0.x(), gyro_bias0.y(), gyro_bias0.z(), accel_bias0.x(),
      accel_bias0.y(), accel_bias0.z());
}

void ImuOptions::validate(const std::string& source) const {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0)
    throw InputError(source, "--rate", fmt::format("must be a rate > 0 Hz, got {}", rate_hz));
  if (rate_hz > 1e6)
    throw InputError(source, "--rate", fmt::format("{} Hz is above 1 MHz", rate_hz));
  if (!std::isfinite(time_offset_s) || std::abs(time_offset_s) > 1e6)
    throw InputError(source, "--time-offset", "must be a finite number of seconds");
  const std::pair<const char*, double> values[] = {
      {"gyroscope_noise_density", noise.gyroscope_noise_density},
      {"gyroscope_random_walk", noise.gyroscope_random_walk},
      {"accelerometer_noise_density", noise.accelerometer_noise_density},
      {"accelerometer_random_walk", noise.accelerometer_random_walk}};
  for (const auto& [key, v] : values)
    if (!std::isfinite(v) || v < 0.0)
      throw InputError(source, key, fmt::format("must be a finite value >= 0, got {}", v));
  if (!noise.gyro_bias0.allFinite() || !noise.accel_bias0.allFinite())
    throw InputError(source, "initial bias", "must be finite");
  if (!gravity_world.allFinite()) throw InputError(source, "gravity", "must be finite");
}

ImuSample idealImuAt(const PoseSpline& spline_world_imu, TimeNs t_ns, const Vec3& gravity_world,
                     double frac_ns) {
  const SplineState s = spline_world_imu.evaluate(t_ns, frac_ns);
  ImuSample m;
  m.t_ns = t_ns;
  m.gyro = s.w_body;
  m.accel = s.q_world_body.conjugate() * (s.a_world - gravity_world);
  return m;
}

std::vector<TimeNs> imuStamps(const PoseSpline& spline, const ImuOptions& opt) {
  const TimeNs offset = secondsToNs(opt.time_offset_s);
  const TimeNs first = spline.startNs() + offset;
  const TimeNs last = spline.endNs() + offset;
  const double period_ns = 1e9 / opt.rate_hz;
  std::vector<TimeNs> stamps;
  stamps.reserve(static_cast<size_t>(static_cast<double>(last - first) / period_ns) + 2);
  for (int64_t k = 0;; ++k) {
    const TimeNs t = first + static_cast<TimeNs>(std::llround(static_cast<double>(k) * period_ns));
    if (t > last) break;
    stamps.push_back(t);
  }
  return stamps;
}

std::vector<ImuSample> sampleIdealImu(const PoseSpline& spline_world_imu, const ImuOptions& opt) {
  const TimeNs offset = secondsToNs(opt.time_offset_s);
  const std::vector<TimeNs> stamps = imuStamps(spline_world_imu, opt);
  std::vector<ImuSample> out(stamps.size());
  for (size_t k = 0; k < stamps.size(); ++k) {
    out[k] = idealImuAt(spline_world_imu, stamps[k] - offset, opt.gravity_world);
    out[k].t_ns = stamps[k];
  }
  return out;
}

void addImuNoise(const std::vector<ImuSample>& ideal, const ImuNoise& noise, double rate_hz,
                 uint64_t seed, std::vector<ImuSample>& measured, std::vector<ImuBias>& bias) {
  INET_CHECK(rate_hz > 0.0);
  const double dt = 1.0 / rate_hz;
  const double sg = noise.gyroscope_noise_density / std::sqrt(dt);
  const double sa = noise.accelerometer_noise_density / std::sqrt(dt);
  const double sbg = noise.gyroscope_random_walk * std::sqrt(dt);
  const double sba = noise.accelerometer_random_walk * std::sqrt(dt);
  measured.resize(ideal.size());
  bias.resize(ideal.size());
  ImuBias b{noise.gyro_bias0, noise.accel_bias0};
  for (size_t k = 0; k < ideal.size(); ++k) {
    // 12 normals per sample: white gyro, white accel, gyro bias step, accel bias step
    CounterRng rng(seed, RngStream::Sensor, kImuRngTag, static_cast<uint32_t>(k),
                   static_cast<uint32_t>(static_cast<uint64_t>(k) >> 32));
    double n[12];
    for (int j = 0; j < 12; j += 2) rng.normalPair(n[j], n[j + 1]);
    const Vec3 wg(n[0], n[1], n[2]), wa(n[3], n[4], n[5]);
    const Vec3 ng(n[6], n[7], n[8]), na(n[9], n[10], n[11]);
    measured[k].t_ns = ideal[k].t_ns;
    measured[k].gyro = ideal[k].gyro + b.gyro + sg * wg;
    measured[k].accel = ideal[k].accel + b.accel + sa * wa;
    bias[k] = b;
    b.gyro += sbg * ng;
    b.accel += sba * na;
  }
}

ImuSequence simulateImu(const Trajectory& traj_world_camera, const ImuOptions& opt,
                        const SplineFitOptions& fit, PoseSpline* spline_out,
                        SplineFitReport* report, const std::string& source) {
  opt.validate(source);
  Trajectory traj_world_imu = traj_world_camera;
  for (TimedPose& p : traj_world_imu.poses) p.T_world_camera = p.T_world_camera * opt.T_cam_imu;
  const PoseSpline spline = PoseSpline::fit(traj_world_imu, fit, report, source);
  ImuSequence seq;
  seq.ideal = sampleIdealImu(spline, opt);
  addImuNoise(seq.ideal, opt.noise, opt.rate_hz, opt.seed, seq.measured, seq.bias);
  if (spline_out) *spline_out = spline;
  return seq;
}

}  // namespace inet
