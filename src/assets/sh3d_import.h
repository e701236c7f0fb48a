#pragma once
// A Sweet Home 3D home (.sh3d) as a Scene (issue 15 part 3; the reader is sh3d_home.h).
//
// Axes: Sweet Home 3D's plan is centimetres with y DOWN; ours is metres, z up:
// (x, y, z) = (x_cm, -y_cm, elevation_cm) / 100, so the plan seen from above looks as it does
// on Sweet Home 3D's screen.
//
// What becomes what:
//  - walls: closed prisms between their side lines, mitred where walls join (wallAtStart /
//    wallAtEnd), round walls (arcExtent) as 24 straight pieces per half turn, sloped walls
//    (heightAtEnd) with a sloped top; each side its own colour or texture; doors and windows
//    cut holes of their cut-out shape (an SVG path, assets/svg_path.h) through every wall
//    their footprint overlaps, with reveals (the hole's sides through the wall);
//  - rooms: floors and ceilings triangulated from the room polygon (concave ones included),
//    at the level's elevation and elevation + height; a Room of our type by its name (in
//    English, French, Italian, German, Spanish or Chinese; living room otherwise); a level
//    with walls and no room gets rooms from the faces its wall centre lines close;
//  - furniture, doors, windows and lights: their models from the archive, read like catalog
//    models (assets/catalog_model.h: modelRotation, size, materials, physics), mirrored,
//    turned (angle, pitch, roll) and placed; colour and per-material overrides applied;
//    labelled by the catalog rule table (the installed catalog's category when its id is
//    known); a light's sources become point lights scaled by its power;
//  - a ceiling light (a point light) in every room no lamp of the home lights;
//  - daylight: a Preetham sky and a sun where the compass (latitude, longitude, north) and the
//    observer camera's date and time put it, and a ground plane;
//  - levels Sweet Home 3D hides (visible='false') are left out unless asked for.
#include <string>
#include <vector>

#include "assets/sh3d_home.h"
#include "core/pose.h"
#include "scene/scene.h"

namespace inet {

struct Sh3dImportOptions {
  std::string catalog_dir;     ///< installed catalogs, for categories by catalog id ("" = default)
  bool daylight = true;        ///< sun, sky and ground from the compass and the camera's time
  bool hidden_levels = false;  ///< also import levels the home hides
  bool room_lights = true;     ///< a ceiling light in each room no lamp lights
};

struct Sh3dImportReport {
  size_t levels = 0, walls = 0, rooms = 0, pieces = 0, doors_windows = 0, lights = 0;
  size_t rooms_from_walls = 0;  ///< rooms made from the faces walls close (homes without rooms)
  size_t holes = 0;             ///< door and window cut-outs made in walls
  size_t hidden = 0;            ///< pieces left out: invisible, or on a hidden level
  size_t unlabelled = 0;        ///< pieces labelled by the default rule only
  size_t empty_models = 0;      ///< pieces left out because their model draws no surface
  size_t added_lights = 0;      ///< rooms without a lamp given a ceiling light
  std::vector<std::string> room_names_untyped;  ///< names no room type matched
  /// For each piece placed: its index in Sh3dHome::pieces and the instance id of its objects.
  std::vector<std::pair<size_t, int>> piece_instances;
  std::string summary() const;
};

/// A camera of the home as a pose (OpenCV axes: x right, y down, z forward) with its name
/// and horizontal field of view.
struct Sh3dView {
  std::string name;
  Pose T_world_camera;
  double hfov_rad = 1.0;
};

/// The home as a Scene. Throws InputError (sh3d_home.h) for a malformed home.
Scene sh3dToScene(const Sh3dHome& home, const Sh3dImportOptions& opt,
                  Sh3dImportReport* report = nullptr);

/// readSh3dHome + sh3dToScene.
Scene importSh3d(const std::string& path, const Sh3dImportOptions& opt,
                 Sh3dImportReport* report = nullptr);

/// The home's views as a camera path: the video path when it has one, else the stored points
/// of view, else the observer camera.
std::vector<Sh3dView> sh3dViews(const Sh3dHome& home);

/// Our room type for a room name ("" when nothing matches).
std::string sh3dRoomType(const std::string& name);

}  // namespace inet
