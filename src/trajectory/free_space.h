#pragma once
// Free space of a layout, where a camera may go: a distance field on a voxel grid for fast,
// smooth queries (the trajectory simulator asks millions of them), and exact distances to the
// triangles through an Embree point query for the final check of every output pose.
//
// The grid marks a voxel occupied when some triangle comes within half a voxel diagonal h of its
// centre, then takes the exact Euclidean distance transform of the occupancy (Felzenszwalb and
// Huttenlocher 2012). For a free voxel centre c the true distance d to the geometry then satisfies
// EDT(c) - h <= d <= EDT(c) + h, and a point p within a voxel of c loses at most another h, so
// lowerBound() = interpolated EDT - 2h never overstates the clearance.
//
// "Indoors" keeps cameras inside the building: with rooms, inside a room's outline between its
// floor and ceiling; without (imported OBJ scenes), the free voxels that cannot be reached from
// the grid's border, i.e. enclosed by geometry. An open scene (no enclosed volume) counts whole.
// The grid's faces count as geometry (an open scene's camera stays inside the box).
// Of that, only the biggest connected free region (and any other larger than 20 m^3) stays
// indoors: the enclosed insides of closed furniture are unreachable.
//
// Floors: a camera's height is measured from the floor below it, not from z = 0, so floors at
// any height, tall rooms and several storeys work alike. With rooms, a room's floor_z is the
// floor of every column inside its outline. Without (imported mesh scenes), floors are found in
// the grid: every indoor surface top (an occupied voxel under a free one) with at least 1 m of
// free space above it is a candidate; the candidate heights whose surfaces together cover at
// least 2 m^2 and 20 % of the largest such height are floor levels, and a level counts only if
// it lies at least 2 m above the level below it (a storey), so a bed or a row of desks is not a
// floor. A column's floor below a point is the highest surface top of a floor level under it.
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/pose.h"
#include "scene/occupancy.h"
#include "scene/scene.h"

namespace inet {

/// Exact distance from a point to the nearest triangle (Embree BVH + point query).
class ExactDistance {
 public:
  /// Takes the triangles (a copy, or moved in): the object owns what it queries.
  explicit ExactDistance(WorldTriangles tris);
  ~ExactDistance();
  ExactDistance(const ExactDistance&) = delete;
  ExactDistance& operator=(const ExactDistance&) = delete;
  /// Distance in metres to the closest triangle, or `max_radius` if none is closer.
  double distance(const Vec3& p, double max_radius = 1e3) const;
  const WorldTriangles& triangles() const { return tris_; }
  /// The closest point on any triangle within `max_radius` (p itself if none).
  Vec3 closestPoint(const Vec3& p, double max_radius = 1e3) const;

 private:
  WorldTriangles tris_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

struct FreeSpaceOptions {
  double voxel = 0.05;            ///< grid spacing (m)
  double max_voxels = 16e6;       ///< the voxel size grows until the grid fits (memory bound)
};

class FreeSpace {
 public:
  /// Builds the grid for `scene`. Throws InputError(source, "geometry", ...) if the scene has no
  /// geometry to bound it.
  FreeSpace(const Scene& scene, const FreeSpaceOptions& opt = {}, const std::string& source = "");

  /// A distance (m) to the geometry that is never larger than the true one; <= 0 in or next to
  /// occupied voxels and outside the grid. Outdoors (see above) counts as 0.
  double lowerBound(const Vec3& p) const;
  /// Gradient of the interpolated distance field (points away from the nearest geometry);
  /// central differences over one voxel, continuous in p.
  Vec3 gradient(const Vec3& p) const;
  /// True if p is indoors and lowerBound(p) >= clearance.
  bool isFree(const Vec3& p, double clearance) const { return lowerBound(p) >= clearance; }
  /// True if p is indoors, outside occupied voxels, and its exact distance to the triangles is
  /// at least `clearance`: as isFree, without the grid's slack (it asks Embree only when the
  /// grid cannot decide).
  bool hasClearance(const Vec3& p, double clearance) const;
  /// The exact distance to the triangles, for final checks.
  double exactDistance(const Vec3& p) const { return exact_->distance(p, 10.0); }

  /// Grid geometry and what it holds.
  double voxel() const { return voxel_; }
  const Vec3& origin() const { return origin_; }  ///< centre of voxel (0, 0, 0)
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  /// A voxel centre, the lower bound of its distance to the geometry (m) and the floor below it.
  struct FreeVoxel {
    Vec3 centre;
    double clearance;
    double floor_z;
  };
  /// Voxels that are indoors with a clearance >= `clearance`, centres between heights h_lo and
  /// h_hi above the floor below them (see the header comment).
  std::vector<FreeVoxel> freeCentres(double clearance, double h_lo, double h_hi) const;
  /// z of the floor under p (the highest floor surface of p's column at most 5 cm above p), or
  /// NaN when p's column has none.
  double floorBelow(const Vec3& p) const;
  /// z of the first geometry above p in its column (a voxel's precision), or NaN.
  double ceilingAbove(const Vec3& p) const;
  /// Were floors found in the grid (a mesh scene) rather than taken from rooms?
  bool floorsFromGeometry() const { return floors_from_geometry_; }
  /// The floor heights found (rooms: their distinct floor_z), lowest first.
  const std::vector<double>& floorLevels() const { return floor_levels_; }
  /// Does the scene enclose no room for a camera (a mesh scene with missing walls or holes)?
  /// Then "indoors" is what is roofed (see the header comment), and a camera's view should be
  /// kept towards it: isIndoors tells.
  bool isOpen() const { return open_; }
  /// Is p in the grid and indoors (occupied voxels count: walls are indoors)?
  bool isIndoors(const Vec3& p) const;
  /// Does the ray from p along dir meet geometry within max_range (m), rather than leave the
  /// grid or the indoors? (Sphere tracing on the grid: steps of the voxel distance field.)
  bool seesGeometry(const Vec3& p, const Vec3& dir, double max_range) const;
  /// The centre of the walls seen from indoors (open scenes: where a view should turn to).
  const Vec3& indoorCentre() const { return indoor_centre_; }
  /// Indoor free volume (m^3), and the part of it at least `clearance` from the geometry: what
  /// an error message can say about a scene with no room for a camera.
  double indoorVolume() const;
  double freeVolume(double clearance) const;

 private:
  size_t index(int i, int j, int k) const { return (static_cast<size_t>(k) * ny_ + j) * nx_ + i; }
  /// Interpolated EDT (m); -1 outside the grid or next to an outdoor voxel.
  double field(const Vec3& p) const;

  std::unique_ptr<ExactDistance> exact_;
  double voxel_ = 0.05;
  Vec3 origin_ = Vec3::Zero();
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<float> dist_;       ///< EDT between voxel centres (m); 0 occupied, -1 outdoors
  /// Floor surfaces per column c = i + nx * j: column_floors_[floor_start_[c] ..
  /// floor_start_[c + 1]), rising z.
  std::vector<uint32_t> floor_start_;
  std::vector<float> column_floors_;
  std::vector<double> floor_levels_;
  bool open_ = false;
  bool floors_from_geometry_ = false;
  Vec3 indoor_centre_ = Vec3::Zero();

  void findRoomFloors(const Scene& scene);
  void findMeshFloors(const std::vector<uint8_t>& occupied, const std::vector<uint8_t>& indoor);
};

}  // namespace inet
