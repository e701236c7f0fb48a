#pragma once
// Placing a camera path from a file into a scene. A motion-capture path (TUM RGB-D, EuRoC,
// TUM-VI) is in the frame of the room it was recorded in: rendered as it is through another
// scene it crosses walls or runs outside. placePath finds the rigid motion of the ground plane
// (a turn about +z and a horizontal shift, the heights kept above the floor found under the
// path) that puts the most of the path's poses at least `clearance` from the scene's geometry.
//
// Search: the path's horizontal centroid is tried at every free voxel centre of the scene
// (thinned to at most max_anchors, in grid order) at each of `yaws` turns; each candidate is
// scored on at most max_samples poses spread evenly over the path, counted free when the
// grid's lower bound of the distance (FreeSpace::lowerBound, never more than the true one)
// reaches the clearance. The best score wins; ties go to the first candidate, so the result is
// deterministic. The path's own z is its height above its floor (z = 0 in TUM's and EuRoC's
// mocap frames, which are Z up); it is kept above the floor under the chosen centroid.
#include <cstddef>

#include "core/pose.h"
#include "trajectory/free_space.h"
#include "trajectory/trajectory.h"

namespace inet {

struct PlacePathOptions {
  double clearance = 0.1;     ///< m: a pose counts as placed this far from the geometry
  int yaws = 16;              ///< turns tried, evenly over 360 degrees
  size_t max_anchors = 4000;  ///< centroid positions tried at most
  size_t max_samples = 200;   ///< poses scored per candidate at most
};

struct PathPlacement {
  bool moved = false;     ///< false: the file's own frame was best (T is the identity)
  Pose T_scene_file;      ///< maps the file's poses into the scene: T * T_file_camera
  double yaw_deg = 0.0;   ///< the turn about +z
  double free_before = 0.0;  ///< share of the scored poses free as the file has them
  double free_after = 0.0;   ///< ... and after placing
};

/// Throws InputError(source, "--place-trajectory", ...) when the scene has no free voxel at all.
PathPlacement placePath(const Trajectory& path, const FreeSpace& space,
                        const PlacePathOptions& opt = {}, const std::string& source = "");

/// The path moved by T (each pose T * pose).
Trajectory transformed(const Trajectory& path, const Pose& T);

}  // namespace inet
