#include "trajectory/free_space.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <fmt/format.h>

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

struct PointQueryData {
  const WorldTriangles* tris;
  Vec3 best;
};

bool pointQueryCallback(RTCPointQueryFunctionArguments* args) {
  auto* data = static_cast<PointQueryData*>(args->userPtr);
  const Tri& t = data->tris->triangles[args->primID];
  const auto& P = data->tris->positions;
  Vec3 p(args->query->x, args->query->y, args->query->z);
  Vec3 q = closestPointOnTriangle(p, P[t[0]].cast<double>(), P[t[1]].cast<double>(),
                                  P[t[2]].cast<double>());
  double d = (q - p).norm();
  if (d < args->query->radius) {
    args->query->radius = static_cast<float>(d);
    data->best = q;
    return true;  // the query sphere shrank
  }
  return false;
}

/// 1-D squared Euclidean distance transform of f (n samples, unit spacing) into d
/// (Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled Functions", 2012).
/// Written here because no Debian-packaged library offers the exact separable transform on a
/// plain array (OpenCV's is 2-D only, OpenVDB's is a narrow band).
void edt1d(const double* f, int n, double* d, int* v, double* z) {
  const double inf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -inf;
  z[1] = inf;
  for (int q = 1; q < n; ++q) {
    double s;
    while (true) {
      s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
      if (s > z[k] || k == 0) break;
      --k;
    }
    if (s <= z[k]) {  // k == 0 and the new parabola is lower everywhere
      v[0] = q;
      z[1] = inf;
      continue;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = inf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

double pointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  Eigen::Vector2d ab = b - a;
  double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
  return (a + t * ab - p).norm();
}

bool insidePolygon(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& poly) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
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

ExactDistance::ExactDistance(WorldTriangles tris) : tris_(std::move(tris)) {
  device_ = rtcNewDevice("threads=1");  // point queries run on the caller's thread anyway
  INET_CHECK_MSG(device_ != nullptr, "rtcNewDevice failed");
  scene_ = rtcNewScene(device_);
  if (!tris_.triangles.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), tris_.positions.size()));
    for (size_t i = 0; i < tris_.positions.size(); ++i)
      for (int c = 0; c < 3; ++c) v[3 * i + c] = tris_.positions[i][c];
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tris_.triangles.size()));
    for (size_t i = 0; i < tris_.triangles.size(); ++i)
      for (int c = 0; c < 3; ++c) idx[3 * i + c] = tris_.triangles[i][c];
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
}

ExactDistance::~ExactDistance() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

Vec3 ExactDistance::closestPoint(const Vec3& p, double max_radius) const {
  RTCPointQuery query;
  query.x = static_cast<float>(p.x());
  query.y = static_cast<float>(p.y());
  query.z = static_cast<float>(p.z());
  query.time = 0.f;
  query.radius = static_cast<float>(max_radius);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  PointQueryData data{&tris_, p};
  rtcPointQuery(scene_, &query, &context, pointQueryCallback, &data);
  return data.best;
}

double ExactDistance::distance(const Vec3& p, double max_radius) const {
  Vec3 q = closestPoint(p, max_radius);
  return q == p ? max_radius : (q - p).norm();
}

FreeSpace::FreeSpace(const Scene& scene, const FreeSpaceOptions& opt, const std::string& source)
    : exact_(std::make_unique<ExactDistance>(worldTriangles(scene))) {
  INET_CHECK(opt.voxel > 0 && opt.max_voxels >= 1);
  const WorldTriangles& tris = exact_->triangles();
  if (tris.triangles.empty())
    throw InputError(source, "geometry", "the scene has no triangles to find free space in");

  // ---- the domain: the rooms, or the geometry without building-sized planes (ground, sky) ----
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  if (!scene.rooms.empty()) {
    for (const Room& r : scene.rooms) {
      for (const auto& p : r.outline) {
        lo = lo.cwiseMin(Vec3(p.x(), p.y(), r.floor_z));
        hi = hi.cwiseMax(Vec3(p.x(), p.y(), r.ceiling_z));
      }
    }
    lo.head<2>() -= Eigen::Vector2d::Constant(0.3);
    hi.head<2>() += Eigen::Vector2d::Constant(0.3);
  } else {
    std::vector<Vec3> obj_lo(scene.objects.size(), lo), obj_hi(scene.objects.size(), hi);
    for (size_t t = 0; t < tris.triangles.size(); ++t)
      for (int c = 0; c < 3; ++c) {
        Vec3 p = tris.positions[tris.triangles[t][c]].cast<double>();
        obj_lo[tris.object[t]] = obj_lo[tris.object[t]].cwiseMin(p);
        obj_hi[tris.object[t]] = obj_hi[tris.object[t]].cwiseMax(p);
      }
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      if (!(obj_lo[o].x() <= obj_hi[o].x())) continue;
      if ((obj_hi[o] - obj_lo[o]).head<2>().maxCoeff() > 50.0) continue;  // a ground plane
      lo = lo.cwiseMin(obj_lo[o]);
      hi = hi.cwiseMax(obj_hi[o]);
    }
    if (!(lo.x() <= hi.x()))
      throw InputError(source, "geometry", "the scene is only planes larger than 50 m");
    // room for cameras at up to 2 m (and their clearance) above low scenes without a ceiling
    hi.z() = std::max(hi.z(), lo.z() + 2.8);
  }
  lo -= Vec3::Constant(0.1);
  hi += Vec3::Constant(0.1);
  voxel_ = opt.voxel;
  auto cells = [&](double v) {
    Eigen::Array3d n = ((hi - lo) / v).array().ceil() + 1;
    return n;
  };
  while (cells(voxel_).prod() > opt.max_voxels) voxel_ *= 1.25;
  Eigen::Array3d n = cells(voxel_);
  nx_ = static_cast<int>(n.x());
  ny_ = static_cast<int>(n.y());
  nz_ = static_cast<int>(n.z());
  origin_ = lo;
  const size_t count = static_cast<size_t>(nx_) * ny_ * nz_;

  // ---- occupancy: voxels whose centre lies within h of a triangle ----
  const double h = voxel_ * std::sqrt(3.0) / 2.0;
  std::vector<uint8_t> occupied(count, 0);
  tbb::parallel_for(size_t(0), tris.triangles.size(), [&](size_t t) {
    const Tri& tri = tris.triangles[t];
    const Vec3 a = tris.positions[tri[0]].cast<double>(), b = tris.positions[tri[1]].cast<double>(),
               c = tris.positions[tri[2]].cast<double>();
    Vec3 tlo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(h);
    Vec3 thi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(h);
    Eigen::Vector3i i0 = ((tlo - origin_) / voxel_).array().ceil().cast<int>().max(0);
    Eigen::Vector3i i1 = ((thi - origin_) / voxel_).array().floor().cast<int>();
    i1 = i1.cwiseMin(Eigen::Vector3i(nx_ - 1, ny_ - 1, nz_ - 1));
    Vec3 normal = (b - a).cross(c - a);
    const double area2 = normal.norm();
    if (area2 > 0) normal /= area2;
    for (int k = i0.z(); k <= i1.z(); ++k)
      for (int j = i0.y(); j <= i1.y(); ++j)
        for (int i = i0.x(); i <= i1.x(); ++i) {
          const Vec3 p = origin_ + voxel_ * Vec3(i, j, k);
          if (area2 > 0 && std::abs(normal.dot(p - a)) > h) continue;
          if ((closestPointOnTriangle(p, a, b, c) - p).squaredNorm() > h * h) continue;
          std::atomic_ref<uint8_t>(occupied[index(i, j, k)]).store(1, std::memory_order_relaxed);
        }
  });

  // ---- indoors ----
  std::vector<uint8_t> indoor(count, 0);
  // ---- keep the big connected regions: the insides of closed objects (a wardrobe, a sofa's
  // box) are enclosed too, but no camera can get there. Returns the biggest region's volume.
  auto keepBigRegions = [&]() {
    std::vector<int> comp(count, -1);
    std::vector<size_t> sizes, stack;
    for (size_t start = 0; start < count; ++start) {
      if (!indoor[start] || occupied[start] || comp[start] >= 0) continue;
      const int id = static_cast<int>(sizes.size());
      sizes.push_back(0);
      comp[start] = id;
      stack.push_back(start);
      while (!stack.empty()) {
        size_t v = stack.back();
        stack.pop_back();
        ++sizes[id];
        const int i = static_cast<int>(v % nx_), j = static_cast<int>((v / nx_) % ny_),
                  k = static_cast<int>(v / (static_cast<size_t>(nx_) * ny_));
        auto visit = [&](int a, int b, int c) {
          if (a < 0 || b < 0 || c < 0 || a >= nx_ || b >= ny_ || c >= nz_) return;
          size_t u = index(a, b, c);
          if (!indoor[u] || occupied[u] || comp[u] >= 0) return;
          comp[u] = id;
          stack.push_back(u);
        };
        visit(i - 1, j, k), visit(i + 1, j, k), visit(i, j - 1, k), visit(i, j + 1, k);
        visit(i, j, k - 1), visit(i, j, k + 1);
      }
    }
    const size_t biggest = sizes.empty() ? 0 : *std::max_element(sizes.begin(), sizes.end());
    const size_t room_sized = static_cast<size_t>(20.0 / (voxel_ * voxel_ * voxel_));
    for (size_t id = 0; id < count; ++id)
      if (comp[id] >= 0 && sizes[comp[id]] != biggest && sizes[comp[id]] < room_sized)
        indoor[id] = 0;
    return biggest * voxel_ * voxel_ * voxel_;
  };

  if (!scene.rooms.empty()) {
    // a room's outline runs along the inner faces of its walls; doorways lie in the walls, so
    // the outlines are widened by 0.15 m (walls are thinner than 0.3 m)
    const double widen = 0.15;
    tbb::parallel_for(0, ny_, [&](int j) {
      for (int i = 0; i < nx_; ++i) {
        Eigen::Vector2d p = (origin_ + voxel_ * Vec3(i, j, 0)).head<2>();
        for (const Room& r : scene.rooms) {
          bool in = insidePolygon(p, r.outline);
          for (size_t e = 0; !in && e < r.outline.size(); ++e)
            in = pointSegmentDistance(p, r.outline[e], r.outline[(e + 1) % r.outline.size()]) <=
                 widen;
          if (!in) continue;
          for (int k = 0; k < nz_; ++k) {
            double z = origin_.z() + voxel_ * k;
            if (z >= r.floor_z && z <= r.ceiling_z) indoor[index(i, j, k)] = 1;
          }
        }
      }
    });
  } else {
    // flood the free voxels from the grid's border: what the flood cannot reach is enclosed
    std::vector<uint8_t> outside(count, 0);
    std::vector<size_t> stack;
    auto seed = [&](int i, int j, int k) {
      size_t id = index(i, j, k);
      if (!occupied[id] && !outside[id]) {
        outside[id] = 1;
        stack.push_back(id);
      }
    };
    for (int k = 0; k < nz_; ++k)
      for (int j = 0; j < ny_; ++j)
        for (int i = 0; i < nx_; ++i)
          if (i == 0 || j == 0 || k == 0 || i == nx_ - 1 || j == ny_ - 1 || k == nz_ - 1)
            seed(i, j, k);
    while (!stack.empty()) {
      size_t id = stack.back();
      stack.pop_back();
      int i = static_cast<int>(id % nx_), j = static_cast<int>((id / nx_) % ny_),
          k = static_cast<int>(id / (static_cast<size_t>(nx_) * ny_));
      if (i > 0) seed(i - 1, j, k);
      if (i + 1 < nx_) seed(i + 1, j, k);
      if (j > 0) seed(i, j - 1, k);
      if (j + 1 < ny_) seed(i, j + 1, k);
      if (k > 0) seed(i, j, k - 1);
      if (k + 1 < nz_) seed(i, j, k + 1);
    }
    for (size_t id = 0; id < count; ++id) indoor[id] = !outside[id];
  }
  // an open scene (a room without a ceiling, furniture on a plate) encloses nothing room-sized
  // (4 m^3, a small toilet): then everything in the box counts
  if (keepBigRegions() < 4.0 && scene.rooms.empty()) {
    std::fill(indoor.begin(), indoor.end(), 1);
    keepBigRegions();
  }

  // ---- exact EDT of the occupancy, separably along x, y, z; outdoors is forced to 0 after ----
  // "no geometry on this line" is a large finite value (not infinity, which would make the
  // parabola intersections NaN); it loses against every real distance
  const double none = 1e20;
  std::vector<double> sq(count);
  for (size_t id = 0; id < count; ++id) sq[id] = occupied[id] ? 0.0 : none;
  auto pass = [&](int n, int lines_a, int lines_b, auto at) {
    tbb::parallel_for(0, lines_b, [&](int b) {
      std::vector<double> f(n), d(n), z(n + 1);
      std::vector<int> v(n);
      for (int a = 0; a < lines_a; ++a) {
        for (int q = 0; q < n; ++q) f[q] = sq[at(q, a, b)];
        edt1d(f.data(), n, d.data(), v.data(), z.data());
        for (int q = 0; q < n; ++q) sq[at(q, a, b)] = d[q];
      }
    });
  };
  pass(nx_, ny_, nz_, [&](int q, int a, int b) { return index(q, a, b); });
  pass(ny_, nx_, nz_, [&](int q, int a, int b) { return index(a, q, b); });
  pass(nz_, nx_, ny_, [&](int q, int a, int b) { return index(a, b, q); });
  const double far = voxel_ * (nx_ + ny_ + nz_);
  // the grid's faces count as obstacles too: an open scene (no walls on a side) must not let a
  // camera sit at the edge of the grid, where every step leaves it
  dist_.assign(count, -1.f);
  for (int k = 0; k < nz_; ++k)
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const size_t id = index(i, j, k);
        if (!indoor[id] && !occupied[id]) continue;
        const int border = std::min({i, j, k, nx_ - 1 - i, ny_ - 1 - j, nz_ - 1 - k});
        dist_[id] = static_cast<float>(std::min({far, std::sqrt(sq[id]) * voxel_, border * voxel_}));
      }
}

double FreeSpace::field(const Vec3& p) const {
  Vec3 g = (p - origin_) / voxel_;
  Eigen::Vector3i i0 = g.array().floor().cast<int>();
  if ((i0.array() < 0).any() || i0.x() + 1 >= nx_ || i0.y() + 1 >= ny_ || i0.z() + 1 >= nz_)
    return -1.0;
  Vec3 f = g - i0.cast<double>();
  double acc = 0.0;
  for (int c = 0; c < 8; ++c) {
    int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    double w = (dx ? f.x() : 1 - f.x()) * (dy ? f.y() : 1 - f.y()) * (dz ? f.z() : 1 - f.z());
    float v = dist_[index(i0.x() + dx, i0.y() + dy, i0.z() + dz)];
    if (v < 0.f) return -1.0;  // a corner outdoors: no claim of clearance
    acc += w * v;
  }
  return acc;
}

double FreeSpace::lowerBound(const Vec3& p) const {
  return std::max(0.0, field(p) - voxel_ * std::sqrt(3.0));
}

bool FreeSpace::hasClearance(const Vec3& p, double clearance) const {
  const double f = field(p);
  if (f < 0.0) return false;
  if (f - voxel_ * std::sqrt(3.0) >= clearance) return true;
  return exact_->distance(p, clearance + 1.0) >= clearance;
}

Vec3 FreeSpace::gradient(const Vec3& p) const {
  // central differences over a whole voxel: the interpolated field is continuous, so this is
  // continuous in p too (a half-voxel step would be piecewise constant)
  const double e = voxel_;
  Vec3 g;
  for (int c = 0; c < 3; ++c) {
    Vec3 d = Vec3::Zero();
    d[c] = e;
    g[c] = (std::max(0.0, field(p + d)) - std::max(0.0, field(p - d))) / (2 * e);
  }
  return g;
}

std::vector<FreeSpace::FreeVoxel> FreeSpace::freeCentres(double clearance, double z_lo,
                                                         double z_hi) const {
  std::vector<FreeVoxel> out;
  const double h2 = voxel_ * std::sqrt(3.0);
  for (int k = 0; k < nz_; ++k) {
    double z = origin_.z() + voxel_ * k;
    if (z < z_lo || z > z_hi) continue;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        if (const double c = dist_[index(i, j, k)] - h2; c >= clearance)
          out.push_back({origin_ + voxel_ * Vec3(i, j, k), c});
  }
  return out;
}

}  // namespace inet
