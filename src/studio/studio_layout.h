#pragma once
// The layout a studio session works on: loaded once at start, read-only afterwards, shared by
// every request and job (the free space's queries are const and thread-safe).
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

#include "pipeline/settings.h"
#include "scene/scene.h"
#include "trajectory/free_space.h"

namespace inet::studio {

struct StudioLayout {
  std::string source;        ///< what was given: a file path, builtin:room, procedural:<seed>
  SceneSource scene_source;  ///< how it was loaded (a sequence job loads it again the same way)
  Scene scene;
  std::unique_ptr<FreeSpace> space;
  nlohmann::json summary;             ///< layoutSummary()
  std::vector<nlohmann::json> plans;  ///< floorPlans(): one per floor level (studio/floor_plan.h)
  double load_s = 0.0;  ///< loading the scene and building the free space took this long
};

/// Loads `src` (SceneSource::load: the scene with its lights, as `layout show` reads it) and
/// builds its free space. Throws InputError as the loaders do.
std::shared_ptr<const StudioLayout> loadStudioLayout(const SceneSource& src);

/// What `interiornet layout show` prints, as JSON: name, source, meshes, triangles, materials,
/// objects (parts), instances, emissive parts, analytic lights, bounds {min, max} (m), the
/// instances per NYU40 class [{id, name, instances}], rooms [{id, type, area_m2, floor_z,
/// ceiling_z, outline [[x, y], ...]}] (a layout.json's; empty for mesh scenes) and, given
/// `space`, the free space {voxel_m, grid, open, floor_levels, indoor_volume_m3,
/// free_volume_m3 (at the default 0.25 m clearance)}.
nlohmann::json layoutSummary(const Scene& s, const std::string& source, const FreeSpace* space);

}  // namespace inet::studio
