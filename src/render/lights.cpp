#include "render/lights.h"

#include "core/color.h"
#include "render/bsdf.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace inet {
namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Share of a sky's samples that go through the portals where some portal faces the receiver.
constexpr float kPortalShare = 0.5f;


float smoothstep(float a, float b, float x) {
  if (a >= b) return x >= b ? 1.f : 0.f;
  float t = std::clamp((x - a) / (b - a), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);
}

}  // namespace

SceneLights::SceneLights(const Scene& scene, std::vector<EmissiveTriangle> triangles,
                         std::vector<PortalTriangle> portals)
    : triangles_(std::move(triangles)) {
  for (PortalTriangle& t : portals)
    if (t.area > 0.f) portals_.push_back(t);
  triangle_in_group_.resize(triangles_.size());
  group_of_.assign(triangles_.size(), -1);
  for (size_t i = 0; i < triangles_.size();) {
    Group g;
    g.first = i;
    Eigen::AlignedBox3f box;
    double power = 0.0;
    std::vector<double> acc;
    for (; i < triangles_.size() && triangles_[i].group == triangles_[g.first].group; ++i) {
      const EmissiveTriangle& t = triangles_[i];
      box.extend(t.p0);
      box.extend(Vec3f(t.p0 + t.e1));
      box.extend(Vec3f(t.p0 + t.e2));
      power += static_cast<double>(t.area) * kPi * luminance(t.radiance);
      acc.push_back(power);
    }
    g.count = i - g.first;
    if (!(power > 0.0)) continue;  // nothing to pick (a black or degenerate emitter)
    g.centre = box.center();
    g.radius2 = std::max(0.25f * box.sizes().squaredNorm(), 1e-6f);
    g.power = static_cast<float>(power);
    for (size_t k = 0; k < g.count; ++k) {
      g.cdf.push_back(static_cast<float>(acc[k] / power));
      const double prev = k ? acc[k - 1] : 0.0;
      triangle_in_group_[g.first + k] = static_cast<float>((acc[k] - prev) / power);
      group_of_[g.first + k] = static_cast<int>(groups_.size());
    }
    g.cdf.back() = 1.f;
    groups_.push_back(std::move(g));
  }
  for (const Light& l : scene.lights) {
    if (!l.on || l.intensity <= 0.f) continue;
    Analytic a;
    a.type = l.type;
    a.position = l.position.cast<float>();
    a.direction = l.direction.normalized().cast<float>();
    a.rgb = l.rgbIntensity();
    a.max_distance = l.max_distance;
    a.radius2 = l.radius * l.radius;
    // Suns: their irradiance; skies: the integral of their luminance over the directions they
    // shine from (an upper bound on the irradiance they give, within a factor 4 for a uniform
    // sky); the same weights relative to each other as the global pick had.
    float irradiance = 0.f;
    if (l.type == LightType::Spot) {
      a.cos_outer = std::cos(l.cone_deg * kPi / 180.f);
      a.cos_inner = std::cos((l.cone_deg - l.falloff_deg) * kPi / 180.f);
    } else if (l.type == LightType::Sky && l.sky_model == SkyModel::Preetham) {
      a.sky = static_cast<int>(skies_.size());
      skies_.emplace_back(l);
      irradiance = static_cast<float>(skies_.back().luminanceIntegral());
    } else if (l.type == LightType::Sky && l.sky_model == SkyModel::EnvMap) {
      a.envmap = static_cast<int>(envmaps_.size());
      envmaps_.emplace_back(l, l.envmap.path);
      irradiance = static_cast<float>(envmaps_.back().luminanceIntegral());
    } else if (l.type == LightType::Sky) {
      irradiance = 4.f * kPi * luminance(a.rgb);  // int L dw over the sphere, as the others
    } else if (l.type == LightType::Sun) {
      float half = 0.5f * l.angular_diameter_deg * kPi / 180.f;
      a.cos_max = std::cos(half);
      a.one_minus_cos_max = static_cast<float>(2.0 * std::pow(std::sin(0.5 * double(half)), 2));
      // a disk of uniform radiance L gives irradiance E = L * pi * sin^2(half) at normal incidence
      a.radiance_scale = 1.f / (kPi * std::sin(half) * std::sin(half));
      irradiance = luminance(a.rgb);
    }
    if (a.type == LightType::Sun || a.type == LightType::Sky)
      environment_.push_back(analytic_.size());
    analytic_.push_back(a);
    env_importance_.push_back(irradiance);
  }
}

float SceneLights::importance(size_t k, const Vec3f& p) const {
  if (k < groups_.size()) {
    const Group& g = groups_[k];
    return g.power / std::max((g.centre - p).squaredNorm(), g.radius2);
  }
  k -= groups_.size();
  const Analytic& a = analytic_[k];
  if (a.type != LightType::Point && a.type != LightType::Spot) return env_importance_[k];
  const Vec3f w = a.position - p;
  const float dist2 = w.squaredNorm();
  if (a.max_distance > 0.f && dist2 > a.max_distance * a.max_distance) return 0.f;
  float falloff = 1.f;
  if (a.type == LightType::Spot) {
    const float dist = std::sqrt(dist2);
    falloff = dist > 0.f ? smoothstep(a.cos_outer, a.cos_inner, a.direction.dot(-w / dist)) : 0.f;
  }
  // 1 cm: closer than that the estimate stops growing (a lamp's own socket)
  return luminance(a.rgb) * falloff / std::max(dist2 + a.radius2, 1e-4f);
}

SceneLights::PickPoint SceneLights::pickAt(const Vec3f& p, const LightCache* cache) const {
  PickPoint at;
  at.p = p;
  const size_t n = pickCount();
  at.cached = static_cast<int>(std::min<size_t>(n, PickPoint::kCached));
  const float* factors = cache ? cache->factors(p) : nullptr;
  for (size_t k = 0; k < n; ++k) {
    float w = importance(k, p);
    const int slot = cacheSlot(k);
    if (slot < at.cached) {
      if (factors) w *= factors[slot];
      at.importance[slot] = w;
    }
    at.total += w;
  }
  return at;
}

float SceneLights::pickProbability(const Vec3f& p, size_t k) const {
  const PickPoint at = pickAt(p);
  return at.total > 0.f ? importance(k, p) / at.total : 0.f;
}

bool SceneLights::sample(const PickPoint& at, float u_pick, const Eigen::Vector2f& u,
                         LightSample& out) const {
  const size_t n = pickCount();
  if (n == 0 || !(at.total > 0.f)) return false;
  // A linear scan, summing the importances in pickAt's order so that the last running sum is
  // at.total exactly (a handful to a few hundred lights per scene; a light tree would make
  // this logarithmic for thousands).
  const Vec3f& p = at.p;
  const float target = u_pick * at.total;
  size_t k = 0;
  float w = 0.f;
  for (float acc = 0.f; k < n; ++k) {
    acc += (w = importance(k, at));
    if (target < acc) break;
  }
  if (k == n) k = n - 1;  // u_pick rounding up to the total
  while (w == 0.f && k > 0) w = importance(--k, at);  // never a light that cannot light p
  const float pmf = w / at.total;
  out.pick = static_cast<int>(k);
  if (k >= groups_.size()) {
    if (!sampleAnalytic(analytic_[k - groups_.size()], p, u, out)) return false;
    out.pdf *= pmf;
    return true;
  }
  const Group& g = groups_[k];
  // the triangle by power within the group, reusing u.x (rescaled) for the choice
  float ux = u.x();
  size_t j = static_cast<size_t>(std::upper_bound(g.cdf.begin(), g.cdf.end(), ux) - g.cdf.begin());
  j = std::min(j, g.count - 1);
  const float lo = j ? g.cdf[j - 1] : 0.f, width = g.cdf[j] - lo;
  ux = width > 0.f ? std::clamp((ux - lo) / width, 0.f, 0.99999994f) : 0.5f;
  const size_t i = g.first + j;
  const EmissiveTriangle& e = triangles_[i];
  Vec3f q = e.point({ux, u.y()});
  Vec3f wq = q - p;
  float dist2 = wq.squaredNorm();
  if (dist2 <= 0.f) return false;
  out.dist = std::sqrt(dist2);
  out.wi = wq / out.dist;
  float cos_l = -e.normal.dot(out.wi);
  if (cos_l <= 0.f) return false;  // one-sided emitter seen from behind
  out.radiance = e.radiance;
  out.pdf = pmf * triangle_in_group_[i] / e.area * dist2 / cos_l;
  out.delta = false;
  return true;
}

bool SceneLights::sampleOwnSky(const Analytic& a, const Eigen::Vector2f& u, Vec3f& d,
                               Vec3f& radiance, float& pdf) const {
  if (a.envmap >= 0) return envmaps_[a.envmap].sample(u, d, radiance, pdf);
  if (a.sky >= 0) return skies_[a.sky].sample(u, d, radiance, pdf);
  // uniform direction on the sphere
  const float z = 1.f - 2.f * u.x(), r = std::sqrt(std::max(0.f, 1.f - z * z));
  const float phi = 2.f * kPi * u.y();
  d = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
  radiance = a.rgb;
  pdf = 1.f / (4.f * kPi);
  return true;
}

bool SceneLights::sampleAnalytic(const Analytic& a, const Vec3f& p, const Eigen::Vector2f& u,
                                 LightSample& out) const {
  if (a.type == LightType::Sky) {
    out.dist = std::numeric_limits<float>::infinity();
    out.delta = false;
    // the portals' weights at p, kept (up to kKeptPortals) for the pick below
    constexpr size_t kKeptPortals = 64;
    float kept[kKeptPortals];
    const float portal_w = portals_.empty() ? 0.f : portalWeight(p, kept, kKeptPortals);
    if (!(portal_w > 0.f)) return sampleOwnSky(a, u, out.wi, out.radiance, out.pdf);
    // the mixture of the sky's own table and the portals (see lights.h)
    const float ux = u.x();
    if (ux < kPortalShare) {
      // a portal triangle by its weight at p, ux rescaled within its share for the point
      const float target = ux / kPortalShare * portal_w;
      size_t i = 0;
      float acc = 0.f, w = 0.f;
      for (; i < portals_.size(); ++i) {
        acc += (w = i < kKeptPortals ? kept[i] : portalPick(i, p));
        if (target < acc) break;
      }
      if (i == portals_.size()) i = portals_.size() - 1;
      const float v = w > 0.f ? std::clamp((target - (acc - w)) / w, 0.f, 0.99999994f) : 0.5f;
      const Vec3f wq = portals_[i].point({v, u.y()}) - p;
      const float len = wq.norm();
      if (!(len > 0.f)) return false;
      out.wi = wq / len;
    } else {
      const Eigen::Vector2f uu(
          std::min((ux - kPortalShare) / (1.f - kPortalShare), 0.99999994f), u.y());
      Vec3f radiance;
      float own_pdf;
      if (!sampleOwnSky(a, uu, out.wi, radiance, own_pdf)) return false;
    }
    out.radiance = skyRadiance(a, out.wi);
    out.pdf = (1.f - kPortalShare) * ownSkyPdf(a, out.wi) +
              kPortalShare * portalPdf(p, out.wi, portal_w);
    return out.pdf > 0.f && out.radiance.maxCoeff() > 0.f;
  }
  if (a.type == LightType::Sun) {
    SunView sun;
    sun.to_sun = -a.direction;
    sun.one_minus_cos_max = a.one_minus_cos_max;
    out.wi = sun.direction(u);
    out.dist = std::numeric_limits<float>::infinity();
    out.radiance = a.rgb * a.radiance_scale;
    out.pdf = 1.f / (2.f * kPi * a.one_minus_cos_max);
    out.delta = false;
    return true;
  }
  Vec3f w = a.position - p;
  float dist2 = w.squaredNorm();
  if (dist2 <= 0.f) return false;
  out.dist = std::sqrt(dist2);
  if (a.max_distance > 0.f && out.dist > a.max_distance) return false;
  out.wi = w / out.dist;
  float falloff = 1.f;
  if (a.type == LightType::Spot) {
    falloff = smoothstep(a.cos_outer, a.cos_inner, a.direction.dot(-out.wi));
    if (falloff <= 0.f) return false;
  }
  // a bulb of radius r: I / (d^2 + r^2), a disk of radius r facing p (Light::radius)
  out.radiance = a.rgb * (falloff / (dist2 + a.radius2));
  out.pdf = 1.f;
  out.delta = true;
  return true;
}

Vec3f SceneLights::SunView::direction(const Eigen::Vector2f& u) const {
  // uniform inside the cone of the disk, around to_sun
  const float cos_t = 1.f - u.x() * one_minus_cos_max;
  const float sin_t = std::sqrt(std::max(0.f, 1.f - cos_t * cos_t));
  const float phi = 2.f * kPi * u.y();
  const Frame3 f = Frame3::fromNormal(to_sun);
  return (f.s * (sin_t * std::cos(phi)) + f.t * (sin_t * std::sin(phi)) + to_sun * cos_t)
      .normalized();
}

float SceneLights::LampView::falloff(const Vec3f& d) const {
  return spot ? smoothstep(cos_outer, cos_inner, direction.dot(d)) : 1.f;
}

std::vector<SceneLights::LampView> SceneLights::lamps() const {
  std::vector<LampView> out;
  for (size_t i = 0; i < analytic_.size(); ++i) {
    const Analytic& a = analytic_[i];
    if (a.type != LightType::Point && a.type != LightType::Spot) continue;
    LampView v;
    v.pick = groups_.size() + i;
    v.position = a.position;
    v.direction = a.direction;
    v.rgb = a.rgb;
    v.spot = a.type == LightType::Spot;
    v.cos_outer = a.cos_outer;
    v.cos_inner = a.cos_inner;
    v.max_distance = a.max_distance;
    v.radius2 = a.radius2;
    out.push_back(v);
  }
  return out;
}

std::optional<SceneLights::SunView> SceneLights::firstSun() const {
  for (size_t i = 0; i < analytic_.size(); ++i) {
    const Analytic& a = analytic_[i];
    if (a.type != LightType::Sun) continue;
    SunView v;
    v.pick = groups_.size() + i;
    v.to_sun = -a.direction;
    v.one_minus_cos_max = a.one_minus_cos_max;
    v.radiance = a.rgb * a.radiance_scale;
    return v;
  }
  return std::nullopt;
}

float SceneLights::trianglePdf(size_t i, const PickPoint& at, float dist, float cos_light) const {
  const int k = group_of_[i];
  if (cos_light <= 0.f || k < 0 || !(at.total > 0.f)) return 0.f;
  const float pick = importance(static_cast<size_t>(k), at) / at.total;
  return pick * triangle_in_group_[i] / triangles_[i].area * dist * dist / cos_light;
}

Vec3f SceneLights::environmentRadiance(const Vec3f& d, const PickPoint* at, float& pdf) const {
  Vec3f L = Vec3f::Zero();
  pdf = 0.f;
  const float total = at ? at->total : 0.f;
  // the pick probability of analytic light k at p (0 when no receiver is given)
  auto pmf = [&](size_t k) {
    return total > 0.f ? importance(groups_.size() + k, *at) / total : 0.f;
  };
  for (size_t k : environment_) {  // not every analytic light: this runs for every escaped ray
    const Analytic& a = analytic_[k];
    if (a.type == LightType::Sky && !portals_.empty()) {
      L += skyRadiance(a, d);
      if (total > 0.f) pdf += pmf(k) * mixturePdf(a, at->p, d);
      continue;
    }
    if (a.envmap >= 0) {
      const EnvMapSkyLight& map = envmaps_[a.envmap];
      L += map.radiance(d);
      pdf += pmf(k) * map.pdf(d);
      continue;
    }
    if (a.sky >= 0) {
      const PreethamSkyLight& sky = skies_[a.sky];
      L += sky.radiance(d);
      pdf += pmf(k) * sky.pdf(d);
      continue;
    }
    if (a.type == LightType::Sky) {
      L += a.rgb;
      pdf += pmf(k) / (4.f * kPi);
      continue;
    }
    if (-a.direction.dot(d) < a.cos_max) continue;  // outside this sun's disk
    L += a.rgb * a.radiance_scale;
    pdf += pmf(k) / (2.f * kPi * a.one_minus_cos_max);
  }
  return L;
}

Vec3f SceneLights::skyRadiance(const Analytic& a, const Vec3f& d) const {
  if (a.envmap >= 0) return envmaps_[a.envmap].radiance(d);
  if (a.sky >= 0) return skies_[a.sky].radiance(d);
  return a.rgb;
}

float SceneLights::ownSkyPdf(const Analytic& a, const Vec3f& d) const {
  if (a.envmap >= 0) return envmaps_[a.envmap].pdf(d);
  if (a.sky >= 0) return skies_[a.sky].pdf(d);
  return 1.f / (4.f * kPi);
}

float SceneLights::portalPick(size_t i, const Vec3f& p) const {
  // the solid angle the triangle roughly subtends at p (its area seen from its centroid),
  // bounded where p comes within the triangle's own size
  const PortalTriangle& t = portals_[i];
  const Vec3f w = t.p0 + (t.e1 + t.e2) * (1.f / 3.f) - p;
  const float d2 = w.squaredNorm();
  if (!(d2 > 0.f)) return 0.f;
  // a receiver on the sky's side (the ground outside, a facade) sees the sky itself: directions
  // through the window would lead it into the building
  if (t.normal.dot(w) >= 0.f) return 0.f;
  const float cos = -t.normal.dot(w) / std::sqrt(d2);
  return t.area * cos / std::max(d2, t.area);
}

float SceneLights::portalWeight(const Vec3f& p, float* kept, size_t kept_count) const {
  float w = 0.f;
  for (size_t i = 0; i < portals_.size(); ++i) {
    const float wi = portalPick(i, p);
    if (i < kept_count) kept[i] = wi;
    w += wi;
  }
  return w;
}

float SceneLights::portalPdf(const Vec3f& p, const Vec3f& d, float w) const {
  // every portal triangle the ray p + t d (t > 0) crosses: the pdf of having
  // chosen that point on it, as a solid angle density
  float pdf = 0.f;
  for (size_t i = 0; i < portals_.size(); ++i) {
    const PortalTriangle& t = portals_[i];
    const float dist = t.crossing(p, d);
    if (!(dist > 0.f)) continue;
    const float cos = std::abs(t.normal.dot(d));
    if (!(cos > 0.f)) continue;
    pdf += portalPick(i, p) / w * dist * dist / (t.area * cos);
  }
  return pdf;
}

float SceneLights::mixturePdf(const Analytic& a, const Vec3f& p, const Vec3f& d) const {
  const float w = portals_.empty() ? 0.f : portalWeight(p);
  if (!(w > 0.f)) return ownSkyPdf(a, d);
  return (1.f - kPortalShare) * ownSkyPdf(a, d) + kPortalShare * portalPdf(p, d, w);
}

float SceneLights::skyPdf(size_t analytic_index, const Vec3f& p, const Vec3f& d) const {
  return mixturePdf(analytic_[analytic_index], p, d);
}

}  // namespace inet
