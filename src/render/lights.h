#pragma once
// Light sampling for next-event estimation: every light of the scene in one list (emissive
// objects, point, spot, sun and sky lights), one picked per sample, so that 50+ lights cost one
// shadow ray, not one per light. The pick depends on the receiver p: each light's probability
// is proportional to the irradiance it could give p if nothing were in the way (intensity x
// spot falloff / d^2 for point and spot lights, power / d^2 for an emissive object, clamped
// inside its bounds; the irradiance of a sun or sky facing it). A global power-proportional
// pick (what this replaces) gave a ceiling spot of 8 W a probability of about 3e-6 next to a
// sun "lighting" the whole scene's cross-section (350 W/m^2 over a 42 m bounding sphere: 2 MW):
// the lamp's light on nearby surfaces came from one sample in some 300,000, each as many times
// too bright, the speckle of an apartment frame.
// Within an emissive object a triangle is picked by its power.
// A uniform sky is sampled uniformly on the sphere; a Preetham sky from a table of its luminance
// over the upper hemisphere, an environment map from a table of its texels' luminance over the
// sphere (sky.h), each with the same pdf for escaped rays (environmentRadiance).
// Sky portals: indoors, nearly every direction those tables choose ends on a wall; the sky is
// seen only through the windows. When the scene has windows (the faces of thin dielectrics that
// see the sky from an enclosed inside, embree_scene.cpp), half of a sky's samples for a receiver
// inside go through them instead: a window triangle picked by the solid angle it roughly
// subtends there (area x |cos| / d^2), a uniform point on it, the direction to it. The sky's pdf
// is the mixture of both strategies, p = (1 - s) p_sky(d) + s p_portal(d | receiver), with
// p_portal summed over the window triangles the ray crosses (dist^2 / (area |cos|) each, times
// its pick probability), in `sample` and for escaped rays alike, so the estimate stays unbiased
// whatever the windows (s = 1/2 for a receiver on the inside of some window, else 0).
// Suns are not sampled through portals: their cone is already tiny.
//
// Conventions: `sample` returns the radiance arriving at p from the chosen point and the pdf of
// choosing it (light pick x solid-angle pdf). Delta lights (point, spot) have no solid-angle pdf:
// their `pdf` is the pick probability alone and `delta` is set, so the integrator skips MIS.
#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

#include "render/light_cache.h"
#include "render/sky.h"
#include "scene/scene.h"

namespace inet {

/// A triangle in world space.
struct WorldTriangle {
  Vec3f p0, e1, e2;  ///< vertex and edges
  Vec3f normal;      ///< unit geometric normal
  float area = 0.f;

  /// The uniformly distributed point of u in [0,1)^2 (u.x through its square root).
  Vec3f point(const Eigen::Vector2f& u) const {
    const float su = std::sqrt(u.x());
    return p0 + e1 * (1.f - su) + e2 * (su * u.y());
  }
  /// The distance t > 0 at which the ray o + t d crosses the triangle, or 0 when it does not
  /// (Moller-Trumbore).
  float crossing(const Vec3f& o, const Vec3f& d) const {
    const Vec3f h = d.cross(e2);
    const float det = e1.dot(h);
    if (std::abs(det) < 1e-12f) return 0.f;
    const float inv = 1.f / det;
    const Vec3f s = o - p0;
    const float b1 = s.dot(h) * inv;
    if (b1 < 0.f || b1 > 1.f) return 0.f;
    const Vec3f q = s.cross(e1);
    const float b2 = d.dot(q) * inv;
    if (b2 < 0.f || b1 + b2 > 1.f) return 0.f;
    const float t = e2.dot(q) * inv;
    return t > 0.f ? t : 0.f;
  }
};

/// An emissive triangle (one-sided: emits along `normal`).
struct EmissiveTriangle : WorldTriangle {
  Vec3f radiance;
  int group = 0;  ///< the emissive object it belongs to (consecutive triangles share it)
};

/// A triangle of a window pane, through which skies are also sampled (see above); its normal
/// faces the inside: receivers on its other side (outdoors) do not sample through it.
using PortalTriangle = WorldTriangle;

struct LightSample {
  Vec3f wi;          ///< unit direction from p toward the light
  float dist = 0.f;  ///< distance to the sampled point (infinity for the sun)
  Vec3f radiance;    ///< incident radiance (area, sun) or intensity / dist^2 (point, spot)
  float pdf = 0.f;   ///< pick probability x solid-angle pdf (pick probability alone if delta)
  bool delta = false;
  int pick = -1;     ///< the pick entry chosen (SceneLights::cacheSlot maps it for LightCache)
};

class SceneLights {
 public:
  /// Collects the lights that are on; `portals` are the window panes skies are also sampled
  /// through (none: skies use their own tables alone).
  SceneLights(const Scene& scene, std::vector<EmissiveTriangle> triangles,
              std::vector<PortalTriangle> portals = {});

  bool empty() const { return groups_.empty() && analytic_.empty(); }
  size_t triangleCount() const { return triangles_.size(); }
  const EmissiveTriangle& triangle(size_t i) const { return triangles_[i]; }

  /// A receiver and the sum of every light's importance there: computed once per path vertex
  /// (pickAt), used by `sample` and, at the next vertex, by the MIS pdfs of what the BSDF
  /// sample hit.
  struct PickPoint {
    Vec3f p = Vec3f::Zero();
    float total = 0.f;
    /// The importances at p of the pick entries whose cacheSlot is below `cached`, by slot, as
    /// pickAt summed them (times their LightCache factor when it had a cache): `sample` and
    /// the MIS pdfs read them instead of evaluating each light again.
    static constexpr int kCached = LightCache::kLights;
    int cached = 0;
    float importance[kCached];
  };
  /// `cache`, when given, weighs each light's estimate by the share of it that gets through
  /// around p (light_cache.h); the pdfs of `sample`, `trianglePdf` and `environmentRadiance`
  /// follow from the pick point, so they agree.
  PickPoint pickAt(const Vec3f& p, const LightCache* cache = nullptr) const;
  /// Where LightCache and PickPoint keep pick entry k: the analytic lights (suns, skies, lamps'
  /// point and spot lights) first, as they are few and the sun is the one whose estimate is
  /// most often wrong indoors, then the emissive objects.
  int cacheSlot(size_t k) const {
    return k >= groups_.size() ? static_cast<int>(k - groups_.size())
                               : static_cast<int>(analytic_.size() + k);
  }

  /// Samples one light for a receiver; u_pick picks the light, u the point on it.
  /// Returns false when the sample carries nothing (back side, outside a spot cone or range).
  bool sample(const PickPoint& at, float u_pick, const Eigen::Vector2f& u,
              LightSample& out) const;
  /// pdf (pick x solid angle) with which `sample` for the receiver `at` would choose the point
  /// of triangle i seen at distance dist with cosine cos_light between its normal and the
  /// direction to the receiver.
  float trianglePdf(size_t i, const PickPoint& at, float dist, float cos_light) const;
  /// Radiance arriving from infinity along unit direction d (suns whose disk covers d, plus the
  /// sky), and (when `at` is given) the pdf with which `sample` for that receiver would have
  /// chosen that direction (0 otherwise).
  Vec3f environmentRadiance(const Vec3f& d, const PickPoint* at, float& pdf) const;
  /// Probability that `sample` for a receiver at p picks light `k` (emissive objects first,
  /// then the analytic lights in scene order, those that are on), for tests.
  float pickProbability(const Vec3f& p, size_t k) const;
  /// The same at a pick point (with its LightCache factors, when it had a cache).
  float pickProbability(const PickPoint& at, size_t k) const {
    return at.total > 0.f ? importance(k, at) / at.total : 0.f;
  }
  size_t pickCount() const { return groups_.size() + analytic_.size(); }
  size_t portalCount() const { return portals_.size(); }
  const PortalTriangle& portal(size_t i) const { return portals_[i]; }

  /// A sun as `sample` sees it: its pick entry, the unit direction toward it, the cone of its
  /// disk (solid angle 2 pi one_minus_cos_max) and its radiance.
  struct SunView {
    size_t pick = 0;
    Vec3f to_sun = Vec3f::UnitZ();
    float one_minus_cos_max = 0.f;
    Vec3f radiance = Vec3f::Zero();
    float solidAngle() const { return 2.f * 3.14159265358979323846f * one_minus_cos_max; }
    /// A uniform direction toward the disk for u in [0,1)^2 (what `sample` draws).
    Vec3f direction(const Eigen::Vector2f& u) const;
  };
  /// The first sun that is on, if any.
  std::optional<SunView> firstSun() const;
  /// A point or spot light as `sample` sees it: its pick entry, position, intensity (W/sr)
  /// and, for a spot, its cone (sample's falloff: 1 inside cos_inner, 0 outside cos_outer).
  struct LampView {
    size_t pick = 0;
    Vec3f position = Vec3f::Zero(), direction = Vec3f::UnitZ(), rgb = Vec3f::Zero();
    bool spot = false;
    float cos_outer = -1.f, cos_inner = -1.f;
    float max_distance = 0.f;  ///< 0: unlimited
    float radius2 = 0.f;       ///< the bulb's radius squared: its light is I / (d^2 + this)
    /// The spot falloff along unit direction d from the light (1 for a point light).
    float falloff(const Vec3f& d) const;
  };
  /// The point and spot lights that are on, in pick order.
  std::vector<LampView> lamps() const;
  /// The solid-angle pdf with which a sky's sample for a receiver at p chooses direction d (the
  /// mixture above, without the light pick), for tests.
  float skyPdf(size_t analytic_index, const Vec3f& p, const Vec3f& d) const;

 private:
  struct Analytic {
    LightType type;
    Vec3f position, direction, rgb;             // rgb: intensity (W/sr) or irradiance (W/m^2)
    float cos_outer = -1.f, cos_inner = -1.f;   // spot
    float cos_max = 1.f, radiance_scale = 0.f;  // sun: cone of the disk, L = rgb * scale
    // sun: 1 - cos_max computed without cancellation (in float, 1 - cos(0.27 deg) keeps only
    // two significant digits: a 0.3% error in the disk's solid angle and so in its light)
    float one_minus_cos_max = 0.f;
    float max_distance = 0.f;
    float radius2 = 0.f;  // point, spot: the bulb's radius squared (Light::radius)
    int sky = -1;  // Preetham sky: index into skies_ (-1: a uniform sky of radiance rgb)
    int envmap = -1;  // environment-map sky: index into envmaps_
  };
  /// An emissive object: its triangles [first, first + count), picked within by power.
  struct Group {
    size_t first = 0, count = 0;
    Vec3f centre;
    float radius2 = 0.f;  // squared half diagonal of its bounds: 1/d^2 is clamped inside
    float power = 0.f;    // luminance of its flux, W
    std::vector<float> cdf;  // per triangle, by power
  };
  bool sampleAnalytic(const Analytic& a, const Vec3f& p, const Eigen::Vector2f& u,
                      LightSample& out) const;
  /// A direction from a sky's own table (uniform for a uniform sky), its radiance and pdf.
  bool sampleOwnSky(const Analytic& a, const Eigen::Vector2f& u, Vec3f& d, Vec3f& radiance,
                    float& pdf) const;
  /// A sky's own radiance and solid-angle pdf (its table, or uniform) along d.
  Vec3f skyRadiance(const Analytic& a, const Vec3f& d) const;
  float ownSkyPdf(const Analytic& a, const Vec3f& d) const;
  /// Sum of the portals' pick weights at p (0: no portal faces p); the first `kept_count`
  /// weights are also written to `kept`, when given.
  float portalWeight(const Vec3f& p, float* kept = nullptr, size_t kept_count = 0) const;
  float portalPick(size_t i, const Vec3f& p) const;
  /// p_portal(d | p) given the total weight w at p (> 0).
  float portalPdf(const Vec3f& p, const Vec3f& d, float w) const;
  /// The mixture pdf of a sky along d for a receiver at p.
  float mixturePdf(const Analytic& a, const Vec3f& p, const Vec3f& d) const;
  /// Unoccluded-irradiance estimate of pick entry k (groups, then analytic) at p.
  float importance(size_t k, const Vec3f& p) const;
  /// The same at a pick point (with its LightCache factor), from its cache where it holds k.
  float importance(size_t k, const PickPoint& at) const {
    const int slot = cacheSlot(k);
    return slot < at.cached ? at.importance[slot] : importance(k, at.p);
  }

  std::vector<EmissiveTriangle> triangles_;
  std::vector<Group> groups_;
  std::vector<float> triangle_in_group_;  // per triangle: its share of its group's power
  std::vector<int> group_of_;             // per triangle: its group, -1 when of no power
  std::vector<Analytic> analytic_;  // pick entry groups_.size() + i
  std::vector<PreethamSkyLight> skies_;
  std::vector<EnvMapSkyLight> envmaps_;
  std::vector<size_t> environment_;  // indices into analytic_ of suns and skies (escaped rays)
  std::vector<float> env_importance_;  // per analytic_: the irradiance of a sun or sky (else 0)
  std::vector<PortalTriangle> portals_;
};

}  // namespace inet
