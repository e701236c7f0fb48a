// The à-trous denoiser on a synthetic frame whose clean image is known exactly: a smooth shading
// field times a sharp checkerboard albedo, on a concave wall corner (normal crease) with a box in
// front (depth discontinuity), plus zero-mean noise of known per-pixel variance.
#include "render/denoise.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "render/sensor_noise.h"
#include "../expect_input_error.h"

namespace inet {
namespace {

struct SyntheticFrame {
  ImageF clean, noisy, albedo, normal, depth, variance;
};

void setNormal(ImageF& n, int x, int y, double nx, double ny, double nz) {
  double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  n.at(x, y, 0) = static_cast<float>(nx / len);
  n.at(x, y, 1) = static_cast<float>(ny / len);
  n.at(x, y, 2) = static_cast<float>(nz / len);
}

/// The scene. Camera frame: x right, y down, z forward; normals face the camera (n_z < 0).
SyntheticFrame makeFrame(int w, int h, uint64_t seed, double noise_scale = 0.2) {
  SyntheticFrame f{ImageF(w, h, 3), ImageF(w, h, 3), ImageF(w, h, 3),
                   ImageF(w, h, 3), ImageF(w, h, 1), ImageF(w, h, 3)};
  const double light[3] = {0.2 / 0.9894, -0.6 / 0.9894, -0.77 / 0.9894};  // towards the light
  const double tint[3] = {1.0, 0.95, 0.85};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      bool box = x >= w * 0.15 && x < w * 0.42 && y >= h * 0.55 && y < h * 0.9;
      bool left = x < w / 2;
      double inv_z = 1.0 / 3.0 + 0.002 * std::abs(x + 0.5 - w / 2.0) + 0.0005 * (y - h / 2.0);
      if (box) {
        inv_z = 1.0;
        setNormal(f.normal, x, y, 0, 0, -1);
      } else {
        setNormal(f.normal, x, y, left ? 0.6 : -0.6, 0.05, -0.8);
      }
      f.depth.at(x, y) = static_cast<float>(1.0 / inv_z);
      // Albedo: 8 px checker on the walls, 6 px checker in other colours on the box.
      int cell = box ? 6 : 8;
      bool odd = ((x / cell) + (y / cell)) % 2 == 1;
      const float wall_a[3] = {0.75f, 0.7f, 0.6f}, wall_b[3] = {0.15f, 0.2f, 0.3f};
      const float box_a[3] = {0.9f, 0.3f, 0.2f}, box_b[3] = {0.2f, 0.6f, 0.3f};
      const float* a = box ? (odd ? box_b : box_a) : (odd ? wall_b : wall_a);
      double n_dot_l = 0;
      for (int c = 0; c < 3; ++c) n_dot_l += f.normal.at(x, y, c) * light[c];
      double dx = x - 0.7 * w, dy = y - 0.3 * h, s = 0.35 * w;
      double falloff = 0.6 + 0.4 * std::exp(-(dx * dx + dy * dy) / (2 * s * s));
      double irradiance = (0.3 + 1.2 * std::max(0.0, n_dot_l)) * falloff;
      CounterRng rng(seed, RngStream::Sensor, 7, static_cast<uint32_t>(y * w + x), 0);
      double common = standardNormal(rng);
      for (int c = 0; c < 3; ++c) {
        f.albedo.at(x, y, c) = a[c];
        double clean = irradiance * tint[c] * a[c];
        // Path-tracer-like: std-dev grows with the signal; channels 64 % correlated.
        double sd = noise_scale * std::sqrt(clean) + 0.01;
        double z = 0.8 * common + 0.6 * standardNormal(rng);
        f.clean.at(x, y, c) = static_cast<float>(clean);
        f.noisy.at(x, y, c) = static_cast<float>(clean + sd * z);
        f.variance.at(x, y, c) = static_cast<float>(sd * sd);
      }
    }
  }
  return f;
}

/// RMSE against the clean image over the pixels `in(x, y)` selects (all channels).
double rmse(const ImageF& img, const ImageF& clean, const std::function<bool(int, int)>& in) {
  double sum = 0;
  long n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (!in(x, y)) continue;
      for (int c = 0; c < 3; ++c) {
        double d = img.at(x, y, c) - clean.at(x, y, c);
        sum += d * d;
        ++n;
      }
    }
  return std::sqrt(sum / static_cast<double>(n));
}

bool everywhere(int, int) {
  return true;
}

/// The 1-pixel-wide band on both sides of every albedo edge: a 4-neighbour has other albedo.
std::function<bool(int, int)> albedoEdgeBand(const ImageF& albedo) {
  return [&albedo](int x, int y) {
    const int dxs[4] = {-1, 1, 0, 0}, dys[4] = {0, 0, -1, 1};
    for (int k = 0; k < 4; ++k) {
      int qx = x + dxs[k], qy = y + dys[k];
      if (qx < 0 || qy < 0 || qx >= albedo.width || qy >= albedo.height) continue;
      for (int c = 0; c < 3; ++c)
        if (albedo.at(x, y, c) != albedo.at(qx, qy, c)) return true;
    }
    return false;
  };
}

/// The 1-pixel band on both sides of the crease and of the box outline: the normal changes.
std::function<bool(int, int)> geometryEdgeBand(const ImageF& normal) {
  return [&normal](int x, int y) {
    const int dxs[4] = {-1, 1, 0, 0}, dys[4] = {0, 0, -1, 1};
    for (int k = 0; k < 4; ++k) {
      int qx = x + dxs[k], qy = y + dys[k];
      if (qx < 0 || qy < 0 || qx >= normal.width || qy >= normal.height) continue;
      for (int c = 0; c < 3; ++c)
        if (normal.at(x, y, c) != normal.at(qx, qy, c)) return true;
    }
    return false;
  };
}

double meanOf(const ImageF& img) {
  double s = 0;
  for (float v : img.data) s += v;
  return s / static_cast<double>(img.data.size());
}

/// A 5x5 box blur: what an edge-unaware filter does to the checker, as a sensitivity check.
ImageF boxBlur5(const ImageF& img) {
  ImageF out(img.width, img.height, img.channels);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < img.channels; ++c) {
        double s = 0;
        int n = 0;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= img.width || qy >= img.height) continue;
            s += img.at(qx, qy, c);
            ++n;
          }
        out.at(x, y, c) = static_cast<float>(s / n);
      }
  return out;
}

TEST(Denoise, WithVarianceCutsRmseFiveTimesAndKeepsAlbedoEdges) {
  SyntheticFrame f = makeFrame(256, 192, 1);
  ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, &f.variance, DenoiseOptions{});
  double before = rmse(f.noisy, f.clean, everywhere), after = rmse(out, f.clean, everywhere);
  auto band = albedoEdgeBand(f.albedo);
  double band_before = rmse(f.noisy, f.clean, band), band_after = rmse(out, f.clean, band);
  double band_blur = rmse(boxBlur5(f.noisy), f.clean, band);
  std::printf(
      "RMSE noisy %.5f -> denoised %.5f (x%.1f); albedo edge band %.5f -> %.5f "
      "(5x5 box blur: %.5f)\n",
      before, after, before / after, band_before, band_after, band_blur);
  EXPECT_LT(after, before / 5);
  // Edges are not smeared: the edge band improves about as much as the whole image, whereas a
  // blur that ignores the albedo makes the band far worse than the noisy input.
  EXPECT_LT(band_after, band_before / 4);
  EXPECT_LT(band_after, 2.0 * after);
  EXPECT_GT(band_blur, band_before);
  // Same for the geometric edges (normal crease, depth discontinuity at the box outline).
  auto geo = geometryEdgeBand(f.normal);
  double geo_before = rmse(f.noisy, f.clean, geo), geo_after = rmse(out, f.clean, geo);
  std::printf("geometry edge band %.5f -> %.5f\n", geo_before, geo_after);
  EXPECT_LT(geo_after, geo_before / 4);
  EXPECT_LT(geo_after, 3.0 * after);  // only about half of the kernel lies on the same surface
  double mean_in = meanOf(f.noisy), mean_out = meanOf(out);
  std::printf("mean: clean %.5f noisy %.5f denoised %.5f\n", meanOf(f.clean), mean_in, mean_out);
  EXPECT_NEAR(mean_out / mean_in, 1.0, 0.005) << mean_in << " vs " << mean_out;
  EXPECT_NEAR(mean_out / meanOf(f.clean), 1.0, 0.005);
}

TEST(Denoise, WithoutVarianceRobustEstimateAlsoCutsRmseFiveTimes) {
  SyntheticFrame f = makeFrame(256, 192, 2);
  ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, nullptr, DenoiseOptions{});
  double before = rmse(f.noisy, f.clean, everywhere), after = rmse(out, f.clean, everywhere);
  auto band = albedoEdgeBand(f.albedo);
  double band_before = rmse(f.noisy, f.clean, band), band_after = rmse(out, f.clean, band);
  std::printf("no variance: RMSE %.5f -> %.5f (x%.1f); edge band %.5f -> %.5f\n", before, after,
              before / after, band_before, band_after);
  EXPECT_LT(after, before / 5);
  EXPECT_LT(band_after, band_before / 4);
  EXPECT_NEAR(meanOf(out) / meanOf(f.noisy), 1.0, 0.005);
}

TEST(Denoise, VarianceFromHalfBuffersIsUnbiased) {
  // Two half buffers with iid N(0, s^2) noise: Var of their mean is s^2 / 2.
  const int w = 200, h = 100;
  const double s = 0.3;
  ImageF a(w, h, 3), b(w, h, 3);
  for (size_t i = 0; i < a.data.size(); ++i) {
    CounterRng rng(5, RngStream::Sensor, 0, static_cast<uint32_t>(i), 1);
    a.data[i] = static_cast<float>(0.5 + s * standardNormal(rng));
    b.data[i] = static_cast<float>(0.5 + s * standardNormal(rng));
  }
  double m = meanOf(varianceFromHalfBuffers(a, b));
  EXPECT_NEAR(m / (s * s / 2), 1.0, 0.02);
}

TEST(Denoise, HalfBufferVarianceDrivesTheFilter) {
  SyntheticFrame f = makeFrame(256, 192, 3);
  // Split the noisy frame into two halves with the same mean: A = x + d, B = x - d with d of
  // variance Var(x): Var((A+B)/2) estimate = d^2, unbiased for Var(x).
  ImageF half_a = f.noisy, half_b = f.noisy;
  for (size_t i = 0; i < f.noisy.data.size(); ++i) {
    CounterRng rng(9, RngStream::Sensor, 0, static_cast<uint32_t>(i), 2);
    float d = static_cast<float>(std::sqrt(f.variance.data[i]) * standardNormal(rng));
    half_a.data[i] += d;
    half_b.data[i] -= d;
  }
  ImageF var = varianceFromHalfBuffers(half_a, half_b);
  ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, &var, DenoiseOptions{});
  EXPECT_LT(rmse(out, f.clean, everywhere), rmse(f.noisy, f.clean, everywhere) / 5);
}

TEST(Denoise, NeighbourhoodVarianceMatchesTheNoiseAndStopsAtEdges) {
  // iid noise of a known level on the synthetic corner: the estimate from the 7x7 neighbourhood
  // (what a 1-spp render gets instead of its own variance) must find it, per surface.
  SyntheticFrame f = makeFrame(256, 192, 4);
  ImageF var = std::move(
      neighbourhoodVariance({&f.noisy}, f.albedo, f.normal, f.depth, DenoiseOptions{})[0]);
  // the ratio of the mean estimate to the mean true variance, away from the image border,
  // over the pixels `in` selects: walls, box, and the 1-px band at the crease and box outline
  auto ratio = [&](const std::function<bool(int, int)>& in) {
    double est = 0, truth = 0;
    for (int y = 3; y < f.noisy.height - 3; ++y)
      for (int x = 3; x < f.noisy.width - 3; ++x)
        if (in(x, y))
          for (int c = 0; c < 3; ++c) {
            est += var.at(x, y, c);
            truth += f.variance.at(x, y, c);
          }
    return est / truth;
  };
  const double all = ratio(everywhere), geo = ratio(geometryEdgeBand(f.normal));
  std::printf("neighbourhood variance / true: all %.3f, geometry edge band %.3f\n", all, geo);
  // the smooth light varies a little over 7 px and counts as noise: a few percent high
  EXPECT_NEAR(all, 1.0, 0.1);
  // at the crease and the box outline only the pixel's own surface counts (the box is lit
  // differently: mixing it in would inflate the estimate)
  EXPECT_NEAR(geo, 1.0, 0.25);
  // noise-free: zero (up to the light's variation over the window, tiny next to the noise)
  ImageF clean_var = std::move(
      neighbourhoodVariance({&f.clean}, f.albedo, f.normal, f.depth, DenoiseOptions{})[0]);
  EXPECT_LT(meanOf(clean_var), 0.02 * meanOf(f.variance));
  // with it, the filter removes the noise as well as with the true variance
  ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, &var, DenoiseOptions{});
  EXPECT_LT(rmse(out, f.clean, everywhere), rmse(f.noisy, f.clean, everywhere) / 5);
  // several images at once give each the estimate it gets alone
  std::vector<ImageF> both =
      neighbourhoodVariance({&f.clean, &f.noisy}, f.albedo, f.normal, f.depth, DenoiseOptions{});
  EXPECT_EQ(both[0].data, clean_var.data);
  EXPECT_EQ(both[1].data, var.data);
}

TEST(Denoise, ConstantImageStaysConstant) {
  const int w = 64, h = 48;
  ImageF rgb(w, h, 3), albedo(w, h, 3), normal(w, h, 3), depth(w, h, 1, 2.5f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c[3] = {0.3f, 0.5f, 0.7f}, a[3] = {0.6f, 0.4f, 0.8f};
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = c[k], albedo.at(x, y, k) = a[k];
      normal.at(x, y, 2) = -1.f;
    }
  ImageF var(w, h, 1, 0.01f);
  for (const ImageF* v : std::initializer_list<const ImageF*>{nullptr, &var}) {
    ImageF out = denoise(rgb, albedo, normal, depth, v, DenoiseOptions{});
    for (size_t i = 0; i < out.data.size(); ++i)
      ASSERT_NEAR(out.data[i], rgb.data[i], 2e-6f * rgb.data[i]) << "index " << i;
  }
}

// Indoor Monte Carlo noise is skewed: most samples of a wall pixel find little light, a few find
// much (here 16 samples per pixel, each 0 or 8 with probability 7/8 and 1/8: mean 1), and the
// pixel's own sample variance grows with its value. The colour stop then leans toward the
// dark majority and the filtered wall comes out dark; mean_levels keeps the input's light.
TEST(Denoise, SkewedNoiseDarkensTheColourStopAndMeanLevelsKeepTheLight) {
  const int w = 160, h = 120, spp = 16;
  ImageF rgb(w, h, 3), albedo(w, h, 3, 0.5f), normal(w, h, 3), depth(w, h, 1, 3.f), var(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      normal.at(x, y, 2) = -1.f;
      CounterRng rng(5, RngStream::Sensor, 1, static_cast<uint32_t>(y * w + x), 0);
      double sum = 0, sum2 = 0;
      for (int s = 0; s < spp; ++s) {
        const double v = rng.uniform() < 0.125f ? 8.0 : 0.0;
        sum += v;
        sum2 += v * v;
      }
      const double mean = sum / spp, var_mean = (sum2 - sum * sum / spp) / (spp - 1) / spp;
      for (int c = 0; c < 3; ++c) {
        rgb.at(x, y, c) = static_cast<float>(0.5 * mean);  // albedo x irradiance 1
        var.at(x, y, c) = static_cast<float>(0.25 * var_mean);
      }
    }
  DenoiseOptions plain;
  plain.iterations = 3;
  plain.sigma_color = 2.f;
  DenoiseOptions kept = plain;
  kept.mean_levels = 5;
  const ImageF a = denoise(rgb, albedo, normal, depth, &var, plain);
  const ImageF b = denoise(rgb, albedo, normal, depth, &var, kept);
  const ImageF truth(w, h, 3, 0.5f);
  const double mean_in = meanOf(rgb) / 0.5, mean_a = meanOf(a) / 0.5, mean_b = meanOf(b) / 0.5;
  const double rmse_a = rmse(a, truth, everywhere), rmse_b = rmse(b, truth, everywhere);
  std::printf("input mean %.4f; colour stop: mean %.4f, RMSE %.4f; keeping the mean: %.4f, %.4f\n",
              mean_in, mean_a, rmse_a, mean_b, rmse_b);
  EXPECT_LT(mean_a, mean_in - 0.02) << "the colour stop's bias this test is about";
  EXPECT_NEAR(mean_b, mean_in, 0.005);
  EXPECT_LT(rmse_b, rmse_a) << "the bias was most of the error";
}

// A single pixel 100x brighter than a flat surround (one sample that found a lamp through its
// shade) must not become a blotch; a 2x2 bright patch is a feature and stays brighter.
TEST(Denoise, IsolatedFireflyGoesABrightPatchStays) {
  const int w = 48, h = 32;
  ImageF rgb(w, h, 3, 0.2f), albedo(w, h, 3, 0.5f), normal(w, h, 3), depth(w, h, 1, 2.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) normal.at(x, y, 2) = -1.f;
  for (int k = 0; k < 3; ++k) rgb.at(10, 10, k) = 20.f;  // the firefly
  for (int y = 20; y < 22; ++y)
    for (int x = 30; x < 32; ++x)
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = 2.f;  // a small bright feature
  ImageF out = denoise(rgb, albedo, normal, depth, nullptr, DenoiseOptions{});
  double around_firefly = 0;
  for (int y = 5; y < 16; ++y)
    for (int x = 5; x < 16; ++x) around_firefly = std::max<double>(around_firefly, out.at(x, y, 1));
  EXPECT_LT(around_firefly, 0.25) << "the firefly neither stays nor spreads";
  EXPECT_GT(out.at(30, 20, 1), 0.5f) << "the 2x2 patch is kept";
}

// Fireflies are real light: the rare bright samples of a skewed estimate. Removing them darkened
// default sequence frames by 2-5 % where they were common (the first frame of an apartment
// sequence). Keeping the surface mean of the input taken before they go spreads their light
// over the mean's width instead: no blotch, no loss.
TEST(Denoise, FirefliesLightIsSpreadNotLostWhenTheSurfaceMeanIsKept) {
  const int w = 128, h = 96;
  ImageF rgb(w, h, 3, 0.2f), albedo(w, h, 3, 0.5f), normal(w, h, 3), depth(w, h, 1, 2.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) normal.at(x, y, 2) = -1.f;
  for (int y = 5; y < h; y += 16)  // one firefly per 16 x 16 tile: 7.4 % of the light
    for (int x = 7; x < w; x += 16)
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = 4.f;
  DenoiseOptions lost;
  lost.iterations = 4;
  lost.sigma_color = 3.f;
  DenoiseOptions kept = lost;
  kept.mean_levels = 5;
  const ImageF a = denoise(rgb, albedo, normal, depth, nullptr, lost);
  const ImageF b = denoise(rgb, albedo, normal, depth, nullptr, kept);
  const double in = meanOf(rgb), mean_a = meanOf(a), mean_b = meanOf(b);
  float brightest = 0.f;
  for (float v : b.data) brightest = std::max(brightest, v);
  std::printf("input mean %.4f; fireflies removed: %.4f; surface mean kept: %.4f, brightest %.3f\n",
              in, mean_a, mean_b, brightest);
  EXPECT_LT(mean_a, 0.95 * in) << "what removing them alone loses";
  EXPECT_NEAR(mean_b, in, 0.01 * in);
  EXPECT_LT(brightest, 0.25f) << "spread wide: no blotch";
}

TEST(Denoise, SameBytesForOneAndTwoThreadsAt640x480) {
  SyntheticFrame f = makeFrame(640, 480, 4);
  auto run = [&](int threads, const ImageF* var) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    auto t0 = std::chrono::steady_clock::now();
    ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, var, DenoiseOptions{});
    double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("640x480, %d thread(s), %s: %.1f ms\n", threads,
                var ? "with variance" : "robust estimate", ms);
    return out;
  };
  for (const ImageF* var : std::initializer_list<const ImageF*>{&f.variance, nullptr}) {
    ImageF one = run(1, var), two = run(2, var);
    EXPECT_TRUE(one == two);
  }
  auto neighbourhood = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return neighbourhoodVariance({&f.noisy}, f.albedo, f.normal, f.depth, DenoiseOptions{})[0];
  };
  EXPECT_TRUE(neighbourhood(1) == neighbourhood(2));
}

TEST(Denoise, PixelsWithoutSurfaceOrFiniteColourPassThroughAndDoNotSpread) {
  SyntheticFrame f = makeFrame(64, 48, 5);
  for (int y = 0; y < 10; ++y)  // a strip of sky: no surface
    for (int x = 0; x < 64; ++x) {
      f.depth.at(x, y) = 0.f;
      for (int c = 0; c < 3; ++c) f.normal.at(x, y, c) = 0.f, f.noisy.at(x, y, c) = 50.f;
    }
  f.noisy.at(30, 30, 1) = NAN;
  f.noisy.at(31, 30, 0) = INFINITY;
  ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, &f.variance, DenoiseOptions{});
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(out.at(x, y, 0), 50.f);
  EXPECT_TRUE(std::isnan(out.at(30, 30, 1)));
  EXPECT_TRUE(std::isinf(out.at(31, 30, 0)));
  for (int y = 10; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        if ((x == 30 || x == 31) && y == 30) continue;
        ASSERT_TRUE(std::isfinite(out.at(x, y, c))) << x << "," << y;
        ASSERT_LT(out.at(x, y, c), 5.f) << "sky leaked into (" << x << "," << y << ")";
      }
}

TEST(Denoise, TinyImagesAndBadOptions) {
  for (int w : {1, 2, 3})
    for (int h : {1, 2}) {
      SyntheticFrame f = makeFrame(w, h, 6);
      ImageF out = denoise(f.noisy, f.albedo, f.normal, f.depth, nullptr, DenoiseOptions{});
      EXPECT_EQ(out.width, w);
      for (float v : out.data) EXPECT_TRUE(std::isfinite(v));
    }
  SyntheticFrame f = makeFrame(8, 8, 6);
  DenoiseOptions bad;
  bad.sigma_depth = 0.f;
  try {
    denoise(f.noisy, f.albedo, f.normal, f.depth, nullptr, bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "denoise.sigma_depth");
  }
  bad = DenoiseOptions{};
  bad.iterations = 0;
  EXPECT_THROW(validateDenoiseOptions(bad, "cfg.json"), InputError);
  EXPECT_NE(DenoiseOptions{}.describe().find("iterations=5"), std::string::npos);
}

// Class-edge pixels (another label in their 3x3) take the result after edge_iterations levels,
// the rest after iterations; without a label pass, or with edge_iterations 0, every pixel takes
// the full filter. Exactly those images, bit for bit.
TEST(Denoise, ClassEdgePixelsTakeTheFirstLevelsOnly) {
  const int w = 64, h = 48;
  SyntheticFrame f = makeFrame(w, h, 11);
  Frame frame;
  frame.albedo = f.albedo;
  frame.normal = f.normal;
  frame.depth_z = f.depth;
  frame.label = ImageU8(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool box = x >= w * 0.15 && x < w * 0.42 && y >= h * 0.55 && y < h * 0.9;
      frame.label.at(x, y) = box ? 5 : (x < w / 2 ? 1 : 2);
    }
  RgbLayers layers;
  layers.emission = ImageF(w, h, 3);
  layers.variance = f.variance;
  DenoiseOptions o;
  o.iterations = 5;
  o.edge_iterations = 3;
  o.mean_levels = 5;
  DenoiseOptions o3 = o;
  o3.iterations = 3;
  const ImageF full = denoise(f.noisy, f.albedo, f.normal, f.depth, &f.variance, o);
  const ImageF first = denoise(f.noisy, f.albedo, f.normal, f.depth, &f.variance, o3);
  frame.rgb = f.noisy;
  denoiseRgb(frame, layers, o);
  int edges = 0, differ = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          edge |= frame.label.at(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1)) !=
                  frame.label.at(x, y);
      edges += edge;
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(frame.rgb.at(x, y, c), (edge ? first : full).at(x, y, c)) << x << "," << y;
        differ += full.at(x, y, c) != first.at(x, y, c);
      }
    }
  EXPECT_GT(edges, 150);  // the box's outline and the wall's middle seam
  EXPECT_GT(differ, w * h) << "the two level counts give different images";
  EXPECT_NE(o.describe().find("edge_iterations=3"), std::string::npos);
  // no label pass, or edge_iterations 0: the full filter everywhere
  for (int variant = 0; variant < 2; ++variant) {
    Frame g = frame;
    g.rgb = f.noisy;
    DenoiseOptions p = o;
    if (variant == 0) g.label = ImageU8();
    if (variant == 1) p.edge_iterations = 0;
    denoiseRgb(g, layers, p);
    EXPECT_EQ(g.rgb.data, full.data) << variant;
  }
  EXPECT_EQ(o3.describe().find("edge_iterations"), std::string::npos) << "inactive at 3 levels";
}

/// makeFrame's scene with the guides denoiseRgb reads: the frame's normal and depth, an albedo
/// pass and the layers' footprint albedo (both 0, for the test's texture to fill in), no emission.
struct LayeredFrame {
  SyntheticFrame f;
  Frame frame;
  RgbLayers layers;
};
LayeredFrame layeredFrame(int w, int h, uint64_t seed) {
  LayeredFrame l{makeFrame(w, h, seed, 0.1), {}, {}};
  l.frame.normal = l.f.normal;
  l.frame.depth_z = l.f.depth;
  l.frame.albedo = ImageF(w, h, 3);
  l.layers.emission = ImageF(w, h, 3);
  l.layers.albedo = ImageF(w, h, 3);
  return l;
}

/// Relative RMSE of img against truth over every channel.
double relRmse(const ImageF& img, const ImageF& truth) {
  double e = 0, t = 0;
  for (size_t i = 0; i < img.data.size(); ++i) {
    e += (img.data[i] - truth.data[i]) * (img.data[i] - truth.data[i]);
    t += truth.data[i] * truth.data[i];
  }
  return std::sqrt(e / t);
}

// A texture finer than a pixel: the albedo pass is the pixel centre's texel, the colour a mean
// over the footprint, whose albedo (RgbLayers::albedo) differs from the centre's by a part the
// centre does not predict. Demodulated by the centre's albedo, the filter printed the centre's
// texture on the result (pixels of like centre albedo are averaged, then multiplied by it); by
// the footprint's, it divides the colour exactly and the result follows the footprint.
TEST(Denoise, FootprintAlbedoDemodulatesATextureFinerThanAPixel) {
  const int w = 64, h = 48;
  auto [f, frame, layers] = layeredFrame(w, h, 12);
  layers.variance = f.variance;
  ImageF truth(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      CounterRng rng(12, RngStream::Sensor, 8, static_cast<uint32_t>(y * w + x), 0);
      const double centre = 0.25 + 0.5 * rng.uniformDouble();  // the centre's texel
      const double rest = 0.25 + 0.5 * rng.uniformDouble();    // the rest of the footprint
      const double footprint = 0.5 * (centre + rest);
      for (int c = 0; c < 3; ++c) {
        // makeFrame's light (clean / its checker albedo) on this texture
        const double light = f.clean.at(x, y, c) / f.albedo.at(x, y, c);
        const double noise = f.noisy.at(x, y, c) - f.clean.at(x, y, c);
        frame.albedo.at(x, y, c) = static_cast<float>(centre);
        layers.albedo.at(x, y, c) = static_cast<float>(footprint);
        truth.at(x, y, c) = static_cast<float>(light * footprint);
        f.noisy.at(x, y, c) = static_cast<float>(light * footprint + noise * footprint);
      }
    }
  DenoiseOptions o;
  o.edge_iterations = 0;
  frame.rgb = f.noisy;
  denoiseRgb(frame, layers, o);
  const ImageF by_footprint = frame.rgb;
  RgbLayers centre_only = layers;
  centre_only.albedo = ImageF();  // the albedo pass only
  frame.rgb = f.noisy;
  denoiseRgb(frame, centre_only, o);
  const ImageF by_centre = frame.rgb;
  const double noisy = relRmse(f.noisy, truth), footprint = relRmse(by_footprint, truth),
               centre = relRmse(by_centre, truth);
  EXPECT_LT(footprint, 0.4 * noisy) << "noisy " << noisy;
  EXPECT_LT(footprint, 0.04);
  EXPECT_GT(centre, 0.10) << "the centre's texture, printed on the result";
  EXPECT_GT(centre, 2.5 * footprint);
  EXPECT_NEAR(meanOf(by_footprint) / meanOf(truth), 1.0, 0.01);
  // a label pass of one class (no class edge) changes nothing; at class edges the footprint's
  // albedo is the share of samples on each surface (noise), so those pixels keep the pass's
  frame.label = ImageU8(w, h, 1);
  for (uint8_t& l : frame.label.data) l = 2;
  frame.rgb = f.noisy;
  denoiseRgb(frame, layers, o);
  EXPECT_EQ(frame.rgb.data, by_footprint.data);
  for (int y = 0; y < h; ++y) frame.label.at(w / 2, y) = 5;  // a one-pixel strip of another class
  frame.rgb = f.noisy;
  denoiseRgb(frame, layers, o);
  int changed = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      changed += frame.rgb.at(x, y, 0) != by_footprint.at(x, y, 0);
  EXPECT_GE(changed, 3 * h) << "the strip and its two neighbours take the pass's albedo";
}

// A varnished floor: diffuse light on a fine wood-like texture plus a sheen (the rest layer)
// that the texture does not scale. Filtered together, divided by the albedo and multiplied by it
// again, the sheen came back with the texture printed on it (each pixel's sheen times its albedo
// over its neighbours'); filtered apart, the diffuse light demodulated and the sheen as it is,
// both come out smooth, and layers.diffuse holds the filtered diffuse light.
TEST(Denoise, AVarnishReflectionIsFilteredApartFromTheTexturedDiffuseLight) {
  const int w = 64, h = 48;
  auto [f, frame, layers] = layeredFrame(w, h, 13);
  layers.diffuse = ImageF(w, h, 3);
  layers.diffuse_variance = ImageF(w, h, 3);
  layers.rest_variance = ImageF(w, h, 3);
  layers.variance = ImageF(w, h, 3);
  ImageF truth(w, h, 3), noisy(w, h, 3), truth_diffuse(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      CounterRng rng(13, RngStream::Sensor, 9, static_cast<uint32_t>(y * w + x), 0);
      const double grain = 0.35 + 0.15 * rng.uniformDouble();  // a texel per pixel
      const double sheen = 0.08 + 0.04 * x / w;                 // smooth over the frame
      for (int c = 0; c < 3; ++c) {
        const double light = f.clean.at(x, y, c) / f.albedo.at(x, y, c);
        const double noise = (f.noisy.at(x, y, c) - f.clean.at(x, y, c)) * grain;
        const double sheen_noise = 0.3 * sheen * standardNormal(rng);
        frame.albedo.at(x, y, c) = layers.albedo.at(x, y, c) = static_cast<float>(grain);
        truth_diffuse.at(x, y, c) = static_cast<float>(light * grain);
        truth.at(x, y, c) = static_cast<float>(light * grain + sheen);
        layers.diffuse.at(x, y, c) = static_cast<float>(light * grain + noise);
        noisy.at(x, y, c) = static_cast<float>(light * grain + noise + sheen + sheen_noise);
        layers.diffuse_variance.at(x, y, c) = f.variance.at(x, y, c) * grain * grain;
        layers.rest_variance.at(x, y, c) = static_cast<float>(0.09 * sheen * sheen);
        layers.variance.at(x, y, c) =
            layers.diffuse_variance.at(x, y, c) + layers.rest_variance.at(x, y, c);
      }
    }
  DenoiseOptions o;
  o.edge_iterations = 0;
  RgbLayers whole = layers;  // without the split: the light filtered together
  whole.diffuse = ImageF();
  frame.rgb = noisy;
  denoiseRgb(frame, whole, o);
  const ImageF together = frame.rgb;
  frame.rgb = noisy;
  denoiseRgb(frame, layers, o);
  const ImageF apart = frame.rgb;
  // the texture printed on the result: the slope of its error over the texel's deviation from
  // the mean texel (the sheen over the mean texel, about 0.24, where it is printed)
  auto printed = [&](const ImageF& img) {
    double mean_grain = 0;
    for (float a : layers.albedo.data) mean_grain += a;
    mean_grain /= static_cast<double>(layers.albedo.data.size());
    double num = 0, den = 0;
    for (size_t i = 0; i < img.data.size(); ++i) {
      const double d = layers.albedo.data[i] - mean_grain;
      num += d * (img.data[i] - truth.data[i]);
      den += d * d;
    }
    return num / den;
  };
  const double e_noisy = relRmse(noisy, truth), e_together = relRmse(together, truth),
               e_apart = relRmse(apart, truth);
  std::printf("rel. RMSE: noisy %.4f together %.4f apart %.4f; texture slope %.4f / %.4f\n",
              e_noisy, e_together, e_apart, printed(together), printed(apart));
  EXPECT_GT(printed(together), 0.1);
  EXPECT_LT(std::fabs(printed(apart)), 0.2 * printed(together)) << "the texture on the sheen";
  EXPECT_LT(e_apart, 0.3 * e_noisy);
  EXPECT_LT(e_apart, 0.8 * e_together);
  EXPECT_LT(relRmse(layers.diffuse, truth_diffuse), 0.3 * e_noisy) << "the filtered diffuse light";
  EXPECT_NEAR(meanOf(apart) / meanOf(truth), 1.0, 0.01);
}

TEST(Denoise, ParamsSetTheNamedFieldsAndRefuseBadOnesNamingTheFlag) {
  DenoiseOptions o;
  applyDenoiseParams("iterations=4,sigma_color=3.5,mean_levels=0", o, "", "--denoise-params");
  EXPECT_EQ(o.iterations, 4);
  EXPECT_EQ(o.sigma_color, 3.5f);
  EXPECT_EQ(o.mean_levels, 0);
  EXPECT_EQ(o.sigma_normal, DenoiseOptions{}.sigma_normal) << "the others keep their values";
  applyDenoiseParams("", o, "", "--denoise-params");  // nothing to change
  EXPECT_EQ(o.iterations, 4);
  for (const char* bad : {"iterations=11", "sigma_color=0", "sigma=3", "iterations=2.5",
                          "iterations", "sigma_color=abc", "sigma_depth=nan", "iterations=4,",
                          "edge_iterations=11", "edge_iterations=-1"}) {
    DenoiseOptions d;
    const InputError e =
        test::expectInputError([&] { applyDenoiseParams(bad, d, "", "--denoise-params"); });
    EXPECT_EQ(e.field(), "--denoise-params") << bad << ": " << e.what();
  }
}

}  // namespace
}  // namespace inet
