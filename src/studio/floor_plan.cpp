#include "studio/floor_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace inet::studio {

namespace {

struct Column {
  char code = 'o';
  char top = '-';  ///< 'f': 'a' + the highest occupied height in decimetres
};

Column classifyColumn(const FreeSpace& space, double x, double y, double floor_z,
                      const FloorPlanOptions& opt) {
  // a column with no floor of its own on this level (above a table, whose underside leaves less
  // than the 1 m a floor needs above it; over a stairwell, where the floor found is a lower
  // level's) is sampled from the level's floor
  double floor = space.floorBelow(Vec3(x, y, floor_z + opt.height_m));
  if (std::isnan(floor) || floor < floor_z - 0.5) floor = floor_z;
  const Vec3 at(x, y, floor + opt.height_m);
  Column c;
  if (!space.isIndoors(at)) return c;
  const double d = space.lowerBound(at);
  if (d <= 0) {
    c.code = '#';
    return c;
  }
  // from 0.2 m: the grid's lower bound is up to two voxels (0.1 m) short, so at 0.1 m the floor
  // itself may count as occupied, depending on how the level's height falls on the voxels
  for (int k = 22; k >= 2; --k)
    if (space.lowerBound(Vec3(x, y, floor + 0.1 * k)) <= 0) {
      c.code = 'f';
      c.top = static_cast<char>('a' + k);
      return c;
    }
  c.code = d < opt.clearance_m ? 'b' : '.';
  return c;
}

}  // namespace

nlohmann::json floorPlan(const Scene& scene, const FreeSpace& space, size_t level,
                         const FloorPlanOptions& opt) {
  auto [lo, hi] = scene.bounds();
  if (!scene.rooms.empty()) {  // the rooms, not the ground around the building
    Vec3 rlo = Vec3::Constant(1e30), rhi = Vec3::Constant(-1e30);
    for (const Room& r : scene.rooms)
      for (const auto& p : r.outline) {
        rlo = rlo.cwiseMin(Vec3(p.x(), p.y(), lo.z()));
        rhi = rhi.cwiseMax(Vec3(p.x(), p.y(), hi.z()));
      }
    const Vec3 margin(0.5, 0.5, 0.0);
    lo = lo.cwiseMax(rlo - margin);
    hi = hi.cwiseMin(rhi + margin);
  }
  double cell = opt.cell_m;
  auto count = [&](double extent) {
    return std::max(1, static_cast<int>(std::ceil(extent / cell)));
  };
  while (static_cast<double>(count(hi.x() - lo.x())) * count(hi.y() - lo.y()) > opt.max_cells)
    cell *= 1.25;
  const int nx = count(hi.x() - lo.x()), ny = count(hi.y() - lo.y());
  const double x0 = lo.x() + cell / 2, y0 = lo.y() + cell / 2;
  const std::vector<double>& levels = space.floorLevels();
  INET_CHECK(level == 0 || level < levels.size());
  const double floor_z = levels.empty() ? lo.z() : levels[level];
  nlohmann::json rooms = nlohmann::json::array();
  for (const Room& r : scene.rooms)
    if (std::abs(r.floor_z - floor_z) <= 0.5) rooms.push_back(r.id);
  nlohmann::json rows = nlohmann::json::array(), tops = nlohmann::json::array();
  for (int j = 0; j < ny; ++j) {
    std::string row(static_cast<size_t>(nx), 'o'), top(static_cast<size_t>(nx), '-');
    for (int i = 0; i < nx; ++i) {
      const Column c = classifyColumn(space, x0 + i * cell, y0 + j * cell, floor_z, opt);
      row[i] = c.code;
      top[i] = c.top;
    }
    rows.push_back(std::move(row));
    tops.push_back(std::move(top));
  }
  return {{"cell_m", cell},
          {"origin", {x0, y0}},
          {"nx", nx},
          {"ny", ny},
          {"level", level},
          {"levels", levels.empty() ? std::vector<double>{floor_z} : levels},
          {"floor_z", floor_z},
          {"height_m", opt.height_m},
          {"clearance_m", opt.clearance_m},
          {"rooms", std::move(rooms)},
          {"rows", std::move(rows)},
          {"tops", std::move(tops)}};
}

std::vector<nlohmann::json> floorPlans(const Scene& scene, const FreeSpace& space,
                                       const FloorPlanOptions& opt) {
  std::vector<nlohmann::json> plans;
  for (size_t level = 0; level < std::max<size_t>(1, space.floorLevels().size()); ++level)
    plans.push_back(floorPlan(scene, space, level, opt));
  return plans;
}

}  // namespace inet::studio
