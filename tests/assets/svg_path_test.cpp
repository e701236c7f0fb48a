// SVG path data to cut-out outlines: the shapes of real Sweet Home 3D catalogs checked against
// closed-form geometry (ellipses, circles, Bézier points, areas), grammar corner cases, error
// messages and hostile input.
#include "assets/svg_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "../expect_input_error.h"
#include "core/error.h"

namespace inet {
namespace {

using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-4;

std::vector<Outline2d> parse(std::string_view d, double tol = kTol) {
  return parseSvgPath(d, tol, "catalog.sh3f", "doorOrWindowCutOutShape");
}

Outline2d parseOne(std::string_view d, double tol = kTol) {
  std::vector<Outline2d> out = parse(d, tol);
  EXPECT_EQ(out.size(), 1u) << d;
  return out.empty() ? Outline2d{} : out[0];
}

double distToSegment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Distance from p to the closed polygon's boundary.
double distToOutline(const Vector2d& p, const Outline2d& o) {
  double d = INFINITY;
  for (size_t i = 0; i < o.size(); ++i)
    d = std::min(d, distToSegment(p, o[i], o[(i + 1) % o.size()]));
  return d;
}

void expectSameOutline(const Outline2d& a, const Outline2d& b, double eps) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_LE((a[i] - b[i]).norm(), eps)
        << "vertex " << i << ": " << a[i].transpose() << " vs " << b[i].transpose();
}

void expectVertices(const Outline2d& o, const std::vector<Vector2d>& want) {
  ASSERT_EQ(o.size(), want.size());
  for (size_t i = 0; i < o.size(); ++i) EXPECT_EQ(o[i], want[i]) << "vertex " << i;
}

TEST(SvgPath, UnitSquareIsExact) {
  const Outline2d o = parseOne("M0,0 v1 h1 v-1 z");
  expectVertices(o, {{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  // Down, right, up on screen is counter-clockwise there, hence clockwise in y-up: negative.
  EXPECT_EQ(outlineArea(o), -1.0);
}

TEST(SvgPath, SpaceSeparatedCatalogShape) {
  const Outline2d o = parseOne("M 0 0.1068 v 0.7864 h 1 v -0.7864 z");
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[0], Vector2d(0, 0.1068));
  EXPECT_EQ(o[2], Vector2d(1, 0.1068 + 0.7864));
  EXPECT_NEAR(std::abs(outlineArea(o)), 0.7864, 1e-12);
}

TEST(SvgPath, EllipticArchLiesOnItsEllipse) {
  const Outline2d o = parseOne("M0,0.234 a0.5,0.234 0 0,1 1,0 v0.766 h-1 z");
  const Vector2d c(0.5, 0.234), r(0.5, 0.234);
  size_t on_arc = 0;
  double min_y = INFINITY;
  for (const Vector2d& p : o) {
    min_y = std::min(min_y, p.y());
    if (p.y() > c.y() + 1e-12) continue;  // the two bottom corners
    ++on_arc;
    EXPECT_NEAR(((p - c).array() / r.array()).matrix().norm(), 1.0, 1e-9) << p.transpose();
  }
  EXPECT_GT(on_arc, 10u);  // really flattened, not a triangle
  EXPECT_EQ(on_arc + 2, o.size());
  EXPECT_GE(min_y, -1e-12);
  EXPECT_LE(min_y, kTol);  // the top of the arch is reached
  // Rectangle below the springing line plus half the ellipse; clockwise on screen: positive.
  EXPECT_NEAR(outlineArea(o), 0.766 + kPi * 0.5 * 0.234 / 2, 1e-3);
  // No point of the true arch is farther than the tolerance from the polygon.
  for (int i = 0; i <= 1000; ++i) {
    const double t = kPi + kPi * i / 1000;
    const Vector2d p(c.x() + r.x() * std::cos(t), c.y() + r.y() * std::sin(t));
    EXPECT_LE(distToOutline(p, o), kTol + 1e-12) << "theta " << t;
  }
}

TEST(SvgPath, OversizedRadiusGivesAShallowArc) {
  const Outline2d o = parseOne("M0,0.0352 a3.7,3.7 0 0,1 1,0 v0.9648 h-1 z");
  // A circle of radius 3.7 through both ends of a chord of length 1 is centred below the
  // chord's middle at depth sqrt(3.7^2 - 0.5^2); the sagitta is what remains of the radius.
  const double depth = std::sqrt(3.7 * 3.7 - 0.25);
  const double sagitta = 3.7 - depth;
  const Vector2d centre(0.5, 0.0352 + depth);
  double min_y = INFINITY;
  for (const Vector2d& p : o) {
    EXPECT_GE(p.x(), 0.0);
    EXPECT_LE(p.x(), 1.0);
    EXPECT_GE(p.y(), 0.0);
    EXPECT_LE(p.y(), 1.0 + 1e-12);
    min_y = std::min(min_y, p.y());
    if (p.y() <= 0.0352 + 1e-12) {
      EXPECT_NEAR((p - centre).norm(), 3.7, 1e-9) << p.transpose();
    }
  }
  EXPECT_NEAR(min_y, 0.0352 - sagitta, kTol);
  EXPECT_GT(o.size(), 5u);
}

// Checks the staircase cut-out of the catalogs, drawn in either direction.
void expectStaircase(const Outline2d& o) {
  // Both candidate circles of radius 0.5 through (1,0.5) and (0.5,1) see the chord under 90
  // degrees; the large arc is 3/4 of the circle centred (0.5,0.5), going round by the top and
  // the left. The straight part adds the triangle (0.5,0.5) (0.575,0.5) (0.5,1), which lies in
  // the quarter the arc leaves out.
  const double want = 0.75 * kPi * 0.25 + 0.5 * 0.075 * 0.5;
  EXPECT_NEAR(std::abs(outlineArea(o)), want, 1e-3);
  double min_x = INFINITY, min_y = INFINITY;
  for (const Vector2d& p : o) {
    min_x = std::min(min_x, p.x());
    min_y = std::min(min_y, p.y());
    if (p != Vector2d(0.575, 0.5)) {
      EXPECT_NEAR((p - Vector2d(0.5, 0.5)).norm(), 0.5, 1e-9) << p.transpose();
    }
  }
  EXPECT_NEAR(min_x, 0.0, kTol);  // reaches the left of the circle, so not the small arc
  EXPECT_NEAR(min_y, 0.0, kTol);
}

TEST(SvgPath, StaircaseLargeArc) {
  const Outline2d o = parseOne("M0.5,1 L0.575,0.5 L1,0.5 A0.5,0.5 0 1,0 0.5,1 z");
  expectStaircase(o);
  // The same arc walked backwards swaps the sweep flag (large arc with positive sweep).
  const Outline2d back = parseOne("M0.5,1 A0.5,0.5 0 1,1 1,0.5 L0.575,0.5 z");
  expectStaircase(back);
  EXPECT_NEAR(outlineArea(back), -outlineArea(o), 1e-12);
}

TEST(SvgPath, RelativeAndAbsoluteAgree) {
  expectSameOutline(parseOne("m0,0.234 a0.5,0.234 0 0,1 1,0 v0.766 h-1 z"),
                    parseOne("M0,0.234 A0.5,0.234 0 0,1 1,0.234 V1 H0 Z"), 1e-12);
  expectSameOutline(parseOne("M0.5,1 l0.075,-0.5 l0.425,0 a0.5,0.5 0 1,0 -0.5,0.5 z"),
                    parseOne("M0.5,1 L0.575,0.5 L1,0.5 A0.5,0.5 0 1,0 0.5,1 z"), 1e-12);
  expectSameOutline(parseOne("M1 1 c0 1 1 1 1 0 q-.5 -1 -1 0"),
                    parseOne("M1 1 C1 2 2 2 2 1 Q1.5 0 1 1"), 1e-12);
}

TEST(SvgPath, ImplicitRepetitionAndLinetoAfterMoveto) {
  expectVertices(parseOne("M0 0 1 0 1 1"), {{0, 0}, {1, 0}, {1, 1}});
  expectVertices(parseOne("m0 0 1 0 0 1"), {{0, 0}, {1, 0}, {1, 1}});
  expectVertices(parseOne("M0,0 L1,0 1,1 0,1"), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  expectVertices(parseOne("M0 0 h1 v1 .5 h-1"), {{0, 0}, {1, 0}, {1, 1}, {1, 1.5}, {0, 1.5}});
  expectVertices(parseOne("M0 0 a0 1 0 0 1 1 0 0 1 0 0 1 0 1"),  // zero radius: lines
                 {{0, 0}, {1, 0}, {1, 1}});
}

TEST(SvgPath, NumberForms) {
  expectVertices(parseOne("M0 0L.5.5-1e-1.5"), {{0, 0}, {0.5, 0.5}, {-0.1, 0.5}});
  expectVertices(parseOne("M+1,0 L1E0,1 L0.,1e+0 L-.5-5E-1"),
                 {{1, 0}, {1, 1}, {0, 1}, {-0.5, -0.5}});
  expectVertices(parseOne("M0,0\tL1 ,0,\n1\r\n,1 L 0 , 1z"), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  expectVertices(parseOne("M0-0l1-0-0 1"), {{0, 0}, {1, 0}, {1, 1}});
}

TEST(SvgPath, CompactArcFlags) {
  expectSameOutline(parseOne("M0 0 a1 1 0 011 0 z"), parseOne("M0 0 a1,1 0 0,1 1,0 z"), 0);
  expectSameOutline(parseOne("M0 0 A1 1 0 1 0 1 0 z"), parseOne("M0 0 A1,1,0,1,0,1,0z"), 0);
}

TEST(SvgPath, CubicFlattenedWithinTolerance) {
  const double tol = 1e-3;
  const Outline2d o = parseOne("M0,0 C0,1 1,1 1,0 z", tol);
  auto bezier = [](double t) {
    const double s = 1 - t;
    return Vector2d(3 * s * t * t + t * t * t, 3 * s * s * t + 3 * s * t * t);
  };
  // Symmetric control polygon: B(1/2) = (0 + 3*0 + 3*1 + 1)/8, (0 + 3 + 3 + 0)/8.
  const Vector2d mid(0.5, 0.75);
  EXPECT_EQ(bezier(0.5), mid);
  double max_y = -INFINITY;
  for (const Vector2d& p : o) max_y = std::max(max_y, p.y());
  EXPECT_LE(max_y, 0.75 + 1e-12);
  EXPECT_GE(max_y, 0.75 - tol);
  EXPECT_LE(distToOutline(mid, o), tol);
  for (int i = 0; i <= 1000; ++i) EXPECT_LE(distToOutline(bezier(i / 1000.0), o), tol);
  EXPECT_LT(o.size(), 60u);  // and not absurdly many chords
}

TEST(SvgPath, QuadraticFlattenedWithinTolerance) {
  const double tol = 1e-3;
  const Outline2d o = parseOne("M0 0 Q0.5 1 1 0 z", tol);
  // B(t) = (t, 2t(1-t)): the apex is (0.5, 0.5).
  for (int i = 0; i <= 1000; ++i) {
    const double t = i / 1000.0;
    EXPECT_LE(distToOutline({t, 2 * t * (1 - t)}, o), tol);
  }
  for (const Vector2d& p : o) EXPECT_NEAR(p.y(), 2 * p.x() * (1 - p.x()), 1e-12);
  EXPECT_LT(o.size(), 30u);
}

TEST(SvgPath, SmoothCurvesReflectTheControlPoint) {
  // (1,1) mirrored through (1,0) is (1,-1); (0.5,1) mirrored through (1,0) is (1.5,-1).
  expectSameOutline(parseOne("M0 0 C0 1 1 1 1 0 S2 -1 2 0 z"),
                    parseOne("M0 0 C0 1 1 1 1 0 C1 -1 2 -1 2 0 z"), 1e-12);
  expectSameOutline(parseOne("M0 0 Q0.5 1 1 0 T2 0 z"), parseOne("M0 0 Q0.5 1 1 0 Q1.5 -1 2 0 z"),
                    1e-12);
  // Without a preceding curve of the same family the first control point is the current point.
  expectSameOutline(parseOne("M0 0 L1 0 S2 1 2 0 z"), parseOne("M0 0 L1 0 C1 0 2 1 2 0 z"), 0);
  expectSameOutline(parseOne("M0 0 C0 1 1 1 1 0 T2 1 z"), parseOne("M0 0 C0 1 1 1 1 0 Q1 0 2 1 z"),
                    0);
}

TEST(SvgPath, ArcRotationAndRadiusCorrections) {
  // An ellipse with radii (2, 1) turned by 90 degrees is the upright ellipse with radii (1, 2).
  const Outline2d upright = parseOne("M0 0 A1 2 0 0 1 0 2 z");
  expectSameOutline(parseOne("M0 0 A2 1 90 0 1 0 2 z"), upright, 1e-9);
  expectSameOutline(parseOne("M0 0 A2 1 450 0 1 0 2 z"), upright, 1e-9);
  expectSameOutline(parseOne("M0 0 A-1 -2 0 0 1 0 2 z"), upright, 0);  // |radius| is used
  // Radii (0.1, 0.05) cannot reach from (0,0) to (1,0): scaled by 5 to a half ellipse (0.5, 0.25).
  const Outline2d half = parseOne("M0 0 A0.1 0.05 0 0 1 1 0 z");
  EXPECT_NEAR(std::abs(outlineArea(half)), kPi * 0.5 * 0.25 / 2, 1e-3);
  for (const Vector2d& p : half)
    EXPECT_NEAR(((p - Vector2d(0.5, 0)).array() / Vector2d(0.5, 0.25).array()).matrix().norm(), 1.0,
                1e-9);
  // Zero radius is a straight line; an arc to its own start point is left out.
  expectVertices(parseOne("M0 0 A0 1 0 0 1 1 0 L1 1 z"), {{0, 0}, {1, 0}, {1, 1}});
  expectVertices(parseOne("M0 0 A1 1 0 1 1 0 0 L1 0 L1 1 z"), {{0, 0}, {1, 0}, {1, 1}});
}

TEST(SvgPath, SubpathsAndClosing) {
  const auto two = parse("M0 0 h1 v1 h-1 z M2 0 h1 v1 h-1 z");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[1][0], Vector2d(2, 0));
  // Not closed with Z: closed anyway; a moveto-only subpath draws nothing.
  expectVertices(parseOne("M5 5 M0 0 L1 0 L1 1"), {{0, 0}, {1, 0}, {1, 1}});
  // After Z the next subpath starts at the initial point of the closed one.
  const auto after_z = parse("M0 0 h1 v1 z h-1 v-1 z z");
  ASSERT_EQ(after_z.size(), 2u);
  expectVertices(after_z[1], {{0, 0}, {-1, 0}, {-1, -1}});
  // Duplicates and a final vertex equal to the first are dropped.
  expectVertices(parseOne("M0 0 L1 0 L1 0 l0 0 L1 1 L0 0 z"), {{0, 0}, {1, 0}, {1, 1}});
}

TEST(SvgPath, OrientationHelper) {
  Outline2d o = parseOne("M0,0 v1 h1 v-1 z");
  orientCounterClockwiseYUp(o);
  EXPECT_EQ(outlineArea(o), 1.0);
  expectVertices(o, {{1, 0}, {1, 1}, {0, 1}, {0, 0}});
  orientCounterClockwiseYUp(o);  // already counter-clockwise: unchanged
  EXPECT_EQ(o[0], Vector2d(1, 0));
}

struct BadPath {
  const char* d;
  const char* offset;   // "offset N" expected in the message
  const char* problem;  // part of the problem text
};

TEST(SvgPath, MalformedInputNamesFileFieldAndOffset) {
  const BadPath cases[] = {
      {"", "offset 0", "must start with a moveto"},
      {"   ", "offset 3", "must start with a moveto"},
      {"L0,0 1,1", "offset 0", "must start with a moveto"},
      {"M0,0 X1", "offset 5", "unknown path command 'X'"},
      {"M0,0 L1", "offset 7", "expected a number"},
      {"M0,0 L nan,1", "offset 7", "expected a number"},
      {"M0,0 L1,0 z", "offset 0", "only 2 distinct vertices"},
      {"M0,0 L0,0 L0,0", "offset 0", "only 1 distinct vertices"},
      {"M0 0 L1 0 L1 1 z 5", "offset 17", "Z takes no arguments"},
      {"M0,0 L1,,0", "offset 8", "expected a number"},
      {"M0,0 L1,0, L1,1", "offset 11", "after ','"},
      {"M0,0 L1e,0", "offset 7", "exponent"},
      {"M0,0 L1e999,0 L1,1", "offset 6", "out of the range"},
      {"M0,0 L.,1", "offset 6", "expected a number"},
      {"M0 0 A1 1 0 2 1 1 1", "offset 12", "arc flag"},
      {"M1 1", "offset 4", "draws no outline"},
      {"M1 1 z", "offset 6", "draws no outline"},
      {"M1e308 0 l1e308 0 0 1", "offset 9", "overflows"},
      {"M0 0 L1 0\x01", "offset 9", "byte 0x01"},
      {"M0 0 h1 v1 z h1 h-1", "offset 13", "distinct vertices"},
  };
  for (const BadPath& c : cases) {
    const InputError e = test::expectInputError([&] { parse(c.d); });
    const std::string what = e.what();
    SCOPED_TRACE(std::string("path \"") + c.d + "\": " + what);
    EXPECT_NE(what.find("catalog.sh3f"), std::string::npos);
    EXPECT_NE(what.find("doorOrWindowCutOutShape"), std::string::npos);
    EXPECT_NE(what.find(c.offset), std::string::npos);
    EXPECT_NE(what.find(c.problem), std::string::npos);
    EXPECT_EQ(what.find('\n'), std::string::npos);  // one line
  }
}

TEST(SvgPath, HostileInputIsRefusedQuickly) {
  const auto start = std::chrono::steady_clock::now();
  // A million distinct tiny segments hit the vertex cap.
  std::string many = "M0 0";
  many.reserve(10'000'000);
  for (int i = 0; i < 1'000'000; ++i) many += " l1e-7 1e-9";
  EXPECT_NE(std::string(test::expectInputError([&] { parse(many); }).what()).find("100000"),
            std::string::npos);
  // A million duplicate vertices collapse and cost nothing but the parse.
  std::string dups = "M0 0";
  dups.reserve(5'000'000);
  for (int i = 0; i < 1'000'000; ++i) dups += " L0 0";
  dups += " L1 0 L1 1 z";
  EXPECT_EQ(parseOne(dups).size(), 3u);
  // Tolerances far below the curve's size would need ~1e150 chords.
  test::expectInputError([&] { parse("M0,0 A0.5,0.5 0 1,0 1,0 z", 1e-300); });
  test::expectInputError([&] { parse("M0,0 C0,1 1,1 1,0 z", 1e-300); });
  // Huge radii or coordinates: refused or flattened, never looping.
  test::expectInputError([&] { parse("M0 0 A1e300 1e300 0 1 0 1 0 z"); });
  test::expectInputError([&] { parse("M-1e308 0 A1 1 0 0 1 1e308 0 z"); });
  test::expectInputError([&] { parse("M0 0 C1e308 1e308 -1e308 -1e308 1 0 z"); });
  // A huge radius on a short chord is an almost straight arc, still exact enough.
  const Outline2d flat = parseOne("M0 0 A1e200 1e200 0 0 1 1 0 L1 1 z");
  EXPECT_EQ(flat.size(), 3u);
  EXPECT_EQ(flat[1], Vector2d(1, 0));
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(secs, 1.0);
}

}  // namespace
}  // namespace inet
