#pragma once
// Whether a segment crosses the surface of objects of one NYU40 class (Moller-Trumbore on
// every triangle, brute force): how tests see that a wall is cut where a door or window is and
// closed elsewhere. Shared by the .sh3d and the apartment tests.
#include "scene/scene.h"

namespace inet::test {

/// Does the segment a-b cross a triangle of an object of class `nyu40`?
inline bool segmentHits(const Scene& s, const Vec3& a, const Vec3& b, int nyu40) {
  const Vec3 d = b - a;
  for (const Object& o : s.objects) {
    if (o.nyu40 != nyu40) continue;
    const Mesh& m = s.meshes[size_t(o.mesh)];
    for (const Tri& t : m.triangles) {
      Vec3 v[3];
      for (int k = 0; k < 3; ++k)
        v[k] = (o.T_world_object * m.positions[t[k]].cast<double>().homogeneous()).head<3>();
      // Moller-Trumbore
      const Vec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
      const Vec3 p = d.cross(e2);
      const double det = e1.dot(p);
      if (std::abs(det) < 1e-12) continue;
      const Vec3 q = a - v[0];
      const double u = q.dot(p) / det;
      if (u < 0 || u > 1) continue;
      const Vec3 r = q.cross(e1);
      const double w = d.dot(r) / det;
      if (w < 0 || u + w > 1) continue;
      const double t_hit = e2.dot(r) / det;
      if (t_hit >= 0 && t_hit <= 1) return true;
    }
  }
  return false;
}

}  // namespace inet::test
