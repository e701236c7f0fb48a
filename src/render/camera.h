#pragma once
// Pinhole camera intrinsics.
//
// Inside the renderer pixel (i, j) covers [i, i+1) x [j, j+1) and is centred at (i+0.5, j+0.5),
// as in ../shared/bench/camera.json: the default 640x480 camera has cx = 320, cy = 240 there.
// Every file written for SLAM tools states the OpenCV convention instead (pixel centres at
// integers): cx_opencv = cx - 0.5, cy_opencv = cy - 0.5, i.e. 319.5, 239.5 by default.
#include <string>

#include "core/pose.h"

namespace inet {

struct CameraIntrinsics {
  int width = 640;
  int height = 480;
  double fx = 600.0;
  double fy = 600.0;
  double cx = 320.0;  ///< renderer convention (pixel centres at +0.5)
  double cy = 240.0;

  /// A width x height pinhole with square pixels of focal length f (pixels) and the principal
  /// point at the image centre.
  static CameraIntrinsics centred(int width, int height, double f) {
    return {width, height, f, f, width / 2.0, height / 2.0};
  }

  double cxOpenCV() const { return cx - 0.5; }
  double cyOpenCV() const { return cy - 0.5; }
  /// Direction in the camera frame through continuous image point (u, v), with z = 1, so that a
  /// hit at ray parameter t has z-depth exactly t.
  Vec3 rayCamera(double u, double v) const { return {(u - cx) / fx, (v - cy) / fy, 1.0}; }
  /// Projects a camera-frame point to continuous image coordinates (renderer convention).
  Eigen::Vector2d project(const Vec3& p_c) const {
    return {fx * p_c.x() / p_c.z() + cx, fy * p_c.y() / p_c.z() + cy};
  }
  /// Throws InputError(where, field, ...) for non-positive size or focal length, etc.
  void validate(const std::string& where) const;
  std::string toString() const;
};

/// A camera.json file (format of ../shared/bench/camera.json): width, height, fx, fy, cx, cy
/// (renderer convention) and either position/look_at/up or cam_to_world (4x4, OpenCV axes,
/// row-major nested arrays).
struct CameraFile {
  CameraIntrinsics intrinsics;
  Pose T_world_camera;
};
CameraFile loadCameraJson(const std::string& path);
/// The same on text in memory; `path` only names the source in error messages.
CameraFile parseCameraJson(const std::string& text, const std::string& path);

}  // namespace inet
