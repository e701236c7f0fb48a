#pragma once
// Kinect-like (structured-light, Kinect v1 / PrimeSense) noisy depth from exact z-depth
// (SENSORS.md section 4, model A `nguyen` with the disparity quantisation of model B).
//
// Per pixel (x, y), with z the true z-depth (metres, 0 = no surface), n the camera-frame normal,
// r the viewing ray through the pixel centre and theta = angle(n, -r), in this order:
//   1. Returns that cannot exist, decided on the true geometry (all -> 0 = no return):
//      a. projector shadow: the IR projector sits at (baseline_m, 0, 0) in the camera frame
//         (x right, y down, z forward), parallel to the camera, so a point seen at column u lies
//         on projector column u_p = u - f b / z of the same row. Scanning a row from the
//         projector's side (right to left for b > 0), a pixel whose u_p exceeds the smallest
//         u_p met so far is hidden from the projector by a nearer surface. With b > 0 the shadow
//         falls on the LEFT (-x) side of a near object, f b (1/z_near - 1/z_far) pixels wide.
//      b. out of range (z < min_range_m or z > max_range_m), grazing angle (theta > max_angle);
//      c. depth edges: a pixel at Chebyshev distance r (pixels) from a discontinuity (relative
//         depth jump > edge_jump_ratio between 4-neighbours, or a neighbour without surface) is
//         dropped with probability edge_dropout_prob * (1 - r / edge_dropout_px).
//   2. lateral noise (Barron & Malik / ICL-NUIM: resample the true depth bilinearly at the pixel
//      centre shifted by N(0, sigma_L^2) px per axis; nearest tap if a tap has no surface), with
//      sigma_L(theta) = lateral_scale * (0.8 + 0.035 theta / (pi/2 - theta)) px (Nguyen et al.);
//   3. axial noise z' = z + sigma_a(z, theta) N(0, 1) (Nguyen et al.), see below;
//   4. disparity quantisation (Khoshelham & Elberink; ICL-NUIM): d = f_d b / z', d_q =
//      floor(d / step + 0.5) * step (step = 1/8 px), z_out = f_d b / d_q.
// Why this order: dropouts are properties of the scene (geometry, projector position), not of
// the noise, so they come first and use exact depth; lateral error comes from the block
// matching window, i.e. it displaces where a depth is read before the depth value itself is
// noisy; the sensor quantises the disparity it measures, so quantisation is last and every
// output is a representable disparity level.
//
// Axial sigma, Nguyen, Izadi & Lovell, "Modeling Kinect sensor noise for improved 3D
// reconstruction and tracking", 3DIMPVT 2012, eq. for sigma_z (metres, theta in radians):
//     sigma_N(z, theta) = 0.0012 + 0.0019 (z - 0.4)^2 + 0.0001 / sqrt(z) * theta^2 / (pi/2 -
//     theta)^2
// (the paper adds the theta term only above 60 degrees; below it is < 0.4 mm / sqrt(z) and we keep
// it everywhere, which makes sigma continuous in theta). Nguyen measured a real Kinect, whose
// output is already quantised, so sigma_N is the TOTAL error. Adding sigma_N and then quantising
// would overshoot (by 11 % at 4.5 m for f = 600 px). With axial_sigma_includes_quantisation
// (default) the Gaussian before quantisation has
//     sigma_a^2 = max(sigma_N^2 - dz^2 / 12, 0),   dz = z^2 step / (f_d b)  (depth step at z)
// so that the output std (Widrow: quantisation of a signal with Gaussian noise wider than half a
// step adds an independent uniform error of variance dz^2 / 12) follows sigma_N again.
// kinectDepthSigma gives the exact std of the output (sum over the quantisation levels).
//
// Randomness: CounterRng(seed, RngStream::Sensor, frame, y * width + x, kDepthNoiseRngTag), the
// same draws in the same order for every pixel (shift x, shift y, axial, edge dropout), so the
// output is a pure function of (seed, frame, pixel) for any thread count.
#include <cstdint>
#include <string>

#include "core/image.h"
#include "render/camera.h"

namespace inet {

/// Third counter word of the depth-noise streams (ASCII "KDN"), apart from kImuRngTag and
/// kSensorNoiseTag.
constexpr uint32_t kDepthNoiseRngTag = 0x4b444eu;

struct KinectNoiseOptions {
  /// Camera -> IR projector along camera +x, metres (negative: projector on the -x side). 0.075 m:
  /// Khoshelham & Elberink, Sensors 12(2) 2012 (Kinect v1 baseline); ICL-NUIM's add_noise.py.
  double baseline_m = 0.075;
  /// Focal length f_d of the disparity model, pixels; 0 = the image's fx (SENSORS.md 4.B: "use the
  /// real f_x"). Khoshelham & Elberink calibrate a Kinect v1 IR camera at f ~ 585 px (640 x 480).
  double disparity_focal_px = 0.0;
  /// Disparity quantisation step, pixels: 1/8 (Kinect v1 sub-pixel resolution; Khoshelham &
  /// Elberink; simkinect round(8 d) / 8). 0 = no quantisation.
  double disparity_step_px = 0.125;
  /// Operating range, metres: SENSORS.md 4.A [0.4, 4.5] (the acceptance range is
  /// 0.5-4.5 m).
  double min_range_m = 0.4;
  double max_range_m = 4.5;
  /// Largest angle between the surface normal and the viewing ray with a return, degrees.
  /// SENSORS.md 4.A: 85; Nguyen et al.'s sigma_z grows without bound as theta -> 90 degrees.
  double max_angle_deg = 85.0;
  /// Width of the edge dropout band, pixels (0 = no edge dropouts), its dropout probability at
  /// the edge itself, and the relative jump |z1 - z2| / min(z1, z2) that makes an edge. Our
  /// choice (no published values); SENSORS.md 4.B's 9 x 9 window drops a band of similar width.
  double edge_dropout_px = 3.0;
  double edge_dropout_prob = 1.0;
  double edge_jump_ratio = 0.05;
  /// Multiplies Nguyen's lateral sigma 0.8 + 0.035 theta / (pi/2 - theta) px (0 = no shift).
  double lateral_scale = 1.0;
  /// Multiplies the axial sigma (0 = no axial noise, quantisation only).
  double axial_scale = 1.0;
  /// True: Nguyen's sigma is the total error and the Gaussian is reduced by the quantisation
  /// variance (see above). False: Nguyen's Gaussian, then quantisation on top.
  bool axial_sigma_includes_quantisation = true;
  bool projector_shadow = true;

  /// Throws InputError(source, field, ...) for non-finite or out-of-range values.
  void validate(const std::string& source = "") const;
  std::string toString() const;
};

/// Nguyen et al.'s axial sigma_N(z, theta) in metres (z metres, theta radians in [0, pi/2)).
double nguyenAxialSigma(double z_m, double theta_rad);
/// Nguyen et al.'s lateral sigma in pixels: 0.8 + 0.035 theta / (pi/2 - theta).
double nguyenLateralSigmaPx(double theta_rad);
/// The Gaussian sigma added before quantisation at (z, theta), metres (opts' scale and
/// quantisation compensation applied). focal_px: the disparity focal length in use.
double kinectAxialSigma(double z_m, double theta_rad, const KinectNoiseOptions& opts,
                        double focal_px);

/// The model's standard deviation of (output - true depth) at true depth z and normal incidence
/// on a flat fronto-parallel surface, metres: exact over the quantisation levels (steps 3-4);
/// focal_px as above (the image's fx when opts.disparity_focal_px is 0).
double kinectDepthSigma(double z_m, const KinectNoiseOptions& opts, double focal_px);

/// Camera-frame unit normals (3 channels, (0,0,0) = unknown) estimated from a z-depth image by
/// finite differences of back-projected points (the side with the smaller depth jump), for
/// sequences stored without a normal pass.
ImageF normalsFromDepth(const ImageF& z_depth, const CameraIntrinsics& K);

/// Noisy z-depth (metres, 0 = no return) from true z-depth (1 channel, metres, 0 = no surface)
/// and camera-frame normals (3 channels; an empty image = estimate with normalsFromDepth).
/// K: pinhole intrinsics in the renderer convention (pixel centres at +0.5); sizes must match.
ImageF kinectNoisyDepth(const ImageF& z_depth, const ImageF& normal_cam, const CameraIntrinsics& K,
                        const KinectNoiseOptions& opts, uint64_t seed, uint32_t frame);

/// The projector-shadow mask alone (1 = hidden from the projector), step 1a above.
/// Geometry only: uses K.fx (the disparity focal length plays no part).
ImageU8 projectorShadowMask(const ImageF& z_depth, const CameraIntrinsics& K, double baseline_m);

}  // namespace inet
