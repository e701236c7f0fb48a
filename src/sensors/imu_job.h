#pragma once
// `interiornet imu` as a library call, so the command line stays a thin option parser and the
// tests can drive every input path: read a trajectory file (any format readTrajectory
// detects), fit the spline, simulate, write imu0/.
#include <string>

#include "sensors/imu.h"

namespace inet {

struct ImuJob {
  std::string trajectory;  ///< TUM / EuRoC / ... trajectory of the camera (T_world_camera)
  std::string out;         ///< output folder; imu0/ is written inside
  ImuOptions imu;
  SplineFitOptions fit;
};

struct ImuJobResult {
  TrajectoryReadReport read;  ///< what the reader did about the file (repeated stamps)
  SplineFitReport fit;
  size_t samples = 0;
  TimeNs first_ns = 0, last_ns = 0;
};

/// Validates everything first (InputError(source, field, ...): "--rate", "--out", the noise
/// keys), then reads the trajectory (InputError naming the file and line), fits, simulates and
/// writes `out`/imu0/ atomically (imu_io.h).
ImuJobResult runImuJob(const ImuJob& job);

}  // namespace inet
