#include "sensors/imu.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../temp_dir.h"
#include "core/error.h"
#include "imu_integration.h"
#include "motion.h"
#include "procedural/apartment.h"
#include "sensors/imu_io.h"
#include "sensors/so3.h"
#include "trajectory/free_space.h"
#include "trajectory/random_trajectory.h"

namespace inet {
namespace {

const Vec3 kGravity(0, 0, -9.81);

ImuOptions noiseFree(double rate = 800.0) {
  ImuOptions o;
  o.rate_hz = rate;
  o.noise = ImuNoise::none();
  return o;
}

Trajectory staticTrajectory(const Pose& T, double seconds) {
  Trajectory traj;
  traj.poses.push_back({0, T});
  traj.poses.push_back({static_cast<TimeNs>(seconds * 1e9), T});
  return traj;
}

TEST(Imu, StaticCameraMeasuresSpecificForceUp) {
  const Pose T{Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized())), Vec3(1, 2, 1.5)};
  const ImuSequence seq = simulateImu(staticTrajectory(T, 1.0), noiseFree());
  ASSERT_EQ(seq.ideal.size(), 801u);  // 0 .. 1 s inclusive at exactly 1.25 ms
  EXPECT_EQ(seq.ideal[1].t_ns - seq.ideal[0].t_ns, 1'250'000);
  EXPECT_EQ(seq.ideal.back().t_ns, 1'000'000'000);
  // expectation built from the pose directly: the specific force R^T (0, 0, +9.81)
  const Vec3 expected = T.q.conjugate() * Vec3(0, 0, 9.81);
  for (const ImuSample& m : seq.ideal) {
    EXPECT_EQ(m.gyro, Vec3::Zero());
    EXPECT_LT((m.accel - expected).norm(), 1e-12);
    EXPECT_LT((T.q * m.accel - Vec3(0, 0, 9.81)).norm(), 1e-12);  // points up in the world
  }
  // with noise "none" the measured stream is the ideal one
  for (size_t k = 0; k < seq.ideal.size(); ++k)
    EXPECT_EQ(seq.measured[k].accel, seq.ideal[k].accel);
}

TEST(Imu, GyroAndAccelMatchFiniteDifferencesOfTheSpline) {
  PoseSpline spline(0, 1, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()},
                    {Quat::Identity(), Quat::Identity(), Quat::Identity(), Quat::Identity()});
  SplineFitOptions fit;
  fit.knot_spacing_ns = 20'000'000;
  const ImuSequence seq =
      simulateImu(test::analyticTrajectory(fit.knot_spacing_ns, 201), noiseFree(), fit, &spline);
  ASSERT_EQ(seq.ideal.size(), 3201u);  // 4 s at 800 Hz
  const TimeNs h = 1'000'000;  // 1 ms; samples within h of a knot are skipped (jerk jumps)
  int checked = 0;
  for (const ImuSample& m : seq.ideal) {
    const TimeNs rel = m.t_ns % fit.knot_spacing_ns;
    if (rel <= h || fit.knot_spacing_ns - rel <= h || m.t_ns - h < spline.startNs() ||
        m.t_ns + h > spline.endNs())
      continue;
    const Pose a = spline.pose(m.t_ns - h), b = spline.pose(m.t_ns), c = spline.pose(m.t_ns + h);
    const Vec3 acc_w = (a.t - 2 * b.t + c.t) / 1e-6;
    const Vec3 accel_fd = b.q.conjugate() * (acc_w - kGravity);
    // Log(R(t-h)^T R(t+h)) / 2h, O(h^2) ~ 1e-6 * |w''|
    const Vec3 gyro_fd = so3::logQuat(a.q.conjugate() * c.q) / 2e-3;
    EXPECT_LT((m.accel - accel_fd).norm(), 1e-6) << m.t_ns;
    EXPECT_LT((m.gyro - gyro_fd).norm(), 2e-5) << m.t_ns;
    ++checked;
  }
  EXPECT_GT(checked, 2000);
}

/// 10+ s of a type-3 (look-forward) trajectory in generated apartment 3.
class LookForward : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir("imu_apartment");
    ApartmentOptions aopt;
    aopt.seed = 3;
    aopt.texture_size = 64;
    Apartment apt = makeApartment(aopt, dir_->path(), dir_->path() / "textures");
    FreeSpace space(apt.scene);
    RandomTrajectoryOptions opt;
    opt.type = MotionType::LookForward;
    opt.seed = 11;
    opt.frames = 275;  // 11 s at 25 Hz
    traj_ = new RandomTrajectory(generateRandomTrajectory(space, opt));
  }
  static void TearDownTestSuite() {
    delete traj_;
    delete dir_;
  }
  static test::TempDir* dir_;
  static RandomTrajectory* traj_;
};
test::TempDir* LookForward::dir_ = nullptr;
RandomTrajectory* LookForward::traj_ = nullptr;

TEST_F(LookForward, Rk4DeadReckoningStaysOnTheSplineFor10s) {
  for (TimeNs knots : {TimeNs{0}, TimeNs{5'000'000}}) {  // default 50 ms, and every dense pose
    SplineFitOptions fit;
    fit.knot_spacing_ns = knots;
    PoseSpline spline(0, 1, std::vector<Vec3>(4), std::vector<Quat>(4, Quat::Identity()));
    SplineFitReport rep;
    const ImuSequence seq = simulateImu(traj_->dense, noiseFree(), fit, &spline, &rep);
    ASSERT_GE(seq.ideal.size(), 8001u);
    const SplineState s0 = spline.evaluate(seq.ideal[0].t_ns);
    test::InertialState x{s0.q_world_body, s0.v_world, s0.p_world};
    x = test::integrateRk4(seq.ideal, 0, 8000, x, kGravity);
    ASSERT_EQ(seq.ideal[8000].t_ns - seq.ideal[0].t_ns, 10'000'000'000);
    const SplineState s1 = spline.evaluate(seq.ideal[8000].t_ns);
    const double dp = (x.p - s1.p_world).norm();
    const double da = so3::angleBetween(x.q, s1.q_world_body) * 180.0 / M_PI;
    const double dv = (x.v - s1.v_world).norm();
    // motion statistics so the figure means something
    double path = 0, max_w = 0, max_a = 0;
    for (size_t k = 1; k <= 8000; ++k) {
      path += (spline.pose(seq.ideal[k].t_ns).t - spline.pose(seq.ideal[k - 1].t_ns).t).norm();
      max_w = std::max(max_w, seq.ideal[k].gyro.norm());
      max_a = std::max(max_a, (seq.ideal[k].accel + s1.q_world_body.conjugate() * kGravity).norm());
    }
    std::printf("type-3, %s knots: 10 s, path %.2f m, max |w| %.2f rad/s; RK4 drift %.3e m, "
                "%.3e deg, %.3e m/s\n  %s\n",
                knots == 0 ? "50 ms" : "5 ms", path, max_w, dp, da, dv, rep.toString().c_str());
    EXPECT_GT(path, 1.0);
    EXPECT_LT(dp, 1e-3);
    EXPECT_LT(da, 0.01);
  }
}

TEST_F(LookForward, RotatedImuFrameRotatesTheMeasurements) {
  ImuOptions cam = noiseFree(), rot = noiseFree();
  const Quat q_ci(Eigen::AngleAxisd(2.0, Vec3(0.3, -1, 0.4).normalized()));
  rot.T_cam_imu = Pose{q_ci, Vec3::Zero()};
  const ImuSequence a = simulateImu(traj_->dense, cam);
  const ImuSequence b = simulateImu(traj_->dense, rot);
  ASSERT_EQ(a.ideal.size(), b.ideal.size());
  for (size_t k = 0; k < a.ideal.size(); k += 13) {
    // a vector v_cam in the camera frame is q_ci^-1 v_cam in the IMU frame
    EXPECT_LT((b.ideal[k].gyro - q_ci.conjugate() * a.ideal[k].gyro).norm(), 1e-9);
    EXPECT_LT((b.ideal[k].accel - q_ci.conjugate() * a.ideal[k].accel).norm(), 1e-8);
  }
}

TEST(Imu, LeverArmAddsTheCentripetalAcceleration) {
  // a camera turning in place about world Z at 1 rad/s; the IMU sits 0.1 m along the camera's
  // x axis (horizontal), so it circles the axis: centripetal 0.1 m/s^2 towards it (-x_imu)
  Trajectory traj;
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.01 * k;
    Mat3 base;
    base << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // columns: x_c = -Y, y_c = -Z, z_c = +X
    const Quat q = Quat(Eigen::AngleAxisd(t, Vec3::UnitZ())) * Quat(base);
    traj.poses.push_back({TimeNs{k} * 10'000'000, Pose{q, Vec3::Zero()}});
  }
  ImuOptions opt = noiseFree(400);
  opt.T_cam_imu = Pose{Quat::Identity(), Vec3(0.1, 0, 0)};
  SplineFitOptions fit;
  fit.knot_spacing_ns = 10'000'000;
  const ImuSequence seq = simulateImu(traj, opt, fit);
  for (size_t k = 400; k < 1200; k += 7) {  // away from the natural ends
    const ImuSample& m = seq.ideal[k];
    EXPECT_LT((m.gyro - Vec3(0, -1, 0)).norm(), 1e-9);  // world Z is -y of this camera
    const Vec3 up_imu(0, -9.81, 0);  // specific force of gravity: world +Z = camera -y
    EXPECT_LT((m.accel - (up_imu + Vec3(-0.1, 0, 0))).norm(), 1e-6) << k;
  }
}

TEST(Imu, TimeOffsetShiftsTheStampsOnly) {
  SplineFitOptions fit;
  fit.knot_spacing_ns = 20'000'000;
  const Trajectory traj = test::analyticTrajectory(fit.knot_spacing_ns, 101);
  ImuOptions opt = noiseFree();
  const ImuSequence a = simulateImu(traj, opt, fit);
  opt.time_offset_s = 0.01;  // t_imu = t_cam + 10 ms
  const ImuSequence b = simulateImu(traj, opt, fit);
  ASSERT_EQ(a.ideal.size(), b.ideal.size());
  for (size_t k = 0; k < a.ideal.size(); ++k) {
    // the IMU sample stamped t + 10 ms measured the motion of camera time t
    EXPECT_EQ(b.ideal[k].t_ns, a.ideal[k].t_ns + 10'000'000);
    EXPECT_EQ(b.ideal[k].gyro, a.ideal[k].gyro);
    EXPECT_EQ(b.ideal[k].accel, a.ideal[k].accel);
  }
  // an offset that is not a multiple of the period: spline time = stamp - offset
  opt.time_offset_s = -0.0031234;
  PoseSpline spline(0, 1, std::vector<Vec3>(4), std::vector<Quat>(4, Quat::Identity()));
  const ImuSequence c = simulateImu(traj, opt, fit, &spline);
  EXPECT_EQ(c.ideal.front().t_ns, -3'123'400);
  const SplineState s = spline.evaluate(c.ideal[100].t_ns + 3'123'400);
  EXPECT_LT((c.ideal[100].gyro - s.w_body).norm(), 1e-12);
}

TEST(Imu, AnyRateAndExactPeriod) {
  const Trajectory traj = staticTrajectory(Pose{}, 2.0);
  const ImuSequence a = simulateImu(traj, noiseFree(300.0));  // 3.333... ms
  ASSERT_EQ(a.ideal.size(), 601u);
  EXPECT_EQ(a.ideal[300].t_ns, 1'000'000'000);  // no drift
  EXPECT_EQ(a.ideal[1].t_ns, 3'333'333);
  EXPECT_EQ(a.ideal[2].t_ns, 6'666'667);
  EXPECT_EQ(simulateImu(traj, noiseFree(800.0)).ideal.size(), 1601u);
}

TEST(Imu, SameSeedSameBytesOtherSeedOtherBytes) {
  const Trajectory traj = test::analyticTrajectory(50'000'000, 41);
  ImuOptions opt;  // EuRoC noise
  opt.seed = 7;
  const std::string a = formatImuCsv(simulateImu(traj, opt).measured);
  const std::string b = formatImuCsv(simulateImu(traj, opt).measured);
  EXPECT_EQ(a, b);
  opt.seed = 8;
  EXPECT_NE(a, formatImuCsv(simulateImu(traj, opt).measured));
}

TEST(Imu, NoiseHasTheKalibrDiscreteStatistics) {
  // static, 60 s at 800 Hz; the residual measured - ideal - bias is the white noise, the bias
  // increments are the random walk steps
  ImuOptions opt;
  opt.noise.gyro_bias0 = Vec3(0.01, -0.02, 0.03);
  opt.noise.accel_bias0 = Vec3(-0.1, 0.2, 0.05);
  opt.seed = 3;
  const ImuSequence seq = simulateImu(staticTrajectory(Pose{}, 60.0), opt);
  const size_t n = seq.measured.size();
  ASSERT_EQ(n, 48001u);
  EXPECT_EQ(seq.bias[0].gyro, opt.noise.gyro_bias0);
  EXPECT_EQ(seq.bias[0].accel, opt.noise.accel_bias0);
  Eigen::Array<double, 6, 1> white = Eigen::Array<double, 6, 1>::Zero(), walk = white;
  for (size_t k = 0; k < n; ++k) {
    Eigen::Matrix<double, 6, 1> r;
    r << seq.measured[k].gyro - seq.ideal[k].gyro - seq.bias[k].gyro,
        seq.measured[k].accel - seq.ideal[k].accel - seq.bias[k].accel;
    white += r.array().square();
    if (k + 1 < n) {
      Eigen::Matrix<double, 6, 1> d;
      d << seq.bias[k + 1].gyro - seq.bias[k].gyro, seq.bias[k + 1].accel - seq.bias[k].accel;
      walk += d.array().square();
    }
  }
  white = (white / static_cast<double>(n)).sqrt();
  walk = (walk / static_cast<double>(n - 1)).sqrt();
  const ImuNoise e = ImuNoise::euroc();
  for (int j = 0; j < 6; ++j) {
    // sigma_d = sigma_c * sqrt(800) and sigma_b / sqrt(800) (SENSORS.md table); +-2 % is
    // about 6 standard errors of a 48000-sample std
    const double w = (j < 3 ? e.gyroscope_noise_density : e.accelerometer_noise_density) *
                     std::sqrt(800.0);
    const double b = (j < 3 ? e.gyroscope_random_walk : e.accelerometer_random_walk) /
                     std::sqrt(800.0);
    EXPECT_NEAR(white[j] / w, 1.0, 0.02) << j;
    EXPECT_NEAR(walk[j] / b, 1.0, 0.02) << j;
  }
  EXPECT_NEAR(e.gyroscope_noise_density * std::sqrt(800.0), 4.7993e-3, 1e-7);
}

TEST(Imu, BadOptionsAreInputErrors) {
  const Trajectory traj = staticTrajectory(Pose{}, 1.0);
  ImuOptions opt;
  opt.rate_hz = 0;
  try {
    simulateImu(traj, opt, {}, nullptr, nullptr, "traj.txt");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--rate");
    EXPECT_EQ(e.file(), "traj.txt");
  }
  opt.rate_hz = 800;
  opt.noise.accelerometer_random_walk = -1;
  try {
    simulateImu(traj, opt);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "accelerometer_random_walk");
  }
}

}  // namespace
}  // namespace inet
