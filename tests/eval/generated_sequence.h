#pragma once
// A small sequence of the built-in room for the tests that evaluate a sequence folder: written
// by the real `interiornet generate` (tests/cli/cli_util.h runs it), so these tests read exactly
// what users get. 240x180 px, 2 spp, 6 frames and only the passes the evaluations read: about
// 3 s on one core.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "../cli/cli_util.h"
#include "core/image.h"
#include "core/image_io.h"
#include "core/rng.h"
#include "sensors/flow_io.h"

namespace inet::test {

inline constexpr int kSeqFrames = 6;

/// Generates the sequence under `out` and returns its folder (a failed run fails the test).
/// The exposure is fixed: the bounds of the odometry tests were measured with it, and the
/// photometric method is ill-conditioned on this view, so its figures move with the image gain
/// alone (auto exposure's +1 EV here: ATE 12.0 -> 7.4 mm, unaligned drift 19 -> 31 mm).
inline std::filesystem::path generateRoom(const std::filesystem::path& out) {
  const RunResult r = runInterinet(
      "generate --layout builtin:room --frames " + std::to_string(kSeqFrames) +
      " --width 240 --height 180 --fx 225 --fy 225 --spp 2 --passes rgb,depth,label,flow "
      "--format asl --exposure fixed --no-progress --out " +
      out.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out / "default_room" / "seq_000";
}

/// Every file under flow0/data/*.flo moved by (du, dv) pixels where it has flow: a flow that is
/// wrong by a known amount everywhere.
inline void shiftFlowFiles(const std::filesystem::path& seq, float du, float dv) {
  for (const auto& e : std::filesystem::directory_iterator(seq / "flow0" / "data")) {
    if (e.path().extension() != ".flo") continue;
    FlowField f = readFlo(e.path());
    for (size_t i = 0; i < f.flow.pixelCount(); ++i) {
      f.flow.data[2 * i] += du;
      f.flow.data[2 * i + 1] += dv;
    }
    writeFlo(e.path(), f);
  }
}

/// Every cam0 PNG with independent uniform noise in [-amplitude, amplitude] codes per pixel and
/// channel (clamped to 0..255), seeded by (frame stamp in ms, sample): deterministic whatever
/// order the folder lists its files in.
inline void addImageNoise(const std::filesystem::path& seq, int amplitude) {
  for (const auto& e : std::filesystem::directory_iterator(seq / "cam0" / "data")) {
    if (e.path().extension() != ".png") continue;
    const auto file = static_cast<uint32_t>(std::stoll(e.path().stem().string()) / 1'000'000);
    ImageU8 img = readPng8(e.path());
    for (size_t i = 0; i < img.data.size(); ++i) {
      CounterRng rng(7, RngStream::Sensor, file, static_cast<uint32_t>(i), 0);
      const int n = static_cast<int>(rng.nextU32() % (2 * amplitude + 1)) - amplitude;
      img.data[i] = static_cast<uint8_t>(std::clamp(img.data[i] + n, 0, 255));
    }
    writePng(e.path(), img);
  }
}

}  // namespace inet::test
