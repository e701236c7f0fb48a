#pragma once
// A test light shared by the light-sampling tests: one emissive quad (two triangles) of
// radiance 20, 0.3 m on a side, at z = 2.7 over x, y in [2, 2.3], facing down.
#include <vector>

#include "render/lights.h"

namespace inet::test {

inline std::vector<EmissiveTriangle> emissiveQuad(int group) {
  EmissiveTriangle a, b;
  a.p0 = Vec3f(2, 2, 2.7f), a.e1 = Vec3f(0.3f, 0, 0), a.e2 = Vec3f(0, 0.3f, 0);
  b.p0 = Vec3f(2.3f, 2.3f, 2.7f), b.e1 = Vec3f(-0.3f, 0, 0), b.e2 = Vec3f(0, -0.3f, 0);
  for (EmissiveTriangle* t : {&a, &b}) {
    t->area = 0.045f;
    t->normal = Vec3f(0, 0, -1);
    t->radiance = Vec3f::Constant(20.f);
    t->group = group;
  }
  return {a, b};
}

/// Which of emissiveQuad's triangles a ray from p along unit d crosses (its plane z = 2.7).
inline size_t emissiveQuadTriangle(const Vec3f& p, const Vec3f& d) {
  const Vec3f hit = p + (2.7f - p.z()) / d.z() * d;
  return (hit.x() - 2.f) + (hit.y() - 2.f) < 0.3f ? 0 : 1;
}

}  // namespace inet::test
