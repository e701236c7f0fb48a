#include <gtest/gtest.h>

#include "core/error.h"
#include "core/pose.h"
#include "core/progress.h"

namespace inet {
namespace {

TEST(Pose, ComposeAndInverse) {
  Pose a{Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())), Vec3(1, -2, 0.5)};
  Pose b{Quat(Eigen::AngleAxisd(-1.1, Vec3(0, 1, 0))), Vec3(0.2, 0.1, 3)};
  Vec3 p(0.7, -0.4, 2.0);
  EXPECT_NEAR(((a * b) * p - a * (b * p)).norm(), 0, 1e-12);
  EXPECT_NEAR((a.inverse() * (a * p) - p).norm(), 0, 1e-12);
  EXPECT_NEAR((Pose::fromMatrix(a.matrix()).matrix() - a.matrix()).norm(), 0, 1e-12);
}

TEST(Pose, CanonicalQuatHasNonNegativeW) {
  Quat q(-0.5, 0.5, -0.5, 0.5);
  Quat c = canonicalQuat(q);
  EXPECT_GE(c.w(), 0);
  EXPECT_NEAR(c.angularDistance(q), 0, 1e-12);
}

TEST(Time, NanosecondsToSecondsIsExact) {
  EXPECT_EQ(nsToSecondsString(1403715273262142976LL), "1403715273.262142976");
  EXPECT_EQ(nsToSecondsString(1305031102175304000LL, 6), "1305031102.175304");
  EXPECT_EQ(nsToSecondsString(0, 6), "0.000000");
  EXPECT_EQ(nsToSecondsString(40000000, 6), "0.040000");
  EXPECT_EQ(nsToSecondsString(1999999999, 6), "2.000000");  // rounds half up at 6 decimals
  EXPECT_EQ(nsToSecondsString(-1500000000, 3), "-1.500");
  EXPECT_EQ(nsToSecondsString(5, 0), "0");
}

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(formatDuration(0), "0:00");
  EXPECT_EQ(formatDuration(75.4), "1:15");
  EXPECT_EQ(formatDuration(3725), "1:02:05");
  EXPECT_EQ(formatDuration(-1), "--:--");
}

TEST(InputError, MessageNamesFileFieldProblem) {
  InputError e("room.json", "objects[3].transform", "negative scale");
  EXPECT_STREQ(e.what(), "room.json: objects[3].transform: negative scale");
  EXPECT_STREQ(InputError("", "--spp", "must be >= 1").what(), "--spp: must be >= 1");
}

}  // namespace
}  // namespace inet
