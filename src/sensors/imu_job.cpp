#include "sensors/imu_job.h"

#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "sensors/imu_io.h"
#include "trajectory/formats.h"

namespace inet {

ImuJobResult runImuJob(const ImuJob& job) {
  job.imu.validate();
  if (job.fit.knot_spacing_ns < 0) throw InputError("", "--knot-spacing", "must be >= 0");
  ImuJobResult res;
  const Trajectory traj = readTrajectory(job.trajectory, {}, {}, &res.read);
  res.seq = simulateImu(traj, job.imu, job.fit, nullptr, &res.fit, job.trajectory);
  const ImuSequence& seq = res.seq;
  res.comment = fmt::format(
      "interiornet IMU from the cubic B-spline (R3 x cumulative SO(3), {:.6f} s knots) of {}; "
      "{}",
      static_cast<double>(res.fit.knot_spacing_ns) * 1e-9,
      std::filesystem::path(job.trajectory).filename().string(),
      job.imu.noise.isZero() ? "noise-free" : "Kalibr discrete noise model");
  res.samples = seq.measured.size();
  if (!seq.measured.empty()) {
    res.first_ns = seq.measured.front().t_ns;
    res.last_ns = seq.measured.back().t_ns;
  }
  return res;
}

}  // namespace inet
