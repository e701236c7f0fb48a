// interiornet imu: an IMU stream (EuRoC imu0/) from any camera trajectory file, through the
// cubic B-spline of sensors/bspline.h; the work is sensors/imu_job.h, this file only parses.
#include <memory>

#include <fmt/format.h>

#include "common.h"
#include "core/error.h"
#include "dataset/sequence_writer.h"
#include "sensors/imu_io.h"
#include "sensors/imu_job.h"

namespace inet::app {
namespace {

struct ImuArgs {
  std::string trajectory, out, noise = "euroc", extrinsics;
  double rate_hz = 800.0;
  double time_offset_s = 0.0;
  double knot_spacing_s = 0.0;
  uint64_t seed = 0;
};

void runImu(const ImuArgs& a) {
  if (a.out.empty()) throw InputError("", "--out", "an output folder is needed");
  ImuJob job;
  job.trajectory = a.trajectory;
  job.imu.rate_hz = a.rate_hz;
  job.imu.time_offset_s = a.time_offset_s;
  job.imu.seed = a.seed;
  job.imu.noise = imuNoiseFromArg(a.noise, "--noise");
  if (!a.extrinsics.empty()) job.imu.T_cam_imu = parseExtrinsicsArg(a.extrinsics, "--extrinsics");
  if (!(a.knot_spacing_s >= 0.0) || a.knot_spacing_s > 10.0)
    throw InputError("", "--knot-spacing", "must be in [0, 10] s (0 = automatic)");
  job.fit.knot_spacing_ns = static_cast<TimeNs>(a.knot_spacing_s * 1e9 + 0.5);
  const ImuJobResult r = runImuJob(job);
  writeImuFolder(a.out, r.seq, job.imu, r.comment);
  warnTrajectoryRead(a.trajectory, r.read);
  fmt::print("{}\n", r.fit.toString());
  fmt::print("wrote {} samples ({:.3f} s at {} Hz, {}) to {}/imu0/\n", r.samples,
             static_cast<double>(r.last_ns - r.first_ns) * 1e-9, a.rate_hz,
             job.imu.noise.isZero() ? "noise-free" : "noisy + noise-free + biases", a.out);
}

}  // namespace

void registerImu(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "imu",
      "Simulate an IMU along a camera trajectory (TUM, EuRoC, ... auto-detected): cubic "
      "B-spline (R3 x cumulative SO(3)) fitted to the poses by least squares (exact for constant "
      "acceleration and turn rate, docs/sensors.md), gyro and accelerometer at any rate, "
      "Kalibr noise model; writes OUT/imu0/{data.csv (EuRoC), data_noise_free.csv, biases.csv, "
      "sensor.yaml}");
  auto a = std::make_shared<ImuArgs>();
  cmd->add_option("--trajectory", a->trajectory, "camera trajectory file (T_world_camera)")
      ->required();
  cmd->add_option("--rate", a->rate_hz, "IMU rate in Hz (default 800)");
  cmd->add_option("--noise", a->noise,
                  "none | euroc (ADIS16448 of the EuRoC MAV dataset, default) | a Kalibr/EuRoC "
                  "imu yaml with the four noise densities");
  cmd->add_option("--seed", a->seed, "seed of the noise (default 0)");
  cmd->add_option("--extrinsics", a->extrinsics,
                  "T_cam_imu (IMU -> camera): 16 numbers row-major, or a yaml with T_cam_imu "
                  "(Kalibr camchain) or T_BS (EuRoC camera sensor.yaml, inverted); default: "
                  "identity, the IMU frame is the camera frame");
  cmd->add_option("--time-offset", a->time_offset_s,
                  "t_imu = t_cam + offset, seconds (Kalibr's timeshift_cam_imu; default 0)");
  cmd->add_option("--knot-spacing", a->knot_spacing_s,
                  "spline knot spacing in s; default 0 = the input's mean spacing but at least "
                  "0.05 s (smooths motion-capture noise; give the pose spacing, e.g. 0.005 for "
                  "200 Hz noise-free poses, to pass exactly through every pose)");
  cmd->add_option("--out", a->out, "output folder (imu0/ is written inside)")->required();
  cmd->callback([a] { runImu(*a); });
}

}  // namespace inet::app
