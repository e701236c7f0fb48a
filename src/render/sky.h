#pragma once
// A clear daylight sky: the analytic model of A. J. Preetham, P. Shirley, B. Smits, "A Practical
// Analytic Model for Daylight", SIGGRAPH 1999 (sections 3 and appendix A.2), and the tables that
// importance-sample it.
//
// The model gives the sky's luminance Y and chromaticity (x, y) toward a direction at zenith
// angle theta and angle gamma from the sun (sun at zenith angle theta_s), for a turbidity T:
//   value(theta, gamma) = value_zenith * F(theta, gamma) / F(0, theta_s)        for Y, x and y
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma)  (Perez)
// with A..E linear in T (one set per quantity), the zenith luminance
//   Y_z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192   [kcd/m^2],
//   chi = (4/9 - T/120) (pi - 2 theta_s),
// and the zenith chromaticities x_z, y_z cubic in theta_s and quadratic in T. xyY goes to CIE XYZ
// and then to linear sRGB (Rec. 709 primaries, D65 white), negative channels clipped.
// Written here from the paper's equations because no Debian package provides the model as a
// library (renderers that have a sky model keep it inside their own code).
//
// Valid for 2 <= T <= 10 and the sun above the horizon. Below the horizon (z <= 0) the sky gives
// nothing: indoors the ground is the floor, not part of the sky.
#include <Eigen/Core>
#include <vector>

#include "core/image.h"
#include "scene/scene.h"

namespace inet {

/// Zenith luminance Y_z (kcd/m^2) for turbidity T and sun zenith angle theta_s (radians).
double preethamZenithLuminance(double turbidity, double theta_sun);
/// Zenith chromaticity (x_z, y_z) for turbidity T and sun zenith angle theta_s (radians).
Eigen::Vector2d preethamZenithChromaticity(double turbidity, double theta_sun);
/// CIE xyY -> linear sRGB (Rec. 709, D65) in the units of Y; negative channels clipped to 0.
Eigen::Vector3d xyYToLinearSrgb(double x, double y, double Y);

/// The Preetham sky in the model's own units (Y in kcd/m^2).
class PreethamSky {
 public:
  /// sun_direction: unit direction the sunlight travels (z < 0); turbidity in [2, 10].
  PreethamSky(double turbidity, const Vec3& sun_direction);

  /// (x, y, Y) seen looking along unit direction d (toward the sky); d.z() must be > 0.
  Eigen::Vector3d xyY(const Vec3& d) const;
  /// Linear sRGB radiance seen looking along unit direction d; zero when d.z() <= 0.
  Eigen::Vector3d rgb(const Vec3& d) const;
  /// Unit vector toward the sun.
  const Vec3& toSun() const { return to_sun_; }

 private:
  struct Perez {
    double A, B, C, D, E;
    double operator()(double cos_theta, double gamma, double cos_gamma) const;
  };
  Vec3 to_sun_;
  Perez perez_[3];   // Y, x, y
  double scale_[3];  // value at the zenith / F(0, theta_s), for Y, x, y
};

/// A piecewise-constant distribution of directions over a polar cap, the upper hemisphere by
/// default (theta_max = pi / 2) or the whole sphere (theta_max = pi), on an n_theta x n_phi grid
/// uniform in zenith angle theta in [0, theta_max] and azimuth phi in [0, 2 pi)
/// (phi = atan2(y, x)). The pdf with respect to solid angle is constant on each cell:
///   pdf = f_ij / sum_kl f_kl Omega_kl,   Omega_ij = (cos theta_i - cos theta_i+1) dphi
/// (Omega is the cell's solid angle, the exact integral of the sin theta Jacobian). Sampling
/// picks a row from the marginal, a cell from the row's conditional, then a direction uniform in
/// solid angle inside the cell (uniform in cos theta and phi).
class HemisphereDistribution {
 public:
  HemisphereDistribution() = default;  ///< empty: pdf 0 everywhere, sample fails
  /// values: n_theta * n_phi non-negative weights, row-major (row 0 at the zenith), not all 0;
  /// theta_max in (0, pi].
  HemisphereDistribution(const std::vector<double>& values, int n_theta, int n_phi,
                         double theta_max = 1.5707963267948966);

  /// A direction for u in [0, 1)^2, and its pdf (solid angle, = pdf(wi)); false if pdf is 0.
  bool sample(const Eigen::Vector2f& u, Vec3f& wi, float& pdf) const;
  /// Solid-angle pdf of unit direction d (0 outside the cap, e.g. d.z() <= 0 for a hemisphere).
  float pdf(const Vec3f& d) const;
  int thetaCells() const { return n_theta_; }
  int phiCells() const { return n_phi_; }

 private:
  int cell(const Vec3f& d) const;  // -1 outside the cap
  int n_theta_ = 0, n_phi_ = 0;
  std::vector<float> cos_edge_;    // n_theta + 1 row edges, cos of theta
  std::vector<float> pdf_;         // per cell
  std::vector<float> row_cdf_;     // marginal, n_theta
  std::vector<float> column_cdf_;  // conditional, n_theta * n_phi
};

/// A Preetham sky as a light: radiance in W sr^-1 m^-2, normalised so that the luminance
/// (Rec. 709 weights) of the RGB irradiance it gives an unoccluded horizontal surface,
///   E = integral over the upper hemisphere of L(w) cos theta dw,
/// equals `irradiance` (W/m^2; Light::intensity), and an importance-sampling table of its
/// luminance (64 x 256 cells, each the mean of 2 x 2 points, plus 0.1 % of the mean so that every
/// direction above the horizon can be sampled).
class PreethamSkyLight {
 public:
  /// From a sky light with SkyModel::Preetham (turbidity, direction, intensity).
  explicit PreethamSkyLight(const Light& light);

  /// Radiance (linear sRGB, W sr^-1 m^-2) arriving along -d, i.e. seen looking along unit d.
  Vec3f radiance(const Vec3f& d) const;
  /// Solid-angle pdf with which `sample` picks unit direction d.
  float pdf(const Vec3f& d) const { return table_.pdf(d); }
  /// A direction toward the sky for u in [0, 1)^2: its radiance, and its pdf (= pdf(wi)).
  bool sample(const Eigen::Vector2f& u, Vec3f& wi, Vec3f& radiance, float& pdf) const;
  /// Integral of the luminance of `radiance` over the hemisphere (W m^-2; for light picking).
  double luminanceIntegral() const { return luminance_integral_; }
  const PreethamSky& model() const { return model_; }

 private:
  PreethamSky model_;
  double scale_ = 0.0;  // W sr^-1 m^-2 per model unit
  double luminance_integral_ = 0.0;
  HemisphereDistribution table_;
};

/// An environment-map sky (SkyModel::EnvMap) as a light: an equirectangular image of radiance
/// (Light::envmap, its convention documented there), turned into the world by
/// Light::envmap_rotation and scaled by Light::intensity. Radiance is interpolated bilinearly
/// between texel centres (repeating in u, clamped at the poles), as Mitsuba's envmap emitter
/// does. Importance sampling uses one HemisphereDistribution cell per texel over the whole
/// sphere (rows uniform in theta, as the image's), weighted by the largest luminance among the
/// texel and its 8 neighbours: bilinear interpolation never leaves that bound inside the cell,
/// so radiance / pdf stays bounded (no fireflies from a dim cell next to the sun) and every
/// direction with radiance can be sampled.
class EnvMapSkyLight {
 public:
  /// Loads the image (Texture::load: PNG, JPEG, EXR; errors name `where` and the light's
  /// file). Negative and non-finite texels read as 0.
  EnvMapSkyLight(const Light& light, const std::string& where);
  /// From an image in memory (linear RGB, 1 or 3 channels), for tests.
  EnvMapSkyLight(ImageF image, const Mat3& rotation, float scale);

  /// Radiance (linear RGB, W sr^-1 m^-2) seen looking along unit world direction d.
  Vec3f radiance(const Vec3f& d) const;
  /// Solid-angle pdf with which `sample` picks unit world direction d.
  float pdf(const Vec3f& d) const;
  /// A direction for u in [0, 1)^2: its radiance and pdf (= pdf(wi)); false if nothing to sample.
  bool sample(const Eigen::Vector2f& u, Vec3f& wi, Vec3f& radiance, float& pdf) const;
  /// Integral of the luminance of `radiance` over the sphere (W m^-2; for light picking).
  double luminanceIntegral() const { return luminance_integral_; }

  /// (u, v) in [0, 1]^2 of a unit direction in the map's own frame (Light::envmap).
  static Eigen::Vector2f directionToUv(const Vec3f& d_map);
  /// Unit direction in the map's own frame of (u, v).
  static Vec3f uvToDirection(const Eigen::Vector2f& uv);

 private:
  void build();
  Vec3f texel(int x, int y) const;
  ImageF image_;  // linear RGB, 3 channels
  Eigen::Matrix3f R_world_map_;
  float scale_ = 1.f;
  double luminance_integral_ = 0.0;
  HemisphereDistribution table_;  // in the "table frame": the map frame with x and y swapped
};

}  // namespace inet
