#include "procedural/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/rng.h"
#include "procedural/periodic_noise.h"

namespace inet {
namespace {

constexpr uint32_t kTextureTag = 0x50544558;  // ASCII "PTEX"
constexpr float kPi = std::numbers::pi_v<float>;

/// What a kind's pattern produces before colour fitting and encoding.
struct Fields {
  Fields(int n, bool has_height)
      : mod(n, n, 3, 1.0f), height(has_height ? ImageF(n, n, 1) : ImageF()), rough(n, n, 1) {}
  ImageF mod;     ///< linear albedo modulation around 1, 3 channels
  ImageF height;  ///< uv units (fraction of the texture width); empty = no normal map
  ImageF rough;   ///< perceptual roughness
  void setGrey(int x, int y, float lum) {
    float* p = mod.pixel(x, y);
    p[0] = p[1] = p[2] = lum;
  }
};

/// One independent random stream per (kind, field).
CounterRng fieldRng(uint64_t seed, TextureKind kind, uint32_t field) {
  return CounterRng(seed, RngStream::Layout, kTextureTag, static_cast<uint32_t>(kind) * 256 + field,
                    0);
}

std::vector<float> uniforms(CounterRng& rng, int count) {
  std::vector<float> v(count);
  for (float& x : v) x = rng.uniform();
  return v;
}

/// Calls f(x, y, s, t) for every texel with (s, t) its centre in texture units (t down the rows).
template <typename F>
void forTexels(int n, F&& f) {
  for (int y = 0; y < n; ++y) {
    float t = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
    for (int x = 0; x < n; ++x) f(x, y, (static_cast<float>(x) + 0.5f) / static_cast<float>(n), t);
  }
}

float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}
float fract(float x) {
  return x - std::floor(x);
}
/// Distance in uv from `a` to the nearest line a = k / cells (k integer), wrapping.
float gridDistance(float a, int cells) {
  float c = a * static_cast<float>(cells);
  return std::abs(c - std::round(c)) / static_cast<float>(cells);
}
/// Box-filtered coverage of a texel by a line of half width `half_uv` at distance `d_uv`.
float lineCoverage(float d_uv, float half_uv, int n) {
  return std::clamp((half_uv - d_uv) * static_cast<float>(n) + 0.5f, 0.0f, 1.0f);
}

/// Wood: 4 planks along u, 2 boards each; rings run along u, distorted by noise. Plank seams sit
/// at t = (k + 1/2) / 4, so the texture's border runs through the middle of a plank.
Fields wood(int n, uint64_t seed) {
  constexpr int kPlanks = 4;
  CounterRng r0 = fieldRng(seed, TextureKind::Wood, 0), r1 = fieldRng(seed, TextureKind::Wood, 1),
             r2 = fieldRng(seed, TextureKind::Wood, 2);
  PeriodicFbm warp(2, 8, 4, 0.5f, r0), fibre(4, 96, 3, 0.6f, r1);
  std::vector<float> rnd = uniforms(r2, kPlanks * 8);
  Fields f(n, true);
  float seam_half = 0.6f / 256.0f, shift = 0.5f / kPlanks;
  forTexels(n, [&](int x, int y, float s, float t) {
    float tp = fract(t + shift) * kPlanks;  // plank coordinate; its fraction runs across a plank
    int p = std::min(static_cast<int>(tp), kPlanks - 1);
    const float* pr = &rnd[p * 8];
    float j0 = pr[0], j1 = j0 + 0.35f + 0.3f * pr[1];  // board joints along u
    int board = fract(s - j0) < j1 - j0 ? 0 : 1;
    const float* br = pr + 2 + 3 * board;  // tone, ring offset, ring density
    float tone = 0.88f + 0.24f * br[0];
    float rings = 7.0f + 4.0f * br[2];  // per plank width
    float r = fract(tp) * rings + 10.0f * br[1] + 1.6f * warp(s + br[1], t);
    // Late wood darkens gradually across a ring and ends at the next ring's early wood; the drop
    // is spread over ~1 texel at size 256 so the lines do not alias into steps.
    float fr = fract(r), late = smoothstep(0.45f, 0.9f, fr) * (1.0f - smoothstep(0.9f, 1.0f, fr));
    float fib = fibre(s, t);
    float lum = tone * (1.0f - 0.38f * late) * (1.0f + 0.12f * fib);
    float d_joint = std::min({gridDistance(s - j0, 1), gridDistance(s - j1, 1)});
    float seam = std::max(lineCoverage(gridDistance(t + shift, kPlanks), seam_half, n),
                          lineCoverage(d_joint, seam_half, n));
    float* m = f.mod.pixel(x, y);
    m[0] = lum;  // late wood is darker and more saturated (blue drops most)
    m[1] = lum * (1.0f - 0.06f * late);
    m[2] = lum * (1.0f - 0.14f * late);
    for (int c = 0; c < 3; ++c) m[c] += seam * (0.35f - m[c]);
    f.height.at(x, y) = -0.0005f * late + 0.0002f * fib - 0.002f * seam;
    f.rough.at(x, y) = 0.48f + 0.1f * late - 0.05f * fib + 0.3f * seam;
  });
  return f;
}

/// Fabric: plain weave; warp threads run along v, weft along u, alternating over/under. The weave
/// is shifted by half a thread so that the border runs along thread centres.
Fields fabric(int n, uint64_t seed) {
  constexpr int kThreads = 64;
  CounterRng r0 = fieldRng(seed, TextureKind::Fabric, 0),
             r1 = fieldRng(seed, TextureKind::Fabric, 1),
             r2 = fieldRng(seed, TextureKind::Fabric, 2);
  PeriodicFbm fuzz(32, 32, 3, 0.5f, r0), mottle(4, 4, 3, 0.5f, r1);
  std::vector<float> tone = uniforms(r2, 2 * kThreads);  // warp i, then weft j
  Fields f(n, true);
  forTexels(n, [&](int x, int y, float s, float t) {
    float cx = s * kThreads + 0.5f, cy = t * kThreads + 0.5f;
    int i = static_cast<int>(cx) % kThreads, j = static_cast<int>(cy) % kThreads;
    float a = fract(cx), b = fract(cy);
    bool warp_over = ((i + j) & 1) == 0;
    float across = warp_over ? a : b, along = warp_over ? b : a;
    float h = std::sqrt(std::sin(kPi * across)) * (0.75f + 0.25f * std::sin(kPi * along));
    float th = warp_over ? tone[i] : tone[kThreads + j];
    float fz = fuzz(s, t);
    f.setGrey(
        x, y,
        (0.92f + 0.16f * th) * (0.6f + 0.45f * h) * (1.0f + 0.06f * fz + 0.05f * mottle(s, t)));
    f.height.at(x, y) = 0.003f * h + 0.0002f * fz;
    f.rough.at(x, y) = 0.83f + 0.08f * (1.0f - h);
  });
  return f;
}

/// Tiles: 4 x 4 square tiles, darker recessed grout, per-tile tone.
Fields tiles(int n, uint64_t seed) {
  constexpr int kTiles = 4;
  CounterRng r0 = fieldRng(seed, TextureKind::Tiles, 0), r1 = fieldRng(seed, TextureKind::Tiles, 1),
             r2 = fieldRng(seed, TextureKind::Tiles, 2);
  PeriodicFbm glaze(8, 8, 3, 0.5f, r0), grit(32, 32, 2, 0.5f, r1);
  std::vector<float> tone = uniforms(r2, kTiles * kTiles);
  Fields f(n, true);
  float grout_half = 1.5f / 256.0f, bevel = 2.5f / 256.0f;
  forTexels(n, [&](int x, int y, float s, float t) {
    float d = std::min(gridDistance(s, kTiles), gridDistance(t, kTiles));
    float cov = lineCoverage(d, grout_half, n);
    int tile = static_cast<int>(t * kTiles) * kTiles + static_cast<int>(s * kTiles);
    float g = glaze(s, t);
    float tile_lum = (0.92f + 0.16f * tone[tile]) * (1.0f + 0.03f * g);
    float grout_lum = 0.45f * (1.0f + 0.1f * grit(s, t));
    f.setGrey(x, y, tile_lum + cov * (grout_lum - tile_lum));
    float e = std::clamp((d - grout_half) / bevel, 0.0f, 1.0f);
    f.height.at(x, y) = 0.003f * std::sin(0.5f * kPi * e);
    f.rough.at(x, y) = 0.12f + 0.04f * g + cov * (0.9f - 0.12f);
  });
  return f;
}

/// Phase field of one vein family: phi = pi (k_s s + k_t t) + amp * turbulence(s, t). Veins are
/// the lines sin(phi) = 0; integer k_s, k_t keep them periodic. Returns per texel the distance to
/// the nearest vein in texels, |sin(phi)| / |grad phi|, so veins keep their width however fast the
/// phase turns (no dotted, aliased lines).
ImageF veinDistance(int n, const PeriodicFbm& turb, float ks, float kt, float amp) {
  ImageF tb(n, n, 1), dist(n, n, 1);
  forTexels(n, [&](int x, int y, float s, float t) { tb.at(x, y) = amp * turb.turbulence(s, t); });
  float gs = kPi * ks / static_cast<float>(n), gt = kPi * kt / static_cast<float>(n);
  forTexels(n, [&](int x, int y, float s, float t) {
    float dx = 0.5f * (tb.at((x + 1) % n, y) - tb.at((x + n - 1) % n, y)) + gs;
    float dy = 0.5f * (tb.at(x, (y + 1) % n) - tb.at(x, (y + n - 1) % n)) + gt;
    float phi = kPi * (ks * s + kt * t) + tb.at(x, y);
    dist.at(x, y) = std::abs(std::sin(phi)) / std::max(std::sqrt(dx * dx + dy * dy), 1e-4f);
  });
  return dist;
}

/// Marble: cloudy light base with two families of turbulence-distorted veins (after Perlin,
/// "An image synthesizer", SIGGRAPH 1985).
Fields marble(int n, uint64_t seed) {
  CounterRng r0 = fieldRng(seed, TextureKind::Marble, 0),
             r1 = fieldRng(seed, TextureKind::Marble, 1),
             r2 = fieldRng(seed, TextureKind::Marble, 2),
             r3 = fieldRng(seed, TextureKind::Marble, 3);
  PeriodicFbm cloud(3, 3, 4, 0.5f, r0), turb(2, 2, 4, 0.5f, r1), turb2(3, 3, 4, 0.5f, r2),
      strength(2, 2, 2, 0.5f, r3);
  ImageF d1 = veinDistance(n, turb, 2.0f, 1.0f, 3.0f),
         d2 = veinDistance(n, turb2, -1.0f, 3.0f, 3.5f);
  float px = static_cast<float>(n) / 256.0f;  // vein widths are given in texels at size 256
  Fields f(n, false);
  forTexels(n, [&](int x, int y, float s, float t) {
    float w = std::clamp(0.5f + strength(s, t), 0.0f, 1.0f);  // vein strength and width
    float vein1 = w * (1.0f - smoothstep(0.0f, (0.8f + 2.5f * w) * px, d1.at(x, y)));
    float vein2 = 1.0f - smoothstep(0.0f, 0.9f * px, d2.at(x, y));
    float halo = w * (1.0f - smoothstep(0.0f, 10.0f * px, d1.at(x, y)));  // soft cloud by veins
    f.setGrey(x, y,
              (1.0f + 0.05f * cloud(s, t)) * (1.0f - 0.08f * halo) * (1.0f - 0.45f * vein1) *
                  (1.0f - 0.12f * vein2));
    f.rough.at(x, y) = 0.17f + 0.1f * vein1 + 0.05f * vein2;
  });
  return f;
}

/// Carpet: soft fibre noise near texel scale plus tuft and mottling variation.
Fields carpet(int n, uint64_t seed) {
  CounterRng r0 = fieldRng(seed, TextureKind::Carpet, 0),
             r1 = fieldRng(seed, TextureKind::Carpet, 1),
             r2 = fieldRng(seed, TextureKind::Carpet, 2);
  PeriodicNoise fibre1(128, 128, r0), fibre2(256, 256, r0);
  PeriodicFbm tuft(16, 16, 2, 0.5f, r1), mottle(4, 4, 3, 0.5f, r2);
  Fields f(n, true);
  forTexels(n, [&](int x, int y, float s, float t) {
    float fb = 0.6f * fibre1(s, t) + 0.4f * fibre2(s, t);
    float tf = tuft(s, t);
    f.setGrey(x, y, 1.0f + 0.25f * fb + 0.07f * tf + 0.05f * mottle(s, t));
    f.height.at(x, y) = 0.0015f * fb + 0.002f * tf;
    f.rough.at(x, y) = 0.95f + 0.03f * fb;
  });
  return f;
}

/// Plaster: painted wall, subtle low-contrast noise and faint roller bumps.
Fields plaster(int n, uint64_t seed) {
  CounterRng r0 = fieldRng(seed, TextureKind::Plaster, 0),
             r1 = fieldRng(seed, TextureKind::Plaster, 1),
             r2 = fieldRng(seed, TextureKind::Plaster, 2);
  PeriodicFbm low(4, 4, 4, 0.5f, r0), bumps(24, 24, 3, 0.5f, r1);
  PeriodicNoise fine(96, 96, r2);
  Fields f(n, true);
  forTexels(n, [&](int x, int y, float s, float t) {
    float b = bumps(s, t), fn = fine(s, t);
    f.setGrey(x, y, 1.0f + 0.1f * low(s, t) + 0.03f * b + 0.01f * fn);
    f.height.at(x, y) = 0.0008f * b + 0.0001f * fn;
    f.rough.at(x, y) = 0.7f + 0.04f * b;
  });
  return f;
}

/// Leather: pebble grain, rounded cells separated by creases (cellular noise on a noise-warped
/// domain so the cells are irregular), with mottled tone.
Fields leather(int n, uint64_t seed) {
  constexpr int kCells = 36;  // grains across the texture
  CounterRng r0 = fieldRng(seed, TextureKind::Leather, 0),
             r1 = fieldRng(seed, TextureKind::Leather, 1),
             r2 = fieldRng(seed, TextureKind::Leather, 2),
             r3 = fieldRng(seed, TextureKind::Leather, 3);
  PeriodicCells cells(kCells, 0.7f, r0);
  PeriodicFbm mottle(4, 4, 3, 0.5f, r1), warp(8, 8, 2, 0.5f, r2);
  std::vector<float> tone = uniforms(r3, cells.points());
  Fields f(n, true);
  forTexels(n, [&](int x, int y, float s, float t) {
    float wu = 0.25f / kCells * warp(s, t), wv = 0.25f / kCells * warp(t + 0.5f, s);
    PeriodicCells::Hit h = cells(s + wu, t + wv);
    float f1 = h.f1, f2 = h.f2;  // in units of the mean grain spacing
    float crease = 1.0f - smoothstep(0.0f, 0.3f, f2 - f1);
    float dome = 1.0f - std::min(f1 * f1, 1.0f);
    float raised = (1.0f - crease) * (0.6f + 0.4f * dome);
    f.setGrey(
        x, y,
        (0.86f + 0.14f * raised) * (0.97f + 0.06f * tone[h.point]) * (1.0f + 0.1f * mottle(s, t)));
    f.height.at(x, y) = 0.0012f * raised;
    f.rough.at(x, y) = 0.42f + 0.16f * crease + 0.06f * (1.0f - dome);
  });
  return f;
}

/// Metal: brushed streaks, long along u and fine across v.
Fields metal(int n, uint64_t seed) {
  CounterRng r0 = fieldRng(seed, TextureKind::Metal, 0), r1 = fieldRng(seed, TextureKind::Metal, 1);
  PeriodicFbm streak(2, 128, 3, 0.7f, r0), sheen(3, 3, 3, 0.5f, r1);
  Fields f(n, true);
  forTexels(n, [&](int x, int y, float s, float t) {
    float st = streak(s, t);
    f.setGrey(x, y, 1.0f + 0.08f * st + 0.03f * sheen(s, t));
    f.height.at(x, y) = 0.00015f * st;
    f.rough.at(x, y) = 0.3f + 0.06f * st;
  });
  return f;
}

/// Exact sRGB EOTF of each 8-bit code.
const std::array<double, 256>& srgbDecodeTable() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int c = 0; c < 256; ++c) {
      double v = c / 255.0;
      t[c] = srgbEotf(v);
    }
    return t;
  }();
  return table;
}

/// Scales each channel of `mod` so that the mean decoded linear albedo equals `target`.
/// The mean grows monotonically with the scale; s <- s * target / mean converges in a few steps
/// (exactly linear until clamping at 1 sets in).
ImageU8 fitAlbedo(const ImageF& mod, const Eigen::Vector3f& target) {
  const std::array<double, 256>& decode = srgbDecodeTable();
  ImageU8 out(mod.width, mod.height, 3);
  size_t count = mod.pixelCount();
  for (int c = 0; c < 3; ++c) {
    double a = target[c];
    if (a <= 0.0) continue;  // all codes 0
    double mod_mean = 0.0;
    for (size_t i = 0; i < count; ++i) mod_mean += mod.data[i * 3 + c];
    mod_mean /= static_cast<double>(count);
    double s = a / std::max(mod_mean, 1e-6);
    for (int it = 0; it < 16; ++it) {
      double sum = 0.0;
      for (size_t i = 0; i < count; ++i) {
        uint8_t code = linearToSrgb8(static_cast<float>(s * mod.data[i * 3 + c]));
        out.data[i * 3 + c] = code;
        sum += decode[code];
      }
      double mean = sum / static_cast<double>(count);
      if (std::abs(mean - a) <= 0.001 * a || it == 15) break;
      s *= mean > 0.0 ? a / mean : 4.0;
    }
  }
  return out;
}

ImageU8 encodeRoughness(const ImageF& rough) {
  ImageU8 out(rough.width, rough.height, 1);
  for (size_t i = 0; i < rough.data.size(); ++i)
    out.data[i] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(rough.data[i], 0.0f, 1.0f)));
  return out;
}

/// Tangent-space normals of a periodic height field (uv units), OpenGL +Y (v up = rows up).
ImageU8 encodeNormals(const ImageF& h) {
  int n = h.width;
  ImageU8 out(n, n, 3);
  float half_n = 0.5f * static_cast<float>(n);  // central difference over 2 texels = 2 / n uv
  for (int y = 0; y < n; ++y) {
    int ym = (y + n - 1) % n, yp = (y + 1) % n;
    for (int x = 0; x < n; ++x) {
      int xm = (x + n - 1) % n, xp = (x + 1) % n;
      float dh_du = (h.at(xp, y) - h.at(xm, y)) * half_n;
      float dh_dv = -(h.at(x, yp) - h.at(x, ym)) * half_n;  // rows run down, v runs up
      Eigen::Vector3f nrm = Eigen::Vector3f(-dh_du, -dh_dv, 1.0f).normalized();
      for (int c = 0; c < 3; ++c)
        out.at(x, y, c) = static_cast<uint8_t>(std::lround(127.5f * (nrm[c] + 1.0f)));
    }
  }
  return out;
}

Fields makeFields(TextureKind kind, int n, uint64_t seed) {
  switch (kind) {
    case TextureKind::Wood:
      return wood(n, seed);
    case TextureKind::Fabric:
      return fabric(n, seed);
    case TextureKind::Tiles:
      return tiles(n, seed);
    case TextureKind::Marble:
      return marble(n, seed);
    case TextureKind::Carpet:
      return carpet(n, seed);
    case TextureKind::Plaster:
      return plaster(n, seed);
    case TextureKind::Leather:
      return leather(n, seed);
    case TextureKind::Metal:
      return metal(n, seed);
    case TextureKind::None:
      break;
  }
  INET_CHECK_MSG(false, "makeFields called for TextureKind::None");
}

}  // namespace

float typicalRoughness(TextureKind kind) {
  switch (kind) {
    case TextureKind::Wood:
      return 0.5f;
    case TextureKind::Fabric:
      return 0.85f;
    case TextureKind::Tiles:
      return 0.2f;
    case TextureKind::Marble:
      return 0.2f;
    case TextureKind::Carpet:
      return 0.95f;
    case TextureKind::Plaster:
      return 0.7f;
    case TextureKind::Leather:
      return 0.5f;
    case TextureKind::Metal:
      return 0.3f;
    case TextureKind::None:
      break;
  }
  return 1.0f;
}

TextureSet makeTexture(TextureKind kind, const Eigen::Vector3f& mean_albedo, uint64_t seed,
                       int size) {
  if (size < 64 || size > 1024 || (size & (size - 1)) != 0)
    throw InputError("", "texture size",
                     std::to_string(size) + " is not a power of two in [64, 1024]");
  for (int c = 0; c < 3; ++c) {
    if (!(mean_albedo[c] >= 0.0f && mean_albedo[c] <= 1.0f))
      throw InputError("", std::string(textureKindName(kind)) + " texture mean_albedo",
                       "component " + std::to_string(c) + " = " + std::to_string(mean_albedo[c]) +
                           " is outside [0, 1]");
  }
  TextureSet set;
  if (kind == TextureKind::None) {
    set.albedo = ImageU8(size, size, 3);
    for (size_t i = 0; i < set.albedo.data.size(); ++i)
      set.albedo.data[i] = linearToSrgb8(mean_albedo[static_cast<int>(i % 3)]);
    return set;
  }
  Fields f = makeFields(kind, size, seed);
  set.albedo = fitAlbedo(f.mod, mean_albedo);
  set.roughness = encodeRoughness(f.rough);
  if (!f.height.empty()) set.normal = encodeNormals(f.height);
  return set;
}

std::array<std::string, 3> writeTexture(const TextureSet& t, const std::filesystem::path& dir,
                                        const std::string& stem) {
  const ImageU8* images[3] = {&t.albedo, &t.roughness, &t.normal};
  const char* suffix[3] = {"_albedo.png", "_roughness.png", "_normal.png"};
  std::array<std::string, 3> paths;
  for (int i = 0; i < 3; ++i) {
    if (images[i]->empty()) continue;
    std::filesystem::path p = dir / (stem + suffix[i]);
    writePng(p, *images[i]);  // atomic (tmp + rename), creates `dir`
    paths[i] = p.string();
  }
  return paths;
}

}  // namespace inet
