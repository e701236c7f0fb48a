// Unidirectional path tracer over the BSDF families of bsdf.h, with smooth shading normals and
// textures (EmbreeScene::surface); one-sided emissive triangles (area lights), point, spot, sun
// and sky lights (lights.h); next-event estimation combined with BSDF sampling by multiple
// importance sampling (power heuristic, Veach 1997), Russian roulette from the third bounce.
// One ray per call (rtcIntersect1 / rtcOccluded1).
//
// Samples: a padded, Owen-scrambled Sobol sampler per (seed, frame, pixel, sample) (sampler.h),
// so the image does not depend on the number of threads or the order of tiles.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/color.h"
#include "render/bsdf.h"
#include "render/denoise.h"
#include "render/embree_scene.h"
#include "render/integrator.h"
#include "render/light_cache.h"
#include "render/radiance_cache.h"
#include "render/sampler.h"

namespace inet {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr int kTile = 16;

struct Ray {
  Vec3f o, d;        // d unit length
  float time = 0.f;  // in the exposure window, [0, 1] (moving objects)
};

Vec3f cosineHemisphere(const Vec3f& n, float u1, float u2) {
  float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  const Frame3 f = Frame3::fromNormal(n);
  float z = std::sqrt(std::max(0.0f, 1.0f - u1));
  return (f.s * (r * std::cos(phi)) + f.t * (r * std::sin(phi)) + n * z).normalized();
}

float powerHeuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

/// Pixel (x, y)'s samples: RenderOptions::spp, times its spp_multiplier where one is given.
int pixelSpp(const RenderOptions& o, int x, int y) {
  return o.spp_multiplier ? o.spp * std::max<int>(1, o.spp_multiplier->at(x, y)) : o.spp;
}

/// What IntegratorOutputs splits off at a path's first surface.
struct FirstSurface {
  Vec3f diffuse = Vec3f::Zero();  ///< light it reflects through its diffuse lobes
  Vec3f albedo = Vec3f::Zero();   ///< its albedo
  float view_alpha = kNoViewDependentLobe;  ///< viewDependentAlpha of its BSDF (none: nothing hit)
};

/// Window panes on the camera's line of sight (before any bounce), split: the path follows
/// one delta lobe of each of the first `forced` panes it meets there, reflecting at the one
/// numbered `reflect_at` (0 = the first; -1: none, straight through all of them) and going
/// straight through the others, with each lobe's full weight (r x tint, or the transmission),
/// no pick. renderBlock sums two paths: straight through, and reflected. Picking a lobe by its
/// share left a pixel at few samples either the bright outdoors or the dim reflection of the
/// room: at 1 spp about a tenth of a window's pixels came out black, and that light is kept out
/// of every filter. A catalog window's glass is a thin box: two panes on every line of sight.
/// Its two reflections (off the front face, and off the back face seen through the front) leave
/// in the same direction a few millimetres apart, so one path stands for both (reflect_at
/// kEitherFace): it reflects at the first face with probability q = 1 / (1 + T) (their shares
/// when the faces are alike), weight r / q, and otherwise goes through it, weight T / (1 - q),
/// and reflects at the second, weight r. Unbiased for any q, and one path fewer per sample.
struct PaneSplit {
  int forced = 0;
  int reflect_at = -1;
  int met = 0;  ///< out: forced panes the path met
};
/// Panes split on each line of sight: a glazing's two faces.
constexpr int kSplitPanes = 2;
/// PaneSplit::reflect_at: at the first or the second face, picked (see above).
constexpr int kEitherFace = -2;

/// The surface a camera ray met after going straight through window panes (the window view of
/// IntegratorOutputs): none when it went on to the sky.
struct WindowHit {
  bool hit = false;
  Vec3f albedo = Vec3f::Zero();
  Vec3f normal = Vec3f::Zero();  ///< shading normal facing the ray, world frame
  float distance = 0.f;          ///< along the camera ray, metres
};

/// Widest spread (radians) a rough bounce gives the texture cone: conservative next to the
/// 2 pi / spp steradians a diffuse sample stands for (0.63 rad at 16 spp), so that texture detail
/// an indirect ray could still resolve is kept.
constexpr float kIndirectConeSpread = 0.1f;

/// Angular width of a BSDF's non-delta lobes, capped at kIndirectConeSpread: diffuse lobes are
/// wide; a GGX lobe is about alpha radians (a Plastic's coat counts, as its base may not be the
/// lobe sampled).
float lobeSpread(const BsdfParams& b) {
  if (b.type == BsdfType::Lambertian || b.type == BsdfType::Translucent)
    return kIndirectConeSpread;
  return std::min(kIndirectConeSpread, std::sqrt(b.alpha_x * b.alpha_y));
}

float offsetScale(const Vec3f& p) {
  return 1e-4f * (1.0f + p.cwiseAbs().maxCoeff());
}

/// The pane triangle farthest along the ray o + t d (t > 0) that it crosses, or -1: where the
/// sun's light on o came in, when that light crossed a pane.
int outermostPortal(const SceneLights& lights, const Vec3f& o, const Vec3f& d) {
  int best = -1;
  float best_t = 0.f;
  for (size_t i = 0; i < lights.portalCount(); ++i) {
    const float t = lights.portal(i).crossing(o, d);
    if (t > best_t) {
      best_t = t;
      best = static_cast<int>(i);
    }
  }
  return best;
}

/// A lit point that a photon found (Photons): from the sun through a pane, or from a lamp.
struct Photon {
  Vec3f p;            ///< on the surface
  Vec3f to_light;     ///< unit direction the photon came from
  Vec3f incident;     ///< the light's irradiance at p per unit cosine: sun L x solid angle x
                      ///< (pane cosines) x panes' T; lamp I x falloff x panes' T / d^2
  float cos_g = 0.f;  ///< |ng . to_light|
  float density = 0.f;     ///< its area density given its group (see Photons)
  float light_pick = 0.f;  ///< probability that the light pick at p (as a path vertex lit from
                           ///< the light's side makes it) chooses its light
  SurfacePoint sp;    ///< the surface there (sp.ng: geometric normal)
  int source = -1;    ///< the portal triangle it came in through (0 .. P - 1), or P + its lamp
};

/// Photons: light that reaches a room by way of the surfaces it lands on first. Each frame
/// traces photons from the lights, and every non-delta path vertex x connects to one of them
/// (a shadow ray x -> y and the path x -> y -> light): bidirectional path tracing's connection
/// of a one-segment light subpath (Veach 1997, ch. 10), written here because nothing packaged
/// does it inside our integrator. Two kinds, each optional (RenderOptions):
///
/// Sun photons. Indoors most light is sunlight bounced off a bright patch on the floor; a path
/// finds that patch only when its BSDF sample happens to point at it, a few percent of
/// directions from a wall, so the walls fill with low-frequency blotches that the denoiser
/// keeps. A photon takes a direction in the sun's disk, a window's portal triangle (the faces
/// of its glass that see the sky, embree_scene.cpp) by its area projected toward the sun (total
/// W), a uniform point on it; the sun must reach that point with no other pane in the way (else
/// an outer pane's photon carries the light), and the photon goes on through the panes to the
/// first other surface, y. Its density there: p_A(y) = |ng . to_sun| / W_pane.
///
/// Lamp photons. A point light inside a lamp model sits a few centimetres from the model's own
/// parts: a ceiling lamp's white back plate 1.8 cm above its bulb gets I / d^2, thousands of
/// times what the room gets, and throws much of the lamp's light back down through the glass.
/// A path finds that plate only by a BSDF sample hitting its small bright patch: on apartment
/// 3's walls the lamps gave 91 % of the noise variance, most of it fireflies, and 17 % of
/// their light came by such rare paths. Each point or spot light sends kLampPhotons photons
/// (uniform on the sphere, or in a spot's outer cone) through panes to the first other surface
/// y; those landing within kLampReach of the light live (farther, next-event estimation does
/// well on its own). Density: p_A(y) = p_dir |ng . to_light| / d^2.
///
/// MIS: the path tracer makes the same path in two ways, a BSDF sample at x hitting y (straight
/// through any panes between) then (a) a BSDF sample at y hitting the light (the sun only) or
/// (b) next-event estimation of the light at y. (a) keeps its weight; the weight (b) had is
/// split between (b) and the photon (c) by the power heuristic on their densities of y given x,
/// p_b = p_bsdf(x) cos_y / d^2 x the light's pick at y and p_c = P(group | x) p_A(y) x emitted /
/// live (only live photons are picked), so the weights still sum to 1 on every path. For the
/// sun only the diffuse lobes at y take part (evalBsdfDiffuse): its glossy reflection (a
/// varnished floor's) stays with (a) and (b), as a photon picked uniformly finds that narrow
/// lobe no better than the BSDF sample at x that goes on to hit the sun. For a lamp every lobe
/// does: there is no (a), and a fixture's polished parts next to the bulb are what (b) finds
/// worst (on apartment 3's lamps, 20 % less variance than with the diffuse lobes alone).
/// Unbiased; the photons are drawn per frame from their own seed, one Sobol sequence per light,
/// at the exposure's start (time 0).
///
/// Picking: the live photons are grouped by their source (a pane triangle, a lamp), and a
/// vertex picks a group by the light it delivered (luminance of its flux) over the squared
/// distance to its photons' centre (never below their own spread), then a photon of it
/// uniformly: the patches of the room a vertex is in, not those behind its walls, get most
/// connections. The path tracer finds the group of a y reached by (b) as the outermost portal
/// triangle its sun ray crosses, or the lamp it sampled.
struct Photons {
  struct Group {
    Vec3f centre = Vec3f::Zero();
    float spread2 = 0.f;    ///< squared RMS distance of its photons from the centre (>= 1 cm^2)
    float delivered = 0.f;  ///< luminance of the flux it carries x live / emitted, unnormalised
    /// emitted / live x the source's density factor: 1 / W_pane (sun; density = cos_g x this)
    /// or the direction pdf (lamp; density = cos_g x this / d^2)
    float density_scale = 0.f;
    int lamp = -1;               ///< its lamp (index into `lamps`), -1 for the sun
    size_t first = 0, count = 0; ///< its photons in `photons`
  };
  std::vector<Photon> photons;  ///< the live ones, by group, in emission order within one
  std::vector<Group> groups;
  std::vector<int> group_of_source;  ///< per portal triangle, then per lamp: -1 when none lived
  std::vector<SceneLights::LampView> lamps;
  std::vector<int> lamp_of_pick;     ///< per light pick entry: its index in `lamps`, or -1
  bool sun = false;
  size_t sun_pick = 0;               ///< the sun's pick entry (when `sun`)
  float solid_angle = 0.f;           ///< of the sun's disk

  /// Unnormalised probability of picking group g from a vertex at x.
  float groupWeight(size_t g, const Vec3f& x) const {
    const Group& gr = groups[g];
    return gr.delivered / std::max((x - gr.centre).squaredNorm(), gr.spread2);
  }
  float groupTotal(const Vec3f& x) const {
    float total = 0.f;
    for (size_t g = 0; g < groups.size(); ++g) total += groupWeight(g, x);
    return total;
  }
  /// The group whose photons could have brought the light of a sample of pick entry `pick` at
  /// y (direction wi, through `panes` panes), or -1: the sun's through the outermost portal
  /// triangle its ray crosses; a lamp's within kLampReach.
  int groupOf(const SceneLights& lights, size_t pick, const Vec3f& y, const Vec3f& wi,
              int panes) const;
  /// p_A(y) given group g, for a point y with |ng . to_light| = cos_g (Photon::density).
  float density(size_t g, const Vec3f& y, float cos_g) const {
    const Group& gr = groups[g];
    if (gr.lamp < 0) return cos_g * gr.density_scale;
    const float d2 = (lamps[static_cast<size_t>(gr.lamp)].position - y).squaredNorm();
    return d2 > 0.f ? cos_g * gr.density_scale / d2 : 0.f;
  }
};

constexpr int kSunPhotons = 1 << 16;
// Every non-delta vertex connects: on the default 12-frame sequence of apartment 3, the first
// two alone saved 10 % of the time and gave back a third of the gain in flat-region error.
constexpr uint64_t kSunPhotonSalt = 0xbb67ae8584caa73bull;
constexpr int kLampPhotons = 1 << 12;  ///< per point or spot light
constexpr float kLampReach = 0.5f;     ///< metres from the light within which they live
constexpr uint64_t kLampPhotonSalt = 0x3c6ef372fe94f82bull;

int Photons::groupOf(const SceneLights& lights, size_t pick, const Vec3f& y, const Vec3f& wi,
                     int panes) const {
  if (sun && pick == sun_pick) {
    if (panes == 0) return -1;
    const int portal = outermostPortal(lights, y, wi);
    return portal >= 0 ? group_of_source[static_cast<size_t>(portal)] : -1;
  }
  const int lamp = pick < lamp_of_pick.size() ? lamp_of_pick[pick] : -1;
  if (lamp < 0 ||
      (lamps[static_cast<size_t>(lamp)].position - y).squaredNorm() > kLampReach * kLampReach)
    return -1;
  return group_of_source[group_of_source.size() - lamps.size() + static_cast<size_t>(lamp)];
}

/// The density of a lamp photon's direction: uniform on the sphere, or in a spot's outer cone.
double lampDirectionPdf(const SceneLights::LampView& lamp) {
  return lamp.spot ? 1.0 / (2.0 * kPi * (1.0 - static_cast<double>(lamp.cos_outer)))
                   : 1.0 / (4.0 * kPi);
}

/// Per-frame helpers of a call of `radiance`: the light cache (light_cache.h) light picks are
/// weighed by, or the one this path's shadow rays train (at most one of the two), and the sun
/// photons its vertices connect to (none while training).
struct LightCaching {
  const LightCache* use = nullptr;
  LightCache* train = nullptr;
  const Photons* photons = nullptr;
  /// the radiance cache paths stop at (RenderOptions::radiance_cache), or the recorder of a
  /// training path (at most one of the two)
  const RadianceCache* radiance = nullptr;
  RadianceCache::Recorder* record = nullptr;
};

/// The radiance cache's training pass: every kRadianceTrainStride-th pixel in each direction,
/// RadianceCache::Config::train_spp full paths each (at least train_min_paths in all); each
/// records at the vertex where the frame's paths read the cache.
constexpr int kRadianceTrainStride = 2;
constexpr uint64_t kRadianceSeedSalt = 0xbb67ae8584caa73bull;
/// A path reads the cache at the vertex after its first rough scattering (its second but for
/// mirrors and panes), where training paths record. After the second (the first design):
/// apartment 3's default sequence 0.0372 / 0.0326 / 0.0352 flat error in 95 s; after the
/// first, with 16 training paths, 0.0335 / 0.0304 / 0.0324 in 74 s (docs/rendering.md).
constexpr int kReadAtRough = 1;

/// The light cache's training pass: every kCacheTrainStride-th pixel in each direction, at
/// least kCacheTrainSpp paths each and at least kCacheTrainPaths in all (a small image would
/// leave most cells under LightCache::kMinTrials), from a seed of their own, so the frame's
/// samples stay independent of them. Every vertex of those paths traces one training shadow
/// ray. At 16 spp it adds 3 % to the frame's paths (8 per 16 pixels) from 320x240 up.
constexpr int kCacheTrainStride = 4;
constexpr int kCacheTrainSpp = 8;
constexpr int kCacheTrainPaths = 1 << 15;
constexpr uint64_t kCacheSeedSalt = 0x6a09e667f3bcc909ull;

class PathTracer final : public Integrator {
 public:
  std::string name() const override { return "path"; }

  void render(const RenderContext& ctx, ImageF& rgb,
              const IntegratorOutputs& out) const override {
    const CameraIntrinsics& K = ctx.lens.K;
    // angle one pixel subtends (fx, fy are pixels per radian for every lens model)
    const auto pixel_spread = static_cast<float>(1.0 / std::sqrt(K.fx * K.fy));
    // Camera rays go out in coherent 16-wide packets: for each sample index, the rays of a 4x4
    // pixel block are intersected together (rtcIntersect16), then each path continues alone.
    // Every pixel still sums its samples in sample order, so the image does not depend on
    // threads or tiles.
    std::unique_ptr<LightCache> cache;
    if (ctx.options.light_cache) cache = trainLightCache(ctx, pixel_spread);
    std::unique_ptr<Photons> photons;
    if (ctx.options.sun_photons || ctx.options.lamp_photons) photons = tracePhotons(ctx, cache.get());
    std::unique_ptr<RadianceCache> radiance_cache;
    if (ctx.options.radiance_cache)
      radiance_cache = trainRadianceCache(ctx, pixel_spread, cache.get(), photons.get());
    const LightCaching caching{cache.get(), nullptr, photons.get(), radiance_cache.get()};
    const int tiles_x = (K.width + kTile - 1) / kTile, tiles_y = (K.height + kTile - 1) / kTile;
    auto tile = [&](const tbb::blocked_range<int>& range) {
      uint64_t tile_rays = 0;
      RTCIntersectContext ictx;
      rtcInitIntersectContext(&ictx);
      ictx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (int t = range.begin(); t < range.end(); ++t) {
        const int x_begin = (t % tiles_x) * kTile, y_begin = (t / tiles_x) * kTile;
        const int x_end = std::min(x_begin + kTile, K.width);
        const int y_end = std::min(y_begin + kTile, K.height);
        for (int by = y_begin; by < y_end; by += 4)
          for (int bx = x_begin; bx < x_end; bx += 4)
            renderBlock(ctx, bx, by, std::min(bx + 4, x_end), std::min(by + 4, y_end), ictx,
                        pixel_spread, caching, rgb, out, tile_rays);
      }
      if (ctx.stats) ctx.stats->rays += tile_rays;
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), tile);
    if (ctx.stats) {
      uint64_t samples = 0;
      for (int y = 0; y < K.height; ++y)
        for (int x = 0; x < K.width; ++x) samples += static_cast<uint64_t>(pixelSpp(ctx.options, x, y));
      ctx.stats->samples += samples;
    }
  }

 private:
  /// The camera paths of a training pass through the frame's own view, at its static pose
  /// (motion blur or rolling shutter only move where a cache learns, never what the frame's
  /// estimate converges to): every `stride`-th pixel in each direction, `min_spp` paths each
  /// and at least `min_paths` in all (a small image would leave most cells untrained), from
  /// `seed`, so the frame's own samples stay independent of them. Rows go to parallel tasks;
  /// each task calls `per_task(trace)` once, and `trace(caching)` traces the task's paths with
  /// the helpers the task set up (a recorder of its own, merged when trace returns).
  template <class PerTask>
  void traceTrainingPaths(const RenderContext& ctx, float pixel_spread, int stride, int min_spp,
                          int min_paths, uint64_t seed, PerTask per_task) const {
    const CameraIntrinsics& K = ctx.lens.K;
    const Eigen::Matrix3f R = ctx.T_world_camera.rotation().cast<float>();
    const Vec3f origin = ctx.T_world_camera.t.cast<float>();
    const int rows = (K.height + stride - 1) / stride;
    const int columns = (K.width + stride - 1) / stride;
    const int spp = std::max(min_spp, (min_paths + rows * columns - 1) / (rows * columns));
    tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
      uint64_t rays = 0;
      uint32_t hashes[PixelSampler::kMaxPairs];
      auto trace = [&](const LightCaching& caching) {
        for (int row = r.begin(); row < r.end(); ++row) {
          const int y = row * stride;
          for (int x = 0; x < K.width; x += stride) {
            const auto pixel = static_cast<uint32_t>(y * K.width + x);
            PixelSampler::pairHashes(seed, ctx.frame_index, pixel, hashes);
            for (int s = 0; s < spp; ++s) {
              PixelSampler smp(seed, ctx.frame_index, pixel, static_cast<uint32_t>(s),
                               static_cast<uint32_t>(spp), hashes);
              const Eigen::Vector2f j = smp.get2D();
              CameraRay cr;
              if (!generateRay(ctx.lens, x + j.x(), y + j.y(), kLensCentre, cr)) continue;
              const Ray ray{R * cr.origin.cast<float>() + origin,
                            (R * cr.dir.cast<float>()).normalized(), 0.f};
              Vec3f le;
              radiance(ctx, ray, pixel_spread, smp, le, nullptr, rays, nullptr, caching);
            }
          }
        }
      };
      per_task(trace);
      if (ctx.stats) ctx.stats->rays += rays;
    });
  }

  /// The light cache of this frame: what each light's shadow rays from the visible surfaces,
  /// and from the surfaces their paths reach, let through.
  std::unique_ptr<LightCache> trainLightCache(const RenderContext& ctx, float pixel_spread) const {
    auto cache = std::make_unique<LightCache>();
    traceTrainingPaths(ctx, pixel_spread, kCacheTrainStride, kCacheTrainSpp, kCacheTrainPaths,
                       ctx.options.seed ^ kCacheSeedSalt,
                       [&](auto& trace) { trace(LightCaching{nullptr, cache.get()}); });
    cache->build();
    return cache;
  }

  /// The radiance cache of this frame (radiance_cache.h), from training paths that pick lights
  /// and photons as the frame's do (`cache`, `photons`), so what a cell records is what the
  /// frame's paths would gather past it.
  std::unique_ptr<RadianceCache> trainRadianceCache(const RenderContext& ctx, float pixel_spread,
                                                    const LightCache* cache,
                                                    const Photons* photons) const {
    const RadianceCache::Config& config = ctx.options.radiance_cache_config;
    auto out = std::make_unique<RadianceCache>(config);
    traceTrainingPaths(ctx, pixel_spread, kRadianceTrainStride, config.train_spp,
                       config.train_min_paths, ctx.options.seed ^ kRadianceSeedSalt,
                       [&](auto& trace) {
                         RadianceCache::Recorder recorder(*out);
                         trace(LightCaching{cache, nullptr, photons, nullptr, &recorder});
                         out->merge(recorder);
                       });
    out->build();
    return out;
  }

  /// This frame's photons (Photons): the sun's with RenderOptions::sun_photons, the lamps' with
  /// lamp_photons; nullptr when none lives.
  std::unique_ptr<Photons> tracePhotons(const RenderContext& ctx, const LightCache* cache) const {
    const EmbreeScene& scene = ctx.scene;
    const SceneLights& lights = scene.lights();
    auto out = std::make_unique<Photons>();
    const size_t n_portals = lights.portalCount();
    std::optional<SceneLights::SunView> sun;
    if (ctx.options.sun_photons && n_portals > 0) sun = lights.firstSun();
    if (ctx.options.lamp_photons) out->lamps = lights.lamps();
    // the sun's portal triangles by their area projected toward it (total W)
    std::vector<double> cdf;
    double W = 0.0;
    if (sun) {
      for (size_t i = 0; i < n_portals; ++i) {
        const PortalTriangle& t = lights.portal(i);
        W += static_cast<double>(t.area) * std::fabs(t.normal.dot(sun->to_sun));
        cdf.push_back(W);
      }
      if (!(W > 0.0)) sun.reset();
    }
    const int n_sun = sun ? kSunPhotons : 0;
    const int n_lamps = static_cast<int>(out->lamps.size());
    const int n_all = n_sun + n_lamps * kLampPhotons;
    if (n_all == 0) return nullptr;
    std::vector<Photon> all(static_cast<size_t>(n_all));
    std::vector<char> live(static_cast<size_t>(n_all), 0);
    std::vector<int> source_of(static_cast<size_t>(n_all), -1);
    // through panes to the first other surface: its hit (of `ray`, moved on to the last pane),
    // the panes' transmission, the distance travelled and the panes crossed, or false when the
    // ray leaves the scene
    auto throughPanes = [&](Ray& ray, RTCRayHit& rh, int& object, Vec3f& ng, Vec3f& T,
                            float& travelled, int& panes, uint64_t& rays) {
      T = Vec3f::Ones();
      travelled = 0.f;
      for (panes = 0;; ++panes) {
        ++rays;
        if (!intersect(scene, ray, rh)) return false;
        object = scene.objectOf(rh.hit);
        ng = scene.worldNormal(object, Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        travelled += rh.ray.tfar;
        if (!isPane(scene, object) || panes == kMaxPanes) return true;
        const BsdfParams& b = scene.object(object).bsdf;
        T = T.cwiseProduct(thinDielectricTransmission(b, ng.dot(ray.d)));
        const Vec3f p = ray.o + rh.ray.tfar * ray.d;
        ray.o = p + ng * (ng.dot(ray.d) > 0.f ? offsetScale(p) : -offsetScale(p));
      }
    };
    // the surface at a photon's hit and the pick of its light there (false: it does not live)
    auto land = [&](Photon& ph, const Ray& ray, const RTCRayHit& rh, int object, const Vec3f& ng,
                    float travelled, size_t pick) {
      ph.p = ray.o + rh.ray.tfar * ray.d;
      scene.surface(object, rh.hit.primID, rh.hit.u, rh.hit.v, ng, ray.d,
                    kIndirectConeSpread * travelled, ph.sp);
      if (isDelta(ph.sp.bsdf)) return false;
      ph.to_light = -ray.d;
      ph.cos_g = std::fabs(ng.dot(ray.d));
      if (!(ph.cos_g > 0.f)) return false;
      // the pick point a vertex here lit from the light's side takes (radiance(): Lambertian
      // vertices pick from just above the surface on the side they light)
      const Vec3f n_face = ng.dot(ph.to_light) > 0.f ? ng : Vec3f(-ng);
      const bool lambert = ph.sp.bsdf.type == BsdfType::Lambertian;
      const Vec3f at = lambert ? Vec3f(ph.p + n_face * offsetScale(ph.p)) : ph.p;
      ph.light_pick = lights.pickProbability(lights.pickAt(at, cache), pick);
      return ph.light_pick > 0.f;
    };
    const float solid_angle = sun ? sun->solidAngle() : 0.f;
    tbb::parallel_for(tbb::blocked_range<int>(0, n_all), [&](const tbb::blocked_range<int>& r) {
      uint64_t rays = 0;
      for (int i = r.begin(); i < r.end(); ++i) {
        const auto slot = static_cast<size_t>(i);
        Photon& ph = all[slot];
        RTCRayHit rh;
        int object = -1;
        Vec3f ng, T;
        float travelled = 0.f;
        int panes = 0;
        if (i < n_sun) {
          // one Sobol sequence over the sun's photons (stratified in direction, pane and point)
          PixelSampler smp(ctx.options.seed ^ kSunPhotonSalt, ctx.frame_index, 0,
                           static_cast<uint32_t>(i), kSunPhotons);
          const Vec3f d = sun->direction(smp.get2D());
          const Eigen::Vector2f u = smp.get2D();
          const double target = static_cast<double>(smp.get1D()) * W;
          const size_t j = std::min<size_t>(
              static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) -
                                  cdf.begin()),
              cdf.size() - 1);
          source_of[slot] = static_cast<int>(j);
          const PortalTriangle& pane = lights.portal(j);
          const float cos_pane = pane.normal.dot(d),
                      cos_pane_centre = pane.normal.dot(sun->to_sun);
          if (!(std::fabs(cos_pane) > 1e-4f) || !(std::fabs(cos_pane_centre) > 1e-4f)) continue;
          const Vec3f q = pane.point(u);
          const Vec3f sun_side = cos_pane > 0.f ? pane.normal : Vec3f(-pane.normal);
          const Vec3f q_out = q + sun_side * (2.f * offsetScale(q));
          // the sun reaches q with no pane or wall in the way
          ++rays;
          if (occluded(scene, q_out, d, std::numeric_limits<float>::infinity(), 0.f)) continue;
          // in through q's pane and any behind it, to the first other surface
          Ray ray{q_out, -d, 0.f};
          if (!throughPanes(ray, rh, object, ng, T, travelled, panes, rays)) continue;
          if (panes == 0 || !(T.maxCoeff() > 0.f)) continue;
          if (!land(ph, ray, rh, object, ng, travelled, sun->pick)) continue;
          ph.incident = (sun->radiance * (solid_angle * std::fabs(cos_pane / cos_pane_centre)))
                            .cwiseProduct(T);
        } else {
          const int k = (i - n_sun) / kLampPhotons, n = (i - n_sun) % kLampPhotons;
          const SceneLights::LampView& lamp = out->lamps[static_cast<size_t>(k)];
          source_of[slot] = static_cast<int>(n_portals) + k;
          PixelSampler smp(ctx.options.seed ^ kLampPhotonSalt, ctx.frame_index,
                           static_cast<uint32_t>(k), static_cast<uint32_t>(n), kLampPhotons);
          const Eigen::Vector2f u = smp.get2D();
          // uniform on the sphere, or in a spot's outer cone (lampDirectionPdf)
          const float z = lamp.spot ? 1.f - u.x() * (1.f - lamp.cos_outer) : 1.f - 2.f * u.x();
          const float rho = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.f * kPi * u.y();
          const Frame3 f = Frame3::fromNormal(lamp.spot ? lamp.direction : Vec3f::UnitZ());
          const Vec3f d =
              (f.s * (rho * std::cos(phi)) + f.t * (rho * std::sin(phi)) + f.n * z).normalized();
          const float falloff = lamp.falloff(d);
          if (!(falloff > 0.f)) continue;
          Ray ray{lamp.position, d, 0.f};
          if (!throughPanes(ray, rh, object, ng, T, travelled, panes, rays)) continue;
          if (travelled > kLampReach ||
              (lamp.max_distance > 0.f && travelled > lamp.max_distance) ||
              !(T.maxCoeff() > 0.f))
            continue;
          if (!land(ph, ray, rh, object, ng, travelled, lamp.pick)) continue;
          const float d2 = (ph.p - lamp.position).squaredNorm();
          if (!(d2 > 0.f)) continue;
          ph.incident = lamp.rgb.cwiseProduct(T) * (falloff / (d2 + lamp.radius2));
        }
        ph.source = source_of[slot];
        live[slot] = 1;
      }
      if (ctx.stats) ctx.stats->rays += rays;
    });
    // groups: per source, of the photons that lived
    const size_t n_sources = n_portals + out->lamps.size();
    std::vector<size_t> emitted(n_sources, 0), lived(n_sources, 0);
    for (size_t i = 0; i < all.size(); ++i) {
      if (source_of[i] >= 0) ++emitted[static_cast<size_t>(source_of[i])];
      if (live[i]) ++lived[static_cast<size_t>(all[i].source)];
    }
    out->group_of_source.assign(n_sources, -1);
    for (size_t j = 0; j < n_sources; ++j) {
      if (lived[j] == 0) continue;
      out->group_of_source[j] = static_cast<int>(out->groups.size());
      Photons::Group g;
      const double share = static_cast<double>(lived[j]) / static_cast<double>(emitted[j]);
      if (j < n_portals) {
        const PortalTriangle& t = lights.portal(j);
        const double W_j = static_cast<double>(t.area) * std::fabs(t.normal.dot(sun->to_sun));
        g.delivered =
            static_cast<float>(luminance(sun->radiance) * solid_angle * W_j * share);
        g.density_scale = static_cast<float>(1.0 / (share * W_j));
      } else {
        g.lamp = static_cast<int>(j - n_portals);
        const SceneLights::LampView& lamp = out->lamps[static_cast<size_t>(g.lamp)];
        g.delivered = static_cast<float>(luminance(lamp.rgb) * 4.0 * kPi * share);
        g.density_scale = static_cast<float>(lampDirectionPdf(lamp) / share);
      }
      out->groups.push_back(g);
    }
    if (out->groups.empty()) return nullptr;
    // the live photons by group (a stable counting sort: emission order within a group)
    for (size_t i = 0; i < all.size(); ++i)
      if (live[i]) ++out->groups[static_cast<size_t>(out->group_of_source[all[i].source])].count;
    size_t next = 0;
    for (Photons::Group& g : out->groups) {
      g.first = next;
      next += g.count;
    }
    out->photons.resize(next);
    std::vector<size_t> fill(out->groups.size(), 0);
    for (size_t i = 0; i < all.size(); ++i) {
      if (!live[i]) continue;
      const auto g = static_cast<size_t>(out->group_of_source[all[i].source]);
      Photon& ph = out->photons[out->groups[g].first + fill[g]++];
      ph = all[i];
      ph.density = out->density(g, ph.p, ph.cos_g);
    }
    for (Photons::Group& g : out->groups) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (size_t k = 0; k < g.count; ++k) c += out->photons[g.first + k].p.cast<double>();
      c /= static_cast<double>(g.count);
      double r2 = 0.0;
      for (size_t k = 0; k < g.count; ++k)
        r2 += (out->photons[g.first + k].p.cast<double>() - c).squaredNorm();
      g.centre = c.cast<float>();
      g.spread2 = std::max(static_cast<float>(r2 / static_cast<double>(g.count)), 1e-4f);
    }
    out->lamp_of_pick.assign(lights.pickCount(), -1);
    for (size_t k = 0; k < out->lamps.size(); ++k)
      out->lamp_of_pick[out->lamps[k].pick] = static_cast<int>(k);
    out->sun = sun.has_value();
    if (sun) out->sun_pick = sun->pick;
    out->solid_angle = solid_angle;
    return out;
  }

  /// Renders pixels [x0, x1) x [y0, y1) (at most 4 x 4) with packets of camera rays.
  void renderBlock(const RenderContext& ctx, int x0, int y0, int x1, int y1,
                   RTCIntersectContext& ictx, float pixel_spread, const LightCaching& caching,
                   ImageF& rgb, const IntegratorOutputs& out, uint64_t& rays) const {
    const CameraIntrinsics& K = ctx.lens.K;
    const bool thin_lens = ctx.lens.type == LensType::ThinLens && ctx.lens.aperture_radius_m > 0;
    // the first surface's diffuse light and albedo, only when a layer asks for them
    const bool split = out.diffuse || out.diffuse_variance || out.rest_variance || out.albedo ||
                       out.view_alpha;
    // timed: the exposure has a duration and something moves (camera or objects); every sample
    // then draws its time, which places the camera (moving) and the objects (ray time)
    const bool timed = ctx.exposure != nullptr && ctx.exposure->span() > 0;
    const bool moving = timed && ctx.exposure->moving();
    const float inv_span = timed ? 1.f / static_cast<float>(ctx.exposure->span()) : 0.f;
    const Eigen::Matrix3f R = ctx.T_world_camera.rotation().cast<float>();
    const Vec3f origin = ctx.T_world_camera.t.cast<float>();
    WindowViewLayers* const view = out.window_view;
    const Vec3f forward = R.col(2);  // the camera's z axis: z-depth = distance x (d . forward)
    struct Lane {
      int x = 0, y = 0;
      uint32_t pixel = 0;
      bool inside = false;
      Vec3f sum = Vec3f::Zero(), sum2 = Vec3f::Zero(), sum_le = Vec3f::Zero();
      Vec3f sum_d = Vec3f::Zero(), sum2_d = Vec3f::Zero(), sum2_rest = Vec3f::Zero();
      Vec3f sum_albedo = Vec3f::Zero();
      float view_alpha = kNoViewDependentLobe;  ///< the least over the pixel's samples
      // the window view: its samples' light, squared light, albedo, normal and z-depth
      Vec3f sum_w = Vec3f::Zero(), sum2_w = Vec3f::Zero(), sum_wa = Vec3f::Zero();
      Vec3f sum_wn = Vec3f::Zero();
      float sum_wz = 0.f;
      int count_w = 0;
      int spp = 0;  ///< this pixel's samples (RenderOptions::spp_multiplier)
      uint32_t hashes[PixelSampler::kMaxPairs];
    };
    Lane lanes[16];
    int block_spp = 0;  // the most samples any pixel of the block takes
    for (int k = 0; k < 16; ++k) {
      Lane& l = lanes[k];
      l.x = x0 + (k & 3);
      l.y = y0 + (k >> 2);
      l.inside = l.x < x1 && l.y < y1;
      if (!l.inside) continue;
      l.pixel = static_cast<uint32_t>(l.y * K.width + l.x);
      l.spp = pixelSpp(ctx.options, l.x, l.y);
      block_spp = std::max(block_spp, l.spp);
      PixelSampler::pairHashes(ctx.options.seed, ctx.frame_index, l.pixel, l.hashes);
    }
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    std::optional<PixelSampler> smp[16];
    Ray ray[16];
    for (int s = 0; s < block_spp; ++s) {
      for (int k = 0; k < 16; ++k) {
        // an inactive lane (outside the block, or no ray: a fisheye's corners) still holds a
        // well-formed, empty ray (tfar < tnear): Debian's Embree is built with assertions on
        // its packet rays, and aborted on the packet's uninitialised lanes (a fisheye at 1 spp;
        // which garbage the stack held decided it)
        valid[k] = 0;
        rh.ray.org_x[k] = rh.ray.org_y[k] = rh.ray.org_z[k] = 0.f;
        rh.ray.dir_x[k] = rh.ray.dir_y[k] = 0.f;
        rh.ray.dir_z[k] = 1.f;
        rh.ray.tnear[k] = 0.f;
        rh.ray.tfar[k] = -std::numeric_limits<float>::infinity();
        rh.ray.time[k] = 0.f;
        rh.ray.mask[k] = 0u;
        rh.ray.id[k] = static_cast<unsigned>(k);
        rh.ray.flags[k] = 0;
        Lane& l = lanes[k];
        if (!l.inside || s >= l.spp) continue;
        smp[k].emplace(ctx.options.seed, ctx.frame_index, l.pixel, static_cast<uint32_t>(s),
                       static_cast<uint32_t>(l.spp), l.hashes);
        Eigen::Vector2f j = smp[k]->get2D();
        Eigen::Vector2d lens_uv = thin_lens ? smp[k]->get2D().cast<double>() : kLensCentre;
        CameraRay cr;
        if (!generateRay(ctx.lens, l.x + j.x(), l.y + j.y(), lens_uv, cr))
          continue;  // no ray: black
        Eigen::Matrix3f Rs = R;
        Vec3f origin_s = origin;
        float time = 0.f;
        if (timed) {  // motion blur: this sample's time inside its row's exposure
          TimeNs t = sampleTime(ctx.exposure->shutter, 0, l.y, K.height, smp[k]->get1D());
          time = std::min(static_cast<float>(t) * inv_span, 1.f);
          if (moving) {
            Pose pose = ctx.exposure->at(t);
            Rs = pose.rotation().cast<float>();
            origin_s = pose.t.cast<float>();
          }
        }
        ray[k] = Ray{Rs * cr.origin.cast<float>() + origin_s,
                     (Rs * cr.dir.cast<float>()).normalized(), time};
        valid[k] = -1;
        rh.ray.org_x[k] = ray[k].o.x();
        rh.ray.org_y[k] = ray[k].o.y();
        rh.ray.org_z[k] = ray[k].o.z();
        rh.ray.dir_x[k] = ray[k].d.x();
        rh.ray.dir_y[k] = ray[k].d.y();
        rh.ray.dir_z[k] = ray[k].d.z();
        rh.ray.tnear[k] = 0.f;
        rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
        rh.ray.time[k] = time;
        rh.ray.mask[k] = 0xffffffffu;
        rh.ray.id[k] = static_cast<unsigned>(k);
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        ++rays;
      }
      rtcIntersect16(valid, ctx.scene.handle(), &ictx, &rh);
      for (int k = 0; k < 16; ++k) {
        if (!valid[k]) continue;
        RTCRayHit first;
        first.ray.tfar = rh.ray.tfar[k];
        first.hit.Ng_x = rh.hit.Ng_x[k];
        first.hit.Ng_y = rh.hit.Ng_y[k];
        first.hit.Ng_z = rh.hit.Ng_z[k];
        first.hit.u = rh.hit.u[k];
        first.hit.v = rh.hit.v[k];
        first.hit.primID = rh.hit.primID[k];
        first.hit.geomID = rh.hit.geomID[k];
        first.hit.instID[0] = rh.hit.instID[0][k];
        Vec3f le;
        FirstSurface fs;
        WindowHit window;
        Vec3f v;
        if (first.hit.geomID != RTC_INVALID_GEOMETRY_ID &&
            isPane(ctx.scene, ctx.scene.objectOf(first.hit))) {
          // the panes on the line of sight, split (PaneSplit): straight through the first two,
          // then reflected at the first or (where there is a second) at either face; both
          // paths draw the same numbers
          PixelSampler again = *smp[k];
          PaneSplit through{kSplitPanes, -1};
          v = radiance(ctx, ray[k], pixel_spread, *smp[k], le, split ? &fs : nullptr, rays,
                       &first, caching, view ? &window : nullptr, &through);
          PaneSplit reflected = through.met >= 2 ? PaneSplit{2, kEitherFace} : PaneSplit{1, 0};
          Vec3f le_r;
          FirstSurface fs_r;
          v += radiance(ctx, ray[k], pixel_spread, again, le_r, split ? &fs_r : nullptr, rays,
                        &first, caching, nullptr, &reflected);
          le += le_r;
          fs.diffuse += fs_r.diffuse;
        } else {
          v = radiance(ctx, ray[k], pixel_spread, *smp[k], le, split ? &fs : nullptr, rays,
                       &first, caching, view ? &window : nullptr);
        }
        Lane& l = lanes[k];
        if (window.hit) {
          ++l.count_w;
          l.sum_w += le;
          l.sum2_w += le.cwiseProduct(le);
          l.sum_wa += window.albedo;
          l.sum_wn += window.normal;
          l.sum_wz += window.distance * ray[k].d.dot(forward);
        }
        l.sum += v;
        l.sum_le += le;
        Vec3f reflected = v - le;  // the variance guide describes what gets filtered
        l.sum2 += reflected.cwiseProduct(reflected);
        if (split) {
          l.sum_d += fs.diffuse;
          l.sum_albedo += fs.albedo;
          l.view_alpha = std::min(l.view_alpha, fs.view_alpha);
          l.sum2_d += fs.diffuse.cwiseProduct(fs.diffuse);
          const Vec3f rest = reflected - fs.diffuse;
          l.sum2_rest += rest.cwiseProduct(rest);
        }
      }
    }
    for (const Lane& l : lanes) {
      if (!l.inside) continue;
      const auto n = static_cast<float>(l.spp);
      // unbiased sample variance of the mean of `count` samples, from their sum and sum of
      // squares
      auto varianceOfMean = [](float sum, float sum2, int count) {
        const auto m = static_cast<float>(count);
        return count > 1 ? std::max(0.f, (sum2 - sum * sum / m) / (m - 1.f)) / m : 0.f;
      };
      if (out.view_alpha) out.view_alpha->at(l.x, l.y) = l.view_alpha;
      if (view) {
        const bool any = l.count_w > 0;
        const auto m = static_cast<float>(l.count_w);
        const float norm = l.sum_wn.norm();
        view->coverage.at(l.x, l.y) = m / n;
        view->depth.at(l.x, l.y) = any ? l.sum_wz / m : 0.f;
        for (int c = 0; c < 3; ++c) {
          view->light.at(l.x, l.y, c) = any ? l.sum_w[c] / m : 0.f;
          view->variance.at(l.x, l.y, c) = varianceOfMean(l.sum_w[c], l.sum2_w[c], l.count_w);
          view->albedo.at(l.x, l.y, c) = any ? l.sum_wa[c] / m : 0.f;
          view->normal.at(l.x, l.y, c) = any && norm > 0.f ? l.sum_wn[c] / norm : 0.f;
        }
      }
      for (int c = 0; c < 3; ++c) {
        rgb.at(l.x, l.y, c) = l.sum[c] / n;
        if (out.emission) out.emission->at(l.x, l.y, c) = l.sum_le[c] / n;
        const float reflected = l.sum[c] - l.sum_le[c];
        if (out.variance) out.variance->at(l.x, l.y, c) = varianceOfMean(reflected, l.sum2[c], l.spp);
        if (out.diffuse) out.diffuse->at(l.x, l.y, c) = l.sum_d[c] / n;
        if (out.albedo) out.albedo->at(l.x, l.y, c) = l.sum_albedo[c] / n;
        if (out.diffuse_variance)
          out.diffuse_variance->at(l.x, l.y, c) = varianceOfMean(l.sum_d[c], l.sum2_d[c], l.spp);
        if (out.rest_variance)
          out.rest_variance->at(l.x, l.y, c) =
              varianceOfMean(reflected - l.sum_d[c], l.sum2_rest[c], l.spp);
      }
    }
  }

  /// A window pane: a thin dielectric that is not a light (what shadow rays pass through).
  static bool isPane(const EmbreeScene& scene, int object) {
    return scene.object(object).bsdf.type == BsdfType::ThinDielectric &&
           scene.object(object).first_light < 0;
  }

  static bool intersect(const EmbreeScene& scene, const Ray& ray, RTCRayHit& rh,
                        float tfar = std::numeric_limits<float>::infinity()) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rh.ray.org_x = ray.o.x();
    rh.ray.org_y = ray.o.y();
    rh.ray.org_z = ray.o.z();
    rh.ray.dir_x = ray.d.x();
    rh.ray.dir_y = ray.d.y();
    rh.ray.dir_z = ray.d.z();
    rh.ray.tnear = 0.f;  // origins are offset off the surface instead
    rh.ray.tfar = tfar;
    rh.ray.time = ray.time;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.handle(), &ctx, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }

  static bool occluded(const EmbreeScene& scene, const Vec3f& o, const Vec3f& d, float tfar,
                       float time) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    ray.org_x = o.x();
    ray.org_y = o.y();
    ray.org_z = o.z();
    ray.dir_x = d.x();
    ray.dir_y = d.y();
    ray.dir_z = d.z();
    ray.tnear = 0.f;
    ray.tfar = tfar;
    ray.time = time;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(scene.handle(), &ctx, &ray);
    return ray.tfar < 0.f;  // Embree sets tfar = -inf on a hit
  }

  /// What reaches along a shadow ray: zero if anything opaque blocks it, else the product of
  /// the straight-through transmissions of the thin panes (windows) it crosses. A pane's
  /// transmission is a delta lobe in the same direction, so light through glass is found by
  /// next-event estimation too (without this, sunlight through a window is reachable only by
  /// BSDF sampling hitting the 0.5-degree sun: fireflies on every sunlit wall).
  static constexpr int kMaxPanes = 8;

  /// `panes`, when given, receives the number of panes crossed.
  static Vec3f shadowTransmittance(const EmbreeScene& scene, Vec3f o, const Vec3f& d, float tfar,
                                   float time, int* panes = nullptr) {
    if (panes) *panes = 0;
    if (!occluded(scene, o, d, tfar, time)) return Vec3f::Ones();  // the common case, fast
    if (!scene.hasPanes()) return Vec3f::Zero();
    Vec3f T = Vec3f::Ones();
    // where the ray ends: after each pane the origin moves off it along its normal, which
    // shifts the line sideways; a finite ray is aimed at its end again from there (the shifted
    // line, a fraction of a millimetre off, met the very surface it was aimed at when that lay
    // just beyond the end at a grazing angle: a lamp's back plate seen through its glass)
    const Vec3f end = o + d * tfar;
    const bool finite = std::isfinite(tfar);
    Vec3f dir = d;
    for (int crossing = 0; crossing < kMaxPanes; ++crossing) {
      if (panes) *panes = crossing;
      RTCRayHit rh;
      if (!intersect(scene, Ray{o, dir, time}, rh, tfar)) return T;
      const int object = scene.objectOf(rh.hit);
      const BsdfParams& b = scene.object(object).bsdf;
      if (b.type != BsdfType::ThinDielectric || scene.object(object).first_light >= 0)
        return Vec3f::Zero();
      const Vec3f ng = scene.worldNormal(object, Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
      T = T.cwiseProduct(thinDielectricTransmission(b, ng.dot(dir)));
      const Vec3f p = o + rh.ray.tfar * dir;
      o = p + ng * (ng.dot(dir) > 0.f ? offsetScale(p) : -offsetScale(p));
      if (panes) *panes = crossing + 1;
      if (finite) {
        const Vec3f to_end = end - o;
        if (!(to_end.dot(dir) > 0.f)) return T;
        tfar = to_end.norm();
        dir = to_end / tfar;
      }
    }
    return Vec3f::Zero();  // more panes than any window has: treat as blocked
  }

  /// Radiance along a camera ray. `seen_emission` receives the part of it the filters must leave
  /// alone: the emission of what the camera sees (lamps, the sky), and all the light of a view
  /// straight through window panes; `first_surface`, when
  /// given, receives what IntegratorOutputs splits off at the first surface.
  /// `rays` counts the rays traced.
  /// `pixel_spread` is the angle of one pixel (radians), for texture footprints. `first`, when
  /// given, is the camera ray's hit, already traced (in a packet) and counted. `caching`: the
  /// light cache light picks are weighed by, or the one this path's shadow rays train.
  Vec3f radiance(const RenderContext& ctx, Ray ray, float pixel_spread, PixelSampler& smp,
                 Vec3f& seen_emission, FirstSurface* first_surface, uint64_t& rays,
                 const RTCRayHit* first = nullptr, const LightCaching& caching = {},
                 WindowHit* window = nullptr, PaneSplit* panes_split = nullptr) const;
};

Vec3f PathTracer::radiance(const RenderContext& ctx, Ray ray, float pixel_spread, PixelSampler& smp,
                           Vec3f& seen_emission, FirstSurface* first_surface, uint64_t& rays,
                           const RTCRayHit* first, const LightCaching& caching,
                           WindowHit* window, PaneSplit* panes_split) const {
  seen_emission = Vec3f::Zero();
  WindowHit beyond;  // the surface behind the panes, while the camera's ray goes straight on
  // The diffuse share of the first surface (scattering vertex 0): its light sample adds
  // f_diffuse / f of its contribution to the diffuse light at once; everything gathered after
  // its BSDF sample (L - L_at_first) is split by that direction's f_diffuse / f, `share`, at the
  // end. `splitting` until the first surface has scattered, when asked.
  Vec3f diffuse = Vec3f::Zero(), share = Vec3f::Zero(), L_at_first = Vec3f::Zero();
  bool splitting = first_surface != nullptr;
  if (first_surface) *first_surface = FirstSurface{};
  const EmbreeScene& scene = ctx.scene;
  const Photons* photons = caching.train ? nullptr : caching.photons;
  Vec3f L = Vec3f::Zero(), throughput = Vec3f::Ones();
  // Texture footprint: a ray cone (Akenine-Moller et al. 2021) of width `cone_width` at the
  // current hit, widening by `cone_spread` radians per metre travelled. From the camera it is the
  // pixel's own spread; a rough bounce widens it to the lobe's angular width, at most
  // kIndirectConeSpread, as production renderers filter textures seen by indirect rays
  // (Christensen et al. 2003: a diffuse ray stands for a solid angle of about 2 pi / spp, far
  // wider than a pixel). Those lookups then read coarse mip levels that stay in cache instead of
  // full-resolution texels at random places; the light they reflect averages over the lobe
  // anyway. The first surface (what the camera sees, the albedo guide) is unchanged.
  float cone_width = 0.f, cone_spread = pixel_spread;
  float prev_bsdf_pdf = 0.f;  // solid-angle pdf of the BSDF sample that produced `ray` (or, for
                              // a delta lobe, the probability of having chosen it)
  // Straight through a thin pane is not a new path vertex for MIS: light sampling looks through
  // panes (shadowTransmittance), so a light reached through one keeps the pdf of the vertex
  // before it. `no_mis`: the camera or a delta lobe made this ray (weight 1); `straight`: metres
  // from that vertex to the ray's origin.
  bool no_mis = true;
  float straight = 0.f;
  SceneLights::PickPoint light_at;  // where the vertex before `ray` sampled lights (MIS pdfs)
  Vec3f prev_p = Vec3f::Zero();     // that vertex (where it picked its sun photon)
  float prev_group_total = 0.f;     // and the sum of the photon groups' weights there
  float group_total = 0.f;          // the same at this vertex, once it has connected
  int panes = 0;  // panes passed straight through (at most kMaxPanes per path)
  // The view through a window: the first pane the camera's ray crosses before it scatters
  // (bounce 0: crossing a pane is not a bounce) starts `through_pane`, and all light gathered
  // from then on is returned in `seen_emission`, which the filters leave alone. The guides of
  // such a pixel are the pane's (a flat normal, its depth, its albedo) and say nothing about the
  // view behind it: filtering with them smeared the sunlit outdoors across the glass, which came
  // out further from a 512-spp reference than the unfiltered samples (docs/denoise.md).
  bool through_pane = false;
  Vec3f L_before_pane = Vec3f::Zero();
  // The radiance cache: rough (non-delta) scatterings so far, and while training, the vertex
  // that records what it sent on (the light gathered after arriving there, over the throughput
  // that reached it and its albedo where it is Lambertian).
  int rough = 0;
  struct Recorded {
    Vec3f p, n, factor, L;
    RadianceCache::Kind kind;
  };
  std::optional<Recorded> recorded;
  for (int bounce = 0, vertex = 0;; ++bounce, ++vertex) {
    const bool from_camera = vertex == 0;  // the camera's own ray (not one through a pane)
    RTCRayHit rh;
    bool hit;
    if (from_camera && first) {
      rh = *first;
      hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    } else {
      ++rays;
      hit = intersect(scene, ray, rh);
    }
    if (!hit) {
      if (through_pane && bounce == 0) beyond.hit = false;  // out to the sky
      float sun_pdf;
      Vec3f sun = scene.lights().environmentRadiance(ray.d, no_mis ? nullptr : &light_at, sun_pdf);
      if (sun.maxCoeff() > 0.f) {
        float w = no_mis ? 1.f : powerHeuristic(prev_bsdf_pdf, sun_pdf);
        L += w * throughput.cwiseProduct(sun);
        if (from_camera) seen_emission = sun;
      }
      break;
    }
    int object = scene.objectOf(rh.hit);
    const ObjectShading& s = scene.object(object);
    Vec3f ng = scene.worldNormal(object, Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    float t = rh.ray.tfar;
    Vec3f p = ray.o + t * ray.d;
    cone_width += cone_spread * t;
    float cos_emit = -ng.dot(ray.d);
    if (s.first_light >= 0 && cos_emit > 0.f) {
      float w = 1.f;
      if (!no_mis) {
        size_t li = static_cast<size_t>(s.first_light) + rh.hit.primID;
        w = powerHeuristic(prev_bsdf_pdf,
                           scene.lights().trianglePdf(li, light_at, straight + t, cos_emit));
      }
      L += w * throughput.cwiseProduct(s.emission);
      if (from_camera) seen_emission = s.emission;
    }
    if (bounce >= ctx.options.max_bounces) break;
    SurfacePoint sp;
    scene.surface(object, rh.hit.primID, rh.hit.u, rh.hit.v, ng, ray.d, cone_width, sp);
    const BsdfParams& bsdf = sp.bsdf;
    if (splitting) {
      first_surface->albedo = sp.albedo;
      first_surface->view_alpha = viewDependentAlpha(bsdf);
    }
    const bool lambert = bsdf.type == BsdfType::Lambertian;
    // Lambertian (the common case) keeps a fast path: two-sided, normal turned to face the ray.
    // Other BSDFs work in the frame of the shading normal (which lies on the geometric normal's
    // side) and handle both sides themselves (a dielectric needs the outward normal to know
    // inside from outside). Shading normals must not leak light: a direction counts only when it
    // is on the same side of the geometric surface as the shading frame says (reflection stays
    // in front, transmission goes through).
    const Vec3f n_face = cos_emit > 0.f ? ng : Vec3f(-ng);
    const Vec3f ns_face = cos_emit > 0.f ? sp.ns : Vec3f(-sp.ns);
    if (through_pane && bounce == 0)  // another pane behind the first is passed by again
      beyond = WindowHit{true, sp.albedo, ns_face, straight + t};
    // The radiance cache: read, or (training) recorded at, the vertex after the path's first
    // rough scattering when a rough BSDF sample reached it and it is rough itself (mirrors and
    // panes go on). Training paths record where the frame's paths read, reached the same way:
    // a cell's mean is then the mean over the points in it where the frame's paths land, so the
    // blur leaves the expected light as it is. (Recording at every vertex, the camera's first
    // surfaces too, made apartment 3's walls 4 % too bright: a light sample after a vertex that
    // connected to a photon gives up the photon's share of its weight (Photons), one after the
    // camera keeps it whole; and points at one depth spread over a cell otherwise than points
    // at another.)
    if (rough == kReadAtRough && !no_mis && !isDelta(bsdf) &&
        (caching.radiance || caching.record)) {
      const auto kind = lambert ? RadianceCache::Kind::PerAlbedo : RadianceCache::Kind::Radiance;
      const Vec3f factor = lambert ? sp.albedo : Vec3f::Ones();
      if (caching.radiance) {
        if (const Vec3f* sent = caching.radiance->lookup(p, n_face, kind)) {
          L += throughput.cwiseProduct(factor).cwiseProduct(*sent);
          break;
        }
      } else if (!recorded) {
        recorded = Recorded{p, n_face, throughput.cwiseProduct(factor), L, kind};
      }
    }
    Frame3 frame{Vec3f::UnitX(), Vec3f::UnitY(), Vec3f::UnitZ()};  // set below unless Lambertian
    Vec3f wo = Vec3f::UnitZ();
    if (!lambert) {
      frame = Frame3::fromNormal(sp.ns);
      wo = frame.toLocal(-ray.d);
    }
    // does world direction w leave on the side the shading frame says (local z sign)?
    auto consistent = [&](const Vec3f& w, float z_local) {
      return ((ng.dot(w) > 0.f) == (cos_emit > 0.f)) == ((z_local > 0.f) == (wo.z() > 0.f));
    };
    const float eps = offsetScale(p);
    auto offset = [&](const Vec3f& w) { return Vec3f(p + ng * (ng.dot(w) > 0.f ? eps : -eps)); };
    const Eigen::Vector2f u_select_rr = smp.get2D();  // x: which light, y: Russian roulette
    const Eigen::Vector2f u_light = smp.get2D();
    const Eigen::Vector2f u_bsdf = smp.get2D();
    LightSample ls;
    // light samples are taken from just above the surface on the side they light (for a
    // Lambertian, the side facing the ray), so that distances and cosines match the shadow ray
    const Vec3f p_face = p + n_face * eps;
    // one importance pass per vertex, none for a delta BSDF (it samples no light, and no MIS
    // weight is needed after it)
    SceneLights::PickPoint at;
    if (!isDelta(bsdf)) at = scene.lights().pickAt(lambert ? p_face : p, caching.use);
    // training the light cache: what this vertex's shadow ray let through (0 when the light
    // sample carried nothing, was behind the surface or was blocked)
    float trained_through = 0.f;
    if (!isDelta(bsdf) && scene.lights().sample(at, u_select_rr.x(), u_light, ls)) {
      Vec3f f_cos = Vec3f::Zero();
      float bsdf_pdf = 0.f;
      if (lambert) {
        if (n_face.dot(ls.wi) > 0.f) {
          float cos_s = std::max(0.f, ns_face.dot(ls.wi));
          f_cos = sp.albedo * (cos_s / kPi);
          bsdf_pdf = cos_s / kPi;
        }
      } else {
        const Vec3f wi_local = frame.toLocal(ls.wi);
        if (consistent(ls.wi, wi_local.z())) {
          BsdfEval e = evalBsdfPdf(bsdf, wo, wi_local);
          f_cos = e.value;
          bsdf_pdf = e.pdf;
        }
      }
      if (f_cos.maxCoeff() > 0.f) {
        Vec3f o = lambert ? p_face : offset(ls.wi);
        float tmax = std::isinf(ls.dist) ? std::numeric_limits<float>::infinity()
                                         : (lambert ? ls.dist : ls.dist - eps) * (1.f - 1e-4f);
        ++rays;
        int panes_crossed = 0;
        const Vec3f through =
            shadowTransmittance(scene, o, ls.wi, tmax, ray.time,
                                photons ? &panes_crossed : nullptr);
        trained_through = luminance(through);
        if (through.maxCoeff() > 0.f) {
          float w = ls.delta ? 1.f : powerHeuristic(ls.pdf, bsdf_pdf);
          Vec3f f_weighted = f_cos * w;  // f cos, times its MIS weight
          // light a photon could have brought (sunlight through a pane, a lamp's near it),
          // reached from a vertex that connected to a photon: the photon's share of this
          // path's diffuse part (Photons)
          const int group =
              photons && !no_mis && prev_group_total > 0.f
                  ? photons->groupOf(scene.lights(), static_cast<size_t>(ls.pick), p, ls.wi,
                                     panes_crossed)
                  : -1;
          if (group >= 0) {
            const auto g = static_cast<size_t>(group);
            // the light's pick at y: a sun sample's pdf is pick / solid angle, a lamp's is pick
            const float pick = photons->groups[g].lamp >= 0 ? ls.pdf : ls.pdf * photons->solid_angle;
            const float d_xy = straight + t;  // x to y, straight through any panes
            const float p_b = prev_bsdf_pdf * std::fabs(cos_emit) / (d_xy * d_xy) * pick;
            const float p_c = photons->groupWeight(g, prev_p) / prev_group_total *
                              photons->density(g, p, std::fabs(ng.dot(ls.wi)));
            // the lobes the photon connection evaluates at y (see its f_y)
            const Vec3f f_shared = lambert || photons->groups[g].lamp >= 0
                                       ? f_cos
                                       : evalBsdfDiffuse(bsdf, wo, frame.toLocal(ls.wi));
            f_weighted -= f_shared * (w * (1.f - powerHeuristic(p_b, p_c)));
          }
          L += throughput.cwiseProduct(f_weighted.cwiseProduct(ls.radiance).cwiseProduct(through)) /
               ls.pdf;
          if (splitting) {
            const Vec3f f_diffuse =
                lambert ? f_cos : evalBsdfDiffuse(bsdf, wo, frame.toLocal(ls.wi));
            diffuse += throughput.cwiseProduct(
                           f_diffuse.cwiseProduct(ls.radiance).cwiseProduct(through)) *
                       (w / ls.pdf);
          }
        }
      }
    }
    if (caching.train && ls.pick >= 0)
      caching.train->record(at.p, scene.lights().cacheSlot(static_cast<size_t>(ls.pick)),
                            trained_through);
    if (photons && !isDelta(bsdf) && bounce + 1 < ctx.options.max_bounces) {
      // connect to one photon (Photons): a group by its weight here, a photon of it
      // uniformly; the path x -> y -> light
      const Eigen::Vector2f u_photon = smp.get2D();
      const float total = photons->groupTotal(p);
      group_total = total;  // the MIS density at the next vertex reads it
      size_t group = 0;
      float acc = 0.f, w_group = 0.f;
      for (const float target = u_photon.x() * total; group < photons->groups.size(); ++group) {
        acc += (w_group = photons->groupWeight(group, p));
        if (target < acc) break;
      }
      if (group == photons->groups.size()) group = photons->groups.size() - 1;
      while (w_group == 0.f && group > 0) w_group = photons->groupWeight(--group, p);
      const Photons::Group& gr = photons->groups[group];
      const size_t k = std::min(
          static_cast<size_t>(u_photon.y() * static_cast<float>(gr.count)), gr.count - 1);
      const Photon& ph = photons->photons[gr.first + k];
      const Vec3f o = lambert ? p_face : offset(ph.p - p);
      Vec3f w = ph.p - o;
      const float dist = w.norm();
      const Vec3f& ng_y = ph.sp.ng;
      const float cos_y = dist > 0.f ? -ng_y.dot(w) / dist : 0.f;  // cos_emit at y
      if (std::fabs(cos_y) > 1e-4f) {
        w /= dist;
        // at x, as for a light sample
        Vec3f f_x = Vec3f::Zero();
        float pdf_x = 0.f;
        if (lambert) {
          if (n_face.dot(w) > 0.f) {
            const float cos_s = std::max(0.f, ns_face.dot(w));
            f_x = sp.albedo * (cos_s / kPi);
            pdf_x = cos_s / kPi;
          }
        } else {
          const Vec3f wl = frame.toLocal(w);
          if (consistent(w, wl.z())) {
            const BsdfEval e = evalBsdfPdf(bsdf, wo, wl);
            f_x = e.value;
            pdf_x = e.pdf;
          }
        }
        // at y, as radiance() would evaluate its sun sample arriving from x
        Vec3f f_y = Vec3f::Zero();
        float pdf_y = 0.f;
        const BsdfParams& by = ph.sp.bsdf;
        if (f_x.maxCoeff() > 0.f) {
          if (by.type == BsdfType::Lambertian) {
            const Vec3f nf = cos_y > 0.f ? ng_y : Vec3f(-ng_y);
            const Vec3f nsf = cos_y > 0.f ? ph.sp.ns : Vec3f(-ph.sp.ns);
            if (nf.dot(ph.to_light) > 0.f) {
              const float cos_s = std::max(0.f, nsf.dot(ph.to_light));
              f_y = ph.sp.albedo * (cos_s / kPi);
              pdf_y = cos_s / kPi;
            }
          } else {
            const Frame3 fy = Frame3::fromNormal(ph.sp.ns);
            const Vec3f wo_y = fy.toLocal(-w), wi_y = fy.toLocal(ph.to_light);
            if (((ng_y.dot(ph.to_light) > 0.f) == (cos_y > 0.f)) ==
                ((wi_y.z() > 0.f) == (wo_y.z() > 0.f))) {
              // the sun's: the diffuse lobes only, as a glossy reflection of the sun is a
              // caustic, which a uniformly picked photon finds no better than the BSDF sample
              // at x (which can go on to hit the sun); a lamp's: every lobe, as its glossy
              // reflection near the lamp (a fixture's polished parts) is found otherwise by
              // next-event estimation after a BSDF sample happened to hit them
              const BsdfEval e = evalBsdfPdf(by, wo_y, wi_y);
              f_y = gr.lamp >= 0 ? e.value : evalBsdfDiffuse(by, wo_y, wi_y);
              pdf_y = e.pdf;
            }
          }
        }
        if (f_y.maxCoeff() > 0.f) {
          const float g = std::fabs(cos_y) / (dist * dist);
          const float tmax = (dist - 4.f * offsetScale(ph.p)) * (1.f - 1e-4f);
          ++rays;
          // straight through any panes between x and y, as the path tracer's BSDF sample
          const Vec3f T_xy =
              tmax > 0.f ? shadowTransmittance(scene, o, w, tmax, ray.time) : Vec3f::Zero();
          if (T_xy.maxCoeff() > 0.f) {
            const float p_b = pdf_x * g * ph.light_pick;
            const float p_c = w_group / total * ph.density;
            // (a), a BSDF sample at y hitting the light, exists for the sun only
            const float mis_y =
                gr.lamp >= 0 ? 1.f : powerHeuristic(ph.light_pick / photons->solid_angle, pdf_y);
            const float weight = mis_y * powerHeuristic(p_c, p_b) * g / p_c;
            const Vec3f light = f_y.cwiseProduct(ph.incident).cwiseProduct(T_xy) * weight;
            L += throughput.cwiseProduct(f_x.cwiseProduct(light));
            if (splitting) {
              const Vec3f f_diffuse = lambert ? f_x : evalBsdfDiffuse(bsdf, wo, frame.toLocal(w));
              diffuse += throughput.cwiseProduct(f_diffuse.cwiseProduct(light));
            }
          }
        }
      }
    }
    // continue the path by sampling the BSDF
    Vec3f wi;
    if (lambert) {
      wi = cosineHemisphere(ns_face, u_bsdf.x(), u_bsdf.y());
      if (n_face.dot(wi) <= 0.f) break;  // below the geometric surface (shading normal)
      prev_bsdf_pdf = std::max(ns_face.dot(wi), 0.f) / kPi;
      if (prev_bsdf_pdf <= 0.f) break;
      if (splitting) share = Vec3f::Ones();
      ++rough;
      cone_spread = std::max(cone_spread, kIndirectConeSpread);
      no_mis = false;
      straight = 0.f;
      light_at = at;
      prev_p = p;
      prev_group_total = group_total;
      throughput = throughput.cwiseProduct(sp.albedo);
    } else {
      const float u_lobe = smp.get1D();
      std::optional<BsdfSample> bs = sampleBsdf(bsdf, wo, u_lobe, u_bsdf);
      if (panes_split && bounce == 0 && bsdf.type == BsdfType::ThinDielectric &&
          panes_split->met < panes_split->forced) {
        // a pane on the camera's line, split (PaneSplit): this path's lobe, its full weight
        const Vec3f T = thinDielectricTransmission(bsdf, wo.z());
        const Vec3f R = bsdf.specular_tint * thinDielectricReflectance(bsdf, wo.z());
        float share = 1.f;  // of this lobe, when the path picked it (kEitherFace)
        if (panes_split->reflect_at == kEitherFace) {
          const float q = 1.f / (1.f + luminance(T));
          const bool here = u_lobe < q;
          share = here ? q : 1.f - q;
          panes_split->reflect_at = here ? 0 : 1;
        }
        const bool transmit = panes_split->met++ != panes_split->reflect_at;
        bs = BsdfSample{transmit ? Vec3f(-wo) : Vec3f(-wo.x(), -wo.y(), wo.z()),
                        (transmit ? T : R) / share, 1.f, true, transmit};
      }
      if (!bs || bs->pdf <= 0.f) break;
      wi = frame.toWorld(bs->wi).normalized();
      if (!consistent(wi, bs->wi.z())) break;
      if (splitting && !bs->delta) {
        const Vec3f f = evalBsdf(bsdf, wo, bs->wi), f_diffuse = evalBsdfDiffuse(bsdf, wo, bs->wi);
        for (int c = 0; c < 3; ++c) share[c] = f[c] > 0.f ? std::min(1.f, f_diffuse[c] / f[c]) : 0.f;
      }
      if (bsdf.type == BsdfType::ThinDielectric && bs->transmission && panes < kMaxPanes) {
        // (not on a split path that reflects at a later face: that light is the room's,
        // reflected on the pane, as the front face's is)
        if (bounce == 0 && !through_pane && !(panes_split && panes_split->reflect_at >= 0)) {
          through_pane = true;
          L_before_pane = L;
        }
        straight += t;  // through the pane: the MIS state of the vertex before it stays, and
        ++panes;        // it is not a bounce (a window does not shorten the path)
        --bounce;
      } else {
        prev_bsdf_pdf = bs->pdf;
        if (!bs->delta) {
          cone_spread = std::max(cone_spread, lobeSpread(bsdf));
          ++rough;
        }
        no_mis = bs->delta;
        straight = 0.f;
        light_at = at;
        prev_p = p;
        prev_group_total = group_total;
      }
      throughput = throughput.cwiseProduct(bs->weight);
    }
    if (splitting) {
      splitting = false;
      L_at_first = L;
    }
    if (throughput.maxCoeff() <= 0.f) break;
    // Russian roulette from the third bounce on. Survival probability sqrt(max throughput)
    // rather than the throughput itself: fewer paths die young, so less variance for the
    // same time (measured on ../shared/bench at 16 spp: efficiency 1/(MSE x s) +12%).
    if (bounce >= 3) {
      float q = std::min(0.95f, std::sqrt(throughput.maxCoeff()));
      if (u_select_rr.y() >= q) break;
      throughput /= q;
    }
    ray = Ray{offset(wi), wi, ray.time};
  }
  if (recorded) {
    Vec3f sent = Vec3f::Zero();
    for (int c = 0; c < 3; ++c)
      if (recorded->factor[c] > 0.f) sent[c] = (L[c] - recorded->L[c]) / recorded->factor[c];
    caching.record->record(recorded->p, recorded->n, recorded->kind, sent);
  }
  if (first_surface) first_surface->diffuse = diffuse + share.cwiseProduct(L - L_at_first);
  if (through_pane) seen_emission = L - L_before_pane;
  if (window) *window = through_pane ? beyond : WindowHit{};
  return L;
}

}  // namespace

std::unique_ptr<Integrator> makePathTracer() {
  return std::make_unique<PathTracer>();
}

}  // namespace inet
