#include "core/plot.h"

#include "core/image_io.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"

namespace inet {
namespace {

constexpr double kTickFont = 12.5, kLabelFont = 14, kTitleFont = 16;
constexpr double kPad = 8;        // generic gap between elements, pixels
constexpr double kMargin = 0.05;  // data range padding on each side (fraction of the span)
constexpr double kLegendRow = 20, kLegendSwatch = 26;
const Rgb kInk{30, 30, 30}, kGrid{225, 225, 225}, kFrame{90, 90, 90};

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void setColour(cairo_t* cr, Rgb c) {
  cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0);
}

void setFont(cairo_t* cr, double size, bool bold = false) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double textWidth(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

double textHeight(cairo_t* cr) {
  cairo_font_extents_t f;
  cairo_font_extents(cr, &f);
  return f.ascent + f.descent;
}

/// Draws `s` so that the point (ax, ay) of its box (0 = left/top, 1 = right/bottom) lies at
/// (x, y), rotated by `angle` radians about that point.
void drawText(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay,
              double angle = 0) {
  if (s.empty()) return;
  cairo_font_extents_t f;
  cairo_font_extents(cr, &f);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  cairo_move_to(cr, -ax * textWidth(cr, s), f.ascent - ay * (f.ascent + f.descent));
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

std::string formatTick(double v, double step) {
  if (std::abs(v) < step * 1e-9) v = 0;  // no "-0" or "1e-17"
  const double mag = std::max(std::abs(v), step);
  if (mag >= 1e6 || step < 1e-4) return fmt::format("{:g}", v);
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  return fmt::format("{:.{}f}", v, decimals);
}

/// One axis: range in "axis units" (log10 of the value on a log axis) and its ticks.
struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  std::vector<double> major;  // axis units
  std::vector<std::string> labels;
  std::vector<double> minor;  // axis units, log axes only

  double toAxis(double v) const { return log ? std::log10(v) : v; }
  bool valid(double v) const { return std::isfinite(v) && (!log || v > 0); }

  void makeTicks(int target) {
    major.clear(), labels.clear(), minor.clear();
    if (log && hi - lo >= 1.0) {
      const int d0 = static_cast<int>(std::ceil(lo - 1e-9)),
                d1 = static_cast<int>(std::floor(hi + 1e-9));
      const int stride = std::max(1, (d1 - d0 + target - 1) / target);
      for (int d = d0; d <= d1; d += stride) {
        major.push_back(d);
        labels.push_back(fmt::format("{:g}", std::pow(10.0, d)));
      }
      if (hi - lo <= 8)
        for (int d = d0 - 1; d <= d1; ++d)
          for (int m = 2; m <= 9; ++m) {
            const double a = d + std::log10(m);
            if (a >= lo && a <= hi) minor.push_back(a);
          }
      return;
    }
    const double vlo = log ? std::pow(10.0, lo) : lo, vhi = log ? std::pow(10.0, hi) : hi;
    const std::vector<double> t = niceTicks(vlo, vhi, target);
    const double step = t.size() > 1 ? t[1] - t[0] : std::max(std::abs(vhi - vlo), 1e-12);
    for (double v : t) {
      if (log && v <= 0) continue;
      major.push_back(toAxis(v));
      labels.push_back(formatTick(v, step));
    }
  }
};

/// Axis range from data values (axis units), padded by kMargin, or the fixed range.
Axis makeAxis(const std::vector<const std::vector<double>*>& data, bool log,
              const std::optional<std::pair<double, double>>& fixed, const std::string& path,
              const char* name) {
  Axis a;
  a.log = log;
  if (fixed) {
    if (!(fixed->first < fixed->second) || !a.valid(fixed->first) || !a.valid(fixed->second))
      throw InputError(path, std::string(name) + " range",
                       fmt::format("invalid range [{}, {}]", fixed->first, fixed->second));
    a.lo = a.toAxis(fixed->first), a.hi = a.toAxis(fixed->second);
    return a;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto* d : data)
    for (double v : *d)
      if (a.valid(v)) lo = std::min(lo, a.toAxis(v)), hi = std::max(hi, a.toAxis(v));
  if (!(lo <= hi)) {
    if (log) throw InputError(path, name, "a log axis needs positive data");
    lo = 0, hi = 1;
  }
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(lo))) {
    const double h = std::max(std::abs(lo) * 0.1, log ? 0.5 : 0.5);
    lo -= h, hi += h;
  } else {
    const double pad = (hi - lo) * kMargin;
    lo -= pad, hi += pad;
  }
  a.lo = lo, a.hi = hi;
  return a;
}

/// Widens the range of the axis that has more pixels per unit, so both have the same.
void equalizeAspect(Axis& x, Axis& y, double w_px, double h_px) {
  const double sx = w_px / (x.hi - x.lo), sy = h_px / (y.hi - y.lo);
  Axis& a = sx > sy ? x : y;
  const double s = std::min(sx, sy), px = sx > sy ? w_px : h_px;
  const double c = 0.5 * (a.lo + a.hi), half = 0.5 * px / s;
  a.lo = c - half, a.hi = c + half;
}

Rgb seriesColour(const Series& s, size_t k) {
  return s.colour ? *s.colour : paletteColour(static_cast<int>(k));
}

void validateSize(const PlotSpec& spec, const std::string& path) {
  if (spec.width < 100 || spec.width > 8000 || spec.height < 100 || spec.height > 8000)
    throw InputError(
        path, "plot size",
        fmt::format("{} x {} pixels; each side must be 100 .. 8000", spec.width, spec.height));
}

void drawTitle(cairo_t* cr, const PlotSpec& spec, double x0, double y0) {
  setColour(cr, kInk);
  setFont(cr, kTitleFont, true);
  drawText(cr, spec.title, x0 + spec.width / 2.0, y0 + kPad, 0.5, 0);
}

/// Grid, frame, ticks and tick labels of both axes for the plot area of `f`.
void drawAxes(cairo_t* cr, const PlotFrame& f, const Axis& x, const Axis& y) {
  cairo_set_line_width(cr, 1);
  setColour(cr, kGrid);
  for (double a : x.major) {
    const double px = std::round(f.toPixel(x.log ? std::pow(10, a) : a, 1)[0]) + 0.5;
    cairo_move_to(cr, px, f.top), cairo_line_to(cr, px, f.bottom);
  }
  for (double a : y.major) {
    const double py = std::round(f.toPixel(1, y.log ? std::pow(10, a) : a)[1]) + 0.5;
    cairo_move_to(cr, f.left, py), cairo_line_to(cr, f.right, py);
  }
  cairo_stroke(cr);
  setColour(cr, kFrame);
  cairo_rectangle(cr, f.left + 0.5, f.top + 0.5, f.right - f.left - 1, f.bottom - f.top - 1);
  cairo_stroke(cr);
  setFont(cr, kTickFont);
  auto xpix = [&](double a) { return f.left + (a - x.lo) / (x.hi - x.lo) * (f.right - f.left); };
  auto ypix = [&](double a) { return f.bottom - (a - y.lo) / (y.hi - y.lo) * (f.bottom - f.top); };
  for (size_t i = 0; i < x.major.size(); ++i) {
    const double px = xpix(x.major[i]);
    cairo_move_to(cr, px, f.bottom), cairo_line_to(cr, px, f.bottom + 5);
    drawText(cr, x.labels[i], px, f.bottom + 7, 0.5, 0);
  }
  for (double a : x.minor)
    cairo_move_to(cr, xpix(a), f.bottom), cairo_line_to(cr, xpix(a), f.bottom + 3);
  for (size_t i = 0; i < y.major.size(); ++i) {
    const double py = ypix(y.major[i]);
    cairo_move_to(cr, f.left - 5, py), cairo_line_to(cr, f.left, py);
    drawText(cr, y.labels[i], f.left - 7, py, 1, 0.5);
  }
  for (double a : y.minor)
    cairo_move_to(cr, f.left - 3, ypix(a)), cairo_line_to(cr, f.left, ypix(a));
  cairo_stroke(cr);
}

void drawAxisLabels(cairo_t* cr, const PlotFrame& f, const PlotSpec& spec, double x0, double y0) {
  setColour(cr, kInk);
  setFont(cr, kLabelFont);
  drawText(cr, spec.x_label, 0.5 * (f.left + f.right), y0 + spec.height - kPad, 0.5, 1);
  drawText(cr, spec.y_label, x0 + kPad, 0.5 * (f.top + f.bottom), 0.5, 0, -M_PI / 2);
}

void drawSeries(cairo_t* cr, const PlotFrame& f, const Axis& x, const Axis& y, const Series& s,
                Rgb colour) {
  cairo_save(cr);
  cairo_rectangle(cr, f.left, f.top, f.right - f.left, f.bottom - f.top);
  cairo_clip(cr);
  setColour(cr, colour);
  const bool lines = s.style != Series::Style::Points;
  const bool points = s.style != Series::Style::Line;
  if (lines) {
    cairo_set_line_width(cr, s.line_width_px);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    const double dash[] = {6 * s.line_width_px, 4 * s.line_width_px};
    if (s.dashed) cairo_set_dash(cr, dash, 2, 0);
    bool pen_down = false;
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!x.valid(s.x[i]) || !y.valid(s.y[i])) {
        pen_down = false;
        continue;
      }
      const auto p = f.toPixel(s.x[i], s.y[i]);
      pen_down ? cairo_line_to(cr, p[0], p[1]) : cairo_move_to(cr, p[0], p[1]);
      pen_down = true;
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  if (points) {
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!x.valid(s.x[i]) || !y.valid(s.y[i])) continue;
      const auto p = f.toPixel(s.x[i], s.y[i]);
      cairo_new_sub_path(cr);
      cairo_arc(cr, p[0], p[1], s.point_radius_px, 0, 2 * M_PI);
    }
    cairo_fill(cr);
  }
  cairo_restore(cr);
}

double legendWidth(cairo_t* cr, const std::vector<Series>& series) {
  setFont(cr, kTickFont);
  double w = 0;
  for (const auto& s : series)
    if (!s.label.empty()) w = std::max(w, textWidth(cr, s.label));
  return w > 0 ? w + kLegendSwatch + 4 * kPad : 0;
}

void drawLegend(cairo_t* cr, const PlotFrame& f, const std::vector<Series>& series, double w) {
  int rows = 0;
  for (const auto& s : series) rows += !s.label.empty();
  const double x = f.right + kPad, h = rows * kLegendRow + kPad;
  setColour(cr, kFrame);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x + 0.5, f.top + 0.5, w - kPad - 1, h);
  cairo_stroke(cr);
  setFont(cr, kTickFont);
  double y = f.top + kPad / 2 + kLegendRow / 2;
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    if (s.label.empty()) continue;
    setColour(cr, seriesColour(s, k));
    if (s.style == Series::Style::Points) {
      cairo_arc(cr, x + kPad + kLegendSwatch / 2, y, std::max(2.5, s.point_radius_px), 0, 2 * M_PI);
      cairo_fill(cr);
    } else {
      cairo_set_line_width(cr, std::max(2.0, s.line_width_px));
      cairo_move_to(cr, x + kPad, y), cairo_line_to(cr, x + kPad + kLegendSwatch, y);
      cairo_stroke(cr);
    }
    setColour(cr, kInk);
    drawText(cr, s.label, x + 2 * kPad + kLegendSwatch, y, 0, 0.5);
    y += kLegendRow;
  }
}

/// Draws one line plot into the rectangle (x0, y0, spec.width, spec.height).
PlotFrame drawLinePlot(cairo_t* cr, double x0, double y0, const PlotSpec& spec,
                       const std::vector<Series>& series, const std::string& path) {
  validateSize(spec, path);
  if (spec.equal_aspect && (spec.log_x || spec.log_y))
    throw InputError(path, "equal aspect", "not possible with a log axis");
  std::vector<const std::vector<double>*> xs, ys;
  for (const auto& s : series) {
    INET_CHECK_MSG(s.x.size() == s.y.size(), "series '" + s.label + "': x and y sizes differ");
    xs.push_back(&s.x), ys.push_back(&s.y);
  }
  Axis x = makeAxis(xs, spec.log_x, spec.x_range, path, "x axis");
  Axis y = makeAxis(ys, spec.log_y, spec.y_range, path, "y axis");
  const double legend_w = spec.legend ? legendWidth(cr, series) : 0;
  setFont(cr, kTickFont);
  const double tick_h = textHeight(cr);
  setFont(cr, kLabelFont);
  const double label_h = textHeight(cr);
  PlotFrame f;
  f.log_x = spec.log_x, f.log_y = spec.log_y;
  f.top = y0 + (spec.title.empty() ? 2 * kPad : 3 * kPad + kTitleFont * 1.3);
  f.bottom = y0 + spec.height - (2 * kPad + tick_h + (spec.x_label.empty() ? 0 : label_h + kPad));
  f.right = x0 + spec.width - std::max(2.5 * kPad, legend_w + kPad);
  // The left margin depends on the y tick labels, which depend on the range, which (equal
  // aspect) depends on the margin: two rounds settle it.
  for (int round = 0; round < 2; ++round) {
    y.makeTicks(std::max(3, static_cast<int>((f.bottom - f.top) / 80)));
    setFont(cr, kTickFont);
    double lw = 0;
    for (const auto& l : y.labels) lw = std::max(lw, textWidth(cr, l));
    f.left = x0 + kPad + lw + 10 + (spec.y_label.empty() ? 0 : label_h + kPad);
    if (spec.equal_aspect) {
      Axis xr = makeAxis(xs, false, spec.x_range, path, "x axis");
      Axis yr = makeAxis(ys, false, spec.y_range, path, "y axis");
      equalizeAspect(xr, yr, f.right - f.left, f.bottom - f.top);
      x.lo = xr.lo, x.hi = xr.hi, y.lo = yr.lo, y.hi = yr.hi;
    }
  }
  x.makeTicks(std::max(3, static_cast<int>((f.right - f.left) / 110)));
  y.makeTicks(std::max(3, static_cast<int>((f.bottom - f.top) / 80)));
  f.x_min = x.lo, f.x_max = x.hi, f.y_min = y.lo, f.y_max = y.hi;
  if (f.log_x) f.x_min = std::pow(10, x.lo), f.x_max = std::pow(10, x.hi);
  if (f.log_y) f.y_min = std::pow(10, y.lo), f.y_max = std::pow(10, y.hi);

  drawTitle(cr, spec, x0, y0);
  drawAxes(cr, f, x, y);
  drawAxisLabels(cr, f, spec, x0, y0);
  for (size_t k = 0; k < series.size(); ++k)
    drawSeries(cr, f, x, y, series[k], seriesColour(series[k], k));
  if (legend_w > 0) drawLegend(cr, f, series, legend_w);
  return f;
}

/// A white RGB24 canvas of w x h pixels.
std::pair<SurfacePtr, ContextPtr> makeCanvas(int w, int h, const std::string& path) {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h), cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw InputError(path, "",
                     "cannot create a " + std::to_string(w) + " x " + std::to_string(h) + " image");
  ContextPtr cr(cairo_create(surface.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  return {std::move(surface), std::move(cr)};
}

void savePng(cairo_surface_t* surface, const std::filesystem::path& path) {
  cairo_surface_flush(surface);
  writeFileAtomic(path, [&](const std::filesystem::path& tmp) {
    const cairo_status_t st = cairo_surface_write_to_png(surface, tmp.c_str());
    if (st != CAIRO_STATUS_SUCCESS)
      throw InputError(path.string(), "",
                       std::string("cannot write PNG: ") + cairo_status_to_string(st));
  });
}

}  // namespace

void writeContactSheetPng(const std::filesystem::path& path, const std::vector<SheetTile>& tiles,
                          int columns, double caption_px) {
  if (tiles.empty()) throw InputError(path.string(), "", "no pictures for a contact sheet");
  if (columns < 1) throw InputError(path.string(), "columns", "must be >= 1");
  int cell_w = 0, cell_h = 0;
  for (const auto& t : tiles) {
    if (t.image.channels != 3)
      throw InputError(path.string(), "", "contact sheet pictures must be RGB (3 channels)");
    cell_w = std::max(cell_w, t.image.width);
    cell_h = std::max(cell_h, t.image.height);
  }
  const int pad = 4, text_h = static_cast<int>(std::ceil(caption_px * 1.5));
  const int cols = std::min<int>(columns, static_cast<int>(tiles.size()));
  const int rows = static_cast<int>((tiles.size() + size_t(cols) - 1) / size_t(cols));
  const int W = cols * (cell_w + pad) + pad, H = rows * (cell_h + text_h + pad) + pad;
  auto [surface, cr] = makeCanvas(W, H, path.string());
  cairo_surface_flush(surface.get());
  unsigned char* px = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (size_t k = 0; k < tiles.size(); ++k) {
    const ImageU8& im = tiles[k].image;
    const int x0 = pad + int(k % size_t(cols)) * (cell_w + pad) + (cell_w - im.width) / 2;
    const int y0 = pad + int(k / size_t(cols)) * (cell_h + text_h + pad) + (cell_h - im.height);
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        uint32_t* dst = reinterpret_cast<uint32_t*>(px + (y0 + y) * stride) + (x0 + x);
        *dst = (uint32_t(im.at(x, y, 0)) << 16) | (uint32_t(im.at(x, y, 1)) << 8) |
               uint32_t(im.at(x, y, 2));
      }
  }
  cairo_surface_mark_dirty(surface.get());
  cairo_set_source_rgb(cr.get(), 0.1, 0.1, 0.1);
  cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr.get(), caption_px);
  for (size_t k = 0; k < tiles.size(); ++k) {
    std::string text = tiles[k].caption;
    cairo_text_extents_t ext;
    cairo_text_extents(cr.get(), text.c_str(), &ext);
    while (ext.x_advance > cell_w && text.size() > 4) {  // cut to the cell, byte-safe for UTF-8
      text.pop_back();
      while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80)
        text.pop_back();
      const std::string shown = text + "...";
      cairo_text_extents(cr.get(), shown.c_str(), &ext);
      if (ext.x_advance <= cell_w) text = shown;
    }
    const double x = pad + double(k % size_t(cols)) * (cell_w + pad);
    const double y = pad + double(k / size_t(cols)) * (cell_h + text_h + pad) + cell_h +
                     caption_px * 1.15;
    cairo_move_to(cr.get(), x, y);
    cairo_show_text(cr.get(), text.c_str());
  }
  const std::string ext = lowerExtension(path.string());
  if (ext != ".jpg" && ext != ".jpeg") {
    savePng(surface.get(), path);
    return;
  }
  cairo_surface_flush(surface.get());
  ImageU8 rgb(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const uint32_t v = reinterpret_cast<const uint32_t*>(px + y * stride)[x];
      rgb.at(x, y, 0) = uint8_t(v >> 16);
      rgb.at(x, y, 1) = uint8_t(v >> 8);
      rgb.at(x, y, 2) = uint8_t(v);
    }
  writeJpeg(path, rgb, 88);
}

Rgb paletteColour(int k) {
  static const Rgb kTab10[10] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                                 {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                                 {188, 189, 34},  {23, 190, 207}};
  return kTab10[((k % 10) + 10) % 10];
}

std::array<double, 2> PlotFrame::toPixel(double x, double y) const {
  auto lin = [](double v, double lo, double hi, bool log) {
    return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
               : (v - lo) / (hi - lo);
  };
  return {left + lin(x, x_min, x_max, log_x) * (right - left),
          bottom - lin(y, y_min, y_max, log_y) * (bottom - top)};
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  INET_CHECK(std::isfinite(lo) && std::isfinite(hi) && target >= 1);
  if (hi < lo) std::swap(lo, hi);
  const double span = hi - lo;
  if (span <= 0) return {lo};
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / mag;
  const double step = (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
  std::vector<double> t;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k += 1)
    t.push_back(k * step);
  return t;
}

PlotFrame writeLinePlotPng(const std::filesystem::path& path, const PlotSpec& spec,
                           const std::vector<Series>& series) {
  return writeLinePlotRowPng(path, {LinePlot{spec, series}}).front();
}

std::vector<PlotFrame> writeLinePlotRowPng(const std::filesystem::path& path,
                                           const std::vector<LinePlot>& panels) {
  INET_CHECK(!panels.empty());
  int w = 0, h = 0;
  for (const auto& p : panels) {
    validateSize(p.spec, path.string());
    w += p.spec.width, h = std::max(h, p.spec.height);
  }
  auto [surface, cr] = makeCanvas(w, h, path.string());
  std::vector<PlotFrame> frames;
  double x0 = 0;
  for (const auto& p : panels) {
    frames.push_back(drawLinePlot(cr.get(), x0, 0, p.spec, p.series, path.string()));
    x0 += p.spec.width;
  }
  savePng(surface.get(), path);
  return frames;
}

PlotFrame writeBarChartPng(const std::filesystem::path& path, const PlotSpec& spec,
                           const std::vector<Bar>& bars) {
  const std::string where = path.string();
  validateSize(spec, where);
  if (spec.log_x || spec.log_y || spec.equal_aspect)
    throw InputError(where, "bar chart", "log axes and equal aspect are for line plots only");
  if (bars.empty()) throw InputError(where, "bar chart", "no bars to draw");
  auto [surface, canvas] = makeCanvas(spec.width, spec.height, where);
  cairo_t* cr = canvas.get();
  // value axis: always includes 0; extra room at the far end for the value labels
  double vlo = 0, vhi = 0;
  for (const Bar& b : bars) {
    if (!std::isfinite(b.value))
      throw InputError(where, "bar '" + b.label + "'", "value is not finite");
    vlo = std::min(vlo, b.value), vhi = std::max(vhi, b.value);
  }
  if (vhi - vlo <= 0) vhi = 1;
  const double pad = (vhi - vlo) * (spec.value_labels ? 0.12 : kMargin);
  Axis value;
  value.lo = vlo < 0 ? vlo - pad : 0, value.hi = vhi > 0 ? vhi + pad : 0;
  Axis cat;  // categories: slot k spans [k, k + 1]
  cat.lo = 0, cat.hi = static_cast<double>(bars.size());
  setFont(cr, kTickFont);
  double label_w = 0;
  for (const Bar& b : bars) label_w = std::max(label_w, textWidth(cr, b.label));
  const double tick_h = textHeight(cr);
  setFont(cr, kLabelFont);
  const double axis_label_h = textHeight(cr) + kPad;

  PlotFrame f;
  f.top = spec.title.empty() ? 2 * kPad : 3 * kPad + kTitleFont * 1.3;
  f.right = spec.width - 2.5 * kPad;
  const double xlab = spec.x_label.empty() ? 0 : axis_label_h;
  const double ylab = spec.y_label.empty() ? 0 : axis_label_h;
  const double tilt = -35 * M_PI / 180;
  bool rotate = false;
  if (spec.horizontal) {
    f.left = kPad + label_w + 10 + ylab;
    f.bottom = spec.height - (2 * kPad + tick_h + xlab);
  } else {
    value.makeTicks(std::max(3, static_cast<int>(spec.height / 100)));
    setFont(cr, kTickFont);
    double lw = 0;
    for (const auto& l : value.labels) lw = std::max(lw, textWidth(cr, l));
    f.left = kPad + lw + 10 + ylab;
    rotate = label_w > (f.right - f.left) / bars.size() - 4;
    const double cat_h = rotate ? label_w * std::sin(-tilt) + tick_h : tick_h;
    f.bottom = spec.height - (2 * kPad + cat_h + xlab);
  }
  Axis& ax = spec.horizontal ? value : cat;
  Axis& ay = spec.horizontal ? cat : value;
  ax.makeTicks(std::max(3, static_cast<int>((f.right - f.left) / 110)));
  ay.makeTicks(std::max(3, static_cast<int>((f.bottom - f.top) / 80)));
  if (spec.horizontal)
    ay.major.clear(), ay.labels.clear();
  else
    ax.major.clear(), ax.labels.clear();
  f.x_min = ax.lo, f.x_max = ax.hi, f.y_min = ay.lo, f.y_max = ay.hi;
  if (spec.horizontal) f.y_min = ay.hi, f.y_max = ay.lo;  // first bar at the top

  drawTitle(cr, spec, 0, 0);
  drawAxes(cr, f, ax, ay);
  drawAxisLabels(cr, f, spec, 0, 0);
  for (size_t k = 0; k < bars.size(); ++k) {
    const Bar& b = bars[k];
    const double c0 = k + 0.15, c1 = k + 0.85;
    const auto p0 = spec.horizontal ? f.toPixel(0, c0) : f.toPixel(c0, 0);
    const auto p1 = spec.horizontal ? f.toPixel(b.value, c1) : f.toPixel(c1, b.value);
    setColour(cr, b.colour ? *b.colour : paletteColour(0));
    cairo_rectangle(cr, std::min(p0[0], p1[0]), std::min(p0[1], p1[1]), std::abs(p1[0] - p0[0]),
                    std::abs(p1[1] - p0[1]));
    cairo_fill(cr);
    setColour(cr, kInk);
    setFont(cr, kTickFont);
    const auto mid = spec.horizontal ? f.toPixel(0, k + 0.5) : f.toPixel(k + 0.5, 0);
    if (spec.horizontal)
      drawText(cr, b.label, f.left - 7, mid[1], 1, 0.5);
    else if (rotate)
      drawText(cr, b.label, mid[0], f.bottom + 7, 1, 0, tilt);
    else
      drawText(cr, b.label, mid[0], f.bottom + 7, 0.5, 0);
    if (!spec.value_labels) continue;
    const std::string v = fmt::format("{:.4g}", b.value);
    const auto end = spec.horizontal ? f.toPixel(b.value, k + 0.5) : f.toPixel(k + 0.5, b.value);
    const bool neg = b.value < 0;
    if (spec.horizontal)
      drawText(cr, v, end[0] + (neg ? -4 : 4), end[1], neg ? 1 : 0, 0.5);
    else
      drawText(cr, v, end[0], end[1] + (neg ? 3 : -3), 0.5, neg ? 0 : 1);
  }
  savePng(surface.get(), path);
  return f;
}

}  // namespace inet
