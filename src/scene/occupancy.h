#pragma once
// A scene's geometry flattened into world-space triangles, and a voxel occupancy grid of them:
// what the free-space analysis (trajectory/free_space.h) and the automatic lighting of imported
// scenes (variation/auto_lights.h) both look at.
//
// A voxel is occupied when some triangle comes within half a voxel diagonal h of its centre, so
// no surface slips between voxel centres: a wall of any thickness becomes a closed layer.
#include <cstdint>
#include <utility>
#include <vector>

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

/// The closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Bounds (min, max) of the triangles of objects no wider than `max_plane_m` in x and y: an
/// imported scene's ground plane or sky dome must not make the grid building-sized. Empty
/// (min > max) when every object is wider.
std::pair<Vec3, Vec3> boundsWithoutHugePlanes(const Scene& scene, const WorldTriangles& tris,
                                              double max_plane_m = 50.0);

/// Occupancy of a regular grid: voxel (i, j, k) has its centre at origin + voxel * (i, j, k).
struct OccupancyGrid {
  Vec3 origin = Vec3::Zero();
  double voxel = 0.05;
  int nx = 0, ny = 0, nz = 0;
  std::vector<uint8_t> occupied;  ///< 1 where a triangle comes within h of the centre

  size_t size() const { return occupied.size(); }
  size_t index(int i, int j, int k) const {
    return (static_cast<size_t>(k) * ny + j) * nx + i;
  }
  Vec3 centre(int i, int j, int k) const { return origin + voxel * Vec3(i, j, k); }
  bool inside(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz;
  }
};

/// A grid covering [lo, hi] with spacing `voxel`, grown by factors of 1.25 until it has at most
/// `max_voxels` voxels (a memory bound), with every voxel near a triangle marked occupied.
OccupancyGrid voxelizeTriangles(const WorldTriangles& tris, const Vec3& lo, const Vec3& hi,
                                double voxel, double max_voxels);

}  // namespace inet
