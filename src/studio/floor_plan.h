#pragma once
// The floor plan the page draws under the keyframes: a raster of the layout's free space seen
// from above, made once when the layout loads (GET /api/layout/plan).
//
// One plan per floor level of the free space (FreeSpace::floorLevels: the rooms' floors, or the
// floors found in the geometry; a Sweet Home 3D home's levels, two storeys of a mesh scene), all
// on the same grid: cells of `cell_m` over every room's outline and 0.5 m around them (without
// rooms, the scene's bounds) in x and y; each cell's centre column is sampled at `height_m` above
// its floor on that level (the camera's usual height; the level's floor where the column has no
// floor of its own there, e.g. above a table or over a stairwell) and every 0.1 m from 0.2 m to
// 2.2 m above it (what a camera passing there could hit; at 0.1 m the grid's conservative
// distance may see the floor itself). One character per cell:
//   'o'  outside: not indoors (FreeSpace::isIndoors: outside the rooms, inside closed furniture)
//   '#'  occupied at height_m (walls, tall furniture)
//   'f'  free at height_m but occupied somewhere between 0.2 m and 2.2 m (tables, beds, sofas)
//   'b'  the clearance band: free, but closer than clearance_m to the geometry at height_m
//   '.'  free
// {"cell_m", "origin": [x, y] (centre of cell 0, 0), "nx", "ny", "level" (its index),
//  "levels": [every level's floor z, lowest first], "floor_z" (this level's), "height_m",
//  "clearance_m", "rooms": [ids of the rooms whose floor is this level's (within 0.5 m)],
//  "rows": [ny strings of nx characters, row j at y = origin y + j cell_m],
//  "tops": [the same shape: for 'f' cells 'a' + k, k decimetres the highest occupied sample
//           above the floor (a table's top, 'h' or 'i'); '-' elsewhere]}
// The grid's lower bound of the distance is used (conservative by up to two voxels); the
// design route checks keyframes and paths exactly.
#include <nlohmann/json.hpp>

#include <vector>

#include "scene/scene.h"
#include "trajectory/free_space.h"

namespace inet::studio {

struct FloorPlanOptions {
  double cell_m = 0.1;
  double height_m = 1.5;
  double clearance_m = 0.25;
  int max_cells = 1'000'000;  ///< the cell grows until the raster fits
};

/// The plan of floor level `level` (an index into space.floorLevels(); 0 when there are none,
/// and then the scene's lowest point is the floor).
nlohmann::json floorPlan(const Scene& scene, const FreeSpace& space, size_t level = 0,
                         const FloorPlanOptions& opt = {});
/// The plans of every level (at least one).
std::vector<nlohmann::json> floorPlans(const Scene& scene, const FreeSpace& space,
                                       const FloorPlanOptions& opt = {});

}  // namespace inet::studio
