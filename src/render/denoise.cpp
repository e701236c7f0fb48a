#include "render/denoise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/text.h"

// Lets the compiler vectorise the per-tap loops without run-time alias checks: every output
// array written there is distinct from every input array.
#if defined(__clang__)
#define INET_IVDEP _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define INET_IVDEP _Pragma("GCC ivdep")
#else
#define INET_IVDEP
#endif

// The tap loop is the hot spot (about 3/4 of the time): also build it for AVX2, picked at run
// time. AVX2 without FMA performs the same IEEE operations in the same order as the SSE2
// baseline, so the bytes do not depend on which version runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define INET_TAP_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define INET_TAP_CLONES
#endif

namespace inet {
namespace {

constexpr float kLumR = 0.2126f, kLumG = 0.7152f, kLumB = 0.0722f;  // Rec. 709 luminance
constexpr float kB3[5] = {1.f / 16, 1.f / 4, 3.f / 8, 1.f / 4, 1.f / 16};
constexpr int kRowGrain = 4;
constexpr int kTile = 16;  // tile size of the robust noise estimate

/// body(y) for every row, in parallel. Rows are independent, so the order does not matter.
template <typename Body>
void forEachRow(int height, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, kRowGrain), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) body(y);
  });
}

/// e^-s for s >= 0, with ~3e-6 relative error, and exactly 0 for s > 20 (and for +inf, NaN):
/// weights below e^-20 change no result but would make w^2 and products underflow into slow
/// denormals. 2^t = 2^round(t) 2^f, f in [-0.5, 0.5], with the degree-5 Taylor polynomial of
/// 2^f = e^(f ln 2). Deterministic (no libm) and branch-free so the tap loops vectorise: the
/// cut-off compares the bit patterns as integers (ordered like the floats for s >= 0), because a
/// float compare may trap and GCC then refuses to if-convert it.
inline float expNegative(float s) {
  constexpr int32_t kCutBits = std::bit_cast<int32_t>(20.f);
  constexpr float kRound = 12582912.f;  // 1.5 * 2^23: adding it rounds to an integer
  int32_t bits = std::bit_cast<int32_t>(s);
  int32_t keep = -static_cast<int32_t>(bits <= kCutBits);  // all ones or all zeros
  bits = (bits & keep) | (kCutBits & ~keep);
  float t = std::bit_cast<float>(bits) * -1.44269504f;  // log2(e^-s), in [-28.9, 0]
  float r = t + kRound;
  int32_t i = std::bit_cast<int32_t>(r) - std::bit_cast<int32_t>(kRound);
  float f = t - (r - kRound);
  float p = 1.f + f * (0.69314718f +
                       f * (0.24022651f + f * (0.05550411f + f * (0.00961813f + f * 0.00133336f))));
  return std::bit_cast<float>((std::bit_cast<int32_t>(p) + i * (1 << 23)) & keep);
}

/// Per-pixel guide data, constant over the iterations. Structure of arrays, row-major.
struct Guide {
  int width = 0, height = 0;
  std::vector<float> nx, ny, nz;  // camera-frame normal
  std::vector<float> iz, gx, gy;  // inverse z-depth and its screen gradient (per pixel)
  std::vector<float> z_tol_inv;   // z / sigma_depth: 1 / tolerance of the inverse depth
  std::vector<float> ar, ag, ab;  // albedo
  std::vector<float> valid;       // 1 = surface with finite colour, 0 = pass through

  size_t size() const { return static_cast<size_t>(width) * height; }
};

/// The filtered signal: demodulated colour, its luminance and the variance of that luminance.
/// Invalid pixels hold 0 so that a zero weight times their value stays 0.
struct Signal {
  std::vector<float> r, g, b, lum, var;
  explicit Signal(size_t n) : r(n), g(n), b(n), lum(n), var(n) {}
};

bool hasSurface(const ImageF& normal, const ImageF& depth, int x, int y) {
  float z = depth.at(x, y);
  const float* n = normal.pixel(x, y);
  bool normal_ok = std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) &&
                   (n[0] != 0.f || n[1] != 0.f || n[2] != 0.f);
  return z > 0.f && std::isfinite(z) && normal_ok;
}

/// One-sided difference with the smaller magnitude, so a gradient next to an occlusion edge is
/// taken from the pixel's own surface.
float robustGradient(const Guide& g, size_t i, size_t stride, bool has_lo, bool has_hi) {
  bool lo = has_lo && g.valid[i - stride] > 0.f;
  bool hi = has_hi && g.valid[i + stride] > 0.f;
  float d_lo = lo ? g.iz[i] - g.iz[i - stride] : 0.f;
  float d_hi = hi ? g.iz[i + stride] - g.iz[i] : 0.f;
  if (lo && hi) return std::fabs(d_lo) <= std::fabs(d_hi) ? d_lo : d_hi;
  return lo ? d_lo : d_hi;
}

Guide buildGuide(const ImageF& rgb, const ImageF& albedo, const ImageF& normal, const ImageF& depth,
                 const DenoiseOptions& opt) {
  Guide g;
  g.width = rgb.width;
  g.height = rgb.height;
  size_t n = g.size();
  for (auto* v :
       {&g.nx, &g.ny, &g.nz, &g.iz, &g.gx, &g.gy, &g.z_tol_inv, &g.ar, &g.ag, &g.ab, &g.valid})
    v->assign(n, 0.f);
  forEachRow(g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      size_t i = static_cast<size_t>(y) * g.width + x;
      const float* c = rgb.pixel(x, y);
      const float* a = albedo.pixel(x, y);
      bool finite = std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) &&
                    std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
      if (!finite || !hasSurface(normal, depth, x, y)) continue;
      const float* nn = normal.pixel(x, y);
      g.valid[i] = 1.f;
      g.nx[i] = nn[0], g.ny[i] = nn[1], g.nz[i] = nn[2];
      g.ar[i] = a[0], g.ag[i] = a[1], g.ab[i] = a[2];
      g.iz[i] = 1.f / depth.at(x, y);
      g.z_tol_inv[i] = depth.at(x, y) / opt.sigma_depth;
    }
  });
  const size_t stride = static_cast<size_t>(g.width);
  forEachRow(g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      size_t i = static_cast<size_t>(y) * g.width + x;
      if (g.valid[i] == 0.f) continue;
      g.gx[i] = robustGradient(g, i, 1, x > 0, x + 1 < g.width);
      g.gy[i] = robustGradient(g, i, stride, y > 0, y + 1 < g.height);
    }
  });
  return g;
}

float luminance(float r, float g, float b) {
  return kLumR * r + kLumG * g + kLumB * b;
}

/// The factor the filter divides pixel i's colour by and multiplies its result by:
/// max(albedo, eps) per channel, or 1 where the light is not the albedo's (eps = 0).
std::array<float, 3> modulation(const Guide& g, float eps, size_t i) {
  if (eps == 0.f) return {1.f, 1.f, 1.f};
  return {std::max(g.ar[i], eps), std::max(g.ag[i], eps), std::max(g.ab[i], eps)};
}

/// Pixel i of the irradiance E = rgb / modulation and, if given, of the variance of E's
/// luminance.
void demodulatePixel(const ImageF& rgb, const ImageF* variance, const Guide& g, float eps, size_t i,
                     Signal& s) {
  const float* c = rgb.data.data() + 3 * i;
  const std::array<float, 3> m = modulation(g, eps, i);
  const float inv[3] = {1.f / m[0], 1.f / m[1], 1.f / m[2]};
  s.r[i] = c[0] * inv[0], s.g[i] = c[1] * inv[1], s.b[i] = c[2] * inv[2];
  s.lum[i] = luminance(s.r[i], s.g[i], s.b[i]);
  if (!variance) return;
  const float* v = variance->data.data() + static_cast<size_t>(variance->channels) * i;
  float sd[3];
  for (int k = 0; k < 3; ++k) {
    float vk = v[variance->channels == 3 ? k : 0];
    sd[k] = std::isfinite(vk) && vk > 0.f ? std::sqrt(vk) * inv[k] : 0.f;
  }
  float sd_lum = luminance(sd[0], sd[1], sd[2]);  // channels assumed fully correlated
  s.var[i] = sd_lum * sd_lum;
}

Signal demodulate(const ImageF& rgb, const ImageF* variance, const Guide& g, float eps) {
  Signal s(g.size());
  forEachRow(g.height, [&](int y) {
    for (size_t i = static_cast<size_t>(y) * g.width; i < static_cast<size_t>(y + 1) * g.width; ++i)
      if (g.valid[i] != 0.f) demodulatePixel(rgb, variance, g, eps, i, s);
  });
  return s;
}

/// The exponent of the filter's geometric edge stops between pixel i and its neighbour q at
/// offset (dx, dy): normal, depth plane and albedo (no colour). addTap computes the same over
/// whole rows in straight-line code so that it vectorises.
float geometricStop(const Guide& g, size_t i, size_t q, float dx, float dy, float sigma_normal,
                    float inv_two_sa2) {
  const float en =
      sigma_normal * std::fabs(1.f - (g.nx[i] * g.nx[q] + g.ny[i] * g.ny[q] + g.nz[i] * g.nz[q]));
  const float ez = std::fabs(g.iz[q] - (g.iz[i] + g.gx[i] * dx + g.gy[i] * dy)) * g.z_tol_inv[i];
  const float da0 = g.ar[i] - g.ar[q], da1 = g.ag[i] - g.ag[q], da2 = g.ab[i] - g.ab[q];
  return en + ez + (da0 * da0 + da1 * da1 + da2 * da2) * inv_two_sa2;
}

/// Residual of the luminance against the mean of its 4 neighbours, if all 4 lie on the same
/// surface (geometric weight > 1/2); NaN otherwise.
float residual(const Guide& g, const Signal& s, int x, int y, const DenoiseOptions& opt) {
  if (x == 0 || y == 0 || x + 1 == g.width || y + 1 == g.height) return NAN;
  size_t i = static_cast<size_t>(y) * g.width + x;
  if (g.valid[i] == 0.f) return NAN;
  const long offs[4] = {-1, 1, -static_cast<long>(g.width), static_cast<long>(g.width)};
  const float dxs[4] = {-1, 1, 0, 0}, dys[4] = {0, 0, -1, 1};
  const float inv_two_sa2 = 1.f / (2.f * opt.sigma_albedo * opt.sigma_albedo);
  float sum = 0.f;
  for (int k = 0; k < 4; ++k) {
    size_t q = static_cast<size_t>(static_cast<long>(i) + offs[k]);
    if (g.valid[q] == 0.f) return NAN;
    float e = geometricStop(g, i, q, dxs[k], dys[k], opt.sigma_normal, inv_two_sa2);
    if (!(e < 0.6931472f)) return NAN;
    sum += s.lum[q];
  }
  return s.lum[i] - 0.25f * sum;
}

/// Robust noise level when the caller has no variance: per kTile x kTile tile, sigma = 1.4826
/// median|residual| / sqrt(1 + 1/4) (the residual of iid noise against a 4-neighbour mean has
/// variance 5/4 sigma^2); tiles with too few samples take the median over tiles; the variance is
/// interpolated bilinearly between tile centres.
void estimateVariance(const Guide& g, Signal& s, const DenoiseOptions& opt) {
  const int tw = (g.width + kTile - 1) / kTile, th = (g.height + kTile - 1) / kTile;
  std::vector<float> sigma(static_cast<size_t>(tw) * th, NAN);
  tbb::parallel_for(0, th, [&](int ty) {
    std::vector<float> abs_res;
    for (int tx = 0; tx < tw; ++tx) {
      abs_res.clear();
      for (int y = ty * kTile; y < std::min(g.height, (ty + 1) * kTile); ++y)
        for (int x = tx * kTile; x < std::min(g.width, (tx + 1) * kTile); ++x) {
          float r = residual(g, s, x, y, opt);
          if (!std::isnan(r)) abs_res.push_back(std::fabs(r));
        }
      if (abs_res.size() < kTile * kTile / 8) continue;
      auto mid = abs_res.begin() + abs_res.size() / 2;
      std::nth_element(abs_res.begin(), mid, abs_res.end());
      sigma[static_cast<size_t>(ty) * tw + tx] = 1.4826f * *mid / std::sqrt(1.25f);
    }
  });
  std::vector<float> known;
  for (float v : sigma)
    if (!std::isnan(v)) known.push_back(v);
  float fallback = 0.f;
  if (!known.empty()) {
    std::nth_element(known.begin(), known.begin() + known.size() / 2, known.end());
    fallback = known[known.size() / 2];
  }
  for (float& v : sigma)
    if (std::isnan(v)) v = fallback;
  auto tileVar = [&](int tx, int ty) {
    float v =
        sigma[static_cast<size_t>(std::clamp(ty, 0, th - 1)) * tw + std::clamp(tx, 0, tw - 1)];
    return v * v;
  };
  for (int y = 0; y < g.height; ++y) {
    float fy = (y + 0.5f) / kTile - 0.5f;
    int ty = static_cast<int>(std::floor(fy));
    float wy = fy - ty;
    for (int x = 0; x < g.width; ++x) {
      float fx = (x + 0.5f) / kTile - 0.5f;
      int tx = static_cast<int>(std::floor(fx));
      float wx = fx - tx;
      size_t i = static_cast<size_t>(y) * g.width + x;
      s.var[i] = g.valid[i] == 0.f
                     ? 0.f
                     : (1 - wy) * ((1 - wx) * tileVar(tx, ty) + wx * tileVar(tx + 1, ty)) +
                           wy * ((1 - wx) * tileVar(tx, ty + 1) + wx * tileVar(tx + 1, ty + 1));
    }
  }
}

/// The 3x3 Gaussian (1 2 1 x 1 2 1) of v over valid pixels, per pixel (0 where no neighbour
/// is valid).
std::vector<float> gaussian3x3(const Guide& g, const std::vector<float>& v) {
  std::vector<float> out(g.size(), 0.f);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, kRowGrain), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < g.width; ++x) {
        float sum = 0.f, wsum = 0.f;
        for (int dy = -1; dy <= 1; ++dy) {
          if (y + dy < 0 || y + dy >= g.height) continue;
          for (int dx = -1; dx <= 1; ++dx) {
            if (x + dx < 0 || x + dx >= g.width) continue;
            size_t q = static_cast<size_t>(y + dy) * g.width + (x + dx);
            float k = (dx == 0 ? 2.f : 1.f) * (dy == 0 ? 2.f : 1.f) * g.valid[q];
            sum += k * v[q];
            wsum += k;
          }
        }
        out[static_cast<size_t>(y) * g.width + x] = wsum > 0.f ? sum / wsum : 0.f;
      }
    }
  });
  return out;
}

/// 1 / (sigma_color * sqrt(3x3 Gaussian of the variance over valid pixels) + 1e-8) per pixel.
std::vector<float> colourScale(const Guide& g, const Signal& s, float sigma_color) {
  std::vector<float> out = gaussian3x3(g, s.var);
  for (float& v : out) v = 1.f / (sigma_color * std::sqrt(v) + 1e-8f);
  return out;
}

/// Running sums of one output row.
struct RowSums {
  std::vector<float> r, g, b, w, v;
  explicit RowSums(int width) : r(width), g(width), b(width), w(width), v(width) {}
  void clear() {
    for (auto* a : {&r, &g, &b, &w, &v}) std::fill(a->begin(), a->end(), 0.f);
  }
};

struct TapContext {
  const Guide& g;
  const Signal& in;
  const float* lum;  ///< the luminance edges are stopped on (in.lum, or its prefiltered copy)
  const std::vector<float>& colour_scale;
  float sigma_normal, inv_two_sa2;
};

/// Adds tap (dx, dy) with spatial weight hw to the sums of row y, over the columns whose
/// neighbour is inside the image. Straight-line code over arrays so it vectorises.
INET_TAP_CLONES void addTap(const TapContext& c, int y, int dx, int dy, float hw, RowSums& sums) {
  const Guide& g = c.g;
  const int x0 = std::max(0, -dx), x1 = std::min(g.width, g.width - dx);
  const size_t p0 = static_cast<size_t>(y) * g.width + x0;
  const size_t q0 = static_cast<size_t>(y + dy) * g.width + (x0 + dx);
  const float *pnx = &g.nx[p0], *pny = &g.ny[p0], *pnz = &g.nz[p0], *piz = &g.iz[p0];
  const float *pgx = &g.gx[p0], *pgy = &g.gy[p0], *pzt = &g.z_tol_inv[p0];
  const float *par = &g.ar[p0], *pag = &g.ag[p0], *pab = &g.ab[p0];
  const float *plum = &c.lum[p0], *pcs = &c.colour_scale[p0];
  const float *qnx = &g.nx[q0], *qny = &g.ny[q0], *qnz = &g.nz[q0], *qiz = &g.iz[q0];
  const float *qar = &g.ar[q0], *qag = &g.ag[q0], *qab = &g.ab[q0], *qok = &g.valid[q0];
  const float *qlum = &c.lum[q0], *qr = &c.in.r[q0], *qg = &c.in.g[q0], *qb = &c.in.b[q0];
  const float* qvar = &c.in.var[q0];
  float *sr = &sums.r[x0], *sg = &sums.g[x0], *sb = &sums.b[x0], *sw = &sums.w[x0];
  float* sv = &sums.v[x0];
  const float fdx = static_cast<float>(dx), fdy = static_cast<float>(dy);
  const float sn = c.sigma_normal, sa = c.inv_two_sa2;
  const int n = x1 - x0;
  INET_IVDEP
  for (int i = 0; i < n; ++i) {
    float en = sn * std::fabs(1.f - (pnx[i] * qnx[i] + pny[i] * qny[i] + pnz[i] * qnz[i]));
    float ez = std::fabs(qiz[i] - (piz[i] + pgx[i] * fdx + pgy[i] * fdy)) * pzt[i];
    float da0 = par[i] - qar[i], da1 = pag[i] - qag[i], da2 = pab[i] - qab[i];
    float ea = (da0 * da0 + da1 * da1 + da2 * da2) * sa;
    float el = std::fabs(plum[i] - qlum[i]) * pcs[i];
    float w = hw * qok[i] * expNegative(en + ez + ea + el);
    sr[i] += w * qr[i];
    sg[i] += w * qg[i];
    sb[i] += w * qb[i];
    sw[i] += w;
    sv[i] += w * w * qvar[i];
  }
}

/// One à-trous level with tap spacing `step`: in -> out. Without `colour_stop` the weights come
/// from the guides alone (normal, depth plane, albedo): a linear filter of `in`.
void atrousLevel(const Guide& g, const Signal& in, Signal& out, int step,
                 const DenoiseOptions& opt, bool colour_stop = true) {
  std::vector<float> scale =
      colour_stop ? colourScale(g, in, opt.sigma_color) : std::vector<float>(g.size(), 0.f);
  // The first level stops edges on a 3x3 Gaussian of the luminance (over valid pixels), with
  // the colour scale of that blur's noise (its variance is 36/256 of a pixel's). On the raw
  // luminance, a dark noisy centre rejected its brighter neighbours more than a bright one its
  // darker ones (indoor noise is skewed: most samples low, a few high), so the filter leaned
  // toward the median: walls of a default sequence frame came out 1.7 % dark.
  std::vector<float> prefiltered;
  if (step == 1 && colour_stop) {
    prefiltered = gaussian3x3(g, in.lum);
    for (float& v : scale) v *= 16.f / 6.f;  // 1 / sqrt(36 / 256)
  }
  TapContext ctx{g,
                 in,
                 prefiltered.empty() ? in.lum.data() : prefiltered.data(),
                 scale,
                 opt.sigma_normal,
                 1.f / (2.f * opt.sigma_albedo * opt.sigma_albedo)};
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, kRowGrain), [&](const auto& rows) {
    RowSums sums(g.width);
    for (int y = rows.begin(); y < rows.end(); ++y) {
      sums.clear();
      for (int ky = -2; ky <= 2; ++ky) {
        int dy = ky * step;
        if (y + dy < 0 || y + dy >= g.height) continue;
        for (int kx = -2; kx <= 2; ++kx) {
          int dx = kx * step;
          if (dx >= g.width || -dx >= g.width) continue;
          addTap(ctx, y, dx, dy, kB3[ky + 2] * kB3[kx + 2], sums);
        }
      }
      for (int x = 0; x < g.width; ++x) {
        size_t i = static_cast<size_t>(y) * g.width + x;
        if (g.valid[i] == 0.f) continue;  // out was zero-initialised like in
        float inv_w = 1.f / sums.w[x];    // >= (3/8)^2: the centre tap always counts
        out.r[i] = sums.r[x] * inv_w;
        out.g[i] = sums.g[x] * inv_w;
        out.b[i] = sums.b[x] * inv_w;
        out.lum[i] = luminance(out.r[i], out.g[i], out.b[i]);
        out.var[i] = sums.v[x] * inv_w * inv_w;
      }
    }
  });
}

void checkPass(const ImageF& img, const ImageF& rgb, int channels, const char* name) {
  INET_CHECK_MSG(img.width == rgb.width && img.height == rgb.height && img.channels == channels,
                 std::string("denoise: ") + name + " pass has the wrong size or channel count");
}

}  // namespace

std::string DenoiseOptions::describe() const {
  std::ostringstream s;
  s << "iterations=" << iterations << " sigma_normal=" << sigma_normal
    << " sigma_depth=" << sigma_depth << " sigma_albedo=" << sigma_albedo
    << " sigma_color=" << sigma_color << " albedo_epsilon=" << albedo_epsilon;
  if (mean_levels > 0) s << " mean_levels=" << mean_levels;
  if (edge_iterations > 0 && edge_iterations < iterations)
    s << " edge_iterations=" << edge_iterations;
  return s.str();
}

void applyDenoiseParams(const std::string& text, DenoiseOptions& o, const std::string& where,
                        const std::string& field) {
  const std::pair<const char*, float*> floats[] = {{"sigma_normal", &o.sigma_normal},
                                                   {"sigma_depth", &o.sigma_depth},
                                                   {"sigma_albedo", &o.sigma_albedo},
                                                   {"sigma_color", &o.sigma_color},
                                                   {"albedo_epsilon", &o.albedo_epsilon}};
  const std::pair<const char*, int*> ints[] = {{"iterations", &o.iterations},
                                               {"mean_levels", &o.mean_levels},
                                               {"edge_iterations", &o.edge_iterations}};
  std::vector<std::string> names;
  for (const auto& item : ints) names.push_back(item.first);
  for (const auto& item : floats) names.push_back(item.first);
  // splitCommaList drops empty items; a stray comma is a typo worth naming
  if (!text.empty() && (text.front() == ',' || text.back() == ',' ||
                        text.find(",,") != std::string::npos))
    throw InputError(where, field, fmt::format("'{}' has an empty item", text));
  for (const std::string& item : splitCommaList(text)) {
    const size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v))
      throw InputError(where, field, fmt::format("'{}' is not key=number", item));
    bool known = false;
    for (const auto& [name, target] : ints) {
      if (key != name) continue;
      if (v != std::floor(v) || std::abs(v) > 1000)
        throw InputError(where, field, fmt::format("{} must be an integer, not {}", key, value));
      *target = static_cast<int>(v);
      known = true;
    }
    for (const auto& [name, target] : floats) {
      if (key != name) continue;
      *target = static_cast<float>(v);
      known = true;
    }
    if (!known)
      throw InputError(where, field,
                       fmt::format("unknown key '{}' ({})", key, listNames(names, names.size())));
  }
  try {
    validateDenoiseOptions(o, where);
  } catch (const InputError& e) {
    throw InputError(where, field, e.field() + ": " + e.problem());
  }
}

void validateDenoiseOptions(const DenoiseOptions& o, const std::string& where) {
  if (o.iterations < 1 || o.iterations > 10)
    throw InputError(where, "denoise.iterations",
                     "must be in 1..10, got " + std::to_string(o.iterations));
  const std::pair<const char*, float> sigmas[] = {{"denoise.sigma_normal", o.sigma_normal},
                                                  {"denoise.sigma_depth", o.sigma_depth},
                                                  {"denoise.sigma_albedo", o.sigma_albedo},
                                                  {"denoise.sigma_color", o.sigma_color}};
  for (const auto& [name, v] : sigmas)
    if (!(std::isfinite(v) && v > 0.f))
      throw InputError(where, name, "must be finite and > 0, got " + std::to_string(v));
  if (o.mean_levels < 0 || o.mean_levels > 10)
    throw InputError(where, "denoise.mean_levels",
                     "must be in 0..10, got " + std::to_string(o.mean_levels));
  if (o.edge_iterations < 0 || o.edge_iterations > 10)
    throw InputError(where, "denoise.edge_iterations",
                     "must be in 0..10, got " + std::to_string(o.edge_iterations));
  if (!(o.albedo_epsilon > 0.f && o.albedo_epsilon <= 1.f))
    throw InputError(where, "denoise.albedo_epsilon",
                     "must be in (0, 1], got " + std::to_string(o.albedo_epsilon));
}

/// Step 0 (before filtering): a pixel whose demodulated luminance is more than kFireflyRatio
/// times that of every one of its (at least 5) valid 8-neighbours is an isolated outlier, i.e. one
/// sample that found a small, bright light path (a lamp seen through its shade, a caustic). The
/// à-trous filter would spread it into a blotch, so it takes the colour of its neighbour of
/// median luminance instead (loneBrightPixels). Real features are never a single pixel brighter
/// than all around it by that much in irradiance (texture is divided out, directly seen lights
/// are not in the signal).
constexpr float kFireflyRatio = 4.f;

void rejectFireflies(const Guide& g, Signal& a) {
  std::vector<uint8_t> valid(g.size());
  for (size_t i = 0; i < valid.size(); ++i) valid[i] = g.valid[i] != 0.f;
  for (const PixelSwap& s : loneBrightPixels(g.width, g.height, a.lum.data(), valid.data(),
                                             valid.data(), kFireflyRatio, 5)) {
    a.r[s.pixel] = a.r[s.with];
    a.g[s.pixel] = a.g[s.with];
    a.b[s.pixel] = a.b[s.with];
    a.lum[s.pixel] = a.lum[s.with];
  }
}

/// `levels` à-trous levels of s without the colour stop: the local mean of s over the pixels
/// of the same surface, 1 + 4 (2^levels - 1) px wide.
Signal surfaceMean(const Guide& g, Signal s, int levels, const DenoiseOptions& opt) {
  Signal t(g.size());
  for (int it = 0; it < levels; ++it) {
    atrousLevel(g, s, t, 1 << it, opt, false);
    std::swap(s, t);
  }
  return s;
}

/// Keeps the input's light where the filter lost or gained some (DenoiseOptions::mean_levels):
/// `out` is scaled per pixel by lum(M(in)) / lum(M(out)), M the surface mean of mean_levels
/// levels, clamped to [1/2, 2] (the scale of a pixel whose means are not positive is 1).
void keepSurfaceMean(const Guide& g, const Signal& in_mean, Signal& out,
                     const DenoiseOptions& opt) {
  const Signal out_mean = surfaceMean(g, out, opt.mean_levels, opt);
  forEachRow(g.height, [&](int y) {
    for (size_t i = static_cast<size_t>(y) * g.width; i < static_cast<size_t>(y + 1) * g.width;
         ++i) {
      if (g.valid[i] == 0.f) continue;
      const float want = in_mean.lum[i], have = out_mean.lum[i];
      if (!(want > 0.f && have > 0.f)) continue;
      const float k = std::clamp(want / have, 0.5f, 2.f);
      out.r[i] *= k;
      out.g[i] *= k;
      out.b[i] *= k;
      out.lum[i] *= k;
      out.var[i] *= k * k;
    }
  });
}

namespace {

/// denoiseLevels(); `by_albedo` false filters rgb itself (the albedo still stops the filter):
/// light that the albedo does not scale, such as a varnish's reflection (denoiseRgb).
std::vector<ImageF> filterLevels(const ImageF& rgb, const ImageF& albedo, const ImageF& normal,
                                 const ImageF& depth, const ImageF* variance,
                                 const DenoiseOptions& opt, const std::vector<int>& levels,
                                 bool by_albedo) {
  INET_CHECK_MSG(rgb.channels == 3, "denoise: rgb must have 3 channels");
  checkPass(albedo, rgb, 3, "albedo");
  checkPass(normal, rgb, 3, "normal");
  checkPass(depth, rgb, 1, "depth");
  if (variance)
    INET_CHECK_MSG(variance->width == rgb.width && variance->height == rgb.height &&
                       (variance->channels == 1 || variance->channels == 3),
                   "denoise: variance must be rgb-sized with 1 or 3 channels");
  validateDenoiseOptions(opt, "");
  INET_CHECK_MSG(std::is_sorted(levels.begin(), levels.end()) && !levels.empty() &&
                     levels.front() >= 1 && levels.back() <= 10,
                 "denoiseLevels: levels must be ascending in 1..10");
  if (rgb.empty()) return std::vector<ImageF>(levels.size(), rgb);

  const Guide g = buildGuide(rgb, albedo, normal, depth, opt);
  const float eps = by_albedo ? opt.albedo_epsilon : 0.f;  // 0: modulation() is 1
  Signal a = demodulate(rgb, variance, g, eps);
  if (!variance) estimateVariance(g, a, opt);
  // the input's surface mean, when the output keeps it: taken before the fireflies go, whose
  // light is real (the rare bright samples of a skewed estimate) and is then spread over the
  // surface mean's width instead of lost
  const Signal in_mean = opt.mean_levels > 0 ? surfaceMean(g, a, opt.mean_levels, opt) : Signal(0);
  rejectFireflies(g, a);
  Signal b(g.size());
  auto remodulated = [&](const Signal& s) {
    ImageF out = rgb;
    forEachRow(g.height, [&](int y) {
      for (size_t i = static_cast<size_t>(y) * g.width; i < static_cast<size_t>(y + 1) * g.width;
           ++i) {
        if (g.valid[i] == 0.f) continue;
        const std::array<float, 3> m = modulation(g, eps, i);
        out.data[3 * i] = s.r[i] * m[0];
        out.data[3 * i + 1] = s.g[i] * m[1];
        out.data[3 * i + 2] = s.b[i] * m[2];
      }
    });
    return out;
  };
  std::vector<ImageF> outs;
  for (int it = 0; it < levels.back(); ++it) {
    atrousLevel(g, a, b, 1 << it, opt);
    std::swap(a, b);
    for (int l : levels) {
      if (l != it + 1) continue;
      if (opt.mean_levels > 0) {
        Signal kept = a;
        keepSurfaceMean(g, in_mean, kept, opt);
        outs.push_back(remodulated(kept));
      } else {
        outs.push_back(remodulated(a));
      }
    }
  }
  return outs;
}

}  // namespace

std::vector<PixelSwap> loneBrightPixels(int width, int height, const float* lum,
                                        const uint8_t* centre, const uint8_t* neighbour,
                                        float ratio, int min_neighbours) {
  std::vector<std::vector<PixelSwap>> rows(static_cast<size_t>(std::max(0, height)));
  forEachRow(height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      if (centre && centre[i] == 0) continue;
      std::array<std::pair<float, size_t>, 8> nb;
      int n = 0;
      float brightest = 0.f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
          const size_t j = static_cast<size_t>(yy) * width + xx;
          if (neighbour && neighbour[j] == 0) continue;
          nb[n++] = {lum[j], j};
          brightest = std::max(brightest, lum[j]);
        }
      if (n < min_neighbours || !(lum[i] > ratio * brightest + 1e-6f)) continue;
      // (luminance, index) pairs: ties go by index, the same neighbour on every run
      std::nth_element(nb.begin(), nb.begin() + n / 2, nb.begin() + n);
      rows[static_cast<size_t>(y)].push_back({i, nb[n / 2].second});
    }
  });
  std::vector<PixelSwap> out;
  for (const std::vector<PixelSwap>& row : rows) out.insert(out.end(), row.begin(), row.end());
  return out;
}

std::vector<ImageF> denoiseLevels(const ImageF& rgb, const ImageF& albedo, const ImageF& normal,
                                  const ImageF& depth, const ImageF* variance,
                                  const DenoiseOptions& opt, const std::vector<int>& levels) {
  return filterLevels(rgb, albedo, normal, depth, variance, opt, levels, true);
}

ImageF denoise(const ImageF& rgb, const ImageF& albedo, const ImageF& normal, const ImageF& depth,
               const ImageF* variance, const DenoiseOptions& opt) {
  validateDenoiseOptions(opt, "");
  return std::move(denoiseLevels(rgb, albedo, normal, depth, variance, opt, {opt.iterations})[0]);
}

ImageF varianceFromHalfBuffers(const ImageF& half_a, const ImageF& half_b) {
  INET_CHECK_MSG(half_a.width == half_b.width && half_a.height == half_b.height &&
                     half_a.channels == half_b.channels,
                 "varianceFromHalfBuffers: buffers differ in size");
  ImageF out(half_a.width, half_a.height, half_a.channels);
  for (size_t i = 0; i < out.data.size(); ++i) {
    float d = 0.5f * (half_a.data[i] - half_b.data[i]);
    out.data[i] = d * d;
  }
  return out;
}

std::vector<ImageF> neighbourhoodVariance(const std::vector<const ImageF*>& values,
                                          const ImageF& albedo, const ImageF& normal,
                                          const ImageF& depth, const DenoiseOptions& opt) {
  INET_CHECK_MSG(!values.empty(), "neighbourhoodVariance: no image");
  const ImageF& first = *values.front();
  for (const ImageF* v : values)
    INET_CHECK_MSG(v->channels == 3 && v->width == first.width && v->height == first.height,
                   "neighbourhoodVariance: values must be 3-channel images of one size");
  checkPass(albedo, first, 3, "albedo");
  checkPass(normal, first, 3, "normal");
  checkPass(depth, first, 1, "depth");
  std::vector<ImageF> out(values.size(), ImageF(first.width, first.height, 3));
  if (first.empty()) return out;
  const Guide g = buildGuide(first, albedo, normal, depth, opt);
  const float eps = opt.albedo_epsilon;
  const float inv_two_sa2 = 1.f / (2.f * opt.sigma_albedo * opt.sigma_albedo);
  constexpr int kRadius = 3, kTaps = (2 * kRadius + 1) * (2 * kRadius + 1);
  forEachRow(g.height, [&](int y) {
    std::array<float, kTaps> weight;
    std::array<size_t, kTaps> tap;
    for (int x = 0; x < g.width; ++x) {
      const size_t i = static_cast<size_t>(y) * g.width + x;
      if (g.valid[i] == 0.f) continue;
      // the filter's geometric stops, once for every image
      int n = 0;
      double sw = 0, sw2 = 0;
      for (int dy = -kRadius; dy <= kRadius; ++dy) {
        if (y + dy < 0 || y + dy >= g.height) continue;
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
          if (x + dx < 0 || x + dx >= g.width) continue;
          const size_t q = static_cast<size_t>(y + dy) * g.width + (x + dx);
          if (g.valid[q] == 0.f) continue;
          const float w = expNegative(geometricStop(g, i, q, static_cast<float>(dx),
                                                    static_cast<float>(dy), opt.sigma_normal,
                                                    inv_two_sa2));
          weight[n] = w;
          tap[n++] = q;
          sw += w;
          sw2 += static_cast<double>(w) * w;
        }
      }
      // weighted variance, unbiased for weights of effective count sw^2 / sw2
      const double correction = sw * sw - sw2;
      const bool alone = correction <= 1e-6 * sw * sw;
      for (size_t k = 0; k < values.size(); ++k) {
        const float* v = values[k]->data.data();
        for (int c = 0; c < 3; ++c) {
          float& o = out[k].data[3 * i + c];
          if (alone) {
            o = v[3 * i + c] * v[3 * i + c];
            continue;
          }
          const float* a = (c == 0 ? g.ar : c == 1 ? g.ag : g.ab).data();
          double s1 = 0, s2 = 0;
          for (int t = 0; t < n; ++t) {
            const double e = v[3 * tap[t] + c] / std::max(a[tap[t]], eps);
            s1 += weight[t] * e;
            s2 += weight[t] * e * e;
          }
          const double var_e = std::max(0.0, s2 - s1 * s1 / sw) / correction * sw;
          const double scale = std::max(a[i], eps);
          o = static_cast<float>(var_e * scale * scale);
        }
      }
    }
  });
  return out;
}

void denoiseRgb(Frame& frame, RgbLayers& layers, const DenoiseOptions& options) {
  // filter only the light reflected by the surfaces; lights in view stay sharp
  ImageF& rgb = frame.rgb;
  for (size_t i = 0; i < rgb.data.size(); ++i) rgb.data[i] -= layers.emission.data[i];
  const ImageU8& label = frame.label;
  const bool labelled = label.width == rgb.width && label.height == rgb.height;
  // class edges: another NYU40 class in the pixel's 3x3 label neighbourhood
  std::vector<uint8_t> edge(labelled ? rgb.data.size() / 3 : 0, 0);
  if (labelled)
    forEachRow(rgb.height, [&](int y) {
      for (int x = 0; x < rgb.width; ++x) {
        const uint8_t c = label.at(x, y);
        bool e = false;
        for (int dy = -1; dy <= 1 && !e; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = std::clamp(x + dx, 0, rgb.width - 1);
            const int yy = std::clamp(y + dy, 0, rgb.height - 1);
            if (label.at(xx, yy) != c) e = true;
          }
        edge[static_cast<size_t>(y) * rgb.width + x] = e;
      }
    });
  const bool edges = options.edge_iterations > 0 && options.edge_iterations < options.iterations &&
                     labelled;
  // The colour is a mean over the pixel's footprint; dividing it by the albedo pass (the pixel
  // centre's texel) and multiplying the filtered light by it again printed the centre's texture
  // on the result: on a wood floor a pixel-scale pattern the reference does not have. The
  // footprint's own albedo divides it exactly. Not at class edges: there the footprint's albedo
  // is the share of samples on each surface, which is noise the result would keep (the edge
  // ring's error rose from 0.12-0.14 to 0.14-0.16 in the default sequence), while the centre's
  // is exact; the filter averages the mix as before.
  const ImageF* albedo = &frame.albedo;
  ImageF mixed;
  if (layers.albedo.width == rgb.width && layers.albedo.height == rgb.height) {
    albedo = &layers.albedo;
    if (labelled) {
      mixed = layers.albedo;
      for (size_t i = 0; i < edge.size(); ++i)
        if (edge[i])
          for (int k = 0; k < 3; ++k) mixed.data[3 * i + k] = frame.albedo.data[3 * i + k];
      albedo = &mixed;
    }
  }
  auto filter = [&](const ImageF& light, const ImageF* variance, bool demodulate) {
    if (!edges)
      return std::move(filterLevels(light, *albedo, frame.normal, frame.depth_z, variance, options,
                                    {options.iterations}, demodulate)[0]);
    std::vector<ImageF> out =
        filterLevels(light, *albedo, frame.normal, frame.depth_z, variance, options,
                     {options.edge_iterations, options.iterations}, demodulate);
    for (size_t i = 0; i < edge.size(); ++i)
      if (edge[i])
        for (int k = 0; k < 3; ++k) out[1].data[3 * i + k] = out[0].data[3 * i + k];
    return std::move(out[1]);
  };
  auto sized = [&](const ImageF& image) {
    return image.width == rgb.width && image.height == rgb.height && image.channels == 3;
  };
  if (sized(layers.diffuse) && sized(layers.diffuse_variance) && sized(layers.rest_variance)) {
    // The albedo scales the diffuse light only. Divided by it too, a varnish's reflection came
    // back multiplied by the texture it does not have (a wood floor's grain printed on its
    // sheen), so the rest is filtered as it is, the albedo only stopping the filter.
    ImageF rest = rgb;
    for (size_t i = 0; i < rest.data.size(); ++i) rest.data[i] -= layers.diffuse.data[i];
    layers.diffuse = filter(layers.diffuse, &layers.diffuse_variance, true);
    rgb = filter(rest, &layers.rest_variance, false);
    for (size_t i = 0; i < rgb.data.size(); ++i) rgb.data[i] += layers.diffuse.data[i];
  } else {
    rgb = filter(rgb, &layers.variance, true);
  }
  for (size_t i = 0; i < rgb.data.size(); ++i) rgb.data[i] += layers.emission.data[i];
}

void filterWindowView(ImageF& rgb, ImageF& emission, const WindowViewLayers& view,
                      const DenoiseOptions& options, bool few_samples) {
  INET_CHECK(rgb.channels == 3 && emission.width == rgb.width && emission.height == rgb.height);
  checkPass(view.light, rgb, 3, "window view light");
  checkPass(view.coverage, rgb, 1, "window view coverage");
  if (std::none_of(view.coverage.data.begin(), view.coverage.data.end(),
                   [](float c) { return c > 0.f; }))
    return;  // no surface seen through a pane
  ImageF variance = few_samples ? std::move(neighbourhoodVariance({&view.light}, view.albedo,
                                                                  view.normal, view.depth,
                                                                  options)[0])
                                : view.variance;
  const ImageF filtered =
      denoise(view.light, view.albedo, view.normal, view.depth, &variance, options);
  for (size_t i = 0; i < view.coverage.data.size(); ++i) {
    const float c = view.coverage.data[i];
    if (!(c > 0.f)) continue;
    for (size_t k = 3 * i; k < 3 * i + 3; ++k) {
      const float delta = c * (filtered.data[k] - view.light.data[k]);
      rgb.data[k] += delta;
      emission.data[k] += delta;
    }
  }
}

}  // namespace inet
