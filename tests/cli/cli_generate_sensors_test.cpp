// `interiornet generate --passes all --stereo B`: every sensor of a sequence, read back the way a
// user's tools read them. The EuRoC part is read by a reader written here from EuRoC's
// documentation (Burri et al. 2016, "The EuRoC micro aerial vehicle datasets", and the files in
// ../shared/data/formats/euroc_asl): every sensor folder has a sensor.yaml that a strict YAML 1.2
// parser (yaml-cpp) loads, with sensor_type, T_BS (4x4, rigid) and the keys of its type; cameras
// list their images in data.csv ("#timestamp [ns],filename", file = <timestamp>.<ext>).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/atomic_file.h"
#include "core/image_io.h"
#include "sensors/depth_noise.h"
#include "sensors/event_io.h"
#include "sensors/flow_io.h"

namespace inet::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    out.push_back(l);
  }
  return out;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string f; std::getline(ss, f, sep);) out.push_back(f);
  return out;
}

/// A EuRoC sensor.yaml: the keys every sensor has, and those of its type.
struct SensorYaml {
  std::string type;
  double T[4][4];
  std::vector<double> intrinsics;
  int width = 0, height = 0;
};

SensorYaml readSensorYaml(const fs::path& p) {
  SCOPED_TRACE(p.string());
  SensorYaml s{};
  const YAML::Node y = YAML::LoadFile(p.string());  // throws on anything not YAML 1.2
  s.type = y["sensor_type"].as<std::string>();
  EXPECT_TRUE(s.type == "camera" || s.type == "imu" || s.type == "visual-inertial") << s.type;
  EXPECT_TRUE(y["comment"].IsScalar());
  const YAML::Node T = y["T_BS"];
  EXPECT_EQ(T["rows"].as<int>(), 4);
  EXPECT_EQ(T["cols"].as<int>(), 4);
  const auto data = T["data"].as<std::vector<double>>();
  EXPECT_EQ(data.size(), 16u);
  for (int i = 0; i < 16; ++i) s.T[i / 4][i % 4] = data.at(i);
  EXPECT_EQ(s.T[3][0], 0);
  EXPECT_EQ(s.T[3][3], 1);
  for (int i = 0; i < 3; ++i)  // rotation part orthonormal
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += s.T[k][i] * s.T[k][j];
      EXPECT_NEAR(dot, i == j ? 1 : 0, 1e-9);
    }
  if (s.type == "camera") {
    EXPECT_TRUE(y["rate_hz"].IsScalar());
    const auto res = y["resolution"].as<std::vector<int>>();
    EXPECT_EQ(res.size(), 2u);
    s.width = res.at(0);
    s.height = res.at(1);
    EXPECT_EQ(y["camera_model"].as<std::string>(), "pinhole");
    s.intrinsics = y["intrinsics"].as<std::vector<double>>();
    EXPECT_EQ(s.intrinsics.size(), 4u);
    EXPECT_EQ(y["distortion_model"].as<std::string>(), "radial-tangential");
    EXPECT_EQ(y["distortion_coefficients"].as<std::vector<double>>().size(), 4u);
  }
  if (s.type == "imu") {
    EXPECT_GT(y["rate_hz"].as<double>(), 0);
    for (const char* k : {"gyroscope_noise_density", "gyroscope_random_walk",
                          "accelerometer_noise_density", "accelerometer_random_walk"})
      EXPECT_GE(y[k].as<double>(), 0) << k;
  }
  return s;
}

/// A camera's data.csv: (timestamp, file) rows, every file present in data/.
std::vector<std::pair<int64_t, std::string>> readCameraCsv(const fs::path& folder) {
  SCOPED_TRACE(folder.string());
  const auto ls = lines(folder / "data.csv");
  EXPECT_EQ(ls.at(0), "#timestamp [ns],filename");
  std::vector<std::pair<int64_t, std::string>> rows;
  for (size_t i = 1; i < ls.size(); ++i) {
    const auto f = split(ls[i], ',');
    EXPECT_EQ(f.size(), 2u) << ls[i];
    const int64_t t = std::stoll(f.at(0));
    // <timestamp>.<ext>; label0 adds a suffix (<t>_nyu.png), which readers take from the csv
    EXPECT_EQ(f.at(1).substr(0, f.at(0).size()), f.at(0)) << "file name starts with the time";
    EXPECT_TRUE(fs::is_regular_file(folder / "data" / f.at(1))) << f.at(1);
    if (!rows.empty()) {
      EXPECT_GT(t, rows.back().first);
    }
    rows.emplace_back(t, f.at(1));
  }
  return rows;
}

class GenerateAllSensors : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("gen_sensors");
    // 64 x 48 at fx 48 (67 degrees), 5 frames of the built-in orbit, stereo 10 cm; the event
    // camera 32 x 24 over the spline's range
    result_ = new RunResult(runInterinet(
        "generate --layout builtin:room --frames 5 --width 64 --height 48 --fx 48 --fy 48 "
        "--spp 2 --passes all "
        "--stereo 0.1 --event-width 32 --event-height 24 --event-spp 2 --no-progress --out " +
        (*dir_ / "out").string()));
    seq_ = (*dir_ / "out" / "default_room" / "seq_000");
  }
  static void TearDownTestSuite() {
    delete result_;
    delete dir_;
  }
  static TempDir* dir_;
  static RunResult* result_;
  static fs::path seq_;
};
TempDir* GenerateAllSensors::dir_ = nullptr;
RunResult* GenerateAllSensors::result_ = nullptr;
fs::path GenerateAllSensors::seq_;

TEST_F(GenerateAllSensors, EurocPartOpensInAReaderFollowingItsDocumentation) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  YAML::LoadFile((seq_ / "body.yaml").string());
  std::set<std::string> sensors;
  for (const auto& e : fs::directory_iterator(seq_))
    if (fs::is_regular_file(e.path() / "sensor.yaml")) sensors.insert(e.path().filename());
  for (const char* s : {"cam0", "cam1", "depth0", "depth1", "depth0_noisy", "depth1_noisy",
                        "normal0", "albedo0", "shading0", "label0", "flow0", "flow1", "imu0",
                        "events0", "state_groundtruth_estimate0"})
    EXPECT_TRUE(sensors.count(s)) << s << " has no sensor.yaml";
  for (const std::string& s : sensors) {
    const SensorYaml y = readSensorYaml(seq_ / s / "sensor.yaml");
    if (y.type != "camera" || s == "events0") continue;
    const auto rows = readCameraCsv(seq_ / s);
    EXPECT_EQ(rows.size(), s.rfind("flow", 0) == 0 ? 4u : 5u) << s;
    EXPECT_EQ(y.width, 64) << s;
    EXPECT_EQ(y.height, 48) << s;
    EXPECT_EQ(y.intrinsics.at(0), 48.0) << s;
    // the right camera's folders sit 10 cm along x of the body (= cam0)
    const bool right = s.find('1') != std::string::npos;
    EXPECT_DOUBLE_EQ(y.T[0][3], right ? 0.1 : 0.0) << s;
    EXPECT_EQ(y.T[1][3], 0.0) << s;
  }
  // the event camera: its own size, at cam0
  const SensorYaml ev = readSensorYaml(seq_ / "events0/sensor.yaml");
  EXPECT_EQ(ev.width, 32);
  EXPECT_EQ(ev.height, 24);
  EXPECT_DOUBLE_EQ(ev.intrinsics.at(0), 24.0) << "cam0's field of view: 48 * 32 / 64";
  // IMU: EuRoC's header, 7 columns, 1.25 ms apart (800 Hz)
  const auto imu = lines(seq_ / "imu0/data.csv");
  EXPECT_EQ(imu.at(0),
            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  ASSERT_GT(imu.size(), 50u);
  for (size_t i = 2; i < imu.size(); ++i) {
    const auto a = split(imu[i - 1], ','), b = split(imu[i], ',');
    ASSERT_EQ(b.size(), 7u);
    EXPECT_EQ(std::stoll(b[0]) - std::stoll(a[0]), 1'250'000);
  }
  // ground truth: 17 columns, unit quaternions
  const auto gt = lines(seq_ / "state_groundtruth_estimate0/data.csv");
  ASSERT_EQ(gt.size(), 6u);
  for (size_t i = 1; i < gt.size(); ++i) {
    const auto f = split(gt[i], ',');
    ASSERT_EQ(f.size(), 17u);
    double n2 = 0;
    for (int c = 4; c <= 7; ++c) n2 += std::stod(f[c]) * std::stod(f[c]);
    EXPECT_NEAR(std::sqrt(n2), 1.0, 1e-6);
  }
}

TEST_F(GenerateAllSensors, StereoDepthAgreesWithTheBaseline) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  // a cam0 pixel at depth z is seen by cam1 (10 cm right) fx b / z pixels further left, at the
  // same z-depth (same orientation)
  const auto rows = readCameraCsv(seq_ / "depth0");
  const ImageU16 d0 = readPng16(seq_ / "depth0/data" / rows[2].second);
  const ImageU16 d1 = readPng16(seq_ / "depth1/data" / rows[2].second);
  std::vector<double> err;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const double z = d0.at(x, y) / 1000.0;
      if (z <= 0) continue;
      const double u1 = x + 0.5 - 48 * 0.1 / z;
      const int x1 = static_cast<int>(std::floor(u1));
      if (x1 < 0 || x1 >= 64 || std::abs(u1 - (x1 + 0.5)) > 0.2) continue;  // near a centre
      err.push_back(std::abs(d1.at(x1, y) / 1000.0 - z) / z);
    }
  ASSERT_GT(err.size(), 300u);
  std::sort(err.begin(), err.end());
  EXPECT_LT(err[err.size() / 2], 0.01) << "median relative depth difference";
}

TEST_F(GenerateAllSensors, FlowNoisyDepthBoxesAndEventsAreWritten) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  const auto rows = readCameraCsv(seq_ / "flow0");
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& [t, flo] : rows) {
    const FlowField a = readFlo(seq_ / "flow0/data" / flo);
    const std::string stem = flo.substr(0, flo.find('.'));
    const FlowField b = readKittiFlowPng(seq_ / "flow0/data" / (stem + ".png"));
    ASSERT_EQ(a.width(), 64);
    EXPECT_EQ(a.valid.data, b.valid.data);
    int valid = 0;
    for (size_t i = 0; i < a.flow.data.size(); ++i)
      EXPECT_NEAR(a.flow.data[i], b.flow.data[i], 1.0 / 128 + 1e-6);
    for (uint8_t v : a.valid.data) valid += v;
    EXPECT_EQ(valid, 64 * 48) << "a closed room: every pixel has flow";
    EXPECT_TRUE(fs::is_regular_file(seq_ / "flow0/data" / (stem + "_occ.png")));
  }
  // backward flow (flow0_bwd/, every frame but the first) undoes the forward flow: from x in
  // frame k to x' = x + f in frame k + 1, the backward flow at x' points back by about -f
  const auto brows = readCameraCsv(seq_ / "flow0_bwd");
  ASSERT_EQ(brows.size(), 4u);
  EXPECT_EQ(brows[0].first, readCameraCsv(seq_ / "flow0")[1].first);
  const FlowField fwd = readFlo(seq_ / "flow0/data" / rows[1].second);
  const FlowField bwd = readFlo(seq_ / "flow0_bwd/data" / brows[1].second);
  std::vector<double> loop;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      if (!fwd.valid.at(x, y)) continue;
      const double u = x + 0.5 + fwd.flow.at(x, y, 0), v = y + 0.5 + fwd.flow.at(x, y, 1);
      const int xi = static_cast<int>(std::floor(u)), yi = static_cast<int>(std::floor(v));
      if (xi < 0 || yi < 0 || xi >= 64 || yi >= 48 || !bwd.valid.at(xi, yi)) continue;
      loop.push_back(std::hypot(fwd.flow.at(x, y, 0) + bwd.flow.at(xi, yi, 0),
                                fwd.flow.at(x, y, 1) + bwd.flow.at(xi, yi, 1)));
    }
  ASSERT_GT(loop.size(), 2000u);
  std::sort(loop.begin(), loop.end());
  EXPECT_LT(loop[loop.size() / 2], 0.1) << "median forward-backward loop error, px";
  // noisy depth at this focal length (48 px) is dominated by the Kinect's 1/8 px disparity
  // steps, z = f b / (k / 8): every return sits on such a level (to the PNG's 1 mm), within a few
  // levels of the true depth
  const auto drows = readCameraCsv(seq_ / "depth0_noisy");
  const ImageU16 truth = readPng16(seq_ / "depth0/data" / drows[0].second);
  const ImageU16 noisy = readPng16(seq_ / "depth0_noisy/data" / drows[0].second);
  const KinectNoiseOptions model;
  const double fb = 48 * model.baseline_m;
  size_t returns = 0, differ = 0;
  for (size_t i = 0; i < truth.data.size(); ++i) {
    if (noisy.data[i] == 0 || truth.data[i] == 0) continue;
    ++returns;
    const double z = truth.data[i] / 1000.0, zn = noisy.data[i] / 1000.0;
    const double level = fb / zn / model.disparity_step_px;  // disparity in steps
    const double mm_in_steps = fb / (zn * zn) * 0.0005 / model.disparity_step_px;
    EXPECT_LT(std::abs(level - std::round(level)), mm_in_steps + 1e-3) << "pixel " << i;
    const double spacing = zn * zn * model.disparity_step_px / fb;  // depth between levels
    EXPECT_LT(std::abs(zn - z), 3 * spacing) << "pixel " << i;
    differ += noisy.data[i] != truth.data[i];
  }
  EXPECT_GT(returns, truth.data.size() / 2);
  EXPECT_GT(differ, returns / 2);
  // boxes.json: one entry per frame, visible objects with pixel counts
  const auto boxes = nlohmann::json::parse(readTextFile(seq_ / "boxes.json"));
  EXPECT_EQ(boxes["frames"].size(), 5u);
  EXPECT_GT(boxes["objects"].size(), 3u);
  int64_t pixels = 0;
  for (const auto& v : boxes["frames"][0]["visible"]) pixels += v["pixels"].get<int64_t>();
  EXPECT_EQ(pixels, 64 * 48);
  // events: text and HDF5 hold the same events, in time order
  const EventFile txt = readEventsTxt(seq_ / "events0/events.txt");
  const EventFile h5 = readEventsH5(seq_ / "events0/events.h5");
  ASSERT_EQ(txt.events.size(), h5.events.size());
  EXPECT_GT(txt.events.size(), 0u);
  EXPECT_EQ(h5.width, 32);
  for (size_t i = 0; i < txt.events.size(); ++i) {
    if (i > 0) {
      EXPECT_LE(txt.events[i - 1].t_ns, txt.events[i].t_ns);
    }
    EXPECT_EQ(txt.events[i].x, h5.events[i].x);
    EXPECT_EQ(txt.events[i].p, h5.events[i].p);
    EXPECT_LE(std::abs(txt.events[i].t_ns - h5.events[i].t_ns), 1000) << "h5 holds microseconds";
  }
  const auto frames = lines(seq_ / "events0/frames/data.csv");
  EXPECT_GT(frames.size(), 3u);
  // meta.json records the stereo rig
  const auto meta = nlohmann::json::parse(readTextFile(seq_ / "meta.json"));
  EXPECT_EQ(meta["stereo"]["baseline_m"], 0.1);
}

TEST_F(GenerateAllSensors, EventsCommandAloneOnTheSequencesTrajectory) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  // the TUM ground truth of the generated sequence as input; knots at its poses
  const fs::path out = *dir_ / "events_alone";
  const std::string cmd = "events --trajectory " + (seq_ / "groundtruth.txt").string() +
                          " --knot-spacing 0.04 --event-width 32 --event-height 24 --event-spp 2 "
                          "--no-progress --out " + out.string();
  const RunResult r = runInterinet(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const EventFile ev = readEventsTxt(out / "events0/events.txt");
  EXPECT_GT(ev.events.size(), 0u);
  const std::string yaml = readTextFile(out / "events0/sensor.yaml");
  EXPECT_NE(yaml.find("resolution: [32, 24]"), std::string::npos);
  // a finished folder is not redone: the rerun leaves every byte
  const auto before = readTree(out);
  ASSERT_EQ(runInterinet(cmd).exit_code, 0);
  EXPECT_EQ(readTree(out), before);
  // bad input: one line naming the flag, nothing written
  const RunResult bad = runInterinet("events --trajectory " + (seq_ / "groundtruth.txt").string() +
                                     " --hfov 200 --out " + (*dir_ / "bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--hfov"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(*dir_ / "bad"));
}

TEST(GenerateSensorErrors, ImpossibleCombinationsNameTheFlag) {
  TempDir dir("gen_sensor_err");
  for (auto [args, flag] : std::vector<std::pair<std::string, std::string>>{
           {"--passes depth_noisy --lens fisheye --width 32", "--passes"},
           {"--passes flow --readout-ms 5", "--passes"},
           {"--passes events --lens panorama --width 64", "--passes"},
           {"--passes rgb,wind", "--passes"},
           {"--stereo -1", "--stereo"},
           {"--passes rgb,events --contrast 0", "--contrast"},
           {"--passes all --contrast-neg 20", "--contrast-neg"},
           {"--passes all --refractory-ms -1", "--refractory-ms"},
           {"--passes all --leak-rate-hz -2", "--leak-rate-hz"}}) {
    const RunResult r =
        runInterinet("generate --layout builtin:room --frames 2 --no-progress " + args +
                     " --out " + (dir / "o").string());
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(flag), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "o")) << args << ": nothing written";
  }
}

}  // namespace
}  // namespace inet::test
