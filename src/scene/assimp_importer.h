#pragma once
// Mesh-file import through Assimp (OBJ, glTF, PLY, FBX, ... anything Assimp reads).
//
// Two entry points:
//  - importMeshScene: a whole file becomes a Scene. Every (node, aiMesh) pair of the node tree is
//    one Object; nodes that reference the same aiMesh share one Mesh. Object names come from the
//    node (for OBJ the `o`/`g` name), labels from a LabelMap, instance ids from distinct names.
//  - loadMeshFile: a whole file (or one named part of it) merged into one object-space Mesh, for
//    layout.json meshes that reference a file.
//
// Axes and units: the world is right-handed, Z up, metres. A file with `up = 'y'` is rotated so
// that +Y becomes +Z (x -> x, y -> z, z -> -y); `scale` is metres per file unit. Both are applied
// to vertex positions (so meshes are in metres, Z up) and conjugated into node transforms
// (T' = C T C^-1, C = scale * R_up), so a rigid node transform stays rigid.
// Faces that are not triangles after triangulation (lines, points) are dropped and counted.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// How to read a mesh file into a Scene.
struct ImportOptions {
  double scale = 1.0;                          ///< metres per file unit, > 0
  /// The file's up axis: 'z', 'y', or 'a' (auto: detectUpAxis decides, and the report says how)
  char up = 'z';
  std::string label_map;                       ///< label map CSV path ("" = NYU40 names only)
  std::string default_category = "otherprop";  ///< NYU40 class for names nothing matches
  bool split_shells = true;  ///< split floors and ceilings out of wall objects (room_shell.h)
  /// Map the Phong parameters of MTL files (specular colour Ks, exponent Ns, opacity d) to our
  /// families instead of taking every material as Lambertian: see phongToMaterial. Off by
  /// default (scanned and CAD scenes often carry meaningless Ks); on for catalog models.
  bool phong_materials = false;
};

/// What an import did that a user may want to know about, reported once (not per object).
struct ImportReport {
  size_t objects = 0;                        ///< objects created
  size_t unmatched_objects = 0;              ///< objects that got default_category
  std::vector<std::string> unmatched_names;  ///< distinct unmatched names, in file order
  size_t dropped_faces = 0;                  ///< non-triangle faces (lines, points) skipped
  size_t clamped_materials = 0;              ///< materials whose diffuse colour left [0, 1]
  size_t flattened_triangles = 0;            ///< triangles whose vertex normals crossed a hard edge
  size_t skipped_textures = 0;  ///< textures missing, empty folders, or unreadable embedded ones
  std::vector<std::string> missing_textures;  ///< their names as written (up to a few)
  /// Textures not where the material said but found beside the model by file name (paths of
  /// the modeller's machine: "C:/Documents and Settings/.../wood.jpg")
  size_t relocated_textures = 0;
  size_t embedded_textures = 0;  ///< embedded images (glTF data URIs, .glb) written to the cache
  size_t ignored_bump_maps = 0;  ///< materials with a bump (height) map, which is not supported
  /// Materials without Ke whose ambient colour Ka exceeds 1 (no reflectance can): taken as
  /// emitted radiance, the way older OBJ files (Cornell boxes) give their light.
  std::vector<std::string> ka_emission_materials;
  size_t lights = 0;          ///< glTF KHR_lights_punctual lights imported (683 lm/W)
  size_t skipped_lights = 0;  ///< lights of other formats (units unknown) or without a node
  size_t split_shells = 0;  ///< wall objects that held the floor or ceiling too (room_shell.h)
  // OBJ files (scene/obj_prepass.h): what Assimp would have got wrong or said nothing about
  size_t obj_w_values = 0;                    ///< `v x y z w` lines whose w was dropped
  size_t obj_missing_normals = 0;  ///< face corners naming a normal the file lacks (dropped)
  size_t obj_leading_dots = 0;                ///< numbers like `.5` read as 0.5
  size_t obj_late_groups = 0;  ///< groups named after their faces (ObjPrepass::late_groups)
  std::vector<std::string> missing_mtllibs;   ///< `mtllib` files not found
  std::vector<std::string> grey_materials;    ///< `usemtl` names no library defines
  double extent_m = 0.0;   ///< largest side of the scene's bounds (a hint for a wrong --scale)
  char up = 'z';           ///< the up axis the scene was read with
  std::string up_reason;   ///< with up = 'a': why that axis (detectUpAxis)

  /// One line, findings separated by "; " (e.g. "12 objects (3 distinct names) matched no label
  /// and were labelled 'otherprop': lamp_a, ..."), or "" when there is nothing to warn about.
  std::string summary(const std::string& default_category) const;
};

/// The up axis of a mesh file, 'y' or 'z', and in `why` the rule that decided:
///  - glTF (.gltf, .glb): y, as its specification says;
///  - objects labelled floor or ceiling: the axis their triangles face along;
///  - otherwise the axis along which the most triangle area faces, of y and z: floors, ceilings
///    and table tops outweigh the walls of any one direction in an interior (a long narrow
///    corridor is the exception: give --up then).
/// `scene` is the file imported as Z-up (its own axes).
char detectUpAxis(const Scene& scene, const std::string& path, std::string* why);

/// Where images embedded in scene files are written once, as <hash>.<ext>:
/// $XDG_CACHE_HOME/interiornet/embedded, else ~/.cache/interiornet/embedded, else the temporary
/// folder. The same bytes give the same file, so reimporting writes nothing.
std::filesystem::path embeddedTextureCache();

/// What phong_materials does with one material (already holding the diffuse colour and
/// textures): opacity d < 0.99 makes a thin dielectric pane (glass; transmittance
/// (1 - d) + d Kd, IOR 1.5); else a specular colour with max(Ks) > 0.04 and Ns > 1 makes a
/// coated plastic of roughness (2 / (Ns + 2))^(1/4) (the Blinn-Phong exponent's usual GGX
/// alpha = sqrt(2 / (Ns + 2)), and alpha = roughness^2), clamped to [0.05, 1]; else it stays
/// Lambertian.
void phongToMaterial(const Vec3f& specular, float shininess, float opacity, Material& mat);

/// Imports the mesh file `path` as a Scene named after the file's stem. Throws InputError naming
/// the file when it is missing, unreadable, malformed (Assimp's message), has no triangles, when
/// the options are invalid, or (naming the CSV) when the label map is bad.
/// `report`, if given, receives the warnings summary.
Scene importMeshScene(const std::string& path, const ImportOptions& opt,
                      ImportReport* report = nullptr);

/// Loads `path` as one object-space Mesh (metres, Z up): every mesh instance of the file merged
/// with its node transform applied, or only the instances whose node or mesh is named
/// `mesh_name` (when not empty). Errors are thrown as InputError(where_file, where_field, ...)
/// so they point at the layout entry that asked for the file. The returned mesh has
/// source.kind == File with `path`, `scale`, `up` and `mesh_name` filled in; callers that resolved
/// a relative path should overwrite source.file with the path as written.
Mesh loadMeshFile(const std::string& path, double scale, char up, const std::string& mesh_name,
                  const std::string& where_file, const std::string& where_field);

}  // namespace inet
