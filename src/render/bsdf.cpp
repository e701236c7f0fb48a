// Every family computes f*|cos| and the pdf together (evalXxx), and every non-delta sample is
// finished by evaluating the family at the sampled direction: sampleBsdf's pdf and weight are
// then consistent with evalBsdf / pdfBsdf by construction, including the mixture pdfs of
// multi-lobe families (one-sample MIS over lobes).
#include "render/bsdf.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "render/microfacet.h"

namespace inet {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kMinCos = 1e-7f;  // |wo.z| below this: wo lies in the tangent plane

Vec3f flipZ(Vec3f v) {
  v.z() = -v.z();
  return v;
}
bool isSmooth(const BsdfParams& p) {
  return std::max(p.alpha_x, p.alpha_y) < kSmoothAlpha;
}
bool isIndexMatched(const BsdfParams& p) {
  return std::abs(p.ior - 1.0f) < kIndexMatchedEps;
}
GgxDistribution ggxOf(const BsdfParams& p) {
  return {std::max(p.alpha_x, kMinAlpha), std::max(p.alpha_y, kMinAlpha)};
}
Vec3f clamp01(const Vec3f& c) {
  return c.cwiseMax(0.0f).cwiseMin(1.0f);
}

/// Cosine-weighted direction on the +z hemisphere (Malley's method), pdf cos / pi.
Vec3f sampleCosineHemisphere(const Eigen::Vector2f& u) {
  float r = std::sqrt(u.x()), phi = 2.0f * kPi * u.y();
  return Vec3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x())));
}

/// Builds a non-delta sample from the family's own eval at wi.
std::optional<BsdfSample> finishSample(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi) {
  BsdfEval e = evalBsdfPdf(p, wo, wi);
  if (!(e.pdf > 0.0f) || !std::isfinite(e.pdf)) return std::nullopt;
  Vec3f weight = e.value / e.pdf;
  if (!weight.allFinite() || !(weight.maxCoeff() > 0.0f)) return std::nullopt;  // no energy
  return BsdfSample{wi, weight, e.pdf, false, wo.z() * wi.z() < 0.0f};
}

BsdfSample deltaSample(const Vec3f& wi, const Vec3f& weight, float prob, bool transmission) {
  return BsdfSample{wi, weight, prob, true, transmission};
}

// --- Lambertian and Translucent ------------------------------------------------------------

BsdfEval evalDiffuse(const Vec3f& reflectance, const Vec3f& transmittance, float p_reflect,
                     const Vec3f& wo, const Vec3f& wi) {
  float c = std::abs(wi.z()) * kInvPi;
  if (wo.z() * wi.z() > 0.0f) return {reflectance * c, p_reflect * c};
  return {transmittance * c, (1.0f - p_reflect) * c};
}

/// Probability of sampling diffuse reflection rather than transmission (Translucent).
float translucentReflectProb(const BsdfParams& p) {
  float r = luminance(p.albedo), t = luminance(p.transmittance);
  return r + t > 0.0f ? r / (r + t) : 1.0f;
}

// --- Conductor -------------------------------------------------------------------------------

BsdfEval evalConductor(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  if (isSmooth(p) || wo.z() * wi.z() <= 0.0f) return {Vec3f::Zero(), 0.0f};
  if (wo.z() < 0.0f) wo = flipZ(wo), wi = flipZ(wi);
  GgxDistribution g = ggxOf(p);
  Vec3f h = (wo + wi).normalized();
  float d = g.ndf(h);
  Vec3f f = fresnelConductor(wo.dot(h), p.eta, p.k).cwiseProduct(p.specular_tint);
  return {f * (d * g.maskShadow(wo, wi) / (4.0f * wo.z())), g.mask(wo) * d / (4.0f * wo.z())};
}

std::optional<BsdfSample> sampleConductor(const BsdfParams& p, const Vec3f& wo,
                                          const Eigen::Vector2f& u) {
  bool flip = wo.z() < 0.0f;
  Vec3f w = flip ? flipZ(wo) : wo;
  if (isSmooth(p)) {
    Vec3f wi(-w.x(), -w.y(), w.z());
    Vec3f f = fresnelConductor(w.z(), p.eta, p.k).cwiseProduct(p.specular_tint);
    return deltaSample(flip ? flipZ(wi) : wi, f, 1.0f, false);
  }
  Vec3f m = ggxOf(p).sampleVisibleNormal(w, u.x(), u.y());
  Vec3f wi = reflect(w, m);
  if (wi.z() <= 0.0f) return std::nullopt;  // reflected below the horizon: energy lost (G2)
  return finishSample(p, wo, flip ? flipZ(wi) : wi);
}

// --- Plastic: GGX dielectric coating over a Lambertian base ------------------------------------
//
// Specular: the rough dielectric reflection lobe, f_s = tint F(wo.h) D G2 / (4 cos_o cos_i).
// Diffuse:  f_d = albedo / pi * (1 - F(cos_o)) (1 - F(cos_i)) / (1 - Fbar), the Kelemen &
// Szirmay-Kalos (2001) coupling with the smooth-interface Fresnel F standing in for the coating's
// directional albedo. It is reciprocal, and its directional albedo is exactly
// albedo * (1 - F(cos_o)) because (1/pi) int (1 - F(cos_i)) cos_i dwi = 1 - Fbar. The total is
// E_s(wo) + albedo (1 - F(cos_o)) <= 1 as long as the rough coating reflects no more than the
// smooth one, E_s(wo) <= F(cos_o); microfacet masking makes that hold in practice and the
// energy test measures it.

float coatProbability(const BsdfParams& p, float f_o) {
  float s = f_o * luminance(p.specular_tint);
  float d = (1.0f - f_o) * luminance(p.albedo);
  if (s <= 0.0f) return 0.0f;
  if (d <= 0.0f) return 1.0f;
  // Keep both lobes at >= 10% so that neither highlights nor the base starve.
  return std::clamp(s / (s + d), 0.1f, 0.9f);
}

BsdfEval evalPlastic(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  if (wo.z() * wi.z() <= 0.0f) return {Vec3f::Zero(), 0.0f};
  if (wo.z() < 0.0f) wo = flipZ(wo), wi = flipZ(wi);
  float eta = std::max(p.ior, 1.0f);
  float f_o = fresnelDielectric(wo.z(), eta), f_i = fresnelDielectric(wi.z(), eta);
  float p_coat = coatProbability(p, f_o);
  float c = wi.z() * kInvPi;
  float diffuse = (1.0f - f_o) * (1.0f - f_i) / (1.0f - fresnelDielectricAverage(eta));
  BsdfEval e{p.albedo * (diffuse * c), (1.0f - p_coat) * c};
  if (!isSmooth(p) && eta != 1.0f) {
    GgxDistribution g = ggxOf(p);
    Vec3f h = (wo + wi).normalized();
    float d = g.ndf(h);
    float f = fresnelDielectric(wo.dot(h), eta);
    e.value += p.specular_tint * (f * d * g.maskShadow(wo, wi) / (4.0f * wo.z()));
    e.pdf += p_coat * g.mask(wo) * d / (4.0f * wo.z());
  }
  return e;
}

std::optional<BsdfSample> samplePlastic(const BsdfParams& p, const Vec3f& wo, float u_lobe,
                                        const Eigen::Vector2f& u) {
  bool flip = wo.z() < 0.0f;
  Vec3f w = flip ? flipZ(wo) : wo;
  float eta = std::max(p.ior, 1.0f);
  float f_o = fresnelDielectric(w.z(), eta);
  float p_coat = coatProbability(p, f_o);
  Vec3f wi;
  if (u_lobe < p_coat) {
    if (isSmooth(p)) {
      wi = Vec3f(-w.x(), -w.y(), w.z());
      return deltaSample(flip ? flipZ(wi) : wi, p.specular_tint * (f_o / p_coat), p_coat, false);
    }
    wi = reflect(w, ggxOf(p).sampleVisibleNormal(w, u.x(), u.y()));
    if (wi.z() <= 0.0f) return std::nullopt;
  } else {
    wi = sampleCosineHemisphere(u);
  }
  return finishSample(p, wo, flip ? flipZ(wi) : wi);
}

// --- Dielectric (Walter et al., "Microfacet Models for Refraction", EGSR 2007) -----------------
//
// With wo on the side of index n_o and eta = n_i / n_o the index ratio across the interface:
//   reflection   h = normalize(wo + wi),   f_r |cos_i| = tint F D G2 / (4 |cos_o|)
//   refraction   h = normalize(wo + eta wi) (flipped to +z),
//                f_t |cos_i| = T (1 - F) D G2 eta^2 |wo.h| |wi.h| / (|cos_o| (wo.h + eta wi.h)^2)
// with F = F(wo.h). Sampling picks h from D_wo, then reflection with probability F, so
//   pdf_r = D_wo(h) F / (4 |wo.h|),   pdf_t = D_wo(h) (1 - F) eta^2 |wi.h| / (wo.h + eta wi.h)^2
// and the weight of either is tint * G2 / G1(wo) <= 1. f_t omits the 1/eta^2 radiance factor
// (see bsdf.h).

BsdfEval evalDielectric(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  if (isSmooth(p) || isIndexMatched(p)) return {Vec3f::Zero(), 0.0f};
  float eta = p.ior;
  if (wo.z() < 0.0f) wo = flipZ(wo), wi = flipZ(wi), eta = 1.0f / eta;
  GgxDistribution g = ggxOf(p);
  if (wi.z() > 0.0f) {
    Vec3f h = (wo + wi).normalized();
    float d = g.ndf(h);
    float f = fresnelDielectric(wo.dot(h), eta);
    return {p.specular_tint * (f * d * g.maskShadow(wo, wi) / (4.0f * wo.z())),
            g.mask(wo) * d * f / (4.0f * wo.z())};
  }
  if (wi.z() == 0.0f) return {Vec3f::Zero(), 0.0f};
  Vec3f h = wo + eta * wi;
  float len2 = h.squaredNorm();
  if (len2 < 1e-12f) return {Vec3f::Zero(), 0.0f};
  h /= std::sqrt(len2);
  if (h.z() < 0.0f) h = -h;
  float d_o = wo.dot(h), d_i = wi.dot(h);
  // The microfacet must face wo and have wi behind it.
  if (d_o <= 0.0f || d_i >= 0.0f) return {Vec3f::Zero(), 0.0f};
  float f = fresnelDielectric(d_o, eta);
  float denom = d_o + eta * d_i;
  denom *= denom;
  if (f >= 1.0f || denom < 1e-12f) return {Vec3f::Zero(), 0.0f};
  float d = g.ndf(h);
  float jacobian = eta * eta * -d_i / denom;  // dw_h / dw_i
  float common = d * d_o * (1.0f - f) * jacobian / wo.z();
  return {p.transmittance * (common * g.maskShadow(wo, wi)), common * g.mask(wo)};
}

std::optional<BsdfSample> sampleDielectric(const BsdfParams& p, const Vec3f& wo, float u_lobe,
                                           const Eigen::Vector2f& u) {
  if (isIndexMatched(p)) return deltaSample(-wo, p.transmittance, 1.0f, true);
  bool flip = wo.z() < 0.0f;
  Vec3f w = flip ? flipZ(wo) : wo;
  float eta = flip ? 1.0f / p.ior : p.ior;
  Vec3f m = isSmooth(p) ? Vec3f(0.0f, 0.0f, 1.0f) : ggxOf(p).sampleVisibleNormal(w, u.x(), u.y());
  float f = fresnelDielectric(w.dot(m), eta);
  Vec3f wi;
  bool reflected = u_lobe < f;
  if (reflected) {
    wi = reflect(w, m);
    if (wi.z() <= 0.0f) return std::nullopt;
  } else {
    if (!refract(w, m, eta, wi) || wi.z() >= 0.0f) return std::nullopt;
  }
  if (flip) wi = flipZ(wi);
  if (isSmooth(p)) {
    if (reflected) return deltaSample(wi, p.specular_tint, f, false);
    return deltaSample(wi.normalized(), p.transmittance, 1.0f - f, true);
  }
  return finishSample(p, wo, wi.normalized());
}

// --- ThinDielectric ----------------------------------------------------------------------------
//
// Two parallel smooth interfaces, incoherent inter-reflections summed:
//   R = F + (1 - F)^2 F (1 + F^2 + F^4 + ...) = 2F / (1 + F),   T = 1 - R,
// with transmission straight through (the pane's lateral offset is ignored).

std::optional<BsdfSample> sampleThinDielectric(const BsdfParams& p, const Vec3f& wo, float u_lobe) {
  const float r = thinDielectricReflectance(p, wo.z());
  if (u_lobe < r) return deltaSample(Vec3f(-wo.x(), -wo.y(), wo.z()), p.specular_tint, r, false);
  return deltaSample(-wo, p.transmittance, 1.0f - r, true);
}

}  // namespace

Frame3 Frame3::fromNormal(const Vec3f& n) {
  float sign = std::copysign(1.0f, n.z());
  float a = -1.0f / (sign + n.z());
  float b = n.x() * n.y() * a;
  return {Vec3f(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x()),
          Vec3f(b, sign + n.y() * n.y() * a, -n.y()), n};
}

Frame3 Frame3::fromNormalTangent(const Vec3f& n, const Vec3f& tangent) {
  Vec3f s = tangent - n * n.dot(tangent);
  float len2 = s.squaredNorm(), t2 = tangent.squaredNorm();
  if (!(t2 > 0.0f) || !(len2 > 1e-10f * t2) || !std::isfinite(len2)) return fromNormal(n);
  s /= std::sqrt(len2);
  return {s, n.cross(s), n};
}

BsdfEval evalBsdfPdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (std::abs(wo.z()) < kMinCos) return {Vec3f::Zero(), 0.0f};
  switch (p.type) {
    case BsdfType::Lambertian:
      return evalDiffuse(p.albedo, Vec3f::Zero(), 1.0f, wo, wi);
    case BsdfType::Translucent:
      return evalDiffuse(p.albedo, p.transmittance, translucentReflectProb(p), wo, wi);
    case BsdfType::Conductor:
      return evalConductor(p, wo, wi);
    case BsdfType::Plastic:
      return evalPlastic(p, wo, wi);
    case BsdfType::Dielectric:
      return evalDielectric(p, wo, wi);
    case BsdfType::ThinDielectric:
      return {Vec3f::Zero(), 0.0f};
  }
  return {Vec3f::Zero(), 0.0f};
}

Vec3f evalBsdfDiffuse(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi) {
  if (std::abs(wo.z()) < kMinCos) return Vec3f::Zero();
  switch (p.type) {
    case BsdfType::Lambertian:
    case BsdfType::Translucent:
      return evalBsdfPdf(p, wo, wi).value;
    case BsdfType::Plastic: {
      // the base term of evalPlastic alone
      if (wo.z() * wi.z() <= 0.0f) return Vec3f::Zero();
      const float eta = std::max(p.ior, 1.0f);
      const float f_o = fresnelDielectric(std::abs(wo.z()), eta);
      const float f_i = fresnelDielectric(std::abs(wi.z()), eta);
      const float diffuse = (1.0f - f_o) * (1.0f - f_i) / (1.0f - fresnelDielectricAverage(eta));
      return p.albedo * (diffuse * std::abs(wi.z()) * kInvPi);
    }
    case BsdfType::Conductor:
    case BsdfType::Dielectric:
    case BsdfType::ThinDielectric:
      return Vec3f::Zero();
  }
  return Vec3f::Zero();
}

float viewDependentAlpha(const BsdfParams& p) {
  switch (p.type) {
    case BsdfType::Lambertian:
    case BsdfType::Translucent:
      return kNoViewDependentLobe;
    case BsdfType::Plastic:
    case BsdfType::Conductor:
    {
      // the narrower axis bounds how far the view may turn; a lobe smooth along one axis is a
      // mirror along it
      const float alpha = std::min(p.alpha_x, p.alpha_y);
      return alpha < kSmoothAlpha ? 0.0f : alpha;
    }
    case BsdfType::Dielectric:
    case BsdfType::ThinDielectric:
      return 0.0f;
  }
  return 0.0f;
}

Vec3f evalBsdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi) {
  return evalBsdfPdf(p, wo, wi).value;
}

float pdfBsdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi) {
  return evalBsdfPdf(p, wo, wi).pdf;
}

std::optional<BsdfSample> sampleBsdf(const BsdfParams& p, const Vec3f& wo, float u_lobe,
                                     const Eigen::Vector2f& u) {
  if (std::abs(wo.z()) < kMinCos) return std::nullopt;
  switch (p.type) {
    case BsdfType::Lambertian:
    case BsdfType::Translucent: {
      Vec3f wi = sampleCosineHemisphere(u);
      bool same_side = p.type == BsdfType::Lambertian || u_lobe < translucentReflectProb(p);
      if ((wo.z() < 0.0f) == same_side) wi = flipZ(wi);
      return finishSample(p, wo, wi);
    }
    case BsdfType::Conductor:
      return sampleConductor(p, wo, u);
    case BsdfType::Plastic:
      return samplePlastic(p, wo, u_lobe, u);
    case BsdfType::Dielectric:
      return sampleDielectric(p, wo, u_lobe, u);
    case BsdfType::ThinDielectric:
      return sampleThinDielectric(p, wo, u_lobe);
  }
  return std::nullopt;
}

bool isDelta(const BsdfParams& p) {
  switch (p.type) {
    case BsdfType::Conductor:
      return isSmooth(p);
    case BsdfType::Dielectric:
      return isSmooth(p) || isIndexMatched(p);
    case BsdfType::ThinDielectric:
      return true;
    default:
      return false;
  }
}

BsdfParams makeLambertian(const Vec3f& albedo) {
  BsdfParams p;
  p.type = BsdfType::Lambertian;
  p.albedo = clamp01(albedo);
  return p;
}

BsdfParams makeConductor(const Vec3f& eta, const Vec3f& k, float alpha_x, float alpha_y,
                         const Vec3f& specular_tint) {
  BsdfParams p;
  p.type = BsdfType::Conductor;
  p.eta = eta.cwiseMax(0.0f);
  p.k = k.cwiseMax(0.0f);
  p.alpha_x = std::max(alpha_x, 0.0f);
  p.alpha_y = std::max(alpha_y, 0.0f);
  p.specular_tint = clamp01(specular_tint);
  return p;
}

BsdfParams makeMetal(Metal metal, float alpha_x, float alpha_y) {
  ComplexIor ior = metalIor(metal);
  return makeConductor(ior.eta, ior.k, alpha_x, alpha_y);
}

BsdfParams makePlastic(const Vec3f& albedo, float alpha, float ior, const Vec3f& specular_tint) {
  BsdfParams p;
  p.type = BsdfType::Plastic;
  p.albedo = clamp01(albedo);
  p.alpha_x = p.alpha_y = std::max(alpha, 0.0f);
  p.ior = std::max(ior, 1.0f);
  p.specular_tint = clamp01(specular_tint);
  return p;
}

BsdfParams makeDielectric(float ior, float alpha, const Vec3f& transmittance,
                          const Vec3f& specular_tint) {
  BsdfParams p;
  p.type = BsdfType::Dielectric;
  p.ior = std::max(ior, 0.01f);
  p.alpha_x = p.alpha_y = std::max(alpha, 0.0f);
  p.transmittance = clamp01(transmittance);
  p.specular_tint = clamp01(specular_tint);
  return p;
}

float thinDielectricReflectance(const BsdfParams& p, float cos_theta) {
  float f = fresnelDielectric(std::abs(cos_theta), std::max(p.ior, 1.0f));
  return 2.0f * f / (1.0f + f);
}

Vec3f thinDielectricTransmission(const BsdfParams& p, float cos_theta) {
  return p.transmittance * (1.0f - thinDielectricReflectance(p, cos_theta));
}

BsdfParams makeThinDielectric(float ior, const Vec3f& transmittance) {
  BsdfParams p;
  p.type = BsdfType::ThinDielectric;
  p.ior = std::max(ior, 1.0f);
  p.transmittance = clamp01(transmittance);
  return p;
}

BsdfParams makeTranslucent(const Vec3f& reflectance, const Vec3f& transmittance) {
  BsdfParams p;
  p.type = BsdfType::Translucent;
  p.albedo = clamp01(reflectance);
  p.transmittance = clamp01(transmittance);
  for (int c = 0; c < 3; ++c) {
    float sum = p.albedo[c] + p.transmittance[c];
    if (sum > 1.0f) p.albedo[c] /= sum, p.transmittance[c] /= sum;
  }
  return p;
}

std::string bsdfTypeName(BsdfType type) {
  switch (type) {
    case BsdfType::Lambertian:
      return "lambertian";
    case BsdfType::Conductor:
      return "conductor";
    case BsdfType::Plastic:
      return "plastic";
    case BsdfType::Dielectric:
      return "dielectric";
    case BsdfType::ThinDielectric:
      return "thin_dielectric";
    case BsdfType::Translucent:
      return "translucent";
  }
  return "unknown";
}

std::string toString(const BsdfParams& p) {
  auto rgb = [](const Vec3f& c) { return fmt::format("({:g}, {:g}, {:g})", c.x(), c.y(), c.z()); };
  std::string s = "BsdfParams{" + bsdfTypeName(p.type);
  switch (p.type) {
    case BsdfType::Lambertian:
      s += " albedo=" + rgb(p.albedo);
      break;
    case BsdfType::Translucent:
      s += " reflectance=" + rgb(p.albedo) + " transmittance=" + rgb(p.transmittance);
      break;
    case BsdfType::Conductor:
      s += fmt::format(" eta={} k={} alpha=({:g}, {:g}) tint={}", rgb(p.eta), rgb(p.k), p.alpha_x,
                       p.alpha_y, rgb(p.specular_tint));
      break;
    case BsdfType::Plastic:
      s += fmt::format(" albedo={} alpha=({:g}, {:g}) ior={:g} tint={}", rgb(p.albedo), p.alpha_x,
                       p.alpha_y, p.ior, rgb(p.specular_tint));
      break;
    case BsdfType::Dielectric:
      s += fmt::format(" ior={:g} alpha=({:g}, {:g}) transmittance={} tint={}", p.ior, p.alpha_x,
                       p.alpha_y, rgb(p.transmittance), rgb(p.specular_tint));
      break;
    case BsdfType::ThinDielectric:
      s += fmt::format(" ior={:g} transmittance={}", p.ior, rgb(p.transmittance));
      break;
  }
  return s + "}";
}

}  // namespace inet
