#pragma once
// 3D bounding boxes of the scene's object instances: one gravity-aligned oriented box per
// instance (all parts of one piece of furniture together), as SUN RGB-D and ScanNet annotate
// them: the box's z axis is the world's up (+z), its heading a rotation about it.
//
// The heading is the one of the smallest-footprint rectangle around the instance's vertices seen
// from above (exact: rotating calipers over the 2D convex hull), except that when the object's
// own placement is a pure rotation about z whose axes bound the points within 1 % of that
// smallest area, the object's own axes are kept, so that a sofa's box x axis is the sofa's x axis
// (its width) rather than whichever edge happens to give the smaller rectangle.
#include <array>
#include <string>
#include <vector>

#include "core/pose.h"
#include "scene/scene.h"

namespace inet {

/// An oriented box: points p = centre + R_world_box * (s .* size / 2) for s in [-1, 1]^3.
struct OrientedBox {
  Vec3 centre = Vec3::Zero();  ///< world, metres
  Vec3 size = Vec3::Zero();    ///< full extents along the box's own x, y, z axes, metres
  Quat q_world_box = Quat::Identity();  ///< rotation box frame -> world

  /// The 8 corners in world coordinates, in the order of the bits of i: x = bit 0, y = bit 1,
  /// z = bit 2 (0 = negative side), i.e. corners 0-3 are the bottom face.
  std::array<Vec3, 8> corners() const;
  /// Heading: angle of the box x axis from world +x about +z (radians, (-pi, pi]); meaningful
  /// when the box is gravity-aligned.
  double yaw() const;
  /// The same box moved rigidly by T (world -> world).
  OrientedBox transformed(const Pose& T) const;
};

/// The smallest-footprint box around `points` whose z axis is world +z (exact; ties go to the
/// first hull edge, so the result is deterministic). Fewer than one point: a zero box at the
/// origin. The yaw is reduced to [0, pi/2) with size.x() and size.y() swapped to match.
OrientedBox gravityAlignedBox(const std::vector<Vec3>& points);

/// One instance's box and what it is.
struct InstanceBox {
  int instance = 0;      ///< instance id (the instance pass's value)
  int nyu40 = 0;         ///< NYU40 class of its first part
  std::string name;      ///< the first part's object name
  std::string kind;      ///< fine-grained category ("" = the NYU40 class)
  int room = -1;         ///< index into Scene::rooms of the first part, -1 = none
  bool moving = false;   ///< some part has motion keyframes
  int first_object = 0;  ///< index into Scene::objects of the first part (for its motion)
  OrientedBox box;       ///< at rest (before any motion keyframe is applied)
};

/// Boxes of every instance id > 0, sorted by instance id. Parts of one instance are boxed
/// together; analytic spheres contribute the corners of their bounding cube.
std::vector<InstanceBox> instanceBoxes(const Scene& scene);

/// The box of `b` at scene time t_s: the rest box moved by the first part's motion (identity for
/// a static instance). Object::transformAt(t) = pose(t) * T_world_object, so the whole instance
/// moves rigidly by pose(t).
OrientedBox boxAt(const Scene& scene, const InstanceBox& b, double t_s);

}  // namespace inet
