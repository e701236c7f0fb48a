// Furniture catalogue: lamps, doors, windows and wall-hung items, rugs (metres, W/sr).
#include <algorithm>
#include <cmath>

#include "procedural/furniture_builder.h"

namespace inet::furniture {
namespace {

using P = FurnitureModel::Placement;

/// A point light for a bulb at `pos`: warm (2700 K or 3000 K) and `w_sr` strong.
void bulb(Builder& b, const Vec3& pos, double w_lo, double w_hi) {
  LightSpec l;
  l.type = LightType::Point;
  l.position = pos;
  l.intensity_w_sr = static_cast<float>(b.uniform(w_lo, w_hi));
  l.temperature_k = b.chance(0.6) ? 2700.f : 3000.f;
  b.model().light = l;
}

int shadeMaterial(Builder& b, double p_metal) {
  return b.chance(p_metal) ? b.pick(Palette::Metal) : b.pick(Palette::Shade);
}

/// Floor lamp: weighted base, pole, socket and an open shade with the bulb inside.
void floorLamp(Builder& b) {
  const double H = b.height(1.45, 1.8), rb = b.uniform(0.13, 0.17), bt = b.uniform(0.025, 0.04);
  const double r0 = b.uniform(0.18, 0.25), r1 = r0 * b.uniform(0.6, 1.0),
               sh = b.uniform(0.25, 0.35);
  const int metal = b.pick(Palette::Metal), shade = shadeMaterial(b, 0.0);
  const int base = b.chance(0.3) ? b.material("marble_white") : metal;
  const double zs1 = H - 0.6 * sh, zs0 = zs1 - 0.05;
  b.cylinder("base", base, {-rb, -rb, 0}, {rb, rb, bt});
  b.cylinder("pole", metal, {-0.012, -0.012, bt}, {0.012, 0.012, zs0});
  b.cylinder("socket", metal, {-0.02, -0.02, zs0}, {0.02, 0.02, zs1});
  b.shadeRing(shade, {0, 0, H - sh}, r0, r1, sh, 12);
  bulb(b, {0, 0, zs1 + 0.04}, 3.0, 6.0);
}

/// Table lamp: ceramic column or ball body, neck, socket and an open shade.
void tableLamp(Builder& b) {
  const double H = b.height(0.35, 0.65), sh = std::min(b.uniform(0.18, 0.28), 0.45 * H);
  const double r0 = b.uniform(0.12, 0.2), r1 = r0 * b.uniform(0.6, 1.0);
  const int body = b.chance(0.7) ? b.pick(Palette::Ceramic) : b.pick(Palette::Metal);
  const int metal = b.pick(Palette::Metal), shade = b.pick(Palette::Shade);
  const double zs1 = H - 0.6 * sh, zs0 = zs1 - 0.04, z_max = std::min(zs0, H - sh) - 0.03;
  double top = 0;  // the body stays below the shade
  if (b.chance(0.5)) {
    const double rb = b.uniform(0.05, 0.09);
    top = std::min(b.uniform(0.25, 0.4) * H, z_max);
    b.cylinder("body", body, {-rb, -rb, 0}, {rb, rb, top});
  } else {
    const double rs = std::min(b.uniform(0.06, 0.1), (z_max - 0.02) / 2);
    b.cylinder("foot", body, {-0.04, -0.04, 0}, {0.04, 0.04, 0.02});
    b.sphere("body", body, {0, 0, 0.02 + rs}, rs);
    top = 0.02 + 2 * rs;
  }
  b.cylinder("neck", metal, {-0.008, -0.008, top}, {0.008, 0.008, zs0});
  b.cylinder("socket", metal, {-0.018, -0.018, zs0}, {0.018, 0.018, zs1});
  b.shadeRing(shade, {0, 0, H - sh}, r0, r1, sh, 10);
  bulb(b, {0, 0, zs1 + 0.035}, 1.5, 3.0);
}

/// Ceiling light: LED panel (emissive quad facing down in a frame), round flush diffuser
/// (emissive disk) or recessed downlight (open can with a spot light and a glowing lens).
void ceilingLight(Builder& b) {
  const int variant = b.integer(0, 2);
  const int housing = b.chance(0.7) ? b.material("paint_white") : b.pick(Palette::Metal);
  const int glow = b.pick(Palette::Emitter);
  if (variant == 0) {
    const double L1 = b.uniform(0.3, 0.6), L2 = b.chance(0.3) ? 1.2 : L1;
    const double t = b.uniform(0.03, 0.05), rw = 0.015;
    b.box("backing", housing, {-L1 / 2, -L2 / 2, 0.01}, {L1 / 2, L2 / 2, t});
    b.box("frame_front", housing, {-L1 / 2, -L2 / 2, 0}, {L1 / 2, -L2 / 2 + rw, 0.01});
    b.box("frame_back", housing, {-L1 / 2, L2 / 2 - rw, 0}, {L1 / 2, L2 / 2, 0.01});
    b.box("frame_left", housing, {-L1 / 2, -L2 / 2 + rw, 0}, {-L1 / 2 + rw, L2 / 2 - rw, 0.01});
    b.box("frame_right", housing, {L1 / 2 - rw, -L2 / 2 + rw, 0}, {L1 / 2, L2 / 2 - rw, 0.01});
    b.quad("diffuser", glow, {0, 0, 0.005}, L1 - 2 * rw, L2 - 2 * rw, Facing::Down);
  } else if (variant == 1) {
    const double D = b.uniform(0.25, 0.45), h = b.uniform(0.06, 0.1), Dd = 0.9 * D;
    b.cylinder("housing", housing, {-D / 2, -D / 2, 0.02}, {D / 2, D / 2, h});
    b.cylinder("diffuser", glow, {-Dd / 2, -Dd / 2, 0}, {Dd / 2, Dd / 2, 0.02});
  } else {
    const double a = b.uniform(0.08, 0.1), rw = 0.02, e = a / 2 + rw, c = a / 2 + 0.004;
    const double wt = 0.004, top = 0.1;
    b.box("trim_front", housing, {-e, -e, 0}, {e, -a / 2, 0.008});
    b.box("trim_back", housing, {-e, a / 2, 0}, {e, e, 0.008});
    b.box("trim_left", housing, {-e, -a / 2, 0}, {-a / 2, a / 2, 0.008});
    b.box("trim_right", housing, {a / 2, -a / 2, 0}, {e, a / 2, 0.008});
    b.box("can_front", housing, {-c, -c, 0.008}, {c, -a / 2, top});
    b.box("can_back", housing, {-c, a / 2, 0.008}, {c, c, top});
    b.box("can_left", housing, {-c, -a / 2, 0.008}, {-c + wt, a / 2, top});
    b.box("can_right", housing, {c - wt, -a / 2, 0.008}, {c, a / 2, top});
    b.box("can_top", housing, {-c, -c, top}, {c, c, top + 0.006});
    b.quad("lens", glow, {0, 0, 0.09}, a, a, Facing::Down);
    LightSpec l;
    l.type = LightType::Spot;
    l.position = {0, 0, 0.05};
    l.cone_deg = static_cast<float>(b.uniform(30, 40));
    l.intensity_w_sr = static_cast<float>(b.uniform(4, 8));
    l.temperature_k = b.chance(0.5) ? 3000.f : 4000.f;
    b.model().light = l;
  }
}

/// Pendant: ceiling canopy, cord, socket and an open shade around the bulb.
void pendantLight(Builder& b) {
  const double H = b.height(0.5, 1.0), r0 = b.uniform(0.12, 0.25), r1 = r0 * b.uniform(0.55, 1.0);
  const double sh = b.uniform(0.15, 0.3);
  const int shade = shadeMaterial(b, 0.4), metal = b.pick(Palette::Metal);
  b.shadeRing(shade, {0, 0, 0}, r0, r1, sh, 12);
  b.cylinder("socket", metal, {-0.018, -0.018, sh - 0.07}, {0.018, 0.018, sh - 0.02});
  b.cylinder("cord", b.material("plastic_black"), {-0.003, -0.003, sh - 0.02},
             {0.003, 0.003, H - 0.025});
  b.cylinder("canopy", metal, {-0.055, -0.055, H - 0.025}, {0.055, 0.055, H});
  bulb(b, {0, 0, sh - 0.11}, 3.0, 6.0);
}

/// Interior door: leaf (0.8..0.9 x 2.0..2.1 m) in a frame (two jambs and a head), lever
/// handles on both faces. The y extent straddles the wall; the hinge side is on the left. The
/// size hint gives the frame's outer size (the wall opening).
void door(Builder& b) {
  const double fw = b.uniform(0.05, 0.07), fd = b.uniform(0.1, 0.16), t = 0.04, g = 0.003;
  const double lw = b.width(0.8 + 2 * (fw + g), 0.9 + 2 * (fw + g)) - 2 * (fw + g);
  const double lh = b.height(2.0 + g + fw, 2.1 + g + fw) - g - fw;
  const int leaf = b.chance(0.6) ? b.pick(Palette::Painted) : b.pick(Palette::Wood);
  const int frame = b.chance(0.7) ? leaf : b.material("paint_white");
  const int metal = b.pick(Palette::Metal);
  b.box("jamb_left", frame, {-lw / 2 - g - fw, -fd / 2, 0}, {-lw / 2 - g, fd / 2, lh + g + fw});
  b.box("jamb_right", frame, {lw / 2 + g, -fd / 2, 0}, {lw / 2 + g + fw, fd / 2, lh + g + fw});
  b.box("head", frame, {-lw / 2 - g, -fd / 2, lh + g}, {lw / 2 + g, fd / 2, lh + g + fw});
  b.box("leaf", leaf, {-lw / 2, -t / 2, 0.01}, {lw / 2, t / 2, lh});
  // door stops behind the leaf, overlapping its edges by 1 cm: the 3 mm gap round the leaf is
  // not see-through (a front door's gap would show the void outside)
  // (parts meet without overlapping: the head stop between the side stops, these above the
  // threshold)
  const double sy0 = t / 2, sy1 = t / 2 + 0.012, so = 0.01, th = 0.012;
  b.box("stop_left", frame, {-lw / 2 - g, sy0, th}, {-lw / 2 + so, sy1, lh + g});
  b.box("stop_right", frame, {lw / 2 - so, sy0, th}, {lw / 2 + g, sy1, lh + g});
  b.box("stop_head", frame, {-lw / 2 + so, sy0, lh - so}, {lw / 2 - so, sy1, lh + g});
  // and a threshold under it, closing the 1 cm gap at the floor
  b.box("threshold", frame, {-lw / 2 - g, -fd / 2, 0}, {lw / 2 + g, fd / 2, th});
  const double xh = lw / 2 - 0.065, zh = b.uniform(0.95, 1.05);
  for (int s : {-1, 1}) {
    const std::string side = s < 0 ? "_front" : "_back";
    // y range [a, b] measured outwards from the leaf face on side s
    auto ys = [&](double a, double c) {
      return s < 0 ? std::pair{-t / 2 - c, -t / 2 - a} : std::pair{t / 2 + a, t / 2 + c};
    };
    auto [r0, r1] = ys(0, 0.01);
    b.cylinder("rose" + side, metal, {xh - 0.025, r0, zh - 0.025}, {xh + 0.025, r1, zh + 0.025},
               Axis::Y);
    auto [n0, n1] = ys(0.01, 0.05);
    b.cylinder("neck" + side, metal, {xh - 0.009, n0, zh - 0.009}, {xh + 0.009, n1, zh + 0.009},
               Axis::Y);
    auto [l0, l1] = ys(0.05, 0.065);
    b.box("lever" + side, metal, {xh - 0.12, l0, zh - 0.01}, {xh + 0.012, l1, zh + 0.01});
  }
}

/// Window: frame, optional mullion, thin-glass panes (quads facing the room) and a sill.
void window(Builder& b) {
  const double w = b.width(0.6, 1.6), h = b.height(0.8, 1.5);
  const double fw = b.uniform(0.05, 0.08), fd = b.uniform(0.06, 0.1), sd = b.uniform(0.03, 0.15);
  const int frame = b.chance(0.6) ? b.material("paint_white") : b.pick(Palette::Wood);
  const int sill = b.chance(0.5) ? b.pick(Palette::Stone) : frame;
  const int pane = b.material("pane_clear");
  b.box("frame_left", frame, {-w / 2, -fd / 2, 0}, {-w / 2 + fw, fd / 2, h});
  b.box("frame_right", frame, {w / 2 - fw, -fd / 2, 0}, {w / 2, fd / 2, h});
  b.box("frame_bottom", frame, {-w / 2 + fw, -fd / 2, 0}, {w / 2 - fw, fd / 2, fw});
  b.box("frame_top", frame, {-w / 2 + fw, -fd / 2, h - fw}, {w / 2 - fw, fd / 2, h});
  const double zc = h / 2, ph = h - 2 * fw;
  if (w > 1.0) {
    const double m = fw / 3;
    b.box("mullion", frame, {-m, -fd / 2 + 0.01, fw}, {m, fd / 2 - 0.01, h - fw});
    const double pw = w / 2 - fw - m;
    b.quad("pane_left", pane, {-m - pw / 2, 0, zc}, pw, ph, Facing::Front);
    b.quad("pane_right", pane, {m + pw / 2, 0, zc}, pw, ph, Facing::Front);
  } else {
    b.quad("pane", pane, {0, 0, zc}, w - 2 * fw, ph, Facing::Front);
  }
  b.box("sill", sill, {-w / 2 - 0.03, -fd / 2 - sd, 0}, {w / 2 + 0.03, -fd / 2, 0.025});
  b.model().mount_height = b.uniform(0.8, 1.0);
}

/// A rod on two brackets (wall at y = 0) with translucent panels hanging below it: `panels` of 1
/// (from the left) or 2 (from both ends), each covering `cover` of the width, a continuous sheet
/// of folds about 12 cm wide and 3 cm deep (at most `pleats` per panel).
void drape(Builder& b, double W, double drop, int panels, double cover, int pleats) {
  const double r = b.uniform(0.01, 0.015), yr = -0.1;
  const int cloth = b.pick(Palette::Curtain), metal = b.pick(Palette::Metal);
  b.cylinder("rod", metal, {-W / 2, yr - r, drop}, {W / 2, yr + r, drop + 2 * r}, Axis::X);
  for (int s : {-1, 1}) {
    const double x = s * (W / 2 - 0.08);
    b.box(s < 0 ? "bracket_left" : "bracket_right", metal, {x - 0.01, yr + r, drop},
          {x + 0.01, 0, drop + 2 * r});
  }
  const int folds = std::clamp(static_cast<int>(std::lround(cover * W / 0.12)), 2, pleats);
  const double fw = cover * W / folds, fd = 0.03;
  for (int p = 0; p < panels; ++p)
    for (int i = 0; i < folds; ++i) {
      const double x0 = p == 0 ? -W / 2 + i * fw : W / 2 - (i + 1) * fw;
      b.rotated("panel_" + std::to_string(p) + "_fold_" + std::to_string(i), "fold", cloth,
                {x0 + fw / 2, yr - 0.01, drop / 2}, {fw, fd, drop}, Mat3::Identity());
    }
}

void curtain(Builder& b) {
  const double W = b.width(1.0, 2.6), drop = b.height(1.8, 2.5);
  const double cover = b.uniform(0.2, 0.5);
  drape(b, W, drop, 2, cover, b.integer(4, 7));
  b.model().mount_height = b.uniform(0.01, 0.03);
}

/// Shower curtain: one panel on a rod, hung along a bathtub's open side.
void showerCurtain(Builder& b) {
  const double W = b.width(1.4, 1.8), drop = b.height(1.6, 1.8);
  const double cover = b.uniform(0.6, 0.95);
  drape(b, W, drop, 1, cover, b.integer(8, 12));
  b.model().mount_height = b.uniform(0.35, 0.45);
}

/// Window blinds: venetian (head rail, slats, bottom rail) or roller (tube, sheet, bar).
void blinds(Builder& b) {
  const double w = b.width(0.6, 1.6), h = b.height(1.0, 1.6);
  if (b.chance(0.6)) {
    const double sd = b.uniform(0.025, 0.05), pitch = 0.85 * sd;
    const int mat = b.chance(0.5) ? b.material("plastic_white") : b.pick(Palette::Wood);
    b.box("head_rail", mat, {-w / 2, -sd - 0.01, h - 0.05}, {w / 2, 0, h});
    b.box("bottom_rail", mat, {-w / 2 + 0.005, -sd - 0.005, 0}, {w / 2 - 0.005, -0.005, 0.02});
    int k = 0;
    for (double z = 0.02 + pitch; z + 0.002 < h - 0.055; z += pitch, ++k)
      b.box("slat_" + std::to_string(k), mat, {-w / 2 + 0.01, -sd - 0.005, z},
            {w / 2 - 0.01, -0.005, z + 0.002});
  } else {
    const int cloth = b.pick(Palette::Curtain), mat = b.material("plastic_white");
    b.cylinder("tube", mat, {-w / 2, -0.06, h - 0.05}, {w / 2, -0.01, h}, Axis::X);
    b.box("sheet", cloth, {-w / 2 + 0.01, -0.062, 0.02}, {w / 2 - 0.01, -0.06, h - 0.025});
    b.box("bottom_bar", mat, {-w / 2 + 0.01, -0.066, 0}, {w / 2 - 0.01, -0.056, 0.02});
  }
  b.model().mount_height = b.uniform(0.85, 1.0);
}

/// Four frame pieces of width fw round a w x h opening, depth fd centred on y = 0.
void frame4(Builder& b, int mat, double w, double h, double fw, double fd) {
  b.box("frame_left", mat, {-w / 2, -fd / 2, 0}, {-w / 2 + fw, fd / 2, h});
  b.box("frame_right", mat, {w / 2 - fw, -fd / 2, 0}, {w / 2, fd / 2, h});
  b.box("frame_bottom", mat, {-w / 2 + fw, -fd / 2, 0}, {w / 2 - fw, fd / 2, fw});
  b.box("frame_top", mat, {-w / 2 + fw, -fd / 2, h - fw}, {w / 2 - fw, fd / 2, h});
}

/// Picture: a framed canvas (optionally on a mat board) or a bare stretched canvas.
void picture(Builder& b) {
  const double w = b.width(0.3, 1.2), h = b.height(0.3, 0.9);
  const int canvas = b.pick(Palette::Canvas);
  if (b.chance(0.7)) {
    const double fw = b.uniform(0.02, 0.06), fd = b.uniform(0.02, 0.04);
    const int frame = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
    frame4(b, frame, w, h, fw, fd);
    const double ow = w - 2 * fw, oh = h - 2 * fw;
    const double mw = b.chance(0.5) ? std::min(b.uniform(0.03, 0.08), 0.25 * std::min(ow, oh)) : 0;
    if (mw > 0) {
      b.box("mat", b.material("paper_white"), {-ow / 2, 0, fw}, {ow / 2, fd / 2, h - fw});
      b.box("canvas", canvas, {-ow / 2 + mw, -0.001, fw + mw}, {ow / 2 - mw, 0, h - fw - mw});
    } else {
      b.box("canvas", canvas, {-ow / 2, 0, fw}, {ow / 2, fd / 2, h - fw});
    }
  } else {
    const double cd = b.uniform(0.02, 0.04);
    b.box("canvas", canvas, {-w / 2, -cd / 2, 0}, {w / 2, cd / 2, h});
  }
  b.model().mount_height = b.uniform(1.2, 1.6);
}

void whiteboard(Builder& b) {
  const double w = b.width(0.9, 1.8), h = b.height(0.6, 1.2), f = 0.015, d = 0.02;
  const int metal = b.pick(Palette::Metal);
  frame4(b, metal, w, h, f, d);
  b.box("board", b.material("whiteboard"), {-w / 2 + f, -d / 2 + 0.004, f},
        {w / 2 - f, d / 2, h - f});
  b.box("tray", metal, {-w / 3, -d / 2 - 0.06, 0}, {w / 3, -d / 2, 0.02});
  b.model().mount_height = b.uniform(0.8, 1.0);
}

/// Rug: rectangular or (without size hints) round, 6..20 mm thick.
void rug(Builder& b) {
  const bool round = !b.hinted() && b.chance(0.25);
  const int mat = b.pick(Palette::Carpet);
  const double t = b.uniform(0.006, 0.02);
  if (round) {
    const double D = b.uniform(1.0, 2.0);
    b.cylinder("rug", mat, {-D / 2, -D / 2, 0}, {D / 2, D / 2, t});
  } else {
    const double w = b.width(1.2, 3.0), d = b.depth(0.8, 2.0);
    b.box("rug", mat, {-w / 2, -d / 2, 0}, {w / 2, d / 2, t});
  }
}

}  // namespace

const std::vector<CategoryDef>& fixtureCategories() {
  static const std::vector<CategoryDef> v = {
      {"floor_lamp", "lamp", floorLamp, 3, 8, true, P::Floor},
      {"table_lamp", "lamp", tableLamp, 1, 3, true, P::OnSurface},
      {"ceiling_light", "lamp", ceilingLight, 0.5, 3, false, P::Ceiling},
      {"pendant_light", "lamp", pendantLight, 0.5, 2.5, false, P::Ceiling},
      {"door", "door", door, 15, 30, false, P::InWall},
      {"window", "window", window, 10, 30, false, P::InWall},
      {"curtain", "curtain", curtain, 1, 4, false, P::Wall},
      {"shower_curtain", "shower_curtain", showerCurtain, 0.5, 1.5, false, P::Wall},
      {"blinds", "blinds", blinds, 1, 4, false, P::Wall},
      {"picture", "picture", picture, 0.5, 5, false, P::Wall},
      {"whiteboard", "whiteboard", whiteboard, 3, 10, false, P::Wall},
      {"rug", "floor_mat", rug, 1, 10, true, P::Floor},
  };
  return v;
}

}  // namespace inet::furniture
