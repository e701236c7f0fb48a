#pragma once
// Mitsuba scene import: the XML scene files of Mitsuba 0.4-0.6 and Mitsuba 2/3 (the format
// rendering researchers keep validation scenes in, e.g. Bitterli's "Rendering resources") read
// into our Scene, plus the perspective sensor as a camera.json camera. docs/mitsuba.md has the
// full mapping table.
//
// What is read (names in either Mitsuba spelling, "toWorld" or "to_world"; mitsuba_xml.h):
//  - shapes: obj, ply (through Assimp), rectangle, cube, sphere, disk, cylinder; to_world,
//    face_normals, flip_normals, flip_tex_coords; a nested or referenced <bsdf>; an area
//    <emitter> (our emissive material, one-sided along the normal as Mitsuba's);
//  - BSDFs: diffuse, roughdiffuse, plastic, roughplastic, conductor, roughconductor, dielectric,
//    roughdielectric, thindielectric, difftrans, principled, phong, ward, and the wrappers
//    twosided, mask, bumpmap, normalmap, coating, blendbsdf, mixturebsdf; bitmap textures;
//  - emitters: area, point, spot, directional, constant, envmap, sun, sky, sunsky;
//  - the perspective (or thinlens) sensor with its film size and sample count.
// Mitsuba's GGX/Beckmann `alpha` is our roughness^2. What our model cannot hold is mapped to the
// nearest thing we have and listed once in MitsubaReport::approximations (never silently);
// unknown plugin types are listed there too rather than failing.
//
// Axes and units: Mitsuba scenes are unitless; the importer takes them as metres times `scale`.
// A file with `up = 'y'` (the default: most Mitsuba scenes are Y up) is turned so that +Y
// becomes +Z (x -> x, y -> z, z -> -y), as assimp_importer.h does. Mesh files keep their
// reference (MeshSource::File with that `up`) when nothing changes their vertices.
//
// Labels: each shape is its own instance. Its NYU40 class comes from a LabelMap matched against
// the shape's id, then its BSDF's id (the only semantics most Mitsuba files carry: "Walls",
// "Sofa", "TableWood"), then the mesh file's name; unmatched shapes get `default_category`.
//
// Errors: malformed XML, a missing or unknown version, missing files, bad numbers, broken
// references and the like are InputErrors naming the file and "line N <element ...>".
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "scene/scene.h"

namespace inet {

struct MitsubaOptions {
  char up = 'y';       ///< the file's up axis: 'y' or 'z'
  double scale = 1.0;  ///< metres per scene unit, > 0
  std::string label_map;                       ///< label map CSV ("" = NYU40 names only)
  std::string default_category = "otherprop";  ///< NYU40 class for names nothing matches
  /// Values of `$name` parameters; they override the file's <default> elements.
  std::map<std::string, std::string> parameters;
  /// false: read the XML alone (fuzzing): shapes that load a file and <include>s are skipped
  /// (and noted), texture and environment-map files are not checked.
  bool read_files = true;
};

/// What an import approximated or skipped, and which names matched no label.
struct MitsubaReport {
  size_t objects = 0;
  size_t unmatched_objects = 0;
  std::vector<std::string> unmatched_names;  ///< distinct names, in file order
  /// One line per kind of approximation, with what it applies to, e.g. "roughplastic
  /// 'nonlinear' ignored (3: Floor, TableWood, Paneling)".
  std::vector<std::string> approximations;
  /// One line, findings separated by "; ", or "" when there is nothing to warn about.
  std::string summary(const std::string& default_category) const;
};

/// The scene's perspective sensor as our pinhole camera (render/camera.h's camera.json).
struct MitsubaSensor {
  int width = 768, height = 576;  ///< the film (Mitsuba's hdrfilm defaults)
  double fx = 0, fy = 0;          ///< focal lengths in pixels (square pixels: fx == fy)
  double cx = 0, cy = 0;          ///< principal point, renderer convention (centre: width / 2)
  Pose T_world_camera;            ///< OpenCV axes (x right, y down, z forward), our world
  int spp = 0;                    ///< the sampler's sample count (0 = not given)
};

struct MitsubaScene {
  Scene scene;
  std::optional<MitsubaSensor> sensor;  ///< absent when the file has no perspective sensor
  MitsubaReport report;
};

/// Reads the scene file `path` (mesh, texture and include paths relative to its folder).
MitsubaScene readMitsubaScene(const std::string& path, const MitsubaOptions& opt);
/// The same on XML text in memory; `path` names it in errors and is the base of relative paths.
MitsubaScene parseMitsubaScene(const std::string& text, const std::string& path,
                               const MitsubaOptions& opt);
/// readMitsubaScene's scene alone; `report`, if given, receives the warnings.
Scene importMitsubaScene(const std::string& path, const MitsubaOptions& opt,
                         MitsubaReport* report = nullptr);

/// The sensor as camera.json text (width, height, fx, fy, cx, cy, cam_to_world), which
/// `interiornet render --camera` reads (render/camera.h).
std::string mitsubaCameraJson(const MitsubaSensor& sensor, const std::string& source);

/// Our conductor preset nearest to a conductor of normal-incidence reflectance `f0` (linear
/// RGB): the preset whose own F0 is closest, and in `tint` the per-channel factor (<= 1) that
/// brings the preset's F0 to `f0` where it can. Used for Mitsuba's eta/k and named materials.
std::string nearestMetal(const Vec3f& f0, Vec3f* tint);
/// Normal-incidence reflectance of our conductor presets (metalNames() order), linear RGB.
const std::vector<Vec3f>& metalPresetF0();

}  // namespace inet
