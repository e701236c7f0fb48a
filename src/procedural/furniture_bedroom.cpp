// Furniture catalogue: beds and storage (dimensions from common retail ranges, metres).
#include <algorithm>
#include <cmath>

#include "procedural/furniture_builder.h"

namespace inet::furniture {
namespace {

using P = FurnitureModel::Placement;

/// A bed: legs or platform, frame, mattress, duvet over the front 3/4, headboard at the back.
/// The mattress (mw x ml) sets the nominal width/depth, its top the nominal height.
void bed(Builder& b, double mw_lo, double mw_hi) {
  const double mw = b.width(mw_lo, mw_hi), ml = b.depth(1.9, 2.1), top = b.height(0.45, 0.6);
  const double mt = b.uniform(0.18, 0.26), rail = 0.03, hb_t = b.uniform(0.04, 0.08);
  const double frame_top = top - mt, W = mw + 2 * rail;
  const bool platform = b.chance(0.3);
  const double leg_h = platform ? 0.0 : std::min(b.uniform(0.08, 0.2), frame_top - 0.08);
  const int frame = b.chance(0.35) ? b.pick(Palette::Fabric) : b.pick(Palette::Wood);
  const int wood = b.pick(Palette::Wood);
  if (leg_h > 0)
    b.legs(wood, {-W / 2, -ml / 2 - rail, 0}, {W / 2, ml / 2, leg_h}, 0.06, b.chance(0.4));
  b.box("frame", frame, {-W / 2, -ml / 2 - rail, leg_h}, {W / 2, ml / 2, frame_top});
  b.box("mattress", b.material("mattress_white"), {-mw / 2, -ml / 2, frame_top},
        {mw / 2, ml / 2, top});
  b.box("duvet", b.pick(Palette::Fabric), {-mw / 2, -ml / 2, top}, {mw / 2, ml / 4, top + 0.04});
  const double hb_top = top + b.uniform(0.35, 0.65);
  b.box("headboard", frame, {-W / 2, ml / 2, 0}, {W / 2, ml / 2 + hb_t, hb_top});
  b.model().support_heights = {top};
}

void bedDouble(Builder& b) {
  bed(b, 1.4, 1.8);
}
void bedSingle(Builder& b) {
  bed(b, 0.8, 1.0);
}

void bunkBed(Builder& b) {
  const double mw = b.width(0.8, 1.0), ml = b.depth(1.9, 2.0), H = b.height(1.5, 1.75);
  const double p = 0.06, W = mw + 2 * p, mt = b.uniform(0.12, 0.16);
  const int wood = b.pick(Palette::Wood), bedding = b.pick(Palette::Fabric);
  const int mattress = b.material("mattress_white");
  for (int sx : {-1, 1})
    for (int sy : {-1, 1}) {
      const double x0 = sx < 0 ? -W / 2 : W / 2 - p, y0 = sy < 0 ? -ml / 2 : ml / 2 - p;
      b.box(std::string("post_") + (sy < 0 ? "front_" : "back_") + (sx < 0 ? "left" : "right"),
            wood, {x0, y0, 0}, {x0 + p, y0 + p, H});
    }
  const double lf0 = 0.18, lf1 = 0.3, uf0 = H - 0.55, uf1 = uf0 + 0.12, ut = uf1 + mt;
  b.box("frame_lower", wood, {-mw / 2, -ml / 2, lf0}, {mw / 2, ml / 2, lf1});
  b.box("mattress_lower", mattress, {-mw / 2, -ml / 2, lf1}, {mw / 2, ml / 2, lf1 + mt});
  b.box("frame_upper", wood, {-mw / 2, -ml / 2, uf0}, {mw / 2, ml / 2, uf1});
  b.box("mattress_upper", mattress, {-mw / 2, -ml / 2, uf1}, {mw / 2, ml / 2, ut});
  b.box("duvet_upper", bedding, {-mw / 2, -ml / 2, ut}, {mw / 2, ml / 4, ut + 0.03});
  // guard rails above the upper mattress: both long sides and the head end
  const double g0 = ut + 0.06, g1 = std::min(H - 0.01, ut + 0.2);
  b.box("rail_left", wood, {-W / 2, -ml / 2 + p, g0}, {-W / 2 + p, ml / 2 - p, g1});
  b.box("rail_right", wood, {W / 2 - p, -ml / 2 + p, g0}, {W / 2, ml / 2 - p, g1});
  b.box("rail_head", wood, {-mw / 2, ml / 2 - 0.025, ut + 0.03}, {mw / 2, ml / 2, g1});
  // ladder rungs at the foot end, between the front posts
  const double r0 = lf1 + mt + 0.12;
  const int rungs = std::max(1, static_cast<int>((uf0 - 0.05 - r0) / 0.25) + 1);
  for (int i = 0; i < rungs; ++i) {
    const double z = r0 + i * 0.25;
    b.box("rung_" + std::to_string(i), wood, {-mw / 2, -ml / 2 - 0.03, z},
          {mw / 2, -ml / 2, z + 0.03});
  }
  b.model().support_heights = {lf1 + mt, ut};
}

FrontGrid grid(Builder& b, int rows, int cols, bool drawers, int front_mat) {
  FrontGrid g;
  g.rows = rows;
  g.cols = cols;
  g.drawers = drawers;
  g.front_mat = front_mat;
  g.handle_mat = b.pick(Palette::Metal);
  return g;
}

/// Body material and a front material that is the same or a painted contrast.
std::pair<int, int> caseMaterials(Builder& b) {
  const int body = b.chance(0.7) ? b.pick(Palette::Wood) : b.pick(Palette::Painted);
  return {body, b.chance(0.7) ? body : b.pick(Palette::Painted)};
}

void nightstand(Builder& b) {
  const double w = b.width(0.4, 0.55), d = b.depth(0.35, 0.45), h = b.height(0.45, 0.65);
  const auto [body, front] = caseMaterials(b);
  const bool legs = b.chance(0.5);
  const double base = legs ? b.uniform(0.1, 0.2) : b.uniform(0.04, 0.08);
  caseGoods(b, grid(b, b.integer(1, 3), 1, true, front), body, {-w / 2, -d / 2, 0},
            {w / 2, d / 2, h}, base, legs);
  b.model().support_heights = {h};
}

void wardrobe(Builder& b) {
  const double w = b.width(0.8, 2.0), d = b.depth(0.55, 0.62), h = b.height(1.9, 2.3);
  const auto [body, front] = caseMaterials(b);
  const int cols = std::clamp(static_cast<int>(std::lround(w / 0.5)), 2, 4);
  const double base = b.uniform(0.06, 0.1);
  caseGoods(b, grid(b, 1, cols, false, front), body, {-w / 2, -d / 2, 0}, {w / 2, d / 2, h}, base,
            false);
}

void dresser(Builder& b) {
  const double w = b.width(0.8, 1.6), d = b.depth(0.4, 0.55), h = b.height(0.7, 1.0);
  const auto [body, front] = caseMaterials(b);
  const bool legs = b.chance(0.4);
  const double base = legs ? b.uniform(0.1, 0.18) : b.uniform(0.05, 0.09);
  caseGoods(b, grid(b, b.integer(3, 4), w > 1.1 ? 2 : 1, true, front), body, {-w / 2, -d / 2, 0},
            {w / 2, d / 2, h}, base, legs);
  b.model().support_heights = {h};
}

/// Sideboard: a row of doors, sometimes under a row of drawers.
void cabinet(Builder& b) {
  const double w = b.width(0.6, 1.8), d = b.depth(0.4, 0.55), h = b.height(0.7, 1.1);
  const auto [body, front] = caseMaterials(b);
  const bool legs = b.chance(0.4);
  const double base = legs ? b.uniform(0.1, 0.18) : b.uniform(0.05, 0.09);
  const int cols = std::clamp(static_cast<int>(std::lround(w / 0.45)), 1, 4);
  FrontGrid doors = grid(b, 0, cols, false, front);
  caseGoods(b, doors, body, {-w / 2, -d / 2, 0}, {w / 2, d / 2, h}, base, legs);
  const double y_front = -d / 2 + doors.handle_d, split = b.chance(0.5) ? h - 0.18 : h;
  doors.rows = 1;
  fronts(b, doors, -w / 2, w / 2, base, split, y_front);
  if (split < h) {
    FrontGrid drawers = doors;
    drawers.drawers = true;
    fronts(b, drawers, -w / 2, w / 2, split, h, y_front);
  }
  b.model().support_heights = {h};
}

void tvStand(Builder& b) {
  const double w = b.width(1.2, 2.0), d = b.depth(0.35, 0.5), h = b.height(0.4, 0.6);
  const auto [body, front] = caseMaterials(b);
  const bool legs = b.chance(0.5);
  const double base = legs ? b.uniform(0.08, 0.15) : b.uniform(0.03, 0.06);
  const int cols = b.integer(2, 4);
  const bool drawers = b.chance(0.5);
  caseGoods(b, grid(b, 1, cols, drawers, front), body, {-w / 2, -d / 2, 0}, {w / 2, d / 2, h}, base,
            legs);
  b.model().support_heights = {h};
}

/// Open shelving: sides, top, plinth, optional back panel and evenly spaced shelves.
void bookshelf(Builder& b) {
  const double w = b.width(0.6, 1.2), d = b.depth(0.25, 0.4), h = b.height(1.0, 2.0);
  const double t = b.uniform(0.018, 0.025), base = b.uniform(0.05, 0.08);
  const int mat = b.chance(0.7) ? b.pick(Palette::Wood) : b.pick(Palette::Painted);
  const bool back = b.chance(0.7);
  const double yb = back ? d / 2 - 0.006 : d / 2, xi = w / 2 - t;
  b.box("side_left", mat, {-w / 2, -d / 2, 0}, {-xi, d / 2, h});
  b.box("side_right", mat, {xi, -d / 2, 0}, {w / 2, d / 2, h});
  b.box("top", mat, {-xi, -d / 2, h - t}, {xi, d / 2, h});
  b.box("plinth", mat, {-xi, -d / 2, 0}, {xi, d / 2, base});
  if (back) b.box("back", mat, {-xi, yb, base}, {xi, d / 2, h - t});
  const int n = std::max(1, static_cast<int>(std::lround((h - base - t) / 0.35)) - 1);
  const double pitch = (h - base - t) / (n + 1);
  auto& s = b.model().support_heights;
  s = {base};
  for (int i = 1; i <= n; ++i) {
    const double z = base + i * pitch;
    b.box("shelf_" + std::to_string(i - 1), mat, {-xi, -d / 2, z - t}, {xi, yb, z});
    s.push_back(z);
  }
  s.push_back(h);
}

void wallShelf(Builder& b) {
  const double w = b.width(0.6, 1.2), d = b.depth(0.15, 0.25);
  const int mat = b.chance(0.7) ? b.pick(Palette::Wood) : b.pick(Palette::Painted);
  const bool floating = b.chance(0.35);
  const double t = floating ? b.uniform(0.035, 0.05) : b.uniform(0.018, 0.03);
  const double bh = floating ? 0.0 : b.uniform(0.1, 0.15);
  b.box("board", mat, {-w / 2, -d / 2, bh}, {w / 2, d / 2, bh + t});
  if (!floating) {
    const int metal = b.pick(Palette::Metal);
    for (int s : {-1, 1}) {
      const double xc = s * (w / 2 - 0.12 * w);
      b.box(s < 0 ? "bracket_left" : "bracket_right", metal, {xc - 0.008, d / 2 - 0.75 * d, 0},
            {xc + 0.008, d / 2, bh});
    }
  }
  b.model().support_heights = {bh + t};
  b.model().mount_height = b.uniform(1.2, 1.7);
}

/// Shoe rack: two sides and 2..4 shelves.
void shoeRack(Builder& b) {
  const double w = b.width(0.6, 1.0), d = b.depth(0.28, 0.35), h = b.height(0.45, 0.9);
  const int mat = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
  const double t = 0.02, xi = w / 2 - t;
  b.box("side_left", mat, {-w / 2, -d / 2, 0}, {-xi, d / 2, h});
  b.box("side_right", mat, {xi, -d / 2, 0}, {w / 2, d / 2, h});
  const int n = std::clamp(static_cast<int>(h / 0.22), 2, 4);
  auto& s = b.model().support_heights;
  for (int i = 0; i < n; ++i) {
    const double z = 0.05 + i * (h - 0.05) / (n - 1);
    b.box("shelf_" + std::to_string(i), mat, {-xi, -d / 2, z - t}, {xi, d / 2, z});
    s.push_back(z);
  }
}

/// Standing coat rack: four feet, pole, hooks near the top, knob.
void coatRack(Builder& b) {
  const double H = b.height(1.7, 1.9), R = b.uniform(0.22, 0.3), r = b.uniform(0.02, 0.025);
  const int mat = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
  const double k = 0.03, fw = 0.015;
  b.box("foot_0", mat, {r, -fw, 0}, {R, fw, 0.04});
  b.box("foot_1", mat, {-R, -fw, 0}, {-r, fw, 0.04});
  b.box("foot_2", mat, {-fw, r, 0}, {fw, R, 0.04});
  b.box("foot_3", mat, {-fw, -R, 0}, {fw, -r, 0.04});
  b.cylinder("pole", mat, {-r, -r, 0}, {r, r, H - 2 * k});
  b.sphere("knob", mat, {0, 0, H - k}, k);
  const double z = H - 0.2, L = 0.09, hw = 0.008;
  b.box("hook_0", mat, {r, -hw, z}, {r + L, hw, z + 0.02});
  b.box("hook_1", mat, {-r - L, -hw, z}, {-r, hw, z + 0.02});
  b.box("hook_2", mat, {-hw, r, z - 0.08}, {hw, r + L, z - 0.06});
  b.box("hook_3", mat, {-hw, -r - L, z - 0.08}, {hw, -r, z - 0.06});
}

}  // namespace

const std::vector<CategoryDef>& bedroomCategories() {
  static const std::vector<CategoryDef> v = {
      {"bed_double", "bed", bedDouble, 40, 80, false, P::Floor},
      {"bed_single", "bed", bedSingle, 25, 45, false, P::Floor},
      {"bunk_bed", "bed", bunkBed, 50, 90, false, P::Floor},
      {"nightstand", "night_stand", nightstand, 8, 20, true, P::Floor},
      {"wardrobe", "cabinet", wardrobe, 50, 120, false, P::Floor},
      {"dresser", "dresser", dresser, 30, 60, false, P::Floor},
      {"cabinet", "cabinet", cabinet, 20, 50, false, P::Floor},
      {"tv_stand", "cabinet", tvStand, 15, 35, true, P::Floor},
      {"bookshelf", "bookshelf", bookshelf, 15, 45, false, P::Floor},
      {"wall_shelf", "shelves", wallShelf, 1, 4, false, P::Wall},
      {"shoe_rack", "shelves", shoeRack, 3, 10, true, P::Floor},
      {"coat_rack", "otherfurniture", coatRack, 3, 8, true, P::Floor},
  };
  return v;
}

}  // namespace inet::furniture
