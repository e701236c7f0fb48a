// The Cornell box (../shared/data/scenes/cornell_box_mcguire) against a Blender Cycles reference
// rendered from the same OBJ and camera at 4096 spp (tests/golden/README.md says how it was made):
// the image mean and the means of a 4 x 4 grid of regions must agree. Our render at 256 spp has a
// per-region noise well under 0.5%, so the tolerances below measure bias, not noise.
//
// The file has a defect both renderers must be spared: each box's "Bottom Face" is written with
// relative indices that reach back past its own vertices (`f -12 -11 -10 -9` in the short box,
// the right face's vertices; `f -8 -7 -6 -5` in the tall box, the front face's), so a side face
// is doubled by a coplanar twin. Cycles' bounce rays start on one twin and hit the other, which
// blackens that face; we offset ray origins and do not. Reference and test both use a copy with
// those two lines corrected to `f -4 -3 -2 -1` (each bottom face's own vertices).
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dataset/image_io.h"
#include "render/renderer.h"
#include "scene/assimp_importer.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

/// Writes the corrected copy of the OBJ (and its MTL) into a temporary folder; returns its path.
fs::path correctedCornellBox(const fs::path& dir) {
  fs::path out = fs::temp_directory_path() / ("inet_cornell_" + std::to_string(::getpid()));
  fs::create_directories(out);
  fs::copy_file(dir / "CornellBox-Original.mtl", out / "CornellBox-Original.mtl",
                fs::copy_options::overwrite_existing);
  std::ifstream in(dir / "CornellBox-Original.obj", std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::string obj = text.str();
  for (const std::string bad : {"\nf -12 -11 -10 -9", "\nf -8 -7 -6 -5"}) {
    size_t at = obj.find(bad);
    EXPECT_NE(at, std::string::npos) << "the known defect is gone: regenerate the reference";
    EXPECT_EQ(obj.find(bad, at + 1), std::string::npos);
    if (at != std::string::npos) obj.replace(at, bad.size(), "\nf -4 -3 -2 -1");
  }
  std::ofstream(out / "CornellBox-Original.obj", std::ios::binary) << obj;
  return out / "CornellBox-Original.obj";
}

double regionMean(const ImageF& img, int x0, int y0, int w, int h) {
  double sum = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      for (int c = 0; c < 3; ++c) sum += img.at(x, y, c);
  return sum / (3.0 * w * h);
}

TEST(CornellBox, AgreesWithCyclesReference) {
  fs::path shared = fs::path(INET_SHARED_DIR) / "data/scenes/cornell_box_mcguire";
  if (!fs::exists(shared / "CornellBox-Original.obj"))
    GTEST_SKIP() << "../shared/data/scenes/cornell_box_mcguire not found";
  fs::path obj = correctedCornellBox(shared);
  fs::path src(INET_SOURCE_DIR);
  ImageF ref = readExr(src / "tests/golden/cornell_cycles_4096spp.exr", {"R", "G", "B"});
  CameraFile cam = loadCameraJson((src / "tests/data/render/cornell_camera.json").string());
  ASSERT_EQ(ref.width, cam.intrinsics.width);

  ImportOptions opt;  // keep the OBJ's own frame (Y up), as the reference did
  Scene scene = importMeshScene(obj.string(), opt);
  Renderer renderer(scene);
  RenderOptions ro;
  ro.spp = 256;
  ro.max_bounces = 8;
  ro.passes = static_cast<PassMask>(Pass::Rgb);
  Frame f;
  renderer.render(cam.intrinsics, cam.T_world_camera, ro, 0, f);

  const int W = ref.width, H = ref.height;
  double ours = regionMean(f.rgb, 0, 0, W, H), theirs = regionMean(ref, 0, 0, W, H);
  EXPECT_NEAR(ours / theirs, 1.0, 0.01) << "image mean " << ours << " vs Cycles " << theirs;
  const int n = 4;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double a = regionMean(f.rgb, i * W / n, j * H / n, W / n, H / n);
      double b = regionMean(ref, i * W / n, j * H / n, W / n, H / n);
      EXPECT_NEAR(a / b, 1.0, 0.03)
          << "region (" << i << ", " << j << "): " << a << " vs Cycles " << b;
    }
  fs::remove_all(obj.parent_path());
}

/// RMSE over the pixels that do not see the light (reference below 1): the denoiser leaves
/// directly visible emitters untouched, and their anti-aliased edges would swamp the measure.
double rmseOfLitSurfaces(const ImageF& a, const ImageF& ref) {
  double sum = 0;
  size_t n = 0;
  for (size_t p = 0; p < ref.pixelCount(); ++p) {
    if (ref.data[3 * p] + ref.data[3 * p + 1] + ref.data[3 * p + 2] > 3.0f) continue;
    for (int c = 0; c < 3; ++c) sum += std::pow(a.data[3 * p + c] - ref.data[3 * p + c], 2.0);
    n += 3;
  }
  return std::sqrt(sum / n);
}

// The denoiser on a real render: at 16 spp it must cut the error against the 4096-spp Cycles
// image well below the raw render's, without moving the mean.
TEST(CornellBox, DenoisingLowersTheErrorNotTheMean) {
  fs::path shared = fs::path(INET_SHARED_DIR) / "data/scenes/cornell_box_mcguire";
  if (!fs::exists(shared / "CornellBox-Original.obj"))
    GTEST_SKIP() << "../shared/data/scenes/cornell_box_mcguire not found";
  fs::path obj = correctedCornellBox(shared);
  fs::path src(INET_SOURCE_DIR);
  ImageF ref = readExr(src / "tests/golden/cornell_cycles_4096spp.exr", {"R", "G", "B"});
  CameraFile cam = loadCameraJson((src / "tests/data/render/cornell_camera.json").string());
  Renderer renderer(importMeshScene(obj.string(), ImportOptions{}));
  RenderOptions ro;
  ro.spp = 16;
  ro.passes = static_cast<PassMask>(Pass::Rgb);
  Frame raw, den;
  renderer.render(cam.intrinsics, cam.T_world_camera, ro, 0, raw);
  ro.denoise = true;
  renderer.render(cam.intrinsics, cam.T_world_camera, ro, 0, den);
  const int W = ref.width, H = ref.height;
  double e_raw = rmseOfLitSurfaces(raw.rgb, ref), e_den = rmseOfLitSurfaces(den.rgb, ref);
  EXPECT_LT(e_den, 0.6 * e_raw) << "raw " << e_raw << " denoised " << e_den;
  EXPECT_NEAR(regionMean(den.rgb, 0, 0, W, H) / regionMean(ref, 0, 0, W, H), 1.0, 0.01);
  EXPECT_TRUE(den.label.empty()) << "ground truth was not asked for and must not appear";
  fs::remove_all(obj.parent_path());
}

}  // namespace
}  // namespace inet
