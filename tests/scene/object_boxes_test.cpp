#include "scene/object_boxes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "core/rng.h"
#include "scene/default_scene.h"
#include "scene/primitives.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;

Mat4 placement(double yaw, const Vec3& t) {
  Mat4 T = Mat4::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  T.block<3, 1>(0, 3) = t;
  return T;
}

Scene boxScene() {
  Scene s;
  Mesh m = makePrimitive("box", {}, "test", "box");
  for (Vec3f& p : m.positions) p = p.cwiseProduct(Vec3f(2.f, 1.f, 0.5f));  // 2 x 1 x 0.5 m
  s.meshes.push_back(std::move(m));
  s.materials.emplace_back();
  return s;
}

TEST(GravityAlignedBox, RecoversARotatedBoxExactly) {
  // 8 corners of a 2 x 1 x 0.5 box turned by 30 degrees, plus interior points
  const double yaw = 30 * kPi / 180;
  const Mat3 R = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 c(1, -2, 0.25);
  std::vector<Vec3> pts;
  CounterRng rng(7, RngStream::Sensor, 0, 0, 0);
  for (int i = 0; i < 8; ++i)
    pts.push_back(c + R * Vec3(i & 1 ? 1 : -1, i & 2 ? 0.5 : -0.5, i & 4 ? 0.25 : -0.25));
  for (int i = 0; i < 100; ++i)
    pts.push_back(c + R * Vec3(rng.uniformDouble(-1, 1), rng.uniformDouble(-0.5, 0.5),
                               rng.uniformDouble(-0.25, 0.25)));
  const OrientedBox b = gravityAlignedBox(pts);
  EXPECT_NEAR((b.centre - c).norm(), 0, 1e-12);
  EXPECT_NEAR(b.size.x() * b.size.y(), 2.0, 1e-12);
  EXPECT_NEAR(b.size.z(), 0.5, 1e-12);
  EXPECT_NEAR(b.size.maxCoeff(), 2.0, 1e-12);
  // yaw in [0, pi/2): 30 degrees; or 120 degrees reduced, with the sizes swapped
  EXPECT_GE(b.yaw(), -1e-12);
  EXPECT_LT(b.yaw(), kPi / 2);
  EXPECT_NEAR(b.yaw(), yaw, 1e-12);
  // every point inside (to rounding), and each face touched by one
  const Mat3 Rb = b.q_world_box.toRotationMatrix();
  for (const Vec3& p : pts) {
    const Vec3 l = Rb.transpose() * (p - b.centre);
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(l[a]), b.size[a] / 2 + 1e-12);
  }
  // corners come back in bit order: corner 7 - corner 0 = the diagonal
  const auto corners = b.corners();
  EXPECT_NEAR((corners[7] - corners[0]).norm(), b.size.norm(), 1e-12);
  EXPECT_NEAR(corners[0].z(), 0.0, 1e-12);
  EXPECT_NEAR(corners[4].z(), 0.5, 1e-12);
}

TEST(GravityAlignedBox, DegenerateInputs) {
  EXPECT_EQ(gravityAlignedBox({}).size, Vec3::Zero());
  const OrientedBox one = gravityAlignedBox({Vec3(1, 2, 3)});
  EXPECT_EQ(one.centre, Vec3(1, 2, 3));
  EXPECT_EQ(one.size, Vec3::Zero());
  // collinear points: a zero-width box along the line
  const OrientedBox line = gravityAlignedBox({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 1)});
  EXPECT_NEAR(line.size.z(), 1.0, 1e-12);
  EXPECT_NEAR(std::min(line.size.x(), line.size.y()), 0.0, 1e-12);
  EXPECT_NEAR(std::max(line.size.x(), line.size.y()), std::sqrt(8.0), 1e-12);
}

TEST(InstanceBoxes, PartsOfOneInstanceShareABoxWithTheObjectsHeading) {
  Scene s = boxScene();
  // a "table": a top and two legs, all instance 5, turned by 100 degrees (the smallest
  // rectangle would report yaw 10 degrees; the object's own heading is kept)
  const double yaw = 100 * kPi / 180;
  const Mat4 T = placement(yaw, Vec3(3, 4, 0));
  auto part = [&](const Vec3& local, const char* name) {
    Mat4 P = T;
    P.block<3, 1>(0, 3) += T.topLeftCorner<3, 3>() * local;
    s.objects.push_back(Object::make(name, 0, 0, P, 7, 5));
  };
  part(Vec3(0, 0, 0.75), "top");  // box 2 x 1 x 0.5 centred at z = 0.75: z in [0.5, 1.0]
  part(Vec3(-0.5, 0, 0.25), "leg_a");
  part(Vec3(0.5, 0, 0.25), "leg_b");
  s.objects.push_back(Object::make("other", 0, 0, placement(0, Vec3(-5, 0, 0.25)), 3, 2));
  s.objects.push_back(Object::make("unlabelled", 0, 0, placement(0, Vec3(9, 9, 9)), 0, 0));
  const auto boxes = instanceBoxes(s);
  ASSERT_EQ(boxes.size(), 2u);  // instance 0 has no box
  EXPECT_EQ(boxes[0].instance, 2);
  EXPECT_EQ(boxes[1].instance, 5);
  const InstanceBox& table = boxes[1];
  EXPECT_EQ(table.name, "top");
  EXPECT_EQ(table.nyu40, 7);
  EXPECT_FALSE(table.moving);
  EXPECT_NEAR(table.box.yaw(), yaw, 1e-9);
  // x: legs at -0.5 and 0.5 with half-width 1 -> [-1.5, 1.5]; y: 1; z: [0, 1]
  EXPECT_NEAR(table.box.size.x(), 3.0, 1e-9);
  EXPECT_NEAR(table.box.size.y(), 1.0, 1e-9);
  EXPECT_NEAR(table.box.size.z(), 1.0, 1e-9);
  EXPECT_NEAR((table.box.centre - Vec3(3, 4, 0.5)).norm(), 0, 1e-9);
}

TEST(InstanceBoxes, MovingInstanceFollowsItsKeyframes) {
  Scene s = boxScene();
  Object o = Object::make("chair", 0, 0, placement(0.3, Vec3(1, 1, 0.25)), 5, 9);
  Pose p0;  // identity at t = 0
  Pose p1;
  p1.t = Vec3(0.5, 0, 0);
  p1.q = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));
  o.motion = {{0.0, p0}, {1.0, p1}};
  s.objects.push_back(o);
  const auto boxes = instanceBoxes(s);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_TRUE(boxes[0].moving);
  const OrientedBox at0 = boxAt(s, boxes[0], 0.0), at1 = boxAt(s, boxes[0], 1.0);
  EXPECT_NEAR((at0.centre - boxes[0].box.centre).norm(), 0, 1e-12);
  // the box moved exactly as the object: compare with the box of the moved object
  Scene moved = boxScene();
  moved.objects.push_back(Object::make("chair", 0, 0, o.transformAt(1.0), 5, 9));
  const OrientedBox expect = instanceBoxes(moved)[0].box;
  EXPECT_NEAR((at1.centre - expect.centre).norm(), 0, 1e-9);
  EXPECT_NEAR(at1.yaw(), expect.yaw(), 1e-9);
  EXPECT_NEAR((at1.size - expect.size).norm(), 0, 1e-9);
}

TEST(InstanceBoxes, DefaultSceneBoxesHoldTheirGeometry) {
  const Scene s = makeDefaultScene();
  const auto boxes = instanceBoxes(s);
  ASSERT_FALSE(boxes.empty());
  for (const InstanceBox& b : boxes) {
    SCOPED_TRACE(b.name);
    EXPECT_GT(b.instance, 0);
    EXPECT_TRUE(b.box.centre.allFinite());
    EXPECT_GE(b.box.size.minCoeff(), 0.0);
    // gravity-aligned
    EXPECT_NEAR((b.box.q_world_box * Vec3::UnitZ() - Vec3::UnitZ()).norm(), 0, 1e-9);
  }
}

}  // namespace
}  // namespace inet
