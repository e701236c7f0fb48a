#pragma once
// Sweet Home 3D homes (.sh3d, issue 15 part 3): the archive's Home.xml (written by Sweet Home
// 3D 5.3 and later) read into plain records, in the file's own units and axes: centimetres,
// plan x right and y DOWN, elevations up, angles in radians. scene/ conversion is in
// sh3d_import.h; this reader only parses and checks.
//
// What is read: levels; walls (ends, thickness, height and height at end, arc extent, joins,
// colours and textures of both sides); rooms (points, name, floor and ceiling visibility,
// colours, textures); furniture, doors and windows, lights and furniture groups (flattened: a
// group's members are stored with absolute coordinates); material overrides; light sources;
// the compass; the observer camera, stored points of view and the video path. Elements and
// attributes Sweet Home 3D writes that we do not use (labels, dimension lines, print setup)
// are skipped.
//
// Errors: InputError(archive, "Home.xml <wall id='wall3'> xStart", problem): the element, its
// id when it has one, and the attribute. A legacy file (only the serialized `Home` entry, from
// Sweet Home 3D before 5.3) is refused with a message saying to re-save it.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace inet {

/// A texture as Sweet Home 3D tiles it: one image per `width` x `height` cm.
struct Sh3dTexture {
  std::string image;  ///< archive entry
  std::string name;
  double width_cm = 100, height_cm = 100;
  double angle = 0;  ///< radians
};

/// A colour override: AARRGGBB as written, turned into sRGB-encoded [0, 1].
using Sh3dColor = std::optional<Eigen::Vector3f>;

struct Sh3dLevel {
  std::string id, name;
  double elevation_cm = 0, floor_thickness_cm = 12, height_cm = 250;
  int elevation_index = 0;
  bool visible = true;
};

struct Sh3dWall {
  std::string id;
  int level = -1;  ///< index into Sh3dHome::levels, -1 = no levels
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();  ///< plan cm
  double thickness_cm = 0;
  std::optional<double> height_cm, height_at_end_cm;  ///< absent: the home's wall height
  double arc_extent = 0;                              ///< radians, 0 = straight
  int wall_at_start = -1, wall_at_end = -1;           ///< joined walls (indices)
  Sh3dColor left_color, right_color, top_color;
  std::optional<Sh3dTexture> left_texture, right_texture;
};

struct Sh3dRoom {
  std::string id, name;
  int level = -1;
  std::vector<Eigen::Vector2d> points;  ///< plan cm, as written
  bool floor_visible = true, ceiling_visible = true;
  Sh3dColor floor_color, ceiling_color;
  std::optional<Sh3dTexture> floor_texture, ceiling_texture;
};

struct Sh3dMaterial {
  std::string name;  ///< the model's material it overrides
  Sh3dColor color;
  std::optional<double> shininess;
  std::optional<Sh3dTexture> texture;
};

struct Sh3dLightSource {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< fractions of width, depth, height
  Eigen::Vector3f color{1, 1, 1};                      ///< sRGB-encoded
  double diameter = 0;                                 ///< fraction of the width
};

struct Sh3dSash {
  double x_axis = 0, y_axis = 0, width = 0, start_angle = 0, end_angle = 0;
};

enum class Sh3dPieceKind { Furniture, DoorOrWindow, Light };

/// A piece of furniture, door or window, or light (members of groups included, with the
/// group's name in `group`).
struct Sh3dPiece {
  std::string id, name, catalog_id, creator, license, group;
  Sh3dPieceKind kind = Sh3dPieceKind::Furniture;
  int level = -1;
  std::string model;  ///< archive entry: a bare OBJ ("12") or "12/name.obj" with its files
  Eigen::Matrix3d model_rotation = Eigen::Matrix3d::Identity();  ///< row-major 9 floats
  double x_cm = 0, y_cm = 0, elevation_cm = 0;  ///< centre of the footprint; bottom
  double angle = 0, pitch = 0, roll = 0;        ///< radians
  double width_cm = 0, depth_cm = 0, height_cm = 0;
  bool mirrored = false, visible = true, movable = true;
  bool back_face_shown = false;
  Sh3dColor color;
  std::optional<double> shininess;
  std::optional<Sh3dTexture> texture;
  std::vector<Sh3dMaterial> materials;
  // doors and windows
  double wall_thickness = 1, wall_distance = 0;  ///< fractions of depth
  bool wall_cut_out_on_both_sides = true;
  std::string cut_out_shape;  ///< SVG path in the unit square, "" = the whole rectangle
  std::vector<Sh3dSash> sashes;
  // lights
  double power = 0.5;  ///< 0..1
  std::vector<Sh3dLightSource> light_sources;
};

/// A camera as Sweet Home 3D stores it: eye at (x, y, z) cm (z above the ground, level
/// elevation included), yaw and pitch in radians, horizontal field of view.
struct Sh3dCamera {
  std::string name, attribute;  ///< "observerCamera", "storedCamera", "topCamera", video path
  double x_cm = 0, y_cm = 0, z_cm = 170;
  double yaw = 0, pitch = 0, field_of_view = 1.0995575;
  int64_t time_ms = 0;  ///< ms since 1970 (UTC): the sun's date and time
};

struct Sh3dCompass {
  double north_direction = 0;          ///< radians
  double latitude = 0, longitude = 0;  ///< radians
  std::string time_zone = "UTC";
};

struct Sh3dHome {
  std::string path;  ///< the archive
  std::string name;
  int version = 0;  ///< Sweet Home 3D's file version (6500 = 6.5)
  double wall_height_cm = 250;
  std::vector<Sh3dLevel> levels;
  std::vector<Sh3dWall> walls;
  std::vector<Sh3dRoom> rooms;
  std::vector<Sh3dPiece> pieces;
  std::optional<Sh3dCamera> observer;
  std::vector<Sh3dCamera> stored_cameras;  ///< stored points of view, in file order
  std::vector<Sh3dCamera> video_path;      ///< the environment's video cameras, in order
  Sh3dCompass compass;
  Eigen::Vector3f sky_color{0.8f, 0.89f, 0.99f}, ground_color{0.66f, 0.66f, 0.66f};
  std::string license, author;  ///< the home's own properties, when given

  /// The level's elevation in cm (0 without levels).
  double levelElevation(int level) const {
    return level >= 0 ? levels[size_t(level)].elevation_cm : 0.0;
  }
  /// The height of the level's rooms in cm (the home's wall height without levels).
  double levelHeight(int level) const {
    return level >= 0 ? levels[size_t(level)].height_cm : wall_height_cm;
  }
};

/// Parses Home.xml text; `where` names the archive in errors. Throws InputError.
Sh3dHome parseHomeXml(const std::string& xml, const std::string& where);

/// Opens a .sh3d archive and parses its Home.xml; also checks that every model and texture
/// entry the home names is in the archive. Throws InputError (see the top of this file).
Sh3dHome readSh3dHome(const std::string& path);

}  // namespace inet
