#pragma once
// Optical flow ground truth (SENSORS.md section 5), two definitions:
//
//  * Two-frame forward flow, frame k -> k+1, pixels: what Middlebury .flo and KITTI PNG
//    consumers expect (sensors/flow_io.h; file names flow_fwd_*). For pixel x of frame k with
//    depth d, through the pixel centre (renderer convention: pixel (i, j) has its centre at
//    (i + 0.5, j + 0.5), render/camera.h) along the lens' chief ray r (generateRay at
//    kLensCentre):
//        X_ck   = d r / r_z (z-depth) or d r / |r| (ray distance)        camera k
//        X_w    = T_world_camera_k X_ck                                    world at t_k
//        X_w'   = D_i X_w,  D_i = T_world_object_i(t_k+1) T_world_object_i(t_k)^-1 for a pixel of
//                 a moving instance i, identity otherwise                  world at t_k+1
//        x'     = project(T_world_camera_k+1^-1 X_w')                      any LensModel
//        flow   = x' - x
//    Backward flow (k+1 -> k) is the same with the frames swapped and D_i inverted.
//
//  * SceneNet RGB-D's instantaneous flow, px/s, static scene, pinhole: the time derivative of
//    the image position of the point seen at x while the camera moves with linear velocity v_C
//    and angular velocity w_C (both in the camera frame):
//        X = Z K^-1 (u, v, 1)^T,  Xdot = -v_C - w_C x X,
//        udot = f_x (Xdot_x Z - X_x Zdot) / Z^2,  vdot = f_y (Xdot_y Z - X_y Zdot) / Z^2.
//    Pixels without depth count as 1000 m away (SceneNet's choice; file names flow_inst_*).
//
// Occlusion (forward flow). A pixel of frame k is occluded when its point is not visible in frame
// k+1: it has no image there (behind the camera / outside the lens' field), lands outside the
// image, or frame k+1 shows something else at its landing point x'. "Something else" means:
//   (a) the pixel of frame k+1 containing x' (the nearest pixel centre) shows another instance, or
//   (b) the point's predicted depth z' (same DepthKind as the input) is outside
//       [z_lo (1 - rel) - abs, z_hi (1 + rel) + abs]    (defaults rel = 1 %, abs = 1 cm),
//       where [z_lo, z_hi] spans the depths of the same-instance pixels among the (up to) four
//       pixel centres around x' that bilinear interpolation would weigh (weight > 0).
// Why a depth range and not one interpolated or nearest depth: for a plane seen by a pinhole 1/z
// is affine in the image, so the true depth at x' lies between the depths at the surrounding
// centres; a nearest tap alone is up to half a pixel off, which on a floor seen at a grazing
// angle is more than 1 % of depth, and a bilinear blend across a depth edge invents a depth that
// belongs to neither surface. Restricting to the same instance keeps foreground and background
// apart at object edges; rule (a) is conservative there (a point landing within half a pixel
// outside its own silhouette in k+1 is flagged, never the reverse), which is what a
// "non-occluded" evaluation mask wants. The lower bound of (b) flags points that would float in
// front of what k+1 shows: only inconsistent input does that (e.g. an object's motion missing
// from the ObjectMotion table); a consistent scene never trips it. Without instance images, (a)
// is skipped and (b) uses every footprint pixel with depth.
#include <cstdint>
#include <map>
#include <string>

#include "core/image.h"
#include "core/pose.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/lens.h"
#include "sensors/bspline.h"

namespace inet {

struct Scene;

// FlowField (the flow and its masks) is in render/frame.h, so that a Frame can carry it.

/// Rigid motion of the moving instances between two scene times t0 -> t1: a world point on
/// instance i at t0 is at delta.at(i) * p at t1 (delta = T_world_object(t1) T_world_object(t0)^-1;
/// i.e. T_world@t1_world@t0). Instances not in the table are static.
struct ObjectMotion {
  std::map<uint16_t, Pose> delta;

  bool empty() const { return delta.empty(); }
  /// The motion t1 -> t0 (every delta inverted), for backward flow.
  ObjectMotion inverse() const;
  std::string toString() const;
};

/// The ObjectMotion of `scene` between scene times t0_s and t1_s (seconds since the sequence's
/// first frame, as Object::transformAt and CameraExposure::scene_time_open_ns / 1e9). Contains
/// every instance that has a part with motion keyframes. Throws InputError(where,
/// "objects['name'].motion", ...) when the parts of one instance would move differently between
/// t0 and t1 (flow needs one rigid motion per instance id).
ObjectMotion objectMotionBetween(const Scene& scene, double t0_s, double t1_s,
                                 const std::string& where = "scene");

/// One frame as the flow sees it (references: no copies of the images).
struct FlowFrameView {
  const ImageF& depth;       ///< 1 channel, metres, of FlowOptions::depth_kind; 0 = no surface
  const ImageU16& instance;  ///< 1 channel instance ids; empty = all 0: no moving objects, and
                             ///< no instance test in the occlusion check (if either is empty)
  Pose T_world_camera;       ///< camera pose at the frame's ground-truth instant (OpenCV axes)
};

struct FlowOptions {
  /// What the depth images hold. ZDepth: Frame::depth_z (Pinhole/ThinLens, and any model within
  /// 90 degrees of the axis); RayDistance: Frame::depth_ray (any model, e.g. fisheye beyond
  /// 180 degrees or panoramas).
  DepthKind depth_kind = DepthKind::ZDepth;
  double occlusion_rel_tol = 0.01;    ///< relative depth tolerance of the visibility test
  double occlusion_abs_tol_m = 0.01;  ///< absolute depth tolerance of the visibility test, metres

  /// Throws InputError(where, field, ...) for negative or non-finite tolerances.
  void validate(const std::string& where) const;
};

/// The camera-frame point seen at pixel centre (x + 0.5, y + 0.5) with depth d of `kind` (X_ck
/// above); false where the lens has no ray there or the depth cannot lie on it (a z-depth on a
/// ray at or beyond 90 degrees).
bool backProjectPixel(const LensModel& lens, DepthKind kind, int x, int y, double d, Vec3& p);

/// Forward flow from frame `from` (k) to frame `to` (k+1), pixels (equations above). `lens`
/// (any model; both frames share it) has the images' size; `motion` maps instance ids of `from`
/// to their rigid motion between the two frames' scene times. A panorama's u flow takes the
/// shorter way round (|u| <= pi fx), and its target wraps at the seam.
/// Throws InputError("optical flow", field, ...) when image sizes differ from lens.K.
FlowField forwardFlow(const FlowFrameView& from, const FlowFrameView& to, const LensModel& lens,
                      const ObjectMotion& motion, const FlowOptions& opt = {});

/// Backward flow k+1 -> k: forwardFlow(next, prev, lens, motion.inverse(), opt), where `motion`
/// is the k -> k+1 table (the same one forwardFlow takes).
FlowField backwardFlow(const FlowFrameView& prev, const FlowFrameView& next, const LensModel& lens,
                       const ObjectMotion& motion, const FlowOptions& opt = {});

/// Camera velocities in the camera frame (OpenCV axes): v_cam in m/s (velocity of the camera
/// centre), w_cam in rad/s. The input of the instantaneous flow.
struct CameraVelocity {
  Vec3 v_cam = Vec3::Zero();
  Vec3 w_cam = Vec3::Zero();
};
/// From a spline state of T_world_camera: v_cam = R_world_camera^T v_world, w_cam = w_body.
CameraVelocity cameraVelocity(const SplineState& s);

/// SceneNet instantaneous flow of a static scene, px/s (2 channels u, v), pinhole `K` without
/// distortion (renderer convention, centres at +0.5), from z-depth (metres; <= 0 or non-finite =
/// no surface, taken as `no_depth_m` away). Defined at every pixel. SceneNet evaluates depth and
/// velocities at the shutter midpoint, i.e. the frame's ground-truth instant (render/shutter.h).
/// Moving objects are not accounted for (SceneNet's scenes are static).
ImageF instantaneousFlow(const ImageF& depth_z, const CameraIntrinsics& K,
                         const CameraVelocity& vel, double no_depth_m = 1000.0);

/// Largest |instantaneous flow| over the image, px/s (same inputs as instantaneousFlow, no image
/// allocated). For adaptive time steps: an event simulator keeps max speed * dt below a pixel.
double maxFlowSpeed(const ImageF& depth_z, const CameraIntrinsics& K, const CameraVelocity& vel,
                    double no_depth_m = 1000.0);

/// Frame k from frame k+1: out(x) = img_next(x + flow(x)), bilinear (pixel centres at +0.5, taps
/// clamped at the border), for every channel. 0 where flow.valid is 0 or x + flow(x) falls
/// outside the image (no wrapping at a panorama's seam). Sizes must match (INET_CHECK).
ImageF warpBackward(const ImageF& img_next, const FlowField& flow);

/// Middlebury colour coding of flow (Baker et al., "A Database and Evaluation Methodology for
/// Optical Flow", IJCV 2011; their colorcode.cpp wheel of 55 hues: red-yellow 15, yellow-green 6,
/// green-cyan 4, cyan-blue 11, blue-magenta 13, magenta-red 6): hue = direction, saturation =
/// |flow| / max_px (|flow| > max_px is darkened by 25 %), white = no motion, black = invalid.
/// max_px <= 0: the largest valid |flow|. Returns 3-channel 8-bit RGB.
ImageU8 flowToColor(const FlowField& flow, double max_px = 0.0);

}  // namespace inet
