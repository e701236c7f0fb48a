// Trajectory files as real tools write them (issue 13, defects 1 and 2): repeated stamps in
// motion-capture ground truth (TUM fr2/desk), numpy.savetxt's scientific notation, byte-order
// marks, header lines without '#'.
#include <gtest/gtest.h>

#include <cmath>
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

// Estimates as SLAM systems write them (found by trying their published outputs).
TEST(SlamOutputs, OrbSlam3EurocRunsInTumLayoutHaveNanosecondStamps) {
  // ORB-SLAM3's KeyFrameTrajectory.txt for EuRoC MH_01: TUM layout, stamps in ns
  const std::string text =
      "1403636584513555456.000000 2.181544304 -0.399600983 -0.430783629 -0.559665382 "
      "-0.625610530 -0.363104433 0.404402494\n"
      "1403636584763555584.000000 2.181544304 -0.399600983 -0.430783629 -0.559665382 "
      "-0.625610530 -0.363104433 0.404402494\n";
  TrajectoryReadReport report;
  const Trajectory t =
      parseTrajectory(text, "KeyFrameTrajectory.txt",
                      detectTrajectoryFormat("KeyFrameTrajectory.txt", text), {}, &report);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].t_ns, 1403636584513555456LL);
  EXPECT_TRUE(report.nanosecond_stamps);
  EXPECT_NE(report.summary().find("nanoseconds"), std::string::npos);
}

TEST(SlamOutputs, VinsRowsWithVelocityAndATrailingComma) {
  // VINS-Mono's vins_result_no_loop.csv: t_ns, p, q (w first), v, and a trailing comma
  const std::string vins =
      "1547620674418966272,-0.01929,0.06007,0.56947,0.99965,0.01204,0.02197,-0.00895,-0.01860,"
      "0.04575,0.59417,\n"
      "1547620674468966272,-0.01929,0.06007,0.56947,0.99965,0.01204,0.02197,-0.00895,-0.01860,"
      "0.04575,0.59417,\n";
  TrajectoryReadReport report;
  Trajectory t = parseTrajectory(vins, "vins.csv", detectTrajectoryFormat("vins.csv", vins), {},
                                 &report);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[1].t_ns, 1547620674468966272LL);
  EXPECT_NEAR(t.poses[0].T_world_camera.q.w(), 0.99965 / std::sqrt(0.99965 * 0.99965 +
                                                                    0.01204 * 0.01204 +
                                                                    0.02197 * 0.02197 +
                                                                    0.00895 * 0.00895),
              1e-12);
  EXPECT_EQ(report.ignored_columns, 3u);
  // an 8-column EuRoC row with a trailing comma
  t = parseTrajectory("1403636580838555648,-0.00230,0.00318,0.00145,0.99999,0.00021,0.00305,"
                      "-0.00142,\n",
                      "e.csv", TrajectoryFormat::Euroc);
  EXPECT_EQ(t.size(), 1u);
}

TEST(SlamOutputs, OpenVinsEvalFilesCarryACovariance) {
  // ov_eval: "# timestamp(s) tx ty tz qx qy qz qw Pr11 Pr12 Pr13 Pr22 Pr23 Pr33 Pt11 ... Pt33"
  std::string row = "1403715273.262142976 1 2 3 0 0 0 1";
  for (int k = 0; k < 12; ++k) row += " 0.0001";
  TrajectoryReadReport report;
  const std::string text = "# timestamp(s) tx ty tz qx qy qz qw Pr11 Pr12 Pr13 Pr22 Pr23 Pr33 "
                           "Pt11 Pt12 Pt13 Pt22 Pt23 Pt33\n" + row + "\n";
  const Trajectory t =
      parseTrajectory(text, "ov.txt", detectTrajectoryFormat("ov.txt", text), {}, &report);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(report.ignored_columns, 12u);
}

TEST(KittiFormat, PosesReadInAZUpWorldAndRoundTrip) {
  // the first KITTI pose is the identity: the camera at the origin looking along its z, which
  // is the first camera frame's forward: ours is +y, with image-down along -z
  const std::string text = "1 0 0 0 0 1 0 0 0 0 1 0\n"
                           "1 0 0 0.5 0 1 0 -0.2 0 0 1 3.0\n";
  const Trajectory t = parseTrajectory(text, "00.txt", detectTrajectoryFormat("00.txt", text));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[1].t_ns, 100000000);  // 10 Hz
  const Mat3 R = t.poses[0].T_world_camera.rotation();
  EXPECT_NEAR((R.col(2) - Vec3(0, 1, 0)).norm(), 0, 1e-12);   // forward
  EXPECT_NEAR((R.col(1) - Vec3(0, 0, -1)).norm(), 0, 1e-12);  // image down = world down
  // 3 m forward, 0.5 right, 0.2 up (KITTI's y is down)
  EXPECT_NEAR((t.poses[1].T_world_camera.t - Vec3(0.5, 3.0, 0.2)).norm(), 0, 1e-12);
  const Trajectory back = parseTrajectory(formatTrajectory(t, TrajectoryFormat::Kitti), "b.txt",
                                          TrajectoryFormat::Kitti);
  ASSERT_EQ(back.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.poses[k].t_ns, t.poses[k].t_ns);
    EXPECT_NEAR((back.poses[k].T_world_camera.t - t.poses[k].T_world_camera.t).norm(), 0, 1e-9);
    EXPECT_NEAR(back.poses[k].T_world_camera.q.angularDistance(t.poses[k].T_world_camera.q), 0,
                1e-9);
  }
  // scenenet_v1 round trips too
  const Trajectory v1 = parseTrajectory(formatTrajectory(t, TrajectoryFormat::SceneNetV1,
                                                         {.pose_list_fps = 10.0}),
                                        "v1.txt", TrajectoryFormat::SceneNetV1,
                                        {.pose_list_fps = 10.0});
  EXPECT_NEAR((v1.poses[1].T_world_camera.t - t.poses[1].T_world_camera.t).norm(), 0, 1e-9);
  EXPECT_NEAR(v1.poses[1].T_world_camera.q.angularDistance(t.poses[1].T_world_camera.q), 0, 1e-9);
}

}  // namespace
}  // namespace inet
