#pragma once
// `interiornet imu` as a library call, so the command line stays a thin option parser and the
// tests can drive every input path: read a trajectory file (any format readTrajectory
// detects), fit the spline, simulate. The caller writes imu0/ (dataset/sequence_writer.h
// writeImuFolder).
#include <string>

#include "sensors/imu.h"

namespace inet {

struct ImuJob {
  std::string trajectory;  ///< TUM / EuRoC / ... trajectory of the camera (T_world_camera)
  ImuOptions imu;
  SplineFitOptions fit;
};

struct ImuJobResult {
  TrajectoryReadReport read;  ///< what the reader did about the file (repeated stamps)
  SplineFitReport fit;
  size_t samples = 0;
  TimeNs first_ns = 0, last_ns = 0;
  ImuSequence seq;      ///< the simulated streams
  std::string comment;  ///< for imu0/sensor.yaml: the spline and the noise model
};

/// Validates everything first (InputError(source, field, ...): "--rate", the noise keys), then
/// reads the trajectory (InputError naming the file and line), fits and simulates.
ImuJobResult runImuJob(const ImuJob& job);

}  // namespace inet
