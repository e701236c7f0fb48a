#pragma once
// A pass over an OBJ file's text before Assimp reads it, for what real OBJ files do that
// Assimp 5.2 gets wrong or reports badly (found on tinyobjloader's test models and others):
//  - `v x y z w`: Assimp divides x, y and z by w (a rational curve's weight); for polygons the
//    weight means nothing (tinyobjloader ignores it), so the 4th value is dropped and counted;
//  - numbers written with a leading dot (`.5`, `-.25`): Assimp's parser misreads them and then
//    fails with "vertex index out of range"; they are written `0.5`, `-0.25`;
//  - a face index of 0 or beyond the vertices read so far: Assimp says "Invalid face index" or
//    "OBJ-file is too small" with no line; here it is an InputError naming the line;
//  - `mtllib` files that do not exist: Assimp falls back to a grey default silently; they are
//    listed, with the materials that get the default;
//  - group names written after their faces: McGuire's Computer Graphics Archive files (the
//    Cornell box in ../shared) start each object with `usemtl shortBox`, its faces, and only
//    then `g shortBox`, so the faces fall into the group before (the short box was a wall). A
//    `usemtl NAME` inside a group of another name, where a group NAME is declared later in the
//    file, starts that group there (a `g NAME` line is put before it) and is counted. A file
//    that truly puts material M's faces in group G and declares a group M later is read the
//    same way: rare, and said in the import report;
//  - faces of one or two vertices (`f 12 40`, edges some exporters write among the faces):
//    Assimp keeps them as faces its own validation then rejects ("is a LINE but
//    mPrimitiveTypes does not report the LINE flag"), failing the whole file; they are
//    rewritten as `l` lines, which are dropped like every line;
//  - a face corner naming a normal that does not exist (`81//125` in a file with no `vn`, in
//    Sweet Home 3D's own window models): the corner loses its normal reference (`81`), as
//    Sweet Home 3D's reader ignores it, instead of the whole file failing.
// The text is only rewritten when something above needs it; Assimp then reads the rewritten
// text in place of the file (ObjPrepass::text), and every other file (MTL, textures) as usual.
#include <string>
#include <vector>

namespace inet {

struct ObjPrepass {
  std::string text;      ///< the rewritten file text; empty when the file needs no rewrite
  size_t w_values = 0;   ///< `v` lines whose 4th value (w) was dropped
  size_t leading_dots = 0;                   ///< numbers given a leading 0
  size_t line_faces = 0;   ///< `f` lines of fewer than 3 vertices rewritten as `l` lines
  size_t missing_normals = 0;  ///< face corners naming a normal beyond those read (dropped)
  size_t late_groups = 0;  ///< `g NAME` lines put before faces whose group is declared later
  std::vector<std::string> missing_mtllibs;  ///< as written in the file
  std::vector<std::string> grey_materials;   ///< `usemtl` names no readable library defines
};

/// Reads `path` (an OBJ file) and checks it as above. InputError(path, "line N", ...) for a
/// face index that cannot be right.
ObjPrepass prepassObj(const std::string& path);

}  // namespace inet
