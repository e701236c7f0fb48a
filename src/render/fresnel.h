#pragma once
// Fresnel reflectance of smooth interfaces (unpolarised light), specular reflection and
// refraction, and complex indices of refraction of common metals.
//
// Dielectric (real relative index eta = n_transmitted / n_incident), with c_i = cos(theta_i) and
// c_t = cos(theta_t) from Snell's law sin(theta_t) = sin(theta_i) / eta:
//   r_s = (c_i - eta c_t) / (c_i + eta c_t),   r_p = (eta c_i - c_t) / (eta c_i + c_t),
//   F = (r_s^2 + r_p^2) / 2, and F = 1 under total internal reflection (sin^2 theta_t > 1).
// Conductor: the same amplitudes with the complex index eta + i k (outside medium index 1),
// evaluated in complex arithmetic (Born & Wolf, Principles of Optics, section 14.2).
#include <Eigen/Core>

#include <string>

namespace inet {

using Vec3f = Eigen::Vector3f;

/// Fresnel reflectance of a dielectric interface. cos_i is the cosine between the incident
/// direction and the normal; eta = n_below / n_above where "above" is the side the normal points
/// to. A negative cos_i means the light arrives from below: then the ratio is inverted. Returns
/// 1 under total internal reflection. If cos_t is given, it receives |cos theta_t| (0 for TIR).
float fresnelDielectric(float cos_i, float eta, float* cos_t = nullptr);

/// Fresnel reflectance of a conductor with complex index eta + i k (outside medium: vacuum/air),
/// per RGB channel. cos_i in [0, 1]; returns 1 at grazing incidence.
Vec3f fresnelConductor(float cos_i, const Vec3f& eta, const Vec3f& k);
/// One channel of fresnelConductor.
float fresnelConductor1(float cos_i, float eta, float k);

/// Cosine-weighted hemispherical average Fbar(eta) = 2 int_0^1 F(mu, eta) mu dmu of
/// fresnelDielectric, for light arriving from the side the normal points to. Tabulated on first
/// use for eta in [1, 4] (linear interpolation, error < 1e-5), integrated directly above 4, and
/// for eta < 1 taken from the reciprocity identity 1 - Fbar(eta) = eta^2 (1 - Fbar(1 / eta)).
float fresnelDielectricAverage(float eta);

/// Mirror reflection of w about n (both unit, any side): 2 (w.n) n - w.
inline Vec3f reflect(const Vec3f& w, const Vec3f& n) {
  return 2.0f * w.dot(n) * n - w;
}

/// Refraction of w (pointing away from the surface) through the interface with normal n, where
/// eta = n_below / n_above relative to n. Works from either side. Returns false under total
/// internal reflection. The result points away from the surface on the other side.
bool refract(const Vec3f& w, const Vec3f& n, float eta, Vec3f& wt);

/// Complex index of refraction per RGB channel (linear sRGB primaries).
struct ComplexIor {
  Vec3f eta;
  Vec3f k;
};

/// Metals with tabulated complex indices of refraction.
enum class Metal { Gold, Silver, Copper, Aluminium, Chromium };

/// RGB complex IOR of a metal: the measured spectral eta and k that Mitsuba ships for its
/// conductor presets (data/ior/<name>.eta.spd / .k.spd), integrated to linear sRGB as tabulated
/// in the Tungsten renderer (src/core/bsdfs/ComplexIorData.hpp). Normal-incidence reflectance:
/// gold (0.97, 0.80, 0.32), silver (0.97, 0.96, 0.91), copper (0.95, 0.62, 0.51), aluminium
/// (0.93, 0.92, 0.91), chromium (0.69, 0.65, 0.69). No iron entry exists in that data; chromium
/// is the chrome-plating preset and a bright stand-in for polished steel (measured stainless
/// F0 is ~0.55-0.6: add specular_tint ~0.85).
ComplexIor metalIor(Metal metal);
/// "gold", "silver", "copper", "aluminium", "chromium".
std::string metalName(Metal metal);

}  // namespace inet
