// Every scene under ../shared/data/scenes that we can read (SceneNet RGB-D layouts, SceneNet
// v1, the Cornell box, the 3D-FRONT house) imports and renders with labels: from the middle of
// the scene, the ground-truth passes see geometry in much of the view and more than one NYU40
// class. (The Bitterli living room is a Mitsuba XML scene, which has no importer yet.)
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "render/renderer.h"
#include "scene/assimp_importer.h"
#include "scene/front3d_importer.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

fs::path scenesDir() {
  return fs::path(INET_SHARED_DIR) / "data" / "scenes";
}

/// Labels seen from (x, y) at 1.5 m above the floor (at most mid-height), looking four ways.
void expectRendersWithLabels(const Scene& s, const Eigen::Vector2d& xy, const std::string& what) {
  SCOPED_TRACE(what);
  Renderer r(s);
  auto [lo, hi] = s.bounds();
  const Vec3 eye(xy.x(), xy.y(), std::min(lo.z() + 1.5, 0.5 * (lo.z() + hi.z())));
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 32);
  RenderOptions opt;
  opt.passes = static_cast<PassMask>(Pass::Label) | static_cast<PassMask>(Pass::DepthRay);
  std::set<int> labels;
  size_t hits = 0, total = 0;
  for (const Vec3& dir :
       {Vec3(1, 0.01, 0), Vec3(-1, 0.01, 0), Vec3(0.01, 1, 0), Vec3(0.01, -1, 0)}) {
    Frame f;
    r.render(K, Pose::lookAt(eye, eye + dir, Vec3::UnitZ()), opt, 0, f);
    for (size_t i = 0; i < f.label.data.size(); ++i) {
      ++total;
      if (f.depth_ray.data[i] > 0) ++hits;
      if (f.label.data[i] > 0) labels.insert(f.label.data[i]);
    }
  }
  // (some SceneNet shells are open on a side: kitchen2 shows the scene in 51 % of the pixels)
  EXPECT_GT(hits, total * 4 / 10) << "the scene fills much of the view";
  EXPECT_GE(labels.size(), 2u) << "more than one class in view";
}

TEST(SharedScenes, MeshScenesImportAndRenderWithLabels) {
  if (!fs::exists(scenesDir())) GTEST_SKIP() << "needs ../shared/data/scenes (absent)";
  int count = 0;
  for (const auto& e : fs::recursive_directory_iterator(scenesDir())) {
    if (e.path().extension() != ".obj" || e.path().string().find("bitterli") != std::string::npos)
      continue;
    ImportOptions opt;
    opt.up = 'y';  // SceneNet, SceneNet v1 and McGuire's Cornell box are all +Y up
    Scene s = importMeshScene(e.path().string(), opt);
    auto [lo, hi] = s.bounds();
    expectRendersWithLabels(s, 0.5 * (lo + hi).head<2>(), e.path().filename().string());
    ++count;
  }
  EXPECT_GE(count, 13) << "11 SceneNet RGB-D layouts, SceneNet v1, the Cornell box";
}

TEST(SharedScenes, Front3dHouseRendersWithLabels) {
  const fs::path house = scenesDir() / "3d_front" / "0a8d471a-2587-458a-9214-586e003e9cf9.json";
  if (!fs::exists(house)) GTEST_SKIP() << "needs ../shared/data/scenes/3d_front (absent)";
  Scene s = importFront3d(house.string(), {});
  // from the middle of its first room (the house's middle may be inside a wall)
  ASSERT_FALSE(s.rooms.empty());
  Eigen::AlignedBox2d b;
  for (const auto& p : s.rooms[0].outline) b.extend(p);
  expectRendersWithLabels(s, b.center(), "3D-FRONT house");
}

}  // namespace
}  // namespace inet
