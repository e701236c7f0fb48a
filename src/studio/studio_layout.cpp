#include "studio/studio_layout.h"

#include <chrono>
#include <map>

#include "scene/nyu40.h"
#include "studio/floor_plan.h"
#include "trajectory/random_trajectory.h"

namespace inet::studio {

std::shared_ptr<const StudioLayout> loadStudioLayout(const SceneSource& src) {
  const auto t0 = std::chrono::steady_clock::now();
  auto layout = std::make_shared<StudioLayout>();
  layout->source =
      src.path.empty() ? (src.default_apartment ? "builtin:apartment" : "builtin:room") : src.path;
  layout->scene_source = src;
  layout->scene = src.load();
  layout->space = std::make_unique<FreeSpace>(layout->scene, FreeSpaceOptions{}, layout->source);
  layout->summary = layoutSummary(layout->scene, layout->source, layout->space.get());
  layout->plans = floorPlans(layout->scene, *layout->space);
  layout->load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return layout;
}

nlohmann::json layoutSummary(const Scene& s, const std::string& source, const FreeSpace* space) {
  using nlohmann::json;
  const auto [lo, hi] = s.bounds();
  std::map<int, int> class_of_instance, instances_per_class;
  int emissive = 0;
  for (const Object& o : s.objects) {
    class_of_instance[o.instance] = o.nyu40;
    if (o.material >= 0 && s.materials[o.material].isEmissive()) ++emissive;
  }
  for (const auto& [instance, label] : class_of_instance) ++instances_per_class[label];
  json classes = json::array();
  for (const auto& [label, count] : instances_per_class)
    classes.push_back(
        {{"id", label}, {"name", std::string(nyu40Name(label))}, {"instances", count}});
  json rooms = json::array();
  for (const Room& r : s.rooms) {
    json outline = json::array();
    for (const auto& p : r.outline) outline.push_back({p.x(), p.y()});
    rooms.push_back({{"id", r.id},
                     {"type", r.type},
                     {"area_m2", r.area()},
                     {"floor_z", r.floor_z},
                     {"ceiling_z", r.ceiling_z},
                     {"outline", outline}});
  }
  json j = {{"name", s.name},
            {"source", source},
            {"meshes", s.meshes.size()},
            {"triangles", s.triangleCount()},
            {"materials", s.materials.size()},
            {"objects", s.objects.size()},
            {"instances", class_of_instance.size()},
            {"emissive_objects", emissive},
            {"lights", s.lights.size()},
            {"bounds", {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}}},
            {"classes", classes},
            {"rooms", rooms}};
  if (space != nullptr) {
    const double clearance = RandomTrajectoryOptions{}.clearance;
    j["free_space"] = {{"voxel_m", space->voxel()},
                       {"grid", {space->nx(), space->ny(), space->nz()}},
                       {"open", space->isOpen()},
                       {"floor_levels", space->floorLevels()},
                       {"indoor_volume_m3", space->indoorVolume()},
                       {"clearance_m", clearance},
                       {"free_volume_m3", space->freeVolume(clearance)}};
  }
  return j;
}

}  // namespace inet::studio
