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

SceneLights::SceneLights(const Scene& scene, std::vector<EmissiveTriangle> triangles,
                         float scene_radius)
    : triangles_(std::move(triangles)) {
  std::vector<double> power;
  for (const auto& t : triangles_)
    power.push_back(static_cast<double>(t.area) * kPi * luminance(t.radiance));
  for (const Light& l : scene.lights) {
    if (!l.on || l.intensity <= 0.f) continue;
    Analytic a;
    a.type = l.type;
    a.position = l.position.cast<float>();
    a.direction = l.direction.normalized().cast<float>();
    a.rgb = l.rgbIntensity();
    a.max_distance = l.max_distance;
    double p = luminance(a.rgb);
    if (l.type == LightType::Point) {
      p *= 4.0 * M_PI;
    } else if (l.type == LightType::Spot) {
      a.cos_outer = std::cos(l.cone_deg * kPi / 180.f);
      a.cos_inner = std::cos((l.cone_deg - l.falloff_deg) * kPi / 180.f);
      p *= 2.0 * M_PI * (1.0 - 0.5 * (a.cos_outer + a.cos_inner));
    } else if (l.type == LightType::Sky && l.sky_model == SkyModel::Preetham) {
      // as for the uniform sky: the light entering the scene's bounding sphere, pi r^2 per
      // steradian of sky, so pi r^2 x the integral of the sky's luminance
      a.sky = static_cast<int>(skies_.size());
      skies_.emplace_back(l);
      p = M_PI * scene_radius * scene_radius * skies_.back().luminanceIntegral();
    } else if (l.type == LightType::Sky && l.sky_model == SkyModel::EnvMap) {
      // as for the Preetham sky, over the whole sphere
      a.envmap = static_cast<int>(envmaps_.size());
      envmaps_.emplace_back(l, l.envmap.path);
      p = M_PI * scene_radius * scene_radius * envmaps_.back().luminanceIntegral();
    } else if (l.type == LightType::Sky) {
      // radiance L from the whole sphere: power ~ pi L x the area of the scene's bounding sphere
      p *= 4.0 * M_PI * M_PI * scene_radius * scene_radius;
    } else {
      float half = 0.5f * l.angular_diameter_deg * kPi / 180.f;
      a.cos_max = std::cos(half);
      a.one_minus_cos_max = static_cast<float>(2.0 * std::pow(std::sin(0.5 * double(half)), 2));
      // a disk of uniform radiance L gives irradiance E = L * pi * sin^2(half) at normal incidence
      a.radiance_scale = 1.f / (kPi * std::sin(half) * std::sin(half));
      p *= M_PI * scene_radius * scene_radius;
    }
    if (a.type == LightType::Sun || a.type == LightType::Sky)
      environment_.push_back(analytic_.size());
    analytic_.push_back(a);
    power.push_back(p);
  }
  double total = 0;
  for (double p : power) total += p;
  if (total <= 0) return;
  double acc = 0;
  for (double p : power) {
    acc += p;
    cdf_.push_back(static_cast<float>(acc / total));
    pmf_.push_back(static_cast<float>(p / total));
  }
  cdf_.back() = 1.f;
}

float SceneLights::pick(float u, size_t& index) const {
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  index = std::min<size_t>(static_cast<size_t>(it - cdf_.begin()), cdf_.size() - 1);
  while (index > 0 && pmf_[index] == 0.f) --index;  // never a zero-power light
  return pmf_[index];
}

bool SceneLights::sample(const Vec3f& p, float u_pick, const Eigen::Vector2f& u,
                         LightSample& out) const {
  if (cdf_.empty()) return false;
  size_t i;
  float pmf = pick(u_pick, i);
  if (i >= triangles_.size()) {
    if (!sampleAnalytic(analytic_[i - triangles_.size()], p, u, out)) return false;
    out.pdf *= pmf;
    return true;
  }
  const EmissiveTriangle& e = triangles_[i];
  float su = std::sqrt(u.x());
  Vec3f q = e.p0 + e.e1 * (1.f - su) + e.e2 * (su * u.y());
  Vec3f w = q - p;
  float dist2 = w.squaredNorm();
  if (dist2 <= 0.f) return false;
  out.dist = std::sqrt(dist2);
  out.wi = w / out.dist;
  float cos_l = -e.normal.dot(out.wi);
  if (cos_l <= 0.f) return false;  // one-sided emitter seen from behind
  out.radiance = e.radiance;
  out.pdf = pmf / e.area * dist2 / cos_l;
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

float SceneLights::trianglePdf(size_t i, float dist, float cos_light) const {
  if (cos_light <= 0.f) return 0.f;
  return pmf_[i] / triangles_[i].area * dist * dist / cos_light;
}

Vec3f SceneLights::environmentRadiance(const Vec3f& d, float& pdf) const {
  Vec3f L = Vec3f::Zero();
  pdf = 0.f;
  for (size_t k : environment_) {  // not every analytic light: this runs for every escaped ray
    const Analytic& a = analytic_[k];
    if (a.envmap >= 0) {
      const EnvMapSkyLight& map = envmaps_[a.envmap];
      L += map.radiance(d);
      pdf += pmf_[triangles_.size() + k] * map.pdf(d);
      continue;
    }
    if (a.sky >= 0) {
      const PreethamSkyLight& sky = skies_[a.sky];
      L += sky.radiance(d);
      pdf += pmf_[triangles_.size() + k] * sky.pdf(d);
      continue;
    }
    if (a.type == LightType::Sky) {
      L += a.rgb;
      pdf += pmf_[triangles_.size() + k] / (4.f * kPi);
      continue;
    }
    if (-a.direction.dot(d) < a.cos_max) continue;  // outside this sun's disk
    L += a.rgb * a.radiance_scale;
    pdf += pmf_[triangles_.size() + k] / (2.f * kPi * a.one_minus_cos_max);
  }
  return L;
}

}  // namespace inet
