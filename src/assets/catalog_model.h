#pragma once
// A catalog piece made ready to place (issue 15): its OBJ read through Assimp from a cache
// folder the archive's files are extracted to once, turned by `modelRotation`, scaled to the
// catalog's size and put in the model frame of procedural/furniture.h (metres, +z up, origin at
// the centre of the footprint with the bottom at z = 0, the front facing -y), with materials,
// lights, collision boxes, physics estimates and its label.
//
// Sweet Home 3D's frame (the one `modelRotation` and the catalog sizes refer to): y up, the
// front towards +z, width along x, depth along z. Like Sweet Home 3D (ModelManager), the model
// is rotated, its bounding box centred, and each axis scaled to width, height and depth: the
// scale is not uniform when the catalog's size differs from the OBJ's proportions. Ours from
// theirs: (x, y, z) = (x', -z', y').
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/catalog_labels.h"
#include "assets/furniture_catalog.h"
#include "scene/assimp_importer.h"
#include "scene/scene.h"

namespace inet {

struct CatalogModel {
  std::string id;       ///< the piece's id
  std::string name;     ///< the piece's name
  std::string creator;  ///< for attribution (CC-BY)
  std::string license;
  std::string catalog;  ///< the catalog's name
  CatalogLabel label;
  /// The parts, one object per (node, material) of the OBJ, each with its own baked mesh and
  /// an identity transform, every object labelled label.nyu40 / label.kind with `part` the
  /// OBJ's group or material name; lamps' bulbs as point lights (Scene::lights). Mesh k has
  /// source Catalog (piece id, part k) and materials carry catalog_piece / catalog_material
  /// (ids "<piece id>/<MTL name>"), so a layout names them instead of writing them out.
  Scene parts;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< metres: width x, depth y, height z
  /// The extent of the OBJ after modelRotation, before scaling (in the file's units), whose
  /// proportions say how far the catalog size stretches the model.
  Eigen::Vector3d natural_extent = Eigen::Vector3d::Zero();
  /// How unevenly the catalog size stretches the model: the largest per-axis scale over the
  /// smallest (1 = proportions kept). A furnisher can pass over strongly deformed pieces.
  double stretch = 1.0;
  double drop_on_top_m = -1.0;  ///< where others are put on it (catalog), < 0 = not given
  double elevation_m = 0.0;                ///< default height of its bottom above the floor
  std::vector<Eigen::AlignedBox3d> hulls;  ///< one box per part (model frame)
  double mass_kg = 1.0;   ///< estimate (catalog_model.cpp: density by class x box volume)
  double friction = 0.2;  ///< estimate by class
  bool movable = true;
  ImportReport report;  ///< what reading the OBJ found (missing textures, ...)
};

/// Where extracted catalog models live: userCacheDir("sh3f") (core/atomic_file.h). One folder
/// per archive content checksum, so a changed archive never reads stale files.
std::filesystem::path catalogModelCache();

/// Extracts the files of `piece` (its model's folder for a multi-part model, else the model
/// file) to `cache_dir`/<checksum>/ once (written to a temporary folder and renamed, so a
/// crash never leaves a half model) and returns the OBJ's path there. Throws InputError
/// naming the archive and entry for an entry that would leave the folder ("..", absolute).
std::filesystem::path extractCatalogModel(const FurnitureCatalog& catalog,
                                          const CatalogPiece& piece,
                                          const std::filesystem::path& cache_dir);

/// The point lights of a lamp's bulbs (`piece.lights`) in the model frame above: Sweet Home
/// 3D's positions are cm from the left, FRONT and bottom; `category` (ours: floor_lamp,
/// table_lamp, ceiling_light, pendant_light, else 2 W/sr) sets the radiant intensity the
/// bulbs share; a grey catalog colour is a brightness hint (warm white, 2700 K), another keeps
/// its hue.
std::vector<Light> lampLights(const CatalogPiece& piece, const std::string& category);

/// Loads `piece` of `catalog` (see the top of this file). `cache_dir` "" = catalogModelCache().
/// Throws InputError naming the archive and "model#N" when the OBJ cannot be read, and
/// NoSurfaceError (core/error.h) when it holds no triangles.
CatalogModel loadCatalogModel(const FurnitureCatalog& catalog, const CatalogPiece& piece,
                              const std::filesystem::path& cache_dir = {});

}  // namespace inet
