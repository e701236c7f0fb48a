#pragma once
// Mitsuba BSDFs and textures -> our materials (part of the Mitsuba importer, mitsuba_importer.h;
// internal to src/scene). The mapping table with its approximations is in docs/mitsuba.md.
#include <map>
#include <set>
#include <string>

#include "scene/mitsuba_xml.h"
#include "scene/scene.h"

namespace inet::mitsuba {

/// Converts BSDF elements into scene.materials, each element once.
struct MaterialContext {
  MaterialContext(Scene& scene, Notes& notes, bool read_files)
      : scene(scene), notes(notes), read_files(read_files) {}
  Scene& scene;
  Notes& notes;
  bool read_files;
  std::map<const void*, int> by_element;  ///< <bsdf> element -> material index (-1: null BSDF)
  std::set<std::string> ids;              ///< material ids in use
  int default_material = -1;

  /// A material id not used yet: `base`, else base_2, base_3, ...
  std::string uniqueId(const std::string& base);
};

/// Index into scene.materials of the material for <bsdf> element `bsdf` (converted on first
/// use), or -1 for Mitsuba's null BSDF (an invisible surface). `owner` names the shape, for the
/// id of an anonymous BSDF.
int materialOf(const Plugin& bsdf, MaterialContext& ctx, const std::string& owner);
/// Mitsuba's BSDF for a shape that names none: diffuse with reflectance 0.5.
int defaultMaterial(MaterialContext& ctx);
/// The image a bitmap texture reads, resolved against its file's folder; InputError when the
/// file is missing (and files are read). Empty when the format is one we cannot read (noted).
TextureRef bitmapFile(const Plugin& texture, MaterialContext& ctx, const std::string& subject);

}  // namespace inet::mitsuba
