// Issue 4 acceptance, end to end: every one of the 1,000 layouts of seeds 0..999 is written as
// layout.json, loads back, and renders labelled frames; every 10th also gets a random
// trajectory through its free space (issue 5) whose first pose renders. (The geometric checks
// of the same 1,000 are in apartment_test.)
#include <gtest/gtest.h>

#include <chrono>
#include <set>

#include "../temp_dir.h"
#include "procedural/apartment.h"
#include "render/renderer.h"
#include "scene/layout_json.h"
#include "trajectory/free_space.h"
#include "trajectory/random_trajectory.h"

namespace inet {
namespace {

/// Renders a 32x24 frame at 1 spp and returns the NYU40 classes in view and the mean colour.
std::pair<std::set<int>, double> renderSmall(const Renderer& r, const Pose& T_world_camera) {
  const CameraIntrinsics K = CameraIntrinsics::centred(32, 24, 20);
  RenderOptions opt;
  opt.spp = 1;
  opt.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Label);
  Frame f;
  r.render(K, T_world_camera, opt, 0, f);
  std::set<int> labels(f.label.data.begin(), f.label.data.end());
  double mean = 0;
  for (float v : f.rgb.data) mean += v;
  return {labels, mean / f.rgb.data.size()};
}

TEST(ApartmentAcceptance, AThousandLayoutsLoadAndRender) {
  test::TempDir dir("apartment_render");
  const auto t0 = std::chrono::steady_clock::now();
  int trajectories = 0;
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    SCOPED_TRACE(seed);
    const auto folder = dir.path() / std::to_string(seed);
    ApartmentOptions opt;
    opt.seed = seed;
    opt.texture_size = 64;
    Apartment apt = makeApartment(opt, folder, dir.path() / "textures");
    saveLayout(apt.scene, (folder / "layout.json").string());
    const Scene scene = loadLayout((folder / "layout.json").string());
    ASSERT_EQ(scene.objects.size(), apt.scene.objects.size());
    Renderer r(scene);
    // from the middle of the first room, 1.5 m up, along its longer side
    Eigen::AlignedBox2d b;
    for (const auto& p : scene.rooms[0].outline) b.extend(p);
    const Eigen::Vector2d c = b.center();
    const Vec3 eye(c.x(), c.y(), 1.5);
    const Vec3 target = b.sizes().x() > b.sizes().y() ? Vec3(b.max().x(), c.y(), 1.0)
                                                      : Vec3(c.x(), b.max().y(), 1.0);
    auto [labels, mean] = renderSmall(r, Pose::lookAt(eye, target, Vec3::UnitZ()));
    EXPECT_TRUE(labels.count(1)) << "walls in view";
    EXPECT_EQ(labels.count(0), 0u) << "a closed apartment: every pixel hits something";
    EXPECT_GT(mean, 0.0) << "lit";
    if (seed % 10 == 0) {
      FreeSpace space(scene);
      RandomTrajectoryOptions topt;
      topt.seed = seed;
      topt.frames = 25;
      RandomTrajectory traj = generateRandomTrajectory(space, topt);
      auto [tl, tm] = renderSmall(r, traj.frames.poses.front().T_world_camera);
      EXPECT_EQ(tl.count(0), 0u) << "indoors, in a closed apartment: every pixel hits something";
      EXPECT_GT(tm, 0.0) << "lit";
      ++trajectories;
    }
    std::filesystem::remove_all(folder);
    if (HasFailure()) break;
  }
  EXPECT_EQ(trajectories, 100);
  std::printf("1000 layouts written, loaded and rendered, 100 with trajectories: %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace
}  // namespace inet
