// SequenceWriter: validation before writing, resumability, determinism and meta.json.
#include "dataset/sequence_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/asl_writer.h"
#include "dataset/image_encode.h"
#include "core/image_io.h"
#include "dataset/tum_writer.h"
#include "dataset_test_util.h"
#include "sensors/imu_io.h"

namespace inet {
namespace {

using namespace inet::test;

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(SequenceWriter, WritesEveryFileOfEveryFrame) {
  TempDir tmp("all");
  const fs::path dir = tmp / "seq";
  Trajectory traj = syntheticTrajectory();
  SequenceWriter w(syntheticSpec(dir), traj, {"asl", "tum"});
  EXPECT_EQ(w.formats(), (std::vector<std::string>{"asl", "tum"}));
  ASSERT_EQ(w.frameCount(), 3u);
  EXPECT_TRUE(fs::exists(dir / "meta.json")) << "meta.json is written by the constructor";
  for (size_t k = 0; k < 3; ++k) {
    // 8 ASL files (cam0, depth png + exr, normal, albedo, shading, nyu, instance) + 2 TUM files
    EXPECT_EQ(w.frameFiles(k).size(), 10u);
    EXPECT_FALSE(w.frameComplete(k));
    w.writeFrame(k, syntheticFrame(smallCamera(), static_cast<int>(k)));
    EXPECT_TRUE(w.frameComplete(k));
    for (const auto& p : w.frameFiles(k)) EXPECT_TRUE(fs::is_regular_file(p)) << p;
  }
  EXPECT_FALSE(fs::exists(dir / "cam0" / "data.csv")) << "index files only in finish()";
  // ASL cam0 and TUM rgb hold the same encoding: encoded once, identical bytes.
  const auto files = w.frameFiles(0);
  ASSERT_EQ(files[0].parent_path().filename(), "data");
  ASSERT_EQ(files[8].parent_path().filename(), "rgb");
  EXPECT_EQ(readBytes(files[0]), readBytes(files[8]));
  w.finish();
  for (const char* f :
       {"cam0/data.csv", "cam0/sensor.yaml", "depth0/data.csv", "normal0/data.csv",
        "albedo0/data.csv", "shading0/data.csv", "label0/data.csv",
        "state_groundtruth_estimate0/data.csv", "state_groundtruth_estimate0/sensor.yaml",
        "body.yaml", "rgb.txt", "depth.txt", "groundtruth.txt", "associations.txt",
        "accelerometer.txt", "camera.txt"})
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  for (const auto& [name, bytes] : readTree(dir)) EXPECT_FALSE(isTemporaryName(name)) << name;

  // A missing file makes the frame incomplete again; finish() then refuses.
  fs::remove(w.frameFiles(1)[3]);
  EXPECT_FALSE(w.frameComplete(1));
  EXPECT_TRUE(w.frameComplete(0));
  EXPECT_THROW(w.finish(), InputError);
}

// docs/output.md section 8: one rule. Frame k is complete when its files exist; the sequence is
// finished when every frame is complete and every sequence-level file exists (indexes, imu0/,
// boxes.json, events0/sensor.yaml).
TEST(SequenceWriter, FinishedMeansEveryFrameAndEverySequenceFile) {
  TempDir tmp("finished");
  const fs::path dir = tmp / "seq";
  const Trajectory traj = syntheticTrajectory();
  SequenceSpec spec = syntheticSpec(dir);
  spec.imu = spec.boxes = spec.events = true;
  SequenceWriter w(spec, traj, {"asl", "tum"});
  const auto seq_files = w.sequenceFiles();
  for (const char* f : {"cam0/data.csv", "rgb.txt", "imu0/data.csv", "imu0/data_noise_free.csv",
                        "imu0/biases.csv", "imu0/sensor.yaml", "boxes.json", "events0/sensor.yaml"})
    EXPECT_NE(std::find(seq_files.begin(), seq_files.end(), dir / f), seq_files.end()) << f;
  for (size_t k = 0; k < w.frameCount(); ++k)
    w.writeFrame(k, syntheticFrame(smallCamera(), static_cast<int>(k)));
  w.finish();
  EXPECT_FALSE(w.finished()) << "imu0/, boxes.json and events0/ are still missing";

  ImuOptions imu;
  imu.rate_hz = 200;
  const ImuSequence imu_seq = simulateImu(traj, imu);
  w.writeImu(imu_seq, imu, "test");
  EXPECT_EQ(readBytes(dir / "imu0/data.csv"), formatImuCsv(imu_seq.measured));
  EXPECT_EQ(readBytes(dir / "imu0/sensor.yaml"), formatImuSensorYaml(imu, "test"));
  Scene scene;
  w.writeBoxes(scene, {}, std::vector<std::vector<InstanceVisibility>>(traj.size()));
  EXPECT_TRUE(fs::is_regular_file(dir / "boxes.json"));
  EXPECT_FALSE(w.finished());

  // events0/: streamed sample by sample, complete (and the sequence finished) only once its
  // sensor.yaml, written last, is there
  EXPECT_FALSE(w.eventsComplete());
  {
    const auto events = w.openEvents(smallCamera());
    events->add(traj.poses[0].t_ns, ImageF(smallCamera().width, smallCamera().height, 1), {});
    EXPECT_FALSE(w.eventsComplete());
    EXPECT_FALSE(w.finished());
    events->finish(EventOptions{}, 1, 0);
  }
  EXPECT_TRUE(w.eventsComplete());
  EXPECT_TRUE(w.finished());
  EXPECT_TRUE(fs::is_regular_file(dir / "events0/events.txt"));
  EXPECT_TRUE(fs::is_regular_file(dir / "events0/events.h5"));
  EXPECT_EQ(readLines(dir / "events0/frames/data.csv").size(), 2u);
  for (const auto& [name, bytes] : readTree(dir)) EXPECT_FALSE(isTemporaryName(name)) << name;

  // any missing file undoes it
  fs::remove(dir / "imu0/biases.csv");
  EXPECT_FALSE(w.finished());
}

TEST(SequenceWriter, OnlyRequestedPassesAreWritten) {
  TempDir tmp("subset");
  const fs::path dir = tmp / "seq";
  PassMask mask = passMask(Pass::Rgb, Pass::Instance);
  writeSyntheticSequence(dir, {"asl"}, mask);
  EXPECT_TRUE(fs::exists(dir / "cam0" / "data.csv"));
  EXPECT_TRUE(fs::exists(dir / "label0" / "data.csv"));
  for (const char* absent : {"depth0", "normal0", "albedo0", "rgb", "depth", "rgb.txt"})
    EXPECT_FALSE(fs::exists(dir / absent)) << absent;
  // label0/data.csv lists the instance file when there is no NYU40 pass.
  auto lines = readLines(dir / "label0" / "data.csv");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_NE(lines[1].find("_instance.png"), std::string::npos) << lines[1];
}

TEST(SequenceWriter, UnknownFormatListsValidNames) {
  TempDir tmp("badformat");
  std::string msg = messageOf([&] {
    SequenceWriter w(syntheticSpec(tmp / "seq"), syntheticTrajectory(), {"asl", "kitti"});
  });
  EXPECT_NE(msg.find("--format"), std::string::npos) << msg;
  EXPECT_NE(msg.find("kitti"), std::string::npos) << msg;
  EXPECT_NE(msg.find("asl, tum"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(tmp / "seq")) << "nothing is written on bad input";
  EXPECT_THROW(SequenceWriter(syntheticSpec(tmp / "seq"), syntheticTrajectory(), {}), InputError);
  EXPECT_THROW(SequenceWriter(syntheticSpec(tmp / "seq"), syntheticTrajectory(), {"tum", "tum"}),
               InputError);
  EXPECT_EQ(parseFormatList(" asl, tum"), (std::vector<std::string>{"asl", "tum"}));
  EXPECT_THROW(parseFormatList("asl,"), InputError);
  EXPECT_NE(messageOf([] { parseFormatList("euroc"); }).find("valid formats: asl, tum"),
            std::string::npos);
}

TEST(SequenceWriter, BadTrajectoryIsRefusedBeforeWriting) {
  TempDir tmp("badtraj");
  Trajectory empty;
  EXPECT_THROW(SequenceWriter(syntheticSpec(tmp / "seq"), empty, {"asl"}), InputError);
  Trajectory back = syntheticTrajectory();
  back.poses[2].t_ns = back.poses[1].t_ns;
  EXPECT_NE(messageOf([&] {
              SequenceWriter w(syntheticSpec(tmp / "seq"), back, {"asl"});
            }).find("pose 2"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(tmp / "seq"));
}

TEST(SequenceWriter, UnwritableOutputFolderIsAnInputErrorAndNothingIsWritten) {
  TempDir tmp("unwritable");
  std::ofstream(tmp / "blocker") << "a file where a folder should be";
  const fs::path dir = tmp / "blocker" / "seq";
  std::string msg = messageOf([&] {
    SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"asl", "tum"});
  });
  EXPECT_NE(msg.find(dir.string()), std::string::npos) << "names the folder: " << msg;
  EXPECT_NE(msg.find("--out"), std::string::npos) << msg;
  auto tree = readTree(tmp.path());
  ASSERT_EQ(tree.size(), 1u) << "only the blocker file";
  EXPECT_EQ(tree.begin()->second, "a file where a folder should be");

  // Folder existing as a file.
  EXPECT_THROW(SequenceWriter(syntheticSpec(tmp / "blocker"), syntheticTrajectory(), {"asl"}),
               InputError);
}

TEST(SequenceWriter, ReadOnlyParentFolderIsAnInputError) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permission bits do not stop writes";
  TempDir tmp("readonly");
  fs::create_directories(tmp / "ro");
  fs::permissions(tmp / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(SequenceWriter(syntheticSpec(tmp / "ro" / "seq"), syntheticTrajectory(), {"asl"}),
               InputError);
  fs::permissions(tmp / "ro", fs::perms::owner_all);
  EXPECT_FALSE(fs::exists(tmp / "ro" / "seq"));
}

TEST(SequenceWriter, StaleTemporariesOfAKilledRunAreRemoved) {
  TempDir tmp("stale");
  const fs::path dir = tmp / "seq";
  fs::create_directories(dir / "cam0" / "data");
  std::ofstream(dir / "cam0" / "data" / "0000000000000000001.png.tmp-4242") << "half a png";
  std::ofstream(dir / "rgb.txt.tmp-17") << "half a list";
  std::ofstream(dir / "keep.txt") << "not ours to remove";
  SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"asl", "tum"});
  EXPECT_FALSE(fs::exists(dir / "cam0" / "data" / "0000000000000000001.png.tmp-4242"));
  EXPECT_FALSE(fs::exists(dir / "rgb.txt.tmp-17"));
  EXPECT_TRUE(fs::exists(dir / "keep.txt"));
}

TEST(SequenceWriter, ResumeSkipsCompleteFramesAndGivesTheSameBytes) {
  TempDir tmp("resume");
  writeSyntheticSequence(tmp / "a" / "seq", {"asl", "tum"});
  // A "killed" run: frame 0 written, frame 1 half written (one file), then a resume.
  const fs::path dir = tmp / "b" / "seq";
  {
    SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"asl", "tum"});
    w.writeFrame(0, syntheticFrame(smallCamera(), 0));
    fs::copy_file(tmp / "a" / "seq" / fs::relative(w.frameFiles(1)[0], dir), w.frameFiles(1)[0]);
  }
  SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"asl", "tum"});
  std::vector<size_t> redo;
  for (size_t k = 0; k < w.frameCount(); ++k)
    if (!w.frameComplete(k)) redo.push_back(k);
  EXPECT_EQ(redo, (std::vector<size_t>{1, 2}));
  for (size_t k : redo) w.writeFrame(k, syntheticFrame(smallCamera(), static_cast<int>(k)));
  w.finish();
  EXPECT_EQ(readTree(dir), readTree(tmp / "a" / "seq"));
}

TEST(SequenceWriter, SameFramesGiveIdenticalBytesWhateverTheOrderAndThreads) {
  TempDir tmp("determinism");
  writeSyntheticSequence(tmp / "a" / "seq", {"asl", "tum"});
  const fs::path dir = tmp / "b" / "seq";
  SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"tum", "asl"});
  std::vector<std::thread> threads;
  for (int k = 2; k >= 0; --k)  // reverse order, concurrently
    threads.emplace_back([&w, k] { w.writeFrame(k, syntheticFrame(smallCamera(), k)); });
  for (auto& t : threads) t.join();
  w.finish();
  auto a = readTree(tmp / "a" / "seq");
  auto b = readTree(dir);
  // Only meta.json may differ: it lists the formats in the order asked for.
  a.erase("meta.json");
  b.erase("meta.json");
  EXPECT_EQ(a.size(), 3u * 10u + 21u);  // frames + 15 ASL and 6 TUM index files
  EXPECT_TRUE(a == b);
  for (const auto& [name, bytes] : a) EXPECT_EQ(bytes, b[name]) << name;
}

TEST(SequenceWriter, MetaJsonStatesBothIntrinsicConventionsAndCallerFields) {
  TempDir tmp("meta");
  const fs::path dir = tmp / "living_room_01";
  SequenceWriter w(syntheticSpec(dir), syntheticTrajectory(), {"asl", "tum"});
  auto j = nlohmann::json::parse(readBytes(dir / "meta.json"));
  EXPECT_EQ(readBytes(dir / "meta.json"), w.metaJson());
  EXPECT_EQ(j["seed"], 42);
  EXPECT_EQ(j["command_line"], "interiornet generate --test");
  EXPECT_EQ(j["sequence"], "living_room_01");
  EXPECT_EQ(j["frame_count"], 3);
  EXPECT_EQ(j["formats"], nlohmann::json({"asl", "tum"}));
  EXPECT_EQ(j["passes"].size(), 8u);
  const auto& cam = j["camera"];
  EXPECT_EQ(cam["lens"], "pinhole");
  EXPECT_DOUBLE_EQ(cam["opencv"]["cx"].get<double>(), 11.5);
  EXPECT_DOUBLE_EQ(cam["opencv"]["cy"].get<double>(), 7.5);
  EXPECT_DOUBLE_EQ(cam["renderer"]["cx"].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(cam["opencv"]["fy"].get<double>(), 21.5);
  EXPECT_TRUE(cam["pixel_centre_convention"].is_string());
  for (double d : cam["distortion_coefficients"]) EXPECT_EQ(d, 0.0);
}

// --hdr: the linear radiance goes to cam0/data/<t>.exr; the PNGs show the display image.
TEST(SequenceWriter, RgbExrHoldsLinearRadianceWhilePngsShowTheDisplayImage) {
  TempDir tmp("rgb_exr");
  const fs::path dir = tmp / "seq";
  SequenceSpec spec = syntheticSpec(dir);
  spec.rgb_exr = true;
  const Trajectory traj = syntheticTrajectory();
  SequenceWriter w(spec, traj, {"asl", "tum"});
  const Frame f = syntheticFrame(smallCamera(), 0);
  ImageF display = f.rgb;
  for (float& v : display.data) v = 0.5f * v;  // e.g. -1 EV
  w.writeFrame(0, f, &display);
  const std::string t = aslStamp(traj.poses[0].t_ns);
  EXPECT_EQ(readExr(dir / "cam0/data" / (t + ".exr"), {"R", "G", "B"}), f.rgb);
  EXPECT_EQ(readPng8(dir / "cam0/data" / (t + ".png")), encodeSrgb8(display));
  EXPECT_EQ(readPng8(dir / "rgb" / (tumStamp(traj.poses[0].t_ns) + ".png")), encodeSrgb8(display));
  EXPECT_TRUE(w.frameComplete(0));
  fs::remove(dir / "cam0/data" / (t + ".exr"));
  EXPECT_FALSE(w.frameComplete(0)) << "the EXR is part of the frame";
  auto j = nlohmann::json::parse(readBytes(dir / "meta.json"));
  EXPECT_TRUE(j["encodings"].contains("rgb_exr"));

  spec.dir = tmp / "tum_only";
  EXPECT_NE(messageOf([&] { SequenceWriter(spec, traj, {"tum"}); }).find("--hdr"),
            std::string::npos);
  spec.passes = static_cast<PassMask>(Pass::DepthZ);
  EXPECT_NE(messageOf([&] { SequenceWriter(spec, traj, {"asl"}); }).find("--hdr"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(tmp / "tum_only"));
}

}  // namespace
}  // namespace inet
