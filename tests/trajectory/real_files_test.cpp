// Trajectory files as real tools write them (issue 13, defects 1 and 2): repeated stamps in
// motion-capture ground truth (TUM fr2/desk), numpy.savetxt's scientific notation, byte-order
// marks, header lines without '#'.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/error.h"
#include "../expect_input_error.h"
#include "trajectory/formats.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

const std::string kTrajectories = std::string(INET_SHARED_DIR) + "/data/trajectories/";

/// The message of the InputError `f` throws.
template <class F>
std::string inputErrorOf(F f) {
  return test::expectInputError(f).what();
}

/// An integer number of nanoseconds written as numpy.savetxt's default '%.18e' would write the
/// seconds: one digit, a point, 18 digits, e+09. Built from the digits, not through a double.
std::string numpySeconds(TimeNs t_ns) {
  const std::string digits = std::to_string(t_ns);  // 19 digits for stamps of 2001..2286
  EXPECT_EQ(digits.size(), 19u);
  return digits.substr(0, 1) + "." + digits.substr(1) + "e+09";
}

TEST(RepeatedStamps, OfficialFr2DeskReadsKeepingTheFirstPoseOfTheRepeatedStamp) {
  const std::string path = kTrajectories + "tum_rgbd_fr2_desk_groundtruth.txt";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data/trajectories not found";
  TrajectoryReadReport report;
  const Trajectory t = readTrajectory(path, {}, {}, &report);
  EXPECT_EQ(t.size(), 20956u);  // 20957 pose lines, one repeats the stamp before it
  EXPECT_EQ(report.repeated_stamps, 1u);
  EXPECT_EQ(report.repeated_with_other_pose, 1u);
  EXPECT_EQ(report.first_repeat_line, 10863);
  // lines 10862/10863: "1311868229.5760 1.4054 0.9615 1.3677 ..." then "... 1.4044 0.9614 ..."
  bool found = false;
  for (const TimedPose& p : t.poses)
    if (p.t_ns == 1311868229576000000LL) {
      found = true;
      EXPECT_NEAR((p.T_world_camera.t - Vec3(1.4054, 0.9615, 1.3677)).norm(), 0, 1e-12);
    }
  EXPECT_TRUE(found);
  const std::string line = report.summary();
  EXPECT_NE(line.find("line 10863"), std::string::npos) << line;
  EXPECT_NE(line.find("first"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << "one warning line";
}

TEST(RepeatedStamps, EveryReaderKeepsTheFirstPoseAndCountsTheRest) {
  struct Case {
    TrajectoryFormat fmt;
    std::string text;
  };
  const Case cases[] = {
      {TrajectoryFormat::Tum, "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n2.000 9 9 9 0 0 0 1\n"
                              "2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n"},
      {TrajectoryFormat::Euroc, "1000000000,0,0,0,1,0,0,0\n2000000000,1,0,0,1,0,0,0\n"
                                "2000000000,9,9,9,1,0,0,0\n2000000000,1,0,0,1,0,0,0\n"
                                "3000000000,2,0,0,1,0,0,0\n"},
      {TrajectoryFormat::SlamBench, "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n2.0 9 9 9 0 0 0 1\n"
                                    "2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n"},
      {TrajectoryFormat::Icl, "30 0 0 0 0 0 0 1\n60 1 0 0 0 0 0 1\n60 9 9 9 0 0 0 1\n"
                              "60 1 0 0 0 0 0 1\n90 2 0 0 0 0 0 1\n"},
      {TrajectoryFormat::SceneNet,
       "time:1 pose:0,0,0 lookat:0,0,1\ntime:2 pose:1,0,0 lookat:1,0,1\n"
       "time:2 pose:9,9,9 lookat:9,9,10\ntime:2 pose:1,0,0 lookat:1,0,1\n"
       "time:3 pose:2,0,0 lookat:2,0,1\n"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(trajectoryFormatName(c.fmt));
    TrajectoryReadReport report;
    const Trajectory t = parseTrajectory(c.text, "dup", c.fmt, {}, &report);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(report.repeated_stamps, 2u);
    EXPECT_EQ(report.repeated_with_other_pose, 1u);  // the third line; the fourth repeats the 2nd
    EXPECT_EQ(report.first_repeat_line, 3);
    EXPECT_NEAR(t.poses[1].T_world_camera.t.norm(), 1.0, 1e-12) << "the first pose is kept";
  }
}

TEST(RepeatedStamps, TimeGoingBackIsStillAnErrorNamingTheLine) {
  const std::string msg = inputErrorOf(
      [] { parseTrajectory("2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n", "back.txt",
                           TrajectoryFormat::Tum); });
  EXPECT_NE(msg.find("back.txt"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
}

TEST(ScientificNotation, SecondsAreReadFromTheDigitsExactly) {
  TimeNs t = 0;
  ASSERT_TRUE(parseSecondsToNs("1.403715529112143517e+09", t));
  EXPECT_EQ(t, 1403715529112143517LL);
  ASSERT_TRUE(parseSecondsToNs("1.5E-3", t));
  EXPECT_EQ(t, 1500000);
  ASSERT_TRUE(parseSecondsToNs("-2.5e0", t));
  EXPECT_EQ(t, -2500000000LL);
  ASSERT_TRUE(parseSecondsToNs("15e-1", t));
  EXPECT_EQ(t, 1500000000LL);
  ASSERT_TRUE(parseSecondsToNs(".5", t));
  EXPECT_EQ(t, 500000000LL);
  ASSERT_TRUE(parseSecondsToNs("1.0000000004", t));  // beyond 1 ns: rounded to the nearest
  EXPECT_EQ(t, 1000000000LL);
  ASSERT_TRUE(parseSecondsToNs("1.0000000005", t));
  EXPECT_EQ(t, 1000000001LL);
  ASSERT_TRUE(parseSecondsToNs("0.000000000000000000000000000001e+30", t));
  EXPECT_EQ(t, 1000000000LL);
  ASSERT_TRUE(parseSecondsToNs("1e+0000000000000000000000009", t));  // leading zeros
  EXPECT_EQ(t, 1000000000000000000LL);
  for (const char* bad : {"1e", "e5", "1e+", "1.5e3.2", "1e99", "1e-99x", "0x10", "inf", "nan",
                          "--1", "99999999999.0", ".", "1e5e5"})
    EXPECT_FALSE(parseSecondsToNs(bad, t)) << bad;
}

TEST(ScientificNotation, NumpySavetxtFilesReadInEveryFormatWithNanosecondsIntact) {
  const TimeNs t0 = 1403715529112143517LL;
  const TimeNs t1 = t0 + 33333334;  // 30 Hz, odd nanoseconds
  // TUM as numpy.savetxt(fname, poses) writes it (default fmt '%.18e', space separated)
  const std::string row = " 1.000000000000000000e+00 -2.500000000000000000e-01 "
                          "0.000000000000000000e+00 0.000000000000000000e+00 "
                          "0.000000000000000000e+00 0.000000000000000000e+00 "
                          "1.000000000000000000e+00\n";
  const std::string tum = numpySeconds(t0) + row + numpySeconds(t1) + row;
  Trajectory t = parseTrajectory(tum, "est.txt", detectTrajectoryFormat("est.txt", tum));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].t_ns, t0);
  EXPECT_EQ(t.poses[1].t_ns, t1);
  EXPECT_NEAR((t.poses[1].T_world_camera.t - Vec3(1, -0.25, 0)).norm(), 0, 1e-15);
  // EuRoC with nanoseconds as numpy writes an int64 column through a float format
  const std::string euroc = "1.403715529112143517e+18,1,2,3,1,0,0,0\n"
                            "1.403715529145476851e+18,1,2,3,1,0,0,0\n";
  t = parseTrajectory(euroc, "est.csv", detectTrajectoryFormat("est.csv", euroc));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].t_ns, t0);
  EXPECT_EQ(t.poses[1].t_ns, 1403715529145476851LL);
  // ...but a fraction of a nanosecond is not a nanosecond count
  const std::string msg = inputErrorOf([] {
    parseTrajectory("1.5e0,1,2,3,1,0,0,0\n", "ns.csv", TrajectoryFormat::Euroc);
  });
  EXPECT_NE(msg.find("nanoseconds"), std::string::npos) << msg;
  // ICL frame numbers
  t = parseTrajectory("0.000000000000000000e+00 0 0 0 0 0 0 1\n3.000000000000000000e+01 0 0 0 0 0 "
                      "0 1\n",
                      "lr.gt.freiburg", TrajectoryFormat::Icl);
  EXPECT_EQ(t.poses[1].t_ns, 1000000000LL);
  // SceneNet
  t = parseTrajectory("time:2.5e-1 pose:0,0,0 lookat:1e0,0,0\n", "v.log", TrajectoryFormat::SceneNet);
  EXPECT_EQ(t.poses[0].t_ns, 250000000LL);
}

TEST(ScientificNotation, SlamBenchStillRefusesWhatSlamBenchsRegexRefuses) {
  // SLAMBench's own reader would stop there: the slambench reader exists to say so
  const std::string msg = inputErrorOf([] {
    parseTrajectory("1.0e+00 0 0 0 0 0 0 1\n", "gt.txt", TrajectoryFormat::SlamBench);
  });
  EXPECT_NE(msg.find("SLAMBench"), std::string::npos) << msg;
}

TEST(RealFileQuirks, ByteOrderMarkAndHeaderRowsWithoutHash) {
  // a UTF-8 byte-order mark (Windows editors) before a '#' comment
  Trajectory t = parseTrajectory("\xEF\xBB\xBF# timestamp tx ty tz qx qy qz qw\n1 0 0 0 0 0 0 1\n",
                                 "bom.txt", TrajectoryFormat::Tum);
  EXPECT_EQ(t.size(), 1u);
  // pandas.to_csv / spreadsheet exports name the columns without '#'
  const std::string csv =
      "timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z\n1000,0,0,0,1,0,0,0\n2000,0,0,0,1,0,0,0\n";
  t = parseTrajectory(csv, "pandas.csv", detectTrajectoryFormat("pandas.csv", csv));
  EXPECT_EQ(t.size(), 2u);
  const std::string tum = "timestamp tx ty tz qx qy qz qw\n1 0 0 0 0 0 0 1\n";
  t = parseTrajectory(tum, "h.txt", detectTrajectoryFormat("h.txt", tum));
  EXPECT_EQ(t.size(), 1u);
  // but only the first line may be a header
  const std::string msg = inputErrorOf([] {
    parseTrajectory("1 0 0 0 0 0 0 1\ntimestamp tx ty tz qx qy qz qw\n", "h2.txt",
                    TrajectoryFormat::Tum);
  });
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
}

TEST(SceneNetV1Format, RandomPoseBlocksOfTheSharedRoomAreOpenGlCamerasInAYUpWorld) {
  const std::string path = std::string(INET_SHARED_DIR) +
                           "/data/scenes/scenenet_v1/room_89_simple_data/"
                           "room_89_simple_trajectory_random_poses_SE3_3x4.txt";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data/scenes/scenenet_v1 not found";
  const Trajectory t = readTrajectory(path);
  ASSERT_EQ(t.size(), 500u);
  EXPECT_EQ(t.poses[1].t_ns - t.poses[0].t_ns, 40000000);  // 25 Hz by default
  // first block: R columns (-0.364, 0, -0.931), (0.0815, 0.996, -0.0319), (0.928, -0.0875,
  // -0.363), t (-1.56063, 1.85001, 0.308069). The camera's y column is the file's up (+Y): an
  // OpenGL camera (x right, y up, looking along -z). In our Z-up world (x, -z, y):
  const Pose& T = t.poses[0].T_world_camera;
  EXPECT_NEAR((T.t - Vec3(-1.56063, -0.308069, 1.85001)).norm(), 0, 1e-9);
  const Vec3 forward = T.rotation().col(2), down = T.rotation().col(1);
  EXPECT_NEAR((forward - Vec3(-0.927768, -0.36275, 0.0875173)).norm(), 0, 1e-5);
  EXPECT_LT(down.z(), -0.99);  // image down is world down: a level camera
}

}  // namespace
}  // namespace inet
