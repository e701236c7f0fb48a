#pragma once
// Axis-aligned boxes appended to a mesh, for tests that build rooms, walls and furniture.
#include "scene/primitives.h"
#include "scene/scene.h"

namespace inet::test {

/// Appends an axis-aligned box (centre, size; outward winding) to `m`.
inline void appendBox(Mesh& m, const Vec3& centre, const Vec3& size) {
  const Mesh unit = makePrimitive("box", {}, "", "");
  const uint32_t base = static_cast<uint32_t>(m.positions.size());
  for (const Vec3f& p : unit.positions)
    m.positions.push_back((centre + p.cast<double>().cwiseProduct(size)).cast<float>());
  for (const Tri& t : unit.triangles) m.triangles.push_back(t + Tri::Constant(base));
}

}  // namespace inet::test
