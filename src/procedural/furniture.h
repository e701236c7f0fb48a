#pragma once
// Parametric furniture library (issue 4; InteriorNet, Li et al. BMVC 2018, section 3.1): more
// than 40 categories covering the NYU40 classes that occur indoors, built from the unit
// primitives of scene/primitives.h in real-world dimensions drawn from realistic ranges.
//
// Why hand-written: no Debian package (nor any small permissively licensed library) offers
// parametric furniture with part labels, physical properties and material variants; the paper
// used a commercial database of 1M CAD models we cannot redistribute. Each category is a short
// function that draws its dimensions and materials from a CounterRng and lays out named parts.
//
// Model frame (every model): metres, +z up, origin at the centre of the footprint on the floor
// (z = 0 is the bottom of the model), the FRONT (where a person sits, opens or looks) faces -y,
// the back is at y = +size.y/2 (against a wall). Doors and windows sit in a wall opening: their
// y extent straddles the wall, front (-y) is the side the handle/sill is drawn for.
//
// Physics follows the paper's ranges: mass 0.05..45 kg (heavier real objects are clamped to 45
// kg and are unmovable), friction 0.08..0.27 from the material of the part touching the support.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assets/catalog_model.h"
#include "core/rng.h"
#include "procedural/texture_kind.h"
#include "scene/scene.h"

namespace inet {

/// A material a part asks for: deduplicated into scene Materials (by name) by the apartment
/// builder, which also makes the procedural texture images (procedural_textures.h).
struct MaterialSpec {
  std::string name;  ///< e.g. "oak_light", "fabric_grey"; equal names always mean equal specs
  MaterialType type = MaterialType::Lambertian;
  Vec3f albedo{0.8f, 0.8f, 0.8f};   ///< linear RGB base colour (the texture's mean colour)
  float roughness = 0.5f;           ///< perceptual roughness in [0, 1]
  std::string metal = "aluminium";  ///< conductor preset (metalNames())
  float ior = 1.5f;                 ///< plastic coating / dielectric
  Vec3f transmittance{1, 1, 1};     ///< dielectric tint / translucent diffuse transmission
  Vec3f emission{0, 0, 0};          ///< emitted radiance, W sr^-1 m^-2 (area lights)
  TextureKind texture = TextureKind::None;
  float texture_scale_m = 0.5f;  ///< metres covered by one texture tile
};

/// One labelled piece of a model: a unit primitive placed in the model frame.
struct FurniturePart {
  std::string name;       ///< part label: "seat", "back", "arm_left", "leg_3", "frame", "shade_2"
  std::string primitive;  ///< "box", "cylinder", "fold", "sphere", "quad" (scene/primitives.h, unit size)
  Mat4 T_model_part = Mat4::Identity();  ///< places the unit primitive in the model frame (m)
  int material = 0;                      ///< index into FurnitureModel::materials
  int nyu40 = 0;  ///< class of this part when it differs from the model's (the sink basin of a
                  ///< kitchen counter, the cabinet under a basin); 0 = the model's class
};

/// A lamp's analytic light, in the model frame. Area lights are emissive parts instead.
/// The position never lies inside a closed part (lamp shades are open rings), so shadow rays
/// leave it freely.
struct LightSpec {
  LightType type = LightType::Point;  ///< Point for bulbs, Spot for downlights
  Vec3 position = Vec3::Zero();
  Vec3 direction = -Vec3::UnitZ();  ///< spot axis (unit)
  float intensity_w_sr = 5.f;       ///< radiant intensity along the axis
  float temperature_k = 2700.f;     ///< blackbody colour
  float cone_deg = 40.f;            ///< spot half-angle
  float max_distance = 0.f;         ///< 0 = unlimited
};

/// A finished piece of furniture or prop in its model frame (see the top of this file).
struct FurnitureModel {
  /// Floor: stands on the floor. Wall: hangs on a wall, back at y = +size.y/2, bottom at
  /// `mount_height`. Ceiling: hangs from the ceiling, its top (z = size.z) touches it.
  /// OnSurface: stands on a support (table, shelf, bed). InWall: fills a wall opening (door,
  /// window); its bottom is at `mount_height` (0 for doors, the sill height for windows).
  enum class Placement { Floor, Wall, Ceiling, OnSurface, InWall };

  std::string category;  ///< "sofa", "nightstand", ... (furnitureCategories())
  int nyu40 = 40;        ///< NYU40 class of the whole model (1..40)
  std::vector<MaterialSpec> materials;
  std::vector<FurniturePart> parts;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< bounding box (x width, y depth, z height)
  /// Convex collision hulls: boxes in the model frame that together cover every part (one per
  /// part, with neighbours merged where the merged box adds little empty space).
  std::vector<Eigen::AlignedBox3d> hulls;
  double mass_kg = 1.0;       ///< 0.05..45
  double friction = 0.2;      ///< Coulomb coefficient, 0.08..0.27
  bool movable = true;        ///< false: beds, wardrobes, counters, fridges, fixtures, doors ...
  double mount_height = 0.0;  ///< bottom above the floor (Wall, InWall); 0 otherwise
  Placement placement = Placement::Floor;
  bool is_support = false;              ///< others may stand on it (support_heights)
  std::vector<double> support_heights;  ///< heights of horizontal support surfaces (m), rising
  std::optional<LightSpec> light;       ///< lamps: a point or spot light
  /// A Sweet Home 3D catalog model standing in for the parametric one (apartment.h,
  /// FurnitureSource): its parts, materials and bulbs replace `parts`, `materials` and `light`;
  /// size, hulls and physics come from it, placement and support from the category.
  std::shared_ptr<const CatalogModel> catalog;

  /// One line: category, class, size, mass, part and material counts.
  std::string toString() const;
};

/// Optional overrides of a category's nominal dimensions (metres), e.g. a wardrobe filling a
/// niche. Each one replaces the value the category would draw for its main width (x), depth (y)
/// or height (z) (a bed's mattress size, a cabinet's carcass); protruding handles, rails or
/// headboards may make `size` slightly larger. Doors and windows take their frame's outer size
/// (the wall opening; a window's sill reaches 3 cm further on each side, on the room face).
/// Interior decoration styles. A style does not change what is placed, only which material
/// variants are preferred (procedural/furniture_builder.h: DecorStyle weights) and the colours of
/// walls and floors. Any = every variant equally likely (the generator's original behaviour).
enum class DecorStyle { Any, Modern, Scandinavian, Classic, Industrial };
/// "any", "modern", "scandinavian", "classic", "industrial"; InputError(field) otherwise.
DecorStyle parseDecorStyle(const std::string& name, const std::string& field = "--style");
const char* decorStyleName(DecorStyle s);
/// The four real styles, for drawing one at random.
const std::vector<DecorStyle>& decorStyles();
/// How much `style` likes a material (> 0; 1 for DecorStyle::Any): a product of Gaussians in the
/// albedo's luminance and warmth around the style's targets and a factor for its type.
double styleWeight(DecorStyle style, const MaterialSpec& m);

struct FurnitureSizeHint {
  std::optional<double> width, depth, height;
  DecorStyle style = DecorStyle::Any;
};

/// Lower-case name of a placement ("floor", "wall", "ceiling", "on_surface", "in_wall").
const char* placementName(FurnitureModel::Placement p);

/// All categories, in a fixed order.
const std::vector<std::string>& furnitureCategories();

/// A model of `category`, dimensions and material variant drawn from `rng` (deterministic per
/// RNG state). Throws InputError(where, "category", ...) listing the valid names for an unknown
/// category.
FurnitureModel makeFurniture(const std::string& category, CounterRng& rng,
                             const std::string& where = "furniture");

/// As makeFurniture, with some nominal dimensions fixed by `hint`. Throws InputError(where,
/// "size_hint.<axis>", ...) for a non-positive or non-finite value, or when the category has no
/// such adjustable dimension (props such as a mug).
FurnitureModel makeFurnitureSized(const std::string& category, const FurnitureSizeHint& hint,
                                  CounterRng& rng, const std::string& where = "furniture");

}  // namespace inet
