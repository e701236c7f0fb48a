// eval/rpe: a constant per-step drift gives exactly that drift as the relative error, in frames,
// metres and seconds; rigid transforms do not change RPE, Sim(3) removes a scale.
#include "eval/rpe.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../temp_dir.h"
#include "core/error.h"
#include "core/image_io.h"
#include "eval/ate.h"
#include "eval/eval_plot.h"
#include "synthetic.h"

namespace inet {
namespace {

using test::helixTrajectory;
using test::somePose;
using test::transformed;

/// gt with a world-frame translation drift d per frame (p_k += k d) and a body-frame yaw drift
/// theta per frame (R_k = R_k Rz(k theta)).
Trajectory drifted(const Trajectory& gt, const Vec3& d, double theta) {
  Trajectory est = gt;
  for (size_t k = 0; k < est.size(); ++k) {
    est.poses[k].T_world_camera.t += static_cast<double>(k) * d;
    est.poses[k].T_world_camera.q =
        est.poses[k].T_world_camera.q * Quat(Eigen::AngleAxisd(k * theta, Vec3::UnitZ()));
  }
  return est;
}

TEST(Rpe, ConstantTranslationDriftPerFrame) {
  const Trajectory gt = helixTrajectory(200);
  const Vec3 d(0.003, -0.001, 0.002);  // |d| = 3.74 mm per frame
  const RpeResult r = computeRpe(gt, drifted(gt, d, 0.0));
  EXPECT_EQ(r.matched, 200u);
  EXPECT_EQ(r.pairs.size(), 199u);  // delta 1: (0,1) .. (198,199)
  // E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) has translation R_j^T d: its norm is |d| for every pair
  EXPECT_NEAR(r.translation_m.rmse, d.norm(), 1e-12);
  EXPECT_NEAR(r.translation_m.min, d.norm(), 1e-12);
  EXPECT_NEAR(r.translation_m.max, d.norm(), 1e-12);
  EXPECT_LT(r.rotation_deg.max, 1e-9);
  RpeOptions opt;  // delta 5 frames, disjoint pairs (0,5), (5,10), ...: error 5 |d|
  opt.delta = 5;
  const RpeResult r5 = computeRpe(gt, drifted(gt, d, 0.0), opt);
  EXPECT_EQ(r5.pairs.size(), 39u);
  EXPECT_EQ(r5.pairs[1], (std::pair<size_t, size_t>{5, 10}));
  EXPECT_NEAR(r5.translation_m.mean, 5 * d.norm(), 1e-12);
  opt.all_pairs = true;
  EXPECT_EQ(computeRpe(gt, drifted(gt, d, 0.0), opt).pairs.size(), 195u);
}

TEST(Rpe, ConstantRotationDriftPerFrame) {
  // est_k = D^k gt_k with D a rotation by theta about the world z axis (the helix axis): a
  // heading drift. Then E = gt_j^-1 D gt_j for delta 1: rotation angle theta exactly, and
  // translation R_j^T (Rz(theta) - I) t_j of norm 2 sin(theta / 2) |t_j,xy| = 4 sin(theta / 2)
  // on a helix of radius 2.
  const Trajectory gt = helixTrajectory(200);
  const double theta = 0.5 * M_PI / 180;
  Trajectory est = gt;
  for (size_t k = 0; k < est.size(); ++k) {
    Pose D;
    D.q = Quat(Eigen::AngleAxisd(k * theta, Vec3::UnitZ()));
    est.poses[k].T_world_camera = D * gt.poses[k].T_world_camera;
  }
  const RpeResult r = computeRpe(gt, est);
  EXPECT_NEAR(r.rotation_deg.mean, 0.5, 1e-9);
  EXPECT_NEAR(r.rotation_deg.std, 0.0, 1e-9);
  EXPECT_NEAR(r.translation_m.min, 4 * std::sin(theta / 2), 1e-12);
  EXPECT_NEAR(r.translation_m.max, 4 * std::sin(theta / 2), 1e-12);
}

TEST(Rpe, DeltaInMetresAndSeconds) {
  const Trajectory gt = helixTrajectory(301, 30);  // 10 s, speed |v| = 0.4 * sqrt(4 + 0.0064)
  const Vec3 d(0.0, 0.002, 0.0);
  const Trajectory est = drifted(gt, d, 0.0);
  RpeOptions opt;
  opt.unit = DeltaUnit::Seconds;
  opt.delta = 1.0;  // 30 frames
  RpeResult r = computeRpe(gt, est, opt);
  ASSERT_EQ(r.pairs.size(), 10u);
  EXPECT_EQ(r.pairs[0], (std::pair<size_t, size_t>{0, 30}));
  EXPECT_NEAR(r.translation_m.mean, 30 * d.norm(), 1e-12);
  opt.unit = DeltaUnit::Metres;
  opt.delta = 0.5;
  r = computeRpe(gt, est, opt);
  // chord per frame: 2 * 2 sin(0.4 / 60) in xy with 0.08 * 0.4 / 30 rise; the first j with
  // accumulated path >= 0.5 m
  const double step_xy = 4 * std::sin(0.2 / 30), step_z = 0.032 / 30;
  const double step = std::hypot(step_xy, step_z);
  const auto frames = static_cast<size_t>(std::ceil(0.5 / step - 1e-9));
  ASSERT_FALSE(r.pairs.empty());
  EXPECT_EQ(r.pairs[0].second, frames);
  EXPECT_NEAR(r.translation_m.mean, frames * d.norm(), 1e-12);
  opt.delta = 1000;  // longer than the path
  try {
    computeRpe(gt, est, opt);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--delta");
  }
  opt.unit = DeltaUnit::Frames;
  opt.delta = 1.5;
  EXPECT_THROW(computeRpe(gt, est, opt), InputError);
  EXPECT_THROW(parseDeltaUnit("metres"), InputError);
  EXPECT_EQ(parseDeltaUnit("m"), DeltaUnit::Metres);
}

TEST(Rpe, InvariantToRigidTransformScaleNeedsSim3) {
  const Trajectory gt = helixTrajectory(200);
  const Vec3 d(0.001, 0.002, 0.0);
  const Trajectory est = drifted(gt, d, 0.001);
  const RpeResult base = computeRpe(gt, est);
  const RpeResult moved = computeRpe(gt, transformed(est, somePose()));
  EXPECT_NEAR(moved.translation_m.rmse, base.translation_m.rmse, 1e-12);
  EXPECT_NEAR(moved.rotation_deg.rmse, base.rotation_deg.rmse, 1e-9);
  // a scaled copy of the ground truth: relative translations are 3x, error 2x the motion
  const Trajectory big = transformed(gt, somePose(), 3.0);
  EXPECT_GT(computeRpe(gt, big).translation_m.rmse, 0.01);
  RpeOptions sim3;
  sim3.align = AlignMode::Sim3;
  const RpeResult r = computeRpe(gt, big, sim3);
  EXPECT_LT(r.translation_m.rmse, 1e-12);
  EXPECT_NEAR(r.alignment.scale, 1.0 / 3, 1e-12);

  test::TempDir dir("eval");
  writeRpePlot(dir / "rpe.png", gt, base, "drift");
  EXPECT_EQ(readPng8(dir / "rpe.png").width, 1400);
}

}  // namespace
}  // namespace inet
