// Trajectory file formats: real samples with the values their READMEs state, round trips of every
// format, the ICL and SceneNet frame conventions derived independently, error messages naming
// file and line, and parsers fed garbage.
#include "trajectory/formats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include <fmt/format.h>

#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

const std::string kShared = std::string(INET_SHARED_DIR) + "/data";
constexpr TrajectoryFormat kAll[] = {TrajectoryFormat::Tum, TrajectoryFormat::Euroc,
                                     TrajectoryFormat::Icl, TrajectoryFormat::SlamBench,
                                     TrajectoryFormat::SceneNet};

double spanSeconds(const Trajectory& t) {
  return (t.poses.back().t_ns - t.poses.front().t_ns) * 1e-9;
}

/// Runs `fn`, which must throw InputError; returns its message.
template <class F>
std::string inputErrorOf(F fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return {};
}

/// 60 poses at 30 fps (t = round(k / 30 s)), random positions in a room and random orientations
/// that never look straight up or down (SceneNet cannot express those).
Trajectory syntheticTrajectory() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Trajectory t;
  for (int k = 0; k < 60; ++k) {
    const Vec3 eye(3 * u(rng), 3 * u(rng), 1.5 + 0.5 * u(rng));
    const Vec3 dir(u(rng), u(rng), 0.6 * u(rng));
    Pose p = Pose::lookAt(eye, eye + dir, Vec3::UnitZ());
    p.q = p.q * Quat(Eigen::AngleAxisd(0.3 * u(rng), Vec3::UnitZ()));  // add roll
    t.poses.push_back({static_cast<TimeNs>(std::llround(k * 1e9 / 30.0)), p});
  }
  return t;
}

void expectSamePoses(const Trajectory& a, const Trajectory& b, double tol_m, double tol_rad) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.poses[i].t_ns, b.poses[i].t_ns) << "pose " << i;
    EXPECT_LE((a.poses[i].T_world_camera.t - b.poses[i].T_world_camera.t).norm(), tol_m)
        << "pose " << i;
    EXPECT_LE(a.poses[i].T_world_camera.q.angularDistance(b.poses[i].T_world_camera.q), tol_rad)
        << "pose " << i;
  }
}

TEST(TrajectoryFormatNames, RoundTripAndListTheValidNames) {
  for (TrajectoryFormat f : kAll) EXPECT_EQ(parseTrajectoryFormat(trajectoryFormatName(f)), f);
  const std::string msg = inputErrorOf([] { parseTrajectoryFormat("kitty", "--to"); });
  EXPECT_NE(msg.find("--to"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tum, euroc, icl, slambench, scenenet"), std::string::npos) << msg;
  EXPECT_EQ(trajectoryFormatFromExtension("a/livingRoom0.gt.freiburg"), TrajectoryFormat::Icl);
  EXPECT_EQ(trajectoryFormatFromExtension("data.csv"), TrajectoryFormat::Euroc);
  EXPECT_EQ(trajectoryFormatFromExtension("render_info.log"), TrajectoryFormat::SceneNet);
  EXPECT_EQ(trajectoryFormatFromExtension("groundtruth.txt"), TrajectoryFormat::Tum);
  EXPECT_EQ(trajectoryFormatFromExtension("poses.bin"), std::nullopt);
}

// formats/README.md: 80 rows x 17 columns, 25 ms spacing; first row copied from the file.
TEST(EurocFormat, ReadsRealGroundTruthExcerpt) {
  const std::string path = kShared + "/formats/euroc_asl/mav0/state_groundtruth_estimate0/data.csv";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data/formats (EuRoC sample) not found";
  EXPECT_EQ(detectTrajectoryFormat(path, readTextFile(path)), TrajectoryFormat::Euroc);
  const Trajectory t = readTrajectory(path);
  ASSERT_EQ(t.size(), 80u);
  EXPECT_EQ(t.poses[0].t_ns, 1403715524922140000LL);
  EXPECT_EQ(t.poses[1].t_ns - t.poses[0].t_ns, 25000000);
  EXPECT_NEAR(spanSeconds(t), 79 * 0.025, 1e-9);
  const Pose& p = t.poses[0].T_world_camera;
  EXPECT_NEAR((p.t - Vec3(0.515292, 1.996597, 0.971028)).norm(), 0, 1e-12);
  const Quat q = Quat(0.161869, 0.790012, -0.205215, 0.554587).normalized();  // w first
  EXPECT_NEAR(p.q.angularDistance(q), 0, 1e-9);
}

// trajectories/README.md: EuRoC V1_02 16702 poses over 83.50 s; TUM-VI rooms (8 columns).
TEST(EurocFormat, ReadsRealSequencesWithTheStatedCountsAndSpans) {
  const std::string dir = kShared + "/trajectories/";
  if (!fs::exists(dir + "euroc_V1_02_medium_state_groundtruth.csv"))
    GTEST_SKIP() << "../shared/data/trajectories not found";
  const Trajectory v102 = readTrajectory(dir + "euroc_V1_02_medium_state_groundtruth.csv");
  EXPECT_EQ(v102.size(), 16702u);
  EXPECT_EQ(v102.poses[0].t_ns, 1403715524907143168LL);
  EXPECT_NEAR(spanSeconds(v102), 83.50, 0.005);
  const struct {
    int room;
    size_t poses;
    double span_s;
  } rooms[] = {{1, 16541, 141.02}, {2, 15477, 144.07}, {3, 15200, 141.02},
               {4, 13075, 111.37}, {5, 16999, 142.32}, {6, 15244, 130.83}};
  for (const auto& r : rooms) {
    const Trajectory t = readTrajectory(dir + fmt::format("tum_vi_room{}_mocap.csv", r.room));
    EXPECT_EQ(t.size(), r.poses) << "room " << r.room;
    EXPECT_NEAR(spanSeconds(t), r.span_s, 0.005) << "room " << r.room;
  }
  const Trajectory room1 = readTrajectory(dir + "tum_vi_room1_mocap.csv");
  EXPECT_EQ(room1.poses[0].t_ns, 1520530308189679351LL);
  EXPECT_NEAR(
      (room1.poses[0].T_world_camera.t - Vec3(0.8417820384, -0.2193354118, 1.2499749141)).norm(), 0,
      1e-12);
}

TEST(TumFormat, DetectsRealFileAndReportsTheDuplicateStampOfFr2Desk) {
  const std::string dir = kShared + "/trajectories/";
  if (!fs::exists(dir + "tum_rgbd_fr1_xyz_groundtruth.txt"))
    GTEST_SKIP() << "../shared/data/trajectories not found";
  const Trajectory t = readTrajectory(dir + "tum_rgbd_fr1_xyz_groundtruth.txt");
  EXPECT_EQ(t.size(), 3000u);
  EXPECT_NEAR(spanSeconds(t), 30.09, 0.005);
  // README: "File lines 10862 and 10863 share the timestamp 1311868229.5760": read as evo reads
  // it (the first pose kept), and reported (real_files_test.cpp has the details)
  TrajectoryReadReport report;
  const Trajectory desk = readTrajectory(dir + "tum_rgbd_fr2_desk_groundtruth.txt", {}, {}, &report);
  EXPECT_EQ(desk.size(), 20956u);
  EXPECT_EQ(report.first_repeat_line, 10863);
}

TEST(TrajectoryFormats, EveryFormatRoundTripsThroughAFile) {
  const Trajectory t = syntheticTrajectory();
  test::TempDir dir("formats");
  for (TrajectoryFormat f : kAll) {
    SCOPED_TRACE(trajectoryFormatName(f));
    // ICL-NUIM's frame numbers look like whole-second TUM stamps: only its extension tells
    const std::string path = (dir / (std::string("traj_") + trajectoryFormatName(f) +
                                     (f == TrajectoryFormat::Icl ? ".gt.freiburg" : "")))
                                 .string();
    writeTrajectory(path, t, f);
    if (f == TrajectoryFormat::Icl) {
      EXPECT_EQ(detectTrajectoryFormat("traj.txt", readTextFile(path)), TrajectoryFormat::Tum);
    }
    // our own output is recognised, except SLAMBench files, which read as (identical) TUM
    const std::string text = readTextFile(path);
    EXPECT_EQ(detectTrajectoryFormat(path, text),
              f == TrajectoryFormat::SlamBench ? TrajectoryFormat::Tum : f);
    const Trajectory back = readTrajectory(path, f);
    if (f == TrajectoryFormat::SceneNet) {
      ASSERT_EQ(back.size(), t.size());
      for (size_t i = 0; i < t.size(); ++i) {
        const Pose &a = t.poses[i].T_world_camera, &b = back.poses[i].T_world_camera;
        EXPECT_EQ(back.poses[i].t_ns, t.poses[i].t_ns);
        EXPECT_LE((a.t - b.t).norm(), 1e-9);
        EXPECT_LE((a.rotation().col(2) - b.rotation().col(2)).norm(), 1e-9);  // view direction
        EXPECT_NEAR(b.rotation().col(0).z(), 0, 1e-12);  // roll is gone: image x horizontal
      }
    } else {
      // TUM keeps the existing 9-decimal quaternions (angle error up to ~2e-9 rad); EuRoC is
      // written losslessly
      const double tol_rad = f == TrajectoryFormat::Tum     ? 3e-9
                             : f == TrajectoryFormat::Euroc ? 1e-14
                                                            : 1e-9;
      expectSamePoses(t, back, f == TrajectoryFormat::Euroc ? 1e-14 : 1e-9, tol_rad);
    }
  }
}

// The 12 extra EuRoC columns: velocity by central differences (one-sided at the ends), zero bias.
TEST(EurocFormat, WritesCentralDifferenceVelocityAndZeroBiases) {
  const Trajectory t = syntheticTrajectory();
  const std::string text = formatTrajectory(t, TrajectoryFormat::Euroc);
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w []", 0), 0u);
  while (std::getline(in, line)) {
    std::vector<double> r;
    std::istringstream f(line);
    std::string cell;
    while (std::getline(f, cell, ',')) r.push_back(std::stod(cell));
    ASSERT_EQ(r.size(), 17u);
    rows.push_back(r);
  }
  ASSERT_EQ(rows.size(), t.size());
  for (size_t k : {size_t(0), size_t(17), t.size() - 1}) {
    const size_t a = k == 0 ? 0 : k - 1, b = k + 1 == t.size() ? k : k + 1;
    const Vec3 v = (t.poses[b].T_world_camera.t - t.poses[a].T_world_camera.t) /
                   ((t.poses[b].t_ns - t.poses[a].t_ns) * 1e-9);
    EXPECT_NEAR(rows[k][8], v.x(), 1e-8);
    EXPECT_NEAR(rows[k][9], v.y(), 1e-8);
    EXPECT_NEAR(rows[k][10], v.z(), 1e-8);
    for (int c = 11; c < 17; ++c) EXPECT_EQ(rows[k][c], 0.0);
  }
}

TEST(TrajectoryFormats, TumToEurocToTumIsIdentical) {
  const std::string path = kShared + "/trajectories/tum_rgbd_fr1_xyz_groundtruth.txt";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data/trajectories not found";
  const Trajectory tum = readTrajectory(path);
  const Trajectory via_euroc = parseTrajectory(formatTrajectory(tum, TrajectoryFormat::Euroc),
                                               "mem.csv", TrajectoryFormat::Euroc);
  EXPECT_EQ(formatTrajectory(via_euroc, TrajectoryFormat::Tum),
            formatTrajectory(tum, TrajectoryFormat::Tum));
}

// ICL-NUIM's lr kt0 starts with the identity at (0, 0, -2.25): POV-Ray's level camera looking
// along its +z (forward), y up. In our Z-up world that camera looks along +y, image-down = -z.
TEST(IclFormat, FirstLivingRoomPoseIsALevelCamera) {
  const Trajectory t =
      parseTrajectory("0 0 0 -2.25 0 0 0 1\n", "lr0.gt.freiburg", TrajectoryFormat::Icl);
  const Pose& p = t.poses[0].T_world_camera;
  EXPECT_EQ(t.poses[0].t_ns, 0);
  EXPECT_NEAR((p.t - Vec3(0, -2.25, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((p.rotation().col(0) - Vec3(1, 0, 0)).norm(), 0, 1e-12);   // image right
  EXPECT_NEAR((p.rotation().col(1) - Vec3(0, 0, -1)).norm(), 0, 1e-12);  // image down
  EXPECT_NEAR((p.rotation().col(2) - Vec3(0, 1, 0)).norm(), 0, 1e-12);   // forward
}

// A camera at (1, 2, 3) looking straight up (+z, ours), image-down = +y. ICL (POV-Ray world:
// x, y = up, z = our y) must see it at (1, 3, 2) looking along its up axis +y, and its camera
// y axis (image UP, since fy < 0) pointing along -y ours = POV -z.
TEST(IclFormat, CameraLookingUpMapsToIclUpAxis) {
  Trajectory t;
  Mat3 r;
  r.col(0) = Vec3(1, 0, 0);
  r.col(1) = Vec3(0, 1, 0);
  r.col(2) = Vec3(0, 0, 1);
  t.poses.push_back({0, Pose{Quat(r), Vec3(1, 2, 3)}});
  const std::string line = formatTrajectory(t, TrajectoryFormat::Icl);
  std::istringstream in(line);
  double frame, tx, ty, tz, qx, qy, qz, qw;
  in >> frame >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
  EXPECT_EQ(frame, 0);
  EXPECT_NEAR((Vec3(tx, ty, tz) - Vec3(1, 3, 2)).norm(), 0, 1e-12);
  const Quat q(qw, qx, qy, qz);
  EXPECT_NEAR((q * Vec3::UnitZ() - Vec3(0, 1, 0)).norm(), 0, 1e-9);   // forward = POV up
  EXPECT_NEAR((q * Vec3::UnitY() - Vec3(0, 0, -1)).norm(), 0, 1e-9);  // ICL camera up
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-9);                              // a -90 deg turn about x
  EXPECT_NEAR(qx, -std::sqrt(0.5), 1e-9);
}

TEST(IclFormat, FrameNumbersFollowTheFrameRate) {
  const std::string text = "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\r\n25 0 0 0 0 0 0 1\n";
  EXPECT_EQ(parseTrajectory(text, "x", TrajectoryFormat::Icl).poses[1].t_ns, 33333333);
  TrajectoryFormatOptions opt;
  opt.icl_fps = 25;
  EXPECT_EQ(parseTrajectory(text, "x", TrajectoryFormat::Icl, opt).poses[2].t_ns, 1000000000);
  Trajectory off;
  off.poses.push_back({10000000, Pose{}});  // 10 ms: between frames 0 and 1 at 30 fps
  const std::string msg = inputErrorOf([&] { formatTrajectory(off, TrajectoryFormat::Icl); });
  EXPECT_NE(msg.find("--fps"), std::string::npos) << msg;
  EXPECT_EQ(formatTrajectory(off, TrajectoryFormat::Icl, {100.0}).substr(0, 2), "1 ");
}

// scenenet.proto: up is [0,1,0]; camera_pose_and_intrinsics_example.py builds the world-to-camera
// rows z = normalize(lookat - camera), x = normalize(z x up), y = -normalize(x x z).
TEST(SceneNetFormat, MatchesSceneNetsOwnCameraConstruction) {
  const Vec3 cam(0.5, 1.6, -2.0), look(1.3, 1.1, -1.2);  // SceneNet y-up coordinates
  const std::string text =
      fmt::format("instance:1;03001627;chair;abc\ntime:0.25 pose:{},{},{} lookat:{},{},{}\n",
                  cam.x(), cam.y(), cam.z(), look.x(), look.y(), look.z());
  const Trajectory t = parseTrajectory(text, "render_info.log", TrajectoryFormat::SceneNet);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.poses[0].t_ns, 250000000);
  Mat3 rows;  // SceneNet's world-to-camera rotation, in SceneNet's world
  rows.row(2) = (look - cam).normalized();
  rows.row(0) = rows.row(2).cross(Vec3(0, 1, 0)).normalized();
  rows.row(1) = -rows.row(0).cross(rows.row(2)).normalized();
  Mat3 rx90;  // SceneNet world -> ours (y up -> z up)
  rx90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const Mat3 expected = rx90 * rows.transpose();
  const Pose& p = t.poses[0].T_world_camera;
  EXPECT_NEAR((p.rotation() - expected).norm(), 0, 1e-12);
  EXPECT_NEAR((p.t - rx90 * cam).norm(), 0, 1e-12);
  EXPECT_NEAR(p.t.z(), 1.6, 1e-12);  // SceneNet's height y is our z
}

TEST(SceneNetFormat, RefusesViewsLookingStraightUp) {
  Trajectory t;
  t.poses.push_back({0, Pose::lookAt(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3::UnitZ())});
  t.poses.push_back({1, Pose{Quat::Identity(), Vec3::Zero()}});  // OpenCV z = world z: up
  const std::string msg = inputErrorOf([&] { formatTrajectory(t, TrajectoryFormat::SceneNet); });
  EXPECT_NE(msg.find("pose 1"), std::string::npos) << msg;
  EXPECT_NE(inputErrorOf([] {
              parseTrajectory("time:0 pose:0,0,0 lookat:0,2,0\n", "v.log",
                              TrajectoryFormat::SceneNet);
            }).find("v.log: line 1"),
            std::string::npos);
}

TEST(SlamBenchFormat, RejectsWhatSlamBenchsRegexRejects) {
  const std::string good = "# comment\r\n1305031102.1753 1 2 3 0 0 0 1\r\n";
  EXPECT_EQ(parseTrajectory(good, "gt.txt", TrajectoryFormat::SlamBench).poses[0].t_ns,
            1305031102175300000LL);
  const char* bad[] = {"1305031102 1 2 3 0 0 0 1\n",     // no fraction
                       "1.5 1e-3 2 3 0 0 0 1\n",         // exponent
                       "1.5 +1 2 3 0 0 0 1\n",           // '+' sign
                       "1.1234567891 1 2 3 0 0 0 1\n"};  // > 9 decimals
  for (const char* text : bad) {
    const std::string msg = inputErrorOf(
        [&] { parseTrajectory(std::string("#\n") + text, "gt.txt", TrajectoryFormat::SlamBench); });
    EXPECT_NE(msg.find("gt.txt: line 2"), std::string::npos) << text << ": " << msg;
  }
  Trajectory neg;
  neg.poses.push_back({-5, Pose{}});
  EXPECT_NE(
      inputErrorOf([&] { formatTrajectory(neg, TrajectoryFormat::SlamBench); }).find("negative"),
      std::string::npos);
}

// Each reader names file and line for each kind of malformed input.
TEST(TrajectoryFormats, ErrorsNameFileAndLine) {
  struct Case {
    TrajectoryFormat f;
    std::string good;  // one valid line, with %T where the time goes
    std::string bad;   // malformed third line
    const char* what;
  };
  const std::string q = " 0 0 0 1";
  const Case cases[] = {
      {TrajectoryFormat::Euroc, "%T,1,2,3,1,0,0,0", "9,1,2,3,1,0,0", "8, 11 or 17"},
      {TrajectoryFormat::Euroc, "%T,1,2,3,1,0,0,0", "9,1,2,x,1,0,0,0", "column 4"},
      {TrajectoryFormat::Euroc, "%T,1,2,3,1,0,0,0", "9,1,2,3,1,1,0,0", "norm"},
      {TrajectoryFormat::Euroc, "%T,1,2,3,1,0,0,0", "1,1,2,3,1,0,0,0", "increase"},
      {TrajectoryFormat::Euroc, "%T,1,2,3,1,0,0,0", "9.5,1,2,3,1,0,0,0", "nanoseconds"},
      {TrajectoryFormat::Icl, "%T 1 2 3" + q, "9 1 2 3 0 0 1", "8 fields"},
      {TrajectoryFormat::Icl, "%T 1 2 3" + q, "9 1 2 3 0 0 nan 1", "column 7"},
      {TrajectoryFormat::Icl, "%T 1 2 3" + q, "-1 1 2 3" + q, "frame number"},
      {TrajectoryFormat::Icl, "%T 1 2 3" + q, "1 1 2 3" + q, "increase"},
      {TrajectoryFormat::SlamBench, "%T.0 1 2 3" + q, "9.0 1 2 3 0.5 0 0 1", "norm"},
      {TrajectoryFormat::Tum, "%T.0 1 2 3" + q, "9.0 1 2 3 0 0", "8 fields"},
      {TrajectoryFormat::SceneNet, "time:%T pose:0,0,0 lookat:1,0,0",
       "time:9 pose:0,0 lookat:1,0,0", "3 comma"},
      {TrajectoryFormat::SceneNet, "time:%T pose:0,0,0 lookat:1,0,0",
       "time:x pose:0,0,0 lookat:1,0,0", "time:"},
      {TrajectoryFormat::SceneNet, "time:%T pose:0,0,0 lookat:1,0,0",
       "time:9 pose:0,0,0 look:1,0,0", "lookat:"},
  };
  for (const Case& c : cases) {
    const size_t at = c.good.find("%T");
    const std::string l1 = c.good.substr(0, at) + "1" + c.good.substr(at + 2);
    const std::string l2 = c.good.substr(0, at) + "2" + c.good.substr(at + 2);
    const std::string msg = inputErrorOf(
        [&] { parseTrajectory(l1 + "\r\n" + l2 + "\n" + c.bad + "\n", "bad.file", c.f); });
    EXPECT_NE(msg.find("bad.file: line 3"), std::string::npos) << c.bad << ": " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << c.bad << ": " << msg;
  }
  for (TrajectoryFormat f : kAll) {
    const std::string msg = inputErrorOf([&] { parseTrajectory("# only a header\n", "e.txt", f); });
    EXPECT_NE(msg.find("e.txt"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no poses"), std::string::npos) << msg;
  }
  const std::string msg = inputErrorOf([] { detectTrajectoryFormat("w.dat", "1 2 3\n"); });
  EXPECT_NE(msg.find("w.dat: line 1"), std::string::npos) << msg;
}

// Random bytes and every truncation of valid files: a reader returns or throws InputError,
// nothing else (no crash, no other exception).
TEST(TrajectoryFormats, ParsersSurviveGarbage) {
  const Trajectory t = syntheticTrajectory();
  std::vector<std::string> inputs;
  for (TrajectoryFormat f : kAll) {
    const std::string text = formatTrajectory(t, f).substr(0, 400);
    for (size_t n = 0; n <= text.size(); ++n) inputs.push_back(text.substr(0, n));
  }
  std::mt19937 rng(11);
  const std::string alphabet = "0123456789.,-+eE:# \t\r\nxyzpostimelkan";
  for (int k = 0; k < 300; ++k) {
    std::string s(rng() % 200, ' ');
    for (char& c : s)
      c = k % 2 ? static_cast<char>(rng() % 256) : alphabet[rng() % alphabet.size()];
    inputs.push_back(s);
  }
  int parsed = 0;
  for (const std::string& s : inputs) {
    for (TrajectoryFormat f : kAll) {
      try {
        parseTrajectory(s, "fuzz", f);
        ++parsed;
      } catch (const InputError&) {
      }
    }
    try {
      detectTrajectoryFormat("fuzz", s);
    } catch (const InputError&) {
    }
  }
  EXPECT_GT(parsed, 0);  // truncations at line ends are valid files
}

TEST(OffsetTrajectory, RightCameraSitsAlongTheLeftCameraXAxis) {
  const Trajectory left = syntheticTrajectory();
  const Trajectory right = offsetTrajectory(left, Pose{Quat::Identity(), Vec3(0.12, 0, 0)});
  ASSERT_EQ(right.size(), left.size());
  for (size_t i = 0; i < left.size(); ++i) {
    const Pose &l = left.poses[i].T_world_camera, &r = right.poses[i].T_world_camera;
    EXPECT_EQ(right.poses[i].t_ns, left.poses[i].t_ns);
    EXPECT_NEAR((r.t - (l.t + 0.12 * l.rotation().col(0))).norm(), 0, 1e-12);
    EXPECT_NEAR(r.q.angularDistance(l.q), 0, 1e-12);
    // a point 2 m ahead of the left camera is 0.12 m to the left in the right camera's image
    const Vec3 p_r = r.inverse() * (l * Vec3(0, 0, 2));
    EXPECT_NEAR((p_r - Vec3(-0.12, 0, 2)).norm(), 0, 1e-12);
  }
}

}  // namespace
}  // namespace inet
