// room_shell.h: a room shell exported as one "wall" object gives up its floor and ceiling.
#include "scene/room_shell.h"

#include <gtest/gtest.h>

#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace inet {
namespace {

int id(const char* name) {
  return *nyu40FromName(name);
}

/// A w x d x h box (a room's shell: floor, ceiling and four walls) as one mesh.
Mesh roomBox(double w, double d, double h) {
  Mesh m = makePrimitive("box", {}, "", "");
  for (Vec3f& p : m.positions) p = Vec3f(p.x() * w + w / 2, p.y() * d + d / 2, p.z() * h + h / 2);
  m.id = "shell";
  return m;
}

double area(const Scene& s, const Object& o) {
  double a = 0;
  const Mesh& m = s.meshes[o.mesh];
  for (const Tri& t : m.triangles)
    a += 0.5 * (m.positions[t[1]] - m.positions[t[0]])
                   .cross(m.positions[t[2]] - m.positions[t[0]])
                   .cast<double>()
                   .norm();
  return a;
}

TEST(RoomShell, AWallObjectHoldingTheWholeRoomIsSplitIntoWallFloorAndCeiling) {
  Scene s;
  s.meshes.push_back(roomBox(5, 4, 2.6));
  s.materials.push_back(Material{});
  s.objects.push_back(Object::make("wall.041", 0, 0, Mat4::Identity(), id("wall"), 3));
  EXPECT_EQ(splitRoomShells(s), 1u);
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[0].nyu40, id("wall"));
  EXPECT_NEAR(area(s, s.objects[0]), 2 * (5 + 4) * 2.6, 1e-4);
  EXPECT_EQ(s.objects[1].nyu40, id("floor"));
  EXPECT_EQ(s.objects[1].name, "wall.041_floor");
  EXPECT_NEAR(area(s, s.objects[1]), 20.0, 1e-4);
  EXPECT_EQ(s.objects[2].nyu40, id("ceiling"));
  EXPECT_NEAR(area(s, s.objects[2]), 20.0, 1e-4);
  EXPECT_EQ(s.objects[1].instance, 4);  // new ids after the largest
  EXPECT_EQ(s.objects[2].instance, 5);
  s.validate("test");
}

TEST(RoomShell, PlacedObjectsAreJudgedInTheWorldAndSmallLedgesStayWall) {
  Scene s;
  // a unit box turned upside down and placed 3 m up: its world top is still the ceiling
  s.meshes.push_back(roomBox(1, 1, 1));
  s.materials.push_back(Material{});
  Mat4 T = Mat4::Identity();
  T.block<3, 3>(0, 0) = Vec3(4, -3, -2.5).asDiagonal();  // a rotation about x with scale
  T(2, 3) = 5.5;
  s.objects.push_back(Object::make("walls", 0, 0, T, id("wall"), 1));
  // and a 0.6 x 0.6 m box (0.36 m^2 top): under the 0.5 m^2 a floor needs, all wall
  s.meshes.push_back(roomBox(0.6, 0.6, 1));
  s.objects.push_back(Object::make("wall_pier", 1, 0, Mat4::Identity(), id("wall"), 2));
  EXPECT_EQ(splitRoomShells(s), 1u);
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[2].nyu40, id("floor"));
  EXPECT_NEAR(area(s, s.objects[2]), 1.0, 1e-4);  // in object space: the unit square
  EXPECT_EQ(s.objects[3].nyu40, id("ceiling"));
  EXPECT_EQ(s.objects[1].nyu40, id("wall"));
  EXPECT_EQ(s.meshes[1].triangles.size(), 12u);
}

TEST(RoomShell, ASlabNamedWallBecomesAFloorAndSharedMeshesAreLeftAlone) {
  Scene s;
  s.materials.push_back(Material{});
  Mesh quad = makePrimitive("quad", {}, "", "");
  Mat4 T = Mat4::Identity();
  T.block<3, 3>(0, 0) *= 4.0;
  s.meshes.push_back(quad);
  s.objects.push_back(Object::make("wall_floor_piece", 0, 0, T, id("wall"), 1));
  EXPECT_EQ(splitRoomShells(s), 1u);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].nyu40, id("floor"));
  // two objects share one shell mesh: splitting it would change both
  Scene shared;
  shared.materials.push_back(Material{});
  shared.meshes.push_back(roomBox(5, 4, 2.6));
  shared.objects.push_back(Object::make("wall_a", 0, 0, Mat4::Identity(), id("wall"), 1));
  shared.objects.push_back(Object::make("wall_b", 0, 0, Mat4::Identity(), id("wall"), 2));
  EXPECT_EQ(splitRoomShells(shared), 0u);
  EXPECT_EQ(shared.objects.size(), 2u);
}

}  // namespace
}  // namespace inet
