#pragma once
// BSDFs of the InteriorNet paper's four material families, as plain data dispatched by a switch
// (no allocation, no virtual calls per hit):
//   Lambertian      diffuse reflection, cosine sampling
//   Conductor       GGX microfacet metal with exact complex Fresnel (or a smooth mirror)
//   Plastic         GGX dielectric coating over a Lambertian base ("glossy plastic", paint)
//   Dielectric      glass: smooth (delta reflection + refraction) or rough (Walter et al. 2007)
//   ThinDielectric  window pane: two parallel smooth interfaces, straight-through transmission
//   Translucent     diffuse reflection + diffuse transmission (curtains, lampshades, paper)
//
// Conventions (all functions):
//  - Directions are in the local shading frame (Frame3::toLocal): normal = +z. wo (towards the
//    viewer / previous vertex) and wi (towards the light / next vertex) are unit vectors
//    pointing AWAY from the surface.
//  - evalBsdf returns f(wo, wi) * |cos theta_i|, i.e. the cosine IS included.
//  - pdfBsdf is the solid-angle density with which sampleBsdf generates wi; delta lobes are
//    excluded from both (evalBsdf and pdfBsdf are 0 for them).
//  - BsdfSample::weight = f * |cos theta_i| / pdf, the path-throughput factor.
//  - Reflection-only families (Lambertian, Conductor, Plastic) are two-sided: a wo below the
//    surface is handled by mirroring the frame. Translucent and ThinDielectric are symmetric.
//    Dielectric is NOT: its normal must point to the outside (n = 1) of the object; wo.z < 0
//    means the path is inside the glass, and the index ratio is inverted. Do not flip the
//    dielectric's shading normal towards the viewer.
//  - The BTDF omits the 1/eta^2 factor that radiance picks up when it enters a denser medium
//    (i.e. it is the importance-transport form): with the camera and the lights outside every
//    glass object, each path crosses in and out and the two factors cancel anyway. The weight of a
//    smooth refraction is exactly the transmittance tint, and the rough-dielectric albedo is <= 1
//    from both sides (the furnace test relies on it).
//  - |wo.z| < 1e-7 (wo in the tangent plane) gives 0 / nullopt: no NaN or Inf, ever.
//
// Using it in a path tracer with next-event estimation and MIS (power heuristic; colour
// products are component-wise):
//   Frame3 F = Frame3::fromNormal(n_shading);         // outward normal for Dielectric
//   Vec3f wo = F.toLocal(-ray.d);
//   if (!isDelta(p)) {                                  // light sampling
//     BsdfEval e = evalBsdfPdf(p, wo, F.toLocal(to_light));
//     L += beta * e.value * Le / light_pdf * mis(light_pdf, e.pdf);
//   }
//   auto s = sampleBsdf(p, wo, rng.uniform(), {rng.uniform(), rng.uniform()});
//   if (!s) break;
//   beta *= s->weight; ray.d = F.toWorld(s->wi);
//   // on hitting an emitter: weight 1 if s->delta, else mis(s->pdf, light_pdf_of_hit)
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <string>

#include "render/fresnel.h"

namespace inet {

/// Orthonormal shading frame: s and t span the tangent plane, n is the normal; s x t = n.
struct Frame3 {
  Vec3f s, t, n;

  /// Frame around unit n with an arbitrary tangent (Duff et al., "Building an Orthonormal
  /// Basis, Revisited", JCGT 6(1) 2017: branchless, no singularity; the tangent jumps where
  /// n.z changes sign, which only matters for anisotropic lobes: use fromNormalTangent there).
  static Frame3 fromNormal(const Vec3f& n);
  /// Frame whose s is the tangent projected onto the plane of unit n (Gram-Schmidt); for
  /// anisotropic roughness alpha_x acts along s. Falls back to fromNormal when the tangent is
  /// (nearly) parallel to n or zero.
  static Frame3 fromNormalTangent(const Vec3f& n, const Vec3f& tangent);

  Vec3f toLocal(const Vec3f& v) const { return Vec3f(v.dot(s), v.dot(t), v.dot(n)); }
  Vec3f toWorld(const Vec3f& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

enum class BsdfType : uint8_t {
  Lambertian,
  Conductor,
  Plastic,
  Dielectric,
  ThinDielectric,
  Translucent
};

/// GGX roughness below this (in both directions) makes a lobe a perfect mirror / refractor.
constexpr float kSmoothAlpha = 1e-3f;
/// Roughness is clamped to at least this (one axis of an anisotropic lobe may be smaller than
/// kSmoothAlpha while the other is rough).
constexpr float kMinAlpha = 1e-4f;
/// |ior - 1| below this makes a dielectric index-matched: it lets light straight through.
constexpr float kIndexMatchedEps = 1e-3f;

/// Parameters of one BSDF; build with the make* functions below. Fields a family does not use
/// are ignored. Colours are linear RGB.
struct BsdfParams {
  BsdfType type = BsdfType::Lambertian;
  /// Lambertian reflectance; Plastic base colour; Translucent diffuse reflectance.
  Vec3f albedo = Vec3f::Constant(0.5f);
  /// Translucent diffuse transmittance; Dielectric / ThinDielectric transmission tint.
  Vec3f transmittance = Vec3f::Ones();
  /// GGX alpha along the frame's s and t axes (alpha = perceptual_roughness^2); both below
  /// kSmoothAlpha means smooth. Conductor, Plastic and Dielectric only.
  float alpha_x = 0.0f, alpha_y = 0.0f;
  /// Conductor complex index of refraction eta + i k per channel.
  Vec3f eta = Vec3f::Ones(), k = Vec3f::Zero();
  /// Dielectric / ThinDielectric / Plastic-coating index of refraction (outside medium: 1).
  float ior = 1.5f;
  /// Multiplies specular reflection (Conductor, Plastic coating, Dielectric reflection).
  Vec3f specular_tint = Vec3f::Ones();
};

/// One sampled direction.
struct BsdfSample {
  Vec3f wi;      ///< local frame, unit, pointing away from the surface
  Vec3f weight;  ///< f * |cos theta_i| / pdf
  /// Solid-angle density for non-delta samples (== pdfBsdf(wo, wi)); for a delta lobe, the
  /// discrete probability of having chosen it (not usable in MIS: use the delta flag).
  float pdf = 0.0f;
  bool delta = false;         ///< wi came from a specular (Dirac) lobe: no light sampling MIS
  bool transmission = false;  ///< wi is on the other side of the surface than wo
};

/// evalBsdf and pdfBsdf in one call (what next-event estimation with MIS needs).
struct BsdfEval {
  Vec3f value;  ///< f * |cos theta_i|
  float pdf;    ///< solid-angle pdf of sampleBsdf
};

/// f(wo, wi) * |cos theta_i| (the cosine is included); 0 for delta lobes.
Vec3f evalBsdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi);
/// The view-independent part of evalBsdf: the diffuse lobes (Lambertian and Translucent whole,
/// Plastic's base under its coating), 0 for specular families. Temporal reuse (sensors/
/// temporal_reuse.h) carries only light reflected through this part from frame to frame. The
/// Plastic base keeps its (1 - F(cos_o)) coating factor, which changes by well under 1 % over
/// the few degrees a camera turns around a point in a reuse window.
Vec3f evalBsdfDiffuse(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi);
/// How far the light a BSDF reflects toward the viewer may be trusted to stay the same while the
/// view direction turns: the GGX alpha of its view-dependent lobe (Plastic's coating, a rough
/// Conductor: the lobe is about 2 alpha radians wide in reflected directions), 0 where that lobe
/// is a delta (a mirror, a smooth coating) or transmits (glass: what is seen through it moves
/// with the viewer), and kNoViewDependentLobe where there is none (Lambertian, Translucent).
/// Temporal reuse (sensors/temporal_reuse.h) carries the view-dependent light of a point from
/// frame to frame only while the view has turned by a fraction of it.
float viewDependentAlpha(const BsdfParams& p);
constexpr float kNoViewDependentLobe = 1e30f;
/// Solid-angle pdf with which sampleBsdf(p, wo, ...) returns wi; 0 for delta lobes.
float pdfBsdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi);
BsdfEval evalBsdfPdf(const BsdfParams& p, const Vec3f& wo, const Vec3f& wi);
/// Samples wi given wo. u_lobe chooses the lobe (reflection / transmission / coating), u the
/// direction; all in [0, 1). Returns nullopt when the sample carries no energy (e.g. a
/// microfacet reflection below the horizon) - the path ends.
std::optional<BsdfSample> sampleBsdf(const BsdfParams& p, const Vec3f& wo, float u_lobe,
                                     const Eigen::Vector2f& u);
/// True if every lobe is a delta (smooth conductor, smooth or index-matched dielectric, thin
/// dielectric): the integrator skips light sampling. A smooth-coated Plastic is not purely
/// delta (its diffuse base still takes light samples).
bool isDelta(const BsdfParams& p);

// --- Named constructors. They clamp colours to [0, 1], alpha to >= 0 and ior to its domain.
/// Perceptual roughness (artist slider, 0..1) to GGX alpha.
inline float roughnessToAlpha(float roughness) {
  return roughness * roughness;
}
BsdfParams makeLambertian(const Vec3f& albedo);
/// Conductor from a complex IOR; alpha_x along the frame's s axis.
BsdfParams makeConductor(const Vec3f& eta, const Vec3f& k, float alpha_x, float alpha_y,
                         const Vec3f& specular_tint = Vec3f::Ones());
/// Metal preset (see metalIor for the data source); isotropic or anisotropic roughness.
BsdfParams makeMetal(Metal metal, float alpha_x, float alpha_y);
inline BsdfParams makeMetal(Metal metal, float alpha) {
  return makeMetal(metal, alpha, alpha);
}
/// Coated diffuse: ior >= 1 (1 gives a plain Lambertian), isotropic coating roughness.
BsdfParams makePlastic(const Vec3f& albedo, float alpha, float ior = 1.5f,
                       const Vec3f& specular_tint = Vec3f::Ones());
/// Glass / water / clear plastic volume boundary; alpha = 0 for smooth.
BsdfParams makeDielectric(float ior = 1.5f, float alpha = 0.0f,
                          const Vec3f& transmittance = Vec3f::Ones(),
                          const Vec3f& specular_tint = Vec3f::Ones());
/// Thin pane (window glass): always smooth; transmission goes straight through.
BsdfParams makeThinDielectric(float ior = 1.5f, const Vec3f& transmittance = Vec3f::Ones());
/// The straight-through transmission of a thin pane at |cos theta| (its delta lobe's weight:
/// transmittance x (1 - 2F / (1 + F))). Shadow rays pass panes with this factor.
Vec3f thinDielectricTransmission(const BsdfParams& p, float cos_theta);
/// Its reflectance 2F / (1 + F) (F: Fresnel at cos_theta), before the specular tint.
float thinDielectricReflectance(const BsdfParams& p, float cos_theta);
/// Diffuse reflectance + diffuse transmittance; scaled down so that their sum is <= 1 per
/// channel.
BsdfParams makeTranslucent(const Vec3f& reflectance, const Vec3f& transmittance);

std::string bsdfTypeName(BsdfType type);
/// One-line description with every field the family uses.
std::string toString(const BsdfParams& p);

}  // namespace inet
