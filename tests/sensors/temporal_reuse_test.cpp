// Temporal reuse along a sequence (sensors/temporal_reuse.h), on the built-in room rendered by
// the path tracer along the built-in orbit:
//  - the noise of static diffuse pixels falls with the number of frames averaged, without bias
//    against a high-spp reference of the same view;
//  - newly seen pixels, a mirror and lights in view keep exactly their own frame's samples;
//  - a rough glossy ball's view-dependent light is reused while the view turns little, and only
//    then;
//  - smoothing averages the denoised light of the last frames, and steadies it;
//  - one frame's firefly does not enter the window;
//  - a window started late (after warm-up frames) gives the same bytes as one run from frame 0,
//    with one thread or many.
#include "sensors/temporal_reuse.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/error.h"
#include "render/denoise.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "scene/primitives.h"
#include "trajectory/builtin_trajectory.h"

namespace inet {
namespace {

LensModel smallLens() {
  return LensModel::pinhole(CameraIntrinsics::centred(96, 72, 70.0));
}

RenderOptions colour(int spp) {
  RenderOptions o;
  o.spp = spp;
  o.passes = static_cast<PassMask>(Pass::Rgb);
  return o;
}

struct Rendered {
  Frame frame;     // after reuse
  ImageF raw;      // the frame's own rgb
  ImageF raw_diffuse;  // and its own diffuse layer
  RgbLayers layers;
  ImageU8 used;
  ImageU8 multiplier;  // plan()'s, when boosted
  ImageF denoised;     // with smoothing: the denoiser's output before smooth()
  ImageF denoised_diffuse;  // and its diffuse light (denoiseRgb filters it apart)
};

/// The knobs of run() beyond the window and samples.
struct RunSettings {
  int boost = 1;          // plan samples (TemporalReuseOptions::boost) when > 1
  int geometry_from = 0;  // with boost: the first frame whose geometry is remembered
  float view_turn = TemporalReuseOptions{}.view_turn;  // tolerance of the glossy reuse
  int smooth = 1;         // > 1: denoise each frame and smooth it over this many
  int step = 2;           // poses of the 50-fps orbit between frames
  bool split = true;      // smooth() the denoiser's diffuse light apart from the rest
};

/// Renders frames first..last of the built-in orbit (25 fps, every `step`-th pose: by default the
/// camera moves a few pixels per frame; 0 = a still camera) at `spp`, through one TemporalReuse
/// of `window`. With `boost` > 1 each frame's samples are planned first (TemporalReuse::plan),
/// after the geometry of frames geometry_from..first-1 (addGeometry).
std::vector<Rendered> run(const Scene& scene, int window, int first, int last, int spp,
                          const RunSettings& set = {}) {
  const int boost = set.boost;
  const LensModel lens = smallLens();
  Renderer r(scene);
  const Trajectory traj = builtinTrajectory(std::max(2, 2 * (last + 1)), 25.0);
  TemporalReuseOptions opt;
  opt.window = window;
  opt.boost = boost;
  opt.boost_edges = boost > 1 ? 2 : 1;
  opt.view_turn = set.view_turn;
  opt.smooth = set.smooth;
  TemporalReuse reuse(scene, lens, opt);
  RenderOptions geometry;
  geometry.passes = passMask(Pass::DepthZ, Pass::Label, Pass::Instance);
  for (int k = set.geometry_from; k < first && boost > 1; ++k) {
    Frame g;
    const Pose& T = traj.poses[set.step * k].T_world_camera;
    r.render(lens, CameraExposure::fixed(T), geometry, static_cast<uint32_t>(k), g);
    reuse.addGeometry(g, T, 0.0);
  }
  std::vector<Rendered> out;
  for (int k = first; k <= last; ++k) {
    Rendered f;
    const Pose& T = traj.poses[set.step * k].T_world_camera;
    RenderOptions o = colour(spp);
    if (boost > 1) {
      Frame g;
      r.render(lens, CameraExposure::fixed(T), geometry, static_cast<uint32_t>(k), g);
      f.multiplier = reuse.plan(g, T, 0.0);
      o.spp_multiplier = &f.multiplier;
    }
    r.render(lens, CameraExposure::fixed(T), o, static_cast<uint32_t>(k), f.frame, &f.layers);
    f.raw = f.frame.rgb;
    f.raw_diffuse = f.layers.diffuse;
    reuse.add(f.frame, f.layers, T, 0.0, &f.used);
    if (set.smooth > 1) {
      denoiseRgb(f.frame, f.layers, DenoiseOptions{});
      f.denoised = f.frame.rgb;
      f.denoised_diffuse = f.layers.diffuse;
      reuse.smooth(f.frame, f.layers, set.split);
    }
    out.push_back(std::move(f));
  }
  return out;
}

/// Frame k of run()'s orbit (every 2nd pose) at 1,024 spp, another frame index (independent
/// samples): the reference the reused frames are compared with.
Frame referenceOfFrame(const Scene& scene, int k) {
  Renderer r(scene);
  Frame ref;
  const Trajectory traj = builtinTrajectory(2 * (k + 1), 25.0);
  r.render(smallLens(), traj.poses[2 * k].T_world_camera, colour(1024), 999, ref);
  return ref;
}

/// Do the 8 neighbours of (x, y) show the same instance (a pixel whose samples all land on it)?
bool interior(const ImageU16& instance, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= instance.width || yy >= instance.height ||
          instance.at(xx, yy) != instance.at(x, y))
        return false;
    }
  return true;
}

TEST(TemporalReuse, StaticDiffuseNoiseFallsWithTheFramesAveragedWithoutBias) {
  const Scene scene = makeDefaultScene();
  const int kWindow = 8;
  const std::vector<Rendered> seq = run(scene, kWindow, 0, kWindow - 1, 4);
  const Rendered& last = seq.back();
  const Frame ref = referenceOfFrame(scene, kWindow - 1);
  double se_raw = 0, se_reused = 0, sum_reused = 0, sum_ref = 0, se_raw_in = 0, se_reused_in = 0;
  double sum_raw = 0;
  int all = 0, px = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      all += last.used.at(x, y) == kWindow;
      // static diffuse pixels seen by every frame, not a light
      if (last.used.at(x, y) != kWindow || last.layers.emission.at(x, y, 0) > 0) continue;
      ++px;
      for (int c = 0; c < 3; ++c) {
        const double rf = ref.rgb.at(x, y, c);
        se_raw += std::pow(last.raw.at(x, y, c) - rf, 2);
        se_reused += std::pow(last.frame.rgb.at(x, y, c) - rf, 2);
        if (interior(last.frame.instance, x, y)) {
          se_raw_in += std::pow(last.raw.at(x, y, c) - rf, 2);
          se_reused_in += std::pow(last.frame.rgb.at(x, y, c) - rf, 2);
        }
        sum_reused += last.frame.rgb.at(x, y, c);
        sum_raw += last.raw.at(x, y, c);
        sum_ref += rf;
      }
    }
  const double ratio = se_raw / se_reused, bias = sum_reused / sum_ref - 1;
  std::printf("%d of %d px averaged over %d frames: squared error raw / reused = %.2f (%.2f "
              "inside objects), mean %+.4f (the frame's own samples: %+.4f)\n",
              px, 96 * 72, kWindow, ratio, se_raw_in / se_reused_in, bias, sum_raw / sum_ref - 1);
  EXPECT_GT(all, 96 * 72 / 2) << "the orbit moves a few pixels per frame";
  // 8 independent frames: 8x less variance, more where a past frame's 4 bilinear taps average
  // (measured 13.4); the reference's own noise is 4/1024 of the raw variance. The mean: +0.14 %
  // measured (the frame's own samples -0.10 %)
  EXPECT_GT(ratio, 8.0);
  EXPECT_LT(std::abs(bias), 0.005);
  // every pixel averaged 1..8 frames
  for (uint8_t n : last.used.data) ASSERT_TRUE(n >= 1 && n <= kWindow);
}

/// The default room with a silver ball of `roughness` (instance 900) where the orbit looks.
Scene roomWithBall(const Material& material) {
  Scene scene = makeDefaultScene();
  scene.materials.push_back(material);
  Object o;
  o.name = "ball";
  o.mesh = static_cast<int>(scene.meshes.size());
  scene.meshes.push_back(makePrimitive("sphere", {}, "t", "ball"));
  o.material = static_cast<int>(scene.materials.size()) - 1;
  o.nyu40 = 19;
  o.instance = 900;
  o.T_world_object = Mat4::Identity();
  o.T_world_object.diagonal() << 0.3, 0.3, 0.3, 1.0;
  o.T_world_object.block<3, 1>(0, 3) = Vec3(2.5, 2.0, 1.2);
  scene.objects.push_back(o);
  return scene;
}

/// The default room with a varnished ball (a coated diffuse of alpha 0.09) where the orbit looks.
Scene roomWithVarnishedBall() {
  Material varnish;
  varnish.id = "varnished_ball";
  varnish.type = MaterialType::Plastic;
  varnish.albedo = {0.6f, 0.4f, 0.25f};
  varnish.roughness = 0.3f;
  return roomWithBall(varnish);
}

Scene roomWithSilverBall(float roughness) {
  Material silver;
  silver.id = "silver_ball";
  silver.type = MaterialType::Conductor;
  silver.metal = "silver";
  silver.roughness = roughness;
  return roomWithBall(silver);
}

TEST(TemporalReuse, NewPixelsMirrorsAndSpecularLightKeepTheirOwnFramesSamples) {
  // a smooth mirror ball where the orbit looks: view-dependent, never reused
  const Scene scene = roomWithSilverBall(0.f);
  const std::vector<Rendered> seq = run(scene, 4, 0, 3, 2);
  int mirror_px = 0, new_px = 0, light_px = 0;
  for (const Rendered& f : seq)
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) {
        const bool is_mirror = f.frame.instance.at(x, y) == 900;
        const bool is_new = f.used.at(x, y) == 1;
        mirror_px += is_mirror;
        new_px += is_new;
        light_px += f.layers.emission.at(x, y, 0) > 0;
        for (int c = 0; c < 3; ++c) {
          // everything but the diffuse layer (emission, specular light) is the frame's own
          const float kept = f.frame.rgb.at(x, y, c) - f.layers.diffuse.at(x, y, c);
          const float own = f.raw.at(x, y, c) - f.raw_diffuse.at(x, y, c);
          ASSERT_NEAR(kept, own, 1e-5f * (1.f + std::abs(f.raw.at(x, y, c)))) << x << "," << y;
          // bit for bit where nothing may be reused (the mirror's edge pixels have samples on
          // the wall behind it)
          const bool whole_mirror = is_mirror && interior(f.frame.instance, x, y);
          if (whole_mirror) {
            ASSERT_EQ(f.raw_diffuse.at(x, y, c), 0.f) << x << "," << y;
          }
          if (whole_mirror || is_new) {
            ASSERT_EQ(f.frame.rgb.at(x, y, c), f.raw.at(x, y, c)) << x << "," << y;
          }
        }
      }
  std::printf("mirror %d px, first seen %d px, lights %d px over 4 frames\n", mirror_px, new_px,
              light_px);
  EXPECT_GT(mirror_px, 100) << "the mirror ball is in view";
  EXPECT_GT(new_px, 96 * 72) << "frame 0 is all new, and the orbit brings in more";
}

// A rough metal ball (GGX alpha 0.36): its light is all view-dependent (`rest`). Along the orbit
// the view at a point on it turns by about 0.02 rad per frame; the reuse's tolerance (0.1 alpha =
// 0.036 rad) lets the ball's light average the last frames, and it comes closer to a 1,024-spp
// reference without moving its mean. A wider tolerance lags: at 0.5 alpha the ball's mean rose
// 2.5 % and its squared error exceeded the raw frame's (0.25: +0.5 %, error / 2.4; 0.1: error /
// 3.2). With view_turn 0 it stays exactly as rendered.
TEST(TemporalReuse, RoughGlossyLightIsReusedOnlyWhileTheViewTurnsLittle) {
  const Scene scene = roomWithSilverBall(0.6f);
  const int kWindow = 8;
  const std::vector<Rendered> seq = run(scene, kWindow, 0, kWindow - 1, 16);
  const Rendered& last = seq.back();
  const Frame ref = referenceOfFrame(scene, kWindow - 1);
  int ball = 0, changed = 0;
  double se_raw = 0, se = 0, sum = 0, sum_raw = 0, sum_ref = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      if (last.frame.instance.at(x, y) != 900 || !interior(last.frame.instance, x, y) ||
          last.used.at(x, y) != kWindow)
        continue;
      ++ball;
      ASSERT_FLOAT_EQ(last.layers.view_alpha.at(x, y), 0.36f) << "the least alpha of its samples";
      ASSERT_EQ(last.raw_diffuse.at(x, y, 1), 0.f) << "a conductor reflects nothing diffusely";
      changed += last.frame.rgb.at(x, y, 1) != last.raw.at(x, y, 1);
      for (int c = 0; c < 3; ++c) {
        const double rf = ref.rgb.at(x, y, c);
        se_raw += std::pow(last.raw.at(x, y, c) - rf, 2);
        se += std::pow(last.frame.rgb.at(x, y, c) - rf, 2);
        sum += last.frame.rgb.at(x, y, c);
        sum_raw += last.raw.at(x, y, c);
        sum_ref += rf;
      }
    }
  std::printf("rough ball: %d px seen by all %d frames, %d reused; squared error raw / reused "
              "%.2f; mean %+.4f (own samples %+.4f)\n",
              ball, kWindow, changed, se_raw / se, sum / sum_ref - 1, sum_raw / sum_ref - 1);
  EXPECT_GT(ball, 100) << "the ball is in view";
  EXPECT_GT(changed, ball * 9 / 10);
  // the frames within 0.036 rad of the view: 3.2x measured
  EXPECT_GT(se_raw / se, 2.5);
  // the mean: -0.5 % measured, as the frame's own samples
  EXPECT_LT(std::abs(sum / sum_ref - 1), 0.01);

  // no turn allowed: the ball keeps its own samples bit for bit (the walls are still reused)
  RunSettings none;
  none.view_turn = 0.f;
  const std::vector<Rendered> kept = run(scene, 4, 0, 3, 2, none);
  int kept_px = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x)
      if (kept.back().frame.instance.at(x, y) == 900 && interior(kept.back().frame.instance, x, y)) {
        ++kept_px;
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(kept.back().frame.rgb.at(x, y, c), kept.back().raw.at(x, y, c)) << x << "," << y;
      }
  EXPECT_GT(kept_px, 100);
  EXPECT_NE(kept.back().frame.rgb, kept.back().raw);
}

// Smoothing, seen from a still camera (every frame's taps are the pixel itself): each interior
// pixel's light becomes the mean of the denoised light of the last 4 frames, exactly (the
// diffuse light's demodulated by the footprint's albedo, the rest's as it is); the mean over the
// image does not move, and the frame-to-frame change of what the denoiser leaves falls.
TEST(TemporalReuse, SmoothingAveragesTheDenoisedLightOfTheLastFrames) {
  const Scene scene = roomWithVarnishedBall();  // a rest to average too
  const int kWindow = 8, kSmooth = 4, kFrames = 10;
  RunSettings still;
  still.smooth = kSmooth;
  still.step = 0;
  const std::vector<Rendered> seq = run(scene, kWindow, 0, kFrames - 1, 4, still);
  const float eps = TemporalReuseOptions{}.albedo_epsilon;
  auto diffuse = [&](const Rendered& f, size_t k) {  // demodulated
    return f.denoised_diffuse.data[k] / std::max(f.layers.albedo.data[k], eps);
  };
  auto rest = [&](const Rendered& f, size_t k) {
    return f.denoised.data[k] - f.layers.emission.data[k] - f.denoised_diffuse.data[k];
  };
  int smoothed = 0;
  double rest_sum = 0, light_sum = 0;
  double change_denoised = 0, change_smoothed = 0, sum_denoised = 0, sum_smoothed = 0;
  for (int k = kSmooth; k < kFrames; ++k) {
    const Rendered& f = seq[k];
    for (size_t i = 0; i < f.used.data.size(); ++i) {
      if (f.used.data[i] != std::min(k + 1, kWindow)) continue;  // interior, seen all along
      ++smoothed;
      for (int c = 0; c < 3; ++c) {
        const size_t at = i * 3 + c;
        double mean = 0, mean_rest = 0;
        for (int j = k - kSmooth + 1; j <= k; ++j) {
          mean += diffuse(seq[j], at);
          mean_rest += rest(seq[j], at);
        }
        mean /= kSmooth;
        mean_rest /= kSmooth;
        const double expected = f.layers.emission.data[at] +
                                mean * std::max(f.layers.albedo.data[at], eps) + mean_rest;
        rest_sum += std::abs(mean_rest);
        light_sum += expected - f.layers.emission.data[at];
        ASSERT_NEAR(f.frame.rgb.data[at], expected, 1e-4 * (1.0 + std::abs(expected)))
            << "frame " << k << " pixel " << i;
        change_denoised += std::abs(f.denoised.data[at] - seq[k - 1].denoised.data[at]);
        change_smoothed += std::abs(f.frame.rgb.data[at] - seq[k - 1].frame.rgb.data[at]);
        sum_denoised += f.denoised.data[at];
        sum_smoothed += f.frame.rgb.data[at];
      }
    }
  }
  std::printf("%d px smoothed; frame-to-frame change denoised / smoothed %.2f; mean %+.4f; "
              "rest %.1f %% of the light\n",
              smoothed, change_denoised / change_smoothed, sum_smoothed / sum_denoised - 1,
              100 * rest_sum / light_sum);
  EXPECT_GT(smoothed, (kFrames - kSmooth) * 96 * 72 / 2);
  EXPECT_GT(change_denoised / change_smoothed, 1.5);
  EXPECT_LT(std::abs(sum_smoothed / sum_denoised - 1), 0.005);
  EXPECT_GT(rest_sum, 0.01 * light_sum) << "the varnish's rest is in the average (1.9 %)";
}

// A varnished ball seen from the moving orbit: its sheen changes with the view, its diffuse
// light does not. Smoothed apart (what denoiseRgb's split allows), the diffuse light is averaged
// over the last frames however far the view turned; smoothed together, the whole light waits
// for a view within the sheen's tolerance, which the orbit leaves at once.
TEST(TemporalReuse, SmoothingAveragesAVarnishsDiffuseLightWhateverTheViewTurn) {
  const Scene scene = roomWithVarnishedBall();
  const int kWindow = 6, kFrames = 6;
  RunSettings set;
  set.smooth = 4;
  const std::vector<Rendered> apart = run(scene, kWindow, 0, kFrames - 1, 4, set);
  set.split = false;
  const std::vector<Rendered> together = run(scene, kWindow, 0, kFrames - 1, 4, set);
  int ball = 0, smoothed_apart = 0, smoothed_together = 0;
  double sum_apart = 0, sum_together = 0, sheen = 0, light = 0;
  for (int k = 3; k < kFrames; ++k)
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) {
        const Rendered& a = apart[k];
        if (a.frame.instance.at(x, y) != 900 || !interior(a.frame.instance, x, y) ||
            a.used.at(x, y) != k + 1)
          continue;
        ++ball;
        smoothed_apart += a.frame.rgb.at(x, y, 0) != a.denoised.at(x, y, 0);
        smoothed_together += together[k].frame.rgb.at(x, y, 0) != together[k].denoised.at(x, y, 0);
        for (int c = 0; c < 3; ++c) {
          sum_apart += a.frame.rgb.at(x, y, c);
          sum_together += together[k].frame.rgb.at(x, y, c);
          sheen += a.denoised.at(x, y, c) - a.denoised_diffuse.at(x, y, c);
          light += a.denoised.at(x, y, c);
        }
      }
  std::printf("varnished ball: %d px, smoothed apart %d, together %d; sheen %.1f %% of its "
              "light; mean apart / together %+.4f\n",
              ball, smoothed_apart, smoothed_together, 100 * sheen / light,
              sum_apart / sum_together - 1);
  EXPECT_GT(ball, 150) << "the ball is in view";
  EXPECT_GT(sheen, 0.02 * light) << "the varnish reflects";
  EXPECT_GT(smoothed_apart, ball * 9 / 10);
  EXPECT_LT(smoothed_together, ball / 10) << "the view turned beyond the sheen's tolerance";
  EXPECT_LT(std::abs(sum_apart / sum_together - 1), 0.02);
}

// With smoothing a late start warms up on warmUpFrames() frames: window - 1 for the reuse, and
// smooth - 1 more whose denoised light the first frames average.
TEST(TemporalReuse, ASmoothedWindowStartedLateGivesTheSameBytes) {
  const Scene scene = makeDefaultScene();
  RunSettings set;
  set.smooth = 2;
  TemporalReuseOptions o;
  o.window = 3;
  o.smooth = set.smooth;
  ASSERT_EQ(o.warmUpFrames(), 3);
  const std::vector<Rendered> whole = run(scene, 3, 0, 6, 2, set);
  std::vector<Rendered> late;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    late = run(scene, 3, 2, 6, 2, set);  // frames 5, 6 after warming up on 2, 3, 4
  }
  for (int k = 5; k <= 6; ++k) EXPECT_EQ(whole[k].frame.rgb, late[k - 2].frame.rgb) << "frame " << k;
  // one frame fewer is not enough: frame 4's denoised light differs, and so does frame 5
  const std::vector<Rendered> short_warm = run(scene, 3, 3, 6, 2, set);
  EXPECT_NE(whole[5].frame.rgb, short_warm[2].frame.rgb);
  EXPECT_NE(whole[6].frame.rgb, whole[6].denoised) << "smoothing did something";
}

TEST(TemporalReuse, AWindowStartedLateGivesTheSameBytesWithAnyThreadCount) {
  const Scene scene = makeDefaultScene();
  const std::vector<Rendered> whole = run(scene, 3, 0, 5, 2);
  // frames 3..5 alone, after warming up on the two frames before 3 (what a resumed run does)
  std::vector<Rendered> late;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    late = run(scene, 3, 1, 5, 2);
  }
  for (int k = 3; k <= 5; ++k) {
    EXPECT_EQ(whole[k].frame.rgb, late[k - 1].frame.rgb) << "frame " << k;
    EXPECT_EQ(whole[k].used, late[k - 1].used) << "frame " << k;
  }
  // and the reuse did something there
  EXPECT_NE(whole[5].frame.rgb, whole[5].raw);
}

// Where the history is short, plan() asks for more samples: max(1, boost - k) where k earlier
// frames of the window will give reused light (exactly the frames add() then averages), the edge
// multiplier on class and depth edges; the first frame is all new. The weighted mean stays
// unbiased and the noise of the frame's static pixels falls as without the plan.
TEST(TemporalReuse, PlannedSamplesFollowTheHistoryAndKeepTheMeanUnbiased) {
  const Scene scene = makeDefaultScene();
  const int kWindow = 8, kBoost = 4;
  const std::vector<Rendered> seq = run(scene, kWindow, 0, kWindow - 1, 4, {kBoost});
  int boosted_new = 0, full_history = 0;
  for (size_t k = 0; k < seq.size(); ++k) {
    const Rendered& f = seq[k];
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) {
        const int m = f.multiplier.at(x, y), used = f.used.at(x, y);
        if (k == 0) {
          ASSERT_TRUE(m == kBoost || m == 2) << x << "," << y;
        }
        if (m == 2 && used == 1) continue;  // an edge (or a new pixel with boost - k == 2)
        // an interior pixel: the frames it averages are the frames its plan counted
        ASSERT_EQ(m, std::max(1, kBoost - (used - 1))) << "frame " << k << " " << x << "," << y;
        boosted_new += k > 0 && used == 1;
      }
  }
  for (uint8_t used : seq.back().used.data) full_history += used == kWindow;
  std::printf("%d new pixels after frame 0 took %dx the samples; %d pixels of the last frame "
              "averaged every frame\n", boosted_new, kBoost, full_history);
  EXPECT_GT(boosted_new, 50) << "the orbit brings new pixels in";
  EXPECT_GT(full_history, 96 * 72 / 2);
  // against 1024 spp: the mean of static pixels seen by every frame stays within 0.5 %
  const Frame ref = referenceOfFrame(scene, kWindow - 1);
  const Rendered& last = seq.back();
  double sum = 0, sum_ref = 0, se = 0, se_raw = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      if (last.used.at(x, y) != kWindow || last.layers.emission.at(x, y, 0) > 0) continue;
      for (int c = 0; c < 3; ++c) {
        sum += last.frame.rgb.at(x, y, c);
        sum_ref += ref.rgb.at(x, y, c);
        se += std::pow(last.frame.rgb.at(x, y, c) - ref.rgb.at(x, y, c), 2);
        se_raw += std::pow(last.raw.at(x, y, c) - ref.rgb.at(x, y, c), 2);
      }
    }
  std::printf("planned: mean %+.4f, squared error raw / reused %.2f\n", sum / sum_ref - 1,
              se_raw / se);
  EXPECT_LT(std::abs(sum / sum_ref - 1), 0.005);
  EXPECT_GT(se_raw / se, 8.0);
}

// A late start with planned samples: the geometry of the window - 1 frames before the warm-up
// frames is what their plans counted, so frames 5..7 come out the same bytes as in one run.
TEST(TemporalReuse, APlannedWindowStartedLateGivesTheSameBytes) {
  const Scene scene = makeDefaultScene();
  const int kWindow = 3;
  const std::vector<Rendered> whole = run(scene, kWindow, 0, 7, 2, {4});
  // frames 5..7: warm-up colour frames 3, 4; their plans' geometry frames 1, 2
  const std::vector<Rendered> late = run(scene, kWindow, 3, 7, 2, {4, 1});
  for (int k = 5; k <= 7; ++k) {
    EXPECT_EQ(whole[k].multiplier, late[k - 3].multiplier) << "frame " << k;
    EXPECT_EQ(whole[k].frame.rgb, late[k - 3].frame.rgb) << "frame " << k;
  }
  // without the geometry the warm-up frames' plans differ, and so does the output
  const std::vector<Rendered> blind = run(scene, kWindow, 3, 7, 2, {4, 3});
  EXPECT_NE(whole[3].multiplier, blind[0].multiplier);
}

// A box sliding over a floor under a sun, seen from above by a still camera: the box's pixels
// are carried with its motion (the instance's rigid motion between the frames' scene times), so
// they average the same points of the box; the floor the box uncovers is new.
TEST(TemporalReuse, AMovingObjectIsFollowedByItsMotion) {
  Scene s;
  s.meshes = {makePrimitive("quad", {}, "t", "quad")};
  s.materials.resize(2);
  s.materials[0].id = "white";
  s.materials[0].albedo = Vec3f::Constant(0.8f);
  s.materials[1].id = "grey";
  s.materials[1].albedo = Vec3f::Constant(0.3f);
  Mat4 T_floor = Mat4::Identity(), T_box = Mat4::Identity();
  T_floor.diagonal() << 4.0, 4.0, 1.0, 1.0;
  T_box.diagonal() << 0.5, 0.5, 1.0, 1.0;
  T_box(2, 3) = 0.2;
  Object box = Object::make("box", 0, 0, T_box, 40, 7);
  ObjectKeyframe a, b;
  a.pose.t = Vec3(-1.5, 0, 0);
  b.t_s = 1.0;
  b.pose.t = Vec3(1.5, 0, 0);
  box.motion = {a, b};
  s.objects = {Object::make("floor", 0, 1, T_floor, 2, 1), box};
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0.3, 0.2, -1).normalized();
  sun.intensity = 2.f;
  s.lights = {sun};
  const LensModel lens = LensModel::pinhole(CameraIntrinsics::centred(64, 64, 32.0));
  const Pose T = Pose::lookAt(Vec3(0, 0, 2), Vec3(0, 0, 0), Vec3::UnitY());
  Renderer r(s);
  TemporalReuseOptions opt;
  opt.window = 4;
  TemporalReuse reuse(s, lens, opt);
  Frame f;
  RgbLayers layers;
  ImageU8 used;
  // 4 frames 0.1 s apart: the box (about 9 px wide) moves 0.3 m = 5 px per frame, so without
  // its motion no box pixel would find itself in all 4 frames
  for (int k = 0; k < 4; ++k) {
    const auto t_ns = static_cast<TimeNs>(k) * 100000000;
    r.render(lens, CameraExposure::fixed(T, t_ns), colour(4), static_cast<uint32_t>(k), f, &layers);
    reuse.add(f, layers, T, k * 0.1, &used);
  }
  int box_px = 0, box_full = 0, floor_px = 0, floor_full = 0;
  double box_sum = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool on_box = f.instance.at(x, y) == 7;
      (on_box ? box_px : floor_px)++;
      if (used.at(x, y) == 4) (on_box ? box_full : floor_full)++;
      if (on_box && used.at(x, y) == 4) box_sum += f.rgb.at(x, y, 1);
    }
  std::printf("box %d px (%d averaged over 4 frames), floor %d px (%d)\n", box_px, box_full,
              floor_px, floor_full);
  EXPECT_GT(box_full, box_px / 2) << "the box's inside is followed along its motion";
  EXPECT_GT(floor_full, floor_px / 2);
  // a lit white Lambertian square: radiance = albedo / pi * E cos; the mean of the reused box
  // pixels matches it within 2 %
  const double expected = 0.8 / 3.14159265358979 * 2.0 * std::abs(sun.direction.z());
  EXPECT_NEAR(box_sum / box_full, expected, 0.02 * expected);
}

// One bright sample in frame 0 (a pixel of a wall 1,000 times its own light, as a caustic of
// the sun found by one BSDF sample makes it) must not reach the frames after it: later frames read
// it through bilinear taps, spread over 4 pixels, where the denoiser's one-pixel test no longer
// sees it. With the firefly test (the default) frame 1's brightest diffuse light is what it is
// without the injected sample; with the test off (ratio 0) it carries the sample.
TEST(TemporalReuse, AFireflyOfOneFrameDoesNotEnterTheWindow) {
  const Scene scene = makeDefaultScene();
  const LensModel lens = smallLens();
  Renderer r(scene);
  const Trajectory traj = builtinTrajectory(4, 25.0);
  // frame 1's brightest demodulated diffuse light, frame 0 given a firefly at (x, y) or not
  // `share`: what the test reported of frame 0's light, and what the injected sample added to it
  struct Share {
    double reported = 0.0, injected = 0.0;
  };
  auto brightest = [&](float ratio, bool inject, size_t* caught, Share* share = nullptr) {
    TemporalReuseOptions opt;
    opt.window = 2;
    opt.boost = opt.boost_edges = 1;
    opt.firefly_ratio = ratio;
    TemporalReuse reuse(scene, lens, opt);
    double most = 0.0;
    for (int k = 0; k < 2; ++k) {
      const Pose& T = traj.poses[2 * k].T_world_camera;
      Frame f;
      RgbLayers layers;
      r.render(lens, CameraExposure::fixed(T), colour(16), static_cast<uint32_t>(k), f, &layers);
      if (k == 0 && inject) {
        // the first wall pixel of the middle row whose 5x5 neighbourhood is one instance
        int at = -1;
        for (int x = 10; x < 86 && at < 0; ++x) {
          bool same = layers.diffuse.at(x, 36, 1) > 0.f;
          for (int dy = -2; dy <= 2 && same; ++dy)
            for (int dx = -2; dx <= 2 && same; ++dx)
              same = f.instance.at(x + dx, 36 + dy) == f.instance.at(x, 36);
          if (same) at = x;
        }
        EXPECT_GE(at, 0) << "no wall pixel in the middle row";
        double extra_lum = 0.0;
        for (int c = 0; c < 3 && at >= 0; ++c) {
          const float extra = 999.f * layers.diffuse.at(at, 36, c);
          layers.diffuse.at(at, 36, c) += extra;
          f.rgb.at(at, 36, c) += extra;
          extra_lum += (c == 0   ? 0.2126
                        : c == 1 ? 0.7152
                                 : 0.0722) *
                       extra / std::max(layers.albedo.at(at, 36, c), 0.01f);
        }
        if (share) {  // the frame's demodulated luminance, the sample included
          double total = 0.0;
          for (size_t i = 0; i < layers.diffuse.data.size(); ++i)
            total += (i % 3 == 0   ? 0.2126
                      : i % 3 == 1 ? 0.7152
                                   : 0.0722) *
                     layers.diffuse.data[i] / std::max(layers.albedo.data[i], 0.01f);
          share->injected = extra_lum / total;
        }
      }
      reuse.add(f, layers, T, 0.0);
      if (k == 0 && caught) *caught = reuse.fireflies().pixels;
      if (k == 0 && share) share->reported = reuse.fireflies().light_share;
      if (k == 1)
        for (size_t i = 0; i < layers.diffuse.data.size(); ++i)
          most = std::max(most, static_cast<double>(layers.diffuse.data[i]) /
                                    std::max(layers.albedo.data[i], 0.01f));
    }
    return most;
  };
  size_t caught = 0, caught_clean = 0, caught_off = 0;
  const double clean = brightest(TemporalReuseOptions{}.firefly_ratio, false, &caught_clean);
  Share share;
  const double tested = brightest(TemporalReuseOptions{}.firefly_ratio, true, &caught, &share);
  const double off = brightest(0.f, true, &caught_off);
  std::printf(
      "frame 1's brightest irradiance: clean %.3g, firefly tested %.3g, untested %.3g; "
      "frame 0's pixels taken as fireflies: %zu clean, %zu injected\n",
      clean, tested, off, caught_clean, caught);
  EXPECT_EQ(caught_off, 0u);
  EXPECT_GE(caught, caught_clean + 1) << "the injected sample was not caught";
  EXPECT_LE(tested, 1.05 * clean) << "the firefly reached frame 1";
  // the light it took is the injected sample's (less its median neighbour's, a 1/1000 part)
  std::printf("light taken %.5f of frame 0's, injected %.5f\n", share.reported, share.injected);
  EXPECT_GE(share.reported, 0.99 * share.injected);
  if (caught == 1) {  // nothing else taken
    EXPECT_LE(share.reported, 1.01 * share.injected);
  }
  EXPECT_GT(off, 10.0 * clean) << "without the test the sample should carry (the test's premise)";
}

TEST(TemporalReuse, BadWindowIsAnInputError) {
  const Scene scene = makeDefaultScene();
  TemporalReuseOptions opt;
  opt.window = 0;
  try {
    TemporalReuse reuse(scene, smallLens(), opt);
    FAIL() << "window 0 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--temporal");
  }
  opt.window = 65;
  EXPECT_THROW(TemporalReuse(scene, smallLens(), opt), InputError);
  opt.window = 8;
  opt.smooth = 0;
  try {
    TemporalReuse reuse(scene, smallLens(), opt);
    FAIL() << "smooth 0 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--temporal-smooth");
  }
  opt.smooth = 4;
  opt.view_turn = -1.f;
  EXPECT_THROW(TemporalReuse(scene, smallLens(), opt), InputError);
  opt.view_turn = 0.1f;
  opt.firefly_ratio = 1.f;  // every pixel brighter than its neighbours would be a firefly
  try {
    TemporalReuse reuse(scene, smallLens(), opt);
    FAIL() << "firefly ratio 1 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--temporal-firefly");
  }
}

}  // namespace
}  // namespace inet
