#pragma once
// SVG path data ("d" attribute) to closed polygons, for the cut-out shapes of Sweet Home 3D
// furniture: `doorOrWindowCutOutShape` (the hole a door or window makes in its wall) and
// `staircaseCutOutShape` (the hole a staircase makes in the floor above), in catalogs and Home.xml.
//
// Why hand-written: Sweet Home 3D parses these strings with Batik's PathParser into a Java2D
// shape. No C++ library packaged for Debian 12 turns path data into polygons without a whole
// SVG renderer: librsvg (over cairo) parses and rasterises documents, and small parsers such as
// nanosvg or lunasvg are not packaged. The grammar is small (SVG 1.1 section 8.3.1) and arcs
// follow the implementation notes (SVG 1.1 appendix F.6), so one self-contained, tested file is
// cheaper than a renderer dependency.
//
// Frame: the path's own units and axes. For cut-out shapes that is the unit square of the front
// face (door/window) or of the footprint (staircase), x from 0 (left) to 1 (right) and y from 0
// (TOP) to 1 (bottom), since SVG's y axis points down. Callers map to metres and flip y.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace inet {

/// One closed outline (polygon); the first vertex is not repeated at the end.
using Outline2d = std::vector<Eigen::Vector2d>;

/// Hard cap on the vertices parseSvgPath produces in total, so a hostile path or a tiny
/// tolerance fails with an InputError instead of exhausting memory or time.
inline constexpr size_t kMaxSvgPathVertices = 100000;

/// Parses an SVG path's `d` attribute into closed polygons, one per drawn subpath, in the order
/// of the path.
///
/// Grammar (SVG 1.1, as Batik reads it): commands M m L l H h V v C c S s Q q T t A a Z z,
/// absolute and relative; a command's argument group may repeat without repeating the letter;
/// extra pairs after a moveto are linetos; numbers like "1e-3", ".5", "-.5", "1.", "+2", and
/// "1.5.5" (= 1.5 then .5); arguments separated by whitespace (space, tab, CR, LF) and/or one
/// comma; arc flags are the single characters 0 or 1 and need no separator ("a1 1 0 011 1").
///
/// Geometry: S/T reflect the previous command's control point (or use the current point when
/// the previous command was no C/S resp. Q/T). Béziers and elliptical arcs are flattened so no
/// chord deviates from the curve by more than `tolerance` (path units), using the bound
/// |curve - chord| <= h^2/8 * max|second derivative| on uniform parameter steps h. Arcs follow
/// SVG 1.1 F.6.5 (endpoint to centre parameterisation) with the F.6.6 corrections: negative
/// radii use their magnitude, radii too small to reach the endpoint are scaled up, a zero
/// radius gives a straight line and an arc to its own start point is omitted.
///
/// Output: a subpath not closed with Z is closed implicitly. Vertices closer than 1e-6 *
/// `tolerance` to their predecessor are dropped (exact duplicates included), and so are last
/// vertices that close to the first. A subpath with no drawing command ("M1 1" alone, "M1 1 z")
/// draws nothing and is skipped, as in SVG.
///
/// Throws InputError(where_file, where_field, "offset N: ...") naming the character offset
/// (0-based, in bytes) and the problem when: the path does not start with M/m; a command letter
/// is unknown; numbers or flags are missing or malformed; a number is beyond double range
/// (overflow or underflow) or a computed coordinate is not finite; a drawn subpath has fewer than 3
/// distinct vertices; nothing is drawn at all; or the flattening would exceed kMaxSvgPathVertices.
/// Precondition (checked, a bug otherwise): `tolerance` is finite and > 0.
std::vector<Outline2d> parseSvgPath(std::string_view d, double tolerance,
                                    const std::string& where_file, const std::string& where_field);

/// Signed area by the shoelace formula. Positive when the vertices run counter-clockwise in a
/// y-up frame, which is CLOCKWISE as drawn in SVG's y-down frame (the unit square
/// "M0,0 v1 h1 v-1 z" has area -1: down, right, up is counter-clockwise on screen).
double outlineArea(const Outline2d& o);

/// Reverses `o` if needed so that outlineArea(o) >= 0 (counter-clockwise in a y-up frame).
/// Triangulators and extruders usually want one fixed winding; path authors use either.
void orientCounterClockwiseYUp(Outline2d& o);

}  // namespace inet
