// Furniture library: category registry, model finishing (frame, size, hulls, physics) and the
// public entry points. The categories themselves live in furniture_<room>.cpp.
#include "procedural/furniture.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/error.h"
#include "procedural/furniture_builder.h"

namespace inet {
namespace {

using furniture::Builder;
using furniture::CategoryDef;
using Box = Eigen::AlignedBox3d;

const std::vector<CategoryDef>& allCategories() {
  static const auto all = [] {
    std::vector<CategoryDef> v;
    for (const auto* list : {&furniture::bedroomCategories(), &furniture::seatingCategories(),
                             &furniture::kitchenBathCategories(), &furniture::fixtureCategories(),
                             &furniture::propCategories()})
      v.insert(v.end(), list->begin(), list->end());
    return v;
  }();
  return all;
}

const CategoryDef* findCategory(const std::string& name) {
  static const auto index = [] {
    std::map<std::string, const CategoryDef*> m;
    for (const auto& c : allCategories())
      INET_CHECK_MSG(m.emplace(c.name, &c).second, std::string("duplicate category ") + c.name);
    return m;
  }();
  auto it = index.find(name);
  return it == index.end() ? nullptr : it->second;
}

/// Bounds of a part's unit primitive (the cylinder and sphere by their bounding cube, the quad
/// as its zero-thickness square).
Box partBounds(const FurniturePart& p) {
  const double hz = p.primitive == "quad" ? 0.0 : 0.5;
  Box b;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector4d c((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? hz : -hz, 1.0);
    b.extend((p.T_model_part * c).head<3>());
  }
  return b;
}

/// Coulomb friction of a material sliding on a wooden or tiled support (paper: 0.08..0.27).
double frictionOf(const MaterialSpec& m) {
  switch (m.texture) {
    case TextureKind::Fabric:
    case TextureKind::Carpet:
      return 0.25;
    case TextureKind::Leather:
      return 0.22;
    case TextureKind::Wood:
    case TextureKind::Plaster:
      return 0.2;
    case TextureKind::Tiles:
    case TextureKind::Metal:
      return 0.12;
    case TextureKind::Marble:
      return 0.1;
    case TextureKind::None:
      break;
  }
  switch (m.type) {
    case MaterialType::Conductor:
      return 0.12;
    case MaterialType::Plastic:
      return 0.15;
    case MaterialType::Dielectric:
    case MaterialType::ThinDielectric:
      return 0.09;
    default:
      return 0.2;
  }
}

/// Merges hulls while the merged box adds little empty space (<= 15% of the pair's volume), so
/// a cabinet's doors join its body but a bookshelf's boards stay apart.
std::vector<Box> mergeHulls(std::vector<Box> hulls) {
  auto vol = [](const Box& b) { return b.volume(); };
  for (;;) {
    double best = 1.15;
    size_t bi = 0, bj = 0;
    for (size_t i = 0; i < hulls.size(); ++i)
      for (size_t j = i + 1; j < hulls.size(); ++j) {
        const Box u = hulls[i].merged(hulls[j]);
        const Box x = hulls[i].intersection(hulls[j]);
        const double parts = vol(hulls[i]) + vol(hulls[j]) - (x.isEmpty() ? 0.0 : vol(x));
        const double ratio = vol(u) / std::max(parts, 1e-12);
        if (ratio < best) best = ratio, bi = i, bj = j;
      }
    if (bi == bj) return hulls;
    hulls[bi] = hulls[bi].merged(hulls[bj]);
    hulls.erase(hulls.begin() + static_cast<std::ptrdiff_t>(bj));
  }
}

/// Brings a built model onto the frame convention and fills size, hulls and physics.
void finish(FurnitureModel& m, const CategoryDef& def, Builder& b) {
  INET_CHECK_MSG(!m.parts.empty(), m.category);
  Box all;
  for (const auto& p : m.parts) {
    INET_CHECK(p.material >= 0 && p.material < static_cast<int>(m.materials.size()));
    all.extend(partBounds(p));
  }
  const Vec3 shift(-all.center().x(), -all.center().y(), -all.min().z());
  for (auto& p : m.parts) p.T_model_part.block<3, 1>(0, 3) += shift;
  if (m.light) m.light->position += shift;
  for (double& h : m.support_heights) h += shift.z();
  std::sort(m.support_heights.begin(), m.support_heights.end());
  m.size = all.sizes();

  std::vector<Box> hulls;
  const FurniturePart* contact = nullptr;
  double contact_area = -1;
  for (const auto& p : m.parts) {
    Box h = partBounds(p);
    for (int k = 0; k < 3; ++k) {  // flat parts get 2 mm of thickness
      const double pad = std::max(0.0, 0.002 - h.sizes()[k]) / 2;
      h.min()[k] -= pad;
      h.max()[k] += pad;
    }
    hulls.push_back(h);
    const Box pb = partBounds(p);
    const double area = pb.sizes().x() * pb.sizes().y();
    if (pb.min().z() < 0.001 && area > contact_area) contact = &p, contact_area = area;
  }
  m.hulls = mergeHulls(std::move(hulls));

  m.nyu40 = furniture::nyu40Id(def.nyu40);
  m.movable = def.movable;
  m.placement = def.placement;
  m.mass_kg = std::clamp(b.uniform(def.mass_lo_kg, def.mass_hi_kg), 0.05, 45.0);
  const double mu = contact ? frictionOf(m.materials[contact->material]) : 0.2;
  m.friction = std::clamp(mu + b.uniform(-0.015, 0.015), 0.08, 0.27);
  m.is_support = !m.support_heights.empty();
}

}  // namespace

std::string FurnitureModel::toString() const {
  return fmt::format(
      "{} (nyu40 {}): {:.3f} x {:.3f} x {:.3f} m, {:.2f} kg, {} parts, {} materials{}", category,
      nyu40, size.x(), size.y(), size.z(), mass_kg, parts.size(), materials.size(),
      light ? ", light" : "");
}

const char* placementName(FurnitureModel::Placement p) {
  switch (p) {
    case FurnitureModel::Placement::Floor:
      return "floor";
    case FurnitureModel::Placement::Wall:
      return "wall";
    case FurnitureModel::Placement::Ceiling:
      return "ceiling";
    case FurnitureModel::Placement::OnSurface:
      return "on_surface";
    case FurnitureModel::Placement::InWall:
      return "in_wall";
  }
  return "unknown";
}

const std::vector<std::string>& furnitureCategories() {
  static const auto names = [] {
    std::vector<std::string> v;
    for (const auto& c : allCategories()) v.emplace_back(c.name);
    return v;
  }();
  return names;
}

DecorStyle parseDecorStyle(const std::string& name, const std::string& field) {
  for (DecorStyle s : {DecorStyle::Any, DecorStyle::Modern, DecorStyle::Scandinavian,
                       DecorStyle::Classic, DecorStyle::Industrial})
    if (name == decorStyleName(s)) return s;
  throw InputError("", field,
                   fmt::format("unknown style '{}' (any, modern, scandinavian, classic, industrial)",
                               name));
}

const char* decorStyleName(DecorStyle s) {
  switch (s) {
    case DecorStyle::Any: return "any";
    case DecorStyle::Modern: return "modern";
    case DecorStyle::Scandinavian: return "scandinavian";
    case DecorStyle::Classic: return "classic";
    case DecorStyle::Industrial: return "industrial";
  }
  return "?";
}

const std::vector<DecorStyle>& decorStyles() {
  static const std::vector<DecorStyle> all = {DecorStyle::Modern, DecorStyle::Scandinavian,
                                              DecorStyle::Classic, DecorStyle::Industrial};
  return all;
}

double styleWeight(DecorStyle style, const MaterialSpec& m) {
  if (style == DecorStyle::Any) return 1.0;
  const Vec3f& a = m.albedo;
  const double lum = 0.2126 * a.x() + 0.7152 * a.y() + 0.0722 * a.z();
  const double warmth = (a.x() - a.z()) / std::max(1e-3f, a.x() + a.y() + a.z());
  // targets: luminance, warmth (red minus blue share), and a factor per material type
  double target_lum = 0.5, target_warmth = 0.0, type = 1.0;
  const bool glossy = m.type == MaterialType::Plastic || m.type == MaterialType::Conductor;
  switch (style) {
    case DecorStyle::Scandinavian:  // light, soft, matte
      target_lum = 0.6, target_warmth = 0.1, type = glossy ? 0.5 : 1.0;
      break;
    case DecorStyle::Modern:  // neutral greys and whites, lacquer and metal
      target_lum = 0.45, target_warmth = 0.0, type = glossy ? 1.5 : 1.0;
      break;
    case DecorStyle::Classic:  // dark warm woods, leather
      target_lum = 0.15, target_warmth = 0.3, type = 1.0;
      break;
    case DecorStyle::Industrial:  // dark, neutral, metal
      target_lum = 0.1, target_warmth = 0.05, type = m.type == MaterialType::Conductor ? 2.0 : 1.0;
      break;
    case DecorStyle::Any: break;
  }
  auto gauss = [](double x, double mu, double sigma) {
    return std::exp(-0.5 * (x - mu) * (x - mu) / (sigma * sigma));
  };
  // a floor of 0.02 keeps every variant possible, so no style empties a palette
  return 0.02 + type * gauss(lum, target_lum, 0.2) * gauss(warmth, target_warmth, 0.2);
}

FurnitureModel makeFurniture(const std::string& category, CounterRng& rng,
                             const std::string& where) {
  return makeFurnitureSized(category, {}, rng, where);
}

FurnitureModel makeFurnitureSized(const std::string& category, const FurnitureSizeHint& hint,
                                  CounterRng& rng, const std::string& where) {
  const CategoryDef* def = findCategory(category);
  if (!def)
    throw InputError(where, "category",
                     fmt::format("unknown furniture category '{}' (valid: {})", category,
                                 fmt::join(furnitureCategories(), ", ")));
  const std::array<std::pair<const char*, const std::optional<double>*>, 3> dims = {
      {{"width", &hint.width}, {"depth", &hint.depth}, {"height", &hint.height}}};
  for (const auto& [axis, v] : dims)
    if (*v && !(std::isfinite(**v) && **v > 0.0))
      throw InputError(where, std::string("size_hint.") + axis,
                       fmt::format("must be a finite length > 0 in metres, got {}", **v));
  FurnitureModel m;
  m.category = category;
  Builder b(rng, hint, m);
  def->build(b);
  std::string unused;
  if (b.hintUnused(&unused))
    throw InputError(where, "size_hint." + unused,
                     fmt::format("category '{}' has no adjustable {}", category, unused));
  finish(m, *def, b);
  return m;
}

}  // namespace inet
