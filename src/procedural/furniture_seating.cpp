// Furniture catalogue: seats and tables (dimensions from common retail ranges, metres).
#include <algorithm>
#include <cmath>

#include "procedural/furniture_builder.h"

namespace inet::furniture {
namespace {

using P = FurnitureModel::Placement;

int woodOrPainted(Builder& b, double p_wood) {
  return b.chance(p_wood) ? b.pick(Palette::Wood) : b.pick(Palette::Painted);
}

/// Desk: a top on four legs (with a modesty panel) or on two side panels (with a drawer
/// pedestal).
void desk(Builder& b) {
  const double w = b.width(1.0, 1.6), d = b.depth(0.6, 0.8), h = b.height(0.72, 0.76);
  const double tt = b.uniform(0.025, 0.04), zt = h - tt;
  const int top = woodOrPainted(b, 0.7);
  b.box("top", top, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h});
  if (b.chance(0.5)) {
    const int leg = b.chance(0.5) ? top : b.pick(Palette::Metal);
    const double t = b.uniform(0.04, 0.06), in = 0.03;
    b.legs(leg, {-w / 2 + in, -d / 2 + in, 0}, {w / 2 - in, d / 2 - in, zt}, t, b.chance(0.3));
    if (b.chance(0.5))
      b.box("modesty_panel", top, {-w / 2 + in + t, d / 2 - in - 0.018, zt - 0.35},
            {w / 2 - in - t, d / 2 - in, zt});
  } else {
    const double t = 0.025;
    b.box("side_left", top, {-w / 2, -d / 2 + 0.02, 0}, {-w / 2 + t, d / 2 - 0.02, zt});
    b.box("side_right", top, {w / 2 - t, -d / 2 + 0.02, 0}, {w / 2, d / 2 - 0.02, zt});
    if (b.chance(0.5)) {
      FrontGrid g;
      g.rows = 3;
      g.drawers = true;
      g.front_mat = top;
      g.handle_mat = b.pick(Palette::Metal);
      const double x1 = w / 2 - t - 0.003;
      caseGoods(b, g, top, {x1 - 0.4, -d / 2 + 0.02, 0}, {x1, d / 2 - 0.04, zt - 0.003}, 0.03,
                false);
    }
  }
  b.model().support_heights = {h};
}

/// Office chair: five-star base on casters, gas column, seat, back, optional armrests.
void officeChair(Builder& b) {
  const double sh = b.height(0.42, 0.52), R = b.uniform(0.3, 0.34);
  const double sw = b.uniform(0.46, 0.52), sd = b.uniform(0.44, 0.5), st = b.uniform(0.07, 0.09);
  const double bh = b.uniform(0.45, 0.65), bt = b.uniform(0.05, 0.08);
  const int base = b.chance(0.5) ? b.material("plastic_black") : b.pick(Palette::Metal);
  const int cover = b.chance(0.75) ? b.pick(Palette::Fabric) : b.pick(Palette::Leather);
  const int black = b.material("plastic_black");
  const double cr = 0.025, hub = 0.04;
  for (int k = 0; k < 5; ++k) {
    const double a = M_PI / 2 + 2 * M_PI * k / 5;
    const Vec3 dir(std::cos(a), std::sin(a), 0);
    b.sphere("caster_" + std::to_string(k), black, dir * (R - cr) + Vec3(0, 0, cr), cr);
    b.rotated("leg_" + std::to_string(k), "box", base, dir * ((hub + R) / 2) + Vec3(0, 0, 0.065),
              {R - hub, 0.035, 0.03}, Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix());
  }
  const double zs = sh - st;
  b.cylinder("hub", base, {-hub, -hub, 0.05}, {hub, hub, 0.09});
  b.cylinder("column", base, {-0.025, -0.025, 0.09}, {0.025, 0.025, zs - 0.05});
  b.box("mechanism", black, {-0.1, -0.1, zs - 0.05}, {0.1, 0.1, zs});
  b.box("seat", cover, {-sw / 2, -sd / 2, zs}, {sw / 2, sd / 2, sh});
  b.box("back_support", base, {-0.025, sd / 2, zs}, {0.025, sd / 2 + 0.03, sh + 0.12});
  b.box("back", cover, {-sw * 0.47, sd / 2 + 0.03, sh + 0.05},
        {sw * 0.47, sd / 2 + 0.03 + bt, sh + bh});
  if (b.chance(0.6))
    for (int s : {-1, 1}) {
      const std::string side = s < 0 ? "left" : "right";
      const double x0 = s < 0 ? -sw / 2 - 0.03 : sw / 2, x1 = x0 + 0.03;
      b.box("arm_post_" + side, black, {x0, -0.03, zs}, {x1, 0.05, sh + 0.2});
      const double p0 = s < 0 ? -sw / 2 - 0.06 : sw / 2 - 0.01;
      b.box("arm_" + side, black, {p0, -0.12, sh + 0.2}, {p0 + 0.07, 0.14, sh + 0.23});
    }
}

/// Dining chair: four legs, seat board (wood or upholstered), two back posts and a backrest.
void diningChair(Builder& b) {
  const double sh = b.height(0.43, 0.48), sw = b.width(0.4, 0.48), sd = b.depth(0.4, 0.48);
  const double st = b.uniform(0.025, 0.04), H = b.uniform(0.8, 0.95), t = b.uniform(0.03, 0.04);
  const int wood = woodOrPainted(b, 0.75);
  const int seat = b.chance(0.4) ? b.pick(Palette::Fabric) : wood;
  b.legs(wood, {-sw / 2, -sd / 2, 0}, {sw / 2, sd / 2, sh - st}, t, b.chance(0.3));
  b.box("seat", seat, {-sw / 2, -sd / 2, sh - st}, {sw / 2, sd / 2, sh});
  b.box("post_left", wood, {-sw / 2, sd / 2 - t, sh}, {-sw / 2 + t, sd / 2, H});
  b.box("post_right", wood, {sw / 2 - t, sd / 2 - t, sh}, {sw / 2, sd / 2, H});
  const double rest = b.uniform(0.12, 0.3);
  b.box("backrest", wood, {-sw / 2 + t, sd / 2 - 0.02, H - rest}, {sw / 2 - t, sd / 2, H});
  if (rest < 0.2) {  // a second slat halfway between the seat and the backrest
    const double zc = (sh + H - rest) / 2;
    b.box("back_slat", wood, {-sw / 2 + t, sd / 2 - 0.02, zc - 0.03},
          {sw / 2 - t, sd / 2, zc + 0.03});
  }
}

/// Rectangular table on four legs with an apron, or (without size hints) a round pedestal table.
struct TableRanges {
  double w_lo, w_hi, d_lo, d_hi, h_lo, h_hi;  ///< rectangular top and height
  double p_round, dia_lo, dia_hi;             ///< round variant: probability, diameter
};

void table(Builder& b, const TableRanges& rg) {
  const bool round = !b.hinted() && b.chance(rg.p_round);
  const double w = round ? b.uniform(rg.dia_lo, rg.dia_hi) : b.width(rg.w_lo, rg.w_hi);
  const double d = round ? w : b.depth(rg.d_lo, rg.d_hi);
  const double h = b.height(rg.h_lo, rg.h_hi), tt = b.uniform(0.025, 0.045), zt = h - tt;
  const bool glass = b.chance(0.2);
  const int top = glass ? b.material("glass_clear") : woodOrPainted(b, 0.75);
  const int frame = glass ? b.pick(Palette::Metal) : (b.chance(0.7) ? top : b.pick(Palette::Metal));
  if (round) {
    const double rb = std::min(0.3, 0.35 * w), rc = b.uniform(0.04, 0.07), bt = 0.03;
    b.cylinder("top", top, {-w / 2, -w / 2, zt}, {w / 2, w / 2, h});
    b.cylinder("base", frame, {-rb, -rb, 0}, {rb, rb, bt});
    b.cylinder("pedestal", frame, {-rc, -rc, bt}, {rc, rc, zt});
  } else {
    b.box("top", top, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h});
    const double in = std::min(0.05, 0.08 * d), t = b.uniform(0.04, 0.07), a = 0.02;
    const double ah = std::min(0.1, 0.2 * zt), za = zt - ah;
    b.legs(frame, {-w / 2 + in, -d / 2 + in, 0}, {w / 2 - in, d / 2 - in, zt}, t, b.chance(0.3));
    const double x0 = -w / 2 + in, x1 = w / 2 - in, y0 = -d / 2 + in, y1 = d / 2 - in;
    b.box("apron_front", frame, {x0 + t, y0, za}, {x1 - t, y0 + a, zt});
    b.box("apron_back", frame, {x0 + t, y1 - a, za}, {x1 - t, y1, zt});
    b.box("apron_left", frame, {x0, y0 + t, za}, {x0 + a, y1 - t, zt});
    b.box("apron_right", frame, {x1 - a, y0 + t, za}, {x1, y1 - t, zt});
  }
  b.model().support_heights = {h};
}

void diningTable(Builder& b) {
  table(b, {1.2, 2.0, 0.75, 1.0, 0.73, 0.77, 0.25, 0.9, 1.3});
}
void sideTable(Builder& b) {
  table(b, {0.4, 0.55, 0.4, 0.55, 0.45, 0.6, 0.5, 0.4, 0.55});
}

/// Coffee table: four legs and a lower shelf between them.
void coffeeTable(Builder& b) {
  const double w = b.width(0.8, 1.3), d = b.depth(0.45, 0.7), h = b.height(0.35, 0.48);
  const double tt = b.uniform(0.02, 0.04), zt = h - tt, t = b.uniform(0.03, 0.05), in = 0.03;
  const bool glass = b.chance(0.3);
  const int top = glass ? b.material("glass_clear") : woodOrPainted(b, 0.8);
  const int frame = glass ? b.pick(Palette::Metal) : top;
  b.box("top", top, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h});
  b.legs(frame, {-w / 2 + in, -d / 2 + in, 0}, {w / 2 - in, d / 2 - in, zt}, t, glass);
  auto& s = b.model().support_heights;
  if (b.chance(0.6)) {
    const double zs = b.uniform(0.08, 0.14);
    b.box("shelf", glass ? frame : top, {-w / 2 + in + t, -d / 2 + in, zs - 0.02},
          {w / 2 - in - t, d / 2 - in, zs});
    s.push_back(zs);
  }
  s.push_back(h);
}

/// Sofa / armchair: legs, base frame, arms, back, seat cushions, optional back cushions.
void sofa(Builder& b, double w_lo, double w_hi, int cushions) {
  const double W = b.width(w_lo, w_hi), D = b.depth(0.8, 1.0), H = b.height(0.75, 0.9);
  const double leg_h = b.uniform(0.05, 0.15), arm_w = b.uniform(0.1, 0.2);
  const double arm_h = std::min(b.uniform(0.55, 0.65), H - 0.08);
  const double seat_top = b.uniform(0.42, 0.48), seat_base = seat_top - b.uniform(0.12, 0.18);
  const double back_d = b.uniform(0.18, 0.25);
  const int cover = b.chance(0.75) ? b.pick(Palette::Fabric) : b.pick(Palette::Leather);
  const int leg = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
  const double xi = W / 2 - arm_w;
  b.legs(leg, {-W / 2 + 0.03, -D / 2 + 0.03, 0}, {W / 2 - 0.03, D / 2 - 0.03, leg_h}, 0.045,
         b.chance(0.5));
  b.box("arm_left", cover, {-W / 2, -D / 2, leg_h}, {-xi, D / 2, arm_h});
  b.box("arm_right", cover, {xi, -D / 2, leg_h}, {W / 2, D / 2, arm_h});
  b.box("frame", cover, {-xi, -D / 2, leg_h}, {xi, D / 2, seat_base});
  b.box("back", cover, {-xi, D / 2 - back_d, seat_base}, {xi, D / 2, H});
  const int n = cushions > 0 ? cushions : (W > 2.0 ? 3 : 2);
  const bool back_cushions = b.chance(0.6);
  const double cw = 2 * xi / n, yb = D / 2 - back_d, bc = 0.12;
  for (int i = 0; i < n; ++i) {
    const double x0 = -xi + i * cw + 0.0015, x1 = x0 + cw - 0.003;
    b.box("seat_cushion_" + std::to_string(i), cover, {x0, -D / 2, seat_base}, {x1, yb, seat_top});
    if (back_cushions)
      b.box("back_cushion_" + std::to_string(i), cover, {x0, yb - bc, seat_top},
            {x1, yb, std::min(H - 0.04, seat_top + 0.4)});
  }
  b.model().support_heights = {seat_top};
}

void sofa3(Builder& b) {
  sofa(b, 1.6, 2.4, 0);
}
void armchair(Builder& b) {
  sofa(b, 0.7, 1.0, 1);
}

/// Stool: round or square seat on four legs; tall (bar) stools get a footrest ring.
void stool(Builder& b) {
  const double h = b.height(0.45, 0.78), sd = b.uniform(0.3, 0.4), st = b.uniform(0.03, 0.05);
  const double t = b.uniform(0.025, 0.035), a = sd / 2 * 0.65;
  const int wood = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
  const int seat = b.chance(0.3) ? b.pick(Palette::Leather) : wood;
  if (b.chance(0.6))
    b.cylinder("seat", seat, {-sd / 2, -sd / 2, h - st}, {sd / 2, sd / 2, h});
  else
    b.box("seat", seat, {-sd / 2, -sd / 2, h - st}, {sd / 2, sd / 2, h});
  b.legs(wood, {-a, -a, 0}, {a, a, h - st}, t, b.chance(0.5));
  if (h > 0.6) {
    const double f = 0.02;
    b.box("footrest_front", wood, {-a + t, -a, 0.25}, {a - t, -a + f, 0.27});
    b.box("footrest_back", wood, {-a + t, a - f, 0.25}, {a - t, a, 0.27});
    b.box("footrest_left", wood, {-a, -a + t, 0.3}, {-a + f, a - t, 0.32});
    b.box("footrest_right", wood, {a - f, -a + t, 0.3}, {a, a - t, 0.32});
  }
}

/// Bench: a seat board on two slab ends or four legs.
void bench(Builder& b) {
  const double w = b.width(0.8, 1.6), d = b.depth(0.3, 0.45), h = b.height(0.42, 0.48);
  const double st = b.uniform(0.03, 0.05), zs = h - st;
  const int wood = woodOrPainted(b, 0.8);
  b.box("seat", wood, {-w / 2, -d / 2, zs}, {w / 2, d / 2, h});
  if (b.chance(0.5)) {
    const double e = b.uniform(0.03, 0.05), in = 0.05;
    b.box("end_left", wood, {-w / 2 + in, -d / 2 + 0.02, 0}, {-w / 2 + in + e, d / 2 - 0.02, zs});
    b.box("end_right", wood, {w / 2 - in - e, -d / 2 + 0.02, 0}, {w / 2 - in, d / 2 - 0.02, zs});
  } else {
    b.legs(wood, {-w / 2 + 0.04, -d / 2 + 0.03, 0}, {w / 2 - 0.04, d / 2 - 0.03, zs}, 0.045, false);
  }
  b.model().support_heights = {h};
}

}  // namespace

const std::vector<CategoryDef>& seatingCategories() {
  static const std::vector<CategoryDef> v = {
      {"desk", "desk", desk, 15, 40, true, P::Floor},
      {"office_chair", "chair", officeChair, 10, 18, true, P::Floor},
      {"dining_chair", "chair", diningChair, 4, 8, true, P::Floor},
      {"dining_table", "table", diningTable, 20, 45, true, P::Floor},
      {"coffee_table", "table", coffeeTable, 8, 25, true, P::Floor},
      {"side_table", "table", sideTable, 3, 8, true, P::Floor},
      {"sofa", "sofa", sofa3, 35, 70, false, P::Floor},
      {"armchair", "chair", armchair, 15, 30, true, P::Floor},
      {"stool", "chair", stool, 2, 6, true, P::Floor},
      {"bench", "otherfurniture", bench, 5, 15, true, P::Floor},
  };
  return v;
}

}  // namespace inet::furniture
