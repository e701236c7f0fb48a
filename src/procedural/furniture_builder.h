#pragma once
// Internal to the furniture library (furniture.h): the part builder, the material palettes and
// the category table the catalogue files (furniture_*.cpp) fill in.
//
// Catalogue functions lay parts out by their bounding-box corners in a frame with the footprint
// centred on x = y = 0 and the bottom at z = 0 (front at -y); finishing the model re-centres the
// union of all parts exactly on that convention, computes `size`, the hulls and friction.
#include <string>
#include <string_view>
#include <vector>

#include "procedural/furniture.h"

namespace inet::furniture {

/// Families of interchangeable material variants; a category draws one variant per family use.
enum class Palette {
  Wood,     // Lambertian / varnished (Plastic) wood grain
  Painted,  // painted MDF: matte plaster-like or glossy plastic
  Fabric,   // upholstery weave
  Leather,  // coated plastic with leather grain
  Metal,    // conductors and powder coat
  Ceramic,  // glazed plastic look
  Stone,    // marble / tiles / laminate worktops
  Shade,    // translucent lampshades
  Curtain,  // translucent fabrics
  Carpet,   // rugs
  Emitter,  // emissive diffusers (area lights)
  Book,     // book covers
  Canvas,   // picture canvases (painted texture)
  Foliage,  // leaves
  Towel,    // terry cloth
  Plastic,  // appliance and housing plastics
};

/// The variants of a family (fixed order; names are unique across all palettes).
const std::vector<MaterialSpec>& palette(Palette p);
/// A material by name from any palette or the fixed set (glass, mirror, screen, rubber, ...).
/// An unknown name is a bug in the catalogue (INET_CHECK).
const MaterialSpec& namedMaterial(std::string_view name);

/// Which way a quad's lit side faces.
enum class Facing { Up, Down, Front, Back };
/// Axis of a cylinder.
enum class Axis { X, Y, Z };

/// Draws dimensions and materials and appends parts to a model.
class Builder {
 public:
  Builder(CounterRng& rng, const FurnitureSizeHint& hint, FurnitureModel& model)
      : rng_(rng), hint_(hint), m_(model) {}

  double uniform(double lo, double hi) { return rng_.uniformDouble(lo, hi); }
  int integer(int lo, int hi);  ///< uniform in [lo, hi]
  bool chance(double p) { return rng_.uniformDouble() < p; }
  /// Nominal width / depth / height: uniform in [lo, hi] unless the size hint fixes it.
  double width(double lo, double hi) { return hinted(hint_.width, used_w_, lo, hi); }
  double depth(double lo, double hi) { return hinted(hint_.depth, used_d_, lo, hi); }
  double height(double lo, double hi) { return hinted(hint_.height, used_h_, lo, hi); }

  /// A random variant of `p`, added to the model's materials; returns its index.
  int pick(Palette p);
  /// The named material (namedMaterial), added once; returns its index.
  int material(std::string_view name);
  int material(const MaterialSpec& spec);

  /// A box spanning the corners lo..hi (axis-aligned).
  void box(const std::string& name, int mat, const Vec3& lo, const Vec3& hi, int nyu40 = 0);
  /// A cylinder filling the box lo..hi along `axis` (elliptic when the cross-section is not
  /// square).
  void cylinder(const std::string& name, int mat, const Vec3& lo, const Vec3& hi,
                Axis axis = Axis::Z, int nyu40 = 0);
  void sphere(const std::string& name, int mat, const Vec3& centre, double radius);
  /// A rectangle of size (sx, sy) centred at `centre`; for Front/Back facing sy is its height.
  void quad(const std::string& name, int mat, const Vec3& centre, double sx, double sy,
            Facing facing);
  /// A primitive scaled by `size` (its own axes), rotated by R, centred at `centre`.
  void rotated(const std::string& name, const char* primitive, int mat, const Vec3& centre,
               const Vec3& size, const Mat3& R);

  /// Four legs filling the corners of the box lo..hi: square section t (round: cylinders).
  void legs(int mat, const Vec3& lo, const Vec3& hi, double t, bool round);
  /// An open lampshade: `n` translucent panels around a vertical axis at `centre_xy` between
  /// z0 and z1, bottom radius r0, top radius r1 (a cone frustum when they differ).
  void shadeRing(int mat, const Vec3& base_centre, double r0, double r1, double height, int n);

  bool hintUnused(std::string* axis) const;
  bool hinted() const { return hint_.width || hint_.depth || hint_.height; }
  FurnitureModel& model() { return m_; }

 private:
  double hinted(const std::optional<double>& h, bool& used, double lo, double hi);
  CounterRng& rng_;
  FurnitureSizeHint hint_;
  FurnitureModel& m_;
  bool used_w_ = false, used_d_ = false, used_h_ = false;
};

/// Cabinet fronts: a grid of `rows` x `cols` doors or drawers on the front face (y = y_front,
/// thickness `t`, then pull handles of depth `handle_d` in front of it), spanning x0..x1, z0..z1.
struct FrontGrid {
  int rows = 1, cols = 1;
  bool drawers = false;  ///< drawer pulls (centred, horizontal) or door pulls (vertical)
  int front_mat = 0, handle_mat = 0;
  double t = 0.018, handle_d = 0.022;
  int index0 = 0;  ///< number of the first front ("door_<index0>"), for several grids per model
  int nyu40 = 0;   ///< part class (0 = the model's)
};
void fronts(Builder& b, const FrontGrid& g, double x0, double x1, double z0, double z1,
            double y_front);

/// A case piece (nightstand, dresser, wardrobe, sideboard): body, fronts, handles and a plinth
/// or legs of height `base_h`, filling lo..hi (handles reach y = lo.y). Returns the body's top.
double caseGoods(Builder& b, const FrontGrid& g, int body_mat, const Vec3& lo, const Vec3& hi,
                 double base_h, bool legs, int nyu40 = 0);

/// A slab lo..hi with a rectangular hole (hx0..hx1, hy0..hy1) and a tub of `depth` hanging in
/// it (walls `wall_t`): a countertop with a recessed basin. Slab parts are called
/// "<slab_name>_front/back/left/right", tub parts "basin_*" (class `basin_nyu40`).
void slabWithBasin(Builder& b, const std::string& slab_name, int slab_mat, int basin_mat,
                   const Vec3& lo, const Vec3& hi, double hx0, double hx1, double hy0, double hy1,
                   double depth, double wall_t, int slab_nyu40, int basin_nyu40);

/// A faucet standing on z = z_top at (x, y): column and a spout reaching `reach` towards -y.
void faucet(Builder& b, int mat, double x, double y, double z_top, double height, double reach);

/// One category: its name, NYU40 class name, builder and physics.
struct CategoryDef {
  const char* name;
  const char* nyu40;
  void (*build)(Builder&);
  double mass_lo_kg, mass_hi_kg;  ///< real-world range; clamped to 0.05..45 afterwards
  bool movable;
  FurnitureModel::Placement placement;
};

// The catalogue files, each a list of categories (concatenated in this order).
const std::vector<CategoryDef>& bedroomCategories();  // beds and storage
const std::vector<CategoryDef>& seatingCategories();  // seats and tables
const std::vector<CategoryDef>& kitchenBathCategories();
const std::vector<CategoryDef>& fixtureCategories();  // lamps, doors, windows, wall items, rugs
const std::vector<CategoryDef>& propCategories();     // small objects

/// NYU40 id of a class name (INET_CHECK on an unknown one: the catalogue is code).
int nyu40Id(const char* name);

}  // namespace inet::furniture
