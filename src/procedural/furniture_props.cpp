// Furniture catalogue: screens and small props (metres).
#include <algorithm>
#include <cmath>

#include "procedural/furniture_builder.h"

namespace inet::furniture {
namespace {

using P = FurnitureModel::Placement;

int housing(Builder& b) {
  static const char* kNames[] = {"plastic_black", "plastic_grey", "aluminium_brushed"};
  return b.material(kNames[b.integer(0, 2)]);
}

/// A 16:9 flat screen of visible width sw_lo..sw_hi on a pedestal or two feet.
void flatScreen(Builder& b, double sw_lo, double sw_hi, double lift_lo, double lift_hi) {
  const double sw = b.width(sw_lo, sw_hi), sh = sw * 9.0 / 16.0, bz = b.uniform(0.008, 0.02);
  const double pw = sw + 2 * bz, ph = sh + 2 * bz, pt = b.uniform(0.02, 0.05);
  const double lift = b.uniform(lift_lo, lift_hi), bd = b.uniform(0.18, 0.25);
  const int shell = housing(b);
  if (sw < 0.9 || b.chance(0.5)) {
    const double bw = std::min(0.4, 0.35 * pw);
    b.box("stand_base", shell, {-bw / 2, -bd / 2, 0}, {bw / 2, bd / 2, 0.015});
    b.box("stand_neck", shell, {-0.03, pt / 2, 0.015}, {0.03, pt / 2 + 0.02, lift + 0.15});
  } else {
    for (int s : {-1, 1}) {
      const double x = s * (pw / 2 - 0.1);
      b.box(s < 0 ? "foot_left" : "foot_right", shell, {x - 0.02, -bd / 2, 0},
            {x + 0.02, bd / 2, lift});
    }
  }
  b.box("panel", shell, {-pw / 2, -pt / 2, lift}, {pw / 2, pt / 2, lift + ph});
  b.box("screen", b.material("screen_black"), {-sw / 2, -pt / 2 - 0.002, lift + bz},
        {sw / 2, -pt / 2, lift + bz + sh});
}

void television(Builder& b) {
  flatScreen(b, 0.9, 1.45, 0.05, 0.1);
}  // 40" .. 65"
void monitor(Builder& b) {
  flatScreen(b, 0.48, 0.71, 0.08, 0.15);
}  // 22" .. 32"

/// Open laptop: base with keyboard, lid opened 100..120 degrees with the screen facing -y.
void laptop(Builder& b) {
  const double w = b.uniform(0.3, 0.38), d = b.uniform(0.21, 0.26), bt = b.uniform(0.015, 0.02);
  const double lt = 0.006, alpha = b.uniform(100, 120) * M_PI / 180;
  const int shell = housing(b);
  b.box("base", shell, {-w / 2, -d / 2, 0}, {w / 2, d / 2, bt});
  b.box("keyboard", b.material("plastic_black"), {-w / 2 + 0.02, -d / 2 + 0.1, bt},
        {w / 2 - 0.02, d / 2 - 0.02, bt + 0.001});
  // lid frame: x, the lid's length direction `dir` and its screen normal n = x cross dir
  const Vec3 hinge(0, d / 2, bt), dir(0, -std::cos(alpha), std::sin(alpha));
  const Vec3 n = Vec3::UnitX().cross(dir);
  Mat3 R;
  R << Vec3::UnitX(), dir, n;
  b.rotated("lid", "box", shell, hinge + dir * (d / 2) - n * (lt / 2), {w, d, lt}, R);
  b.rotated("screen", "quad", b.material("screen_black"), hinge + dir * (d / 2) + n * 0.0005,
            {w - 0.02, d - 0.02, 1.0}, R);
}

/// A row of 3..8 standing books (spines to the front) or a stack of 2..5 lying books.
void books(Builder& b) {
  auto& s = b.model().support_heights;
  if (b.chance(0.75)) {
    const int n = b.integer(3, 8);
    double x = 0;
    for (int i = 0; i < n; ++i) {
      const double bw = b.uniform(0.015, 0.05), bh = b.uniform(0.18, 0.3),
                   bd = b.uniform(0.13, 0.22);
      b.box("book_" + std::to_string(i), b.pick(Palette::Book), {x, -0.11, 0},
            {x + bw, -0.11 + bd, bh});
      x += bw + 0.001;
    }
  } else {
    const int n = b.integer(2, 5);
    double z = 0;
    for (int i = 0; i < n; ++i) {
      const double w = b.uniform(0.15, 0.22), d = b.uniform(0.2, 0.28), t = b.uniform(0.015, 0.05);
      const double ox = b.uniform(-0.015, 0.015), oy = b.uniform(-0.015, 0.015);
      b.box("book_" + std::to_string(i), b.pick(Palette::Book), {ox - w / 2, oy - d / 2, z},
            {ox + w / 2, oy + d / 2, z + t});
      z += t;
    }
    s = {z};
  }
}

void mug(Builder& b) {
  const double D = b.uniform(0.075, 0.09), H = b.uniform(0.085, 0.105), r = D / 2, hw = 0.006;
  const int mat = b.pick(Palette::Ceramic);
  b.cylinder("body", mat, {-r, -r, 0}, {r, r, H});
  b.box("handle_top", mat, {r, -hw, H - 0.025}, {r + 0.03, hw, H - 0.015});
  b.box("handle_bottom", mat, {r, -hw, 0.02}, {r + 0.03, hw, 0.03});
  b.box("handle_side", mat, {r + 0.02, -hw, 0.03}, {r + 0.03, hw, H - 0.025});
}

/// Bowl: foot ring and two stacked discs widening upwards.
void bowl(Builder& b) {
  const double D = b.uniform(0.14, 0.22), H = b.uniform(0.05, 0.08), zm = 0.01 + 0.45 * (H - 0.01);
  const double p = b.uniform(0, 1);
  const int mat = p < 0.6 ? b.pick(Palette::Ceramic)
                          : (p < 0.85 ? b.pick(Palette::Wood) : b.material("glass_clear"));
  auto disc = [&](const char* name, double dia, double z0, double z1) {
    b.cylinder(name, mat, {-dia / 2, -dia / 2, z0}, {dia / 2, dia / 2, z1});
  };
  disc("foot", 0.45 * D, 0, 0.01);
  disc("lower", 0.8 * D, 0.01, zm);
  disc("upper", D, zm, H);
}

/// Cardboard box (taped) or a storage box with a lid.
void box(Builder& b) {
  const double w = b.width(0.2, 0.6), d = b.depth(0.2, 0.5), h = b.height(0.15, 0.45);
  if (b.chance(0.6)) {
    b.box("body", b.material("cardboard"), {-w / 2, -d / 2, 0}, {w / 2, d / 2, h});
    b.box("tape", b.material("tape_brown"), {-0.025, -d / 2, h}, {0.025, d / 2, h + 0.001});
    b.model().support_heights = {h + 0.001};
  } else {
    const int mat = b.pick(Palette::Plastic);
    b.box("body", mat, {-w / 2 + 0.005, -d / 2 + 0.005, 0},
          {w / 2 - 0.005, d / 2 - 0.005, h - 0.02});
    b.box("lid", mat, {-w / 2, -d / 2, h - 0.02}, {w / 2, d / 2, h});
    b.model().support_heights = {h};
  }
}

int cover(Builder& b) {
  return b.chance(0.4) ? b.material("mattress_white") : b.pick(Palette::Fabric);
}

/// Bed pillow lying flat: a core slab and a rounded (elliptic) top.
void pillow(Builder& b) {
  const double w = b.width(0.5, 0.75), d = b.depth(0.35, 0.5), t = b.uniform(0.1, 0.18);
  const int mat = cover(b);
  b.box("core", mat, {-w / 2, -d / 2, 0}, {w / 2, d / 2, 0.55 * t});
  b.cylinder("puff", mat, {-0.46 * w, -0.425 * d, 0.55 * t}, {0.46 * w, 0.425 * d, t});
}

/// Square sofa cushion standing upright (leaning against a back), puffed front and back.
void cushion(Builder& b) {
  const double s = b.uniform(0.38, 0.5), t = b.uniform(0.1, 0.16);
  const int mat = cover(b);
  b.box("core", mat, {-s / 2, -0.3 * t, 0}, {s / 2, 0.3 * t, s});
  b.box("puff_front", mat, {-0.42 * s, -0.5 * t, 0.08 * s}, {0.42 * s, -0.3 * t, 0.92 * s});
  b.box("puff_back", mat, {-0.42 * s, 0.3 * t, 0.08 * s}, {0.42 * s, 0.5 * t, 0.92 * s});
}

/// A pair of shoes, toes to the front: sole, toe cap and upper each.
void shoes(Builder& b) {
  const double L = b.uniform(0.24, 0.3), sw = b.uniform(0.085, 0.105), st = b.uniform(0.02, 0.03);
  const double uh = b.uniform(0.06, 0.12), gap = b.uniform(0.02, 0.06);
  const int upper = b.chance(0.5) ? b.pick(Palette::Leather) : b.pick(Palette::Fabric);
  const int sole = b.chance(0.6) ? b.material("rubber_black") : b.material("plastic_white");
  for (int s : {-1, 1}) {
    const std::string side = s < 0 ? "_left" : "_right";
    const double xc = s * (sw / 2 + gap / 2), x0 = xc - sw / 2 + 0.005, x1 = xc + sw / 2 - 0.005;
    b.box("sole" + side, sole, {xc - sw / 2, -L / 2, 0}, {xc + sw / 2, L / 2, st});
    b.box("toe" + side, upper, {x0, -L / 2 + 0.01, st}, {x1, -L / 2 + 0.4 * L, st + 0.04});
    b.box("upper" + side, upper, {x0, -L / 2 + 0.4 * L, st}, {x1, L / 2 - 0.01, st + uh});
  }
}

/// A pile of 2..5 folded garments.
void clothes(Builder& b) {
  const int n = b.integer(2, 5);
  const double w0 = b.uniform(0.28, 0.4), d0 = b.uniform(0.22, 0.32);
  double z = 0;
  for (int i = 0; i < n; ++i) {
    const double w = w0 + b.uniform(-0.02, 0.02), d = d0 + b.uniform(-0.02, 0.02);
    const double t = b.uniform(0.025, 0.06), ox = b.uniform(-0.015, 0.015),
                 oy = b.uniform(-0.015, 0.015);
    b.box("garment_" + std::to_string(i), b.pick(Palette::Fabric), {ox - w / 2, oy - d / 2, z},
          {ox + w / 2, oy + d / 2, z + t});
    z += t;
  }
}

/// Handbag: body, front pocket and a carry handle.
void bag(Builder& b) {
  const double w = b.uniform(0.28, 0.45), d = b.uniform(0.12, 0.2), h = b.uniform(0.25, 0.4);
  const double hw = std::min(w - 0.06, b.uniform(0.12, 0.2)), hh = b.uniform(0.08, 0.15), s = 0.015;
  const int mat = b.chance(0.5) ? b.pick(Palette::Leather) : b.pick(Palette::Fabric);
  b.box("body", mat, {-w / 2, -d / 2, 0}, {w / 2, d / 2, h});
  b.box("pocket", mat, {-0.35 * w, -d / 2 - 0.03, 0.05}, {0.35 * w, -d / 2, 0.6 * h});
  b.box("handle_left", mat, {-hw / 2 - s / 2, -s / 2, h}, {-hw / 2 + s / 2, s / 2, h + hh});
  b.box("handle_right", mat, {hw / 2 - s / 2, -s / 2, h}, {hw / 2 + s / 2, s / 2, h + hh});
  b.box("handle_top", mat, {-hw / 2 - s / 2, -s / 2, h + hh}, {hw / 2 + s / 2, s / 2, h + hh + s});
}

/// A pot with soil, a stem and 1..3 stacked foliage balls.
void plantIn(Builder& b, double pd_lo, double pd_hi, double ph_lo, double ph_hi, double stem_lo,
             double stem_hi, double r_lo, double r_hi, int n_lo, int n_hi) {
  const double pd = b.uniform(pd_lo, pd_hi), ph = b.uniform(ph_lo, ph_hi);
  const double stem = b.uniform(stem_lo, stem_hi), r0 = b.uniform(r_lo, r_hi);
  const int n = b.integer(n_lo, n_hi);
  const int pot = b.pick(Palette::Ceramic), leaves = b.pick(Palette::Foliage);
  b.cylinder("pot", pot, {-pd / 2, -pd / 2, 0}, {pd / 2, pd / 2, ph});
  b.cylinder("soil", b.material("soil"), {-0.45 * pd, -0.45 * pd, ph},
             {0.45 * pd, 0.45 * pd, ph + 0.005});
  double z = ph + 0.005;
  if (stem > 0.005) {
    const double sr = std::max(0.005, 0.05 * pd);
    b.cylinder("stem", b.material("oak"), {-sr, -sr, z}, {sr, sr, z + stem});
    z += stem;
  }
  for (int i = 0; i < n; ++i) {
    const double r = r0 * (1 - 0.25 * i);
    b.sphere("foliage_" + std::to_string(i), leaves, {0, 0, z + r}, r);
    z += 2 * r;
  }
}

void pottedPlant(Builder& b) {
  plantIn(b, 0.1, 0.2, 0.1, 0.18, 0.0, 0.03, 0.06, 0.12, 1, 2);
}
void floorPlant(Builder& b) {
  plantIn(b, 0.25, 0.4, 0.25, 0.45, 0.2, 0.6, 0.15, 0.3, 2, 3);
}

void vase(Builder& b) {
  const double D = b.uniform(0.08, 0.16), H = b.uniform(0.12, 0.3), nh = b.uniform(0.03, 0.08);
  const double p = b.uniform(0, 1);
  const int mat =
      p < 0.7 ? b.pick(Palette::Ceramic) : b.material(p < 0.85 ? "glass_clear" : "glass_frosted");
  const double z1 = H - nh - 0.01;
  b.cylinder("body", mat, {-D / 2, -D / 2, 0}, {D / 2, D / 2, z1});
  b.cylinder("neck", mat, {-D / 4, -D / 4, z1}, {D / 4, D / 4, H - 0.01});
  b.cylinder("lip", mat, {-0.35 * D, -0.35 * D, H - 0.01}, {0.35 * D, 0.35 * D, H});
}

/// A stack of A4 or US-letter paper, sometimes with a loose sheet askew on top.
void paper(Builder& b) {
  const bool a4 = b.chance(0.7);
  const double w = a4 ? 0.21 : 0.216, d = a4 ? 0.297 : 0.279, t = b.uniform(0.002, 0.03);
  const int mat = b.material("paper_white");
  b.box("stack", mat, {-w / 2, -d / 2, 0}, {w / 2, d / 2, t});
  if (b.chance(0.5)) {
    const double yaw = b.uniform(-0.2, 0.2);
    b.rotated("sheet", "box", mat, {0, 0, t + 0.00025}, {w, d, 0.0005},
              Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix());
  }
}

/// Waste bin: round or square, sometimes with a pedal lid.
void trashBin(Builder& b) {
  const double D = b.uniform(0.22, 0.32), H = b.uniform(0.3, 0.45);
  const int mat = b.chance(0.5) ? b.pick(Palette::Metal) : b.pick(Palette::Plastic);
  const bool round = b.chance(0.6);
  if (round)
    b.cylinder("body", mat, {-D / 2, -D / 2, 0}, {D / 2, D / 2, H});
  else
    b.box("body", mat, {-D / 2, -D / 2, 0}, {D / 2, D / 2, H});
  if (b.chance(0.5)) {
    const double L = D / 2 + 0.005;
    if (round)
      b.cylinder("lid", mat, {-L, -L, H}, {L, L, H + 0.02});
    else
      b.box("lid", mat, {-L, -L, H}, {L, L, H + 0.02});
    b.box("pedal", b.material("plastic_black"), {-0.04, -D / 2 - 0.04, 0.01},
          {0.04, -D / 2, 0.025});
  }
}

}  // namespace

const std::vector<CategoryDef>& propCategories() {
  static const std::vector<CategoryDef> v = {
      {"television", "television", television, 8, 25, true, P::OnSurface},
      {"monitor", "television", monitor, 3, 7, true, P::OnSurface},
      {"laptop", "otherprop", laptop, 1.2, 2.5, true, P::OnSurface},
      {"books", "books", books, 0.5, 4, true, P::OnSurface},
      {"mug", "otherprop", mug, 0.25, 0.4, true, P::OnSurface},
      {"bowl", "otherprop", bowl, 0.2, 0.8, true, P::OnSurface},
      {"box", "box", box, 0.3, 3, true, P::Floor},
      {"pillow", "pillow", pillow, 0.4, 1.0, true, P::OnSurface},
      {"cushion", "pillow", cushion, 0.2, 0.6, true, P::OnSurface},
      {"shoes", "otherprop", shoes, 0.5, 1.5, true, P::Floor},
      {"clothes", "clothes", clothes, 0.3, 1.5, true, P::OnSurface},
      {"bag", "bag", bag, 0.5, 2.5, true, P::Floor},
      {"potted_plant", "otherprop", pottedPlant, 0.5, 2.5, true, P::OnSurface},
      {"plant", "otherprop", floorPlant, 5, 20, true, P::Floor},
      {"vase", "otherprop", vase, 0.3, 1.5, true, P::OnSurface},
      {"paper", "paper", paper, 0.05, 1.2, true, P::OnSurface},
      {"trash_bin", "otherprop", trashBin, 0.5, 2.5, true, P::Floor},
  };
  return v;
}

}  // namespace inet::furniture
