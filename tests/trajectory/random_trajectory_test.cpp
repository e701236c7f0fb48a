// Base random trajectories (issue 5 acceptance): 200 of each type in 20 generated apartments,
// every sample checked against the layout's own collision geometry (the exact distance to its
// triangles and its pieces' collision boxes), heights, tilt, the look-at rules of each type,
// and speeds that follow the multipliers.
#include "trajectory/random_trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "../temp_dir.h"
#include "core/error.h"
#include "procedural/apartment.h"
#include "scene/assimp_importer.h"
#include "scene/front3d_importer.h"

namespace inet {
namespace {

double spearman(std::vector<double> a, std::vector<double> b) {
  auto ranks = [](const std::vector<double>& v) {
    std::vector<size_t> idx(v.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](size_t x, size_t y) { return v[x] < v[y]; });
    std::vector<double> r(v.size());
    for (size_t i = 0; i < idx.size(); ++i) r[idx[i]] = static_cast<double>(i);
    return r;
  };
  std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(a.size()), mean = (n - 1) / 2;
  double num = 0, da = 0, db = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    num += (ra[i] - mean) * (rb[i] - mean);
    da += (ra[i] - mean) * (ra[i] - mean);
    db += (rb[i] - mean) * (rb[i] - mean);
  }
  return num / std::sqrt(da * db);
}

/// Mean horizontal speed (m/s) and mean angular speed of the viewing direction (rad/s) from
/// the dense poses.
std::pair<double, double> meanSpeeds(const Trajectory& dense) {
  double v = 0, w = 0;
  for (size_t i = 1; i < dense.size(); ++i) {
    const double dt = (dense.poses[i].t_ns - dense.poses[i - 1].t_ns) * 1e-9;
    Vec3 d = dense.poses[i].T_world_camera.t - dense.poses[i - 1].T_world_camera.t;
    v += d.head<2>().norm() / dt;
    Vec3 f0 = dense.poses[i - 1].T_world_camera.rotation().col(2);
    Vec3 f1 = dense.poses[i].T_world_camera.rotation().col(2);
    w += std::atan2(f0.cross(f1).norm(), f0.dot(f1)) / dt;
  }
  const double n = static_cast<double>(dense.size() - 1);
  return {v / n, w / n};
}

class RandomTrajectories : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir("random_trajectory");
    for (uint64_t seed = 0; seed < 20; ++seed) {
      ApartmentOptions opt;
      opt.seed = seed;
      opt.texture_size = 64;
      apartments_.push_back(makeApartment(opt, dir_->path(), dir_->path() / "textures"));
    }
  }
  static void TearDownTestSuite() {
    apartments_.clear();
    delete dir_;
  }

  /// The mean free line of sight (m, up to 5) from the first frame over five horizontal
  /// directions across 60 degrees about its view.
  static double firstViewRange(const FreeSpace& space, const Trajectory& frames) {
    const Pose& T = frames.poses.front().T_world_camera;
    const Vec3 f = T.rotation().col(2);
    const double a = std::atan2(f.y(), f.x());
    double sum = 0;
    for (const double off : {-30.0, -15.0, 0.0, 15.0, 30.0}) {
      const double b = a + off * M_PI / 180;
      const Vec3 dir(std::cos(b), std::sin(b), 0);
      double r = 0;
      while (r < 5.0 && space.lowerBound(T.t + (r + 0.1) * dir) > 0.0) r += 0.1;
      sum += r;
    }
    return sum / 5;
  }

  // Trajectories per apartment. The speed and turn statistics below are estimates whose
  // standard error at 100 trajectories (5 per apartment) was about 0.06, as large as their
  // margins: on hand-held, Spearman(v_mult, speed) is 0.73 over 300 trajectories but came out
  // 0.66 and then 0.63 on the first 100 when the curtains changed shape. 200 halve the variance.
  static constexpr int kPerLayout = 10;

  void checkType(MotionType type) {
    std::vector<double> v_mult, w_mult, v_mean, w_mean, agreement;
    int open_starts = 0;
    double max_ratio = 0;
    int samples = 0;
    double min_clear = 1e9;
    for (size_t layout = 0; layout < apartments_.size(); ++layout) {
      const Apartment& apt = apartments_[layout];
      FreeSpace space(apt.scene);
      WorldTriangles tris = worldTriangles(apt.scene);
      ExactDistance exact(tris);
      for (int n = 0; n < kPerLayout; ++n) {
        RandomTrajectoryOptions opt;
        opt.type = type;
        opt.seed = layout * 1000 + n;
        opt.frames = 125;  // 5 s at 25 Hz
        opt.exposure_s = 0.01;
        RandomTrajectory traj = generateRandomTrajectory(space, opt);
        ASSERT_EQ(traj.frames.size(), 125u);
        ASSERT_EQ(traj.shutter_close.size(), 125u);
        EXPECT_EQ(traj.shutter_close.poses[3].t_ns - traj.frames.poses[3].t_ns, 10'000'000);
        EXPECT_GE(traj.v_mult, 0.5);
        EXPECT_LT(traj.v_mult, 5.0);
        EXPECT_GE(traj.w_mult, 0.5);
        EXPECT_LT(traj.w_mult, 3.0);
        for (double tilt : traj.tilt_deg) EXPECT_LE(tilt, opt.max_tilt_deg + 1e-9);
        open_starts += firstViewRange(space, traj.frames) >= 1.5;

        std::vector<const TimedPose*> all;
        for (const auto& p : traj.dense.poses) all.push_back(&p);
        for (const auto& p : traj.frames.poses) all.push_back(&p);
        for (const auto& p : traj.shutter_close.poses) all.push_back(&p);
        for (const TimedPose* p : all) {
          const Vec3 c = p->T_world_camera.t;
          const Mat3 R = p->T_world_camera.rotation();
          ++samples;
          const double d = exact.distance(c, 5.0);
          min_clear = std::min(min_clear, d);
          ASSERT_GE(d, opt.clearance) << motionTypeName(type) << " layout " << layout << " traj "
                                      << n << " t " << p->t_ns << " at " << c.transpose();
          for (const PlacedPiece& piece : apt.pieces)
            for (const auto& hull : piece.hulls)
              ASSERT_FALSE(hull.contains(c)) << "inside " << piece.name;
          bool in_room = false;
          for (const Room& r : apt.scene.rooms) {
            Eigen::AlignedBox2d box;
            for (const auto& q : r.outline) box.extend(q);
            // outlines run along the walls' inner faces; a doorway lies within the wall
            box.min() -= Eigen::Vector2d::Constant(0.1);
            box.max() += Eigen::Vector2d::Constant(0.1);
            in_room = in_room || box.contains(c.head<2>());
          }
          ASSERT_TRUE(in_room) << "outside every room at " << c.transpose();
          ASSERT_GE(c.z(), opt.min_height - 1e-9);
          ASSERT_LE(c.z(), opt.max_height + 1e-9);
          // roll: the image x axis leans at most the tilt limit out of the horizontal plane
          ASSERT_LE(std::abs(std::asin(R.col(0).z())) * 180 / M_PI, opt.max_tilt_deg + 1e-6);
          if (type == MotionType::HandHeld) {
            ASSERT_LT(R.col(2).z(), 0.0) << "looks up";
          }
        }
        if (type == MotionType::LookForward) {
          // the view follows the motion: forward and velocity agree when moving
          double agree = 0;
          int moving = 0;
          for (size_t k = 0; k < traj.frames.size(); ++k) {
            Vec3 vel = traj.frames.velocityWorld(k);
            if (vel.head<2>().norm() < 0.1) continue;
            Vec3 f = traj.frames.poses[k].T_world_camera.rotation().col(2);
            agree += f.head<2>().normalized().dot(vel.head<2>().normalized());
            ++moving;
          }
          if (moving > 20) agreement.push_back(agree / moving);
        }
        // no runaway: the fastest moment stays within a few RMS speeds (a feedback between the
        // steering and its low-pass once drove a camera to 20 m/s)
        double v_max = 0;
        for (size_t i = 1; i < traj.dense.size(); ++i)
          v_max = std::max(
              v_max,
              (traj.dense.poses[i].T_world_camera.t - traj.dense.poses[i - 1].T_world_camera.t)
                      .norm() /
                  ((traj.dense.poses[i].t_ns - traj.dense.poses[i - 1].t_ns) * 1e-9));
        EXPECT_LT(v_max, 4.0 * 0.3 * traj.v_mult + 0.3) << "layout " << layout << " traj " << n;
        max_ratio = std::max(max_ratio, v_max / (0.3 * traj.v_mult));
        auto [v, w] = meanSpeeds(traj.dense);
        v_mult.push_back(traj.v_mult);
        w_mult.push_back(traj.w_mult);
        v_mean.push_back(v);
        w_mean.push_back(w);
      }
    }
    std::vector<double> ratio(v_mean.size());
    for (size_t i = 0; i < ratio.size(); ++i) ratio[i] = v_mean[i] / (0.3 * v_mult[i]);
    std::sort(ratio.begin(), ratio.end());
    const double rho_v = spearman(v_mult, v_mean), rho_w = spearman(w_mult, w_mean);
    // least-squares slope of log(mean speed) on log(multiplier): 1 means proportional
    auto logSlope = [](const std::vector<double>& x, const std::vector<double>& y) {
      double mx = 0, my = 0;
      for (size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]), my += std::log(y[i]);
      mx /= x.size(), my /= y.size();
      double sxy = 0, sxx = 0;
      for (size_t i = 0; i < x.size(); ++i) {
        sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
        sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
      }
      return sxy / sxx;
    };
    const double slope_v = logSlope(v_mult, v_mean), slope_w = logSlope(w_mult, w_mean);
    std::printf("log-log slopes: speed %.2f, turn %.2f; fastest moment %.2f x 0.3 v_mult\n",
                slope_v, slope_w, max_ratio);
    // log(turn) = a + b log(w_mult) + c log(v_mult): the turn rate's share of each multiplier
    Eigen::MatrixXd X(w_mult.size(), 3);
    Eigen::VectorXd y(w_mult.size());
    for (size_t i = 0; i < w_mult.size(); ++i) {
      X.row(i) << 1.0, std::log(w_mult[i]), std::log(v_mult[i]);
      y[i] = std::log(w_mean[i]);
    }
    Eigen::Vector3d coef = X.colPivHouseholderQr().solve(y);
    std::printf("log turn = %.2f + %.2f log w_mult + %.2f log v_mult\n", coef[0], coef[1], coef[2]);
    if (!agreement.empty()) {
      std::sort(agreement.begin(), agreement.end());
      std::printf("look-forward agreement: 10%% %.2f median %.2f 90%% %.2f\n",
                  agreement[agreement.size() / 10], agreement[agreement.size() / 2],
                  agreement[agreement.size() * 9 / 10]);
    }
    std::printf(
        "%s: %d samples, min clearance %.3f m, speed/(0.3 v_mult) median %.2f "
        "(10%% %.2f, 90%% %.2f), Spearman(v_mult, speed) %.2f, Spearman(w_mult, turn) %.2f\n",
        motionTypeName(type), samples, min_clear, ratio[ratio.size() / 2], ratio[ratio.size() / 10],
        ratio[ratio.size() * 9 / 10], rho_v, rho_w);
    const int count = kPerLayout * static_cast<int>(apartments_.size());
    EXPECT_EQ(v_mean.size(), static_cast<size_t>(count));
    // a sequence does not open on a wall at arm's length (hand-held looks down by design)
    std::printf("%s: %d of %d first views see 1.5 m or more across their field\n",
                motionTypeName(type), open_starts, count);
    if (type != MotionType::HandHeld) {
      EXPECT_GE(open_starts, count * 95 / 100);
    }
    // Speeds follow v_mult: near proportional and near base_speed * v_mult. Walls of 3-4 m
    // rooms cap the fastest cameras, so the log-log slope is under 1: 0.70-0.99 over the types
    // and the variants of the force model tried (its standard error here is about 0.07).
    EXPECT_GT(rho_v, 0.65);
    EXPECT_GT(slope_v, 0.6);
    EXPECT_LT(slope_v, 1.1);
    EXPECT_GT(ratio[ratio.size() / 2], 0.5);
    EXPECT_LT(ratio[ratio.size() / 2], 1.2);
    if (type != MotionType::LookForward) {
      // the view turns with w_mult and not with the camera's speed. The coefficient's standard
      // error was about 0.06 at 100 trajectories of 5 s (0.04 at 200); two-body measures 0.8,
      // hand-held about 0.6 (keeping the look-at point below the camera takes away vertical turns
      // that would scale with w_mult)
      EXPECT_GT(coef[1], type == MotionType::TwoBody ? 0.6 : 0.45);
      EXPECT_LT(coef[1], 1.1);
      EXPECT_LT(std::abs(coef[2]), 0.2);
    } else {
      // the view follows the velocity, whose direction turns with w_mult (and steering round
      // obstacles adds turns that grow with speed)
      EXPECT_GT(coef[1], 0.5);
      EXPECT_GT(coef[2], -0.1);
      ASSERT_GE(agreement.size(), static_cast<size_t>(count * 8 / 10));
      EXPECT_GT(agreement[agreement.size() / 2], 0.8) << "the view looks where the camera goes";
      EXPECT_GT(agreement[agreement.size() / 10], 0.5);
    }
  }

  static test::TempDir* dir_;
  static std::vector<Apartment> apartments_;
};

test::TempDir* RandomTrajectories::dir_ = nullptr;
std::vector<Apartment> RandomTrajectories::apartments_;

TEST_F(RandomTrajectories, TwoBody) {
  checkType(MotionType::TwoBody);
}
TEST_F(RandomTrajectories, HandHeld) {
  checkType(MotionType::HandHeld);
}
TEST_F(RandomTrajectories, LookForward) {
  checkType(MotionType::LookForward);
}

TEST(RandomTrajectory, SameSeedSameTrajectoryAndMultipliersCanBeSet) {
  test::TempDir dir("random_trajectory_det");
  ApartmentOptions aopt;
  aopt.seed = 5;
  aopt.texture_size = 64;
  Apartment apt = makeApartment(aopt, dir.path(), dir.path() / "textures");
  FreeSpace space(apt.scene);
  RandomTrajectoryOptions opt;
  opt.seed = 42;
  opt.frames = 50;
  opt.v_mult = 2.0;
  opt.w_mult = 1.5;
  RandomTrajectory a = generateRandomTrajectory(space, opt);
  RandomTrajectory b = generateRandomTrajectory(space, opt);
  EXPECT_EQ(a.v_mult, 2.0);
  EXPECT_EQ(a.w_mult, 1.5);
  ASSERT_EQ(a.dense.size(), b.dense.size());
  for (size_t i = 0; i < a.dense.size(); ++i) {
    EXPECT_EQ(a.dense.poses[i].T_world_camera.t, b.dense.poses[i].T_world_camera.t);
    EXPECT_EQ(a.dense.poses[i].T_world_camera.q.coeffs(),
              b.dense.poses[i].T_world_camera.q.coeffs());
  }
  opt.seed = 43;
  RandomTrajectory c = generateRandomTrajectory(space, opt);
  EXPECT_NE(a.frames.poses[10].T_world_camera.t, c.frames.poses[10].T_world_camera.t);
  // 50 frames at 25 Hz span 1.96 s; dense samples at 200 Hz cover it
  EXPECT_EQ(a.dense.size(), 393u);
  EXPECT_EQ(a.dense.poses.back().t_ns, 1'960'000'000);
}

TEST(RandomTrajectory, ParsesTypeNames) {
  EXPECT_EQ(parseMotionType("hand-held"), MotionType::HandHeld);
  EXPECT_STREQ(motionTypeName(parseMotionType("look-forward")), "look-forward");
  EXPECT_THROW(parseMotionType("walk"), InputError);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

/// Imported scenes (the issue's "generate --layout imported.json finds free space and makes a
/// trajectory inside the rooms"): every SceneNet RGB-D layout, SceneNet v1 and the 3D-FRONT house
/// of ../shared get a 10 s trajectory of each type that keeps its clearance from the triangles.
TEST(RandomTrajectory, ImportedScenesGetCollisionFreeTrajectories) {
  namespace fs = std::filesystem;
  const fs::path scenes = fs::path(INET_SHARED_DIR) / "data" / "scenes";
  if (!fs::exists(scenes)) GTEST_SKIP() << "needs ../shared/data/scenes (absent)";
  std::vector<std::pair<std::string, Scene>> imported;
  for (const auto& e : fs::recursive_directory_iterator(scenes)) {
    const std::string p = e.path().string();
    if (e.path().extension() != ".obj" || p.find("scenenet") == std::string::npos) continue;
    ImportOptions opt;
    opt.up = 'y';
    imported.emplace_back(e.path().filename().string(), importMeshScene(p, opt));
  }
  for (const auto& e : fs::directory_iterator(scenes / "3d_front"))
    imported.emplace_back(e.path().filename().string(), importFront3d(e.path().string(), {}));
  std::sort(imported.begin(), imported.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  EXPECT_GE(imported.size(), 13u) << "11 SceneNet RGB-D layouts, SceneNet v1, 3D-FRONT";
  for (const auto& [name, scene] : imported) {
    FreeSpace space(scene, {}, name);
    ExactDistance exact(worldTriangles(scene));
    for (MotionType type : {MotionType::TwoBody, MotionType::HandHeld, MotionType::LookForward}) {
      RandomTrajectoryOptions opt;
      opt.type = type;
      opt.seed = 7;
      opt.frames = 250;
      RandomTrajectory traj = generateRandomTrajectory(space, opt, name);
      double min_d = 1e9;
      for (const auto& p : traj.dense.poses)
        min_d = std::min(min_d, exact.distance(p.T_world_camera.t, 5));
      EXPECT_GE(min_d, opt.clearance) << name << " " << motionTypeName(type);
      // it moves: a trajectory stuck in a corner would pass the clearance check trivially
      const Vec3 a = traj.frames.poses.front().T_world_camera.t;
      double furthest = 0;
      for (const auto& p : traj.frames.poses)
        furthest = std::max(furthest, (p.T_world_camera.t - a).norm());
      EXPECT_GT(furthest, 0.3) << name << " " << motionTypeName(type);
    }
  }
}

}  // namespace
}  // namespace inet
