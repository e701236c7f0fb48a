// core/plot: the PNG decodes, has the requested size, and the data are drawn where the returned
// frame says (found by colour on the decoded image).
#include "core/plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "../temp_dir.h"
#include "core/error.h"
#include "core/image_io.h"

namespace inet {
namespace {

const Rgb kRed{220, 0, 0}, kBlue{0, 0, 220}, kGreen{0, 170, 0};

bool near(const ImageU8& img, int x, int y, Rgb c, int tol = 40) {
  const uint8_t* p = img.pixel(x, y);
  return std::abs(p[0] - c.r) <= tol && std::abs(p[1] - c.g) <= tol && std::abs(p[2] - c.b) <= tol;
}

/// Rows [min, max] and count of pixels of colour c inside the rectangle.
struct Extent {
  int min_x = INT_MAX, max_x = -1, min_y = INT_MAX, max_y = -1, count = 0;
};
Extent findColour(const ImageU8& img, Rgb c, int x0 = 0, int y0 = 0, int x1 = INT_MAX,
                  int y1 = INT_MAX) {
  Extent e;
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x)
      if (near(img, x, y, c)) {
        e.min_x = std::min(e.min_x, x), e.max_x = std::max(e.max_x, x);
        e.min_y = std::min(e.min_y, y), e.max_y = std::max(e.max_y, y);
        ++e.count;
      }
  return e;
}

/// Test output folder: a fresh temporary, or $INET_PLOT_TEST_OUT to keep the images for a look.
struct OutDir {
  test::TempDir tmp{"plot"};
  std::filesystem::path dir =
      std::getenv("INET_PLOT_TEST_OUT") ? std::getenv("INET_PLOT_TEST_OUT") : tmp.path();
  std::filesystem::path operator/(const std::string& name) const { return dir / name; }
  std::filesystem::path path() const { return dir; }
};

Extent insideFrame(const ImageU8& img, Rgb c, const PlotFrame& f) {
  return findColour(img, c, static_cast<int>(f.left) + 2, static_cast<int>(f.top) + 2,
                    static_cast<int>(f.right) - 1, static_cast<int>(f.bottom) - 1);
}

TEST(NiceTicks, RoundNumbersCoveringTheRange) {
  auto t = niceTicks(0.0, 1.0, 5);
  ASSERT_EQ(t.size(), 6u);  // 0, 0.2, ..., 1
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_NEAR(t[1], 0.2, 1e-12);
  EXPECT_NEAR(t.back(), 1.0, 1e-12);
  t = niceTicks(-3.7, 12.1, 6);  // step 2 or 5 (15.8 / 6 = 2.6 -> 2)
  for (double v : t) EXPECT_NEAR(std::remainder(v, 2.0), 0.0, 1e-9) << v;
  EXPECT_LE(t.front(), -2.0);
  EXPECT_GE(t.back(), 12.0);
  t = niceTicks(1303.2, 1303.9, 4);  // small span far from zero
  ASSERT_GE(t.size(), 3u);
  for (double v : t) EXPECT_TRUE(v >= 1303.2 && v <= 1303.9) << v;
}

TEST(LinePlot, HorizontalLineLandsInTheMiddleBand) {
  OutDir dir;
  PlotSpec spec;
  spec.title = "one line";
  spec.x_label = "x";
  spec.y_label = "y";
  spec.x_range = {{0.0, 1.0}};
  spec.y_range = {{0.0, 1.0}};
  spec.width = 640, spec.height = 480;
  Series s{"y = 0.5", {0.0, 1.0}, {0.5, 0.5}, kRed};
  s.line_width_px = 3;
  const auto path = dir / "line.png";
  const PlotFrame f = writeLinePlotPng(path, spec, {s});
  const ImageU8 img = readPng8(path);
  ASSERT_EQ(img.width, 640);
  ASSERT_EQ(img.height, 480);
  ASSERT_EQ(img.channels, 3);
  const Extent e = insideFrame(img, kRed, f);
  ASSERT_GT(e.count, 0);
  const double mid = 0.5 * (f.top + f.bottom);
  EXPECT_GE(e.min_y, mid - 3);
  EXPECT_LE(e.max_y, mid + 3);
  EXPECT_LE(e.min_x, f.left + 4);  // spans the whole width of the plot area
  EXPECT_GE(e.max_x, f.right - 4);
  // the frame maps the data: y = 0.5 is the middle row, y = 0 the bottom edge
  EXPECT_NEAR(f.toPixel(0.0, 0.5)[1], mid, 1e-9);
  EXPECT_NEAR(f.toPixel(0.0, 0.0)[1], f.bottom, 1e-9);
  // the legend (outside the plot area) has a red swatch too, right of the frame
  EXPECT_GT(findColour(img, kRed, static_cast<int>(f.right) + 1).count, 0);
}

TEST(LinePlot, PointsAtTheirDataPositionsAndOrderedSeries) {
  OutDir dir;
  PlotSpec spec;
  spec.legend = false;
  const std::vector<double> xs = {1, 2, 3, 4};
  Series low{"low", xs, {1, 1, 1, 1}, kBlue, Series::Style::Points};
  Series high{"high", xs, {3, 3, 3, 3}, kGreen, Series::Style::Points};
  low.point_radius_px = high.point_radius_px = 4;
  const auto path = dir / "points.png";
  const PlotFrame f = writeLinePlotPng(path, spec, {low, high});
  const ImageU8 img = readPng8(path);
  EXPECT_EQ(img.width, 900);
  EXPECT_EQ(img.height, 600);
  for (double x : xs) {  // each point: a coloured disc at toPixel(x, y)
    auto p = f.toPixel(x, 1.0);
    EXPECT_TRUE(near(img, static_cast<int>(p[0]), static_cast<int>(p[1]), kBlue)) << x;
    p = f.toPixel(x, 3.0);
    EXPECT_TRUE(near(img, static_cast<int>(p[0]), static_cast<int>(p[1]), kGreen)) << x;
  }
  const Extent b = insideFrame(img, kBlue, f), g = insideFrame(img, kGreen, f);
  EXPECT_LT(g.max_y, b.min_y);  // larger y is higher up on the image
  EXPECT_NEAR(b.max_y - b.min_y, 8, 2);
  // automatic range: data padded by 5 %, so the outer points are inside the frame
  EXPECT_LT(f.x_min, 1.0);
  EXPECT_GT(f.x_max, 4.0);
  EXPECT_GT(f.x_min, 0.5);
}

TEST(LinePlot, EqualAspectGivesSquareUnits) {
  OutDir dir;
  PlotSpec spec;
  spec.equal_aspect = true;
  spec.width = 900, spec.height = 500;
  // a unit square, drawn as a closed line: its pixel width must equal its pixel height
  Series sq{"square", {0, 1, 1, 0, 0}, {0, 0, 1, 1, 0}, kRed};
  const auto path = dir / "square.png";
  const PlotFrame f = writeLinePlotPng(path, spec, {sq});
  const double px_per_x = (f.right - f.left) / (f.x_max - f.x_min);
  const double px_per_y = (f.bottom - f.top) / (f.y_max - f.y_min);
  EXPECT_NEAR(px_per_x, px_per_y, 1e-6);
  const Extent e = insideFrame(readPng8(path), kRed, f);
  EXPECT_NEAR(e.max_x - e.min_x, e.max_y - e.min_y, 2);
}

TEST(LinePlot, LogLogPowerLaw) {
  OutDir dir;
  PlotSpec spec;
  spec.log_x = spec.log_y = true;
  spec.title = "power spectrum";
  Series s{"1/f^2", {}, {}, kBlue};
  s.line_width_px = 3;
  for (int k = 0; k <= 60; ++k) {
    const double fr = std::pow(10.0, -1 + 4.0 * k / 60);  // 0.1 .. 1000 Hz
    s.x.push_back(fr);
    s.y.push_back(1.0 / (fr * fr));
  }
  s.x.push_back(0.0), s.y.push_back(1.0);  // not drawable on a log axis: skipped
  const auto path = dir / "loglog.png";
  const PlotFrame f = writeLinePlotPng(path, spec, {s});
  const ImageU8 img = readPng8(path);
  // a power law is a straight line: the middle sample lies on the chord of the ends
  const auto a = f.toPixel(0.1, 100.0), b = f.toPixel(1000.0, 1e-6), m = f.toPixel(10.0, 0.01);
  EXPECT_NEAR(m[1], 0.5 * (a[1] + b[1]), 1e-6);
  EXPECT_TRUE(near(img, static_cast<int>(m[0]), static_cast<int>(m[1]), kBlue));
  spec.log_y = false;
  EXPECT_NO_THROW(writeLinePlotPng(dir / "semilog.png", spec, {s}));
  Series bad{"neg", {1, 2}, {-1, -2}, kRed};
  spec.log_y = true;
  EXPECT_THROW(writeLinePlotPng(dir / "bad.png", spec, {bad}), InputError);
}

TEST(LinePlot, RowOfPanelsIsSideBySide) {
  OutDir dir;
  PlotSpec a, b;
  a.width = 400, a.height = 300;
  b.width = 500, b.height = 350;
  const auto path = dir / "row.png";
  auto frames = writeLinePlotRowPng(
      path, {{a, {Series{"a", {0, 1}, {0, 1}, kRed}}}, {b, {Series{"b", {0, 1}, {1, 0}, kBlue}}}});
  const ImageU8 img = readPng8(path);
  EXPECT_EQ(img.width, 900);
  EXPECT_EQ(img.height, 350);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_LT(frames[0].right, 400);
  EXPECT_GT(frames[1].left, 400);
  EXPECT_GT(insideFrame(img, kRed, frames[0]).count, 0);
  EXPECT_EQ(insideFrame(img, kRed, frames[1]).count, 0);
  EXPECT_GT(insideFrame(img, kBlue, frames[1]).count, 0);
}

TEST(BarChart, BarHeightsFollowValues) {
  OutDir dir;
  PlotSpec spec;
  spec.title = "bars";
  spec.y_label = "count";
  const std::vector<Bar> bars = {{"ten", 10, kRed}, {"forty", 40, kBlue}, {"twenty", 20, kGreen}};
  const auto path = dir / "bars.png";
  const PlotFrame f = writeBarChartPng(path, spec, bars);
  const ImageU8 img = readPng8(path);
  EXPECT_EQ(img.width, 900);
  const Extent r = findColour(img, kRed), b = findColour(img, kBlue), g = findColour(img, kGreen);
  const int hr = r.max_y - r.min_y, hb = b.max_y - b.min_y, hg = g.max_y - g.min_y;
  EXPECT_GT(hb, hg);
  EXPECT_GT(hg, hr);
  EXPECT_NEAR(static_cast<double>(hb) / hr, 4.0, 0.1);
  EXPECT_LT(r.max_x, b.min_x);  // in the given order, left to right
  EXPECT_LT(b.max_x, g.min_x);
  EXPECT_NEAR(r.max_y, f.toPixel(0, 0)[1], 1.5);  // bars stand on 0
  EXPECT_NEAR(b.min_y, f.toPixel(0, 40)[1], 1.5);
}

TEST(BarChart, HorizontalBarsAndErrors) {
  OutDir dir;
  PlotSpec spec;
  spec.horizontal = true;
  spec.x_label = "metres";
  const std::vector<Bar> bars = {{"a rather long category name", 3, kRed}, {"b", 1.5, kBlue}};
  const auto path = dir / "hbars.png";
  writeBarChartPng(path, spec, bars);
  const ImageU8 img = readPng8(path);
  const Extent r = findColour(img, kRed), b = findColour(img, kBlue);
  EXPECT_NEAR(static_cast<double>(r.max_x - r.min_x) / (b.max_x - b.min_x), 2.0, 0.05);
  EXPECT_LT(r.max_y, b.min_y);  // first bar on top
  EXPECT_THROW(writeBarChartPng(dir / "none.png", spec, {}), InputError);
  spec.log_y = true;
  EXPECT_THROW(writeBarChartPng(dir / "log.png", spec, bars), InputError);
  spec.log_y = false;
  spec.width = 20;
  EXPECT_THROW(writeBarChartPng(dir / "tiny.png", spec, bars), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "tiny.png"));
}

TEST(Plot, UnwritablePathIsAnInputErrorAndLeavesNoTemporary) {
  test::TempDir dir("plot");
  const std::string file = dir.write("file.txt", "x");
  // the parent "folder" is a file
  EXPECT_THROW(writeLinePlotPng(std::filesystem::path(file) / "x.png", PlotSpec{}, {}), InputError);
  // the target is an existing folder: cairo writes the temporary, the rename fails
  std::filesystem::create_directories(dir / "taken.png");
  EXPECT_THROW(writeLinePlotPng(dir / "taken.png", PlotSpec{}, {}), InputError);
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

TEST(ContactSheet, TilesInRowsWithCaptionsBelow) {
  test::TempDir dir("sheet");
  std::vector<SheetTile> tiles;
  const uint8_t colours[5][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}, {0, 0, 0}};
  for (const auto& c : colours) {
    SheetTile t;
    t.image = ImageU8(20, 10, 3);
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 20; ++x)
        for (int k = 0; k < 3; ++k) t.image.at(x, y, k) = c[k];
    t.caption = "a caption far too long for twenty pixels";
    tiles.push_back(std::move(t));
  }
  const auto path = dir / "sheet.png";
  writeContactSheetPng(path, tiles, 3, 8.0);
  const ImageU8 im = readPng8(path);
  // 3 columns x 2 rows of 20 x 10 cells, 4 px apart, 12 px of caption under each
  EXPECT_EQ(im.width, 3 * 24 + 4);
  EXPECT_EQ(im.height, 2 * (10 + 12 + 4) + 4);
  auto px = [&](int x, int y, int k) { return int(im.at(x, y, k)); };
  EXPECT_EQ(px(4 + 10, 4 + 5, 0), 255);  // tile 0 red
  EXPECT_EQ(px(4 + 10, 4 + 5, 1), 0);
  EXPECT_EQ(px(4 + 24 + 10, 4 + 5, 1), 255);  // tile 1 green
  EXPECT_EQ(px(4 + 48 + 10, 4 + 5, 2), 255);  // tile 2 blue
  const int row2 = 4 + 26;
  EXPECT_EQ(px(4 + 10, row2 + 5, 0), 255);  // tile 3 yellow
  EXPECT_EQ(px(4 + 10, row2 + 5, 1), 255);
  EXPECT_EQ(px(4 + 24 + 10, row2 + 5, 0), 0);  // tile 4 black
  EXPECT_EQ(px(4 + 48 + 10, row2 + 5, 0), 255);  // no tile 5: white
  // some caption ink under tile 0, none to the right of the cell (cut with "...")
  int ink = 0, spill = 0;
  for (int y = 4 + 10; y < 4 + 22; ++y) {
    for (int x = 4; x < 24; ++x) ink += px(x, y, 0) < 128;
    for (int x = 24; x < 28; ++x) spill += px(x, y, 0) < 128;
  }
  EXPECT_GT(ink, 5);
  EXPECT_EQ(spill, 0);
  EXPECT_THROW(writeContactSheetPng(dir / "none.png", {}, 3), InputError);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

TEST(ContactSheet, JpegByExtension) {
  test::TempDir dir("sheet_jpg");
  SheetTile t;
  t.image = ImageU8(30, 20, 3, 0);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) t.image.at(x, y, 2) = 255;  // blue
  t.caption = "blue";
  writeContactSheetPng(dir / "s.jpg", {t, t}, 2);
  const ImageU8 im = readJpeg8(dir / "s.jpg");
  EXPECT_EQ(im.width, 2 * 34 + 4);
  EXPECT_NEAR(im.at(4 + 15, 4 + 10, 2), 255, 8);  // lossy, but blue
  EXPECT_NEAR(im.at(4 + 15, 4 + 10, 0), 0, 8);
  EXPECT_THROW(writeJpeg(dir / "bad.jpg", ImageU8(2, 2, 4)), InputError);
}

}  // namespace
}  // namespace inet
