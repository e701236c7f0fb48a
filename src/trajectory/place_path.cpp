#include "trajectory/place_path.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace inet {

namespace {

/// How many of `points` (turned by yaw c, s and shifted by t) are free; stops counting as soon
/// as it cannot reach `need`.
size_t countFree(const std::vector<Vec3>& points, double c, double s, const Vec3& t,
                 const FreeSpace& space, double clearance, size_t need) {
  size_t free = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const Vec3 q(c * p.x() - s * p.y() + t.x(), s * p.x() + c * p.y() + t.y(), p.z() + t.z());
    free += space.lowerBound(q) >= clearance;
    if (free + (points.size() - 1 - i) < need) return free;  // cannot win any more
  }
  return free;
}

}  // namespace

PathPlacement placePath(const Trajectory& path, const FreeSpace& space,
                        const PlacePathOptions& opt, const std::string& source) {
  INET_CHECK(opt.yaws >= 1 && opt.max_anchors >= 1 && opt.max_samples >= 1);
  PathPlacement out;
  if (path.poses.empty()) return out;
  // the scored poses, relative to the path's horizontal centroid
  std::vector<Vec3> points;
  const size_t n = path.poses.size(), m = std::min(n, opt.max_samples);
  for (size_t k = 0; k < m; ++k)
    points.push_back(path.poses[m == 1 ? 0 : k * (n - 1) / (m - 1)].T_world_camera.t);
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  centroid.z() = 0.0;
  for (Vec3& p : points) p -= centroid;
  size_t before = 0;
  for (const Vec3& p : points) before += space.lowerBound(p + centroid) >= opt.clearance;
  out.free_before = static_cast<double>(before) / static_cast<double>(points.size());
  out.free_after = out.free_before;
  if (before == points.size()) return out;  // already in free space: left as it is

  // anchors: free voxel centres at camera heights, thinned evenly
  std::vector<FreeSpace::FreeVoxel> anchors = space.freeCentres(opt.clearance, 0.3, 2.5);
  if (anchors.empty())
    throw InputError(source, "--place-trajectory",
                     "the scene has no free space to place the camera path in");
  if (anchors.size() > opt.max_anchors) {
    std::vector<FreeSpace::FreeVoxel> thin;
    for (size_t k = 0; k < opt.max_anchors; ++k)
      thin.push_back(anchors[k * anchors.size() / opt.max_anchors]);
    anchors = std::move(thin);
  }
  // the best candidate so far must beat the file's own frame
  size_t best = before;
  double best_yaw = 0.0;
  Vec3 best_t = Vec3::Zero();
  for (int y = 0; y < opt.yaws && best < points.size(); ++y) {
    const double yaw = 2.0 * M_PI * y / opt.yaws, c = std::cos(yaw), s = std::sin(yaw);
    for (const FreeSpace::FreeVoxel& a : anchors) {
      const Vec3 t(a.centre.x(), a.centre.y(), a.floor_z);
      const size_t f = countFree(points, c, s, t, space, opt.clearance, best + 1);
      if (f > best) {
        best = f, best_yaw = yaw, best_t = t;
        if (best == points.size()) break;
      }
    }
  }
  if (best == before) return out;  // nothing does better than the file's own frame
  out.moved = true;
  out.free_after = static_cast<double>(best) / static_cast<double>(points.size());
  out.yaw_deg = best_yaw * 180.0 / M_PI;
  // T: p -> R (p - centroid) + t
  const Quat q(Eigen::AngleAxisd(best_yaw, Vec3::UnitZ()));
  out.T_scene_file = Pose{q, best_t - (q * centroid)};
  return out;
}

Trajectory transformed(const Trajectory& path, const Pose& T) {
  Trajectory out = path;
  for (TimedPose& p : out.poses) p.T_world_camera = T * p.T_world_camera;
  return out;
}

}  // namespace inet
