// End-to-end `interiornet generate`: every pass on disk, same bytes for 1 and 2 threads, a run
// killed mid-sequence resumes to the same bytes, and memory does not grow with sequence length.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <set>
#include <thread>

#include "cli_util.h"
#include "dataset/image_io.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

const std::string kSmall = "generate --width 160 --height 120 --fx 150 --fy 150 --no-progress ";

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

pid_t spawn(const std::string& args) {
  pid_t pid = fork();
  if (pid == 0) {
    std::string cmd = std::string("exec ") + INET_BINARY + " " + args + " >/dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

void killAfterFrames(const std::string& args, const fs::path& cam_dir, size_t frames, int sig) {
  pid_t pid = spawn(args);
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (filesIn(cam_dir, ".png") < frames && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
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

TEST(Generate, CtrlCStopsCleanlyAndResumes) {
  TempDir dir("gen_int");
  fs::path out = dir / "out";
  std::string args = kSmall + "--frames 30 --spp 16 --out " + out.string();
  killAfterFrames(args, seqDir(out) / "cam0/data", 3, SIGINT);
  for (const auto& [name, bytes] : readTree(out))
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
  RunResult resumed = runInterinet(args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(filesIn(seqDir(out) / "cam0/data", ".png"), 30u);
}

}  // namespace
}  // namespace inet::test
