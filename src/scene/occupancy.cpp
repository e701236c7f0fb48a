#include "scene/occupancy.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace inet {
namespace {

/// The 12 vertices and 20 faces of an icosahedron whose inscribed sphere has radius r.
void appendEnclosingIcosahedron(const Mat4& T, double r, int object, WorldTriangles& out) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  // the unit-circumradius icosahedron has inradius 0.7946545
  const double s = r / 0.7946544722917661 / std::sqrt(1.0 + phi * phi);
  const double v[12][3] = {{-1, phi, 0}, {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0},
                           {0, -1, phi}, {0, 1, phi},  {0, -1, -phi}, {0, 1, -phi},
                           {phi, 0, -1}, {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const uint32_t base = static_cast<uint32_t>(out.positions.size());
  for (const auto& p : v) {
    Eigen::Vector4d w = T * Eigen::Vector4d(p[0] * s, p[1] * s, p[2] * s, 1.0);
    out.positions.push_back(w.head<3>().cast<float>());
  }
  for (const auto& t : f) {
    out.triangles.push_back(Tri(base + t[0], base + t[1], base + t[2]));
    out.object.push_back(object);
  }
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return a;  // degenerate triangle
  return a + ab * (vb / denom) + ac * (vc / denom);
}

WorldTriangles worldTriangles(const Scene& scene) {
  WorldTriangles out;
  for (size_t oi = 0; oi < scene.objects.size(); ++oi) {
    const Object& o = scene.objects[oi];
    if (o.mesh < 0) continue;
    const Mesh& m = scene.meshes[o.mesh];
    const Mat4 T = o.transformAt(0.0);
    if (m.isSphere()) {
      appendEnclosingIcosahedron(T, m.sphere_radius, static_cast<int>(oi), out);
      continue;
    }
    const uint32_t base = static_cast<uint32_t>(out.positions.size());
    for (const Vec3f& p : m.positions) {
      Eigen::Vector4d w = T * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
      out.positions.push_back(w.head<3>().cast<float>());
    }
    for (const Tri& t : m.triangles) {
      out.triangles.push_back(Tri(base + t[0], base + t[1], base + t[2]));
      out.object.push_back(static_cast<int>(oi));
    }
  }
  return out;
}

std::pair<Vec3, Vec3> boundsWithoutHugePlanes(const Scene& scene, const WorldTriangles& tris,
                                              double max_plane_m) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<Vec3> obj_lo(scene.objects.size(), lo), obj_hi(scene.objects.size(), hi);
  for (size_t t = 0; t < tris.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Vec3 p = tris.positions[tris.triangles[t][c]].cast<double>();
      obj_lo[tris.object[t]] = obj_lo[tris.object[t]].cwiseMin(p);
      obj_hi[tris.object[t]] = obj_hi[tris.object[t]].cwiseMax(p);
    }
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    if (!(obj_lo[o].x() <= obj_hi[o].x())) continue;
    if ((obj_hi[o] - obj_lo[o]).head<2>().maxCoeff() > max_plane_m) continue;  // ground, sky
    lo = lo.cwiseMin(obj_lo[o]);
    hi = hi.cwiseMax(obj_hi[o]);
  }
  return {lo, hi};
}

OccupancyGrid voxelizeTriangles(const WorldTriangles& tris, const Vec3& lo, const Vec3& hi,
                                double voxel, double max_voxels) {
  INET_CHECK(voxel > 0 && max_voxels >= 1 && lo.x() <= hi.x());
  OccupancyGrid g;
  g.voxel = voxel;
  auto cells = [&](double v) -> Eigen::Array3d { return ((hi - lo) / v).array().ceil() + 1; };
  while (cells(g.voxel).prod() > max_voxels) g.voxel *= 1.25;
  const Eigen::Array3d n = cells(g.voxel);
  g.nx = static_cast<int>(n.x());
  g.ny = static_cast<int>(n.y());
  g.nz = static_cast<int>(n.z());
  g.origin = lo;
  g.occupied.assign(static_cast<size_t>(g.nx) * g.ny * g.nz, 0);
  const double h = g.voxel * std::sqrt(3.0) / 2.0;
  tbb::parallel_for(size_t(0), tris.triangles.size(), [&](size_t t) {
    const Tri& tri = tris.triangles[t];
    const Vec3 a = tris.positions[tri[0]].cast<double>(), b = tris.positions[tri[1]].cast<double>(),
               c = tris.positions[tri[2]].cast<double>();
    const Vec3 tlo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(h);
    const Vec3 thi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(h);
    const Eigen::Vector3i i0 = ((tlo - g.origin) / g.voxel).array().ceil().cast<int>().max(0);
    Eigen::Vector3i i1 = ((thi - g.origin) / g.voxel).array().floor().cast<int>();
    i1 = i1.cwiseMin(Eigen::Vector3i(g.nx - 1, g.ny - 1, g.nz - 1));
    Vec3 normal = (b - a).cross(c - a);
    const double area2 = normal.norm();
    if (area2 > 0) normal /= area2;
    for (int k = i0.z(); k <= i1.z(); ++k)
      for (int j = i0.y(); j <= i1.y(); ++j)
        for (int i = i0.x(); i <= i1.x(); ++i) {
          const Vec3 p = g.centre(i, j, k);
          if (area2 > 0 && std::abs(normal.dot(p - a)) > h) continue;
          if ((closestPointOnTriangle(p, a, b, c) - p).squaredNorm() > h * h) continue;
          std::atomic_ref<uint8_t>(g.occupied[g.index(i, j, k)]).store(1, std::memory_order_relaxed);
        }
  });
  return g;
}

}  // namespace inet
