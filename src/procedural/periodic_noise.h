#pragma once
// Periodic (tileable) noise for procedural textures: gradient noise on a lattice that wraps
// around, its fractal sum (fBm), and cellular (Worley) noise on a wrapping grid of jittered
// points.
//
// Coordinates are texture uv in units of the whole texture: a field with period (pu, pv) lattice
// cells repeats exactly when u or v moves by 1, so every image sampled from it tiles seamlessly.
// Any real uv is accepted (domain warping may push it outside [0, 1)).
//
// Why hand-written: no Debian package offers seamless procedural texture synthesis as a C++
// library (libnoise is not periodic; FastNoise and OpenSimplex are not packaged), and the
// periodic lattice is ~100 lines. Gradient noise follows Perlin, "Improving Noise" (SIGGRAPH
// 2002): n(x) = sum over the 4 lattice corners c of fade-weighted g_c . (x - c), with the quintic
// fade 6t^5 - 15t^4 + 10t^3 and random unit gradients g_c.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "core/rng.h"

namespace inet {

/// Gradient noise with `pu` x `pv` lattice cells across the texture; values in about [-1, 1],
/// mean 0. Deterministic in the RNG it is built from. The lattice is shifted by a random offset
/// (any shift keeps the period): otherwise every octave of an fBm would put a lattice line, where
/// gradient noise is steepest, exactly on the texture's border and the border would stand out.
class PeriodicNoise {
 public:
  PeriodicNoise(int pu, int pv, CounterRng& rng) : pu_(pu), pv_(pv) {
    INET_CHECK(pu > 0 && pv > 0);
    off_u_ = rng.uniform();
    off_v_ = rng.uniform();
    grad_.resize(static_cast<size_t>(pu) * pv * 2);
    for (size_t i = 0; i < grad_.size(); i += 2) {
      float a = 2.0f * std::numbers::pi_v<float> * rng.uniform();
      grad_[i] = std::cos(a);
      grad_[i + 1] = std::sin(a);
    }
  }

  float operator()(float u, float v) const {
    float x = (u + off_u_) * static_cast<float>(pu_), y = (v + off_v_) * static_cast<float>(pv_);
    float fx = std::floor(x), fy = std::floor(y);
    float tx = x - fx, ty = y - fy;
    int ix0 = wrap(static_cast<long>(fx), pu_), iy0 = wrap(static_cast<long>(fy), pv_);
    int ix1 = ix0 + 1 == pu_ ? 0 : ix0 + 1, iy1 = iy0 + 1 == pv_ ? 0 : iy0 + 1;
    float n00 = dot(ix0, iy0, tx, ty), n10 = dot(ix1, iy0, tx - 1.0f, ty);
    float n01 = dot(ix0, iy1, tx, ty - 1.0f), n11 = dot(ix1, iy1, tx - 1.0f, ty - 1.0f);
    float sx = fade(tx), sy = fade(ty);
    float a = n00 + sx * (n10 - n00), b = n01 + sx * (n11 - n01);
    return 1.4142f * (a + sy * (b - a));  // sqrt(2) scales the +-sqrt(1/2) extremes to +-1
  }

  static int wrap(long i, int p) {
    long m = i % p;
    return static_cast<int>(m < 0 ? m + p : m);
  }

 private:
  static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
  float dot(int ix, int iy, float dx, float dy) const {
    const float* g = &grad_[(static_cast<size_t>(iy) * pu_ + ix) * 2];
    return g[0] * dx + g[1] * dy;
  }
  int pu_, pv_;
  float off_u_ = 0.0f, off_v_ = 0.0f;  ///< lattice shift, texture units
  std::vector<float> grad_;
};

/// Fractal sum of `octaves` PeriodicNoise layers; octave k has (pu, pv) * 2^k cells and weight
/// gain^k. The sum is divided by the sum of weights, so values stay in about [-1, 1].
/// turbulence() sums |noise| instead (creased, in [0, 1]), as in Perlin's marble.
class PeriodicFbm {
 public:
  PeriodicFbm(int pu, int pv, int octaves, float gain, CounterRng& rng) {
    float w = 1.0f, total = 0.0f;
    for (int k = 0; k < octaves; ++k) {
      layers_.emplace_back(pu << k, pv << k, rng);
      weights_.push_back(w);
      total += w;
      w *= gain;
    }
    for (float& x : weights_) x /= total;
  }
  float operator()(float u, float v) const {
    float s = 0.0f;
    for (size_t k = 0; k < layers_.size(); ++k) s += weights_[k] * layers_[k](u, v);
    return s;
  }
  float turbulence(float u, float v) const {
    float s = 0.0f;
    for (size_t k = 0; k < layers_.size(); ++k) s += weights_[k] * std::abs(layers_[k](u, v));
    return s;
  }

 private:
  std::vector<PeriodicNoise> layers_;
  std::vector<float> weights_;
};

/// Cellular noise (Worley, "A cellular texture basis function", SIGGRAPH 1996) over feature
/// points spread by periodic dart throwing (a Poisson-disc set: no two points closer than
/// `min_spacing`). Neither jittered-grid points (their Voronoi edges crowd onto the grid lines, so
/// the grid shows) nor Poisson points (clumps make tiny cells) look like grain. About n x n points;
/// distances are in units of the mean spacing 1 / n. Returns the distances to the nearest (f1)
/// and second nearest (f2) points and the nearest point's index (for per-grain colours).
class PeriodicCells {
 public:
  struct Hit {
    float f1, f2;
    int point;  ///< index of the nearest feature point, in [0, points())
  };
  PeriodicCells(int n, float min_spacing, CounterRng& rng) : n_(n), cells_(n * n) {
    INET_CHECK(n > 0 && min_spacing > 0.0f && min_spacing < 1.0f);
    float r2 = min_spacing * min_spacing;
    // Darts in grid units; a point is kept if no kept point in the 3 x 3 cells is within r.
    for (int attempt = 0; attempt < 30 * n * n && points() < n * n; ++attempt) {
      float x = rng.uniform() * static_cast<float>(n), y = rng.uniform() * static_cast<float>(n);
      if (nearest2(x, y, 1) >= r2) {
        int id = static_cast<int>(y) * n + static_cast<int>(x);
        cells_[id].push_back(static_cast<int>(pts_.size() / 2));
        pts_.push_back(x);
        pts_.push_back(y);
      }
    }
  }
  int points() const { return static_cast<int>(pts_.size() / 2); }
  Hit operator()(float u, float v) const {
    Hit h{1e9f, 1e9f, 0};
    // Two cells around: empty cells are common, and a 3 x 3 search would break f2 along the
    // grid lines (visible lines).
    visit(u * static_cast<float>(n_), v * static_cast<float>(n_), 2, [&](float d, int k) {
      if (d < h.f1) {
        h.f2 = h.f1;
        h.f1 = d;
        h.point = k;
      } else if (d < h.f2) {
        h.f2 = d;
      }
    });
    h.f1 = std::sqrt(h.f1);
    h.f2 = std::sqrt(h.f2);
    return h;
  }

 private:
  /// Calls f(squared distance, point index) for the points in the (2 r + 1)^2 cells around (x, y)
  /// (grid units), with the periodic image of each point nearest to (x, y).
  template <typename F>
  void visit(float x, float y, int r, F&& f) const {
    long cx = static_cast<long>(std::floor(x)), cy = static_cast<long>(std::floor(y));
    for (long j = cy - r; j <= cy + r; ++j) {
      for (long i = cx - r; i <= cx + r; ++i) {
        int wi = PeriodicNoise::wrap(i, n_), wj = PeriodicNoise::wrap(j, n_);
        float sx = static_cast<float>(i - wi), sy = static_cast<float>(j - wj);  // image shift
        for (int k : cells_[wj * n_ + wi]) {
          float dx = pts_[k * 2] + sx - x, dy = pts_[k * 2 + 1] + sy - y;
          f(dx * dx + dy * dy, k);
        }
      }
    }
  }
  float nearest2(float x, float y, int r) const {
    float best = 1e9f;
    visit(x, y, r, [&](float d, int) { best = std::min(best, d); });
    return best;
  }

  int n_;
  std::vector<std::vector<int>> cells_;  ///< point indices per grid cell
  std::vector<float> pts_;               ///< x, y in grid units, in [0, n)
};

}  // namespace inet
