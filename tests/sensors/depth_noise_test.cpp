// Kinect-like depth noise (sensors/depth_noise.h): the flat-wall sigma curve (issue 6
// acceptance), grazing-angle and range dropouts, projector shadow geometry, edge dropouts,
// disparity quantisation and determinism. Scenes are analytic planes and boxes.
#include "sensors/depth_noise.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/plot.h"

namespace inet {
namespace {

CameraIntrinsics vga() {
  return CameraIntrinsics{};
}  // 640 x 480, f = 600, c = (320, 240)

/// A fronto-parallel wall at depth z (normal towards the camera).
void wall(double z, const CameraIntrinsics& K, ImageF& depth, ImageF& normal) {
  depth = ImageF(K.width, K.height, 1, static_cast<float>(z));
  normal = ImageF(K.width, K.height, 3, 0.f);
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) normal.at(x, y, 2) = -1.f;
}

/// The wall with a box face at z_box over columns [x0, x1) and rows [y0, y1).
void boxOnWall(double z_wall, double z_box, int x0, int x1, int y0, int y1,
               const CameraIntrinsics& K, ImageF& depth, ImageF& normal) {
  wall(z_wall, K, depth, normal);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) depth.at(x, y) = static_cast<float>(z_box);
}

struct Stats {
  double mean = 0, std = 0;
  size_t n = 0, total = 0;
};

/// Error statistics of the returned pixels in the central half of the image.
Stats centralStats(const ImageF& noisy, double z_true) {
  double s = 0, s2 = 0;
  Stats st;
  for (int y = noisy.height / 4; y < 3 * noisy.height / 4; ++y)
    for (int x = noisy.width / 4; x < 3 * noisy.width / 4; ++x) {
      ++st.total;
      const double v = noisy.at(x, y);
      if (v <= 0) continue;
      const double e = v - z_true;
      s += e;
      s2 += e * e;
      ++st.n;
    }
  st.mean = s / st.n;
  st.std = std::sqrt(std::max(s2 / st.n - st.mean * st.mean, 0.0));
  return st;
}

TEST(DepthNoise, FlatWallStdFollowsModelCurve) {
  const CameraIntrinsics K = vga();
  const KinectNoiseOptions opts;
  std::vector<double> zs, measured, model;
  for (int i = 0; i <= 8; ++i) {
    const double z = 0.5 + 0.5 * i;
    ImageF depth, normal;
    wall(z, K, depth, normal);
    const ImageF noisy = kinectNoisyDepth(depth, normal, K, opts, 7, static_cast<uint32_t>(i));
    const Stats st = centralStats(noisy, z);
    const double sigma = kinectDepthSigma(z, opts, K.fx);
    std::printf(
        "z %.1f m: measured std %.5f m, model %.5f m (ratio %.4f), Nguyen %.5f m, "
        "bias %.5f m, returns %zu / %zu\n",
        z, st.std, sigma, st.std / sigma, nguyenAxialSigma(z, 0), st.mean, st.n, st.total);
    EXPECT_EQ(st.n, st.total) << "a fronto-parallel wall in range loses no central pixel";
    EXPECT_NEAR(st.std / sigma, 1.0, 0.10) << "z = " << z;  // the acceptance
    EXPECT_NEAR(st.std / sigma, 1.0, 0.02) << "z = " << z;  // 76 800 samples: ~0.3 % error
    // Nguyen's sigma is the total error of a (quantised) Kinect: the default model keeps it, up
    // to a ripple with the position of z between two levels (smallest when z sits on a level).
    EXPECT_NEAR(sigma / nguyenAxialSigma(z, 0), 1.0, 0.03) << "z = " << z;
    EXPECT_LT(std::abs(st.mean), 0.1 * sigma) << "z = " << z;
    zs.push_back(z);
    measured.push_back(st.std * 1000);
    model.push_back(sigma * 1000);
  }
  // The docs figure (docs/images/depth_noise_sigma.png) when asked for.
  if (const char* path = std::getenv("INET_DEPTH_NOISE_PLOT")) {
    KinectNoiseOptions on_top = opts;
    on_top.axial_sigma_includes_quantisation = false;
    Series curve;
    curve.label = "model: Nguyen total incl. 1/8 px quantisation";
    Series nguyen;
    nguyen.label = "Nguyen et al. 2012 sigma_z";
    Series naive;
    naive.label = "Nguyen, then quantisation on top";
    Series quant;
    quant.label = "quantisation alone (dz / sqrt 12)";
    nguyen.dashed = true;
    for (double z = 0.4; z <= 4.5001; z += 0.02) {
      curve.x.push_back(z), curve.y.push_back(kinectDepthSigma(z, opts, K.fx) * 1000);
      nguyen.x.push_back(z), nguyen.y.push_back(nguyenAxialSigma(z, 0) * 1000);
      naive.x.push_back(z), naive.y.push_back(kinectDepthSigma(z, on_top, K.fx) * 1000);
      quant.x.push_back(z),
          quant.y.push_back(z * z * 0.125 / (K.fx * 0.075) / std::sqrt(12.0) * 1000);
    }
    Series pts;
    pts.label = "measured, flat wall 640x480, f = 600 px";
    pts.x = zs;
    pts.y = measured;
    pts.style = Series::Style::Points;
    pts.point_radius_px = 4;
    PlotSpec spec;
    spec.title = "Kinect-like depth noise: std of (noisy - true) at normal incidence";
    spec.x_label = "true depth z [m]";
    spec.y_label = "std [mm]";
    spec.width = 1150;
    writeLinePlotPng(path, spec, {curve, nguyen, naive, quant, pts});
  }
}

TEST(DepthNoise, QuantisationOnTopAlsoFollowsItsCurve) {
  const CameraIntrinsics K = vga();
  KinectNoiseOptions opts;
  opts.axial_sigma_includes_quantisation = false;
  for (double z : {1.0, 3.0, 4.5}) {
    ImageF depth, normal;
    wall(z, K, depth, normal);
    const Stats st = centralStats(kinectNoisyDepth(depth, normal, K, opts, 3, 0), z);
    const double sigma = kinectDepthSigma(z, opts, K.fx);
    EXPECT_NEAR(st.std / sigma, 1.0, 0.02) << "z = " << z;
    // Widrow: the quantisation adds step^2 / 12 in variance.
    const double dz = z * z * 0.125 / (K.fx * 0.075);
    EXPECT_NEAR(sigma, std::hypot(nguyenAxialSigma(z, 0), dz / std::sqrt(12.0)), 0.01 * sigma);
  }
}

TEST(DepthNoise, GrazingAnglesAndRangeGiveNoReturn) {
  // A plane through (0, 0, 0.6) tilted 75 degrees about the y axis: along a row the angle between
  // the ray and the normal runs from about 47 to past 90 degrees.
  const CameraIntrinsics K = vga();
  const double a = 75.0 * std::numbers::pi / 180;
  const Eigen::Vector3d n(std::sin(a), 0, -std::cos(a));
  const double c = n.dot(Eigen::Vector3d(0, 0, 0.6));
  ImageF depth(K.width, K.height, 1, 0.f), normal(K.width, K.height, 3, 0.f), theta_deg = depth;
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      const Eigen::Vector3d r = K.rayCamera(x + 0.5, y + 0.5);
      const double t = c / n.dot(r);  // z-depth, as r.z = 1
      if (!(t > 0)) continue;
      depth.at(x, y) = static_cast<float>(t);
      for (int k = 0; k < 3; ++k) normal.at(x, y, k) = static_cast<float>(n[k]);
      theta_deg.at(x, y) =
          static_cast<float>(std::acos(std::abs(n.dot(r.normalized()))) * 180 / std::numbers::pi);
    }
  for (double max_angle : {85.0, 75.0}) {
    KinectNoiseOptions opts;
    opts.max_angle_deg = max_angle;
    const ImageF noisy = kinectNoisyDepth(depth, normal, K, opts, 1, 0);
    size_t beyond = 0, beyond_returned = 0, within = 0, within_returned = 0, far = 0,
           far_returned = 0;
    for (int y = 0; y < K.height; ++y)
      for (int x = 0; x < K.width; ++x) {
        const double z = depth.at(x, y), th = theta_deg.at(x, y);
        const bool ret = noisy.at(x, y) > 0;
        if (z <= 0) {
          EXPECT_FALSE(ret);
          continue;
        }
        if (z > 4.5 || z < 0.4) {
          ++far, far_returned += ret;
        } else if (th > max_angle + 0.3) {
          ++beyond, beyond_returned += ret;
        } else if (th < max_angle - 0.5 && z > 0.45 && z < 4.3) {
          ++within, within_returned += ret;
        }
      }
    std::printf(
        "max angle %.0f: beyond %zu (returned %zu), within %zu (returned %zu), out of "
        "range %zu (returned %zu)\n",
        max_angle, beyond, beyond_returned, within, within_returned, far, far_returned);
    EXPECT_GT(beyond, 5000u);
    EXPECT_EQ(beyond_returned, 0u);
    EXPECT_EQ(far_returned, 0u);
    EXPECT_GT(far, 1000u);
    EXPECT_GT(within, 20000u);
    EXPECT_GT(static_cast<double>(within_returned) / within, 0.99);
  }
}

TEST(DepthNoise, BeyondRangeIsZero) {
  const CameraIntrinsics K = vga();
  for (double z : {0.3, 4.6, 7.0}) {
    ImageF depth, normal;
    wall(z, K, depth, normal);
    const ImageF noisy = kinectNoisyDepth(depth, normal, K, {}, 1, 0);
    for (float v : noisy.data) ASSERT_EQ(v, 0.f) << "z = " << z;
  }
  ImageF depth(K.width, K.height, 1, 0.f), normal(K.width, K.height, 3, 0.f);
  for (float v : kinectNoisyDepth(depth, normal, K, {}, 1, 0).data) ASSERT_EQ(v, 0.f);
}

/// Shadowed columns of row y as a list.
std::vector<int> shadowColumns(const ImageU8& mask, int y) {
  std::vector<int> cols;
  for (int x = 0; x < mask.width; ++x)
    if (mask.at(x, y)) cols.push_back(x);
  return cols;
}

TEST(DepthNoise, ProjectorShadowSideAndWidth) {
  // Box face at z_b over columns [280, 360), wall at z_w. A wall point at column u lies on
  // projector column u - f b / z_w, a box point on u - f b / z_b. With b > 0 the box hides the
  // wall points whose projector column falls in the box's [280, 360) - f b / z_b, i.e. u in
  // [280 - w, 280) with w = f b (1 / z_b - 1 / z_w) = b (z_w - z_b) f / (z_w z_b) pixels: a band
  // on the LEFT of the box. With b < 0 the band is [360, 360 + w) on the right.
  const CameraIntrinsics K = vga();
  const double z_w = 2.9, z_b = 1.1, b = 0.075;
  const double w = b * (z_w - z_b) * K.fx / (z_w * z_b);  // 25.39 px
  ImageF depth, normal;
  boxOnWall(z_w, z_b, 280, 360, 200, 280, K, depth, normal);
  for (double sign : {1.0, -1.0}) {
    const ImageU8 mask = projectorShadowMask(depth, K, sign * b);
    // Expected: pixels whose centre x + 0.5 lies in the continuous band.
    const double lo = sign > 0 ? 280 - w : 360, hi = sign > 0 ? 280 : 360 + w;
    std::vector<int> expected;
    for (int x = 0; x < K.width; ++x)
      if (x + 0.5 >= lo && x + 0.5 < hi) expected.push_back(x);
    ASSERT_EQ(expected.size(), 25u);
    for (int y = 200; y < 280; ++y) ASSERT_EQ(shadowColumns(mask, y), expected) << "row " << y;
    for (int y : {0, 199, 280, 479}) EXPECT_TRUE(shadowColumns(mask, y).empty()) << y;
  }
  // Through the whole pipeline (no edge dropouts): the band has no return, the wall beside it
  // does.
  KinectNoiseOptions opts;
  opts.edge_dropout_px = 0;
  const ImageF noisy = kinectNoisyDepth(depth, normal, K, opts, 5, 0);
  for (int y = 202; y < 278; ++y) {
    for (int x = 256; x < 279; ++x) EXPECT_EQ(noisy.at(x, y), 0.f) << x << "," << y;
    for (int x = 200; x < 253; ++x) EXPECT_GT(noisy.at(x, y), 0.f) << x << "," << y;
    for (int x = 362; x < 440; ++x) EXPECT_GT(noisy.at(x, y), 0.f) << x << "," << y;
  }
}

TEST(DepthNoise, EdgesDropPixels) {
  // Box face at 1.5 m over [160, 480) x [120, 360) on a wall at 3 m; no projector shadow, so
  // every dropout near the edges is an edge dropout. Dropout probability at Chebyshev distance r
  // from the edge pixels (both sides of the jump): 1 - r / 3 for r = 0, 1, 2, and 0 beyond.
  const CameraIntrinsics K = vga();
  ImageF depth, normal;
  boxOnWall(3.0, 1.5, 160, 480, 120, 360, K, depth, normal);
  KinectNoiseOptions opts;
  opts.projector_shadow = false;
  const ImageF noisy = kinectNoisyDepth(depth, normal, K, opts, 11, 0);
  // Distance to the box outline along the top and bottom edges (rows), away from the corners.
  // Edge pixels: rows 119 (wall) and 120 (box) at the top, 359 (box) and 360 (wall) at the bottom.
  auto dropRate = [&](std::initializer_list<int> rows) {
    size_t n = 0, dropped = 0;
    for (int y : rows)
      for (int x = 170; x < 470; ++x) ++n, dropped += noisy.at(x, y) == 0.f;
    return static_cast<double>(dropped) / n;
  };
  const double r0 = dropRate({119, 120, 359, 360}), r1 = dropRate({118, 121, 358, 361});
  const double r2 = dropRate({117, 122, 357, 362}), r3 = dropRate({116, 123, 356, 363});
  std::printf("edge dropout rate at distance 0..3 px: %.3f %.3f %.3f %.3f\n", r0, r1, r2, r3);
  EXPECT_EQ(r0, 1.0);
  EXPECT_NEAR(r1, 2.0 / 3, 0.05);  // 1200 pixels: binomial sd 0.014
  EXPECT_NEAR(r2, 1.0 / 3, 0.05);
  EXPECT_EQ(r3, 0.0);
  // Random, so the outline is ragged: different frames drop different pixels.
  const ImageF other = kinectNoisyDepth(depth, normal, K, opts, 11, 1);
  size_t differ = 0;
  for (int x = 170; x < 470; ++x) differ += (noisy.at(x, 118) == 0.f) != (other.at(x, 118) == 0.f);
  EXPECT_GT(differ, 30u);
}

TEST(DepthNoise, QuantisedToDisparityLevels) {
  // At true depth 2 m, f = 600, b = 0.075: disparity f b / z = 22.5 px. Every output is
  // f b / (k / 8) for an integer k, consecutive levels appear, and neighbouring values are
  // dz = z^2 (1/8) / (f b) = 11.1 mm apart.
  const CameraIntrinsics K = vga();
  ImageF depth, normal;
  wall(2.0, K, depth, normal);
  const ImageF noisy = kinectNoisyDepth(depth, normal, K, {}, 2, 0);
  const double fb = K.fx * 0.075;
  std::set<long> levels;
  for (float v : noisy.data) {
    if (v <= 0) continue;
    const double k = fb / v * 8;
    ASSERT_NEAR(k, std::round(k), 1e-3) << v;
    levels.insert(std::lround(k));
  }
  ASSERT_GE(levels.size(), 5u);
  EXPECT_EQ(static_cast<long>(levels.size()), *levels.rbegin() - *levels.begin() + 1)
      << "levels are contiguous";
  const double dz = 2.0 * 2.0 * 0.125 / fb;
  const long k180 = 180;  // the level of 2 m exactly
  ASSERT_TRUE(levels.count(k180) && levels.count(k180 + 1));
  EXPECT_NEAR(fb / (k180 / 8.0) - fb / ((k180 + 1) / 8.0), dz, 0.01 * dz);
}

TEST(DepthNoise, DeterministicPerSeedFrameAndThreadCount) {
  const CameraIntrinsics K = vga();
  ImageF depth, normal;
  boxOnWall(3.0, 1.2, 200, 400, 150, 330, K, depth, normal);
  const ImageF a = kinectNoisyDepth(depth, normal, K, {}, 42, 3);
  ImageF single;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    single = kinectNoisyDepth(depth, normal, K, {}, 42, 3);
  }
  EXPECT_TRUE(a == single);
  EXPECT_TRUE(a == kinectNoisyDepth(depth, normal, K, {}, 42, 3));
  for (auto [seed, frame] : {std::pair<uint64_t, uint32_t>{42, 4}, {43, 3}}) {
    const ImageF b = kinectNoisyDepth(depth, normal, K, {}, seed, frame);
    size_t differ = 0, both = 0;
    for (size_t i = 0; i < a.data.size(); ++i)
      if (a.data[i] > 0 && b.data[i] > 0) ++both, differ += a.data[i] != b.data[i];
    EXPECT_GT(static_cast<double>(differ) / both, 0.3) << seed << " " << frame;
  }
}

TEST(DepthNoise, NormalsFromDepthMatchThePlane) {
  const CameraIntrinsics K = vga();
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, -1.0).normalized();
  const double c = n.dot(Eigen::Vector3d(0, 0, 2));
  ImageF depth(K.width, K.height, 1, 0.f);
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x)
      depth.at(x, y) = static_cast<float>(c / n.dot(K.rayCamera(x + 0.5, y + 0.5)));
  const ImageF est = normalsFromDepth(depth, K);
  double worst = 0;
  for (int y = 0; y < K.height; y += 7)
    for (int x = 0; x < K.width; x += 7) {
      const Eigen::Vector3d e(est.at(x, y, 0), est.at(x, y, 1), est.at(x, y, 2));
      worst = std::max(worst, (e - n).norm());
    }
  EXPECT_LT(worst, 2e-3);
  // An empty normal image means "estimate": same result as passing the estimate.
  EXPECT_TRUE(kinectNoisyDepth(depth, ImageF{}, K, {}, 1, 0) ==
              kinectNoisyDepth(depth, est, K, {}, 1, 0));
}

TEST(DepthNoise, BadOptionsAreInputErrors) {
  KinectNoiseOptions o;
  o.baseline_m = 0;
  EXPECT_THROW(o.validate("cfg"), InputError);
  o = {};
  o.max_angle_deg = 95;
  EXPECT_THROW(o.validate("cfg"), InputError);
  o = {};
  o.min_range_m = 5;
  EXPECT_THROW(o.validate("cfg"), InputError);
  EXPECT_NO_THROW(KinectNoiseOptions{}.validate());
}

}  // namespace
}  // namespace inet
