#pragma once
// Planar polygon operations for building architecture from plans (issue 15, .sh3d import):
// the face of a wall minus its door and window cut-outs, a room's floor. Polygon booleans and
// the constrained Delaunay triangulation come from GEOS (Debian's libgeos-dev, the C API);
// only the conversion to and from its geometries is written here.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace inet {

using Ring = std::vector<Eigen::Vector2d>;  ///< a closed polygon's corners, not repeated
using Triangle2 = std::array<Eigen::Vector2d, 3>;

/// Triangles covering `outer` minus the union of `holes`, each counter-clockwise. Rings may be
/// in either orientation; holes may cross the outline or each other; a self-intersecting ring
/// is repaired (GEOS MakeValid) first. An empty result for a degenerate outline.
std::vector<Triangle2> triangulateDifference(const Ring& outer, const std::vector<Ring>& holes);

/// Triangles covering the polygon `outer` (as triangulateDifference without holes).
std::vector<Triangle2> triangulatePolygon(const Ring& outer);

/// The boundary rings (outer and inner) of `a` intersected with `b`: the outline of the part
/// of a hole that lies inside a face, whose edges become the hole's reveals.
std::vector<Ring> intersectionRings(const Ring& a, const Ring& b);

/// One reveal of an opening: an edge (a, b) of the part of a hole inside a face, and the
/// direction in the face's plane from the edge towards the hole's centre, which the reveal
/// faces.
struct RevealEdge {
  Eigen::Vector2d a, b, inward;
};

/// A flat face with openings, in its own 2-D frame (u along it, v up): the triangles covering
/// `outline` minus `holes` and, with `reveals`, the edges of each hole's part inside the
/// outline, except those lying on v = `floor_v` (a door's sill on the floor, where the room's
/// floor is drawn and a reveal face would fight with it).
struct FaceWithHoles {
  std::vector<Triangle2> triangles;
  std::vector<RevealEdge> reveals;
};
FaceWithHoles faceWithHoles(const Ring& outline, const std::vector<Ring>& holes, bool reveals,
                            double floor_v);

/// The area of `a` intersected with `b` (>= 0).
double intersectionArea(const Ring& a, const Ring& b);

/// The closed faces a set of line segments encloses (GEOS node + polygonize): the rooms a plan
/// of wall centre lines draws. Outer rings only, counter-clockwise; faces under `min_area` are
/// dropped.
std::vector<Ring> enclosedFaces(const std::vector<std::array<Eigen::Vector2d, 2>>& segments,
                                double min_area);

/// Twice the signed area of a ring (> 0: counter-clockwise with y up).
double signedArea2(const Ring& r);

}  // namespace inet
