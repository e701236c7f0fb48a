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
#include <memory>

#include "core/atomic_file.h"
#include "core/image_io.h"
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
  std::string obj = readTextFile(dir / "CornellBox-Original.obj");
  for (const std::string bad : {"\nf -12 -11 -10 -9", "\nf -8 -7 -6 -5"}) {
    size_t at = obj.find(bad);
    EXPECT_NE(at, std::string::npos) << "the known defect is gone: regenerate the reference";
    EXPECT_EQ(obj.find(bad, at + 1), std::string::npos);
    if (at != std::string::npos) obj.replace(at, bad.size(), "\nf -4 -3 -2 -1");
  }
  writeTextAtomic(out / "CornellBox-Original.obj", obj);
  return out / "CornellBox-Original.obj";
}

double regionMean(const ImageF& img, int x0, int y0, int w, int h) {
  double sum = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      for (int c = 0; c < 3; ++c) sum += img.at(x, y, c);
  return sum / (3.0 * w * h);
}

/// The corrected box, the Cycles reference and the camera; skips without ../shared.
class CornellBox : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::path shared = fs::path(INET_SHARED_DIR) / "data/scenes/cornell_box_mcguire";
    if (!fs::exists(shared / "CornellBox-Original.obj"))
      GTEST_SKIP() << "../shared/data/scenes/cornell_box_mcguire not found";
    obj_ = correctedCornellBox(shared);
    fs::path src(INET_SOURCE_DIR);
    ref_ = readExr(src / "tests/golden/cornell_cycles_4096spp.exr", {"R", "G", "B"});
    cam_ = loadCameraJson((src / "tests/data/render/cornell_camera.json").string());
    ASSERT_EQ(ref_.width, cam_.intrinsics.width);
    // keep the OBJ's own frame (Y up), as the reference did
    renderer_ = std::make_unique<Renderer>(importMeshScene(obj_.string(), ImportOptions{}));
  }
  void TearDown() override {
    if (!obj_.empty()) fs::remove_all(obj_.parent_path());
  }
  ImageF render(int spp, bool denoise) {
    RenderOptions ro;
    ro.spp = spp;
    ro.max_bounces = 8;
    ro.passes = static_cast<PassMask>(Pass::Rgb);
    ro.denoise = denoise;
    Frame f;
    renderer_->render(cam_.intrinsics, cam_.T_world_camera, ro, 0, f);
    EXPECT_TRUE(f.label.empty()) << "ground truth was not asked for and must not appear";
    return f.rgb;
  }

  fs::path obj_;
  ImageF ref_;
  CameraFile cam_;
  std::unique_ptr<Renderer> renderer_;
};

TEST_F(CornellBox, AgreesWithCyclesReference) {
  ImageF img = render(256, false);
  const int W = ref_.width, H = ref_.height;
  double ours = regionMean(img, 0, 0, W, H), theirs = regionMean(ref_, 0, 0, W, H);
  EXPECT_NEAR(ours / theirs, 1.0, 0.01) << "image mean " << ours << " vs Cycles " << theirs;
  const int n = 4;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double a = regionMean(img, i * W / n, j * H / n, W / n, H / n);
      double b = regionMean(ref_, i * W / n, j * H / n, W / n, H / n);
      EXPECT_NEAR(a / b, 1.0, 0.03)
          << "region (" << i << ", " << j << "): " << a << " vs Cycles " << b;
    }
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
TEST_F(CornellBox, DenoisingLowersTheErrorNotTheMean) {
  ImageF raw = render(16, false), den = render(16, true);
  double e_raw = rmseOfLitSurfaces(raw, ref_), e_den = rmseOfLitSurfaces(den, ref_);
  EXPECT_LT(e_den, 0.6 * e_raw) << "raw " << e_raw << " denoised " << e_den;
  const int W = ref_.width, H = ref_.height;
  EXPECT_NEAR(regionMean(den, 0, 0, W, H) / regionMean(ref_, 0, 0, W, H), 1.0, 0.01);
}

// One sample per pixel has no variance of its own: the render estimates it from the
// neighbourhood (denoise.h neighbourhoodVariance). Without that the filter took the zero sample
// variance for an exact image and left the noise as it was.
TEST_F(CornellBox, DenoisingWorksFromOneSamplePerPixel) {
  ImageF raw = render(1, false), den = render(1, true);
  double e_raw = rmseOfLitSurfaces(raw, ref_), e_den = rmseOfLitSurfaces(den, ref_);
  std::printf("1 spp: raw RMSE %.4f, denoised %.4f\n", e_raw, e_den);
  EXPECT_LT(e_den, 0.5 * e_raw) << "raw " << e_raw << " denoised " << e_den;
  const int W = ref_.width, H = ref_.height;
  EXPECT_NEAR(regionMean(den, 0, 0, W, H) / regionMean(ref_, 0, 0, W, H), 1.0, 0.05);
}

}  // namespace
}  // namespace inet
