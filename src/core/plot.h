#pragma once
// PNG charts for reports (trajectory views, error curves, power spectra, histograms as bars),
// drawn with cairo and written atomically (core/atomic_file.h). Deliberately small: line and
// scatter plots of 2D series, and bar charts. No interactive backend, no global state.
//
// Layout of a line plot: title on top, the plot area with a frame, round-number ticks
// (1, 2, 5 x 10^k; decades on log axes) and axis labels, and a legend to the right of the plot
// area (outside it, so it never hides data). Axis ranges default to the data range plus 5 %
// on each side (decades on log axes); equal_aspect widens one range so that one unit is as many
// pixels along x as along y (top-down trajectory views).
//
// Points that cannot be drawn (NaN, inf, or <= 0 on a log axis) break a line and are skipped.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace inet {

/// An 8-bit sRGB colour.
struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

/// The k-th colour of the default palette (matplotlib's "tab10", cycling): blue, orange, green,
/// red, purple, brown, pink, grey, olive, cyan.
Rgb paletteColour(int k);

/// One data series of a line or scatter plot.
struct Series {
  enum class Style { Line, Points, LinePoints };
  std::string label;          ///< legend text; empty = not in the legend
  std::vector<double> x, y;   ///< same length
  std::optional<Rgb> colour;  ///< empty = paletteColour(index of the series)
  Style style = Style::Line;
  double line_width_px = 1.5;    ///< Line / LinePoints
  double point_radius_px = 2.0;  ///< Points / LinePoints
  bool dashed = false;           ///< Line / LinePoints
};

/// What a chart looks like. Log flags apply to line plots only (a bar chart with one is an
/// InputError); `horizontal` and `value_labels` to bar charts only.
struct PlotSpec {
  std::string title, x_label, y_label;
  bool equal_aspect = false;
  bool log_x = false, log_y = false;
  /// Fixed axis ranges in data units (both ends > 0 on a log axis); empty = from the data.
  std::optional<std::pair<double, double>> x_range, y_range;
  bool legend = true;             ///< line plots: legend of the labelled series
  bool horizontal = false;        ///< bar charts: bars grow to the right, labels on the left
  bool value_labels = true;       ///< bar charts: the value printed at the end of each bar
  int width = 900, height = 600;  ///< pixels, 100 .. 8000 each
};

/// Where the plot area of a written chart is, and how data maps into it; returned so callers
/// and tests can find data on the image. Pixel (0, 0) is the top-left corner of the PNG.
struct PlotFrame {
  double left = 0, top = 0, right = 0, bottom = 0;    ///< plot area edges, pixels
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;  ///< axis range, data units
  bool log_x = false, log_y = false;
  /// Pixel position (column, row) of a data point (log axes map log10 linearly).
  std::array<double, 2> toPixel(double x, double y) const;
};

/// A bar of a bar chart.
struct Bar {
  std::string label;
  double value = 0;
  std::optional<Rgb> colour;  ///< empty = paletteColour(0)
};

/// One panel of a multi-panel figure: a line plot of spec.width x spec.height pixels.
struct LinePlot {
  PlotSpec spec;
  std::vector<Series> series;
};

/// Writes a line/scatter plot of `series` to `path` (PNG, 8-bit RGB). Throws InputError naming
/// the path for bad sizes, a log axis without positive data, or an unwritable file.
PlotFrame writeLinePlotPng(const std::filesystem::path& path, const PlotSpec& spec,
                           const std::vector<Series>& series);

/// Writes panels side by side (left to right) into one PNG of sum(width) x max(height) pixels.
std::vector<PlotFrame> writeLinePlotRowPng(const std::filesystem::path& path,
                                           const std::vector<LinePlot>& panels);

/// Writes a bar chart, bars in the given order (left to right, or top to bottom if horizontal).
/// The value axis always includes 0. The frame's x range is the value axis for horizontal
/// charts, the y range for vertical ones.
PlotFrame writeBarChartPng(const std::filesystem::path& path, const PlotSpec& spec,
                           const std::vector<Bar>& bars);

/// One picture of a contact sheet: an 8-bit sRGB image (3 channels) and a caption.
struct SheetTile {
  ImageU8 image;
  std::string caption;  ///< drawn under the image, cut with "..." to the tile's width
};

/// Writes `tiles` in a grid of `columns` (row by row, in order), each image at its own size
/// in a cell as large as the largest, its caption below in `caption_px` pixel text, on white;
/// a JPEG (quality 88) when `path` ends in .jpg or .jpeg, else a PNG.
/// Throws InputError naming the path for no tiles, a tile that is not 3-channel, or an
/// unwritable file.
void writeContactSheetPng(const std::filesystem::path& path, const std::vector<SheetTile>& tiles,
                          int columns, double caption_px = 11.0);

/// Round tick positions covering [lo, hi]: multiples of 1, 2 or 5 x 10^k, about `target` of
/// them (Heckbert, "Nice numbers for graph labels", Graphics Gems 1990).
std::vector<double> niceTicks(double lo, double hi, int target = 6);

}  // namespace inet
