// eval/rgbd_odometry and the `eval features | odometry` commands on a generated sequence of the
// built-in room: every step tracked, a small ATE, the chaining direction (the depth-based
// methods drift far less than a camera that stands still; chaining the inverse steps drifts
// twice as much as standing still, while its SE(3)-aligned ATE stays under 0.2 mm, because on
// a short, nearly straight path the alignment turns the reversed path around), bridging
// untracked steps, the CLI's numbers equal the library's, and bad input is a one-line error
// naming the file.
#include "eval/rgbd_odometry.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "../expect_input_error.h"
#include "core/atomic_file.h"
#include "generated_sequence.h"
#include "trajectory/formats.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

/// The ATE of a "camera that never moves" estimate (it stays at the first pose): the bar every
/// odometry must clear.
double standStillAte(const Trajectory& gt, AlignMode align) {
  Trajectory still = gt;
  for (TimedPose& p : still.poses) p.T_world_camera = gt.poses.front().T_world_camera;
  AteOptions opt;
  opt.align = align;
  return computeAte(gt, still, opt).translation_m.rmse;
}

TEST(RgbdOdometry, TracksTheGeneratedRoom) {
  test::TempDir dir("eval_odometry");
  const fs::path seq = test::generateRoom(dir / "out");
  for (OdometryMethod m : {OdometryMethod::Rgbd, OdometryMethod::Icp, OdometryMethod::RgbdIcp}) {
    SCOPED_TRACE(odometryMethodName(m));
    OdometryOptions opt;
    opt.method = m;
    const OdometryResult r = rgbdOdometry(seq, opt);
    ASSERT_EQ(r.estimate.size(), static_cast<size_t>(test::kSeqFrames));
    ASSERT_EQ(r.steps.size(), r.estimate.size() - 1);
    EXPECT_EQ(r.tracked, r.steps.size()) << r.toString();
    // the estimate starts at the ground truth and keeps its stamps
    EXPECT_EQ(r.estimate.poses[0].T_world_camera.t, r.ground_truth.poses[0].T_world_camera.t);
    for (size_t k = 0; k < r.estimate.size(); ++k)
      EXPECT_EQ(r.estimate.poses[k].t_ns, r.ground_truth.poses[k].t_ns);
    // measured (6 frames, 4.5 cm of path): rgbd 3.9 mm, icp 0.09 mm, rgbd-icp 0.13 mm; a
    // camera that stands still scores 15 mm. Unaligned (drift): icp 0.8 mm, rgbd-icp 0.6 mm,
    // which pins the direction the steps are chained in (the three methods chain through the
    // same code). The photometric method's unaligned drift is not checked: it is
    // ill-conditioned on this view (docs/eval.md) and tells nothing, not even the direction.
    // Its 38 mm is worse than standing still (27 mm) and than the same steps chained the wrong
    // way round (29 mm). 256-spp frames of the same poses drift 25.9 mm, and the fixture's
    // 2-spp frames drifted anywhere from 15 to 38 mm as the renderer's noise changed, while
    // their aligned ATE went from 10.5 mm to 3.9 mm. Its aligned ATE is what is checked, at
    // 10 mm (it was 20 mm when the frames gave 10.5).
    const double bound_m = m == OdometryMethod::Rgbd ? 0.01 : 0.003;
    EXPECT_LT(r.ate.translation_m.rmse, bound_m) << r.toString();
    EXPECT_EQ(r.ate.matches.size(), r.estimate.size());
    if (m != OdometryMethod::Rgbd) {
      const double still_m = standStillAte(r.ground_truth, AlignMode::None);
      EXPECT_LT(r.drift.translation_m.rmse, 0.1 * still_m) << r.toString();
    }
    // deterministic: OpenCV samples its pixel subset with a fixed seed
    const OdometryResult again = rgbdOdometry(seq, opt);
    EXPECT_EQ(again.ate.translation_m.rmse, r.ate.translation_m.rmse);
  }
  // a gate no step passes (the camera moves 9 mm per frame): nothing is tracked, every step
  // is bridged with the previous one, which never existed (identity), so the estimate stands
  // still at the first pose
  OdometryOptions strict;
  strict.max_step_m = 0.001;
  const OdometryResult r = rgbdOdometry(seq, strict);
  EXPECT_EQ(r.tracked, 0u);
  for (const OdometryStep& s : r.steps) {
    EXPECT_TRUE(s.converged);
    EXPECT_GT(s.translation_m, 0.001);
  }
  EXPECT_DOUBLE_EQ(r.drift.translation_m.rmse, standStillAte(r.ground_truth, AlignMode::None));
}

TEST(RgbdOdometry, BadOptionsAndFoldersAreInputErrors) {
  OdometryOptions o;
  o.max_step_m = -1;
  EXPECT_EQ(test::expectInputError([&] { o.validate(); }).field(), "odometry.max_step_m");
  const InputError e = test::expectInputError([] { parseOdometryMethod("orb"); });
  EXPECT_EQ(e.field(), "--method");
  EXPECT_NE(e.problem().find("rgbd, icp, rgbd-icp"), std::string::npos);
  EXPECT_EQ(test::expectInputError([] { rgbdOdometry("/nonexistent/seq"); }).file(),
            "/nonexistent/seq");
}

TEST(EvalCli, FeaturesAndOdometryOnAGeneratedSequence) {
  test::TempDir dir("eval_cli");
  const fs::path seq = test::generateRoom(dir / "out");
  const fs::path est = dir / "est.txt";
  test::RunResult r = test::runInterinet("eval odometry " + seq.string() + " --method icp --out " +
                                         est.string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  OdometryOptions opt;
  opt.method = OdometryMethod::Icp;
  const OdometryResult lib = rgbdOdometry(seq, opt);
  EXPECT_EQ(j["sequence"]["tracked"].get<size_t>(), lib.tracked);
  EXPECT_DOUBLE_EQ(j["sequence"]["ate_translation_m"]["rmse"].get<double>(),
                   lib.ate.translation_m.rmse);
  // --out is a TUM trajectory that `eval ate` scores to the same ATE
  const Trajectory written = readTrajectory(est.string(), TrajectoryFormat::Tum);
  ASSERT_EQ(written.size(), lib.estimate.size());
  EXPECT_NEAR(computeAte(lib.ground_truth, written, {}).translation_m.rmse,
              lib.ate.translation_m.rmse, 1e-6);

  // features against itself as the reference: every ratio is 1
  r = test::runInterinet("eval features " + seq.string() + " --reference " + seq.string() +
                         " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json f = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(f["summary"]["ratio"]["correct_share"].get<double>(), 1.0);
  EXPECT_GT(f["sequence"]["all"]["matches"].get<size_t>(), 0u);
  EXPECT_EQ(f["sequence"]["pairs"].size(), static_cast<size_t>(test::kSeqFrames - 1));

  // a missing folder: exit 2, one line naming it
  for (const char* cmd : {"features", "odometry"}) {
    r = test::runInterinet(std::string("eval ") + cmd + " " + (dir / "nope").string());
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_NE(r.err.find((dir / "nope").string() + ": sequence folder not found"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // a sequence without flow: the features command names flow0/data.csv
  fs::remove_all(seq / "flow0");
  r = test::runInterinet("eval features " + seq.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find((seq / "flow0" / "data.csv").string()), std::string::npos) << r.err;
}

}  // namespace
}  // namespace inet
