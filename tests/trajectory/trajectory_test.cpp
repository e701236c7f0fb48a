#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"
#include "trajectory/trajectory.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

TEST(SecondsParsing, ExactNanoseconds) {
  TimeNs t;
  ASSERT_TRUE(parseSecondsToNs("1305031102.175304", t));
  EXPECT_EQ(t, 1305031102175304000LL);
  ASSERT_TRUE(parseSecondsToNs("1403715273.262142976", t));
  EXPECT_EQ(t, 1403715273262142976LL);
  ASSERT_TRUE(parseSecondsToNs("7", t));
  EXPECT_EQ(t, 7000000000LL);
  EXPECT_FALSE(parseSecondsToNs("1.2.3", t));
  EXPECT_FALSE(parseSecondsToNs("abc", t));
  EXPECT_FALSE(parseSecondsToNs("", t));
}

TEST(TumTrajectory, ReadsRealGroundTruthAndRoundTrips) {
  std::string path =
      std::string(INET_SHARED_DIR) + "/data/trajectories/tum_rgbd_fr1_xyz_groundtruth.txt";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data/trajectories not found";
  Trajectory t = readTumTrajectory(path);
  EXPECT_EQ(t.size(), 3000u);
  fs::path out = fs::temp_directory_path() / ("inet_tum_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(out) << formatTumTrajectory(t, "round trip");
  Trajectory back = readTumTrajectory(out.string());
  ASSERT_EQ(back.size(), t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(back.poses[i].t_ns, t.poses[i].t_ns);
    EXPECT_NEAR((back.poses[i].T_world_camera.t - t.poses[i].T_world_camera.t).norm(), 0, 1e-9);
    EXPECT_NEAR(back.poses[i].T_world_camera.q.angularDistance(t.poses[i].T_world_camera.q), 0,
                1e-8);
  }
  fs::remove(out);
}

TEST(TumTrajectory, CommasTabsAndCrlfAreSpaces) {
  fs::path p = fs::temp_directory_path() / ("inet_tum_sep_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(p) << "# header\r\n1.5,1,2,3,0,0,0,1\r\n2.5\t1\t2\t3\t0\t0\t0\t1\r\n";
  Trajectory t = readTumTrajectory(p.string());
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[1].t_ns, 2500000000LL);
  fs::remove(p);
}

// The built-in path stays inside the room, at least 0.3 m from every surface: checked by casting
// rays in 26 directions from each pose against the real scene geometry.
TEST(BuiltinTrajectory, CollisionFreeInDefaultRoom) {
  Scene scene = makeDefaultScene();
  Renderer r(scene);
  Trajectory traj = builtinTrajectory(400, 25.0);  // one 16 s loop
  CameraIntrinsics K;
  K.width = 32;
  K.height = 32;
  K.fx = K.fy = 8;  // ~127 degree field of view
  K.cx = K.cy = 16;
  const Vec3 dirs[6] = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                        -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  double min_dist = 1e9;
  for (size_t k = 0; k < traj.size(); k += 10) {
    const Vec3& eye = traj.poses[k].T_world_camera.t;
    EXPECT_GT(eye.z(), 1.0);
    EXPECT_LT(eye.z(), 2.0);
    for (const Vec3& d : dirs) {
      Vec3 up = std::abs(d.z()) > 0.5 ? Vec3::UnitX() : Vec3::UnitZ();
      Frame f;
      r.renderGroundTruth(K, Pose::lookAt(eye, eye + d, up), static_cast<PassMask>(Pass::DepthRay),
                          f);
      for (float v : f.depth_ray.data) {
        ASSERT_GT(v, 0.f) << "ray escaped the closed room";
        min_dist = std::min(min_dist, static_cast<double>(v));
      }
    }
  }
  EXPECT_GT(min_dist, 0.3);
  // timestamps: 25 Hz exactly in integer nanoseconds
  EXPECT_EQ(traj.poses[1].t_ns, 40000000);
  EXPECT_EQ(traj.poses[399].t_ns, 399LL * 40000000);
}

TEST(Trajectory, VelocityFromPositions) {
  Trajectory t;
  for (int k = 0; k < 5; ++k)
    t.poses.push_back({k * 100000000LL, Pose{Quat::Identity(), Vec3(0.2 * k, 0, 0)}});
  EXPECT_NEAR((t.velocityWorld(0) - Vec3(2, 0, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR((t.velocityWorld(2) - Vec3(2, 0, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR((t.velocityWorld(4) - Vec3(2, 0, 0)).norm(), 0, 1e-9);
}

}  // namespace
}  // namespace inet
