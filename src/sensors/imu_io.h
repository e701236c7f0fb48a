#pragma once
// IMU files: the texts of EuRoC/ASL `imu0/` (written by dataset/sequence_writer.h) and the
// Kalibr/EuRoC yaml inputs.
//
// Output folder:
//   imu0/data.csv             measured (noisy) stream, EuRoC header and units (rad/s, m/s^2),
//                             comma separated without spaces, stamps in IMU time (int64 ns)
//   imu0/data_noise_free.csv  the ideal stream, same layout (ground truth)
//   imu0/biases.csv           b_g, b_a actually added to each measured row
//                             (`#timestamp [ns],b_w_RS_S_x [rad s^-1],...,b_a_RS_S_z [m s^-2]`,
//                             the bias column names of EuRoC's state_groundtruth_estimate0)
//   imu0/sensor.yaml          EuRoC layout: sensor_type imu, T_BS, rate_hz, the four noise
//                             densities; plus the time offset, gravity and seed used. Body B =
//                             cam0 (as in dataset/asl_writer), so T_BS = T_cam_imu.
// Numbers are written in the shortest form that reads back to the same double (lossless).
//
// Yaml inputs are read by a small line parser rather than yaml-cpp: the files are flat `key:
// value` lines (Kalibr imu.yaml, EuRoC sensor.yaml) plus one 4x4 matrix, the project has no
// yaml dependency, and a hand parser can name the file, line and key in every error (what
// yaml-cpp's exceptions give only partly). Flow-style lists may span lines (EuRoC's T_BS data).
#include <filesystem>
#include <string>
#include <vector>

#include "sensors/imu.h"

namespace inet {

extern const char* const kEurocImuCsvHeader;
extern const char* const kImuBiasCsvHeader;

/// Kalibr / EuRoC imu yaml: the four noise keys are required; rate_hz, update_rate, rostopic,
/// sensor_type, comment, T_BS and time_offset-style keys that other tools write are accepted and
/// ignored. Throws InputError(path, key, "line N: ...") for a malformed line, a non-number, a
/// negative value, a missing noise key, or an unknown key (the message lists the known ones).
ImuNoise readImuNoiseYaml(const std::string& path);
ImuNoise parseImuNoiseYaml(const std::string& text, const std::string& path);

/// "none", "euroc" or a yaml path (readImuNoiseYaml). `field` names the option in errors.
ImuNoise imuNoiseFromArg(const std::string& arg, const std::string& field = "--noise");

/// T_cam_imu from 16 numbers (row-major 4x4, separated by commas and/or spaces) or from a yaml
/// file with `T_cam_imu:` (Kalibr camchain, list of 4 rows or {data: [16]}) or, as the inverse,
/// `T_BS:` of an EuRoC camera sensor.yaml (camera -> IMU body). Throws InputError(source,
/// field, ...) when the numbers are not 16, the last row is not 0 0 0 1, or the rotation is not
/// orthonormal within 1e-6 (then re-orthonormalised exactly).
Pose parseExtrinsicsArg(const std::string& arg, const std::string& field = "--extrinsics");
Pose poseFromRowMajor16(const std::vector<double>& m, const std::string& source,
                        const std::string& field);

std::string formatImuCsv(const std::vector<ImuSample>& samples);
std::string formatImuBiasCsv(const std::vector<ImuSample>& samples,
                             const std::vector<ImuBias>& bias);
std::string formatImuSensorYaml(const ImuOptions& opt, const std::string& comment);
/// Parses an EuRoC imu data.csv (header line optional, '#' lines skipped); InputError naming
/// the file and line for a wrong column count or a non-number.
std::vector<ImuSample> parseImuCsv(const std::string& text, const std::string& path);

}  // namespace inet
