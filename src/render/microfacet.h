#pragma once
// Anisotropic GGX / Trowbridge-Reitz microfacet distribution in the local shading frame
// (normal = +z, roughness alpha_x along +x = the tangent, alpha_y along +y).
//
//   D(m)      = 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2)            for mz > 0
//   Lambda(w) = (sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2) - 1) / 2          (Smith, GGX)
//   G1(w)     = 1 / (1 + Lambda(w))
//   G2(o, i)  = 1 / (1 + Lambda(o) + Lambda(i))     height-correlated (Heitz 2014, eq. 99)
//   D_o(m)    = G1(o) max(0, o.m) D(m) / o.z        distribution of visible normals
// Visible normals are sampled exactly with Heitz, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4) 2018: stretch the view direction to the alpha = 1 configuration, sample
// the projected hemisphere there, and unstretch.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace inet {

using Vec3f = Eigen::Vector3f;

struct GgxDistribution {
  float alpha_x;  ///< > 0; callers clamp to >= 1e-4
  float alpha_y;

  /// Normal distribution D(m) (per unit projected area, per steradian); 0 if m.z <= 0.
  float ndf(const Vec3f& m) const;
  /// Smith Lambda(w); uses |w.z| (either hemisphere). +inf at the horizon, never NaN.
  float lambda(const Vec3f& w) const;
  /// Masking G1(w) = 1 / (1 + Lambda(w)).
  float mask(const Vec3f& w) const { return 1.0f / (1.0f + lambda(w)); }
  /// Height-correlated masking-shadowing G2(wo, wi).
  float maskShadow(const Vec3f& wo, const Vec3f& wi) const {
    return 1.0f / (1.0f + lambda(wo) + lambda(wi));
  }
  /// Density of visible normals D_wo(m) for wo.z > 0 (0 if wo.m <= 0 or m.z <= 0).
  float visibleNdf(const Vec3f& wo, const Vec3f& m) const;
  /// Samples a microfacet normal m with density visibleNdf(wo, .); requires wo.z >= 0 and
  /// u in [0, 1)^2. The result has m.z > 0 and wo.m >= 0.
  Vec3f sampleVisibleNormal(const Vec3f& wo, float u0, float u1) const;
};

}  // namespace inet
