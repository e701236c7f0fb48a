// Shutter timing and pose interpolation. Expected rotations are built from angle-axis values
// chosen by hand, not from the slerp under test.
#include "render/shutter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;

Quat aa(double angle, const Vec3& axis) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

/// Angle of the rotation taking a to b, radians (q and -q alike).
double angleBetween(const Quat& a, const Quat& b) {
  return a.angularDistance(b);
}

TEST(Shutter, GlobalShutterGivesOneTimeForAllRows) {
  Shutter s{.exposure_ns = 8'000'000, .readout_ns = 0};
  EXPECT_TRUE(s.global());
  const TimeNs t0 = 1'305'031'102'175'304'000;
  for (int row : {0, 1, 239, 479}) {
    EXPECT_EQ(rowStart(s, t0, row, 480), t0);
    EXPECT_EQ(sampleTime(s, t0, row, 480, 0.25f), t0 + 2'000'000);
    EXPECT_EQ(groundTruthTime(s, t0, row, 480), t0 + 4'000'000);
  }
  EXPECT_EQ(frameCentreTime(s, t0), t0 + 4'000'000);  // = every row's ground-truth time
  Shutter instant;
  EXPECT_TRUE(instant.global());
  EXPECT_EQ(sampleTime(instant, t0, 17, 480, 0.9f), t0);
  EXPECT_EQ(groundTruthTime(instant, t0, 479, 480), t0);
  EXPECT_EQ(frameCentreTime(instant, t0), t0);
}

TEST(Shutter, RollingRowsAreSpacedReadoutOverHeightMinusOne) {
  // 479 rows in 47.9 ms: exactly 100 us apart
  Shutter s{.exposure_ns = 1'000'000, .readout_ns = 47'900'000};
  EXPECT_FALSE(s.global());
  const TimeNs t0 = 40'000'000;
  for (int row = 0; row < 480; ++row) EXPECT_EQ(rowStart(s, t0, row, 480), t0 + 100'000 * row);
  EXPECT_EQ(rowStart(s, t0, 479, 480), t0 + s.readout_ns);  // last row starts at frame_t + readout
  EXPECT_EQ(sampleTime(s, t0, 10, 480, 0.5f), t0 + 1'000'000 + 500'000);
  EXPECT_EQ(sampleTime(s, t0, 10, 480, 0.0f), t0 + 1'000'000);
  EXPECT_EQ(groundTruthTime(s, t0, 479, 480), t0 + 47'900'000 + 500'000);
  EXPECT_EQ(frameCentreTime(s, t0), t0 + (47'900'000 + 1'000'000) / 2);
  // a spacing that is not a whole number of ns: 10 ms over 4 rows is 3333333.33 ns, and each
  // row start is rounded to the nearest ns (no accumulated drift)
  Shutter r{.exposure_ns = 0, .readout_ns = 10'000'000};
  EXPECT_EQ(rowStart(r, 0, 1, 4), 3'333'333);
  EXPECT_EQ(rowStart(r, 0, 2, 4), 6'666'667);
  EXPECT_EQ(rowStart(r, 0, 3, 4), 10'000'000);
  for (int row = 0; row < 4; ++row)
    EXPECT_LE(std::abs(static_cast<double>(rowStart(r, 0, row, 4)) - 1e7 * row / 3.0), 0.5);
  EXPECT_EQ(rowStart(r, 5, 0, 1), 5);  // a one-row image has no readout
}

TEST(Shutter, SampleTimesCoverTheRowExposureUniformly) {
  Shutter s{.exposure_ns = 16'666'667, .readout_ns = 30'000'000};
  const int n = 1000;
  double sum = 0;
  TimeNs lo = INT64_MAX, hi = INT64_MIN;
  for (int k = 0; k < n; ++k) {
    TimeNs t = sampleTime(s, 0, 240, 481, (k + 0.5f) / n);
    sum += static_cast<double>(t);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  const double row_start = 15'000'000;  // row 240 of 481 is exactly half way through readout
  EXPECT_GE(lo, row_start);
  EXPECT_LE(hi, row_start + s.exposure_ns);
  // the mean sample time is the row's ground-truth time (within the 1 ns rounding)
  EXPECT_NEAR(sum / n, static_cast<double>(groundTruthTime(s, 0, 240, 481)), 1.0);
}

TEST(Shutter, ValidateNamesTheField) {
  try {
    Shutter{.exposure_ns = -1}.validate("rig.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "exposure_ns");
  }
  try {
    Shutter{.exposure_ns = 0, .readout_ns = 200'000'000'000}.validate("rig.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "readout_ns");
  }
  EXPECT_NO_THROW(Shutter({.exposure_ns = 10'000'000, .readout_ns = 30'000'000}).validate("x"));
  EXPECT_NE(Shutter{.readout_ns = 5}.toString().find("rolling"), std::string::npos);
}

TEST(InterpolatePose, EndpointsAreExact) {
  Pose a{aa(0.3, Vec3(1, 2, 3)), Vec3(1, -2, 0.5)};
  Pose b{aa(-1.1, Vec3(0, 1, -1)), Vec3(4, 0, 2)};
  Pose p = interpolatePose(a, 100, b, 300, 100);
  EXPECT_EQ(p.q.coeffs(), a.q.coeffs());
  EXPECT_EQ(p.t, a.t);
  p = interpolatePose(a, 100, b, 300, 300);
  EXPECT_EQ(p.q.coeffs(), b.q.coeffs());
  EXPECT_EQ(p.t, b.t);
  p = interpolatePose(a, 100, a, 100, 100);
  EXPECT_EQ(p.t, a.t);
}

TEST(InterpolatePose, MidpointOfPureRotationIsTheHalfAngle) {
  const Vec3 axis = Vec3(0.2, -0.7, 0.4).normalized();
  Pose a{aa(0.2, axis), Vec3(1, 1, 1)};
  Pose b{aa(0.2 + 2.4, axis), Vec3(1, 1, 1)};
  Pose mid = interpolatePose(a, 0, b, 1'000'000, 500'000);
  EXPECT_LT(angleBetween(mid.q, aa(0.2 + 1.2, axis)), 1e-12);
  EXPECT_NEAR((mid.t - Vec3(1, 1, 1)).norm(), 0, 1e-15);
  EXPECT_NEAR(mid.q.norm(), 1, 1e-15);
  // a quarter of the way: a quarter of the angle (constant angular velocity)
  Pose q1 = interpolatePose(a, 0, b, 1'000'000, 250'000);
  EXPECT_LT(angleBetween(q1.q, aa(0.2 + 0.6, axis)), 1e-12);
  // tiny rotations (1e-10 rad) still interpolate to the right fraction
  Pose c{aa(1e-10, axis), Vec3::Zero()};
  Pose small = interpolatePose(Pose{}, 0, c, 10, 3);
  EXPECT_LT(angleBetween(small.q, aa(3e-11, axis)), 1e-20);
}

TEST(InterpolatePose, TakesTheShortArcAcrossTheSignFlip) {
  // 170 and -170 degrees about z are 20 degrees apart through 180, but their quaternions have a
  // negative dot product, so a naive slerp would turn 340 degrees the long way round; the same
  // must hold when b is given as -q
  const Vec3 z = Vec3::UnitZ();
  Quat qa = aa(170 * kPi / 180, z), qb = aa(-170 * kPi / 180, z);
  ASSERT_LT(qa.coeffs().dot(qb.coeffs()), 0);
  Pose mid = interpolatePose({qa, Vec3::Zero()}, 0, {qb, Vec3::Zero()}, 2, 1);
  EXPECT_LT(angleBetween(mid.q, aa(kPi, z)), 1e-12);
  Quat nb = qb;
  nb.coeffs() = -nb.coeffs();  // same rotation as qb
  for (double f : {0.1, 0.5, 0.9}) {
    TimeNs t = static_cast<TimeNs>(f * 1000);
    Pose x = interpolatePose({qa, Vec3::Zero()}, 0, {qb, Vec3::Zero()}, 1000, t);
    Pose y = interpolatePose({qa, Vec3::Zero()}, 0, {nb, Vec3::Zero()}, 1000, t);
    Quat expected = aa((170 + 20 * f) * kPi / 180, z);
    EXPECT_LT(angleBetween(x.q, expected), 1e-12) << f;
    EXPECT_LT(angleBetween(y.q, expected), 1e-12) << f;
  }
}

TEST(InterpolatePose, PositionIsLinearInTime) {
  Pose a{Quat::Identity(), Vec3(0, 0, 0)}, b{aa(0.5, Vec3::UnitX()), Vec3(3, -6, 9)};
  Pose p = interpolatePose(a, 1000, b, 4000, 2000);
  EXPECT_NEAR((p.t - Vec3(1, -2, 3)).norm(), 0, 1e-15);
  p = interpolatePose(a, 1000, b, 4000, 7000);  // extrapolates
  EXPECT_NEAR((p.t - Vec3(6, -12, 18)).norm(), 0, 1e-14);
  EXPECT_LT(angleBetween(p.q, aa(1.0, Vec3::UnitX())), 1e-12);
}

struct Stamped {  // the members interpolatePoseAt expects (as trajectory's TimedPose has)
  TimeNs t_ns;
  Pose T_world_camera;
};

TEST(InterpolatePose, InAListOfTimedPoses) {
  std::vector<Stamped> list;
  // k^2 rather than k: interpolating between the wrong neighbours would give another value
  for (int k = 0; k < 5; ++k)
    list.push_back({1000 + 100 * k, Pose{aa(0.1 * k * k, Vec3::UnitY()), Vec3(k * k, 0, 0)}});
  Pose p;
  ASSERT_TRUE(interpolatePoseAt(list, 1250, p));  // half way from the 3rd (4) to the 4th (9)
  EXPECT_NEAR((p.t - Vec3(6.5, 0, 0)).norm(), 0, 1e-15);
  EXPECT_LT(angleBetween(p.q, aa(0.65, Vec3::UnitY())), 1e-12);
  ASSERT_TRUE(interpolatePoseAt(list, 1010, p));  // in the first interval
  EXPECT_NEAR((p.t - Vec3(0.1, 0, 0)).norm(), 0, 1e-15);
  for (const Stamped& s : list) {  // exact at every stored time, including both ends
    ASSERT_TRUE(interpolatePoseAt(list, s.t_ns, p));
    EXPECT_EQ(p.t, s.T_world_camera.t);
    EXPECT_EQ(p.q.coeffs(), s.T_world_camera.q.coeffs());
  }
  EXPECT_FALSE(interpolatePoseAt(list, 999, p));  // before the start: holds the first pose
  EXPECT_EQ(p.t, list.front().T_world_camera.t);
  EXPECT_FALSE(interpolatePoseAt(list, 1401, p));
  EXPECT_EQ(p.t, list.back().T_world_camera.t);
  EXPECT_FALSE(interpolatePoseAt(std::vector<Stamped>{}, 0, p));
  std::vector<Stamped> one = {list[2]};
  EXPECT_TRUE(interpolatePoseAt(one, 1200, p));
  EXPECT_FALSE(interpolatePoseAt(one, 1201, p));
}

}  // namespace
}  // namespace inet
