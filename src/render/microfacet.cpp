#include "render/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace inet {
namespace {
constexpr float kPi = 3.14159265358979323846f;
}

float GgxDistribution::ndf(const Vec3f& m) const {
  if (m.z() <= 0.0f) return 0.0f;
  float ex = m.x() / alpha_x, ey = m.y() / alpha_y;
  float t = ex * ex + ey * ey + m.z() * m.z();
  return 1.0f / (kPi * alpha_x * alpha_y * t * t);
}

float GgxDistribution::lambda(const Vec3f& w) const {
  // Written as a2 / (2 |wz| (sqrt(wz^2 + a2) + |wz|)), algebraically equal to the form in the
  // header but free of cancellation for small a2 / wz^2, and +inf (not NaN) at wz = 0.
  float wz = std::abs(w.z());
  float a2 = alpha_x * alpha_x * w.x() * w.x() + alpha_y * alpha_y * w.y() * w.y();
  if (a2 <= 0.0f) return 0.0f;
  if (wz <= 0.0f) return std::numeric_limits<float>::infinity();
  return a2 / (2.0f * wz * (std::sqrt(wz * wz + a2) + wz));
}

float GgxDistribution::visibleNdf(const Vec3f& wo, const Vec3f& m) const {
  float dot = wo.dot(m);
  if (wo.z() <= 0.0f || dot <= 0.0f) return 0.0f;
  return mask(wo) * dot * ndf(m) / wo.z();
}

Vec3f GgxDistribution::sampleVisibleNormal(const Vec3f& wo, float u0, float u1) const {
  // Stretched view direction: the alpha = 1 hemisphere configuration.
  Vec3f v = Vec3f(alpha_x * wo.x(), alpha_y * wo.y(), std::max(wo.z(), 0.0f)).normalized();
  // Orthonormal basis (t1, t2, v) with t1 horizontal.
  float len2 = v.x() * v.x() + v.y() * v.y();
  Vec3f t1 = len2 > 1e-14f ? Vec3f(-v.y(), v.x(), 0.0f) / std::sqrt(len2) : Vec3f(1.0f, 0.0f, 0.0f);
  Vec3f t2 = v.cross(t1);
  // Uniform point on the unit disk, then warp the lower half to the visible part of the
  // projected hemisphere (its outline is an ellipse scaled by v.z on the far side).
  float r = std::sqrt(u0), phi = 2.0f * kPi * u1;
  float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + v.z());
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  Vec3f nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
  // Unstretch back to the ellipsoid configuration.
  Vec3f m(alpha_x * nh.x(), alpha_y * nh.y(), std::max(nh.z(), 1e-6f));
  return m.normalized();
}

}  // namespace inet
