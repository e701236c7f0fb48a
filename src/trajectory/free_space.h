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
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/pose.h"
#include "scene/scene.h"

namespace inet {

/// World-space triangles of a scene's static geometry (moving objects at scene time 0).
struct WorldTriangles {
  std::vector<Vec3f> positions;
  std::vector<Tri> triangles;
  std::vector<int> object;  ///< per triangle: index into Scene::objects
};
/// Flattens every object's mesh into world space. Analytic spheres become 20-sided polyhedra
/// that enclose them, so distances stay conservative.
WorldTriangles worldTriangles(const Scene& scene);

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

/// The closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

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
  /// A voxel centre and the lower bound of its distance to the geometry (m).
  struct FreeVoxel {
    Vec3 centre;
    double clearance;
  };
  /// Voxels that are indoors with a clearance >= `clearance`, centres between heights z_lo and
  /// z_hi.
  std::vector<FreeVoxel> freeCentres(double clearance, double z_lo, double z_hi) const;

 private:
  size_t index(int i, int j, int k) const { return (static_cast<size_t>(k) * ny_ + j) * nx_ + i; }
  /// Interpolated EDT (m); -1 outside the grid or next to an outdoor voxel.
  double field(const Vec3& p) const;

  std::unique_ptr<ExactDistance> exact_;
  double voxel_ = 0.05;
  Vec3 origin_ = Vec3::Zero();
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<float> dist_;       ///< EDT between voxel centres (m); 0 occupied, -1 outdoors
};

}  // namespace inet
