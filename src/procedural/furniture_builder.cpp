// Part builder, material palettes and shared composite parts of the furniture library.
#include "procedural/furniture_builder.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "scene/nyu40.h"

namespace inet::furniture {
namespace {

using MT = MaterialType;
using TK = TextureKind;

MaterialSpec spec(const char* name, MT type, Vec3f albedo, float roughness, TK tex = TK::None,
                  float scale_m = 0.5f) {
  MaterialSpec s;
  s.name = name;
  s.type = type;
  s.albedo = albedo;
  s.roughness = roughness;
  s.texture = tex;
  s.texture_scale_m = scale_m;
  return s;
}

MaterialSpec metal(const char* name, const char* preset, Vec3f tint, float roughness, TK tex) {
  MaterialSpec s = spec(name, MT::Conductor, tint, roughness, tex, 0.3f);
  s.metal = preset;
  return s;
}

/// Translucent: albedo reflected, `trans` transmitted diffusely (albedo + trans <= 1).
MaterialSpec translucent(const char* name, Vec3f albedo, Vec3f trans, TK tex) {
  MaterialSpec s = spec(name, MT::Translucent, albedo, 0.9f, tex, 0.2f);
  s.transmittance = trans;
  return s;
}

MaterialSpec emitter(const char* name, Vec3f radiance) {
  MaterialSpec s = spec(name, MT::Lambertian, {0.8f, 0.8f, 0.8f}, 0.9f);
  s.emission = radiance;
  return s;
}

MaterialSpec glass(const char* name, MT type, Vec3f trans, float roughness) {
  MaterialSpec s = spec(name, type, {0.f, 0.f, 0.f}, roughness);
  s.transmittance = trans;
  s.ior = 1.5f;
  return s;
}

std::vector<MaterialSpec> makePalette(Palette p) {
  switch (p) {
    case Palette::Wood:
      return {spec("oak_light", MT::Lambertian, {0.55f, 0.40f, 0.25f}, 0.6f, TK::Wood, 0.8f),
              spec("oak", MT::Lambertian, {0.40f, 0.26f, 0.14f}, 0.6f, TK::Wood, 0.8f),
              spec("walnut", MT::Plastic, {0.20f, 0.12f, 0.07f}, 0.35f, TK::Wood, 0.8f),
              spec("cherry", MT::Plastic, {0.42f, 0.19f, 0.10f}, 0.35f, TK::Wood, 0.8f),
              spec("ash_white", MT::Lambertian, {0.72f, 0.66f, 0.56f}, 0.6f, TK::Wood, 0.8f),
              spec("wenge", MT::Lambertian, {0.10f, 0.07f, 0.05f}, 0.55f, TK::Wood, 0.8f)};
    case Palette::Painted:
      return {spec("paint_white", MT::Lambertian, {0.80f, 0.80f, 0.78f}, 0.7f, TK::Plaster, 1.f),
              spec("paint_grey", MT::Lambertian, {0.35f, 0.36f, 0.37f}, 0.7f, TK::Plaster, 1.f),
              spec("paint_sage", MT::Lambertian, {0.35f, 0.42f, 0.33f}, 0.7f, TK::Plaster, 1.f),
              spec("lacquer_white", MT::Plastic, {0.82f, 0.82f, 0.80f}, 0.2f),
              spec("lacquer_navy", MT::Plastic, {0.05f, 0.08f, 0.18f}, 0.25f),
              spec("lacquer_black", MT::Plastic, {0.03f, 0.03f, 0.03f}, 0.25f)};
    case Palette::Fabric:
      return {
          spec("fabric_grey", MT::Lambertian, {0.30f, 0.30f, 0.30f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_beige", MT::Lambertian, {0.55f, 0.48f, 0.38f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_navy", MT::Lambertian, {0.05f, 0.08f, 0.20f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_green", MT::Lambertian, {0.12f, 0.25f, 0.15f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_mustard", MT::Lambertian, {0.60f, 0.40f, 0.08f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_charcoal", MT::Lambertian, {0.08f, 0.08f, 0.09f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_rust", MT::Lambertian, {0.45f, 0.15f, 0.07f}, 0.9f, TK::Fabric, 0.1f),
          spec("fabric_cream", MT::Lambertian, {0.75f, 0.72f, 0.65f}, 0.9f, TK::Fabric, 0.1f)};
    case Palette::Leather:
      return {spec("leather_brown", MT::Plastic, {0.22f, 0.11f, 0.05f}, 0.45f, TK::Leather, 0.2f),
              spec("leather_black", MT::Plastic, {0.03f, 0.03f, 0.03f}, 0.45f, TK::Leather, 0.2f),
              spec("leather_tan", MT::Plastic, {0.45f, 0.25f, 0.12f}, 0.45f, TK::Leather, 0.2f)};
    case Palette::Metal:
      return {metal("aluminium_brushed", "aluminium", {0.95f, 0.95f, 0.95f}, 0.3f, TK::Metal),
              metal("chrome", "chromium", {0.95f, 0.95f, 0.95f}, 0.05f, TK::None),
              metal("brass", "gold", {0.90f, 0.80f, 0.60f}, 0.25f, TK::None),
              metal("copper_satin", "copper", {0.95f, 0.95f, 0.95f}, 0.3f, TK::None),
              metal("steel_brushed", "chromium", {0.90f, 0.90f, 0.90f}, 0.35f, TK::Metal),
              spec("powder_black", MT::Plastic, {0.02f, 0.02f, 0.02f}, 0.5f)};
    case Palette::Ceramic:
      return {spec("ceramic_white", MT::Plastic, {0.85f, 0.85f, 0.83f}, 0.1f),
              spec("ceramic_cream", MT::Plastic, {0.80f, 0.75f, 0.62f}, 0.1f),
              spec("ceramic_grey", MT::Plastic, {0.45f, 0.46f, 0.47f}, 0.1f),
              spec("ceramic_blue", MT::Plastic, {0.10f, 0.20f, 0.45f}, 0.1f),
              spec("terracotta", MT::Lambertian, {0.50f, 0.22f, 0.12f}, 0.8f)};
    case Palette::Stone:
      return {spec("marble_white", MT::Plastic, {0.80f, 0.79f, 0.76f}, 0.15f, TK::Marble, 0.8f),
              spec("marble_black", MT::Plastic, {0.05f, 0.05f, 0.05f}, 0.15f, TK::Marble, 0.8f),
              spec("marble_grey", MT::Plastic, {0.40f, 0.40f, 0.40f}, 0.2f, TK::Marble, 0.8f),
              spec("tiles_white", MT::Plastic, {0.78f, 0.78f, 0.76f}, 0.2f, TK::Tiles, 0.6f),
              spec("laminate_grey", MT::Plastic, {0.55f, 0.55f, 0.53f}, 0.4f)};
    case Palette::Shade:
      return {translucent("shade_white", {0.45f, 0.45f, 0.45f}, {0.50f, 0.50f, 0.50f}, TK::None),
              translucent("shade_cream", {0.45f, 0.40f, 0.30f}, {0.50f, 0.45f, 0.35f}, TK::None),
              translucent("shade_linen", {0.40f, 0.37f, 0.32f}, {0.45f, 0.40f, 0.35f}, TK::Fabric)};
    case Palette::Curtain:
      return {
          translucent("curtain_white", {0.50f, 0.50f, 0.48f}, {0.45f, 0.45f, 0.44f}, TK::Fabric),
          translucent("curtain_beige", {0.50f, 0.44f, 0.34f}, {0.40f, 0.35f, 0.27f}, TK::Fabric),
          translucent("curtain_grey", {0.20f, 0.20f, 0.20f}, {0.15f, 0.15f, 0.15f}, TK::Fabric),
          translucent("curtain_blue", {0.10f, 0.15f, 0.30f}, {0.10f, 0.12f, 0.20f}, TK::Fabric)};
    case Palette::Carpet:
      return {spec("carpet_grey", MT::Lambertian, {0.30f, 0.30f, 0.30f}, 0.95f, TK::Carpet, 0.4f),
              spec("carpet_beige", MT::Lambertian, {0.55f, 0.47f, 0.35f}, 0.95f, TK::Carpet, 0.4f),
              spec("carpet_red", MT::Lambertian, {0.40f, 0.08f, 0.06f}, 0.95f, TK::Carpet, 0.4f),
              spec("carpet_blue", MT::Lambertian, {0.08f, 0.12f, 0.30f}, 0.95f, TK::Carpet, 0.4f),
              spec("carpet_green", MT::Lambertian, {0.15f, 0.25f, 0.12f}, 0.95f, TK::Carpet, 0.4f)};
    case Palette::Emitter:  // radiance W sr^-1 m^-2; colour of 2700 K, 4000 K and 6500 K light
      return {emitter("emitter_warm", {12.0f, 8.6f, 5.0f}),
              emitter("emitter_neutral", {11.0f, 10.0f, 8.6f}),
              emitter("emitter_cool", {9.5f, 10.0f, 11.0f})};
    case Palette::Book:
      return {spec("book_red", MT::Lambertian, {0.45f, 0.06f, 0.05f}, 0.7f),
              spec("book_blue", MT::Lambertian, {0.05f, 0.12f, 0.35f}, 0.7f),
              spec("book_green", MT::Lambertian, {0.06f, 0.22f, 0.10f}, 0.7f),
              spec("book_ochre", MT::Lambertian, {0.60f, 0.42f, 0.10f}, 0.7f),
              spec("book_black", MT::Lambertian, {0.03f, 0.03f, 0.03f}, 0.6f),
              spec("book_white", MT::Lambertian, {0.78f, 0.77f, 0.72f}, 0.7f)};
    case Palette::Canvas:
      return {spec("canvas_ochre", MT::Lambertian, {0.60f, 0.35f, 0.15f}, 0.8f, TK::Plaster, 0.4f),
              spec("canvas_sea", MT::Lambertian, {0.15f, 0.35f, 0.55f}, 0.8f, TK::Plaster, 0.4f),
              spec("canvas_olive", MT::Lambertian, {0.30f, 0.35f, 0.12f}, 0.8f, TK::Plaster, 0.4f),
              spec("canvas_rose", MT::Lambertian, {0.70f, 0.35f, 0.38f}, 0.8f, TK::Plaster, 0.4f),
              spec("canvas_ivory", MT::Lambertian, {0.80f, 0.78f, 0.70f}, 0.8f, TK::Plaster, 0.4f)};
    case Palette::Foliage:
      return {spec("leaf_green", MT::Lambertian, {0.06f, 0.20f, 0.05f}, 0.6f),
              spec("leaf_dark", MT::Lambertian, {0.03f, 0.12f, 0.04f}, 0.6f),
              spec("leaf_lime", MT::Lambertian, {0.15f, 0.30f, 0.05f}, 0.6f)};
    case Palette::Towel:
      return {spec("towel_white", MT::Lambertian, {0.80f, 0.80f, 0.78f}, 0.95f, TK::Fabric, 0.05f),
              spec("towel_blue", MT::Lambertian, {0.15f, 0.30f, 0.50f}, 0.95f, TK::Fabric, 0.05f),
              spec("towel_grey", MT::Lambertian, {0.40f, 0.40f, 0.40f}, 0.95f, TK::Fabric, 0.05f),
              spec("towel_sage", MT::Lambertian, {0.40f, 0.48f, 0.38f}, 0.95f, TK::Fabric, 0.05f)};
    case Palette::Plastic:
      return {spec("plastic_white", MT::Plastic, {0.80f, 0.80f, 0.80f}, 0.3f),
              spec("plastic_black", MT::Plastic, {0.03f, 0.03f, 0.03f}, 0.4f),
              spec("plastic_grey", MT::Plastic, {0.30f, 0.30f, 0.31f}, 0.4f),
              spec("plastic_red", MT::Plastic, {0.50f, 0.05f, 0.04f}, 0.35f)};
  }
  return {};
}

constexpr Palette kAllPalettes[] = {
    Palette::Wood,    Palette::Painted, Palette::Fabric,  Palette::Leather,
    Palette::Metal,   Palette::Ceramic, Palette::Stone,   Palette::Shade,
    Palette::Curtain, Palette::Carpet,  Palette::Emitter, Palette::Book,
    Palette::Canvas,  Palette::Foliage, Palette::Towel,   Palette::Plastic};

/// Materials that are not variants of a family.
std::vector<MaterialSpec> fixedMaterials() {
  return {glass("glass_clear", MT::Dielectric, {0.95f, 0.97f, 0.96f}, 0.f),
          glass("glass_frosted", MT::Dielectric, {0.90f, 0.92f, 0.91f}, 0.3f),
          glass("pane_clear", MT::ThinDielectric, {0.92f, 0.95f, 0.93f}, 0.f),
          metal("mirror_silver", "silver", {0.95f, 0.95f, 0.95f}, 0.01f, TK::None),
          spec("screen_black", MT::Plastic, {0.01f, 0.01f, 0.01f}, 0.05f),
          spec("rubber_black", MT::Lambertian, {0.03f, 0.03f, 0.03f}, 0.9f),
          spec("paper_white", MT::Lambertian, {0.85f, 0.85f, 0.82f}, 0.8f),
          spec("cardboard", MT::Lambertian, {0.45f, 0.32f, 0.18f}, 0.8f),
          spec("tape_brown", MT::Plastic, {0.50f, 0.35f, 0.18f}, 0.3f),
          spec("soil", MT::Lambertian, {0.08f, 0.05f, 0.03f}, 0.95f),
          spec("mattress_white", MT::Lambertian, {0.82f, 0.82f, 0.80f}, 0.9f, TK::Fabric, 0.1f),
          spec("whiteboard", MT::Plastic, {0.85f, 0.85f, 0.85f}, 0.15f),
          metal("stainless", "chromium", {0.90f, 0.90f, 0.90f}, 0.25f, TK::Metal)};
}

const std::map<std::string, MaterialSpec, std::less<>>& materialIndex() {
  static const auto index = [] {
    std::map<std::string, MaterialSpec, std::less<>> m;
    auto add = [&](const MaterialSpec& s) {
      INET_CHECK_MSG(m.emplace(s.name, s).second, "duplicate furniture material " + s.name);
    };
    for (Palette p : kAllPalettes)
      for (const auto& s : palette(p)) add(s);
    for (const auto& s : fixedMaterials()) add(s);
    return m;
  }();
  return index;
}

}  // namespace

const std::vector<MaterialSpec>& palette(Palette p) {
  static const auto all = [] {
    std::map<Palette, std::vector<MaterialSpec>> m;
    for (Palette q : kAllPalettes) m[q] = makePalette(q);
    return m;
  }();
  return all.at(p);
}

const MaterialSpec& namedMaterial(std::string_view name) {
  const auto& index = materialIndex();
  auto it = index.find(name);
  INET_CHECK_MSG(it != index.end(), "unknown furniture material " + std::string(name));
  return it->second;
}

int nyu40Id(const char* name) {
  auto id = nyu40FromName(name);
  INET_CHECK_MSG(id.has_value() && *id > 0, name);
  return *id;
}

// --- Builder --------------------------------------------------------------------------------

int Builder::integer(int lo, int hi) {
  const int n = hi - lo + 1;
  return lo + std::min(n - 1, static_cast<int>(rng_.uniformDouble() * n));
}

double Builder::hinted(const std::optional<double>& h, bool& used, double lo, double hi) {
  const double drawn = uniform(lo, hi);  // drawn even when hinted: later draws stay the same
  if (!h) return drawn;
  used = true;
  return *h;
}

bool Builder::hintUnused(std::string* axis) const {
  if (hint_.width && !used_w_)
    *axis = "width";
  else if (hint_.depth && !used_d_)
    *axis = "depth";
  else if (hint_.height && !used_h_)
    *axis = "height";
  else
    return false;
  return true;
}

int Builder::material(const MaterialSpec& s) {
  for (size_t i = 0; i < m_.materials.size(); ++i)
    if (m_.materials[i].name == s.name) return static_cast<int>(i);
  m_.materials.push_back(s);
  return static_cast<int>(m_.materials.size() - 1);
}

int Builder::material(std::string_view name) {
  return material(namedMaterial(name));
}

int Builder::pick(Palette p) {
  const auto& v = palette(p);
  if (hint_.style == DecorStyle::Any) return material(v[integer(0, static_cast<int>(v.size()) - 1)]);
  // a style weighs the variants: one uniform draw against the cumulative weights
  std::vector<double> cumulative;
  double total = 0.0;
  for (const MaterialSpec& m : v) cumulative.push_back(total += styleWeight(hint_.style, m));
  const double u = uniform(0.0, total);
  const size_t k = std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin();
  return material(v[std::min(k, v.size() - 1)]);
}

void Builder::rotated(const std::string& name, const char* primitive, int mat, const Vec3& centre,
                      const Vec3& size, const Mat3& R) {
  INET_CHECK_MSG(size.minCoeff() >= 0.0 && mat >= 0, name);
  FurniturePart p;
  p.name = name;
  p.primitive = primitive;
  p.material = mat;
  Eigen::Affine3d a = Eigen::Translation3d(centre) * Eigen::Affine3d(R) * Eigen::Scaling(size);
  p.T_model_part = a.matrix();
  m_.parts.push_back(std::move(p));
}

void Builder::box(const std::string& name, int mat, const Vec3& lo, const Vec3& hi, int nyu40) {
  INET_CHECK_MSG((hi - lo).minCoeff() > 0.0, m_.category + "/" + name);
  rotated(name, "box", mat, (lo + hi) / 2, hi - lo, Mat3::Identity());
  m_.parts.back().nyu40 = nyu40;
}

void Builder::cylinder(const std::string& name, int mat, const Vec3& lo, const Vec3& hi, Axis axis,
                       int nyu40) {
  const Vec3 e = hi - lo;
  INET_CHECK_MSG(e.minCoeff() > 0.0, m_.category + "/" + name);
  Mat3 R = Mat3::Identity();
  Vec3 size = e;
  if (axis == Axis::X) {  // the unit cylinder's z axis turned onto x
    R = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()).toRotationMatrix();
    size = {e.z(), e.y(), e.x()};
  } else if (axis == Axis::Y) {
    R = Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    size = {e.x(), e.z(), e.y()};
  }
  rotated(name, "cylinder", mat, (lo + hi) / 2, size, R);
  m_.parts.back().nyu40 = nyu40;
}

void Builder::sphere(const std::string& name, int mat, const Vec3& centre, double radius) {
  rotated(name, "sphere", mat, centre, Vec3::Constant(2 * radius), Mat3::Identity());
}

void Builder::quad(const std::string& name, int mat, const Vec3& centre, double sx, double sy,
                   Facing facing) {
  Mat3 R = Mat3::Identity();
  if (facing == Facing::Down) R = Eigen::AngleAxisd(M_PI, Vec3::UnitX()).toRotationMatrix();
  if (facing == Facing::Front) R = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  if (facing == Facing::Back) R = Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  rotated(name, "quad", mat, centre, {sx, sy, 1.0}, R);
}

void Builder::legs(int mat, const Vec3& lo, const Vec3& hi, double t, bool round) {
  int k = 0;
  for (double y : {lo.y(), hi.y() - t})
    for (double x : {lo.x(), hi.x() - t}) {
      const Vec3 a(x, y, lo.z()), c(x + t, y + t, hi.z());
      const std::string name = "leg_" + std::to_string(k++);
      if (round)
        cylinder(name, mat, a, c);
      else
        box(name, mat, a, c);
    }
}

void Builder::shadeRing(int mat, const Vec3& base_centre, double r0, double r1, double height,
                        int n) {
  const double t = 0.003, r_max = std::max(r0, r1);
  const double slant = std::hypot(height, r0 - r1), tilt = std::atan2(r0 - r1, height);
  const double panel_w = 2 * r_max * std::tan(M_PI / n) + t;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Vec3 radial(std::cos(a), std::sin(a), 0);
    // local y onto the radial direction, then lean the top inwards by `tilt`
    const Mat3 R =
        (Eigen::AngleAxisd(a - M_PI / 2, Vec3::UnitZ()) * Eigen::AngleAxisd(tilt, Vec3::UnitX()))
            .toRotationMatrix();
    const Vec3 c = base_centre + radial * ((r0 + r1) / 2) + Vec3(0, 0, height / 2);
    rotated("shade_" + std::to_string(i), "box", mat, c, {panel_w, t, slant}, R);
  }
}

// --- composite parts ------------------------------------------------------------------------

void fronts(Builder& b, const FrontGrid& g, double x0, double x1, double z0, double z1,
            double y_front) {
  const double gap = 0.003, fw = (x1 - x0) / g.cols, fh = (z1 - z0) / g.rows;
  const double yf0 = y_front, yf1 = y_front + g.t, yh0 = y_front - g.handle_d;
  const char* kind = g.drawers ? "drawer_" : "door_";
  int k = g.index0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c, ++k) {
      const double fx0 = x0 + c * fw + gap / 2, fx1 = fx0 + fw - gap;
      const double fz1 = z1 - r * fh - gap / 2, fz0 = fz1 - fh + gap;
      const std::string id = kind + std::to_string(k);
      b.box(id, g.front_mat, {fx0, yf0, fz0}, {fx1, yf1, fz1}, g.nyu40);
      const double hw = std::min(0.012, (fx1 - fx0) / 4);
      if (g.drawers) {  // horizontal pull, centred, in the upper part of the front
        const double len = std::min(0.3, (fx1 - fx0) * 0.4), xc = (fx0 + fx1) / 2;
        const double zc = fz1 - std::min(0.06, (fz1 - fz0) / 3);
        b.box(id + "_handle", g.handle_mat, {xc - len / 2, yh0, zc - hw},
              {xc + len / 2, yf0, zc + hw}, g.nyu40);
      } else {  // vertical pull at the opening edge: the inner edge for pairs, else the right
        const bool right = g.cols == 1 ? true : (c % 2 == 0);
        const double xc = right ? fx1 - 0.04 : fx0 + 0.04;
        const double len = std::min(0.25, (fz1 - fz0) * 0.3);
        const double zc = g.rows == 1 && fz1 - fz0 > 1.2 ? fz0 + 1.0 : (fz0 + fz1) / 2;
        b.box(id + "_handle", g.handle_mat, {xc - hw, yh0, zc - len / 2},
              {xc + hw, yf0, zc + len / 2}, g.nyu40);
      }
    }
}

double caseGoods(Builder& b, const FrontGrid& g, int body_mat, const Vec3& lo, const Vec3& hi,
                 double base_h, bool legs, int nyu40) {
  const double y_front = lo.y() + g.handle_d, y_body = y_front + g.t;
  b.box("body", body_mat, {lo.x(), y_body, lo.z() + base_h}, hi, nyu40);
  fronts(b, g, lo.x(), hi.x(), lo.z() + base_h, hi.z(), y_front);
  if (base_h <= 0) return hi.z();
  if (legs) {
    const double t = std::clamp(0.08 * (hi.x() - lo.x()), 0.03, 0.05);
    b.legs(body_mat, {lo.x() + 0.02, y_body + 0.02, lo.z()},
           {hi.x() - 0.02, hi.y() - 0.02, lo.z() + base_h}, t, false);
  } else {  // recessed plinth (toe kick)
    const double inset = std::min(0.05, 0.2 * (hi.y() - y_body));
    b.box("plinth", body_mat, {lo.x() + 0.01, y_body + inset, lo.z()},
          {hi.x() - 0.01, hi.y() - 0.01, lo.z() + base_h}, nyu40);
  }
  return hi.z();
}

void slabWithBasin(Builder& b, const std::string& slab_name, int slab_mat, int basin_mat,
                   const Vec3& lo, const Vec3& hi, double hx0, double hx1, double hy0, double hy1,
                   double depth, double wall_t, int slab_nyu40, int basin_nyu40) {
  const double z0 = lo.z(), z1 = hi.z();
  b.box(slab_name + "_front", slab_mat, lo, {hi.x(), hy0, z1}, slab_nyu40);
  b.box(slab_name + "_back", slab_mat, {lo.x(), hy1, z0}, hi, slab_nyu40);
  b.box(slab_name + "_left", slab_mat, {lo.x(), hy0, z0}, {hx0, hy1, z1}, slab_nyu40);
  b.box(slab_name + "_right", slab_mat, {hx1, hy0, z0}, {hi.x(), hy1, z1}, slab_nyu40);
  const double zb = z1 - depth;  // the tub hangs in the hole, its rim flush with the slab top
  b.box("basin_left", basin_mat, {hx0, hy0, zb}, {hx0 + wall_t, hy1, z1}, basin_nyu40);
  b.box("basin_right", basin_mat, {hx1 - wall_t, hy0, zb}, {hx1, hy1, z1}, basin_nyu40);
  b.box("basin_front", basin_mat, {hx0 + wall_t, hy0, zb}, {hx1 - wall_t, hy0 + wall_t, z1},
        basin_nyu40);
  b.box("basin_back", basin_mat, {hx0 + wall_t, hy1 - wall_t, zb}, {hx1 - wall_t, hy1, z1},
        basin_nyu40);
  b.box("basin_bottom", basin_mat, {hx0 + wall_t, hy0 + wall_t, zb},
        {hx1 - wall_t, hy1 - wall_t, zb + wall_t}, basin_nyu40);
}

void faucet(Builder& b, int mat, double x, double y, double z_top, double height, double reach) {
  const double r = 0.016;
  b.cylinder("faucet", mat, {x - r, y - r, z_top}, {x + r, y + r, z_top + height});
  b.box("spout", mat, {x - 0.012, y - reach, z_top + height},
        {x + 0.012, y + r, z_top + height + 0.022});
}

}  // namespace inet::furniture
