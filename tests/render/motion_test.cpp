// Moving objects (Object::motion): ground truth places them at the frame's time, and the path
// tracer blurs them over the exposure. The scene: a 0.2 m white square sliding along x from
// x = -0.5 (t = 0 s) to x = +0.5 (t = 1 s), lit by a sun overhead, seen from 1 m above by a
// 64 x 64 camera whose image spans exactly [-1, 1]^2 on the plane z = 0 (32 px per metre); no
// floor, so everything but the box is black and has instance 0.
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "scene/primitives.h"

namespace inet {
namespace {

constexpr int kSize = 64;
constexpr double kSide = 0.2;
constexpr float kAlbedo = 0.8f, kSunIrradiance = 2.f;

Scene slidingBox() {
  Scene s;
  Mesh box = makePrimitive("quad", {}, "t", "box");
  box.id = "box";
  s.meshes = {box};
  Material m;
  m.id = "white";
  m.albedo = Vec3f::Constant(kAlbedo);
  s.materials = {m};
  Object o;
  o.name = "box";
  o.mesh = 0;
  o.material = 0;
  o.nyu40 = 40;
  o.instance = 7;
  o.T_world_object = Mat4::Identity();
  o.T_world_object.diagonal() << kSide, kSide, 1.0, 1.0;
  ObjectKeyframe a, b;
  a.t_s = 0.0;
  a.pose.t = Vec3(-0.5, 0, 0);
  b.t_s = 1.0;
  b.pose.t = Vec3(0.5, 0, 0);
  o.motion = {a, b};
  s.objects = {o};
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = -Vec3::UnitZ();
  sun.intensity = kSunIrradiance;
  s.lights = {sun};
  return s;
}

LensModel topLens() {
  CameraIntrinsics K;
  K.width = K.height = kSize;
  K.fx = K.fy = kSize / 2.0;
  K.cx = K.cy = kSize / 2.0;
  return LensModel::pinhole(K);
}

CameraExposure topExposure(double open_s, double exposure_s) {
  CameraExposure ex =
      CameraExposure::fixed(Pose::lookAt(Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3::UnitY()),
                            static_cast<TimeNs>(std::llround(open_s * 1e9)));
  ex.shutter.exposure_ns = static_cast<TimeNs>(std::llround(exposure_s * 1e9));
  return ex;
}

/// Centroid (x, y) in pixels of the pixels whose instance is `id`, and their count.
Eigen::Vector3d instanceCentroid(const Frame& f, uint16_t id) {
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  for (int y = 0; y < f.instance.height; ++y)
    for (int x = 0; x < f.instance.width; ++x)
      if (f.instance.at(x, y) == id) acc += Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
  return {acc.x() / acc.z(), acc.y() / acc.z(), acc.z()};
}

TEST(Motion, GroundTruthPlacesTheObjectAtTheFrameTime) {
  Renderer r(slidingBox());
  RenderOptions opt;
  opt.passes = static_cast<PassMask>(Pass::Instance);
  for (double t : {0.0, 0.25, 0.6, 1.0, 1.5}) {
    SCOPED_TRACE(t);
    Frame f;
    r.render(topLens(), topExposure(t, 0.0), opt, 0, f);
    const double x = std::clamp(t, 0.0, 1.0) - 0.5;  // holds after the last keyframe
    // 32 px per metre: the square covers 6.4 x 6.4 px around column 32 + 32 x
    const Eigen::Vector3d c = instanceCentroid(f, 7);
    EXPECT_NEAR(c.x(), 32.0 + 32.0 * x, 0.3);
    EXPECT_NEAR(c.y(), 32.0, 0.3);
    EXPECT_NEAR(c.z(), std::pow(kSide * 32.0, 2), 8.0) << "pixels covered";
  }
}

TEST(Motion, ExposureBlursTheObjectAndKeepsItsEnergy) {
  Renderer r(slidingBox());
  RenderOptions opt;
  opt.spp = 64;
  opt.max_bounces = 1;
  opt.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Instance);
  Frame blurred, still;
  r.render(topLens(), topExposure(0.0, 1.0), opt, 0, blurred);
  r.render(topLens(), topExposure(0.5, 0.0), opt, 0, still);
  auto mean = [](const ImageF& img) {
    double s = 0;
    for (size_t i = 0; i < img.pixelCount(); ++i) s += img.data[3 * i + 1];
    return s / img.pixelCount();
  };
  // the whole box stays in view all the time: blur moves light around, it adds none
  EXPECT_NEAR(mean(blurred.rgb), mean(still.rgb), 0.02 * mean(still.rgb));
  // the square sweeps x in [-0.6, 0.6]; a point with |x| < 0.4 is under it for 0.2 s of the
  // 1 s exposure, so it shows 20% of the lit square's radiance (rows inside its y extent)
  const double lit = kAlbedo / M_PI * kSunIrradiance;
  double band = 0;
  int n = 0;
  for (int y = 30; y < 34; ++y)
    for (int x = 32 - 12; x < 32 + 12; ++x, ++n) band += blurred.rgb.at(x, y, 1);
  EXPECT_NEAR(band / n, 0.2 * lit, 0.01 * lit);
  // ground truth of a global shutter: the middle of the exposure, t = 0.5 s, x = 0
  const Eigen::Vector3d c = instanceCentroid(blurred, 7);
  EXPECT_NEAR(c.x(), 32.0, 0.3);
}

TEST(Motion, StaticScenesTraceTheSameWithOrWithoutAWindow) {
  // a scene without motion ignores the exposure's scene time: same bytes at t = 0 and t = 3
  Scene s = slidingBox();
  s.objects[0].motion.clear();
  Renderer r(s);
  RenderOptions opt;
  opt.spp = 4;
  Frame a, b;
  r.render(topLens(), topExposure(0.0, 0.0), opt, 0, a);
  r.render(topLens(), topExposure(3.0, 0.0), opt, 0, b);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.instance, b.instance);
}

}  // namespace
}  // namespace inet
