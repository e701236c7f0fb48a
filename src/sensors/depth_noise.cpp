#include "sensors/depth_noise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;

double normalCdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

double focalOf(const KinectNoiseOptions& o, const CameraIntrinsics& K) {
  return o.disparity_focal_px > 0 ? o.disparity_focal_px : K.fx;
}

/// Angle between the (camera-facing) normal and the reversed viewing ray through pixel (x, y);
/// 0 when the normal is unknown (all zero or not finite).
double incidenceAngle(const ImageF& normal, const CameraIntrinsics& K, int x, int y) {
  const float* n = normal.pixel(x, y);
  const Eigen::Vector3d nv(n[0], n[1], n[2]);
  const double len = nv.norm();
  if (!(len > 1e-6) || !std::isfinite(len)) return 0.0;
  const Eigen::Vector3d r = K.rayCamera(x + 0.5, y + 0.5).normalized();
  const double c = std::min(1.0, std::abs(nv.dot(r)) / len);
  return std::acos(c);
}

/// Bilinear sample of z at continuous point (u, v) (renderer convention, centres at +0.5) with
/// border replication; the nearest tap's value if any of the four taps has no surface.
double sampleDepth(const ImageF& z, double u, double v) {
  const double fx = u - 0.5, fy = v - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto tap = [&z](int x, int y) {
    return static_cast<double>(z.at(std::clamp(x, 0, z.width - 1), std::clamp(y, 0, z.height - 1)));
  };
  const double z00 = tap(x0, y0), z10 = tap(x0 + 1, y0);
  const double z01 = tap(x0, y0 + 1), z11 = tap(x0 + 1, y0 + 1);
  if (z00 > 0 && z10 > 0 && z01 > 0 && z11 > 0)
    return (1 - ty) * ((1 - tx) * z00 + tx * z10) + ty * ((1 - tx) * z01 + tx * z11);
  return tap(x0 + (tx >= 0.5 ? 1 : 0), y0 + (ty >= 0.5 ? 1 : 0));
}

/// Chebyshev distance (pixels) of each pixel to the nearest depth-edge pixel, capped at `cap`
/// (cap = "farther than cap - 1"). An edge pixel has a surface and a 4-neighbour without one or
/// with a relative depth jump above `ratio`.
std::vector<int> edgeDistance(const ImageF& z, double ratio, int cap) {
  const int W = z.width, H = z.height;
  auto jump = [&](int x, int y, int xn, int yn) {
    if (xn < 0 || yn < 0 || xn >= W || yn >= H) return false;
    const double a = z.at(x, y), b = z.at(xn, yn);
    return !(b > 0) || std::abs(a - b) > ratio * std::min(a, b);
  };
  std::vector<int> horiz(z.pixelCount(), cap);
  for (int y = 0; y < H; ++y) {
    std::vector<char> edge(W, 0);
    for (int x = 0; x < W; ++x)
      edge[x] = z.at(x, y) > 0 && (jump(x, y, x - 1, y) || jump(x, y, x + 1, y) ||
                                   jump(x, y, x, y - 1) || jump(x, y, x, y + 1));
    for (int x = 0; x < W; ++x)
      for (int dx = -(cap - 1); dx <= cap - 1; ++dx)
        if (x + dx >= 0 && x + dx < W && edge[x + dx])
          horiz[static_cast<size_t>(y) * W + x] =
              std::min(horiz[static_cast<size_t>(y) * W + x], std::abs(dx));
  }
  std::vector<int> dist(z.pixelCount(), cap);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      int d = cap;
      for (int dy = -(cap - 1); dy <= cap - 1; ++dy)
        if (y + dy >= 0 && y + dy < H)
          d = std::min(d, std::max(std::abs(dy), horiz[static_cast<size_t>(y + dy) * W + x]));
      dist[static_cast<size_t>(y) * W + x] = d;
    }
  return dist;
}

}  // namespace

void KinectNoiseOptions::validate(const std::string& source) const {
  auto need = [&](bool ok, const char* field, const std::string& what) {
    if (!ok) throw InputError(source, field, what);
  };
  need(std::isfinite(baseline_m) && std::abs(baseline_m) >= 1e-4 && std::abs(baseline_m) <= 10,
       "baseline_m", "must be finite, non-zero, |b| in [1e-4, 10] m");
  need(std::isfinite(disparity_focal_px) && disparity_focal_px >= 0, "disparity_focal_px",
       "must be >= 0 (0 = the image's fx)");
  need(std::isfinite(disparity_step_px) && disparity_step_px >= 0 && disparity_step_px <= 10,
       "disparity_step_px", "must be in [0, 10] px (0 = no quantisation)");
  need(std::isfinite(min_range_m) && min_range_m >= 0 && std::isfinite(max_range_m) &&
           max_range_m > min_range_m,
       "min_range_m/max_range_m", "need 0 <= min_range_m < max_range_m, finite");
  need(std::isfinite(max_angle_deg) && max_angle_deg > 0 && max_angle_deg <= 90, "max_angle_deg",
       "must be in (0, 90]");
  need(std::isfinite(edge_dropout_px) && edge_dropout_px >= 0 && edge_dropout_px <= 32,
       "edge_dropout_px", "must be in [0, 32]");
  need(edge_dropout_prob >= 0 && edge_dropout_prob <= 1, "edge_dropout_prob", "must be in [0, 1]");
  need(std::isfinite(edge_jump_ratio) && edge_jump_ratio > 0, "edge_jump_ratio", "must be > 0");
  need(std::isfinite(lateral_scale) && lateral_scale >= 0, "lateral_scale", "must be >= 0");
  need(std::isfinite(axial_scale) && axial_scale >= 0, "axial_scale", "must be >= 0");
}

std::string KinectNoiseOptions::toString() const {
  return fmt::format(
      "KinectNoiseOptions(baseline_m={}, disparity_focal_px={}, disparity_step_px={}, "
      "range_m=[{}, {}], max_angle_deg={}, edge_dropout_px={}, edge_dropout_prob={}, "
      "edge_jump_ratio={}, lateral_scale={}, axial_scale={}, "
      "axial_sigma_includes_quantisation={}, projector_shadow={})",
      baseline_m, disparity_focal_px, disparity_step_px, min_range_m, max_range_m, max_angle_deg,
      edge_dropout_px, edge_dropout_prob, edge_jump_ratio, lateral_scale, axial_scale,
      axial_sigma_includes_quantisation, projector_shadow);
}

double nguyenAxialSigma(double z_m, double theta_rad) {
  const double t = std::clamp(theta_rad, 0.0, kHalfPi - 1e-6);
  const double g = t / (kHalfPi - t);
  return 0.0012 + 0.0019 * (z_m - 0.4) * (z_m - 0.4) + 0.0001 / std::sqrt(z_m) * g * g;
}

double nguyenLateralSigmaPx(double theta_rad) {
  const double t = std::clamp(theta_rad, 0.0, kHalfPi - 1e-6);
  return 0.8 + 0.035 * t / (kHalfPi - t);
}

double kinectAxialSigma(double z_m, double theta_rad, const KinectNoiseOptions& opts,
                        double focal_px) {
  const double s = opts.axial_scale * nguyenAxialSigma(z_m, theta_rad);
  if (!opts.axial_sigma_includes_quantisation || opts.disparity_step_px <= 0) return s;
  const double dz = z_m * z_m * opts.disparity_step_px / (focal_px * std::abs(opts.baseline_m));
  return std::sqrt(std::max(s * s - dz * dz / 12.0, 0.0));
}

double kinectDepthSigma(double z_m, const KinectNoiseOptions& opts, double focal_px) {
  const double sigma = kinectAxialSigma(z_m, 0.0, opts, focal_px);
  const double step = opts.disparity_step_px;
  const double fb = focal_px * std::abs(opts.baseline_m);
  if (step <= 0) return sigma;
  // Output level k: disparity k * step, depth fb / (k step); it collects the z' = z + sigma n
  // with fb / z' in [(k - 1/2) step, (k + 1/2) step) (round half up).
  if (sigma <= 0) return 0.0;  // every pixel gives the same level
  const double z_lo = std::max(z_m - 12 * sigma, 1e-3 * z_m), z_hi = z_m + 12 * sigma;
  const long k_min = std::max(1L, static_cast<long>(std::floor(fb / (z_hi * step) + 0.5)));
  const long k_max = static_cast<long>(std::floor(fb / (z_lo * step) + 0.5));
  double p_sum = 0, m1 = 0, m2 = 0;
  for (long k = k_min; k <= k_max; ++k) {
    const double z_near = fb / ((k + 0.5) * step), z_far = fb / ((k - 0.5) * step);
    const double p = normalCdf((z_far - z_m) / sigma) - normalCdf((z_near - z_m) / sigma);
    const double e = fb / (k * step) - z_m;
    p_sum += p;
    m1 += p * e;
    m2 += p * e * e;
  }
  m1 /= p_sum;
  return std::sqrt(std::max(m2 / p_sum - m1 * m1, 0.0));
}

ImageF normalsFromDepth(const ImageF& z, const CameraIntrinsics& K) {
  INET_CHECK(z.channels == 1);
  ImageF out(z.width, z.height, 3, 0.f);
  auto point = [&](int x, int y) -> Eigen::Vector3d {
    return K.rayCamera(x + 0.5, y + 0.5) * static_cast<double>(z.at(x, y));
  };
  // Difference towards the neighbour with the smaller depth jump (so as not to differentiate
  // across an edge); zero if neither neighbour has a surface.
  auto diff = [&](int x, int y, int dx, int dy, Eigen::Vector3d& d) {
    const double zc = z.at(x, y);
    double best = std::numeric_limits<double>::infinity();
    for (int s : {1, -1}) {
      const int xn = x + s * dx, yn = y + s * dy;
      if (xn < 0 || yn < 0 || xn >= z.width || yn >= z.height || !(z.at(xn, yn) > 0)) continue;
      const double j = std::abs(z.at(xn, yn) - zc);
      if (j < best) {
        best = j;
        d = (point(xn, yn) - point(x, y)) * s;
      }
    }
    return std::isfinite(best);
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, z.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < z.width; ++x) {
        Eigen::Vector3d du, dv;
        if (!(z.at(x, y) > 0) || !diff(x, y, 1, 0, du) || !diff(x, y, 0, 1, dv)) continue;
        Eigen::Vector3d n = du.cross(dv);
        if (!(n.norm() > 0)) continue;
        n.normalize();
        if (n.dot(point(x, y)) > 0) n = -n;  // face the camera
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(n[c]);
      }
  });
  return out;
}

ImageU8 projectorShadowMask(const ImageF& z, const CameraIntrinsics& K, double baseline_m) {
  INET_CHECK(z.channels == 1);
  ImageU8 mask(z.width, z.height, 1, 0);
  const double fb = K.fx * baseline_m;
  constexpr double kEps = 1e-3;  // px: a smooth surface never shadows itself by rounding
  tbb::parallel_for(tbb::blocked_range<int>(0, z.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      // Scan from the projector's side: the projector column u_p = u - f b / z of a visible
      // point must keep decreasing (b > 0, scanning right to left) or increasing (b < 0).
      double extreme = baseline_m > 0 ? std::numeric_limits<double>::infinity()
                                      : -std::numeric_limits<double>::infinity();
      for (int i = 0; i < z.width; ++i) {
        const int x = baseline_m > 0 ? z.width - 1 - i : i;
        const double zz = z.at(x, y);
        if (!(zz > 0)) continue;  // no surface: blocks nothing
        const double up = x + 0.5 - fb / zz;
        if (baseline_m > 0 ? up > extreme + kEps : up < extreme - kEps) mask.at(x, y) = 1;
        extreme = baseline_m > 0 ? std::min(extreme, up) : std::max(extreme, up);
      }
    }
  });
  return mask;
}

ImageF kinectNoisyDepth(const ImageF& z, const ImageF& normal_cam, const CameraIntrinsics& K,
                        const KinectNoiseOptions& opts, uint64_t seed, uint32_t frame) {
  opts.validate();
  INET_CHECK(z.channels == 1 && z.width == K.width && z.height == K.height);
  const ImageF estimated = normal_cam.empty() ? normalsFromDepth(z, K) : ImageF{};
  const ImageF& normal = normal_cam.empty() ? estimated : normal_cam;
  INET_CHECK(normal.channels == 3 && normal.width == z.width && normal.height == z.height);
  const double f_d = focalOf(opts, K);
  const double fb = f_d * std::abs(opts.baseline_m);
  const double step = opts.disparity_step_px;
  const double max_theta = opts.max_angle_deg * std::numbers::pi / 180.0;
  const ImageU8 shadow =
      opts.projector_shadow ? projectorShadowMask(z, K, opts.baseline_m) : ImageU8{};
  const double w = opts.edge_dropout_px;
  const int cap = std::max(1, static_cast<int>(std::ceil(w)));
  const std::vector<int> edge =
      w > 0 ? edgeDistance(z, opts.edge_jump_ratio, cap) : std::vector<int>{};
  ImageF out(z.width, z.height, 1, 0.f);
  tbb::parallel_for(tbb::blocked_range<int>(0, z.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < z.width; ++x) {
        const size_t idx = static_cast<size_t>(y) * z.width + x;
        // Fixed draws per pixel: lateral shift (2), axial (1, its pair unused), dropout (1).
        CounterRng rng(seed, RngStream::Sensor, frame, static_cast<uint32_t>(idx),
                       kDepthNoiseRngTag);
        double sx, sy, na, unused;
        rng.normalPair(sx, sy);
        rng.normalPair(na, unused);
        const double u_drop = rng.uniformDouble();
        // 1. Returns that cannot exist.
        const double z0 = z.at(x, y);
        if (!(z0 > 0) || z0 < opts.min_range_m || z0 > opts.max_range_m) continue;
        if (!shadow.empty() && shadow.at(x, y)) continue;
        const double theta = incidenceAngle(normal, K, x, y);
        if (theta > max_theta) continue;
        if (!edge.empty() && edge[idx] < w &&
            u_drop < opts.edge_dropout_prob * (1.0 - edge[idx] / w))
          continue;
        // 2. Lateral: read the depth at a jittered position.
        const double sigma_l = opts.lateral_scale * nguyenLateralSigmaPx(theta);
        const double zl = sampleDepth(z, x + 0.5 + sigma_l * sx, y + 0.5 + sigma_l * sy);
        if (!(zl > 0)) continue;
        // 3. Axial.
        double zn = zl + kinectAxialSigma(zl, theta, opts, f_d) * na;
        // 4. Disparity quantisation.
        if (step > 0) {
          if (!(zn > 0)) continue;
          const double level = std::floor(fb / (zn * step) + 0.5);
          if (!(level >= 1)) continue;  // disparity rounds to 0: infinitely far, no return
          zn = fb / (level * step);
        }
        if (zn > 0) out.at(x, y) = static_cast<float>(zn);
      }
  });
  return out;
}

}  // namespace inet
