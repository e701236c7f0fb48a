#pragma once
// Sweet Home 3D furniture catalogs (.sh3f): the real, free model libraries Debian packages as
// sweethome3d-furniture (about 820 models: CC0, CC-BY). A .sh3f is a zip holding
// PluginFurnitureCatalog.properties (java_properties.h), LICENSE.TXT and per model an OBJ with
// its MTL and textures. The keys are Sweet Home 3D's (DefaultFurnitureCatalog): per piece N
// `id#N`, `name#N`, `category#N`, `model#N`, `width#N`, `depth#N`, `height#N` (centimetres), ...
//
// Sizes and positions stay in the catalog's own units and frame here (centimetres; the piece's
// box seen from its front: width along x, depth along y from its back, height up); catalog_model.h
// converts to ours (metres, Z up, front facing -y).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "assets/java_properties.h"
#include "scene/scene.h"

namespace inet {

/// A light bulb of a lamp: position in cm from the piece's left side (x), back side (y) and
/// bottom (z) at the catalog size, sRGB colour, and diameter (cm, 0 = not given).
struct CatalogLightSource {
  Eigen::Vector3d position_cm = Eigen::Vector3d::Zero();
  Vec3f color{1.f, 1.f, 1.f};  ///< sRGB-encoded in [0, 1] as written ("#RRGGBB")
  double diameter_cm = 0.0;
};

/// One sash (hinged leaf) of a door or window: hinge position in cm (from the left, from the
/// back), leaf width (cm) and opening angles (radians, as written in the catalog).
struct CatalogSash {
  double x_axis_cm = 0, y_axis_cm = 0, width_cm = 0, start_angle = 0, end_angle = 0;
};

/// What a door or window needs to be cut into a wall.
struct CatalogDoorOrWindow {
  /// The hole in the wall: an SVG path in the unit square of the front face (x right, y down);
  /// empty = the whole front rectangle.
  std::string cut_out_shape;
  double wall_thickness_cm = 0.0;  ///< depth of the wall it is made for; 0 = its own depth
  double wall_distance_cm = 0.0;   ///< from the piece's back to the wall's back face
  std::vector<CatalogSash> sashes;
};

/// One model of a catalog, as its properties describe it.
struct CatalogPiece {
  int index = 0;         ///< N of its keys
  std::string id;        ///< "Kator Legaz#futon-couch": unique within the installed catalogs
  std::string name;      ///< "Futon couch"
  std::string category;  ///< Sweet Home 3D's: "Living room", "Kitchen", "Lights", ...
  std::vector<std::string> tags;
  std::string creator;      ///< author (attribution)
  std::string license;      ///< the piece's own licence, else its catalog's
  std::string model;        ///< archive entry of the OBJ (no leading '/')
  bool multi_part = false;  ///< the model's folder holds its MTL and textures
  double width_cm = 0, depth_cm = 0, height_cm = 0;  ///< > 0
  double elevation_cm = 0;            ///< height above the floor it is placed at by default
  double drop_on_top_elevation = -1;  ///< where others stand on it, as a share of height; < 0 none
  /// Rotates the OBJ's coordinates into Sweet Home 3D's (y up, front towards +z): row-major,
  /// v' = R v. Identity when not given.
  Eigen::Matrix3d model_rotation = Eigen::Matrix3d::Identity();
  bool movable = true;
  bool back_face_shown = false;
  std::optional<CatalogDoorOrWindow> door_or_window;
  std::vector<CatalogLightSource> lights;  ///< lamps
  std::string staircase_cut_out_shape;     ///< staircases: the hole in the floor above

  /// Not an exterior piece or a vehicle (the categories "Exterior" and "Vehicles").
  bool isInterior() const;
};

/// One .sh3f archive.
struct FurnitureCatalog {
  std::string path;                  ///< the archive
  std::string id;                    ///< "SweetHome3D#KatorLegazModels"
  std::string name;                  ///< "Kator Legaz catalog"
  std::string license;               ///< catalog-wide licence text
  std::string checksum;              ///< ZipArchive::contentChecksum (keys the model cache)
  std::vector<CatalogPiece> pieces;  ///< in index order
};

/// Reads the catalog `path`. Throws InputError naming the archive and the key (e.g.
/// "width#12") for a missing archive or properties file, a missing id/name/category/model or
/// size, a non-numeric or non-positive size, a malformed modelRotation, light or sash list,
/// a model entry the archive lacks, or an id used twice.
FurnitureCatalog readFurnitureCatalog(const std::string& path);

/// The catalog described by `props` (the parsed PluginFurnitureCatalog.properties of archive
/// `path`), with the checks of readFurnitureCatalog; `has_entry` says whether the archive holds
/// an entry. The checksum is left empty.
FurnitureCatalog catalogFromProperties(const JavaProperties& props, const std::string& path,
                                       const std::function<bool(const std::string&)>& has_entry);

/// The catalogs folder: `override_dir` when not empty, else $INTERIORNET_CATALOG, else
/// /usr/share/sweethome3d/furniture (Debian's sweethome3d-furniture).
std::string catalogDir(const std::string& override_dir = "");

/// Every *.sh3f in `dir`, sorted by file name. Throws InputError when `dir` is not a folder or
/// holds no catalog; a bad archive throws as readFurnitureCatalog does.
std::vector<FurnitureCatalog> readFurnitureCatalogs(const std::string& dir);

}  // namespace inet
