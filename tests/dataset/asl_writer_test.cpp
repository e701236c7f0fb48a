// ASL/EuRoC writer: headers and yaml structure against the real EuRoC sample files, the 17-column
// ground truth, and the pixel encodings read back from disk.
#include "dataset/asl_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "dataset/image_encode.h"
#include "core/image_io.h"
#include "dataset/tum_writer.h"
#include "dataset_test_util.h"

namespace inet {
namespace {

using namespace inet::test;

const fs::path kEuroc = fs::path(INET_SHARED_DIR) / "data/formats/euroc_asl/mav0";

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t begin = 0;
  for (size_t end; (end = s.find(sep, begin)) != std::string::npos; begin = end + 1)
    out.push_back(s.substr(begin, end - begin));
  out.push_back(s.substr(begin));
  return out;
}

/// Top-level yaml keys in file order ("sensor_type", "comment", "T_BS", ...).
std::vector<std::string> yamlKeys(const fs::path& p) {
  std::vector<std::string> keys;
  std::regex key(R"(^([A-Za-z_][A-Za-z0-9_]*):.*)");
  std::smatch m;
  for (const auto& line : readLines(p))
    if (std::regex_match(line, m, key)) keys.push_back(m[1]);
  return keys;
}

/// The "T_BS:" block: that line and the indented lines after it.
std::string tbsBlock(const fs::path& p) {
  std::string block;
  bool in = false;
  for (const auto& line : readLines(p)) {
    if (line.rfind("T_BS:", 0) == 0)
      in = true;
    else if (in && (line.empty() || line[0] != ' '))
      break;
    if (in) block += line + "\n";
  }
  return block;
}

class AslWriterTest : public ::testing::Test {
 protected:
  void SetUp() override { writeSyntheticSequence(dir_, {"asl"}); }
  TempDir tmp_{"asl"};
  fs::path dir_ = tmp_ / "seq";
  Trajectory traj_ = syntheticTrajectory();
};

TEST_F(AslWriterTest, HeadersAreByteEqualToRealEurocFiles) {
  if (!fs::exists(kEuroc))
    GTEST_SKIP() << "EuRoC samples not found at " << kEuroc << " (../shared absent)";
  EXPECT_EQ(readLines(dir_ / "cam0/data.csv")[0], readLines(kEuroc / "cam0/data.csv")[0]);
  EXPECT_EQ(readLines(dir_ / "state_groundtruth_estimate0/data.csv")[0],
            readLines(kEuroc / "state_groundtruth_estimate0/data.csv")[0]);
  EXPECT_EQ(readLines(kEuroc / "cam0/data.csv")[0], kEurocCameraCsvHeader);
  EXPECT_EQ(readLines(kEuroc / "state_groundtruth_estimate0/data.csv")[0],
            kEurocGroundTruthCsvHeader);
  for (const char* sensor : {"depth0", "normal0", "albedo0", "label0"})
    EXPECT_EQ(readLines(dir_ / sensor / "data.csv")[0], kEurocCameraCsvHeader) << sensor;
}

TEST_F(AslWriterTest, SensorYamlHasTheKeysAndLayoutOfTheRealFiles) {
  if (!fs::exists(kEuroc))
    GTEST_SKIP() << "EuRoC samples not found at " << kEuroc << " (../shared absent)";
  for (const char* sensor : {"cam0", "depth0", "normal0", "albedo0", "label0"}) {
    EXPECT_EQ(yamlKeys(dir_ / sensor / "sensor.yaml"), yamlKeys(kEuroc / "cam0/sensor.yaml"))
        << sensor;
    EXPECT_EQ(readLines(dir_ / sensor / "sensor.yaml")[0], "# General sensor definitions.");
  }
  const fs::path gt = "state_groundtruth_estimate0/sensor.yaml";
  EXPECT_EQ(yamlKeys(dir_ / gt), yamlKeys(kEuroc / gt));
  EXPECT_EQ(tbsBlock(dir_ / gt), tbsBlock(kEuroc / gt)) << "identity T_BS written as EuRoC does";
  EXPECT_EQ(yamlKeys(dir_ / "body.yaml"), yamlKeys(kEuroc / "body.yaml"));
  for (const auto& [name, bytes] : readTree(dir_)) {
    if (name.ends_with(".yaml")) {
      EXPECT_NE(bytes.rfind("%YAML", 0), 0u) << name;
    }
  }
}

TEST_F(AslWriterTest, CameraYamlStatesOpenCvIntrinsics) {
  auto lines = readLines(dir_ / "cam0/sensor.yaml");
  auto has = [&](const std::string& l) {
    return std::find(lines.begin(), lines.end(), l) != lines.end();
  };
  EXPECT_TRUE(has("sensor_type: camera"));
  EXPECT_TRUE(has("rate_hz: 25"));  // median interval 40.000123 ms -> 25 Hz nominal
  EXPECT_TRUE(has("resolution: [24, 16]"));
  EXPECT_TRUE(has("camera_model: pinhole"));
  EXPECT_TRUE(has("distortion_model: radial-tangential"));
  EXPECT_TRUE(has("distortion_coefficients: [0.0, 0.0, 0.0, 0.0]"));
  bool found = false;
  for (const auto& l : lines)
    if (l.rfind("intrinsics: [20.0, 21.5, 11.5, 7.5]", 0) == 0) found = true;
  EXPECT_TRUE(found) << "fx, fy, cx - 0.5, cy - 0.5";
}

TEST_F(AslWriterTest, CameraCsvRowsNameExistingFiles) {
  for (const char* sensor : {"cam0", "depth0", "normal0", "albedo0", "label0"}) {
    auto lines = readLines(dir_ / sensor / "data.csv");
    ASSERT_EQ(lines.size(), 4u) << sensor;
    for (size_t k = 0; k < 3; ++k) {
      auto f = split(lines[k + 1], ',');
      ASSERT_EQ(f.size(), 2u);
      EXPECT_EQ(f[0].size(), 19u);
      EXPECT_EQ(std::stoll(f[0]), traj_.poses[k].t_ns);
      EXPECT_EQ(f[1].rfind(f[0], 0), 0u) << "file name starts with the timestamp";
      EXPECT_TRUE(fs::is_regular_file(dir_ / sensor / "data" / f[1])) << f[1];
    }
  }
  EXPECT_EQ(readLines(dir_ / "cam0/data.csv")[1], "1403715273262142976,1403715273262142976.png");
  EXPECT_EQ(aslStamp(42), "0000000000000000042");
}

TEST_F(AslWriterTest, GroundTruthRowsHave17ColumnsAndUnitQuaternions) {
  auto lines = readLines(dir_ / "state_groundtruth_estimate0/data.csv");
  ASSERT_EQ(lines.size(), 4u);
  for (size_t k = 0; k < 3; ++k) {
    auto f = split(lines[k + 1], ',');
    ASSERT_EQ(f.size(), 17u) << lines[k + 1];
    EXPECT_EQ(lines[k + 1].find(' '), std::string::npos) << "no spaces in rows";
    std::vector<double> v;
    for (size_t i = 1; i < f.size(); ++i) v.push_back(std::strtod(f[i].c_str(), nullptr));
    EXPECT_EQ(std::stoll(f[0]), traj_.poses[k].t_ns);
    const Pose& T = traj_.poses[k].T_world_camera;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], T.t[i], 1e-9);
    Quat q(v[3], v[4], v[5], v[6]);  // w first
    EXPECT_NEAR(q.norm(), 1.0, 1e-9);
    EXPECT_GE(q.w(), 0.0);
    EXPECT_LT(q.angularDistance(T.q), 1e-8) << "same rotation (sign may differ)";
    // velocity: central difference of the positions, computed here from the poses
    size_t a = k == 0 ? 0 : k - 1, b = k == 2 ? 2 : k + 1;
    Vec3 vel = (traj_.poses[b].T_world_camera.t - traj_.poses[a].T_world_camera.t) /
               ((traj_.poses[b].t_ns - traj_.poses[a].t_ns) * 1e-9);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[7 + i], vel[i], 1e-8);
    for (int i = 10; i < 16; ++i) EXPECT_EQ(v[i], 0.0);
  }
}

TEST_F(AslWriterTest, ImagesDecodeToTheEncodedPasses) {
  const CameraIntrinsics K = smallCamera();
  for (size_t k = 0; k < 3; ++k) {
    const Frame f = syntheticFrame(K, static_cast<int>(k));
    const std::string t = aslStamp(traj_.poses[k].t_ns);
    ImageU16 mm = readPng16(dir_ / "depth0/data" / (t + ".png"));
    ASSERT_EQ(mm.channels, 1);
    for (int y = 0; y < K.height; ++y)
      for (int x = 0; x < K.width; ++x) {
        int n = depthCode5000(x, y, static_cast<int>(k));           // depth = n / 5000 m = n / 5 mm
        EXPECT_EQ(mm.at(x, y), (2 * n + 5) / 10) << x << "," << y;  // n/5 has no .5 case
      }
    EXPECT_EQ(readExr(dir_ / "depth0/data" / (t + ".exr"), {"Z"}), f.depth_ray);
    EXPECT_EQ(readPng8(dir_ / "label0/data" / (t + "_nyu.png")), f.label);
    EXPECT_EQ(readPng16(dir_ / "label0/data" / (t + "_instance.png")), f.instance);
    ImageU8 rgb = readPng8(dir_ / "cam0/data" / (t + ".png"));
    ASSERT_EQ(rgb.channels, 3);
    for (size_t i = 0; i < rgb.data.size(); ++i)
      EXPECT_EQ(rgb.data[i], linearToSrgb8(f.rgb.data[i]));
    EXPECT_EQ(readPng8(dir_ / "albedo0/data" / (t + ".png")), encodeSrgb8(f.albedo));
    ImageF n = decodeNormal16(readPng16(dir_ / "normal0/data" / (t + ".png")));
    for (size_t i = 0; i < n.data.size(); ++i)
      EXPECT_NEAR(n.data[i], f.normal.data[i], 1.0 / 65535 + 1e-7);
    EXPECT_EQ(n.at(0, 0, 0), 0.0f);
  }
}

// ---- lenses other than the pinhole ----------------------------------------------------------

constexpr PassMask kRayDepthPasses = kRenderPasses & ~static_cast<PassMask>(Pass::DepthZ);

/// Writes the synthetic sequence through `lens` (its K is the image) with the given formats.
void writeWithLens(const fs::path& dir, const LensModel& lens, PassMask passes,
                   const std::vector<std::string>& formats = {"asl", "tum"}) {
  SequenceSpec spec = syntheticSpec(dir, passes);
  spec.intrinsics = lens.K;
  spec.lens = lens;
  Trajectory traj = syntheticTrajectory();
  SequenceWriter w(spec, traj, formats);
  for (size_t k = 0; k < w.frameCount(); ++k)
    w.writeFrame(k, syntheticFrame(lens.K, static_cast<int>(k)));
  w.finish();
}

bool hasLine(const fs::path& p, const std::string& line) {
  auto l = readLines(p);
  return std::find(l.begin(), l.end(), line) != l.end();
}

TEST(AslWriterLens, FisheyeIsKalibrEquidistantAndDepthPngHoldsRayDistance) {
  TempDir tmp("asl_fisheye");
  const LensModel lens = LensModel::fisheye(20, 200.0);
  writeWithLens(tmp / "seq", lens, kRayDepthPasses);
  for (const char* sensor : {"cam0", "depth0", "normal0", "albedo0", "shading0", "label0"}) {
    const fs::path yaml = tmp / "seq" / sensor / "sensor.yaml";
    EXPECT_TRUE(hasLine(yaml, "camera_model: pinhole")) << sensor;
    EXPECT_TRUE(hasLine(yaml, "distortion_model: equidistant")) << sensor;
    EXPECT_TRUE(hasLine(yaml, "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]")) << sensor;
    EXPECT_NE(readBytes(yaml).find("field of view 200.0 deg"), std::string::npos) << sensor;
    // f = 20 px / (200 deg in rad); centre 10 - 0.5
    EXPECT_TRUE(hasLine(yaml, fmt::format("intrinsics: [{}, {}, 9.5, 9.5] #fu, fv, cu, cv (OpenCV "
                                          "convention, pixel centres at integers)",
                                          formatFloat(lens.K.fx), formatFloat(lens.K.fy))))
        << sensor;
    if (fs::exists(yaml)) {
      EXPECT_EQ(yamlKeys(yaml),
                (std::vector<std::string>{"sensor_type", "comment", "T_BS", "rate_hz", "resolution",
                                          "camera_model", "intrinsics", "distortion_model",
                                          "distortion_coefficients"}))
          << sensor;
    }
  }
  Trajectory traj = syntheticTrajectory();
  for (size_t k = 0; k < 3; ++k) {
    const Frame f = syntheticFrame(lens.K, static_cast<int>(k));
    const std::string t = aslStamp(traj.poses[k].t_ns);
    EXPECT_EQ(readPng16(tmp / "seq/depth0/data" / (t + ".png")),
              encodeDepth16(f.depth_ray, kDepthScaleMm))
        << "the ray distance, not z";
    EXPECT_EQ(readPng16(tmp / "seq/depth" / (tumStamp(traj.poses[k].t_ns) + ".png")),
              encodeDepth16(f.depth_ray, kDepthScaleTum));
  }
  auto meta = nlohmann::json::parse(readBytes(tmp / "seq/meta.json"));
  EXPECT_EQ(meta["lens"]["type"], "fisheye");
  EXPECT_EQ(meta["lens"]["fov_deg"], 200.0);
  EXPECT_EQ(meta["camera"]["distortion_model"], "equidistant");
  EXPECT_EQ(readLines(tmp / "seq/camera.txt")[1],
            fmt::format("{0} {0} 9.5 9.5 0.0 0.0 0.0 0.0", formatFloat(lens.K.fx)));
}

TEST(AslWriterLens, PanoramaIsEquirectangularWithoutKalibrFields) {
  TempDir tmp("asl_pano");
  writeWithLens(tmp / "seq", LensModel::panorama(32, 16), kRayDepthPasses);
  const fs::path yaml = tmp / "seq/cam0/sensor.yaml";
  EXPECT_TRUE(hasLine(yaml, "camera_model: equirectangular"));
  EXPECT_TRUE(hasLine(yaml, "resolution: [32, 16]"));
  EXPECT_EQ(yamlKeys(yaml), (std::vector<std::string>{"sensor_type", "comment", "T_BS", "rate_hz",
                                                      "resolution", "camera_model"}));
  EXPECT_NE(readBytes(yaml).find("NOT a Kalibr camera model"), std::string::npos);
  EXPECT_NE(readBytes(yaml).find("longitude = (i - 15.5) / "), std::string::npos);
  auto meta = nlohmann::json::parse(readBytes(tmp / "seq/meta.json"));
  EXPECT_EQ(meta["lens"]["fov_deg"], nlohmann::json({360.0, 180.0}));
  EXPECT_EQ(meta["camera"]["distortion_model"], "none");
  EXPECT_EQ(readLines(tmp / "seq/camera.txt")[0].rfind("# fu fv cu cv (NOT a pinhole", 0), 0u);
}

TEST(AslWriterLens, ThinLensStatesApertureAndFocusBesideThePinhole) {
  TempDir tmp("asl_thin");
  writeWithLens(tmp / "seq", LensModel::thinLens(smallCamera(), 0.004, 1.25), kRenderPasses);
  const fs::path yaml = tmp / "seq/cam0/sensor.yaml";
  EXPECT_TRUE(hasLine(yaml, "camera_model: pinhole"));
  EXPECT_TRUE(hasLine(yaml, "distortion_model: radial-tangential"));
  EXPECT_NE(readBytes(yaml).find("aperture radius 0.004 m, focused on the plane z = 1.25 m"),
            std::string::npos);
  auto meta = nlohmann::json::parse(readBytes(tmp / "seq/meta.json"));
  EXPECT_EQ(meta["lens"]["type"], "thin_lens");
  EXPECT_EQ(meta["lens"]["aperture_radius_m"], 0.004);
  EXPECT_EQ(meta["lens"]["focus_distance_m"], 1.25);
}

TEST(AslWriterLens, ZDepthPassIsRefusedForFisheyeAndPanorama) {
  for (const LensModel& lens : {LensModel::fisheye(16), LensModel::panorama(32, 16)}) {
    TempDir tmp("asl_nodepth");
    SequenceSpec spec = syntheticSpec(tmp / "seq", kRenderPasses);
    spec.intrinsics = lens.K;
    spec.lens = lens;
    try {
      SequenceWriter w(spec, syntheticTrajectory(), {"asl"});
      ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "--passes");
      EXPECT_NE(std::string(e.what()).find("ray_depth"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(tmp / "seq"));
  }
}

}  // namespace
}  // namespace inet
