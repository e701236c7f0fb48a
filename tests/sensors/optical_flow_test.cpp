// Optical flow ground truth (sensors/optical_flow.h), SENSORS.md section 5:
//  - analytic scenes: translation toward a fronto-parallel plane (forward, backward and
//    instantaneous flow in closed form), a wall and a box (occlusion against ray-cast
//    visibility), rotations of a fisheye, a panorama and a distorted pinhole;
//  - instantaneous flow x dt against two-frame reprojection of spline poses;
// The acceptance test on rendered frames is in optical_flow_acceptance_test.cpp.
#include "sensors/optical_flow.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "../temp_dir.h"
#include "core/color.h"
#include "core/error.h"
#include "core/image_io.h"
#include "procedural/apartment.h"
#include "flow_test_util.h"
#include "render/renderer.h"
#include "scene/primitives.h"
#include "sensors/bspline.h"

namespace inet {
namespace {

using test::axisAngle;
using test::kDeg;

// ---- an analytic scene: planes parallel to the image plane of camera k --------------------

/// A rectangle on the world plane z = const (the world is camera k's frame), or the whole plane
/// when unbounded.
struct Rect {
  double z = 3;
  double x0 = -1e9, x1 = 1e9, y0 = -1e9, y1 = 1e9;
  uint16_t instance = 1;
};

struct Raster {
  ImageF depth;
  ImageU16 instance;
};

/// z-depth and instance seen from T_world_camera through pixel centres (nearest rect wins).
/// `offsets[i]` translates rects[i] (world).
Raster rasterise(const CameraIntrinsics& K, const Pose& T_world_camera,
                 const std::vector<Rect>& rects, const std::vector<Vec3>& offsets) {
  Raster r{ImageF(K.width, K.height, 1, 0.f), ImageU16(K.width, K.height, 1, 0)};
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      const Vec3 d = T_world_camera.q * K.rayCamera(x + 0.5, y + 0.5);
      double best = 1e30;
      for (size_t i = 0; i < rects.size(); ++i) {
        const Rect& q = rects[i];
        const Vec3 o = T_world_camera.t - offsets[i];  // move the camera instead of the rect
        const double s = (q.z - o.z()) / d.z();
        if (!(s > 0) || s >= best) continue;
        const Vec3 p = o + s * d;
        if (p.x() < q.x0 || p.x() > q.x1 || p.y() < q.y0 || p.y() > q.y1) continue;
        best = s;  // the ray parameter is the z-depth: the camera ray has z = 1
        r.depth.at(x, y) = static_cast<float>(s);
        r.instance.at(x, y) = q.instance;
      }
    }
  return r;
}

// ---- 1. translation along z toward a fronto-parallel plane ---------------------------------

TEST(OpticalFlow, TranslationTowardAPlaneMatchesTheClosedForm) {
  // camera moves tz along its axis toward a plane at Z: a point at u goes to
  // cx + (u - cx) Z / (Z - tz), so flow_u = (u - cx) tz / (Z - tz) (the same in v)
  const CameraIntrinsics K = CameraIntrinsics::centred(640, 480, 600);
  const double Z = 3.0, tz = 0.1;
  const ImageF depth0(K.width, K.height, 1, static_cast<float>(Z));
  const ImageF depth1(K.width, K.height, 1, static_cast<float>(Z - tz));
  const ImageU16 none;
  Pose T1;
  T1.t = Vec3(0, 0, tz);
  const FlowField f = forwardFlow({depth0, none, Pose()}, {depth1, none, T1}, LensModel::pinhole(K),
                                  ObjectMotion{});
  double worst = 0;
  int outside_mismatch = 0, occluded = 0;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      const double du = (x + 0.5 - K.cx) * tz / (Z - tz), dv = (y + 0.5 - K.cy) * tz / (Z - tz);
      ASSERT_EQ(f.valid.at(x, y), 1);
      worst =
          std::max({worst, std::abs(f.flow.at(x, y, 0) - du), std::abs(f.flow.at(x, y, 1) - dv)});
      const double u1 = x + 0.5 + du, v1 = y + 0.5 + dv;
      const bool outside = u1 < 0 || u1 >= K.width || v1 < 0 || v1 >= K.height;
      outside_mismatch += outside != (f.occluded.at(x, y) == 1);
      occluded += f.occluded.at(x, y);
    }
  std::printf("forward: largest error %.3g px; %d pixels leave the image\n", worst, occluded);
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(outside_mismatch, 0) << "occluded = leaves the image, nothing else";
  EXPECT_GT(occluded, 0);

  // backward (k+1 -> k): the plane at Z - tz goes back to Z, flow = -(u - cx) tz / Z
  const FlowField b = backwardFlow({depth0, none, Pose()}, {depth1, none, T1},
                                   LensModel::pinhole(K), ObjectMotion{});
  worst = 0;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      ASSERT_EQ(b.valid.at(x, y), 1);
      ASSERT_EQ(b.occluded.at(x, y), 0) << "zooming out keeps everything in view";
      worst = std::max({worst, std::abs(b.flow.at(x, y, 0) + (x + 0.5 - K.cx) * tz / Z),
                        std::abs(b.flow.at(x, y, 1) + (y + 0.5 - K.cy) * tz / Z)});
    }
  std::printf("backward: largest error %.3g px\n", worst);
  EXPECT_LT(worst, 1e-4);

  // instantaneous: udot = (u - cx) vz / Z
  const CameraVelocity vel{Vec3(0, 0, 0.5), Vec3::Zero()};
  const ImageF inst = instantaneousFlow(depth0, K, vel);
  worst = 0;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x)
      worst = std::max({worst, std::abs(inst.at(x, y, 0) - (x + 0.5 - K.cx) * 0.5 / Z),
                        std::abs(inst.at(x, y, 1) - (y + 0.5 - K.cy) * 0.5 / Z)});
  std::printf("instantaneous: largest error %.3g px/s\n", worst);
  EXPECT_LT(worst, 1e-4);
  // the largest speed is at the corners: |corner - c| vz / Z
  EXPECT_NEAR(maxFlowSpeed(depth0, K, vel), std::hypot(319.5, 239.5) * 0.5 / Z, 1e-9);
}

// ---- 2. instantaneous flow x dt against two-frame reprojection -----------------------------

TEST(OpticalFlow, InstantaneousFlowMatchesTwoFrameReprojectionOfSplinePoses) {
  const CameraIntrinsics K = CameraIntrinsics::centred(320, 240, 300);
  // a hand-held-like spline: knots every 50 ms, ~0.5 m/s and ~40 deg/s
  std::vector<Pose> knots;
  for (int j = 0; j < 8; ++j) {
    Pose p;
    p.t = Vec3(0.025 * j, 0.01 * std::sin(j), 0.015 * j);
    p.q = axisAngle(Vec3(0.2, 1.0, 0.1), 0.035 * j) * axisAngle(Vec3::UnitX(), 0.01 * j * j);
    knots.push_back(p);
  }
  const TimeNs t0 = 0, dt = 50'000'000;
  const PoseSpline spline = PoseSpline::interpolate(t0, dt, knots);
  const TimeNs t = 3 * dt + 17'000'000, h = 500'000;  // 0.5 ms
  const SplineState s = spline.evaluate(t);
  const Pose T_now{s.q_world_body, s.p_world};
  const CameraVelocity vel = cameraVelocity(s);
  std::printf("camera speed %.3f m/s, %.1f deg/s\n", vel.v_cam.norm(), vel.w_cam.norm() / kDeg);
  // a slanted wall: n . X = 2 in camera coordinates at t, so z = 2 / (n . ray), 1.5 .. 3 m
  const Vec3 n = Vec3(0.15, -0.1, 1.0).normalized();
  ImageF depth(K.width, K.height, 1);
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x)
      depth.at(x, y) = static_cast<float>(2.0 / n.dot(K.rayCamera(x + 0.5, y + 0.5)));
  const ImageU16 none;
  const LensModel lens = LensModel::pinhole(K);
  // forward flow to t + h and to t - h, both from the depth at t
  const FlowField fwd =
      forwardFlow({depth, none, T_now}, {depth, none, spline.pose(t + h)}, lens, {});
  const FlowField bwd =
      forwardFlow({depth, none, T_now}, {depth, none, spline.pose(t - h)}, lens, {});
  const ImageF inst = instantaneousFlow(depth, K, vel);
  double worst_fwd = 0, worst_central = 0, largest = 0;
  const double h_s = 1e-9 * h;
  for (size_t i = 0; i < depth.pixelCount(); ++i)
    for (int c = 0; c < 2; ++c) {
      const double inst_px = inst.data[2 * i + c] * h_s;
      largest = std::max(largest, std::abs(inst_px));
      worst_fwd = std::max(worst_fwd, std::abs(fwd.flow.data[2 * i + c] - inst_px));
      // central difference (x(t+h) - x(t-h)) / 2: the error is O(h^3)
      const double central = 0.5 * (fwd.flow.data[2 * i + c] - bwd.flow.data[2 * i + c]);
      worst_central = std::max(worst_central, std::abs(central - inst_px));
    }
  std::printf(
      "flow over 0.5 ms up to %.3f px; |inst dt - forward| <= %.3g px, "
      "|inst dt - central| <= %.3g px\n",
      largest, worst_fwd, worst_central);
  EXPECT_GT(largest, 0.25) << "the test moves the camera enough to matter";
  EXPECT_LT(worst_fwd, 1e-3);
  EXPECT_LT(worst_central, 1e-5);
  double speed = 0;
  for (size_t i = 0; i < depth.pixelCount(); ++i)
    speed = std::max(speed, std::hypot(double{inst.data[2 * i]}, double{inst.data[2 * i + 1]}));
  EXPECT_NEAR(maxFlowSpeed(depth, K, vel), speed, 1e-3 * speed);
}

TEST(OpticalFlow, PixelsWithoutDepthAreAThousandMetresAwayInTheInstantaneousFlow) {
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 60);
  const ImageF none(K.width, K.height, 1, 0.f), far(K.width, K.height, 1, 1000.f);
  const CameraVelocity vel{Vec3(1, 0.5, 2), Vec3(0.3, -0.2, 0.1)};
  EXPECT_EQ(instantaneousFlow(none, K, vel), instantaneousFlow(far, K, vel));
  // a pure rotation about the optical axis: |udot| = w r at the corner (depth plays no part)
  const CameraVelocity roll{Vec3::Zero(), Vec3(0, 0, 2.0)};
  EXPECT_NEAR(maxFlowSpeed(none, K, roll), 2.0 * std::hypot(31.5, 23.5), 1e-9);
}

// ---- occlusion: a closer object covers part of the background in frame k+1 ------------------

/// Is world point X (seen in frame k) visible from camera c1, with the rects at `offsets`?
bool rayCastVisible(const Vec3& X, const Pose& T_world_c1, const std::vector<Rect>& rects,
                    const std::vector<Vec3>& offsets, uint16_t own) {
  const Vec3 c = T_world_c1.t;
  for (size_t i = 0; i < rects.size(); ++i) {
    if (rects[i].instance == own) continue;
    const Rect& q = rects[i];
    const Vec3 o = c - offsets[i], d = X - c;
    const double s = (q.z - o.z()) / d.z();
    if (!(s > 0 && s < 1 - 1e-9)) continue;
    const Vec3 p = o + s * d;
    if (p.x() >= q.x0 && p.x() <= q.x1 && p.y() >= q.y0 && p.y() <= q.y1) return false;
  }
  return true;
}

/// Runs forward flow on wall + box, compares `occluded` with ray-cast visibility of each pixel's
/// point, ignoring pixels within 1.5 px of a depth edge of frame k+1 at the point's landing spot.
void checkOcclusion(const Pose& T_world_c1, const Vec3& box_move, int expect_min_occluded) {
  const CameraIntrinsics K = CameraIntrinsics::centred(200, 150, 100);
  const std::vector<Rect> rects = {Rect{3.0, -1e9, 1e9, -1e9, 1e9, 1},
                                   Rect{1.0, -0.2, 0.2, -0.15, 0.15, 2}};
  const Raster r0 = rasterise(K, Pose(), rects, {Vec3::Zero(), Vec3::Zero()});
  const Raster r1 = rasterise(K, T_world_c1, rects, {Vec3::Zero(), box_move});
  ObjectMotion motion;
  if (box_move.norm() > 0) motion.delta[2] = Pose{Quat::Identity(), box_move};
  const LensModel lens = LensModel::pinhole(K);
  const FlowField f = forwardFlow({r0.depth, r0.instance, Pose()},
                                  {r1.depth, r1.instance, T_world_c1}, lens, motion);
  int occluded = 0, compared = 0, wrong = 0, box_occluded = 0;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      ASSERT_EQ(f.valid.at(x, y), 1);
      const uint16_t inst = r0.instance.at(x, y);
      const Vec3 X =
          r0.depth.at(x, y) * K.rayCamera(x + 0.5, y + 0.5) + (inst == 2 ? box_move : Vec3::Zero());
      Eigen::Vector2d uv;
      ASSERT_TRUE(project(lens, T_world_c1.inverse() * X, uv));
      const bool inside = uv.x() >= 0 && uv.x() < K.width && uv.y() >= 0 && uv.y() < K.height;
      const bool truth =
          !inside || !rayCastVisible(X, T_world_c1, rects, {Vec3::Zero(), box_move}, inst);
      occluded += f.occluded.at(x, y);
      box_occluded += inst == 2 && f.occluded.at(x, y);
      // skip landing spots next to a depth edge of frame k+1 (sub-pixel ambiguity)
      bool near_edge = false;
      if (inside) {
        const int cx = static_cast<int>(uv.x()), cy = static_cast<int>(uv.y());
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const int xx = std::clamp(cx + dx, 0, K.width - 1),
                      yy = std::clamp(cy + dy, 0, K.height - 1);
            near_edge = near_edge || r1.instance.at(xx, yy) != r1.instance.at(cx, cy);
          }
      }
      if (near_edge) continue;
      ++compared;
      wrong += truth != (f.occluded.at(x, y) == 1);
    }
  std::printf(
      "occluded %d px (box %d), %d compared away from edges, %d disagree with ray casting\n",
      occluded, box_occluded, compared, wrong);
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(occluded, expect_min_occluded);
  EXPECT_EQ(box_occluded, 0) << "the nearest object is never hidden";
}

TEST(OpticalFlow, OcclusionFlagsTheWallAMovingBoxCoversInTheNextFrame) {
  // static camera; the box (z = 1 m, 40 px wide at f = 100) moves 0.1 m right = 10 px: the wall
  // strip of 10 x 30 px right of it is covered in k+1
  checkOcclusion(Pose(), Vec3(0.1, 0, 0), 10 * 30);
}

TEST(OpticalFlow, OcclusionFlagsTheWallAStaticBoxCoversByParallax) {
  // the camera moves 0.1 m right (and turns 1 degree): the box shifts 10 px left, the wall 3.3 px,
  // so a 6.7 px strip of wall left of the box is covered in k+1 (plus pixels leaving the image)
  Pose T1;
  T1.t = Vec3(0.1, 0, 0);
  T1.q = axisAngle(Vec3::UnitY(), 1 * kDeg);
  checkOcclusion(T1, Vec3::Zero(), 6 * 30);
}

TEST(OpticalFlow, InstanceMismatchAloneFlagsOcclusion) {
  // same depth, other instance at the landing spot (a poster swapped in): occluded
  const CameraIntrinsics K = CameraIntrinsics::centred(40, 30, 40);
  const ImageF depth(K.width, K.height, 1, 2.f);
  const ImageU16 a(K.width, K.height, 1, 5), b(K.width, K.height, 1, 6);
  const FlowField f =
      forwardFlow({depth, a, Pose()}, {depth, b, Pose()}, LensModel::pinhole(K), {});
  EXPECT_EQ(f.toString(), "FlowField[40x30, 1200 valid, 1200 occluded, max |flow| 0.000 px]");
  // and the same instance at the same depth is visible
  const FlowField g =
      forwardFlow({depth, a, Pose()}, {depth, a, Pose()}, LensModel::pinhole(K), {});
  EXPECT_EQ(g.toString(), "FlowField[40x30, 1200 valid, 0 occluded, max |flow| 0.000 px]");
}

// ---- other lens models -----------------------------------------------------------------------

TEST(OpticalFlow, FisheyeRollRotatesPixelsAboutTheCentre) {
  // camera k+1 = camera k rolled by theta about its axis: image points turn by -theta about the
  // centre (equidistant fisheye, fx = fy), whatever the depth
  const LensModel lens = LensModel::fisheye(200, 180);
  const CameraIntrinsics& K = lens.K;
  const double theta = 10 * kDeg;
  ImageF depth(K.width, K.height, 1, 0.f);  // a sphere of radius 2 m around the camera
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      CameraRay ray;
      if (generateRay(lens, x + 0.5, y + 0.5, kLensCentre, ray)) depth.at(x, y) = 2.f;
    }
  const ImageU16 none;
  Pose T1;
  T1.q = axisAngle(Vec3::UnitZ(), theta);
  FlowOptions opt;
  opt.depth_kind = DepthKind::RayDistance;
  const FlowField f = forwardFlow({depth, none, Pose()}, {depth, none, T1}, lens, {}, opt);
  double worst = 0;
  int valid = 0, occluded = 0;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      if (!f.valid.at(x, y)) {
        EXPECT_EQ(depth.at(x, y), 0.f);
        continue;
      }
      ++valid;
      occluded += f.occluded.at(x, y);
      const double px = x + 0.5 - K.cx, py = y + 0.5 - K.cy;
      const double ex = std::cos(theta) * px + std::sin(theta) * py - px;
      const double ey = -std::sin(theta) * px + std::cos(theta) * py - py;
      worst =
          std::max({worst, std::abs(f.flow.at(x, y, 0) - ex), std::abs(f.flow.at(x, y, 1) - ey)});
    }
  std::printf("fisheye roll: %d valid, %d occluded, largest error %.3g px\n", valid, occluded,
              worst);
  EXPECT_GT(valid, 0.75 * K.width * K.height);  // pi/4 of the square is the image circle
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(occluded, 0) << "the circle maps onto itself";
}

TEST(OpticalFlow, PanoramaYawShiftsEveryPixelTheShortWayRound) {
  const LensModel lens = LensModel::panorama(360, 180);
  const double alpha = 0.3;  // rad; every pixel moves -alpha fx in u, wrapping at the seam
  const ImageF depth(lens.K.width, lens.K.height, 1, 2.f);
  const ImageU16 inst(lens.K.width, lens.K.height, 1, 3);
  Pose T1;
  T1.q = axisAngle(Vec3::UnitY(), alpha);
  FlowOptions opt;
  opt.depth_kind = DepthKind::RayDistance;
  const FlowField f = forwardFlow({depth, inst, Pose()}, {depth, inst, T1}, lens, {}, opt);
  double worst = 0;
  for (int y = 0; y < lens.K.height; ++y)
    for (int x = 0; x < lens.K.width; ++x) {
      ASSERT_EQ(f.valid.at(x, y), 1);
      ASSERT_EQ(f.occluded.at(x, y), 0) << x << "," << y << ": the panorama wraps";
      worst = std::max({worst, std::abs(f.flow.at(x, y, 0) + alpha * lens.K.fx),
                        double{std::abs(f.flow.at(x, y, 1))}});
    }
  std::printf("panorama yaw: largest error %.3g px\n", worst);
  EXPECT_LT(worst, 1e-3);  // rows next to the poles carry atan2 round-off
}

TEST(OpticalFlow, DistortedPinholeRotationFlowIsIndependentOfDepth) {
  LensModel lens = LensModel::pinhole(CameraIntrinsics::centred(160, 120, 120));
  lens.k1 = -0.2;
  lens.k2 = 0.05;
  lens.p1 = 0.001;
  lens.validate("test");
  const ImageU16 none;
  ImageF near(160, 120, 1), far(160, 120, 1, 40.f);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) near.at(x, y) = 0.5f + 0.01f * (x + y);
  // no motion: no flow (generateRay and project invert each other)
  const FlowField zero = forwardFlow({near, none, Pose()}, {near, none, Pose()}, lens, {});
  float largest = 0;
  for (float v : zero.flow.data) largest = std::max(largest, std::abs(v));
  EXPECT_LT(largest, 1e-5);
  // a rotation: the same flow whatever the depth
  Pose T1;
  T1.q = axisAngle(Vec3(0.3, 1, 0.2), 2 * kDeg);
  const FlowField a = forwardFlow({near, none, Pose()}, {near, none, T1}, lens, {});
  const FlowField b = forwardFlow({far, none, Pose()}, {far, none, T1}, lens, {});
  double worst = 0;
  for (size_t i = 0; i < a.flow.data.size(); ++i)
    if (a.valid.data[i / 2] && b.valid.data[i / 2])
      worst = std::max(worst, double{std::abs(a.flow.data[i] - b.flow.data[i])});
  EXPECT_LT(worst, 1e-4);
}

// ---- warping, colour coding, motion tables --------------------------------------------------

TEST(OpticalFlow, WarpBackwardIsExactOnLinearImages) {
  // bilinear interpolation reproduces a linear function exactly
  const int W = 30, H = 20;
  ImageF next(W, H, 2);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      next.at(x, y, 0) = 0.1f * (x + 0.5f) + 0.3f * (y + 0.5f);
      next.at(x, y, 1) = 2.0f - 0.05f * (x + 0.5f);
    }
  FlowField f{ImageF(W, H, 2), ImageU8(W, H, 1, 1), ImageU8(W, H, 1, 0)};
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      f.flow.at(x, y, 0) = 2.25f;
      f.flow.at(x, y, 1) = -1.5f;
    }
  f.valid.at(3, 4) = 0;
  const ImageF warped = warpBackward(next, f);
  for (int y = 2; y < H; ++y)
    for (int x = 0; x < W - 3; ++x) {
      if (x == 3 && y == 4) {
        EXPECT_EQ(warped.at(x, y, 0), 0.f) << "invalid pixels are 0";
        continue;
      }
      const float u = x + 0.5f + 2.25f, v = y + 0.5f - 1.5f;
      EXPECT_NEAR(warped.at(x, y, 0), 0.1f * u + 0.3f * v, 1e-5);
      EXPECT_NEAR(warped.at(x, y, 1), 2.0f - 0.05f * u, 1e-5);
    }
  EXPECT_EQ(warped.at(W - 1, 5, 0), 0.f) << "lands outside the image: 0";
}

TEST(OpticalFlow, FlowToColorFollowsTheMiddleburyWheel) {
  FlowField f{ImageF(6, 1, 2, 0.f), ImageU8(6, 1, 1, 1), ImageU8(6, 1, 1, 0)};
  f.flow.at(1, 0, 0) = 4;   // right (v = +0: atan2(-0, -1) = -pi), full scale: wheel[0], red
  f.flow.at(2, 0, 0) = -4;  // left: wheel index 27 = cyan-blue (0, 255 - 255*2/11, 255)
  f.flow.at(3, 0, 1) = 2;   // down, half scale: index 13.5, halfway to white
  f.flow.at(4, 0, 0) = 8;   // beyond max_px: darkened to 75 % (255 * 0.75 = 191.25)
  f.valid.at(5, 0) = 0;     // invalid: black
  const ImageU8 c = flowToColor(f, 4.0);
  auto rgb = [&](int x) { return std::array<int, 3>{c.at(x, 0, 0), c.at(x, 0, 1), c.at(x, 0, 2)}; };
  EXPECT_EQ(rgb(0), (std::array<int, 3>{255, 255, 255})) << "no motion is white";
  EXPECT_EQ(rgb(1), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(rgb(2), (std::array<int, 3>{0, 255 - 255 * 2 / 11, 255}));
  // index 13.5 between (255, 255*13/15, 0) and (255, 255*14/15, 0), then 1 - 0.5 (1 - col)
  const double g = 0.5 * (255 * 13 / 15 + 255 * 14 / 15) / 255.0;
  EXPECT_EQ(rgb(3), (std::array<int, 3>{255, static_cast<int>(255 * (1 - 0.5 * (1 - g))), 127}));
  EXPECT_EQ(rgb(4), (std::array<int, 3>{191, 0, 0}));
  EXPECT_EQ(rgb(5), (std::array<int, 3>{0, 0, 0}));
}

Scene twoPartScene() {
  Scene s;
  s.meshes = {makePrimitive("box", {}, "t", "box")};
  s.meshes[0].id = "box";
  Material m;
  m.id = "m";
  s.materials = {m};
  Mat4 scaled = Mat4::Identity();
  scaled.diagonal() << 0.5, 0.2, 0.1, 1;
  scaled.block<3, 1>(0, 3) = Vec3(1, 2, 0.4);
  s.objects = {Object::make("top", 0, 0, scaled, 7, 4),
               Object::make("leg", 0, 0, Mat4::Identity(), 7, 4),
               Object::make("lamp", 0, 0, Mat4::Identity(), 35, 9)};
  ObjectKeyframe a, b;
  a.t_s = 1.0;
  b.t_s = 2.0;
  b.pose.t = Vec3(0.2, 0, 0);
  b.pose.q = axisAngle(Vec3::UnitZ(), 30 * kDeg);
  s.objects[0].motion = s.objects[1].motion = {a, b};
  return s;
}

TEST(OpticalFlow, ObjectMotionBetweenSceneTimes) {
  const Scene s = twoPartScene();
  const ObjectMotion m = objectMotionBetween(s, 1.25, 1.75);
  ASSERT_EQ(m.delta.size(), 1u) << m.toString();
  ASSERT_TRUE(m.delta.count(4));
  // keyframe poses at alpha 0.25 and 0.75: delta = P(0.75) P(0.25)^-1, independent of the
  // rest placement (the top is scaled, the leg is not, both give this)
  auto P = [](double alpha) {
    return Pose{axisAngle(Vec3::UnitZ(), alpha * 30 * kDeg), Vec3(0.2 * alpha, 0, 0)};
  };
  const Pose expect = P(0.75) * P(0.25).inverse();
  const Pose& d = m.delta.at(4);
  EXPECT_LT((d.t - expect.t).norm(), 1e-12);
  EXPECT_LT(d.q.angularDistance(expect.q), 1e-12);
  const Pose back = m.inverse().delta.at(4) * d;
  EXPECT_LT(back.t.norm() + back.q.angularDistance(Quat::Identity()), 1e-12);
  // before the first keyframe nothing moves
  EXPECT_LT(objectMotionBetween(s, 0.0, 0.5).delta.at(4).t.norm(), 1e-15);
  // parts of one instance that move differently cannot have one flow
  Scene bad = s;
  bad.objects[1].motion[1].pose.t = Vec3(0.3, 0, 0);
  try {
    objectMotionBetween(bad, 1.0, 2.0, "layout.json");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "layout.json");
    EXPECT_EQ(e.field(), "objects['leg'].motion") << e.what();
  }
  bad.objects[1].motion.clear();  // a static part of a moving instance: the same problem
  EXPECT_THROW(objectMotionBetween(bad, 1.0, 2.0), InputError);
}

TEST(OpticalFlow, MismatchedImageSizesAreInputErrors) {
  const CameraIntrinsics K = CameraIntrinsics::centred(40, 30, 40);
  const ImageF depth(40, 30, 1, 1.f), small(20, 30, 1, 1.f);
  const ImageU16 none, inst_small(20, 30, 1, 0);
  const LensModel lens = LensModel::pinhole(K);
  EXPECT_THROW(forwardFlow({small, none, Pose()}, {depth, none, Pose()}, lens, {}), InputError);
  EXPECT_THROW(forwardFlow({depth, inst_small, Pose()}, {depth, none, Pose()}, lens, {}),
               InputError);
  FlowOptions opt;
  opt.occlusion_rel_tol = -1;
  EXPECT_THROW(forwardFlow({depth, none, Pose()}, {depth, none, Pose()}, lens, {}, opt),
               InputError);
}

}  // namespace
}  // namespace inet
