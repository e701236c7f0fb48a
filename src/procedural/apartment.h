#pragma once
// Procedural furnished apartments (issue 4): a floor plan (floorplan.h) built into walls with
// door and window openings, floors, ceilings and skirting, then furnished room by room from the
// furniture library (furniture.h) by per-room-type rules: functional groups (a bed between
// nightstands with lamps, a sofa facing a TV across a coffee table, a dining table with chairs,
// a desk with its chair, kitchen counters with sink, stove and fridge, toilet, basin and bath),
// tall pieces against walls and clear of windows, nothing in front of doorways, small clutter on
// support surfaces, a ceiling light in every room, and daylight (a Preetham sky and a sun)
// through the windows.
//
// Guarantees the builder checks as it goes (and tests check again on 1,000 seeds): no two
// pieces' collision hulls overlap by more than 1 cm; every piece is inside its room and stands on
// the floor, a support surface or a wall; at least 60 % of each room's floor stays free; every
// room stays reachable from the front door through free floor (a 0.1 m grid, cleared by a 0.25 m
// robot radius).
//
// Textures are procedural images (procedural_textures.h) written once per material under
// `texture_dir`; meshes of textured pieces carry texture coordinates in metres / tile size.
#include <filesystem>
#include <string>
#include <vector>

#include "procedural/floorplan.h"
#include "procedural/furniture.h"
#include "scene/scene.h"

namespace inet {

/// Where furniture comes from: our parametric library (furniture.h), the installed Sweet Home
/// 3D catalogs (assets/catalog_library.h) for every category a real model fits, or either at
/// random per piece. Catalog pieces are chosen among the interior models labelled with the
/// category whose size lies within the category's parametric range (0.7x its smallest to 1.4x
/// its largest per axis, with 5 cm of slack, or half the largest on thinner sides) and that
/// the catalog does not stretch by more than
/// 1.6x; doors, windows and curtains (cut to their openings) stay parametric. Small things
/// that stand in for a prop (CatalogLabel::slot: a teapot for a mug) fit when no side exceeds
/// 0.45 m and they are at most 0.5 m tall.
enum class FurnitureSource { Parametric, Catalog, Mixed };
/// "parametric", "catalog", "mixed"; InputError(field) otherwise.
FurnitureSource parseFurnitureSource(const std::string& name,
                                     const std::string& field = "--furniture");
const char* furnitureSourceName(FurnitureSource s);

struct ApartmentOptions {
  uint64_t seed = 0;
  int rooms = 0;           ///< 1..16; 0 = drawn from the room-count distribution
  int texture_size = 256;  ///< texels per side of the procedural textures
  bool daylight = true;    ///< sky and sun through the windows
  DecorStyle style = DecorStyle::Any;  ///< materials and colours (furniture.h)
  bool random_style = false;  ///< draw one of decorStyles() per seed (overrides `style`)
  FurnitureSource furniture = FurnitureSource::Parametric;
  std::string catalog_dir;  ///< catalogs folder for Catalog and Mixed ("" = catalogDir())
};

/// A placed piece of furniture: what the checks and statistics need.
struct PlacedPiece {
  std::string name;      ///< instance name in the scene ("sofa_3")
  std::string category;  ///< furniture category
  std::string catalog_piece;  ///< the catalog model's id, "" = parametric
  int room = -1;
  int instance = 0;
  std::vector<Eigen::AlignedBox3d> hulls;  ///< world-space collision boxes
  bool on_floor = false;                   ///< stands on the floor (footprint blocks cameras)
  bool flat = false;                       ///< rugs: on the floor but walkable
  /// What holds it up: "floor", "wall" (hung, incl. doors and windows in openings), "ceiling",
  /// or "support" (standing on piece `support` at height `support_z`).
  std::string rests_on = "floor";
  int support = -1;
  double support_z = 0.0;
};

struct Apartment {
  Scene scene;
  FloorPlan plan;
  std::vector<PlacedPiece> pieces;
};

/// Builds the apartment of `opt.seed`. Texture images go to `texture_dir` (created; the
/// scene's TextureRefs point there, `file` relative to `layout_dir`).
Apartment makeApartment(const ApartmentOptions& opt, const std::filesystem::path& layout_dir,
                        const std::filesystem::path& texture_dir);

/// Free-space reachability on a grid of `cell` metres over the plan: cells inside rooms or in
/// doorways, minus floor pieces' footprints grown by `radius`. Returns, per room, whether a free
/// cell of that room is reachable from the front door; `free_fraction` (if given) receives each
/// room's free floor fraction (footprints not grown).
std::vector<bool> reachableRooms(const Apartment& apt, double cell, double radius,
                                 std::vector<double>* free_fraction = nullptr);

}  // namespace inet
