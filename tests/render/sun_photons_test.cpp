// Sun photons (path_tracer.cpp, RenderOptions::sun_photons): a closed grey room whose only
// light is the sun through two glazed windows (so the photons fall into groups of unequal
// shares), seen toward the walls their patches light. The photons keep the mean of plain path
// tracing and cut its noise, with the same bytes on any thread count.
#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>

#include "render/renderer.h"
#include "scene/primitives.h"
#include "image_stats.h"

namespace inet {
namespace {

/// A room 4 x 3 x 2.5 m of grey slabs (walls 10 cm thick), with 1 x 1 m windows closed by panes
/// in the walls at x = +2 and y = -1.5, under a sun low enough to shine through both onto the
/// floor (through the second at a grazing angle: the photons' groups get unequal shares).
Scene sunlitRoom() {
  Scene s;
  Mesh box = makePrimitive("box", {}, "test", "box");
  box.id = "box";
  Mesh quad = makePrimitive("quad", {}, "test", "quad");
  quad.id = "quad";
  s.meshes = {box, quad};
  Material plaster, glass;
  plaster.id = "plaster";
  plaster.albedo = Vec3f::Constant(0.6f);
  glass.id = "pane";
  glass.type = MaterialType::ThinDielectric;
  glass.ior = 1.5f;
  s.materials = {plaster, glass};
  auto slab = [&](const char* name, Vec3 lo, Vec3 hi) {
    const Mat4 T = (Eigen::Translation3d(0.5 * (lo + hi)) * Eigen::Scaling(hi - lo)).matrix();
    s.objects.push_back(Object::make(name, 0, 0, T, 1, static_cast<int>(s.objects.size()) + 1));
  };
  const double t = 0.1;
  slab("floor", Vec3(-2 - t, -1.5 - t, -t), Vec3(2 + t, 1.5 + t, 0));
  slab("ceiling", Vec3(-2 - t, -1.5 - t, 2.5), Vec3(2 + t, 1.5 + t, 2.5 + t));
  slab("west", Vec3(-2 - t, -1.5, 0), Vec3(-2, 1.5, 2.5));
  // the south wall around a window of x in [-1, 0], z in [0.75, 1.75]
  slab("south_low", Vec3(-2, -1.5 - t, 0), Vec3(2, -1.5, 0.75));
  slab("south_high", Vec3(-2, -1.5 - t, 1.75), Vec3(2, -1.5, 2.5));
  slab("south_left", Vec3(-2, -1.5 - t, 0.75), Vec3(-1, -1.5, 1.75));
  slab("south_right", Vec3(0, -1.5 - t, 0.75), Vec3(2, -1.5, 1.75));
  slab("north", Vec3(-2, 1.5, 0), Vec3(2, 1.5 + t, 2.5));
  // the east wall around a window of y in [-0.5, 0.5], z in [0.75, 1.75]
  slab("east_low", Vec3(2, -1.5, 0), Vec3(2 + t, 1.5, 0.75));
  slab("east_high", Vec3(2, -1.5, 1.75), Vec3(2 + t, 1.5, 2.5));
  slab("east_left", Vec3(2, -1.5, 0.75), Vec3(2 + t, -0.5, 1.75));
  slab("east_right", Vec3(2, 0.5, 0.75), Vec3(2 + t, 1.5, 1.75));
  Mat4 P = Mat4::Identity();  // the unit quad (normal +z) turned to face +x, in the window
  P.block<3, 3>(0, 0) << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  P.block<3, 1>(0, 3) = Vec3(2.05, 0, 1.25);
  s.objects.push_back(Object::make("pane", 1, 1, P, 9, static_cast<int>(s.objects.size()) + 1));
  Mat4 Q = Mat4::Identity();  // the unit quad turned to face -y, in the south window
  Q.block<3, 3>(0, 0) << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  Q.block<3, 1>(0, 3) = Vec3(-0.5, -1.55, 1.25);
  s.objects.push_back(Object::make("pane2", 1, 1, Q, 9, static_cast<int>(s.objects.size()) + 1));
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(-1, 0.25, -0.7).normalized();
  sun.intensity = 350.f;
  s.lights = {sun};
  return s;
}

TEST(SunPhotons, IndirectSunlightKeepsItsMeanWithLessNoiseAndTheSameBytesOnAnyThreadCount) {
  const Scene s = sunlitRoom();
  Renderer r(s);
  const CameraIntrinsics K = CameraIntrinsics::centred(48, 36, 40);
  // from the east window's side toward the west wall, the floor and the ceiling
  const Pose pose = Pose::lookAt(Vec3(1.6, 0.9, 1.6), Vec3(-2, -0.3, 1.3), Vec3::UnitZ());
  auto render = [&](int spp, bool photons, uint64_t seed, int bounces = 4) {
    RenderOptions opt;
    opt.spp = spp;
    opt.max_bounces = bounces;
    opt.seed = seed;
    opt.light_cache = true;
    opt.sun_photons = photons;
    opt.passes = static_cast<PassMask>(Pass::Rgb);
    Frame f;
    r.render(K, pose, opt, 0, f);
    return f.rgb;
  };
  for (int bounces : {2, 4}) {
    const ImageF reference = render(2048, false, 99, bounces);
    const auto plain = test::againstReference(render(16, false, 1, bounces), reference);
    const auto photons = test::againstReference(render(16, true, 1, bounces), reference);
    const auto converged = test::againstReference(render(512, true, 7, bounces), reference);
    std::printf("%d bounces, relative RMSE at 16 spp: plain %.4f, sun photons %.4f; mean at 512 "
                "spp with photons %.4f of the reference\n",
                bounces, plain.rel_rmse, photons.rel_rmse, converged.mean_ratio);
    EXPECT_NEAR(converged.mean_ratio, 1.0, 0.01) << bounces << " bounces: unbiased";
    EXPECT_NEAR(photons.mean_ratio, 1.0, 0.05) << bounces << " bounces";
    EXPECT_LT(photons.rel_rmse, 0.5 * plain.rel_rmse) << bounces << " bounces";
  }
  const auto [one, two] = test::onOneAndTwoThreads([&] { return render(4, true, 3); });
  EXPECT_EQ(one.data, two.data);
  EXPECT_NE(one.data, render(4, false, 3).data) << "the photons must change the estimate";
}

}  // namespace
}  // namespace inet
