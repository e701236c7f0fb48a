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

/// Openings narrower than twice this close when a mesh scene's indoors are found (m).
constexpr double kClosingRadius = 0.6;

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
    std::tie(lo, hi) = boundsWithoutHugePlanes(scene, tris);
    if (!(lo.x() <= hi.x()))
      throw InputError(source, "geometry",
                       "every object of the scene is wider than 50 m (a ground, a sky dome: no "
                       "room to move in); if the file is in centimetres or millimetres, give "
                       "--scale 0.01 or 0.001");
    // room for cameras at up to 2 m (and their clearance) above low scenes without a ceiling
    hi.z() = std::max(hi.z(), lo.z() + 2.8);
  }
  // a mesh scene's margin leaves room round the geometry for the closing of its openings below
  const double margin = scene.rooms.empty() ? kClosingRadius + 0.2 : 0.1;
  lo -= Vec3::Constant(margin);
  hi += Vec3::Constant(margin);
  OccupancyGrid grid = voxelizeTriangles(tris, lo, hi, opt.voxel, opt.max_voxels);
  voxel_ = grid.voxel;
  nx_ = grid.nx;
  ny_ = grid.ny;
  nz_ = grid.nz;
  origin_ = grid.origin;
  const size_t count = grid.size();
  const std::vector<uint8_t>& occupied = grid.occupied;

  // ---- exact EDT of the occupancy, separably along x, y, z; outdoors is forced to 0 after ----
  // "no geometry on this line" is a large finite value (not infinity, which would make the
  // parabola intersections NaN); it loses against every real distance
  const double none = 1e20;
  std::vector<double> sq(count);
  for (size_t id = 0; id < count; ++id) sq[id] = occupied[id] ? 0.0 : none;
  // squared distances (in voxels) to the voxels where `field` is 0, in place
  auto transform = [&](std::vector<double>& field) {
    auto pass = [&](int n, int lines_a, int lines_b, auto at) {
      tbb::parallel_for(0, lines_b, [&](int b) {
        std::vector<double> f(n), d(n), z(n + 1);
        std::vector<int> v(n);
        for (int a = 0; a < lines_a; ++a) {
          for (int q = 0; q < n; ++q) f[q] = field[at(q, a, b)];
          edt1d(f.data(), n, d.data(), v.data(), z.data());
          for (int q = 0; q < n; ++q) field[at(q, a, b)] = d[q];
        }
      });
    };
    pass(nx_, ny_, nz_, [&](int q, int a, int b) { return index(q, a, b); });
    pass(ny_, nx_, nz_, [&](int q, int a, int b) { return index(a, q, b); });
    pass(nz_, nx_, ny_, [&](int q, int a, int b) { return index(a, b, q); });
  };
  transform(sq);

  // ---- indoors ----
  std::vector<uint8_t> indoor(count, 0);
  // ---- keep the big connected regions: the insides of closed objects (a wardrobe, a sofa's
  // box, a wall or a floor slab modelled as a closed box) are enclosed too, but no camera can
  // get there. With `by_room`, a region's size is its room for a camera: its voxels at least
  // 0.3 m from the geometry (a slab's or a wall's inside has none, however large); otherwise
  // its volume. Keeps the biggest region and any other of at least `keep_m3`; returns the
  // biggest one's size (m^3).
  const double roomy_sq = std::pow(0.3 / voxel_, 2);  // sq is in voxels^2
  auto keepBigRegions = [&](bool by_room, double keep_m3) {
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
        sizes[id] += !by_room || sq[v] >= roomy_sq;
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
    const size_t keep = static_cast<size_t>(keep_m3 / (voxel_ * voxel_ * voxel_));
    for (size_t id = 0; id < count; ++id)
      if (comp[id] >= 0 && sizes[comp[id]] != biggest && sizes[comp[id]] < keep) indoor[id] = 0;
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
    // Flood from the grid's border: what the flood cannot reach is enclosed. The flood goes
    // only where the geometry is more than kClosingRadius away, and what it reached is then
    // widened by that radius: a morphological closing, so that a doorway or a window hole
    // (up to 2 x 0.6 m wide) does not let the outside in, while the outside still reaches
    // every outer face of the walls.
    const double r2 = std::pow(kClosingRadius / voxel_, 2);
    std::vector<uint8_t> outside(count, 0);
    std::vector<size_t> stack;
    auto seed = [&](int i, int j, int k) {
      size_t id = index(i, j, k);
      if (sq[id] > r2 && !outside[id]) {
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
    std::vector<double> to_outside(count);
    for (size_t id = 0; id < count; ++id) to_outside[id] = outside[id] ? 0.0 : none;
    transform(to_outside);
    for (size_t id = 0; id < count; ++id) indoor[id] = to_outside[id] > r2;
  }
  // An open scene (a room with holes for windows or missing walls, a room without a ceiling,
  // furniture on a plate) encloses no room for a camera but perhaps a cupboard's inside. Then
  // what is roofed counts: the free voxels with geometry both above and below them in their
  // column (SceneNet's kitchen2 has three walls, but its floor and ceiling). A scene is open
  // when its enclosed room is less than 1 m^3 or a quarter of its roofed room; with less than
  // 1 m^3 of roofed room too (no ceiling at all) and nothing enclosed, everything in the box
  // counts. Either way the insides of closed objects (under 1 m^3) do not.
  const double enclosed_room = keepBigRegions(true, 2.0);
  if (scene.rooms.empty()) {
    const std::vector<uint8_t> enclosed = indoor;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        int top = -1, bottom = nz_;
        for (int k = 0; k < nz_; ++k)
          if (occupied[index(i, j, k)]) top = k, bottom = std::min(bottom, k);
        for (int k = 0; k < nz_; ++k) indoor[index(i, j, k)] = k > bottom && k < top;
      }
    const double roofed_room = keepBigRegions(true, 2.0);
    if (enclosed_room >= 1.0 && enclosed_room >= 0.25 * roofed_room) {
      indoor = enclosed;
    } else if (roofed_room >= 1.0) {
      open_ = true;
    } else {
      // nothing roomy anywhere: a tight but closed scene stays what it encloses (so that the
      // error says it is too tight), an open one counts whole
      indoor = enclosed;
      if (keepBigRegions(false, 1.0) < 1.0) {
        open_ = true;
        std::fill(indoor.begin(), indoor.end(), 1);
        keepBigRegions(false, 1.0);
      }
    }
  }

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
  // the middle of what an indoor camera sees of the walls: occupied voxels with an indoor free
  // neighbour beside them (not above or below: floors and ceilings run on under a missing wall)
  Vec3 sum = Vec3::Zero();
  size_t walls = 0;
  for (int k = 0; k < nz_; ++k)
    for (int j = 1; j + 1 < ny_; ++j)
      for (int i = 1; i + 1 < nx_; ++i) {
        if (!occupied[index(i, j, k)]) continue;
        const bool faces_indoors =
            dist_[index(i - 1, j, k)] > 0.f || dist_[index(i + 1, j, k)] > 0.f ||
            dist_[index(i, j - 1, k)] > 0.f || dist_[index(i, j + 1, k)] > 0.f;
        if (faces_indoors) sum += origin_ + voxel_ * Vec3(i, j, k), ++walls;
      }
  if (walls > 0) indoor_centre_ = sum / static_cast<double>(walls);
  if (!scene.rooms.empty())
    findRoomFloors(scene);
  else
    findMeshFloors(occupied, indoor);
}

void FreeSpace::findRoomFloors(const Scene& scene) {
  const double widen = 0.15;  // as for "indoors": doorways lie in the walls
  std::vector<std::vector<float>> per_column(static_cast<size_t>(nx_) * ny_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const Eigen::Vector2d p = (origin_ + voxel_ * Vec3(i, j, 0)).head<2>();
      std::vector<float>& floors = per_column[i + static_cast<size_t>(nx_) * j];
      for (const Room& r : scene.rooms) {
        bool in = insidePolygon(p, r.outline);
        for (size_t e = 0; !in && e < r.outline.size(); ++e)
          in = pointSegmentDistance(p, r.outline[e], r.outline[(e + 1) % r.outline.size()]) <=
               widen;
        if (in) floors.push_back(static_cast<float>(r.floor_z));
      }
      std::sort(floors.begin(), floors.end());
      floors.erase(std::unique(floors.begin(), floors.end()), floors.end());
    }
  for (const Room& r : scene.rooms) floor_levels_.push_back(r.floor_z);
  std::sort(floor_levels_.begin(), floor_levels_.end());
  floor_levels_.erase(std::unique(floor_levels_.begin(), floor_levels_.end()),
                      floor_levels_.end());
  floor_start_.assign(1, 0);
  for (const auto& f : per_column) {
    column_floors_.insert(column_floors_.end(), f.begin(), f.end());
    floor_start_.push_back(static_cast<uint32_t>(column_floors_.size()));
  }
}

void FreeSpace::findMeshFloors(const std::vector<uint8_t>& occupied,
                               const std::vector<uint8_t>& indoor) {
  floors_from_geometry_ = true;
  // every indoor surface top (k of the free voxel on it); those with at least 1 m of free space
  // above them give the area per height from which the levels are found (floor under a desk
  // is a floor surface of its column, but only open floor says where the floors are)
  const int min_free = static_cast<int>(std::ceil(1.0 / voxel_));
  const double cell = voxel_ * voxel_;
  std::vector<double> area(nz_, 0.0);
  std::vector<std::vector<int>> tops(static_cast<size_t>(nx_) * ny_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      for (int k = 1; k < nz_; ++k) {
        if (!occupied[index(i, j, k - 1)] || occupied[index(i, j, k)] || !indoor[index(i, j, k)])
          continue;
        tops[i + static_cast<size_t>(nx_) * j].push_back(k);
        int run = 0;
        while (k + run < nz_ && !occupied[index(i, j, k + run)] && run < min_free) ++run;
        if (run >= min_free) area[k] += cell;
      }
  // levels: runs of heights whose tops (within a voxel) cover >= 2 m^2 and 20 % of the most
  // covered height; in each run the height with the most area (ties: the lower); each level at
  // least 2 m above the one under it
  std::vector<double> band(nz_, 0.0);
  for (int k = 0; k < nz_; ++k)
    for (int d = -1; d <= 1; ++d)
      if (k + d >= 0 && k + d < nz_) band[k] += area[k + d];
  const double most = band.empty() ? 0.0 : *std::max_element(band.begin(), band.end());
  std::vector<int> levels;
  for (int k = 0; k < nz_;) {
    if (!(band[k] >= 2.0 && band[k] >= 0.2 * most)) {
      ++k;
      continue;
    }
    int peak = k;
    for (; k < nz_ && band[k] >= 2.0 && band[k] >= 0.2 * most; ++k)
      if (area[k] > area[peak]) peak = k;
    if (levels.empty() || (peak - levels.back()) * voxel_ >= 2.0) levels.push_back(peak);
  }
  // a voxel's surface is within half a voxel diagonal of its centre: the floor surface lies
  // about one voxel under the first free voxel
  auto surfaceZ = [&](int k) { return origin_.z() + voxel_ * (k - 1); };
  for (int k : levels) floor_levels_.push_back(surfaceZ(k));
  floor_start_.assign(1, 0);
  for (const std::vector<int>& column : tops) {
    for (int k : column)
      for (int l : levels)
        if (std::abs(k - l) <= 1) {
          column_floors_.push_back(static_cast<float>(surfaceZ(k)));
          break;
        }
    floor_start_.push_back(static_cast<uint32_t>(column_floors_.size()));
  }
}

double FreeSpace::floorBelow(const Vec3& p) const {
  const int i = static_cast<int>(std::lround((p.x() - origin_.x()) / voxel_));
  const int j = static_cast<int>(std::lround((p.y() - origin_.y()) / voxel_));
  double best = std::numeric_limits<double>::quiet_NaN();
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return best;
  const size_t c = i + static_cast<size_t>(nx_) * j;
  for (uint32_t f = floor_start_[c]; f < floor_start_[c + 1]; ++f)
    if (column_floors_[f] <= p.z() + 0.05) best = column_floors_[f];
  return best;
}

double FreeSpace::ceilingAbove(const Vec3& p) const {
  const Vec3 g = (p - origin_) / voxel_;
  const int i = static_cast<int>(std::lround(g.x())), j = static_cast<int>(std::lround(g.y()));
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return std::numeric_limits<double>::quiet_NaN();
  for (int k = std::max(0, static_cast<int>(std::lround(g.z()))); k < nz_; ++k)
    if (dist_[index(i, j, k)] == 0.f) return origin_.z() + voxel_ * k;
  return std::numeric_limits<double>::quiet_NaN();
}

bool FreeSpace::isIndoors(const Vec3& p) const {
  const Vec3 g = (p - origin_) / voxel_;
  const int i = static_cast<int>(std::lround(g.x())), j = static_cast<int>(std::lround(g.y())),
            k = static_cast<int>(std::lround(g.z()));
  if (i < 0 || j < 0 || k < 0 || i >= nx_ || j >= ny_ || k >= nz_) return false;
  return dist_[index(i, j, k)] >= 0.f;
}

bool FreeSpace::seesGeometry(const Vec3& p, const Vec3& dir, double max_range) const {
  const double n = dir.norm();
  if (!(n > 0)) return false;
  const Vec3 d = dir / n;
  for (double t = 0.0; t <= max_range;) {
    const Vec3 g = (p + t * d - origin_) / voxel_;
    const int i = static_cast<int>(std::lround(g.x())), j = static_cast<int>(std::lround(g.y())),
              k = static_cast<int>(std::lround(g.z()));
    if (i < 0 || j < 0 || k < 0 || i >= nx_ || j >= ny_ || k >= nz_) return false;
    const float v = dist_[index(i, j, k)];
    if (v < 0.f) return false;
    if (v == 0.f) return true;
    t += std::max(voxel_, static_cast<double>(v) - voxel_);
  }
  return false;
}

double FreeSpace::indoorVolume() const {
  size_t n = 0;
  for (float d : dist_) n += d > 0.f;
  return static_cast<double>(n) * voxel_ * voxel_ * voxel_;
}

double FreeSpace::freeVolume(double clearance) const {
  const double h2 = voxel_ * std::sqrt(3.0);
  size_t n = 0;
  for (float d : dist_) n += d > 0.f && d - h2 >= clearance;
  return static_cast<double>(n) * voxel_ * voxel_ * voxel_;
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

std::vector<FreeSpace::FreeVoxel> FreeSpace::freeCentres(double clearance, double h_lo,
                                                         double h_hi) const {
  std::vector<FreeVoxel> out;
  const double h2 = voxel_ * std::sqrt(3.0);
  for (int k = 0; k < nz_; ++k)
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const double c = dist_[index(i, j, k)] - h2;
        if (!(c >= clearance)) continue;
        const Vec3 centre = origin_ + voxel_ * Vec3(i, j, k);
        const double floor = floorBelow(centre);
        if (!(centre.z() - floor >= h_lo && centre.z() - floor <= h_hi)) continue;  // NaN: none
        out.push_back({centre, c, floor});
      }
  return out;
}

}  // namespace inet
