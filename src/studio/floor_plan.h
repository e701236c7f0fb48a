#pragma once
// The floor plan the page draws under the keyframes: a raster of the layout's free space seen
// from above, made once when the layout loads (GET /api/layout/plan).
//
// Cells of `cell_m` over the rooms' outlines and 0.5 m around them (without rooms, the scene's
// bounds) in x and y; each cell's centre column is sampled at
// `height_m` above its floor (the camera's usual height; the lowest floor level where the
// column has no floor of its own, e.g. above a table) and every 0.1 m from 0.1 m to 2.2 m above
// it (what a camera passing there could hit). One character per cell:
//   'o'  outside: not indoors (FreeSpace::isIndoors: outside the rooms, inside closed furniture)
//   '#'  occupied at height_m (walls, tall furniture)
//   'f'  free at height_m but occupied somewhere between 0.1 m and 2.2 m (tables, beds, sofas)
//   'b'  the clearance band: free, but closer than clearance_m to the geometry at height_m
//   '.'  free
// {"cell_m", "origin": [x, y] (centre of cell 0, 0), "nx", "ny", "floor_z", "height_m",
//  "clearance_m", "rows": [ny strings of nx characters, row j at y = origin y + j cell_m],
//  "tops": [the same shape: for 'f' cells 'a' + k, k decimetres the highest occupied sample
//           above the floor (a table's top, 'h' or 'i'); '-' elsewhere]}
// The grid's lower bound of the distance is used (conservative by up to two voxels); the
// design route checks keyframes and paths exactly.
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "trajectory/free_space.h"

namespace inet::studio {

struct FloorPlanOptions {
  double cell_m = 0.1;
  double height_m = 1.5;
  double clearance_m = 0.25;
  int max_cells = 1'000'000;  ///< the cell grows until the raster fits
};

nlohmann::json floorPlan(const Scene& scene, const FreeSpace& space,
                         const FloorPlanOptions& opt = {});

}  // namespace inet::studio
