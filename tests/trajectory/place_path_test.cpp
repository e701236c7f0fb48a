// Placing a file's camera path into a scene: a path recorded elsewhere (a motion-capture room's
// frame) is moved so that its poses keep their clearance; a path already inside is left alone;
// the search is deterministic; a scene without free space is an InputError.
#include "trajectory/place_path.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "../box_mesh.h"

namespace inet {
namespace {

/// A closed 6 x 2 x 2.6 m corridor room (walls as boxes 0.2 m thick), floor at z = 0.
Scene corridor() {
  Scene s;
  Mesh m;
  test::appendBox(m, {3, 1, -0.1}, {6.4, 2.4, 0.2});   // floor
  test::appendBox(m, {3, 1, 2.7}, {6.4, 2.4, 0.2});    // ceiling
  test::appendBox(m, {-0.1, 1, 1.3}, {0.2, 2.4, 2.6});  // x walls
  test::appendBox(m, {6.1, 1, 1.3}, {0.2, 2.4, 2.6});
  test::appendBox(m, {3, -0.1, 1.3}, {6.4, 0.2, 2.6});  // y walls
  test::appendBox(m, {3, 2.1, 1.3}, {6.4, 0.2, 2.6});
  s.meshes.push_back(m);
  s.materials.push_back(Material{});
  s.objects.push_back(Object::make("walls", 0, 0, Mat4::Identity(), 1, 1));
  return s;
}

/// A 5.2 m straight walk along y at 1.5 m height, far outside the corridor (x = 40): it fits the
/// corridor only when turned by 90 or 270 degrees (at 67.5 it would span 2 m across it).
Trajectory walk(double x0) {
  Trajectory t;
  for (int k = 0; k <= 80; ++k)
    t.poses.push_back({k * 50'000'000LL, Pose{Quat::Identity(), Vec3(x0, -2.0 + 0.065 * k, 1.5)}});
  return t;
}

TEST(PlacePath, AWalkFromAnotherRoomIsTurnedAndMovedIntoTheCorridor) {
  const Scene s = corridor();
  const FreeSpace space(s);
  const Trajectory path = walk(40.0);
  const PathPlacement p = placePath(path, space);
  EXPECT_TRUE(p.moved);
  EXPECT_EQ(p.free_before, 0.0);
  EXPECT_EQ(p.free_after, 1.0);
  EXPECT_NEAR(std::fmod(p.yaw_deg, 180.0), 90.0, 1e-9) << "the walk lies along the corridor";
  const Trajectory moved = transformed(path, p.T_scene_file);
  for (const TimedPose& q : moved.poses) {
    EXPECT_GE(space.exactDistance(q.T_world_camera.t), 0.1);
    EXPECT_NEAR(q.T_world_camera.t.z(), 1.5, 1e-6) << "heights above the floor (a float) kept";
  }
  // rigid: the steps keep their length, the stamps their values
  for (size_t k = 1; k < moved.poses.size(); ++k) {
    EXPECT_NEAR((moved.poses[k].T_world_camera.t - moved.poses[k - 1].T_world_camera.t).norm(),
                0.065, 1e-9);
    EXPECT_EQ(moved.poses[k].t_ns, path.poses[k].t_ns);
  }
  // deterministic
  const PathPlacement again = placePath(path, space);
  EXPECT_EQ(again.yaw_deg, p.yaw_deg);
  EXPECT_EQ(again.T_scene_file.t, p.T_scene_file.t);
}

TEST(PlacePath, APathAlreadyInsideIsLeftAsItIs) {
  const Scene s = corridor();
  const FreeSpace space(s);
  Trajectory inside;
  for (int k = 0; k <= 40; ++k)
    inside.poses.push_back({k * 50'000'000LL, Pose{Quat::Identity(), Vec3(1.0 + 0.1 * k, 1.0, 1.4)}});
  const PathPlacement p = placePath(inside, space);
  EXPECT_FALSE(p.moved);
  EXPECT_EQ(p.free_before, 1.0);
  EXPECT_EQ(p.free_after, 1.0);
  EXPECT_EQ(p.yaw_deg, 0.0);
  EXPECT_EQ(p.T_scene_file.t, Vec3::Zero());
}

TEST(PlacePath, NoFreeSpaceIsAnInputError) {
  Scene s;
  Mesh m;
  test::appendBox(m, {0, 0, 1}, {0.3, 0.3, 2.0});  // a closed pillar: nothing inside it
  for (int i = 0; i < 4; ++i) test::appendBox(m, {0.0, 0.0, 1.0}, {0.3 + 0.01 * i, 0.3, 2.0});
  s.meshes.push_back(m);
  s.materials.push_back(Material{});
  s.objects.push_back(Object::make("pillar", 0, 0, Mat4::Identity(), 1, 1));
  const FreeSpace space(s);
  PlacePathOptions opt;
  opt.clearance = 5.0;  // more than any free voxel has
  try {
    placePath(walk(40.0), space, opt, "walk.txt");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--place-trajectory");
    EXPECT_NE(std::string(e.what()).find("no free space"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace inet
