#include "sensors/imu_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "imu_integration.h"
#include "motion.h"
#include "sensors/imu_job.h"
#include "sensors/so3.h"
#include "trajectory/formats.h"

namespace inet {
namespace {

const std::string kHeader =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m "
    "s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]";

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

using test::expectInputError;

TEST(ImuIo, CsvHeaderIsEuRoCsAndRowsReadBackExactly) {
  const Trajectory traj = test::analyticTrajectory(50'000'000, 21);
  const ImuSequence seq = simulateImu(traj, ImuOptions{});
  const std::string csv = formatImuCsv(seq.measured);
  EXPECT_EQ(firstLine(csv), kHeader);
  EXPECT_EQ(std::string(kEurocImuCsvHeader), kHeader);
  const std::string shared = test::sharedDir();
  if (!shared.empty()) {  // the real file, byte for byte
    EXPECT_EQ(firstLine(readTextFile(shared + "/data/formats/euroc_asl/mav0/imu0/data.csv")),
              kHeader);
  }
  EXPECT_EQ(csv.find(' ', csv.find('\n')), std::string::npos);  // no spaces in the rows
  const std::vector<ImuSample> back = parseImuCsv(csv, "data.csv");
  ASSERT_EQ(back.size(), seq.measured.size());
  for (size_t k = 0; k < back.size(); ++k) {
    EXPECT_EQ(back[k].t_ns, seq.measured[k].t_ns);
    EXPECT_EQ(back[k].gyro, seq.measured[k].gyro);  // shortest round-trip text: lossless
    EXPECT_EQ(back[k].accel, seq.measured[k].accel);
  }
  const InputError e = expectInputError([] { parseImuCsv(kHeader + "\n1,2,3\n", "x.csv"); });
  EXPECT_EQ(e.file(), "x.csv");
  EXPECT_EQ(e.field(), "line 2");
}

TEST(ImuIo, EuRoCSampleFilesParse) {
  const std::string shared = test::sharedDir();
  if (shared.empty()) GTEST_SKIP() << "no ../shared/data: the EuRoC sample files are there";
  const std::string dir = shared + "/data/formats/euroc_asl/mav0/";
  const ImuNoise n = readImuNoiseYaml(dir + "imu0/sensor.yaml");
  const ImuNoise e = ImuNoise::euroc();
  EXPECT_EQ(n.gyroscope_noise_density, e.gyroscope_noise_density);
  EXPECT_EQ(n.gyroscope_random_walk, e.gyroscope_random_walk);
  EXPECT_EQ(n.accelerometer_noise_density, e.accelerometer_noise_density);
  EXPECT_EQ(n.accelerometer_random_walk, e.accelerometer_random_walk);
  // real EuRoC rows: |a| ~ 9.8 on the (nearly static) start of the sequence
  const std::vector<ImuSample> rows =
      parseImuCsv(readTextFile(dir + "imu0/data.csv"), dir + "imu0/data.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows[0].accel.norm(), 9.8, 0.3);
  // the camera's T_BS is camera -> IMU body; T_cam_imu is its inverse
  const Pose T_cam_imu = parseExtrinsicsArg(dir + "cam0/sensor.yaml");
  const Pose T_BS = T_cam_imu.inverse();
  EXPECT_NEAR(T_BS.t.x(), -0.0216401454975, 1e-12);
  EXPECT_NEAR(T_BS.rotation()(1, 0), 0.999557249008, 1e-6);
}

TEST(ImuIo, KalibrYamlsParse) {
  test::TempDir dir("imu_yaml");
  const std::string kalibr = dir.write("imu.yaml",
                                       "#Accelerometers\n"
                                       "accelerometer_noise_density: 1.86e-03   #Noise density\n"
                                       "accelerometer_random_walk:   4.33e-04\n"
                                       "#Gyroscopes\n"
                                       "gyroscope_noise_density:     1.87e-04\n"
                                       "gyroscope_random_walk:       2.66e-05\n"
                                       "rostopic:                    /imu0\n"
                                       "update_rate:                 200.0  #Hz\n");
  const ImuNoise n = readImuNoiseYaml(kalibr);
  EXPECT_EQ(n.accelerometer_noise_density, 1.86e-3);
  EXPECT_EQ(n.gyroscope_random_walk, 2.66e-5);
  // Kalibr's result file nests the values under imu0 with a T_i_b block
  const std::string nested = dir.write("result.yaml",
                                       "imu0:\n  T_i_b:\n  - [1.0, 0.0, 0.0, 0.0]\n"
                                       "  - [0.0, 1.0, 0.0, 0.0]\n  - [0.0, 0.0, 1.0, 0.0]\n"
                                       "  - [0.0, 0.0, 0.0, 1.0]\n"
                                       "  accelerometer_noise_density: 0.01\n"
                                       "  accelerometer_random_walk: 0.0002\n"
                                       "  gyroscope_noise_density: 0.005\n"
                                       "  gyroscope_random_walk: 4.0e-06\n"
                                       "  model: calibrated\n  rostopic: /imu0\n"
                                       "  time_offset: 0.0\n  update_rate: 200.0\n");
  EXPECT_EQ(readImuNoiseYaml(nested).gyroscope_noise_density, 0.005);
  // a camchain gives the extrinsics
  const std::string camchain = dir.write(
      "camchain.yaml",
      "cam0:\n  T_cam_imu:\n  - [0.0, -1.0, 0.0, 0.1]\n  - [1.0, 0.0, 0.0, 0.2]\n"
      "  - [0.0, 0.0, 1.0, 0.3]\n  - [0.0, 0.0, 0.0, 1.0]\n  camera_model: pinhole\n");
  const Pose T = parseExtrinsicsArg(camchain);
  EXPECT_LT((T.t - Vec3(0.1, 0.2, 0.3)).norm(), 1e-15);
  EXPECT_LT((T.q * Vec3::UnitX() - Vec3::UnitY()).norm(), 1e-15);
  // and so do 16 numbers on the command line
  const Pose T2 = parseExtrinsicsArg("0 -1 0 0.1, 1 0 0 0.2, 0 0 1 0.3, 0 0 0 1");
  EXPECT_LT((T2.matrix() - T.matrix()).norm(), 1e-15);
}

TEST(ImuIo, BadYamlAndExtrinsicsNameFileAndField) {
  test::TempDir dir("imu_yaml_bad");
  const std::string good =
      "gyroscope_noise_density: 1e-4\ngyroscope_random_walk: 1e-5\n"
      "accelerometer_noise_density: 1e-3\naccelerometer_random_walk: 1e-3\n";
  InputError e = expectInputError([&] {
    readImuNoiseYaml(dir.write("a.yaml", "gyroscope_noise_density: 1e-4x\n"));
  });
  EXPECT_NE(e.file().find("a.yaml"), std::string::npos);
  EXPECT_EQ(e.field(), "gyroscope_noise_density");
  EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos);
  e = expectInputError([&] { readImuNoiseYaml(dir.write("b.yaml", "rate_hz: 200\n")); });
  EXPECT_EQ(e.field(), "accelerometer_noise_density");  // the first missing one
  e = expectInputError([&] { readImuNoiseYaml(dir.write("c.yaml", good + "gyro_noise: 1\n")); });
  EXPECT_EQ(e.field(), "gyro_noise");
  EXPECT_NE(std::string(e.what()).find("known: "), std::string::npos);
  e = expectInputError([&] { readImuNoiseYaml(dir.write("d.yaml", good + "just words\n")); });
  EXPECT_EQ(e.field(), "line 5");
  e = expectInputError([&] {
    readImuNoiseYaml(dir.write("e.yaml", good + "gyroscope_random_walk: 2e-5\n"));
  });
  EXPECT_NE(std::string(e.what()).find("given twice"), std::string::npos);
  e = expectInputError([&] {
    readImuNoiseYaml(dir.write("f.yaml", "accelerometer_random_walk: -1\n"));
  });
  EXPECT_EQ(e.field(), "accelerometer_random_walk");
  e = expectInputError([&] { readImuNoiseYaml((dir / "missing.yaml").string()); });
  EXPECT_NE(e.file().find("missing.yaml"), std::string::npos);
  e = expectInputError([] { imuNoiseFromArg("eurocc"); });
  EXPECT_EQ(e.field(), "--noise");
  e = expectInputError([] { parseExtrinsicsArg("1 0 0 0 0 1 0 0 0 0 1 0 0 0 0"); });
  EXPECT_EQ(e.field(), "--extrinsics");
  e = expectInputError([] { parseExtrinsicsArg("1 0 0 0 0 2 0 0 0 0 1 0 0 0 0 1"); });
  EXPECT_NE(std::string(e.what()).find("orthonormal"), std::string::npos);
  e = expectInputError([&] { parseExtrinsicsArg(dir.write("g.yaml", "T_cam_imu: [1, 2]\n")); });
  EXPECT_NE(e.file().find("g.yaml"), std::string::npos);
  EXPECT_EQ(e.field(), "T_cam_imu");
}

// imu0/ itself is written by dataset/sequence_writer.h (tests/dataset/sequence_writer_test.cpp);
// here its texts.
TEST(ImuIo, TextsHoldEverythingAndTheYamlReadsBack) {
  ImuOptions opt;
  opt.noise.gyro_bias0 = Vec3(0.001, 0.002, -0.003);
  opt.T_cam_imu = Pose{so3::expQuat(Vec3(0.1, 0.2, 0.3)), Vec3(0.01, -0.02, 0.03)};
  opt.seed = 9;
  const ImuSequence seq = simulateImu(test::analyticTrajectory(50'000'000, 21), opt);
  const ImuNoise n = parseImuNoiseYaml(formatImuSensorYaml(opt, "test"), "sensor.yaml");
  EXPECT_EQ(n.gyroscope_noise_density, opt.noise.gyroscope_noise_density);
  EXPECT_EQ(n.accelerometer_random_walk, opt.noise.accelerometer_random_walk);
  EXPECT_EQ(n.gyro_bias0, opt.noise.gyro_bias0);
  // noisy = noise-free + bias + white noise, row by row from the files alone
  const auto noisy = parseImuCsv(formatImuCsv(seq.measured), "data.csv");
  const auto clean = parseImuCsv(formatImuCsv(seq.ideal), "nf.csv");
  const std::string bias_text = formatImuBiasCsv(seq.measured, seq.bias);
  EXPECT_EQ(firstLine(bias_text), kImuBiasCsvHeader);
  const auto bias = parseImuCsv(bias_text, "biases.csv");  // same 7-column layout
  ASSERT_EQ(noisy.size(), clean.size());
  ASSERT_EQ(noisy.size(), bias.size());
  double sum = 0;
  for (size_t k = 0; k < noisy.size(); ++k)
    sum += (noisy[k].gyro - clean[k].gyro - bias[k].gyro).squaredNorm();
  const double white = std::sqrt(sum / (3.0 * static_cast<double>(noisy.size())));
  EXPECT_NEAR(white / (opt.noise.gyroscope_noise_density * std::sqrt(800.0)), 1.0, 0.05);
}

TEST(ImuJob, BadInputNamesFileAndField) {
  test::TempDir dir("imu_job_bad");
  ImuJob job;
  job.trajectory = (dir / "nope.txt").string();
  InputError e = expectInputError([&] { runImuJob(job); });
  EXPECT_NE(e.file().find("nope.txt"), std::string::npos);
  job.trajectory = dir.write("bad.txt", "0.0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n");
  e = expectInputError([&] { runImuJob(job); });
  EXPECT_NE(e.file().find("bad.txt"), std::string::npos);
  EXPECT_NE(std::string(e.what()).find("2"), std::string::npos);  // the line
  job.imu.rate_hz = 0;
  e = expectInputError([&] { runImuJob(job); });
  EXPECT_EQ(e.field(), "--rate");
}

TEST(ImuJob, RealTumTrajectory) {
  const std::string shared = test::sharedDir();
  if (shared.empty()) GTEST_SKIP() << "no ../shared/data: the TUM fr1_xyz run needs it";
  ImuJob job;
  job.trajectory = shared + "/data/trajectories/tum_rgbd_fr1_xyz_groundtruth.txt";
  job.imu.seed = 1;
  const ImuJobResult res = runImuJob(job);
  std::printf("fr1_xyz: %zu samples, %s\n", res.samples, res.fit.toString().c_str());
  const auto clean = parseImuCsv(formatImuCsv(res.seq.ideal), "data_noise_free.csv");
  ASSERT_EQ(clean.size(), res.samples);
  EXPECT_GT(res.samples, 800u * 29);
  EXPECT_EQ(clean[1].t_ns - clean[0].t_ns, 1'250'000);
  // hand-held near-static shaking: the specific force is gravity give or take the motion
  double mean_a = 0, max_w = 0;
  for (const ImuSample& m : clean) {
    mean_a += m.accel.norm() / static_cast<double>(clean.size());
    max_w = std::max(max_w, m.gyro.norm());
  }
  std::printf("fr1_xyz: mean |a| %.3f m/s^2, max |w| %.3f rad/s\n", mean_a, max_w);
  EXPECT_NEAR(mean_a, 9.81, 0.3);
  EXPECT_LT(max_w, 3.0);
  // dead reckoning over the first 10 s against the spline
  const Trajectory traj = readTrajectory(job.trajectory);
  ImuOptions opt;
  opt.noise = ImuNoise::none();
  PoseSpline spline(0, 1, std::vector<Vec3>(4), std::vector<Quat>(4, Quat::Identity()));
  const ImuSequence seq = simulateImu(traj, opt, {}, &spline);
  const SplineState s0 = spline.evaluate(seq.ideal[0].t_ns);
  test::InertialState x{s0.q_world_body, s0.v_world, s0.p_world};
  x = test::integrateRk4(seq.ideal, 0, 8000, x, opt.gravity_world);
  const SplineState s1 = spline.evaluate(seq.ideal[8000].t_ns);
  std::printf("fr1_xyz RK4 10 s drift: %.3e m, %.3e deg\n", (x.p - s1.p_world).norm(),
              so3::angleBetween(x.q, s1.q_world_body) * 180 / M_PI);
  EXPECT_LT((x.p - s1.p_world).norm(), 1e-3);
  EXPECT_LT(so3::angleBetween(x.q, s1.q_world_body) * 180 / M_PI, 0.01);
}

}  // namespace
}  // namespace inet
