#pragma once
// 3D-FRONT import: a house JSON (Alibaba's 3D-FRONT release) as a Scene with rooms.
//
// What is read:
//  - `mesh`: the architecture (walls, floors, ceilings, baseboards, doors and windows as
//    triangle soups); its flat `xyz` and `faces` arrays (numbers or, in some files, numeric
//    strings), with the mesh `type` giving the NYU40 class (WallInner -> wall, Floor -> floor,
//    Ceiling -> ceiling, Door -> door, Window -> window, Cabinet -> cabinet, ...);
//  - `material`: colours (sRGB 0-255, decoded to linear albedo);
//  - `furniture`: 3D-FUTURE models by `jid`, with `category`, `size`/`bbox`. When a model folder
//    is given and has `<jid>/raw_model.obj`, the model is imported; otherwise the piece becomes
//    a labelled placeholder box of its bounding box (the importer reports how many);
//  - `scene.room[]`: room type (mapped to our 16 types), and the placed children (`ref`, `pos`,
//    `rot` quaternion x y z w, `scale`); a room's outline is the bounding rectangle of its floor
//    meshes.
// Axes: 3D-FRONT is metres, +Y up; the scene is converted to Z up (x -> x, y -> z, z -> -y).
// 3D-FRONT has no lights: one ceiling point light per room is added so the house renders.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

struct Front3dOptions {
  std::string models_dir;  ///< 3D-FUTURE model folder ("" = placeholders only)
  std::string label_map;   ///< CSV 'category,nyu40' overriding the built-in table
  bool add_lights = true;  ///< a point light under each room's ceiling
};

struct Front3dReport {
  size_t rooms = 0, meshes = 0, furniture = 0;
  size_t placeholders = 0;                        ///< furniture placed as boxes (no model file)
  size_t missing_refs = 0;                        ///< room children that name nothing in the file
  std::vector<std::string> unmatched_categories;  ///< labelled otherprop
  /// One line for the user ("" when there is nothing to say).
  std::string summary() const;
};

/// Imports the house `path`. Throws InputError(path, field, problem) for a missing or malformed
/// file (field names the JSON path, e.g. "mesh[12].xyz[7]").
Scene importFront3d(const std::string& path, const Front3dOptions& opt,
                    Front3dReport* report = nullptr);

}  // namespace inet
