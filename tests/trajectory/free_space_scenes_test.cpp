// Free space and random trajectories on the scenes real imports bring (issue 13, defect 5): a
// double-height office whose furniture is one merged mesh, the same office with its floor at
// z = 3.2 m, two storeys, an office with window holes (open to the outside), and the message
// when there truly is no room for a camera.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "../box_mesh.h"
#include "scene/primitives.h"
#include "trajectory/free_space.h"
#include "trajectory/random_trajectory.h"

namespace inet {
namespace {

using test::appendBox;

/// A room shell: floor and ceiling slabs and four walls 0.2 m thick around [0, w] x [0, d],
/// floor top at z0, ceiling underside at z0 + h. `holes` cuts two 1.5 x 1.2 m window openings
/// into the south wall (the shell is then open to the outside).
Mesh shell(double w, double d, double h, double z0, bool holes) {
  Mesh m;
  const double t = 0.2;
  appendBox(m, {w / 2, d / 2, z0 - t / 2}, {w + 2 * t, d + 2 * t, t});
  appendBox(m, {w / 2, d / 2, z0 + h + t / 2}, {w + 2 * t, d + 2 * t, t});
  appendBox(m, {-t / 2, d / 2, z0 + h / 2}, {t, d, h});
  appendBox(m, {w + t / 2, d / 2, z0 + h / 2}, {t, d, h});
  appendBox(m, {w / 2, d + t / 2, z0 + h / 2}, {w, t, h});
  if (!holes) {
    appendBox(m, {w / 2, -t / 2, z0 + h / 2}, {w, t, h});
    return m;
  }
  // south wall in pieces around two openings from 1.0 to 2.2 m, x in [2, 3.5] and [6, 7.5]
  const double y = -t / 2;
  appendBox(m, {w / 2, y, z0 + 0.5}, {w, t, 1.0});                     // below the sills
  appendBox(m, {w / 2, y, z0 + (2.2 + h) / 2}, {w, t, h - 2.2});       // above the lintels
  appendBox(m, {1.0, y, z0 + 1.6}, {2.0, t, 1.2});                     // piers
  appendBox(m, {4.75, y, z0 + 1.6}, {2.5, t, 1.2});
  appendBox(m, {(7.5 + w) / 2, y, z0 + 1.6}, {w - 7.5, t, 1.2});
  return m;
}

/// Desks, shelves full of books and cabinets of a 10 x 11 m office, all in one mesh (as
/// SceneNet's "furniture" objects are).
Mesh mergedFurniture(double z0) {
  Mesh m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const Vec3 desk(2.0 + 3.0 * c, 2.5 + 3.0 * r, z0);
      appendBox(m, desk + Vec3(0, 0, 0.74), {1.6, 0.8, 0.03});  // top
      for (int leg = 0; leg < 4; ++leg)
        appendBox(m, desk + Vec3(leg % 2 ? 0.75 : -0.75, leg / 2 ? 0.35 : -0.35, 0.365),
                  {0.04, 0.04, 0.73});
    }
  for (int s = 0; s < 4; ++s) {  // shelves along the north wall, 2.2 m tall, books on them
    const double x = 1.5 + 2.2 * s;
    appendBox(m, {x, 10.7, z0 + 1.1}, {2.0, 0.4, 2.2});
    for (int b = 0; b < 30; ++b)
      appendBox(m, {x - 0.9 + 0.06 * b, 10.45, z0 + 1.6}, {0.04, 0.1, 0.25});
  }
  appendBox(m, {9.6, 5.5, z0 + 0.5}, {0.6, 3.0, 1.0});  // cabinets on the east wall
  return m;
}

Scene sceneOf(std::vector<Mesh> meshes) {
  Scene s;
  s.materials.push_back(Material{});
  for (size_t k = 0; k < meshes.size(); ++k) {
    meshes[k].id = "m" + std::to_string(k);
    s.meshes.push_back(std::move(meshes[k]));
    s.objects.push_back(Object::make("o" + std::to_string(k), static_cast<int>(k), 0,
                                     Mat4::Identity(), 1, static_cast<int>(k) + 1));
  }
  return s;
}

/// Generates one trajectory of each type and checks its heights above `floor_z`.
void expectTrajectoriesAbove(const Scene& scene, double floor_z, const char* what) {
  SCOPED_TRACE(what);
  const FreeSpace space(scene);
  for (MotionType type : {MotionType::TwoBody, MotionType::HandHeld, MotionType::LookForward}) {
    RandomTrajectoryOptions opt;
    opt.type = type;
    opt.frames = 50;
    opt.seed = 3;
    RandomTrajectory t;
    try {
      t = generateRandomTrajectory(space, opt, what);
    } catch (const InputError& e) {
      FAIL() << e.what();
    }
    for (const TimedPose& p : t.dense.poses) {
      const Vec3& c = p.T_world_camera.t;
      EXPECT_GE(c.z(), floor_z + opt.min_height - 1e-9);
      EXPECT_LE(c.z(), floor_z + opt.max_height + 1e-9);
      EXPECT_GE(space.exactDistance(c), opt.clearance - 1e-9);
    }
  }
}

TEST(FreeSpaceScenes, DoubleHeightOfficeWithMergedFurniture) {
  const Scene s = sceneOf({shell(10, 11, 7, 0, false), mergedFurniture(0)});
  const FreeSpace space(s);
  ASSERT_EQ(space.floorLevels().size(), 1u);  // desks (14 % of the floor) are no floor
  EXPECT_NEAR(space.floorLevels()[0], 0.0, space.voxel());
  EXPECT_NEAR(space.floorBelow({5, 5.5, 1.5}), 0.0, space.voxel());
  expectTrajectoriesAbove(s, 0.0, "office");
}

TEST(FreeSpaceScenes, FloorAtThreeMetresTwenty) {
  // failed before floors were found: heights were 1-2 m above z = 0, inside the floor slab
  const Scene s = sceneOf({shell(10, 11, 7, 3.2, false), mergedFurniture(3.2)});
  const FreeSpace space(s);
  ASSERT_EQ(space.floorLevels().size(), 1u);
  EXPECT_NEAR(space.floorLevels()[0], 3.2, space.voxel());
  expectTrajectoriesAbove(s, space.floorLevels()[0], "raised office");
}

TEST(FreeSpaceScenes, WindowHolesOpenTheOfficeToTheOutside) {
  const Scene s = sceneOf({shell(10, 11, 3.5, 0, true), mergedFurniture(0)});
  expectTrajectoriesAbove(s, 0.0, "office with window holes");
}

TEST(FreeSpaceScenes, TwoStoreysEachKeepTheirHeights) {
  // ground floor 0..2.7 m, upper floor from 2.9 m (slab 0.2 m)
  const Scene s = sceneOf({shell(8, 6, 2.7, 0, false), shell(8, 6, 2.7, 2.9, false)});
  const FreeSpace space(s);
  ASSERT_EQ(space.floorLevels().size(), 2u);
  EXPECT_NEAR(space.floorLevels()[0], 0.0, space.voxel());
  EXPECT_NEAR(space.floorLevels()[1], 2.9, space.voxel());
  EXPECT_NEAR(space.floorBelow({4, 3, 1.5}), 0.0, space.voxel());
  EXPECT_NEAR(space.floorBelow({4, 3, 4.4}), 2.9, space.voxel());
  // a trajectory starts on either storey and stays 1-2 m above that storey's floor
  int upper = 0;
  for (uint64_t seed = 0; seed < 8; ++seed) {
    RandomTrajectoryOptions opt;
    opt.frames = 30;
    opt.seed = seed;
    const RandomTrajectory t = generateRandomTrajectory(space, opt, "two storeys");
    const double floor = space.floorBelow(t.dense.poses.front().T_world_camera.t);
    upper += floor > 1.0;
    for (const TimedPose& p : t.dense.poses) {
      EXPECT_GE(p.T_world_camera.t.z(), floor + 1.0 - 1e-9);
      EXPECT_LE(p.T_world_camera.t.z(), floor + 2.0 + 1e-9);
    }
  }
  EXPECT_GT(upper, 0);
  EXPECT_LT(upper, 8);
}

TEST(FreeSpaceScenes, NoRoomForACameraSaysWhatWasTriedAndWhatToChange) {
  // a 0.5 m wide corridor: free, but never 0.25 m (+ margin) from both walls
  const Scene s = sceneOf({shell(0.5, 6, 2.5, 0, false)});
  const FreeSpace space(s);
  RandomTrajectoryOptions opt;
  try {
    generateRandomTrajectory(space, opt, "closet.obj");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("closet.obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find("m^3 of free space indoors"), std::string::npos) << msg;
    EXPECT_NE(msg.find("floors at z = 0.0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--clearance"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace inet
