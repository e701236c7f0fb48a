// eval/align, eval/error_stats and eval/ate: known transforms align back exactly, Sim(3)
// recovers a known scale, known noise gives its own RMS, and the real fr1/xyz ground truth
// against a shifted, perturbed copy of itself.
#include "eval/ate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "../temp_dir.h"
#include "core/error.h"
#include "core/image_io.h"
#include "eval/eval_plot.h"
#include "synthetic.h"

namespace inet {
namespace {

using test::helixTrajectory;
using test::somePose;
using test::transformed;

TEST(ErrorStats, HandComputedValues) {
  const ErrorStats s = computeErrorStats({4, 1, 3, 2});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std: ((1.5^2 + 0.5^2) * 2) / 4
  EXPECT_DOUBLE_EQ(s.sse, 30.0);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.max, 4);
  EXPECT_DOUBLE_EQ(computeErrorStats({5, 1, 3}).median, 3);
  EXPECT_EQ(computeErrorStats({}).count, 0u);
}

TEST(Align, ParseModeListsTheValidNames) {
  EXPECT_EQ(parseAlignMode("sim3"), AlignMode::Sim3);
  try {
    parseAlignMode("SE3");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--align");
    EXPECT_NE(std::string(e.what()).find("none, se3, sim3"), std::string::npos);
  }
}

TEST(Ate, RigidlyTransformedCopyAlignsBackExactly) {
  const Trajectory gt = helixTrajectory(300);
  const Pose T = somePose();
  const Trajectory est = transformed(gt, T);
  const AteResult r = computeAte(gt, est);
  EXPECT_EQ(r.matches.size(), 300u);
  EXPECT_LT(r.translation_m.rmse, 1e-9);
  EXPECT_LT(r.translation_m.max, 1e-9);
  EXPECT_LT(r.rotation_deg.max, 1e-6);
  // the alignment is T's inverse
  const Pose Ti = T.inverse();
  EXPECT_LT((r.alignment.T_gt_est.t - Ti.t).norm(), 1e-9);
  EXPECT_LT(rotationAngleDeg(r.alignment.T_gt_est.q.conjugate() * Ti.q), 1e-7);
  EXPECT_DOUBLE_EQ(r.alignment.scale, 1.0);
  EXPECT_DOUBLE_EQ(r.tracked_in_span, 1.0);
  EXPECT_DOUBLE_EQ(r.tracked_overall, 1.0);
  // without alignment the error is the displacement T makes: at least |t| - |R p - p| > 0
  AteOptions none;
  none.align = AlignMode::None;
  EXPECT_GT(computeAte(gt, est, none).translation_m.min, 0.5);
}

TEST(Ate, Sim3RecoversAKnownScale) {
  const Trajectory gt = helixTrajectory(300);
  const double s = 2.5;  // a monocular estimate 2.5 times too large
  const Trajectory est = transformed(gt, somePose(), s);
  AteOptions opt;
  opt.align = AlignMode::Sim3;
  const AteResult r = computeAte(gt, est, opt);
  EXPECT_NEAR(r.alignment.scale, 1.0 / s, 1e-12);
  EXPECT_LT(r.translation_m.rmse, 1e-9);
  EXPECT_LT(r.rotation_deg.max, 1e-6);
  opt.align = AlignMode::SE3;  // a rigid alignment cannot absorb the scale
  EXPECT_GT(computeAte(gt, est, opt).translation_m.rmse, 0.5);
}

TEST(Ate, KnownNoiseGivesItsRms) {
  const Trajectory gt = helixTrajectory(2000);
  Trajectory est = gt;
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n(0.0, 0.01);
  double sum_sq = 0;
  for (auto& p : est.poses) {
    const Vec3 e(n(rng), n(rng), n(rng));
    p.T_world_camera.t += e;
    sum_sq += e.squaredNorm();
  }
  const double rms = std::sqrt(sum_sq / est.size());
  AteOptions opt;
  opt.align = AlignMode::None;  // nothing absorbs any noise: exactly its RMS
  const AteResult none = computeAte(gt, est, opt);
  EXPECT_NEAR(none.translation_m.rmse, rms, 1e-12);
  EXPECT_NEAR(none.translation_m.rmse * none.translation_m.rmse,
              none.translation_m.mean * none.translation_m.mean +
                  none.translation_m.std * none.translation_m.std,
              1e-12);
  // SE(3) alignment removes the 6 of 3n noise dimensions it can fit: rmse^2 ~ rms^2 (1 - 2/n)
  opt.align = AlignMode::SE3;
  const AteResult se3 = computeAte(gt, est, opt);
  EXPECT_LE(se3.translation_m.rmse, rms);
  EXPECT_GT(se3.translation_m.rmse, 0.995 * rms);
  // the same noise on a moved copy: the same ATE, the rigid part is aligned away
  const AteResult moved = computeAte(gt, transformed(est, somePose()), opt);
  EXPECT_NEAR(moved.translation_m.rmse, se3.translation_m.rmse, 1e-10);
}

TEST(Ate, TrackedFractionCountsMatchedGroundTruthPoses) {
  const Trajectory gt = helixTrajectory(400);
  Trajectory est;  // tracks the middle half of the sequence, every other frame
  for (size_t k = 100; k < 300; k += 2) est.poses.push_back(gt.poses[k]);
  const AteResult r = computeAte(gt, est);
  EXPECT_EQ(r.matches.size(), 100u);
  // span [t100 - 20 ms, t298 + 20 ms] holds gt poses 100..298 (33 ms spacing): 199
  EXPECT_EQ(r.gt_poses_in_est_span, 199u);
  EXPECT_NEAR(r.tracked_in_span, 100.0 / 199, 1e-12);
  EXPECT_NEAR(r.tracked_overall, 100.0 / 400, 1e-12);
}

TEST(Ate, BadInputIsAnInputError) {
  const Trajectory gt = helixTrajectory(50);
  EXPECT_THROW(computeAte(gt, Trajectory{}), InputError);
  Trajectory late = gt;
  for (auto& p : late.poses) p.t_ns += 3'600'000'000'000;  // an hour later: no overlap
  try {
    computeAte(gt, late);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "association");
    EXPECT_NE(std::string(e.what()).find("--offset"), std::string::npos);
  }
  Trajectory two;
  two.poses = {gt.poses[0], gt.poses[1]};
  EXPECT_THROW(computeAte(gt, two), InputError);  // SE3 needs 3 pairs
  Trajectory still = gt;
  for (auto& p : still.poses) p.T_world_camera.t = Vec3(1, 2, 3);
  AteOptions sim3;
  sim3.align = AlignMode::Sim3;
  EXPECT_THROW(computeAte(gt, still, sim3), InputError);
}

TEST(Ate, RealGroundTruthAgainstAShiftedPerturbedCopy) {
  const std::string path =
      std::string(INET_SHARED_DIR) + "/data/trajectories/tum_rgbd_fr1_xyz_groundtruth.txt";
  if (!std::filesystem::exists(path))
    GTEST_SKIP() << "skipped: " << path << " not found (INET_SHARED_DIR, ../shared/data)";
  const Trajectory gt = readTumTrajectory(path);
  ASSERT_EQ(gt.size(), 3000u);
  // the estimate: 10 ms late, in another frame, with 5 mm of position noise per axis
  Trajectory est = transformed(gt, somePose());
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 0.005);
  double sum_sq = 0;
  for (auto& p : est.poses) {
    p.t_ns += 10'000'000;
    const Vec3 e(n(rng), n(rng), n(rng));
    p.T_world_camera.t += e;
    sum_sq += e.squaredNorm();
  }
  const double rms = std::sqrt(sum_sq / est.size());
  AteOptions opt;
  opt.association.offset_ns = -10'000'000;  // undo the shift: every stamp matches exactly
  opt.association.max_diff_ns = 1'000'000;
  const AteResult r = computeAte(gt, est, opt);
  EXPECT_EQ(r.matches.size(), 3000u);
  EXPECT_DOUBLE_EQ(r.tracked_overall, 1.0);
  EXPECT_LE(r.translation_m.rmse, rms);
  EXPECT_GT(r.translation_m.rmse, 0.99 * rms);
  // without the offset each estimate pose pairs with a neighbouring mocap sample (100 Hz): the
  // camera's motion in ~10 ms adds to the error
  const AteResult shifted = computeAte(gt, est);
  EXPECT_GT(shifted.matches.size(), 2900u);
  EXPECT_GT(shifted.translation_m.rmse, r.translation_m.rmse);

  test::TempDir dir("eval");
  const auto png = dir / "ate.png";
  writeAtePlot(png, gt, est, r, "fr1/xyz vs perturbed copy");
  const ImageU8 img = readPng8(png);
  EXPECT_EQ(img.width, 1500);  // 800 + 700 pixels
  EXPECT_EQ(img.height, 600);
}

}  // namespace
}  // namespace inet
