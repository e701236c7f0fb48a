#include "render/lights.h"

#include "core/color.h"
#include "render/bsdf.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace inet {
namespace {

constexpr float kPi = 3.14159265358979323846f;


float smoothstep(float a, float b, float x) {
  if (a >= b) return x >= b ? 1.f : 0.f;
  float t = std::clamp((x - a) / (b - a), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);
}

}  // namespace

SceneLights::SceneLights(const Scene& scene, std::vector<EmissiveTriangle> triangles)
    : triangles_(std::move(triangles)) {
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
  return luminance(a.rgb) * falloff / std::max(dist2, 1e-4f);
}

SceneLights::PickPoint SceneLights::pickAt(const Vec3f& p) const {
  PickPoint at{p, 0.f};
  for (size_t k = 0; k < pickCount(); ++k) at.total += importance(k, p);
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
    acc += (w = importance(k, p));
    if (target < acc) break;
  }
  if (k == n) k = n - 1;  // u_pick rounding up to the total
  while (w == 0.f && k > 0) w = importance(--k, p);  // never a light that cannot light p
  const float pmf = w / at.total;
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
  float su = std::sqrt(ux);
  Vec3f q = e.p0 + e.e1 * (1.f - su) + e.e2 * (su * u.y());
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

bool SceneLights::sampleAnalytic(const Analytic& a, const Vec3f& p, const Eigen::Vector2f& u,
                                 LightSample& out) const {
  if (a.envmap >= 0 || a.sky >= 0) {
    const bool ok = a.envmap >= 0 ? envmaps_[a.envmap].sample(u, out.wi, out.radiance, out.pdf)
                                  : skies_[a.sky].sample(u, out.wi, out.radiance, out.pdf);
    if (!ok) return false;
    out.dist = std::numeric_limits<float>::infinity();
    out.delta = false;
    return true;
  }
  if (a.type == LightType::Sky) {
    // uniform direction on the sphere
    float z = 1.f - 2.f * u.x(), r = std::sqrt(std::max(0.f, 1.f - z * z));
    float phi = 2.f * kPi * u.y();
    out.wi = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
    out.dist = std::numeric_limits<float>::infinity();
    out.radiance = a.rgb;
    out.pdf = 1.f / (4.f * kPi);
    out.delta = false;
    return true;
  }
  if (a.type == LightType::Sun) {
    // uniform direction inside the cone of the sun's disk, around -direction
    float cos_t = 1.f - u.x() * a.one_minus_cos_max;
    float sin_t = std::sqrt(std::max(0.f, 1.f - cos_t * cos_t));
    float phi = 2.f * kPi * u.y();
    const Vec3f axis = -a.direction;
    const Frame3 f = Frame3::fromNormal(axis);
    out.wi =
        (f.s * (sin_t * std::cos(phi)) + f.t * (sin_t * std::sin(phi)) + axis * cos_t).normalized();
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
  out.radiance = a.rgb * (falloff / dist2);
  out.pdf = 1.f;
  out.delta = true;
  return true;
}

float SceneLights::trianglePdf(size_t i, const PickPoint& at, float dist, float cos_light) const {
  const int k = group_of_[i];
  if (cos_light <= 0.f || k < 0 || !(at.total > 0.f)) return 0.f;
  const float pick = importance(static_cast<size_t>(k), at.p) / at.total;
  return pick * triangle_in_group_[i] / triangles_[i].area * dist * dist / cos_light;
}

Vec3f SceneLights::environmentRadiance(const Vec3f& d, const PickPoint* at, float& pdf) const {
  Vec3f L = Vec3f::Zero();
  pdf = 0.f;
  const float total = at ? at->total : 0.f;
  // the pick probability of analytic light k at p (0 when no receiver is given)
  auto pmf = [&](size_t k) { return total > 0.f ? env_importance_[k] / total : 0.f; };
  for (size_t k : environment_) {  // not every analytic light: this runs for every escaped ray
    const Analytic& a = analytic_[k];
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

}  // namespace inet
