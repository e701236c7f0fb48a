// Optical flow files (sensors/flow_io.h): Middlebury .flo and KITTI 16-bit PNG round trips, the
// shared real-world samples decoded to the values in ../shared/data/formats/README.md, atomic
// writes, and malformed files rejected with the file and field named.
#include "sensors/flow_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "../temp_dir.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/rng.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// Flow in [-range, range] px with every 7th pixel invalid and every 5th occluded.
FlowField randomFlow(int W, int H, double range, uint64_t seed) {
  FlowField f{ImageF(W, H, 2, 0.f), ImageU8(W, H, 1, 0), ImageU8(W, H, 1, 0)};
  for (size_t i = 0; i < f.flow.pixelCount(); ++i) {
    CounterRng rng(seed, RngStream::Sensor, 0, static_cast<uint32_t>(i), 0);
    f.occluded.data[i] = i % 5 == 0;
    if (i % 7 == 0) continue;
    f.valid.data[i] = 1;
    f.flow.data[2 * i] = static_cast<float>(range * (2 * rng.uniform() - 1));
    f.flow.data[2 * i + 1] = static_cast<float>(range * (2 * rng.uniform() - 1));
  }
  return f;
}

fs::path sharedFlow(const std::string& name) {
  return fs::path(INET_SHARED_DIR) / "data" / "formats" / "flow" / name;
}

/// The InputError thrown by f, with file and field checked.
template <class F>
void expectInputError(F&& f, const fs::path& file, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "no InputError for field " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string()) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::string& s) {
  std::ofstream(p, std::ios::binary) << s;
}

TEST(FlowIo, FloRoundTripIsExact) {
  TempDir dir("flo");
  const FlowField f = randomFlow(37, 23, 300.0, 1);
  writeFlo(dir / "a.flo", f);
  const std::string bytes = bytesOf(dir / "a.flo");
  ASSERT_EQ(bytes.size(), 12u + 37 * 23 * 8);
  EXPECT_EQ(bytes.substr(0, 4), "PIEH");  // 202021.25f little-endian
  const FlowField g = readFlo(dir / "a.flo");
  EXPECT_EQ(g.flow, f.flow);  // float32 stored as is; invalid pixels read back as 0
  EXPECT_EQ(g.valid, f.valid);
  EXPECT_TRUE(g.occluded.empty()) << "neither format stores occlusion";
  // unknown pixels are the 1e10 sentinel on disk
  float u0;
  std::memcpy(&u0, bytes.data() + 12, 4);  // pixel 0 is invalid (0 % 7 == 0)
  EXPECT_EQ(u0, 1e10f);
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "no temporaries";
}

TEST(FlowIo, ExrRoundTripIsExact) {
  TempDir dir("flowexr");
  // smooth flow, like a rendered one (a camera motion): what compression can shrink
  FlowField f = randomFlow(64, 48, 1.0, 2);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t i = static_cast<size_t>(y) * 64 + x;
      if (!f.valid.data[i]) continue;  // unknown flow reads back as 0 from either file
      f.flow.data[2 * i] = 3.25f + 0.01f * x;
      f.flow.data[2 * i + 1] = -1.5f + 0.02f * y;
    }
  for (ExrCompression c : {ExrCompression::Zip, ExrCompression::Piz}) {
    writeFlowExr(dir / "a.exr", f, c);
    const FlowField g = readFlowExr(dir / "a.exr");
    EXPECT_EQ(g.flow, f.flow);  // invalid pixels (NaN on disk) read back as 0, as from .flo
    EXPECT_EQ(g.valid, f.valid);
  }
  writeFlo(dir / "a.flo", f);
  // float mantissas compress poorly; the saving on rendered flow is measured in bench/storage.sh
  EXPECT_LT(fs::file_size(dir / "a.exr"), fs::file_size(dir / "a.flo"));
  writeExr(dir / "z.exr", ImageF(4, 4, 1, 1.f), {"Z"});
  EXPECT_THROW(readFlowExr(dir / "z.exr"), InputError);
}

TEST(FlowIo, NonOccludedOnlyDropsOccludedPixels) {
  TempDir dir("flo_noc");
  const FlowField f = randomFlow(20, 10, 10.0, 2);
  writeFlo(dir / "noc.flo", f, true);
  writeKittiFlowPng(dir / "noc.png", f, true);
  for (const FlowField& g : {readFlo(dir / "noc.flo"), readKittiFlowPng(dir / "noc.png")})
    for (size_t i = 0; i < f.valid.pixelCount(); ++i)
      EXPECT_EQ(g.valid.data[i], f.valid.data[i] && !f.occluded.data[i]) << i;
  FlowField no_mask = f;
  no_mask.occluded = {};
  expectInputError([&] { writeFlo(dir / "x.flo", no_mask, true); }, dir / "x.flo", "occluded");
}

TEST(FlowIo, KittiRoundTripWithinQuantisationAndClamps) {
  TempDir dir("kitti");
  FlowField f = randomFlow(41, 17, 500.0, 3);
  // corners of the range: beyond +-512 px clamps to the codes 65535 and 0
  f.valid.at(1, 0) = f.valid.at(2, 0) = 1;
  f.flow.at(1, 0, 0) = 700.f;
  f.flow.at(1, 0, 1) = -900.f;
  f.flow.at(2, 0, 0) = 1.0f / 64 * 3;  // exactly representable
  f.flow.at(2, 0, 1) = -0.5f;
  writeKittiFlowPng(dir / "k.png", f);
  const ImageU16 raw = readPng16(dir / "k.png");
  ASSERT_EQ(raw.channels, 3);
  EXPECT_EQ(raw.at(0, 0, 0), 0);  // pixel 0 invalid: all zero
  EXPECT_EQ(raw.at(0, 0, 2), 0);
  EXPECT_EQ(raw.at(1, 0, 0), 65535);
  EXPECT_EQ(raw.at(1, 0, 1), 0);
  EXPECT_EQ(raw.at(2, 0, 0), 32768 + 3);
  EXPECT_EQ(raw.at(2, 0, 1), 32768 - 32);
  const FlowField g = readKittiFlowPng(dir / "k.png");
  EXPECT_EQ(g.valid, f.valid);
  EXPECT_FLOAT_EQ(g.flow.at(1, 0, 0), (65535 - 32768) / 64.f);
  EXPECT_FLOAT_EQ(g.flow.at(1, 0, 1), -512.f);
  EXPECT_EQ(g.flow.at(2, 0, 0), 3.f / 64);
  EXPECT_EQ(g.flow.at(2, 0, 1), -0.5f);
  double worst = 0;
  for (size_t i = 3; i < f.flow.pixelCount(); ++i)
    for (int c = 0; c < 2; ++c)
      worst = std::max(worst, std::abs(double{g.flow.data[2 * i + c]} - f.flow.data[2 * i + c]));
  EXPECT_LE(worst, 1.0 / 128 + 1e-6) << "rounding to the nearest 1/64 px";
  std::printf("KITTI round trip: largest error %.6f px (bound 1/128 = %.6f)\n", worst, 1.0 / 128);
}

TEST(FlowIo, DecodesTheShippedMiddleburySample) {
  const fs::path p = sharedFlow("middlebury_50x50.flo");
  if (!fs::exists(p)) GTEST_SKIP() << "needs ../shared/data/formats/flow/middlebury_50x50.flo";
  EXPECT_EQ(fs::file_size(p), 20012u);
  const FlowField f = readFlo(p);
  ASSERT_EQ(f.width(), 50);
  ASSERT_EQ(f.height(), 50);
  EXPECT_FLOAT_EQ(f.flow.at(0, 0, 0), -8.693274f);
  EXPECT_FLOAT_EQ(f.flow.at(0, 0, 1), -7.0224833f);
  float umin = 1e9f, umax = -1e9f, vmin = 1e9f, vmax = -1e9f;
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x) {
      ASSERT_EQ(f.valid.at(x, y), 1);
      umin = std::min(umin, f.flow.at(x, y, 0));
      umax = std::max(umax, f.flow.at(x, y, 0));
      vmin = std::min(vmin, f.flow.at(x, y, 1));
      vmax = std::max(vmax, f.flow.at(x, y, 1));
    }
  EXPECT_NEAR(umin, -10.2704, 1e-4);
  EXPECT_NEAR(umax, 0.6829, 1e-4);
  EXPECT_NEAR(vmin, -7.7472, 1e-4);
  EXPECT_NEAR(vmax, -1.2153, 1e-4);
  // and our writer reproduces the file byte for byte
  TempDir dir("flo_sample");
  writeFlo(dir / "copy.flo", f);
  EXPECT_EQ(bytesOf(dir / "copy.flo"), bytesOf(p));
}

TEST(FlowIo, DecodesTheShippedKittiSample) {
  const fs::path p = sharedFlow("kitti_sparse_50x50.png");
  if (!fs::exists(p)) GTEST_SKIP() << "needs ../shared/data/formats/flow/kitti_sparse_50x50.png";
  const FlowField f = readKittiFlowPng(p);
  ASSERT_EQ(f.width(), 50);
  ASSERT_EQ(f.height(), 50);
  int valid = 0, first = -1;
  for (int i = 0; i < 2500; ++i)
    if (f.valid.data[i]) {
      ++valid;
      if (first < 0) first = i;
    }
  EXPECT_EQ(valid, 39);
  EXPECT_EQ(first, 43 * 50 + 2) << "row 43, col 2";
  EXPECT_EQ(f.flow.at(2, 43, 0), -21.796875f);  // (31373 - 32768) / 64
  EXPECT_EQ(f.flow.at(2, 43, 1), -1.609375f);   // (32665 - 32768) / 64
  // every valid pixel re-encodes to the same codes (values are multiples of 1/64 px)
  TempDir dir("kitti_sample");
  writeKittiFlowPng(dir / "copy.png", f);
  const ImageU16 a = readPng16(p), b = readPng16(dir / "copy.png");
  for (int i = 0; i < 2500; ++i)
    if (a.data[3 * i + 2]) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(b.data[3 * i + c], a.data[3 * i + c]) << i;
    }
}

TEST(FlowIo, MalformedFloFilesNameFileAndField) {
  TempDir dir("flo_bad");
  const FlowField f = randomFlow(4, 3, 5.0, 4);
  writeFlo(dir / "good.flo", f);
  const std::string good = bytesOf(dir / "good.flo");
  auto variant = [&](const std::string& name, const std::string& bytes) {
    writeBytes(dir / name, bytes);
    return dir / name;
  };
  const fs::path short_header = variant("short.flo", good.substr(0, 7));
  expectInputError([&] { readFlo(short_header); }, short_header, "size");
  std::string bad_tag = good;
  bad_tag[0] = 'X';
  const fs::path tag = variant("tag.flo", bad_tag);
  expectInputError([&] { readFlo(tag); }, tag, "tag");
  std::string big_endian = good;  // the tag written big-endian is not accepted
  std::swap(big_endian[0], big_endian[3]);
  std::swap(big_endian[1], big_endian[2]);
  const fs::path be = variant("be.flo", big_endian);
  expectInputError([&] { readFlo(be); }, be, "tag");
  std::string neg_w = good;
  neg_w[7] = '\xff';  // width's top byte: negative
  const fs::path w = variant("w.flo", neg_w);
  expectInputError([&] { readFlo(w); }, w, "width");
  std::string zero_h = good;
  zero_h[8] = zero_h[9] = zero_h[10] = zero_h[11] = 0;
  const fs::path h = variant("h.flo", zero_h);
  expectInputError([&] { readFlo(h); }, h, "height");
  const fs::path trunc = variant("trunc.flo", good.substr(0, good.size() - 1));
  expectInputError([&] { readFlo(trunc); }, trunc, "size");
  const fs::path longer = variant("long.flo", good + "x");
  expectInputError([&] { readFlo(longer); }, longer, "size");
  expectInputError([&] { readFlo(dir / "missing.flo"); }, dir / "missing.flo", "");
  // a bad shape on write is an InputError naming the path, and leaves nothing behind
  FlowField one_channel = f;
  one_channel.flow = ImageF(4, 3, 1);
  expectInputError([&] { writeFlo(dir / "bad.flo", one_channel); }, dir / "bad.flo", "flow");
  EXPECT_FALSE(fs::exists(dir / "bad.flo"));
}

TEST(FlowIo, MalformedKittiFilesNameFileAndField) {
  TempDir dir("kitti_bad");
  writePng(dir / "grey16.png", ImageU16(5, 5, 1, 32768));
  expectInputError([&] { readKittiFlowPng(dir / "grey16.png"); }, dir / "grey16.png", "channels");
  writePng(dir / "rgb8.png", ImageU8(5, 5, 3, 1));
  EXPECT_THROW(readKittiFlowPng(dir / "rgb8.png"), InputError) << "8-bit is not a flow PNG";
  writeBytes(dir / "junk.png", "not a png at all");
  EXPECT_THROW(readKittiFlowPng(dir / "junk.png"), InputError);
}

}  // namespace
}  // namespace inet
