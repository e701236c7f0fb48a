// End-to-end `interiornet generate`: every pass on disk, same bytes for 1 and 2 threads, a run
// killed mid-sequence resumes to the same bytes, and memory does not grow with sequence length.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/image_io.h"
#include "render/lens.h"
#include "sensors/flow_io.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

const std::string kSmall =
    "generate --layout builtin:room --width 160 --height 120 --fx 150 --fy 150 --no-progress ";

fs::path seqDir(const fs::path& out) {
  return out / "default_room" / "seq_000";
}

size_t filesIn(const fs::path& dir, const std::string& suffix) {
  if (!fs::exists(dir)) return 0;
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::string s = e.path().filename().string();
    if (s.size() >= suffix.size() &&
        s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0)
      ++n;
  }
  return n;
}

TEST(Generate, WritesEveryPassInAslAndTumLayouts) {
  TempDir dir("gen_all");
  RunResult r = runInterinet(kSmall + "--frames 4 --spp 2 --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::path s = seqDir(dir / "out");
  EXPECT_NE(r.out.find(s.string()), std::string::npos)
      << "should say where the frames are: " << r.out;
  EXPECT_EQ(filesIn(s / "cam0/data", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "depth0/data", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "depth0/data", ".exr"), 4u);
  EXPECT_EQ(filesIn(s / "normal0/data", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "albedo0/data", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "shading0/data", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "label0/data", "_nyu.png"), 4u);
  EXPECT_EQ(filesIn(s / "label0/data", "_instance.png"), 4u);
  EXPECT_EQ(filesIn(s / "rgb", ".png"), 4u);
  EXPECT_EQ(filesIn(s / "depth", ".png"), 4u);
  for (const char* f : {"meta.json", "cam0/data.csv", "state_groundtruth_estimate0/data.csv",
                        "rgb.txt", "depth.txt", "groundtruth.txt", "associations.txt"})
    EXPECT_TRUE(fs::exists(s / f)) << f;
  EXPECT_EQ(countFiles(s) - readTree(s).size(), 0u);
  for (const auto& [name, bytes] : readTree(s))
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;

  // the TUM depth (x5000) and the ASL depth (mm) describe the same z-depth; the ray depth is
  // never shorter; the label image holds several NYU40 classes
  std::set<std::string> asl_png, tum_png;
  for (const auto& e : fs::directory_iterator(s / "depth0/data"))
    if (e.path().extension() == ".png") asl_png.insert(e.path().string());
  for (const auto& e : fs::directory_iterator(s / "depth")) tum_png.insert(e.path().string());
  ImageU16 mm = readPng16(*asl_png.begin());
  ImageU16 tum = readPng16(*tum_png.begin());
  ImageF ray = readExr(fs::path(*asl_png.begin()).replace_extension(".exr"), {"Z"});
  ASSERT_EQ(mm.width, 160);
  int valid = 0;
  for (size_t i = 0; i < mm.pixelCount(); ++i) {
    if (mm.data[i] == 0) continue;
    ++valid;
    EXPECT_NEAR(tum.data[i] / 5000.0, mm.data[i] / 1000.0, 0.0006);
    EXPECT_GE(ray.data[i] + 0.0006, mm.data[i] / 1000.0);
  }
  EXPECT_EQ(valid, 160 * 120) << "the room is closed: every pixel has depth";
  std::set<int> classes;
  for (const auto& e : fs::directory_iterator(s / "label0/data")) {
    std::string n = e.path().filename().string();
    if (n.find("_nyu.png") == std::string::npos) continue;
    ImageU8 lab = readPng8(e.path());
    for (uint8_t v : lab.data) classes.insert(v);
  }
  EXPECT_GE(classes.size(), 5u);
}

TEST(Generate, OneAndTwoThreadsGiveIdenticalBytes) {
  TempDir dir("gen_threads");
  std::string common = kSmall + "--frames 3 --spp 4 --seed 11 ";
  RunResult a = runInterinet(common + "--threads 1 --out " + (dir / "a").string());
  RunResult b = runInterinet(common + "--threads 2 --out " + (dir / "b").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto ta = readTree(dir / "a"), tb = readTree(dir / "b");
  ASSERT_EQ(ta.size(), tb.size());
  for (const auto& [name, bytes] : ta) EXPECT_TRUE(tb[name] == bytes) << name << " differs";
  RunResult c = runInterinet(common + "--seed 12 --out " + (dir / "c").string());
  ASSERT_EQ(c.exit_code, 0);
  auto tc = readTree(dir / "c");
  int differing = 0;
  for (const auto& [name, bytes] : ta)
    if (name.find("cam0/data/") != std::string::npos && tc[name] != bytes) ++differing;
  EXPECT_EQ(differing, 3) << "another seed must give other noise";
}

// The camera response (exposure, tone curve, sensor noise) changes the colour images only: every
// ground-truth file stays byte for byte the same.
TEST(Generate, CameraResponseTouchesColourOnly) {
  TempDir dir("gen_response");
  std::string common = kSmall + "--frames 2 --spp 4 ";
  RunResult a = runInterinet(common + "--out " + (dir / "a").string());
  RunResult b = runInterinet(common + "--tone aces --exposure-ev 1 --sensor-noise --out " +
                             (dir / "b").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto ta = readTree(seqDir(dir / "a")), tb = readTree(seqDir(dir / "b"));
  ASSERT_EQ(ta.size(), tb.size());
  int colour_differs = 0;
  for (const auto& [name, bytes] : ta) {
    bool colour = name.find("cam0/data/") != std::string::npos || name.rfind("rgb/", 0) == 0;
    if (colour) {
      colour_differs += tb[name] != bytes;
    } else if (name != "meta.json") {
      EXPECT_TRUE(tb[name] == bytes) << name << " changed";
    }
  }
  EXPECT_EQ(colour_differs, 4);  // 2 frames x (cam0 + TUM rgb)
  EXPECT_NE(tb["meta.json"].find("aces"), std::string::npos);
}

// A global shutter with an exposure blurs the colour image, but the ground truth is traced at the
// middle of the exposure, which is the frame's timestamp: identical to a static camera's.
TEST(Generate, MotionBlurKeepsGroundTruthAtTheTimestamp) {
  TempDir dir("gen_blur");
  std::string common = kSmall + "--frames 3 --spp 4 ";
  RunResult a = runInterinet(common + "--out " + (dir / "a").string());
  RunResult b = runInterinet(common + "--exposure-ms 30 --out " + (dir / "b").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto ta = readTree(seqDir(dir / "a")), tb = readTree(seqDir(dir / "b"));
  int colour_differs = 0;
  for (const auto& [name, bytes] : ta) {
    bool colour = name.find("cam0/data/") != std::string::npos || name.rfind("rgb/", 0) == 0;
    if (colour) colour_differs += tb[name] != bytes;
    if (name.find("depth0/data/") != std::string::npos ||
        name.find("label0/data/") != std::string::npos ||
        name.find("normal0/data/") != std::string::npos) {
      EXPECT_TRUE(tb[name] == bytes) << name << " changed";
    }
  }
  EXPECT_EQ(colour_differs, 6) << "every colour image is blurred";
  // a rolling shutter moves rows of the ground truth
  RunResult c = runInterinet(common + "--readout-ms 30 --out " + (dir / "c").string());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  auto tc = readTree(seqDir(dir / "c"));
  int depth_differs = 0;
  for (const auto& [name, bytes] : ta)
    if (name.find("depth0/data/") != std::string::npos) depth_differs += tc[name] != bytes;
  EXPECT_EQ(depth_differs, 6);  // 3 frames x (PNG + EXR)
}

/// Starts the binary with `args`, its stderr into `err_file` ("" = discarded).
pid_t spawn(const std::string& args, const std::string& err_file = "") {
  pid_t pid = fork();
  if (pid == 0) {
    std::string cmd = std::string("exec ") + INET_BINARY + " " + args + " >/dev/null 2>" +
                      (err_file.empty() ? std::string("&1") : "'" + err_file + "'");
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

/// Sends `sig` once `frames` frames are written; returns the wait status.
int killAfterFrames(const std::string& args, const fs::path& cam_dir, size_t frames, int sig,
                    const std::string& err_file = "") {
  pid_t pid = spawn(args, err_file);
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (filesIn(cam_dir, ".png") < frames && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(Generate, KilledRunResumesToIdenticalFolder) {
  TempDir dir("gen_kill");
  std::string common = kSmall + "--frames 30 --spp 16 ";
  RunResult ref = runInterinet(common + "--out " + (dir / "ref").string());
  ASSERT_EQ(ref.exit_code, 0) << ref.err;
  auto expected = readTree(dir / "ref");

  fs::path out = dir / "killed";
  killAfterFrames(common + "--out " + out.string(), seqDir(out) / "cam0/data", 5, SIGKILL);
  size_t partial = filesIn(seqDir(out) / "cam0/data", ".png");
  EXPECT_GE(partial, 5u);
  EXPECT_LT(partial, 30u) << "the run finished before it could be killed; make it longer";
  EXPECT_FALSE(fs::exists(seqDir(out) / "rgb.txt")) << "index files are written last";
  RunResult resumed = runInterinet(common + "--out " + out.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resuming"), std::string::npos) << resumed.err;
  auto got = readTree(out);
  ASSERT_EQ(got.size(), expected.size());
  for (const auto& [name, bytes] : expected) EXPECT_TRUE(got[name] == bytes) << name << " differs";
}

// ---- lenses: fisheye and panorama through the whole pipeline -------------------------------

std::vector<std::string> lines(const fs::path& p) {
  std::vector<std::string> out;
  std::string text = readTextFile(p), line;
  for (std::istringstream in(text); std::getline(in, line);) out.push_back(line);
  return out;
}

bool hasLine(const fs::path& p, const std::string& line) {
  auto l = lines(p);
  return std::find(l.begin(), l.end(), line) != l.end();
}

/// The four numbers of the "intrinsics: [fu, fv, cu, cv] #..." line of a sensor.yaml.
std::vector<double> yamlIntrinsics(const fs::path& p) {
  for (const auto& l : lines(p)) {
    if (l.rfind("intrinsics: [", 0) != 0) continue;
    std::vector<double> v;
    std::string list = l.substr(13, l.find(']') - 13);
    for (size_t b = 0; b < list.size();) {
      size_t e = std::min(list.find(',', b), list.size());
      v.push_back(std::stod(list.substr(b, e - b)));
      b = e + 1;
    }
    return v;
  }
  return {};
}

/// The ASL depth PNG (mm) of every frame equals the ray depth EXR (m): both hold the Euclidean
/// ray distance. Returns the number of pixels with depth.
size_t expectPngHoldsRayDistance(const fs::path& seq) {
  size_t valid = 0;
  for (const auto& e : fs::directory_iterator(seq / "depth0/data")) {
    if (e.path().extension() != ".png") continue;
    ImageU16 mm = readPng16(e.path());
    ImageF ray = readExr(fs::path(e.path()).replace_extension(".exr"), {"Z"});
    for (size_t i = 0; i < mm.pixelCount(); ++i) {
      EXPECT_NEAR(mm.data[i], std::floor(ray.data[i] * 1000.0 + 0.5), 1.0) << e.path() << " " << i;
      valid += mm.data[i] != 0;
    }
  }
  return valid;
}

TEST(Generate, FisheyeWritesEquidistantCalibrationAndEveryPass) {
  TempDir dir("gen_fisheye");
  RunResult r =
      runInterinet("generate --layout builtin:room --lens fisheye --width 64 --frames 2 --spp 1 "
                   "--no-progress --out " +
                   (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::path s = seqDir(dir / "out");
  for (const char* folder : {"cam0", "depth0", "normal0", "albedo0", "shading0", "label0"}) {
    const fs::path yaml = s / folder / "sensor.yaml";
    EXPECT_TRUE(hasLine(yaml, "resolution: [64, 64]")) << folder;
    EXPECT_TRUE(hasLine(yaml, "camera_model: pinhole")) << folder;
    EXPECT_TRUE(hasLine(yaml, "distortion_model: equidistant")) << folder;
    EXPECT_TRUE(hasLine(yaml, "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]")) << folder;
    EXPECT_NE(readTextFile(yaml).find("r = f * theta"), std::string::npos) << folder;
    std::vector<double> k = yamlIntrinsics(yaml);
    ASSERT_EQ(k.size(), 4u) << folder;
    const double f = (64 / 2.0) / (std::numbers::pi / 2);  // 180 deg across 64 px
    EXPECT_NEAR(k[0], f, 1e-9);
    EXPECT_NEAR(k[1], f, 1e-9);
    EXPECT_EQ(k[2], 31.5);
    EXPECT_EQ(k[3], 31.5);
  }
  for (auto [folder, suffix] :
       std::vector<std::pair<const char*, const char*>>{{"cam0/data", ".png"},
                                                        {"depth0/data", ".png"},
                                                        {"depth0/data", ".exr"},
                                                        {"normal0/data", ".png"},
                                                        {"albedo0/data", ".png"},
                                                        {"shading0/data", ".png"},
                                                        {"label0/data", "_nyu.png"},
                                                        {"label0/data", "_instance.png"},
                                                        {"rgb", ".png"},
                                                        {"depth", ".png"}})
    EXPECT_EQ(filesIn(s / folder, suffix), 2u) << folder << " " << suffix;
  auto meta = nlohmann::json::parse(readTextFile(s / "meta.json"));
  EXPECT_EQ(meta["lens"]["type"], "fisheye");
  EXPECT_EQ(meta["lens"]["fov_deg"], 180.0);
  EXPECT_EQ(meta["camera"]["distortion_model"], "equidistant");
  EXPECT_NE(lines(s / "camera.txt")[0].find("NOT a pinhole"), std::string::npos) << "TUM side";
  // depth PNG = ray distance (a z-depth PNG would be far smaller near the circle's edge); the
  // corners lie outside the 180 degree image circle: no ray, depth 0
  const size_t valid = expectPngHoldsRayDistance(s);
  EXPECT_LT(valid, 2u * 64 * 64);
  EXPECT_GT(valid, 2u * 64 * 64 * 3 / 4);  // the circle covers pi/4 of the square
  ImageU16 first = readPng16(s / "depth0/data/0000000000000000000.png");
  EXPECT_EQ(first.at(0, 0), 0);
  EXPECT_GT(first.at(1, 32), 0) << "85 degrees off axis, still inside the circle";
}

TEST(Generate, PanoramaWritesEquirectangularCalibration) {
  TempDir dir("gen_pano");
  RunResult r = runInterinet(
      "generate --layout builtin:room --lens panorama --width 64 --height 32 --frames 2 --spp 1 "
      "--no-progress --out " +
      (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::path s = seqDir(dir / "out");
  const fs::path yaml = s / "cam0/sensor.yaml";
  EXPECT_TRUE(hasLine(yaml, "camera_model: equirectangular"));
  EXPECT_TRUE(hasLine(yaml, "resolution: [64, 32]"));
  EXPECT_NE(readTextFile(yaml).find("NOT a Kalibr camera model"), std::string::npos);
  for (const auto& l : lines(yaml)) {
    EXPECT_NE(l.rfind("distortion", 0), 0u) << l;
    EXPECT_NE(l.rfind("intrinsics", 0), 0u) << l;
  }
  EXPECT_TRUE(hasLine(s / "depth0/sensor.yaml", "camera_model: equirectangular"));
  auto meta = nlohmann::json::parse(readTextFile(s / "meta.json"));
  EXPECT_EQ(meta["lens"]["type"], "panorama");
  EXPECT_EQ(meta["camera"]["lens"], "panorama");
  EXPECT_EQ(meta["passes"][1], "ray_depth") << "a panorama has no z-depth pass";
  // the room is closed: every direction, also behind the camera (where z-depth would be
  // negative), has a ray distance
  EXPECT_EQ(expectPngHoldsRayDistance(s), 2u * 64 * 32);
}

/// --distortion reaches every pass and every calibration file: a scene point keeps its ray
/// distance, so the distorted depth at pixel u equals the undistorted depth at the pixel where
/// the undistorted pinhole sees the same ray (K times the undistorted normalised point).
TEST(Generate, DistortionBendsEveryPassAndIsWrittenToTheCalibration) {
  TempDir dir("gen_distortion");
  // EuRoC cam0's radtan coefficients (Kalibr)
  const std::string k = "-0.28340811,0.07395907,0.00019359,1.76187114e-05";
  const std::string common = "generate --layout builtin:room --width 160 --height 120 --fx 120 "
                             "--fy 120 --frames 2 --spp 1 --passes depth,ray_depth,label,flow --format asl "
                             "--no-progress ";
  RunResult plain = runInterinet(common + "--out " + (dir / "plain").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  RunResult bent = runInterinet(common + "--distortion " + k + " --out " + (dir / "bent").string());
  ASSERT_EQ(bent.exit_code, 0) << bent.err;
  const fs::path s = seqDir(dir / "bent");
  for (const char* folder : {"depth0", "label0"}) {
    const fs::path yaml = s / folder / "sensor.yaml";
    EXPECT_TRUE(hasLine(yaml, "distortion_model: radial-tangential")) << folder;
    EXPECT_TRUE(hasLine(yaml, "distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, "
                              "1.76187114e-05]"))
        << readTextFile(yaml);
  }
  auto meta = nlohmann::json::parse(readTextFile(s / "meta.json"));
  ASSERT_EQ(meta["camera"]["distortion_coefficients"].size(), 5u);  // OpenCV's k1 k2 p1 p2 k3
  EXPECT_DOUBLE_EQ(meta["camera"]["distortion_coefficients"][0].get<double>(), -0.28340811);
  EXPECT_EQ(meta["camera"]["distortion_model"], "radial-tangential");

  const std::string first = "depth0/data/0000000000000000000.exr";
  const ImageF d_plain = readExr(seqDir(dir / "plain") / first, {"Z"});
  const ImageF d_bent = readExr(s / first, {"Z"});
  LensModel lens = LensModel::pinhole(CameraIntrinsics::centred(160, 120, 120));
  lens.k1 = -0.28340811, lens.k2 = 0.07395907, lens.p1 = 0.00019359, lens.p2 = 1.76187114e-05;
  std::vector<double> mapped, same;
  for (int y = 0; y < 120; y += 3)
    for (int x = 0; x < 160; x += 3) {
      const double mx = (x + 0.5 - lens.K.cx) / lens.K.fx, my = (y + 0.5 - lens.K.cy) / lens.K.fy;
      if (mx * mx + my * my < 0.25) continue;  // the outer part, where distortion moves pixels
      Eigen::Vector2d xy;
      ASSERT_TRUE(undistortNormalised(lens, {mx, my}, xy));
      const int u = static_cast<int>(std::floor(lens.K.cx + lens.K.fx * xy.x()));
      const int v = static_cast<int>(std::floor(lens.K.cy + lens.K.fy * xy.y()));
      if (u < 0 || v < 0 || u >= 160 || v >= 120) continue;
      const float d = d_bent.at(x, y, 0);
      mapped.push_back(std::abs(d_plain.at(u, v, 0) - d) / d);
      same.push_back(std::abs(d_plain.at(x, y, 0) - d) / d);
    }
  ASSERT_GT(mapped.size(), 300u);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  // nearest pixel of a smooth room: well under 1 %; the same pixel is far off
  EXPECT_LT(median(mapped), 0.01);
  EXPECT_GT(median(same), 5 * median(mapped));
  // the principal point does not move
  EXPECT_NEAR(d_bent.at(80, 60, 0), d_plain.at(80, 60, 0), 1e-4 * d_plain.at(80, 60, 0));
  // the flow of a distorted camera is not the pinhole flow
  EXPECT_NE(readTree(s / "flow0"), readTree(seqDir(dir / "plain") / "flow0"));
}

TEST(Generate, BadLensCombinationsFailNamingTheFlag) {
  TempDir dir("gen_badlens");
  const std::pair<std::string, std::string> cases[] = {
      {"--lens fisheye --width 64 --height 32", "--height"},
      {"--lens panorama --width 64 --height 64", "--height"},
      {"--lens panorama --width 63", "--width"},
      {"--lens fish", "--lens"},
      {"--lens fisheye --fisheye-fov 0", "--fisheye-fov"},
      {"--lens fisheye --fisheye-fov 361", "--fisheye-fov"},
      {"--lens fisheye --fisheye-fov -90", "--fisheye-fov"},
      {"--lens fisheye --fx 100", "--fx"},
      {"--lens panorama --cy 3", "--cy"},
      {"--lens pinhole --aperture 0.01", "--aperture"},
      {"--lens fisheye --focus 3", "--focus"},
      {"--fisheye-fov 90", "--fisheye-fov"},
      {"--distortion 0.1,0.2,0", "--distortion"},
      {"--distortion 0.1,0,0,0,0,0", "--distortion"},
      {"--distortion nan,0,0,0", "--distortion"},
      {"--distortion -0.2,0.05,0,0,0.01", "--distortion"},  // k3 and the ASL sensor.yaml
      {"--lens fisheye --width 64 --distortion -0.2,0.05,0,0", "--distortion"},
      {"--lens panorama --width 64 --height 32 --distortion -0.2,0.05,0,0", "--distortion"},
      {"--width 640 --height 480 --fx 600 --fy 600 --distortion -2,0,0,0", "--distortion"},
      {"--hdr --passes depth", "--hdr"},
      {"--hdr --format tum", "--hdr"},
  };
  for (const auto& [args, flag] : cases) {
    const fs::path out = dir / "out";
    RunResult r = runInterinet("generate --layout builtin:room --frames 1 --spp 1 --no-progress " +
                               args + " --out " +
                               out.string());
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("error: " + flag + ":", 0), 0u) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args << " wrote output";
  }
}

// ---- linear HDR EXR -------------------------------------------------------------------------

TEST(Generate, HdrExrIsTheLinearRadianceBehindThePng) {
  TempDir dir("gen_hdr");
  // the raw path-traced colour (no reuse, no denoiser): its brightest pixels exceed 1
  const std::string common =
      kSmall + "--hdr --frames 2 --spp 2 --tone none --no-denoise --temporal 1 --exposure fixed ";
  RunResult a = runInterinet(common + "--exposure-ev 0 --out " + (dir / "a").string());
  RunResult b = runInterinet(common + "--exposure-ev 2 --out " + (dir / "b").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  fs::path s = seqDir(dir / "a");
  EXPECT_EQ(filesIn(s / "cam0/data", ".exr"), 2u);
  EXPECT_EQ(filesIn(s / "rgb", ".exr"), 0u) << "TUM has no EXR";
  EXPECT_EQ(exrChannelNames(s / "cam0/data/0000000000000000000.exr"),
            (std::vector<std::string>{"B", "G", "R"}));
  size_t bright = 0;
  for (const char* t : {"0000000000000000000", "0000000000040000000"}) {
    ImageF exr = readExr(s / "cam0/data" / (std::string(t) + ".exr"), {"R", "G", "B"});
    ImageU8 png = readPng8(s / "cam0/data" / (std::string(t) + ".png"));
    ASSERT_EQ(exr.width, png.width);
    ASSERT_EQ(exr.data.size(), png.data.size());
    for (size_t i = 0; i < exr.data.size(); ++i) {
      EXPECT_LE(std::abs(int(png.data[i]) - int(linearToSrgb8(exr.data[i]))), 1) << t << " " << i;
      bright += exr.data[i] > 1.f;
    }
    // exposure changes the PNG, never the linear EXR
    const fs::path sb = seqDir(dir / "b") / "cam0/data";
    EXPECT_EQ(readTextFile(sb / (std::string(t) + ".exr")),
              readTextFile(s / "cam0/data" / (std::string(t) + ".exr")));
    EXPECT_NE(readTextFile(sb / (std::string(t) + ".png")),
              readTextFile(s / "cam0/data" / (std::string(t) + ".png")));
  }
  EXPECT_GT(bright, 0u) << "radiance above 1 is kept: the EXR must not be clipped";
  auto meta = nlohmann::json::parse(readTextFile(s / "meta.json"));
  EXPECT_TRUE(meta["encodings"].contains("rgb_exr"));
}

// Auto exposure (the default) meters the sequence once on its preview: one multiplier, a power
// of 2 in third stops, for every frame (the PNG is the EXR times it, encoded), chosen so the
// log-average brightness is middle grey; the linear EXR and the ground truth are those of a
// fixed exposure, and --exposure-ev compensates on top.
TEST(Generate, AutoExposureMetersOneMultiplierPerSequenceToMiddleGrey) {
  TempDir dir("gen_auto_exposure");
  const std::string common = kSmall + "--hdr --frames 3 --spp 4 ";
  RunResult a = runInterinet(common + "--out " + (dir / "auto").string());
  RunResult f = runInterinet(common + "--exposure fixed --out " + (dir / "fixed").string());
  RunResult c = runInterinet(common + "--exposure-ev 1 --out " + (dir / "plus1").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(f.exit_code, 0) << f.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  auto metaOf = [&](const char* run) {
    return nlohmann::json::parse(readTextFile(seqDir(dir / run) / "meta.json"));
  };
  auto scaleOf = [](const nlohmann::json& meta) {
    const std::string r = meta["camera_response"].get<std::string>();
    const size_t at = r.find("exposure_scale=");
    EXPECT_NE(at, std::string::npos) << r;
    return std::stod(r.substr(at + 15));
  };
  const double scale = scaleOf(metaOf("auto"));
  EXPECT_EQ(scaleOf(metaOf("fixed")), 1.0);
  EXPECT_EQ(scaleOf(metaOf("plus1")), scale) << "--exposure-ev compensates, the metering stays";
  const double thirds = 3.0 * std::log2(scale);
  EXPECT_NEAR(thirds, std::round(thirds), 1e-4) << scale;
  EXPECT_NE(metaOf("auto")["auto_exposure"].get<std::string>().find("EV"), std::string::npos);
  EXPECT_NE(metaOf("fixed")["auto_exposure"].get<std::string>().find("off"), std::string::npos);
  double log_sum = 0;
  size_t n = 0;
  for (const char* t : {"0000000000000000000", "0000000000040000000", "0000000000080000000"}) {
    const fs::path s = seqDir(dir / "auto") / "cam0/data";
    EXPECT_EQ(readTextFile(s / (std::string(t) + ".exr")),
              readTextFile(seqDir(dir / "fixed") / "cam0/data" / (std::string(t) + ".exr")));
    ImageF exr = readExr(s / (std::string(t) + ".exr"), {"R", "G", "B"});
    ImageU8 png = readPng8(s / (std::string(t) + ".png"));
    ASSERT_EQ(exr.data.size(), png.data.size());
    int off = 0;
    for (size_t i = 0; i < exr.data.size(); ++i)
      off += std::abs(int(png.data[i]) - int(linearToSrgb8(float(scale) * exr.data[i]))) > 1;
    EXPECT_EQ(off, 0) << t;
    for (size_t i = 0; i + 2 < exr.data.size(); i += 3) {
      const double y = 0.2126 * exr.data[i] + 0.7152 * exr.data[i + 1] + 0.0722 * exr.data[i + 2];
      log_sum += std::log(1e-4 + scale * y);
      ++n;
    }
  }
  // the frames are not the preview (other poses in between, 4 spp, 160 px), so within 1/2 stop
  const double log_average = std::exp(log_sum / n);
  EXPECT_NEAR(std::log2(log_average / 0.18), 0.0, 0.5) << log_average << " at scale " << scale;
}

// The learned denoiser (render/neural_denoise.h) in a sequence, and the training dump it
// learns from: the dump's reflected colour plus its emission is the unfiltered colour, the
// network removes most of the pixel-to-pixel noise, and its output does not depend on the
// thread count.
TEST(Generate, LearnedDenoiserAndItsTrainingDump) {
  TempDir dir("gen_learned");
  // (the same samples everywhere: the network was trained on frames without planned samples)
  const std::string common = kSmall + "--hdr --frames 2 --spp 4 --exposure fixed --passes rgb,depth " +
                             "--history-boost 1 --history-boost-edges 1 ";
  RunResult raw = runInterinet(common + "--no-denoise --save-denoiser-inputs --out " +
                               (dir / "raw").string());
  RunResult l1 = runInterinet(common + "--denoiser learned --threads 1 --out " + (dir / "l1").string());
  RunResult l2 = runInterinet(common + "--denoiser learned --threads 2 --out " + (dir / "l2").string());
  RunResult bad = runInterinet(common + "--denoiser oidn --out " + (dir / "bad").string());
  ASSERT_EQ(raw.exit_code, 0) << raw.err;
  ASSERT_EQ(l1.exit_code, 0) << l1.err;
  ASSERT_EQ(l2.exit_code, 0) << l2.err;
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--denoiser"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad" / "default_room"));
  const fs::path s = seqDir(dir / "raw");
  EXPECT_EQ(filesIn(s / "denoise_in", ".exr"), 2u);
  auto meta = nlohmann::json::parse(readTextFile(seqDir(dir / "l1") / "meta.json"));
  EXPECT_NE(meta["render"]["denoise"].get<std::string>().find("learned"), std::string::npos);
  // high-frequency energy: mean |x - mean of its 4 neighbours| over pixels seen in both
  auto roughness = [](const ImageF& img) {
    double r = 0, m = 0;
    for (int y = 1; y + 1 < img.height; ++y)
      for (int x = 1; x + 1 < img.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const float v = img.at(x, y, c);
          const float n = 0.25f * (img.at(x - 1, y, c) + img.at(x + 1, y, c) +
                                   img.at(x, y - 1, c) + img.at(x, y + 1, c));
          r += std::abs(v - n);
          m += v;
        }
    return r / m;
  };
  for (const char* t : {"0000000000000000000", "0000000000040000000"}) {
    const std::string name = std::string(t) + ".exr";
    const ImageF exr = readExr(s / "cam0/data" / name, {"R", "G", "B"});
    const ImageF dump = readExr(s / "denoise_in" / name,
                                {"R", "G", "B", "emission.R", "emission.G", "emission.B", "Z"});
    ASSERT_EQ(dump.width, exr.width);
    for (size_t i = 0; i < exr.pixelCount(); ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(dump.data[7 * i + c] + dump.data[7 * i + 3 + c], exr.data[3 * i + c],
                    1e-5f * (1.f + exr.data[3 * i + c]));
    const std::string a = readTextFile(seqDir(dir / "l1") / "cam0/data" / name);
    EXPECT_EQ(a, readTextFile(seqDir(dir / "l2") / "cam0/data" / name)) << "thread count";
    const ImageF learned = readExr(seqDir(dir / "l1") / "cam0/data" / name, {"R", "G", "B"});
    const double r_raw = roughness(exr), r_learned = roughness(learned);
    EXPECT_LT(r_learned, 0.3 * r_raw) << t;
  }
}

struct FileId {
  ino_t inode;
  int64_t mtime_ns;
  bool operator==(const FileId&) const = default;
};
FileId fileId(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return {st.st_ino, int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
}

TEST(Generate, HdrRerunSkipsCompleteFramesAndRedoesAFrameMissingItsExr) {
  TempDir dir("gen_hdr_resume");
  const std::string args = kSmall + "--hdr --frames 3 --spp 1 --out " + (dir / "out").string();
  RunResult first = runInterinet(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const fs::path cam = seqDir(dir / "out") / "cam0/data";
  const std::string t[3] = {"0000000000000000000", "0000000000040000000", "0000000000080000000"};
  std::map<std::string, FileId> before;
  for (const auto& e : fs::directory_iterator(cam))
    before[e.path().filename().string()] = fileId(e.path());
  ASSERT_EQ(before.size(), 6u);
  const std::string exr1 = readTextFile(cam / (t[1] + ".exr"));
  fs::remove(cam / (t[1] + ".exr"));  // frame 1 lacks only its EXR

  RunResult again = runInterinet(args);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("resuming: 2 of 3 frames"), std::string::npos) << again.err;
  for (int k : {0, 2})
    for (const char* ext : {".png", ".exr"})
      EXPECT_TRUE(fileId(cam / (t[k] + ext)) == before[t[k] + ext]) << t[k] << ext << " rewritten";
  EXPECT_FALSE(fileId(cam / (t[1] + ".png")) == before[t[1] + ".png"]) << "frame 1 re-rendered";
  EXPECT_EQ(readTextFile(cam / (t[1] + ".exr")), exr1) << "same bytes as the first run";

  // a folder written without --hdr is incomplete for an --hdr run: every frame is redone
  TempDir dir2("gen_hdr_upgrade");
  const std::string plain = kSmall + "--frames 2 --spp 1 --out " + (dir2 / "out").string();
  ASSERT_EQ(runInterinet(plain).exit_code, 0);
  RunResult hdr =
      runInterinet(kSmall + "--hdr --frames 2 --spp 1 --out " + (dir2 / "out").string());
  ASSERT_EQ(hdr.exit_code, 0) << hdr.err;
  EXPECT_EQ(hdr.err.find("resuming"), std::string::npos) << hdr.err;
  EXPECT_EQ(filesIn(seqDir(dir2 / "out") / "cam0/data", ".exr"), 2u);
}

// Temporal reuse (--temporal): frame k's colour depends on frames k - N + 1 .. k, and with the
// smoothing after the denoiser (3 frames here: the window bounds it) on frames k - N - 1 .. k,
// so a rerun that finds frames 0..5 done renders frames 2..5 again first and writes the same
// bytes for 6..7; cam1 has its own window. The colour differs from a run without reuse.
TEST(Generate, TemporalReuseResumesToTheSameBytes) {
  TempDir dir("gen_temporal");
  const std::string args = kSmall + "--hdr --frames 8 --spp 2 --temporal 3 --stereo 0.1 " +
                           "--passes rgb,depth --format asl --imu 0 --out ";
  RunResult whole = runInterinet(args + (dir / "whole").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto full = readTree(dir / "whole");
  // a run killed after 6 frames: the first 6 frames' files only. The rerun renders frames 2..5
  // again (4 and 5 for the window, 2 and 3 for theirs, as 4 and 5 are denoised and smoothed
  // into 6), after the geometry of frames 0 and 1, which planned their samples
  // (TemporalReuse::plan)
  const fs::path part = dir / "part";
  fs::create_directories(part);
  fs::copy(dir / "whole", part, fs::copy_options::recursive);
  for (const char* cam : {"cam0", "cam1", "depth0", "depth1"})
    for (const auto& e : fs::directory_iterator(seqDir(part) / cam / "data"))
      if (e.path().filename().string() >= "0000000000240000000") fs::remove(e.path());
  RunResult resumed = runInterinet(args + part.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resuming: 6 of 8 frames"), std::string::npos) << resumed.err;
  const auto again = readTree(part);
  ASSERT_EQ(again.size(), full.size());
  for (const auto& [name, bytes] : full) {
    if (name.find("/cam") != std::string::npos) {
      EXPECT_TRUE(again.at(name) == bytes) << name << " differs after resuming";
    }
  }
  // and reuse changed the colour
  RunResult plain = runInterinet(kSmall + "--hdr --frames 8 --spp 2 --stereo 0.1 --temporal 1 " +
                                 "--passes rgb,depth --format asl --imu 0 --out " +
                                 (dir / "plain").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const std::string last = "default_room/seq_000/cam0/data/0000000000200000000.exr";
  EXPECT_NE(readTree(dir / "plain").at(last), full.at(last));
  // frame 0 has no past: reuse leaves it as rendered, and only the planned samples (more of
  // them where no earlier frame saw a point: all of frame 0) and the wider filter after reuse
  // change it (--denoise-params gives it the single-frame filter of --temporal 1)
  const std::string first = "default_room/seq_000/cam0/data/0000000000000000000.exr";
  EXPECT_NE(readTree(dir / "plain").at(first), full.at(first));
  RunResult unplanned = runInterinet(
      kSmall + "--hdr --frames 1 --spp 2 --temporal 3 --history-boost 1 --history-boost-edges 1 " +
      "--denoise-params iterations=3,sigma_color=2 --passes rgb --format asl --imu 0 --out " +
      (dir / "unplanned").string());
  ASSERT_EQ(unplanned.exit_code, 0) << unplanned.err;
  EXPECT_EQ(readTree(dir / "plain").at(first), readTree(dir / "unplanned").at(first));
}

TEST(Generate, TemporalReuseRejectsBadWindowsAndMotionBlurButIsOnByDefault) {
  TempDir dir("gen_temporal_bad");
  const std::string out = " --frames 2 --spp 1 --out " + (dir / "out").string();
  RunResult zero = runInterinet(kSmall + "--temporal 0" + out);
  EXPECT_NE(zero.exit_code, 0);
  EXPECT_NE(zero.err.find("--temporal"), std::string::npos) << zero.err;
  RunResult boost = runInterinet(kSmall + "--history-boost 17" + out);
  EXPECT_NE(boost.exit_code, 0);
  EXPECT_NE(boost.err.find("--history-boost"), std::string::npos) << boost.err;
  for (const char* smooth : {"--temporal-smooth 0", "--temporal-smooth 0 --no-denoise"}) {
    RunResult bad = runInterinet(kSmall + smooth + out);
    EXPECT_NE(bad.exit_code, 0) << smooth;
    EXPECT_NE(bad.err.find("--temporal-smooth"), std::string::npos) << bad.err;
  }
  for (const char* ratio : {"--temporal-firefly 1", "--temporal-firefly -3"}) {
    RunResult bad = runInterinet(kSmall + ratio + out);
    EXPECT_NE(bad.exit_code, 0) << ratio;
    EXPECT_NE(bad.err.find("--temporal-firefly"), std::string::npos) << bad.err;
  }
  RunResult blur = runInterinet(kSmall + "--temporal 4 --exposure-ms 5" + out);
  EXPECT_NE(blur.exit_code, 0);
  EXPECT_NE(blur.err.find("global shutter"), std::string::npos) << blur.err;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing written";
  // by default, motion blur simply turns the reuse off (meta.json says so)
  RunResult by_default = runInterinet(kSmall + "--exposure-ms 5" + out);
  ASSERT_EQ(by_default.exit_code, 0) << by_default.err;
  const std::string meta = readTextFile(seqDir(dir / "out") / "meta.json");
  EXPECT_EQ(meta.find("temporal_reuse"), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"denoise\": \"iterations="), std::string::npos) << meta;
}

// The radiance cache (render/radiance_cache.h) is on by default and meta.json says so with its
// settings; --no-radiance-cache renders other colour; bad settings name their flag.
TEST(Generate, TheRadianceCacheIsOnByDefaultSaysSoAndRejectsBadSettings) {
  TempDir dir("gen_radiance");
  const std::string args = kSmall + "--hdr --frames 1 --spp 2 --passes rgb --format asl --imu 0 ";
  RunResult on = runInterinet(args + "--out " + (dir / "on").string());
  ASSERT_EQ(on.exit_code, 0) << on.err;
  const std::string meta = readTextFile(seqDir(dir / "on") / "meta.json");
  EXPECT_NE(meta.find("\"radiance_cache\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"train_spp\": 16"), std::string::npos) << meta;
  RunResult off = runInterinet(args + "--no-radiance-cache --out " + (dir / "off").string());
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_EQ(readTextFile(seqDir(dir / "off") / "meta.json").find("\"radiance_cache\""),
            std::string::npos);
  const std::string frame = "default_room/seq_000/cam0/data/0000000000000000000.exr";
  EXPECT_NE(readTree(dir / "on").at(frame), readTree(dir / "off").at(frame));
  for (const char* bad : {"--radiance-cell 0", "--radiance-cell 9", "--radiance-train 0"}) {
    RunResult r = runInterinet(args + bad + " --out " + (dir / "bad").string());
    EXPECT_NE(r.exit_code, 0) << bad;
    const std::string flag = std::string(bad).substr(0, std::string(bad).find(' '));
    EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "bad")) << "nothing written";
}

TEST(Generate, CtrlCStopsCleanlyAndResumes) {
  TempDir dir("gen_int");
  fs::path out = dir / "out";
  std::string args = kSmall + "--frames 30 --spp 16 --out " + out.string();
  const int status = killAfterFrames(args, seqDir(out) / "cam0/data", 3, SIGINT);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  for (const auto& [name, bytes] : readTree(out))
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
  RunResult resumed = runInterinet(args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(filesIn(seqDir(out) / "cam0/data", ".png"), 30u);
}

// A scheduler's SIGTERM (Slurm, Kubernetes: the warning before SIGKILL) stops the run between
// frames with status 143 and says that a rerun resumes; the rerun finishes the sequence.
TEST(Generate, SigtermStopsWith143AndARerunResumes) {
  TempDir dir("gen_term");
  fs::path out = dir / "out";
  const std::string args = kSmall + "--frames 30 --spp 16 --out " + out.string();
  const std::string err_file = (dir / "stderr.txt").string();
  const int status = killAfterFrames(args, seqDir(out) / "cam0/data", 3, SIGTERM, err_file);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), 143);
  const std::string err = readTree(dir.path())["stderr.txt"];
  EXPECT_NE(err.find("stopped by SIGTERM after"), std::string::npos) << err;
  EXPECT_NE(err.find("rerun the same command to resume"), std::string::npos) << err;
  const size_t partial = filesIn(seqDir(out) / "cam0/data", ".png");
  EXPECT_LT(partial, 30u) << "the run finished before the signal; make it longer";
  for (const auto& [name, bytes] : readTree(out))
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
  RunResult resumed = runInterinet(args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resuming"), std::string::npos) << resumed.err;
  EXPECT_EQ(filesIn(seqDir(out) / "cam0/data", ".png"), 30u);
}

// A trajectory file in another frame than the scene's (a motion-capture path has the origin of
// its own room) rendered the outside of the walls, silently: now it is said, with both extents.
// A path inside the room says nothing.
TEST(Generate, AFilePathOutsideTheSceneIsWarnedAbout) {
  TempDir dir("gen_outside");
  const std::string small = "generate --layout builtin:room --width 32 --height 24 --fx 30 "
                            "--fy 30 --spp 1 --frames 3 "
                            "--passes rgb,depth --no-progress ";
  RunResult first = runInterinet(small + "--out " + (dir / "a").string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::string inside = readTextFile((seqDir(dir / "a") / "groundtruth.txt").string());
  std::string shifted;  // every position 50 m along x
  std::istringstream lines(inside);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') {
      shifted += line + "\n";
      continue;
    }
    std::istringstream in(line);
    std::string t;
    double x;
    in >> t >> x;
    std::string rest;
    std::getline(in, rest);
    shifted += t + " " + std::to_string(x + 50.0) + rest + "\n";
  }
  writeFile(dir / "inside.txt", inside);
  writeFile(dir / "outside.txt", shifted);
  RunResult ok = runInterinet(small + "--trajectory " + (dir / "inside.txt").string() +
                              " --out " + (dir / "b").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(ok.err.find("camera positions"), std::string::npos) << ok.err;
  // outside, it renders black: the dark frames' error says why
  RunResult out = runInterinet(small + "--trajectory " + (dir / "outside.txt").string() +
                               " --out " + (dir / "c").string());
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.err.find("essentially black"), std::string::npos) << out.err;
  EXPECT_NE(out.err.find("the camera path leaves the scene (warned above)"), std::string::npos)
      << out.err;
  EXPECT_NE(out.err.find("outside.txt: 3 of 3 camera positions are outside the scene's indoor "
                         "space"),
            std::string::npos)
      << out.err;
  EXPECT_NE(out.err.find("the path spans x [5"), std::string::npos) << out.err;
  EXPECT_FALSE(fs::exists(dir / "c" / "default_room" / "seq_000" / "cam0"));
  // --place-trajectory moves it back into the room: no warning, a lit sequence, the moved path
  // as ground truth
  RunResult placed = runInterinet(small + "--trajectory " + (dir / "outside.txt").string() +
                                  " --place-trajectory --out " + (dir / "d").string());
  ASSERT_EQ(placed.exit_code, 0) << placed.err;
  EXPECT_NE(placed.err.find("outside.txt: placed in the scene: turned"), std::string::npos)
      << placed.err;
  EXPECT_NE(placed.err.find("100 % of its poses at least 0.1 m from the geometry (as given: 0 %)"),
            std::string::npos)
      << placed.err;
  EXPECT_EQ(placed.err.find("camera positions"), std::string::npos) << placed.err;
  const std::string gt = readTextFile((seqDir(dir / "d") / "groundtruth.txt").string());
  EXPECT_EQ(gt.find(" 5"), std::string::npos) << "no position left at x = 50 m: " << gt;
  RunResult inside_placed = runInterinet(small + "--trajectory " + (dir / "inside.txt").string() +
                                         " --place-trajectory --out " + (dir / "e").string());
  ASSERT_EQ(inside_placed.exit_code, 0) << inside_placed.err;
  EXPECT_NE(inside_placed.err.find("left where it is (100 %"), std::string::npos)
      << inside_placed.err;
  // it needs a file
  RunResult no_file = runInterinet(small + "--place-trajectory --out " + (dir / "f").string());
  EXPECT_EQ(no_file.exit_code, 2);
  EXPECT_NE(no_file.err.find("--place-trajectory: needs a camera path file"), std::string::npos)
      << no_file.err;
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

// Issue 16: a sequence made as frame ranges (pipeline/sequence_job.h) is the sequence made at
// once, whatever the order of the ranges or if they run together: the same bytes in every file,
// imu0/, boxes.json and events0/ included, and the sequence-level files come only from the run
// that finds every frame done.
TEST(Generate, FrameRangesInAnyOrderOrAtOnceGiveTheWholeSequence) {
  TempDir dir("gen_ranges");
  const std::string args = kSmall + "--frames 6 --spp 2 --temporal 3 --seed 5 " +
                           "--passes default,events --event-width 40 --event-height 30 " +
                           "--event-spp 1 --out ";
  const RunResult whole = runInterinet(args + (dir / "whole").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto full = readTree(dir / "whole");
  ASSERT_TRUE(full.count("default_room/seq_000/boxes.json"));
  ASSERT_TRUE(full.count("default_room/seq_000/events0/sensor.yaml"));

  // the last range first: frames only, no index, no boxes, no events yet
  const RunResult late = runInterinet(args + (dir / "ranges").string() + " --frame-range 3:6");
  ASSERT_EQ(late.exit_code, 0) << late.err;
  EXPECT_NE(late.out.find("wrote frames 3..5 of 6"), std::string::npos) << late.out;
  const fs::path seq = seqDir(dir / "ranges");
  EXPECT_FALSE(fs::exists(seq / "boxes.json"));
  EXPECT_FALSE(fs::exists(seq / "events0" / "sensor.yaml"));
  EXPECT_FALSE(fs::exists(seq / "cam0" / "data.csv"));
  EXPECT_EQ(countFiles(seq / "cam0" / "data"), 3u);
  // then the first: it completes the sequence and writes the rest
  const RunResult early = runInterinet(args + (dir / "ranges").string() + " --frame-range 0:3");
  ASSERT_EQ(early.exit_code, 0) << early.err;
  EXPECT_NE(early.out.find("wrote 6 frames"), std::string::npos) << early.out;
  const auto ranged = readTree(dir / "ranges");
  ASSERT_EQ(ranged.size(), full.size());
  for (const auto& [name, bytes] : full)
    EXPECT_TRUE(ranged.count(name) && ranged.at(name) == bytes) << name << " differs";

  // two ranges at once into one folder (as two ranks would): whoever ends last finishes it; a
  // rerun of either then finds everything done and writes the same bytes
  const std::string together = args + (dir / "together").string();
  auto first = std::async(std::launch::async,
                          [&] { return runInterinet(together + " --frame-range 0:2"); });
  const RunResult second = runInterinet(together + " --frame-range 2:9");
  ASSERT_EQ(first.get().exit_code, 0);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const RunResult again = runInterinet(together + " --frame-range 0:2");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("resuming: 2 of frames 0..1 already complete"), std::string::npos)
      << again.err;
  const auto both = readTree(dir / "together");
  ASSERT_EQ(both.size(), full.size());
  for (const auto& [name, bytes] : full)
    EXPECT_TRUE(both.count(name) && both.at(name) == bytes) << name << " differs";

  // ranges that are not ranges
  for (const char* bad : {"3", "4:2", "a:3", "2:2"}) {
    const RunResult r = runInterinet(args + (dir / "bad").string() + " --frame-range " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("--frame-range"), std::string::npos) << r.err;
  }
  const RunResult past = runInterinet(args + (dir / "bad").string() + " --frame-range 6:8");
  EXPECT_EQ(past.exit_code, 2);
  EXPECT_NE(past.err.find("starts at frame 6 but the camera path has 6 frames"),
            std::string::npos)
      << past.err;
  EXPECT_FALSE(fs::exists(dir / "bad")) << "nothing written";
}

}  // namespace
}  // namespace inet::test

namespace inet::test {
namespace {

/// Sorted paths of the files in `dir` whose names end in `suffix`.
std::vector<fs::path> filesEnding(const fs::path& dir, const std::string& suffix) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.size() >= suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Storage choices (docs/output.md section 9) change the files, never the ground truth: flow as
// EXR only holds the .flo's floats, every PNG at level 9 decodes to the same samples, PIZ EXRs
// to the same depth, half-float radiance within 2^-11; eval reads the EXR flow; meta.json says
// what was chosen.
TEST(Generate, StorageChoicesChangeFilesNotGroundTruth) {
  TempDir dir("gen_storage");
  const std::string common =
      kSmall + "--frames 3 --spp 1 --passes rgb,depth,ray_depth,label,flow --format asl ";
  const fs::path a = dir / "a", b = dir / "b";
  RunResult r = runInterinet(common + "--hdr --out " + a.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = runInterinet(common + "--hdr-half --flow-files exr --png-level 9 --exr-compression piz "
                   "--out " + b.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path sa = seqDir(a), sb = seqDir(b);
  EXPECT_EQ(filesEnding(sb / "flow0/data", ".flo").size(), 0u);
  EXPECT_EQ(filesEnding(sb / "flow0/data", "_occ.png").size(), 2u);
  const auto flos = filesEnding(sa / "flow0/data", ".flo");
  const auto exrs = filesEnding(sb / "flow0/data", ".exr");
  ASSERT_EQ(flos.size(), 2u);
  ASSERT_EQ(exrs.size(), 2u);
  EXPECT_EQ(filesEnding(sb / "flow0/data", ".png").size(), 2u) << "only the occlusion masks";
  for (size_t i = 0; i < 2; ++i) {
    const FlowField fa = readFlo(flos[i]), fb = readFlowExr(exrs[i]);
    EXPECT_EQ(fa.flow, fb.flow);
    EXPECT_EQ(fa.valid, fb.valid);
    EXPECT_LT(fs::file_size(exrs[i]), fs::file_size(flos[i]));
  }
  size_t bytes_a = 0, bytes_b = 0;
  for (const fs::path& p : filesEnding(sa / "depth0/data", ".png")) {
    const fs::path q = sb / "depth0/data" / p.filename();
    EXPECT_EQ(readPng16(p), readPng16(q));
    bytes_a += fs::file_size(p);
    bytes_b += fs::file_size(q);
  }
  EXPECT_LT(bytes_b, bytes_a) << "zlib level 9 against 1";
  for (const fs::path& p : filesEnding(sa / "depth0/data", ".exr"))
    EXPECT_EQ(readExr(p, {"Z"}), readExr(sb / "depth0/data" / p.filename(), {"Z"}));
  for (const fs::path& p : filesEnding(sa / "label0/data", "_nyu.png"))
    EXPECT_EQ(readPng8(p), readPng8(sb / "label0/data" / p.filename()));
  for (const fs::path& p : filesEnding(sa / "cam0/data", ".exr")) {
    const ImageF full = readExr(p, {"R", "G", "B"});
    const ImageF half = readExr(sb / "cam0/data" / p.filename(), {"R", "G", "B"});
    ASSERT_EQ(full.data.size(), half.data.size());
    for (size_t i = 0; i < full.data.size(); ++i)
      ASSERT_LE(std::abs(full.data[i] - half.data[i]), std::abs(full.data[i]) * 0x1p-11f + 1e-7f);
  }
  const auto meta = nlohmann::json::parse(readTextFile(sb / "meta.json"));
  EXPECT_EQ(meta["storage"]["flow"], "exr");
  EXPECT_EQ(meta["storage"]["png_level"], 9);
  EXPECT_EQ(meta["storage"]["exr_compression"], "piz");
  EXPECT_EQ(meta["storage"]["rgb_exr"], "half");
  // the evaluation reads the EXR flow where there is no .flo
  r = runInterinet("eval features " + sb.string() + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = runInterinet(common + "--flow-files flo+jpeg --out " + (dir / "c").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--flow-files"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "c"));
}

}  // namespace
}  // namespace inet::test
