#pragma once
// layout.json: our versioned scene description (DESIGN.md section 2; schema in docs/layout.md).
//
//   {"format": "interiornet-layout", "version": 1, "name": ...,
//    "meshes": [...], "materials": [...], "objects": [...], "lights": [...]}
//
// Reading validates everything before returning (STYLE.md section 4): types, unknown and missing
// keys, ranges, duplicate ids, references, transforms (Scene::validate) and referenced mesh files.
// Every problem is an InputError "file: field: problem" on one line, where field is a
// JSON-pointer-like path such as "objects[3].transform" or "line 4, column 17" for syntax errors.
//
// Writing is canonical: 2-space indent, keys in schema order, arrays of scalars on one line,
// every double printed as the shortest text that parses back to the same bits and every float
// (albedo, vertices) as the shortest text that parses back to the same float, and a trailing
// newline. So save(load(save(x))) == save(x) byte for byte.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// The value of the top-level "format" key.
inline constexpr const char* kLayoutFormat = "interiornet-layout";
/// The layout versions this build reads (and the one it writes, the last).
inline const std::vector<int>& supportedLayoutVersions() {
  static const std::vector<int> versions = {1};
  return versions;
}

/// Reads and validates the layout file `path`. Mesh files are resolved relative to the layout's
/// folder and loaded through Assimp. Throws InputError on any problem.
Scene loadLayout(const std::string& path);

/// Same as loadLayout for JSON already in memory; `path` names the source in errors and is the
/// base for relative mesh file paths (its folder).
Scene parseLayout(const std::string& text, const std::string& path);

/// Canonical layout text of `scene` (see above). File meshes are written by reference (their
/// MeshSource), primitives by name and parameters, other meshes inline. Throws InputError if the
/// scene cannot be written faithfully (fails Scene::validate, duplicate or empty ids, a sphere
/// that is not a "sphere" primitive).
std::string layoutToJson(const Scene& scene);

/// Writes layoutToJson(scene) to `path` atomically (a temporary renamed into place).
void saveLayout(const Scene& scene, const std::string& path);

}  // namespace inet
