#pragma once
// Camera lens models: pure maths, no renderer state. A lens maps a continuous image point (u, v)
// to a camera-frame ray (generateRay) and a camera-frame point back to (u, v) (project).
//
// Conventions (docs/cameras.md has the full derivations):
//  - Camera frame: OpenCV, x right, y down, z forward, metres.
//  - Image: continuous pixel coordinates in the renderer convention of CameraIntrinsics (pixel
//    (i, j) covers [i, i+1) x [j, j+1), centre at (i+0.5, j+0.5)). Files for SLAM tools state the
//    OpenCV convention (centres at integers), i.e. cx - 0.5, cy - 0.5: see toOpenCv().
//  - Normalised coordinates: mx = (u - cx) / fx, my = (v - cy) / fy.
//
// Models, with (mx, my) the normalised coordinates of the image point:
//  Pinhole   Brown-Conrady radial-tangential distortion exactly as OpenCV's projectPoints:
//              x = X/Z, y = Y/Z, r2 = x^2 + y^2, g = 1 + k1 r2 + k2 r2^2 + k3 r2^3
//              mx = x g + 2 p1 x y + p2 (r2 + 2 x^2),  my = y g + p1 (r2 + 2 y^2) + 2 p2 x y
//            generateRay inverts this by damped Newton; ray dir = (x, y, 1).
//  ThinLens  the pinhole (with its distortion) plus an aperture disk of radius aperture_radius_m
//            on the plane z = 0; every ray of an image point passes through the point where the
//            pinhole ray meets the focus plane z = focus_distance_m. dir = (x, y, 1) - o / F.
//  Fisheye   equidistant: theta = sqrt(mx^2 + my^2) is the angle from +z, azimuth atan2(my, mx);
//            rays exist for theta <= fisheye_fov_deg / 2. dir is unit length.
//  Panorama  equirectangular: longitude lon = mx in [-pi, pi] (0 = +z, +pi/2 = +x),
//            latitude lat = my in [-pi/2, pi/2] (-pi/2 = -y, up);
//            dir = (cos lat sin lon, sin lat, cos lat cos lon), unit length.
//
// Ray parameter and ground-truth depth: for Pinhole and ThinLens the ray starts on the plane
// z = 0 with dir.z = 1, so a hit's ray parameter t IS its z-depth; for Fisheye and Panorama
// dir is unit length from the camera centre, so t is the Euclidean ray distance. That t is
// exactly the depth a ground-truth pass stores for the model (groundTruthDepthKind), because
// z-depth is undefined or negative for fields of view of 180 degrees and more.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose.h"
#include "render/camera.h"

namespace inet {

enum class LensType { Pinhole, ThinLens, Fisheye, Panorama };

/// Registry names: "pinhole", "thin_lens", "fisheye", "panorama".
const char* lensTypeName(LensType type);
/// Inverse of lensTypeName; throws InputError(where, field, ...) listing the valid names.
LensType parseLensType(const std::string& name, const std::string& where,
                       const std::string& field = "lens");

/// A camera lens: plain data. Fields a model does not use must keep their defaults (validate
/// rejects e.g. distortion on a fisheye), so a configuration never silently ignores a value.
struct LensModel {
  LensType type = LensType::Pinhole;
  CameraIntrinsics K;  ///< width, height, fx, fy (px), cx, cy (px, renderer convention)
  /// Brown-Conrady coefficients in OpenCV's order (k1, k2, p1, p2, k3); Pinhole and ThinLens.
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
  double aperture_radius_m = 0;  ///< ThinLens: radius of the aperture disk; 0 = pinhole
  double focus_distance_m = 1;   ///< ThinLens: z of the plane in focus (> 0)
  double fisheye_fov_deg = 180;  ///< Fisheye: full field of view of the image circle, (0, 360]

  /// Equidistant fisheye of size x size px whose image circle (diameter = size) spans fov_deg:
  /// f = size / fov_rad, centre (size/2, size/2). Defaults: the paper's 600x600, 180 degrees.
  static LensModel fisheye(int size = 600, double fov_deg = 180);
  /// Full 360 x 180 degree equirectangular panorama: fx = width / (2 pi), fy = height / pi
  /// (px per radian), centre (width/2, height/2). Defaults: the paper's 5000x2500.
  static LensModel panorama(int width = 5000, int height = 2500);
  /// Pinhole (aperture 0) or thin lens with the given intrinsics.
  static LensModel pinhole(const CameraIntrinsics& K);
  static LensModel thinLens(const CameraIntrinsics& K, double aperture_radius_m,
                            double focus_distance_m);

  bool hasDistortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
  /// Throws InputError(where, field, problem) for any invalid or unused-but-set field, and for
  /// distortion that cannot be inverted somewhere on the image border (the polynomial folds).
  void validate(const std::string& where) const;
  std::string toString() const;
};

/// A ray in the camera frame: points origin + t * dir, t >= 0.
struct CameraRay {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ();
};

/// lens_uv that selects the centre of the aperture: the chief ray, identical to the pinhole ray.
/// Ground-truth passes use it so that depth, normals and labels are never defocused.
inline const Eigen::Vector2d kLensCentre{0.5, 0.5};

/// Ray through continuous image point (u, v). lens_uv in [0,1)^2 samples the aperture disk
/// (ThinLens only; concentric mapping, so stratified lens_uv gives stratified disk points).
/// Returns false where no ray exists: outside the fisheye circle, outside the panorama's angle
/// range, or where the distortion cannot be inverted (beyond the fold of the polynomial).
/// Pinhole/ThinLens: origin on z = 0, dir.z = 1. Fisheye/Panorama: origin 0, |dir| = 1.
/// With zero distortion the pinhole dir equals CameraIntrinsics::rayCamera(u, v) bit for bit.
bool generateRay(const LensModel& lens, double u, double v, const Eigen::Vector2d& lens_uv,
                 CameraRay& out);

/// Projects a camera-frame point to continuous image coordinates (renderer convention), with
/// distortion applied exactly as OpenCV's projectPoints does. For ThinLens this is the chief-ray
/// image, i.e. the centre of the point's blur disk. Returns false if the point has no image
/// under the model: z <= 0 (Pinhole/ThinLens), beyond the radius where the radial polynomial
/// stops increasing (where projectPoints would fold it back), theta > fov/2 (Fisheye), the
/// camera centre itself (all). Does NOT test the image bounds: uv may lie outside the image.
/// Panorama: longitude in [-pi, pi), so the direction -z maps to u = cx - pi fx (= 0 by default).
bool project(const LensModel& lens, const Vec3& p_cam, Eigen::Vector2d& uv);

/// The Brown-Conrady forward model of Pinhole/ThinLens on normalised coordinates: undistorted
/// (x, y) = (X/Z, Y/Z) to distorted (mx, my) (equations above), and optionally its Jacobian
/// d(mx, my)/d(x, y) (symmetric). Identity when the model has no distortion.
Eigen::Vector2d distortNormalised(const LensModel& lens, const Eigen::Vector2d& xy,
                                  Eigen::Matrix2d* J = nullptr);
/// Inverse of distortNormalised by damped Newton from xy = m, converged to a residual below
/// 1e-14 (1 + |m|) (normalised units). Returns false where no root exists on the unfolded branch
/// (orientation-preserving, radius inside the part where the radial polynomial increases).
bool undistortNormalised(const LensModel& lens, const Eigen::Vector2d& m, Eigen::Vector2d& xy);

/// Which depth a ground-truth depth pass stores for a model (docs/cameras.md).
enum class DepthKind {
  ZDepth,       ///< p_cam.z: Pinhole and ThinLens (chief ray); the "depth.Z" convention
  RayDistance,  ///< |p_cam|: Fisheye and Panorama, where z-depth is not usable beyond 180 deg
};
DepthKind groundTruthDepthKind(LensType type);
/// The ground-truth depth of camera-frame point p under the model's DepthKind, metres.
double groundTruthDepth(const LensModel& lens, const Vec3& p_cam);

/// ThinLens: radius in x pixels of the blur disk of a point at z-depth depth_m,
/// fx * aperture * |1/depth - 1/focus| (0 for other models). For choosing an aperture.
double blurRadiusPx(const LensModel& lens, double depth_m);

/// Parameters as a SLAM tool reads them: principal point in the OpenCV convention (pixel centres
/// at integers) and the distortion vector of the named model.
struct OpenCvCamera {
  std::string model;  ///< "radtan" (cv::projectPoints), "equidistant" (cv::fisheye, Kalibr
                      ///< pinhole-equi), or "equirectangular" (no OpenCV model)
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::vector<double> distortion;  ///< radtan: k1 k2 p1 p2 k3; equidistant: k1..k4 (all 0)
};
OpenCvCamera toOpenCv(const LensModel& lens);

}  // namespace inet
