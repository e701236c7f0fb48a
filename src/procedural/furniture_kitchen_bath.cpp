// Furniture catalogue: kitchen and bathroom (dimensions from common fittings, metres).
#include <algorithm>
#include <cmath>

#include "procedural/furniture_builder.h"

namespace inet::furniture {
namespace {

using P = FurnitureModel::Placement;

int ceramic(Builder& b) {
  static const char* kNames[] = {"ceramic_white", "ceramic_white", "ceramic_cream", "ceramic_grey"};
  return b.material(kNames[b.integer(0, 3)]);
}

int applianceFinish(Builder& b) {
  static const char* kNames[] = {"plastic_white", "stainless", "plastic_black"};
  return b.material(kNames[b.integer(0, 2)]);
}

/// A cabinet body filling x0..x1, y0..y1, z0..z1 except the box above z_cut around the hole
/// (hx0..hx1, hy0..hy1) where a basin hangs.
void bodyAroundHole(Builder& b, int mat, const Vec3& lo, const Vec3& hi, double z_cut, double hx0,
                    double hx1, double hy0, double hy1, int nyu40) {
  b.box("body", mat, lo, {hi.x(), hi.y(), z_cut}, nyu40);
  b.box("body_front", mat, {lo.x(), lo.y(), z_cut}, {hi.x(), hy0, hi.z()}, nyu40);
  b.box("body_back", mat, {lo.x(), hy1, z_cut}, {hi.x(), hi.y(), hi.z()}, nyu40);
  b.box("body_left", mat, {lo.x(), hy0, z_cut}, {hx0, hy1, hi.z()}, nyu40);
  b.box("body_right", mat, {hx1, hy0, z_cut}, {hi.x(), hy1, hi.z()}, nyu40);
}

/// Base cabinets under a worktop, optionally with a recessed sink and faucet. Doors or drawers
/// per 0.6 m module; the fronts sit 3 mm behind the worktop's front edge with their handles.
void counter(Builder& b, bool sink) {
  const double w = b.width(sink ? 0.8 : 0.6, 2.4), d = b.depth(0.6, 0.65);
  const double h = b.height(0.88, 0.92), tt = b.uniform(0.03, 0.04), zt = h - tt;
  const double base = b.uniform(0.1, 0.15);
  const int cab = nyu40Id("cabinet");
  const int body = b.chance(0.6) ? b.pick(Palette::Painted) : b.pick(Palette::Wood);
  const int top = b.chance(0.7) ? b.pick(Palette::Stone) : b.pick(Palette::Wood);
  FrontGrid g;
  g.drawers = !sink && b.chance(0.3);  // under a sink: doors
  g.rows = g.drawers ? 3 : 1;
  g.cols = std::max(1, static_cast<int>(std::lround(w / 0.6)));
  g.front_mat = body;
  g.handle_mat = b.pick(Palette::Metal);
  g.nyu40 = cab;
  const double y_front = -d / 2 + 0.003 + g.handle_d, y_body = y_front + g.t;
  fronts(b, g, -w / 2, w / 2, base, zt, y_front);
  b.box("plinth", body, {-w / 2 + 0.01, y_body + 0.05, 0}, {w / 2 - 0.01, d / 2 - 0.01, base}, cab);
  b.model().support_heights = {h};
  if (!sink) {
    b.box("body", body, {-w / 2, y_body, base}, {w / 2, d / 2, zt}, cab);
    b.box("countertop", top, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h});
    return;
  }
  const double bw = std::min(w - 0.2, b.uniform(0.4, 0.55)),
               bd = std::min(d - 0.17, b.uniform(0.35, 0.42));
  const double depth = b.uniform(0.16, 0.2);
  const int module = b.integer(0, g.cols - 1);
  const double cx =
      std::clamp(-w / 2 + (module + 0.5) * w / g.cols, -w / 2 + 0.1 + bw / 2, w / 2 - 0.1 - bw / 2);
  const double hx0 = cx - bw / 2, hx1 = cx + bw / 2, hy0 = -d / 2 + 0.07, hy1 = hy0 + bd;
  bodyAroundHole(b, body, {-w / 2, y_body, base}, {w / 2, d / 2, zt}, h - depth, hx0, hx1, hy0, hy1,
                 cab);
  const int basin = b.chance(0.7) ? b.material("stainless") : ceramic(b);
  slabWithBasin(b, "countertop", top, basin, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h}, hx0, hx1, hy0,
                hy1, depth, 0.01, 0, nyu40Id("sink"));
  const double fy = (hy1 + d / 2) / 2, fh = b.uniform(0.2, 0.3);
  faucet(b, b.pick(Palette::Metal), cx, fy, h, fh, fy - (hy0 + hy1) / 2);
}

void kitchenCounter(Builder& b) {
  counter(b, false);
}
void kitchenSinkCounter(Builder& b) {
  counter(b, true);
}

void upperCabinet(Builder& b) {
  const double w = b.width(0.6, 1.2), d = b.depth(0.3, 0.35), h = b.height(0.6, 0.9);
  const int body = b.chance(0.6) ? b.pick(Palette::Painted) : b.pick(Palette::Wood);
  FrontGrid g;
  g.cols = w > 0.7 ? 2 : 1;
  g.front_mat = body;
  g.handle_mat = b.pick(Palette::Metal);
  caseGoods(b, g, body, {-w / 2, -d / 2, 0}, {w / 2, d / 2, h}, 0.0, false);
  b.model().mount_height = b.uniform(1.4, 1.5);
}

/// Fridge-freezer: body, freezer door below, fridge door above, vertical handles.
void refrigerator(Builder& b) {
  const double w = b.width(0.55, 0.7), d = b.depth(0.6, 0.7), h = b.height(1.7, 2.0);
  const int finish = applianceFinish(b), handle = b.pick(Palette::Metal);
  const double hd = 0.035, y_door = -d / 2 + hd, y_body = y_door + 0.05;
  const double split = b.uniform(0.3, 0.38) * h, xh = w / 2 - 0.06;
  b.box("body", finish, {-w / 2, y_body, 0}, {w / 2, d / 2, h});
  b.box("freezer_door", finish, {-w / 2, y_door, 0.03}, {w / 2, y_body, split - 0.0015});
  b.box("fridge_door", finish, {-w / 2, y_door, split + 0.0015}, {w / 2, y_body, h - 0.005});
  b.box("freezer_handle", handle, {xh, -d / 2, split - 0.25}, {xh + 0.02, y_door, split - 0.05});
  b.box("fridge_handle", handle, {xh, -d / 2, split + 0.05}, {xh + 0.02, y_door, split + 0.45});
}

/// Free-standing cooker: oven door, control panel with knobs, glass-ceramic or steel hob.
void stove(Builder& b) {
  const double w = b.width(0.5, 0.6), d = b.depth(0.58, 0.62), h = b.height(0.85, 0.92);
  const int finish = applianceFinish(b), handle = b.pick(Palette::Metal);
  const bool ceramic_hob = b.chance(0.6);
  const int hob = b.material(ceramic_hob ? "screen_black" : "stainless");
  const int rings = b.material(ceramic_hob ? "plastic_grey" : "powder_black");
  const int black = b.material("plastic_black");
  const double yf = -d / 2 + 0.035, yd = yf - 0.02, zh = h - 0.008;
  b.box("body", finish, {-w / 2, yf, 0}, {w / 2, d / 2, zh});
  b.box("hob", hob, {-w / 2, yf, zh}, {w / 2, d / 2, h});
  b.box("oven_door", b.material("screen_black"), {-w / 2 + 0.02, yd, 0.1},
        {w / 2 - 0.02, yf, h - 0.2});
  b.box("control_panel", finish, {-w / 2 + 0.02, yd, h - 0.17}, {w / 2 - 0.02, yf, h - 0.03});
  b.cylinder("oven_handle", handle, {-w / 2 + 0.06, -d / 2, h - 0.26},
             {w / 2 - 0.06, yd, h - 0.245}, Axis::X);
  for (int i = 0; i < 4; ++i) {
    const double x = -w / 2 + (i + 1) * w / 5;
    b.cylinder("knob_" + std::to_string(i), black, {x - 0.0175, yd - 0.015, h - 0.1175},
               {x + 0.0175, yd, h - 0.0825}, Axis::Y);
  }
  const double depth = d / 2 - yf, r = std::min(w / 4, 0.22 * depth) - 0.015;  // 2r < gap
  for (int i = 0; i < 4; ++i) {
    const double x = (i % 2 ? 1 : -1) * w / 4, y = yf + depth * (i < 2 ? 0.28 : 0.72);
    b.cylinder("burner_" + std::to_string(i), rings, {x - r, y - r, h}, {x + r, y + r, h + 0.003});
  }
  b.model().support_heights = {h + 0.003};
}

/// Front-loading washing machine: body, top, control panel, round door with glass.
void washingMachine(Builder& b) {
  const double w = b.width(0.595, 0.6), d = b.depth(0.55, 0.65), h = b.height(0.82, 0.86);
  const int finish = b.chance(0.8) ? b.material("plastic_white") : b.material("plastic_grey");
  const int ring = b.chance(0.5) ? b.material("chrome") : b.material("plastic_grey");
  const double yf = -d / 2 + 0.03, D = b.uniform(0.3, 0.34), zc = 0.45 * h;
  b.box("body", finish, {-w / 2, yf, 0}, {w / 2, d / 2, h - 0.02});
  b.box("top", finish, {-w / 2, yf, h - 0.02}, {w / 2, d / 2, h});
  b.box("control_panel", finish, {-w / 2 + 0.01, yf - 0.02, h - 0.15},
        {w / 2 - 0.01, yf, h - 0.03});
  b.cylinder("knob", b.material("plastic_grey"), {w / 4 - 0.025, -d / 2, h - 0.115},
             {w / 4 + 0.025, yf - 0.02, h - 0.065}, Axis::Y);
  b.cylinder("door_ring", ring, {-D / 2, yf - 0.025, zc - D / 2}, {D / 2, yf, zc + D / 2}, Axis::Y);
  const double g = D - 0.08;
  b.cylinder("door_glass", b.material("glass_clear"), {-g / 2, -d / 2, zc - g / 2},
             {g / 2, yf - 0.025, zc + g / 2}, Axis::Y);
  b.model().support_heights = {h};
}

/// Toilet: pedestal, bowl, seat, cistern and flush button.
void toilet(Builder& b) {
  const double bw = b.width(0.35, 0.4), D = b.depth(0.6, 0.72), H = b.height(0.72, 0.85);
  const double cd = b.uniform(0.16, 0.2), cw = b.uniform(0.36, 0.45);
  const double seat_top = b.uniform(0.4, 0.44), zb = seat_top - 0.02;
  const int cer = ceramic(b);
  const int seat = b.chance(0.75) ? b.material("plastic_white") : b.pick(Palette::Wood);
  b.box("pedestal", cer, {-0.1, -D / 2 + 0.15, 0}, {0.1, D / 2 - 0.6 * cd, 0.2});
  b.cylinder("bowl", cer, {-bw / 2, -D / 2, 0.2}, {bw / 2, D / 2 - 0.4 * cd, zb});
  b.cylinder("seat", seat, {-bw / 2, -D / 2, zb}, {bw / 2, D / 2 - cd, seat_top});
  b.box("cistern", cer, {-cw / 2, D / 2 - cd, zb}, {cw / 2, D / 2, H});
  b.cylinder("flush_button", b.material("chrome"), {-0.025, D / 2 - cd / 2 - 0.025, H},
             {0.025, D / 2 - cd / 2 + 0.025, H + 0.006});
}

/// Bathtub: four full-height walls round a raised bottom, faucet on the back rim.
void bathtub(Builder& b) {
  const double L = b.width(1.5, 1.8), W = b.depth(0.7, 0.8), H = b.height(0.5, 0.6);
  const double ts = b.uniform(0.06, 0.08), te = b.uniform(0.1, 0.15);
  const int cer = ceramic(b);
  b.box("wall_front", cer, {-L / 2, -W / 2, 0}, {L / 2, -W / 2 + ts, H});
  b.box("wall_back", cer, {-L / 2, W / 2 - ts, 0}, {L / 2, W / 2, H});
  b.box("end_left", cer, {-L / 2, -W / 2 + ts, 0}, {-L / 2 + te, W / 2 - ts, H});
  b.box("end_right", cer, {L / 2 - te, -W / 2 + ts, 0}, {L / 2, W / 2 - ts, H});
  b.box("bottom", cer, {-L / 2 + te, -W / 2 + ts, 0}, {L / 2 - te, W / 2 - ts, 0.1});
  faucet(b, b.pick(Palette::Metal), L / 2 - te - 0.15, W / 2 - ts / 2, H, 0.1, 0.15);
}

/// Washbasin: a vanity cabinet under a worktop with a recessed basin, or a pedestal basin.
void bathroomBasin(Builder& b) {
  const bool vanity = b.chance(0.65);
  const double w = vanity ? b.width(0.6, 1.2) : b.width(0.5, 0.65);
  const double d = b.depth(0.45, 0.55), h = b.height(0.8, 0.9);
  const int cer = ceramic(b), metal = b.pick(Palette::Metal);
  const double bw = std::min(w - 0.12, b.uniform(0.4, 0.55));
  const double bd = std::min(d - 0.17, b.uniform(0.3, 0.38)), depth = b.uniform(0.12, 0.16);
  const double hx0 = -bw / 2, hx1 = bw / 2, hy0 = -d / 2 + 0.06, hy1 = hy0 + bd;
  if (vanity) {
    const int cab = nyu40Id("cabinet");
    const int body = b.chance(0.6) ? b.pick(Palette::Painted) : b.pick(Palette::Wood);
    const int top = b.chance(0.5) ? b.pick(Palette::Stone) : cer;
    const double zt = h - b.uniform(0.02, 0.04), base = b.uniform(0.08, 0.12);
    FrontGrid g;
    g.cols = w > 0.8 ? 2 : 1;
    g.front_mat = body;
    g.handle_mat = metal;
    g.nyu40 = cab;
    const double y_front = -d / 2 + 0.003 + g.handle_d, y_body = y_front + g.t;
    fronts(b, g, -w / 2, w / 2, base, zt, y_front);
    b.box("plinth", body, {-w / 2 + 0.01, y_body + 0.05, 0}, {w / 2 - 0.01, d / 2 - 0.01, base},
          cab);
    bodyAroundHole(b, body, {-w / 2, y_body, base}, {w / 2, d / 2, zt}, h - depth, hx0, hx1, hy0,
                   hy1, cab);
    slabWithBasin(b, "countertop", top, cer, {-w / 2, -d / 2, zt}, {w / 2, d / 2, h}, hx0, hx1, hy0,
                  hy1, depth, 0.012, nyu40Id("counter"), 0);
  } else {  // the rim is as deep as the basin; the pedestal carries the basin's bottom
    slabWithBasin(b, "rim", cer, cer, {-w / 2, -d / 2, h - depth}, {w / 2, d / 2, h}, hx0, hx1, hy0,
                  hy1, depth, 0.012, 0, 0);
    b.cylinder("pedestal", cer, {-0.09, hy1 - 0.2, 0}, {0.09, hy1 - 0.02, h - depth});
  }
  const double fy = (hy1 + d / 2) / 2;
  faucet(b, metal, 0, fy, h, b.uniform(0.12, 0.2), fy - (hy0 + hy1) / 2);
}

/// Corner shower: tray, glass panels on the open front and left side, head on the back wall.
void shower(Builder& b) {
  const double s = b.width(0.8, 1.0), d = b.depth(0.8, 1.0), H = b.height(2.0, 2.1);
  const double th = b.uniform(0.04, 0.06), t = 0.008, rail = 0.03;
  const int tray = b.chance(0.7) ? b.material("ceramic_white") : b.material("tiles_white");
  const int glass = b.material("pane_clear"), metal = b.pick(Palette::Metal);
  b.box("tray", tray, {-s / 2, -d / 2, 0}, {s / 2, d / 2, th});
  b.box("glass_front", glass, {-s / 2, -d / 2, th}, {s / 2, -d / 2 + t, H - rail});
  b.box("glass_left", glass, {-s / 2, -d / 2 + t, th}, {-s / 2 + t, d / 2, H - rail});
  b.box("rail_front", metal, {-s / 2, -d / 2, H - rail}, {s / 2, -d / 2 + t, H});
  b.box("rail_left", metal, {-s / 2, -d / 2 + t, H - rail}, {-s / 2 + t, d / 2, H});
  const double xr = s / 4;
  b.box("mixer", metal, {xr - 0.08, d / 2 - 0.05, 0.95}, {xr + 0.08, d / 2, 1.0});
  b.cylinder("riser", metal, {xr - 0.01, d / 2 - 0.02, 1.0}, {xr + 0.01, d / 2, H - 0.09});
  b.box("arm", metal, {xr - 0.01, d / 2 - 0.2, H - 0.11}, {xr + 0.01, d / 2 - 0.02, H - 0.09});
  b.cylinder("head", metal, {xr - 0.1, d / 2 - 0.3, H - 0.13}, {xr + 0.1, d / 2 - 0.1, H - 0.11});
}

/// Wall mirror: framed (frame, backing, glass) or a frameless pane.
void mirror(Builder& b) {
  const double w = b.width(0.4, 1.0), h = b.height(0.5, 1.2);
  const int glass = b.material("mirror_silver");
  if (b.chance(0.6)) {
    const double fw = b.uniform(0.03, 0.07), fd = b.uniform(0.02, 0.04);
    const int frame = b.chance(0.6) ? b.pick(Palette::Wood) : b.pick(Palette::Metal);
    b.box("frame_left", frame, {-w / 2, -fd / 2, 0}, {-w / 2 + fw, fd / 2, h});
    b.box("frame_right", frame, {w / 2 - fw, -fd / 2, 0}, {w / 2, fd / 2, h});
    b.box("frame_bottom", frame, {-w / 2 + fw, -fd / 2, 0}, {w / 2 - fw, fd / 2, fw});
    b.box("frame_top", frame, {-w / 2 + fw, -fd / 2, h - fw}, {w / 2 - fw, fd / 2, h});
    b.box("glass", glass, {-w / 2 + fw, -0.003, fw}, {w / 2 - fw, 0.003, h - fw});
    b.box("backing", frame, {-w / 2 + fw, 0.003, fw}, {w / 2 - fw, fd / 2, h - fw});
  } else {
    b.box("glass", glass, {-w / 2, -0.003, 0}, {w / 2, 0.003, h});
  }
  b.model().mount_height = b.uniform(1.0, 1.3);
}

/// Towel hanging over a wall-mounted rail.
void towel(Builder& b) {
  const double w = b.width(0.4, 0.7), L = b.uniform(0.3, 0.5), t = 0.012, r = 0.012;
  const int cloth = b.pick(Palette::Towel), metal = b.pick(Palette::Metal);
  const double yr = -0.06, zr = L;  // rail axis; the wall is at y = 0
  const double tw = w - 0.06;
  b.box("bracket_left", metal, {-w / 2, yr - r, zr - r}, {-w / 2 + 0.02, 0, zr + r});
  b.box("bracket_right", metal, {w / 2 - 0.02, yr - r, zr - r}, {w / 2, 0, zr + r});
  b.cylinder("rail", metal, {-w / 2 + 0.02, yr - r, zr - r}, {w / 2 - 0.02, yr + r, zr + r},
             Axis::X);
  b.box("towel_front", cloth, {-tw / 2, yr - r - t, zr + r - L}, {tw / 2, yr - r, zr + r});
  b.box("towel_back", cloth, {-tw / 2, yr + r, zr + r - 0.85 * L}, {tw / 2, yr + r + t, zr + r});
  b.box("towel_top", cloth, {-tw / 2, yr - r - t, zr + r}, {tw / 2, yr + r + t, zr + r + t});
  b.model().mount_height = b.uniform(0.9, 1.3);
}

}  // namespace

const std::vector<CategoryDef>& kitchenBathCategories() {
  static const std::vector<CategoryDef> v = {
      {"kitchen_counter", "counter", kitchenCounter, 40, 90, false, P::Floor},
      {"kitchen_sink_counter", "counter", kitchenSinkCounter, 40, 90, false, P::Floor},
      {"upper_cabinet", "cabinet", upperCabinet, 10, 25, false, P::Wall},
      {"refrigerator", "refridgerator", refrigerator, 55, 90, false, P::Floor},
      {"stove", "otherfurniture", stove, 40, 70, false, P::Floor},
      {"washing_machine", "otherfurniture", washingMachine, 60, 80, false, P::Floor},
      {"toilet", "toilet", toilet, 20, 35, false, P::Floor},
      {"bathtub", "bathtub", bathtub, 25, 60, false, P::Floor},
      {"bathroom_basin", "sink", bathroomBasin, 15, 45, false, P::Floor},
      {"shower", "otherstructure", shower, 45, 80, false, P::Floor},
      {"mirror", "mirror", mirror, 2, 12, false, P::Wall},
      {"towel", "towel", towel, 0.3, 1.0, false, P::Wall},
  };
  return v;
}

}  // namespace inet::furniture
