// TUM RGB-D writer: list files parsed with the rules of TUM's associate.py, comment lines as in
// the real fr1/xyz files, depth PNG = round(z * 5000), ground truth and the side files.
#include "dataset/tum_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "core/error.h"
#include "core/image_io.h"
#include "dataset_test_util.h"

namespace inet {
namespace {

using namespace inet::test;

const fs::path kTum =
    fs::path(INET_SHARED_DIR) / "data/formats/tum_rgbd/rgbd_dataset_freiburg1_xyz";

using TumList = std::map<double, std::vector<std::string>>;

/// associate.py's read_file_list: ',' and tab count as spaces, lines starting with '#' are
/// skipped, rows need at least 2 fields, key = float(first field).
TumList readFileList(const fs::path& p) {
  std::string data = readBytes(p);
  std::replace(data.begin(), data.end(), ',', ' ');
  std::replace(data.begin(), data.end(), '\t', ' ');
  TumList list;
  std::istringstream in(data);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<std::string> v;
    for (std::string f; fields >> f;) v.push_back(f);
    if (v.size() > 1) list[std::stod(v[0])] = std::vector<std::string>(v.begin() + 1, v.end());
  }
  return list;
}

/// associate.py's associate(): greedy matching by smallest time difference below max_difference.
std::vector<std::pair<double, double>> associate(const TumList& a, const TumList& b,
                                                 double max_diff) {
  std::vector<std::tuple<double, double, double>> candidates;
  for (const auto& [ta, va] : a)
    for (const auto& [tb, vb] : b)
      if (std::abs(ta - tb) < max_diff) candidates.emplace_back(std::abs(ta - tb), ta, tb);
  std::sort(candidates.begin(), candidates.end());
  std::set<double> used_a, used_b;
  std::vector<std::pair<double, double>> matches;
  for (const auto& [d, ta, tb] : candidates)
    if (!used_a.count(ta) && !used_b.count(tb)) {
      used_a.insert(ta);
      used_b.insert(tb);
      matches.emplace_back(ta, tb);
    }
  std::sort(matches.begin(), matches.end());
  return matches;
}

int commentLines(const fs::path& p) {
  int n = 0;
  for (const auto& l : readLines(p)) {
    if (l.empty() || l[0] != '#') break;
    ++n;
  }
  return n;
}

class TumWriterTest : public ::testing::Test {
 protected:
  void SetUp() override { writeSyntheticSequence(dir_, {"tum"}); }
  TempDir tmp_{"tum"};
  fs::path dir_ = tmp_ / "seq";
  Trajectory traj_ = syntheticTrajectory();
};

TEST_F(TumWriterTest, ListsHaveThreeCommentLinesLikeTheRealFiles) {
  for (const char* f : {"rgb.txt", "depth.txt", "groundtruth.txt", "accelerometer.txt"})
    EXPECT_EQ(commentLines(dir_ / f), 3) << f;
  EXPECT_EQ(readLines(dir_ / "rgb.txt")[1], "# file: 'seq'");
  if (!fs::exists(kTum))
    GTEST_SKIP() << "TUM samples not found at " << kTum << " (../shared absent)";
  for (const char* f : {"rgb.txt", "depth.txt", "groundtruth.txt"}) {
    auto ours = readLines(dir_ / f), real = readLines(kTum / f);
    EXPECT_EQ(ours[0], real[0]) << f;
    EXPECT_EQ(ours[2], real[2]) << f;
    EXPECT_EQ(ours[1].rfind("# file: '", 0), 0u);
  }
}

TEST_F(TumWriterTest, ListsParseWithAssociatePyRules) {
  TumList rgb = readFileList(dir_ / "rgb.txt");
  TumList depth = readFileList(dir_ / "depth.txt");
  TumList gt = readFileList(dir_ / "groundtruth.txt");
  ASSERT_EQ(rgb.size(), 3u);
  ASSERT_EQ(depth.size(), 3u);
  ASSERT_EQ(gt.size(), 3u);
  size_t k = 0;
  for (const auto& [t, fields] : rgb) {
    EXPECT_NEAR(t, traj_.poses[k].t_ns * 1e-9, 1e-6);
    ASSERT_EQ(fields.size(), 1u);
    EXPECT_EQ(fields[0], "rgb/" + tumStamp(traj_.poses[k].t_ns) + ".png");
    EXPECT_TRUE(fs::is_regular_file(dir_ / fields[0])) << fields[0];
    ++k;
  }
  for (const auto& [t, fields] : depth) EXPECT_TRUE(fs::is_regular_file(dir_ / fields[0]));
  for (const auto& [t, fields] : gt) EXPECT_EQ(fields.size(), 7u);
  auto m = associate(rgb, depth, 0.02);
  ASSERT_EQ(m.size(), 3u);
  for (const auto& [a, b] : m) EXPECT_EQ(a, b) << "identical stamps for one render";
  EXPECT_EQ(associate(rgb, gt, 0.02).size(), 3u);

  // associations.txt is what associate.py prints ("%f %s %f %s") for rgb.txt and depth.txt.
  auto lines = readLines(dir_ / "associations.txt");
  ASSERT_EQ(lines.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    double t = m[i].first;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%f %s %f %s", t, rgb[t][0].c_str(), m[i].second,
                  depth[m[i].second][0].c_str());
    EXPECT_EQ(lines[i], buf);
  }
}

TEST_F(TumWriterTest, DepthPngIsZTimes5000) {
  const CameraIntrinsics K = smallCamera();
  for (size_t k = 0; k < 3; ++k) {
    ImageU16 d = readPng16(dir_ / "depth" / (tumStamp(traj_.poses[k].t_ns) + ".png"));
    ASSERT_EQ(d.width, K.width);
    ASSERT_EQ(d.channels, 1);
    for (int y = 0; y < K.height; ++y)
      for (int x = 0; x < K.width; ++x)
        ASSERT_EQ(d.at(x, y), depthCode5000(x, y, static_cast<int>(k))) << x << "," << y;
    ImageU8 rgb = readPng8(dir_ / "rgb" / (tumStamp(traj_.poses[k].t_ns) + ".png"));
    EXPECT_EQ(rgb.channels, 3);
  }
}

TEST_F(TumWriterTest, GroundTruthIsTWorldCameraWithPositiveW) {
  auto lines = readLines(dir_ / "groundtruth.txt");
  ASSERT_EQ(lines.size(), 6u);
  for (size_t k = 0; k < 3; ++k) {
    std::istringstream in(lines[3 + k]);
    std::string t;
    double v[7];
    in >> t;
    for (double& x : v) in >> x;
    ASSERT_TRUE(in) << lines[3 + k];
    EXPECT_EQ(t, tumStamp(traj_.poses[k].t_ns));
    const Pose& T = traj_.poses[k].T_world_camera;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], T.t[i], 1e-9);
    Quat q(v[6], v[3], v[4], v[5]);  // file order qx qy qz qw
    EXPECT_NEAR(q.norm(), 1.0, 1e-8);
    EXPECT_GE(q.w(), 0.0);
    EXPECT_LT(q.angularDistance(T.q), 1e-8);
  }
}

TEST_F(TumWriterTest, SideFiles) {
  auto cam = readLines(dir_ / "camera.txt");
  ASSERT_EQ(cam.size(), 2u);
  EXPECT_EQ(cam[0].rfind("# fx fy cx cy k1 k2 p1 p2 k3", 0), 0u);
  EXPECT_EQ(cam[1], "20.0 21.5 11.5 7.5 0.0 0.0 0.0 0.0 0.0");
  EXPECT_EQ(readLines(dir_ / "accelerometer.txt").size(), 3u) << "header only";
  EXPECT_EQ(readLines(dir_ / "accelerometer.txt")[2], "# timestamp ax ay az");
}

TEST(TumWriter, StampsAndValidation) {
  EXPECT_EQ(tumStamp(1305031102175304000LL), "1305031102.175304");
  EXPECT_EQ(tumStamp(1500), "0.000002") << "half up";
  EXPECT_EQ(tumStamp(0), "0.000000");

  TempDir tmp("tumbad");
  Trajectory close = syntheticTrajectory();
  close.poses[1].t_ns = close.poses[0].t_ns + 400;  // same microsecond as pose 0
  try {
    SequenceWriter w(syntheticSpec(tmp / "seq"), close, {"asl", "tum"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pose 1"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(tmp / "seq"));
  // Without a depth pass there is nothing for depth.txt: refused, and the message says why.
  try {
    SequenceWriter w(syntheticSpec(tmp / "seq", static_cast<PassMask>(Pass::Rgb)),
                     syntheticTrajectory(), {"tum"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--passes"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(tmp / "seq"));
}

}  // namespace
}  // namespace inet
