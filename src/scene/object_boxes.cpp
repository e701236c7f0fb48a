#include "scene/object_boxes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

namespace inet {
namespace {

using P2 = Eigen::Vector2d;

double cross(const P2& o, const P2& a, const P2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// Andrew's monotone chain, counter-clockwise, no collinear points. Written here: a 2D hull of a
/// few thousand points is a dozen lines, and no library of DESIGN.md provides one (CGAL is not
/// among them).
std::vector<P2> convexHull(std::vector<P2> p) {
  std::sort(p.begin(), p.end(), [](const P2& a, const P2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<P2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

/// Extents of `pts` along the unit axes (c, s) and (-s, c): min and max of each.
struct Rect {
  double area = 0, min_u = 0, max_u = 0, min_v = 0, max_v = 0;
};
Rect rectAlong(const std::vector<P2>& pts, double c, double s) {
  Rect r{0, 1e300, -1e300, 1e300, -1e300};
  for (const P2& p : pts) {
    const double u = c * p.x() + s * p.y(), v = -s * p.x() + c * p.y();
    r.min_u = std::min(r.min_u, u);
    r.max_u = std::max(r.max_u, u);
    r.min_v = std::min(r.min_v, v);
    r.max_v = std::max(r.max_v, v);
  }
  r.area = (r.max_u - r.min_u) * (r.max_v - r.min_v);
  return r;
}

OrientedBox boxFromRect(const Rect& r, double yaw, double z0, double z1) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double u = (r.min_u + r.max_u) / 2, v = (r.min_v + r.max_v) / 2;
  OrientedBox b;
  b.centre = Vec3(c * u - s * v, s * u + c * v, (z0 + z1) / 2);
  b.size = Vec3(r.max_u - r.min_u, r.max_v - r.min_v, z1 - z0);
  b.q_world_box = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
  return b;
}

/// The yaw of a rotation that turns only about z (its z axis stays world +z within 1e-6), else
/// nothing: such an object's own x axis is a meaningful heading.
bool pureYaw(const Mat4& T, double& yaw) {
  Mat3 R = T.topLeftCorner<3, 3>();
  for (int i = 0; i < 3; ++i) {
    const double n = R.col(i).norm();
    if (n <= 0) return false;
    R.col(i) /= n;  // drop a scale
  }
  if ((R.col(2) - Vec3::UnitZ()).norm() > 1e-6) return false;
  yaw = std::atan2(R(1, 0), R(0, 0));
  return true;
}

void meshPoints(const Scene& scene, const Object& o, std::vector<Vec3>& out) {
  const Mesh& m = scene.meshes.at(o.mesh);
  const Mat4& T = o.T_world_object;
  auto put = [&](const Vec3& p) { out.push_back(T.topLeftCorner<3, 3>() * p + T.block<3, 1>(0, 3)); };
  if (m.isSphere()) {
    const double r = m.sphere_radius;
    for (int i = 0; i < 8; ++i) put(Vec3(i & 1 ? r : -r, i & 2 ? r : -r, i & 4 ? r : -r));
    return;
  }
  for (const Vec3f& p : m.positions) put(p.cast<double>());
}

}  // namespace

std::array<Vec3, 8> OrientedBox::corners() const {
  std::array<Vec3, 8> c;
  const Mat3 R = q_world_box.toRotationMatrix();
  for (int i = 0; i < 8; ++i) {
    const Vec3 s(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    c[i] = centre + R * s.cwiseProduct(size);
  }
  return c;
}

double OrientedBox::yaw() const {
  const Vec3 x = q_world_box * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

OrientedBox OrientedBox::transformed(const Pose& T) const {
  OrientedBox b = *this;
  b.centre = T.q * centre + T.t;
  b.q_world_box = (T.q * q_world_box).normalized();
  return b;
}

OrientedBox gravityAlignedBox(const std::vector<Vec3>& points) {
  if (points.empty()) return {};
  double z0 = 1e300, z1 = -1e300;
  std::vector<P2> flat;
  flat.reserve(points.size());
  for (const Vec3& p : points) {
    z0 = std::min(z0, p.z());
    z1 = std::max(z1, p.z());
    flat.emplace_back(p.x(), p.y());
  }
  const std::vector<P2> hull = convexHull(std::move(flat));
  // The smallest enclosing rectangle has a side on a hull edge (Freeman and Shapira 1975).
  double best_yaw = 0;
  Rect best = rectAlong(hull, 1, 0);
  const size_t edges = hull.size() < 2 ? 0 : hull.size() == 2 ? 1 : hull.size();
  for (size_t i = 0; i < edges; ++i) {
    const P2 e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() <= 0) continue;
    double yaw = std::atan2(e.y(), e.x());
    // the same rectangle for yaw + k pi/2: keep yaw in [0, pi/2)
    yaw = std::fmod(yaw, std::numbers::pi / 2);
    if (yaw < 0) yaw += std::numbers::pi / 2;
    if (yaw >= std::numbers::pi / 2 - 1e-12) yaw = 0;
    const Rect r = rectAlong(hull, std::cos(yaw), std::sin(yaw));
    if (r.area < best.area * (1 - 1e-12)) {
      best = r;
      best_yaw = yaw;
    }
  }
  return boxFromRect(best, best_yaw, z0, z1);
}

std::vector<InstanceBox> instanceBoxes(const Scene& scene) {
  std::map<int, std::vector<int>> parts;  // instance -> object indices, in scene order
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].instance > 0) parts[scene.objects[i].instance].push_back(static_cast<int>(i));
  std::vector<InstanceBox> boxes;
  boxes.reserve(parts.size());
  std::vector<Vec3> pts;
  for (const auto& [instance, idx] : parts) {
    const Object& first = scene.objects[idx.front()];
    InstanceBox b;
    b.instance = instance;
    b.nyu40 = first.nyu40;
    b.name = first.name;
    b.kind = first.kind;
    b.room = first.room;
    b.first_object = idx.front();
    pts.clear();
    for (int i : idx) {
      b.moving |= scene.objects[i].moving();
      meshPoints(scene, scene.objects[i], pts);
    }
    b.box = gravityAlignedBox(pts);
    // Prefer the object's own heading when its axes bound the points nearly as tightly.
    double yaw = 0;
    if (!pts.empty() && pureYaw(first.T_world_object, yaw)) {
      std::vector<P2> flat;
      flat.reserve(pts.size());
      for (const Vec3& p : pts) flat.emplace_back(p.x(), p.y());
      const Rect own = rectAlong(flat, std::cos(yaw), std::sin(yaw));
      const double best_area = b.box.size.x() * b.box.size.y();
      if (own.area <= best_area * 1.01 + 1e-12)
        b.box = boxFromRect(own, yaw, b.box.centre.z() - b.box.size.z() / 2,
                            b.box.centre.z() + b.box.size.z() / 2);
    }
    boxes.push_back(std::move(b));
  }
  return boxes;
}

OrientedBox boxAt(const Scene& scene, const InstanceBox& b, double t_s) {
  const Object& o = scene.objects.at(b.first_object);
  if (!o.moving()) return b.box;
  // transformAt(t) = pose(t) * T_world_object: recover pose(t) as a rigid motion.
  const Mat4 motion = o.transformAt(t_s) * o.T_world_object.inverse();
  return b.box.transformed(Pose::fromMatrix(motion));
}

}  // namespace inet
