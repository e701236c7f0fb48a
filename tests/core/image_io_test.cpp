// PNG and EXR round trips, byte order, determinism, JPEG reading and failure paths of
// dataset/image_io.
#include "core/image_io.h"

#include <gtest/gtest.h>

#include <set>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"
#include "../dataset/dataset_test_util.h"
#include "jpeg_test_util.h"

namespace inet {
namespace {

using test::readBytes;
using test::TempDir;
namespace fs = std::filesystem;

template <typename T>
Image<T> pattern(int w, int h, int c, int mul) {
  Image<T> img(w, h, c);
  for (size_t i = 0; i < img.data.size(); ++i)
    img.data[i] = static_cast<T>((i * mul + i / 7) & 0xffff);
  return img;
}

uint32_t be32(const std::string& s, size_t at) {
  auto b = [&](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>(s[at + i])); };
  return b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
}

/// The raw (filtered) scanlines of a PNG, by inflating its IDAT chunks with zlib directly.
std::string inflatedIdat(const std::string& png) {
  std::string z;
  for (size_t at = 8; at + 8 <= png.size();) {
    uint32_t len = be32(png, at);
    if (png.compare(at + 4, 4, "IDAT") == 0) z += png.substr(at + 8, len);
    at += 12 + len;
  }
  std::string out(1 << 16, '\0');
  uLongf out_len = out.size();
  EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(out.data()), &out_len,
                       reinterpret_cast<const Bytef*>(z.data()), z.size()),
            Z_OK);
  out.resize(out_len);
  return out;
}

TEST(ImageIo, Png8RoundTripGreyAndRgb) {
  TempDir dir("png8");
  for (int c : {1, 3}) {
    ImageU8 img = pattern<uint8_t>(37, 19, c, 31);
    auto p = dir / ("img" + std::to_string(c) + ".png");
    writePng(p, img);
    EXPECT_EQ(readPng8(p), img) << c << " channels";
  }
}

TEST(ImageIo, Png16RoundTripGreyAndRgb) {
  TempDir dir("png16");
  for (int c : {1, 3}) {
    ImageU16 img = pattern<uint16_t>(33, 21, c, 2741);
    img.data[0] = 65535;
    img.data[1] = 256;
    auto p = dir / ("img" + std::to_string(c) + ".png");
    writePng(p, img);
    EXPECT_EQ(readPng16(p), img) << c << " channels";
  }
}

TEST(ImageIo, Png16IsBigEndianOnDisk) {
  // Decoded without libpng: the IHDR says 16-bit grey and the first scanline holds 0x12 0x34.
  TempDir dir("png16be");
  ImageU16 img(1, 1, 1, 0x1234);
  writePng(dir / "one.png", img);
  std::string bytes = readBytes(dir / "one.png");
  ASSERT_EQ(bytes.compare(12, 4, "IHDR"), 0);
  EXPECT_EQ(static_cast<int>(bytes[24]), 16);  // bit depth
  EXPECT_EQ(static_cast<int>(bytes[25]), 0);   // colour type grey
  std::string raw = inflatedIdat(bytes);
  ASSERT_EQ(raw.size(), 3u);  // filter byte + one 2-byte sample
  // NONE (0), SUB (1) and UP (2) leave the first sample of the first row unchanged.
  EXPECT_GE(raw[0], 0);
  EXPECT_LE(raw[0], 2);
  EXPECT_EQ(static_cast<unsigned char>(raw[1]), 0x12);
  EXPECT_EQ(static_cast<unsigned char>(raw[2]), 0x34);
}

TEST(ImageIo, PngWritesAreDeterministicAndLeaveNoTemporary) {
  TempDir dir("pngdet");
  ImageU16 img = pattern<uint16_t>(64, 48, 3, 977);
  writePng(dir / "a.png", img);
  writePng(dir / "b.png", img);
  EXPECT_EQ(readBytes(dir / "a.png"), readBytes(dir / "b.png"));
  std::string bytes = readBytes(dir / "a.png");
  EXPECT_EQ(bytes.find("tIME"), std::string::npos) << "no time stamp chunk";
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    ++files;
    EXPECT_FALSE(isTemporaryName(e.path().filename().string()));
  }
  EXPECT_EQ(files, 2u);
}

TEST(ImageIo, PngWriteIntoUnwritablePlaceThrowsInputError) {
  TempDir dir("pngfail");
  std::ofstream(dir / "blocker") << "a file, not a folder";
  ImageU8 img(4, 4, 1, 7);
  try {
    writePng(dir / "blocker" / "x.png", img);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("blocker"), std::string::npos) << e.what();
  }
  ImageU8 two(4, 4, 2);
  EXPECT_THROW(writePng(dir / "two.png", two), InputError);  // 2 channels are not supported
  EXPECT_FALSE(std::filesystem::exists(dir / "two.png"));
}

TEST(ImageIo, PngWriteErrorInsideLibpngBecomesInputError) {
  // /dev/full accepts the open and fails every write: libpng's own error path (longjmp) runs.
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "/dev/full not available";
  // writeFileAtomic writes to "<path>.tmp-<pid>", so aim a symlink with that name at /dev/full.
  TempDir dir("pngfull");
  auto target = dir / "full.png";
  std::filesystem::path tmp = target;
  tmp += ".tmp-" + std::to_string(::getpid());
  std::filesystem::create_symlink("/dev/full", tmp);
  ImageU8 img(256, 256, 3);  // incompressible noise, far more than one stdio buffer
  uint32_t state = 12345;
  for (auto& v : img.data) v = static_cast<uint8_t>((state = state * 1664525u + 1013904223u) >> 24);
  try {
    writePng(target, img);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("full.png"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_FALSE(std::filesystem::exists(tmp)) << "the temporary is removed";
}

TEST(ImageIo, PngReadErrors) {
  TempDir dir("pngread");
  EXPECT_THROW(readPng8(dir / "missing.png"), InputError);
  std::ofstream(dir / "text.png") << "definitely not a png";
  EXPECT_THROW(readPng8(dir / "text.png"), InputError);

  writePng(dir / "d8.png", pattern<uint8_t>(40, 30, 3, 7));
  writePng(dir / "d16.png", pattern<uint16_t>(40, 30, 1, 7));
  EXPECT_THROW(readPng16(dir / "d8.png"), InputError) << "8-bit file read as 16-bit";
  EXPECT_THROW(readPng8(dir / "d16.png"), InputError) << "16-bit file read as 8-bit";

  // Truncated in the middle of the image data: libpng reports it through longjmp.
  std::string bytes = readBytes(dir / "d8.png");
  std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  try {
    readPng8(dir / "cut.png");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.png"), std::string::npos) << e.what();
  }
}

TEST(ImageIo, ExrRoundTripKeepsChannelOrder) {
  TempDir dir("exr");
  ImageF z(31, 17, 1);
  for (size_t i = 0; i < z.data.size(); ++i) z.data[i] = 0.25f + 0.001f * i;
  z.data[3] = 0.0f;
  writeExr(dir / "z.exr", z, {"Z"});
  EXPECT_EQ(readExr(dir / "z.exr", {"Z"}), z);
  EXPECT_EQ(exrChannelNames(dir / "z.exr"), std::vector<std::string>{"Z"});

  ImageF rgb(9, 5, 3);
  for (size_t i = 0; i < rgb.data.size(); ++i) rgb.data[i] = static_cast<float>(i % 3) + 0.5f * i;
  writeExr(dir / "rgb.exr", rgb, {"R", "G", "B"});
  EXPECT_EQ(readExr(dir / "rgb.exr", {"R", "G", "B"}), rgb);
  ImageF g = readExr(dir / "rgb.exr", {"G"});
  for (size_t p = 0; p < g.pixelCount(); ++p) EXPECT_EQ(g.data[p], rgb.data[3 * p + 1]);
}

// Every storage choice (docs/output.md section 9) is lossless where it must be: each EXR
// compression gives the floats back bit for bit, half floats keep 11 significant bits, and every
// PNG level gives the samples back while higher levels write fewer bytes.
TEST(ImageIo, EveryLosslessCompressionReadsBackExactly) {
  TempDir dir("exrcomp");
  ImageF noisy(48, 33, 3);
  uint32_t x = 12345;
  for (float& v : noisy.data) {
    x = x * 1664525u + 1013904223u;
    v = static_cast<float>(x >> 8) / (1u << 20);  // 0..16, all mantissa bits in use
  }
  std::set<std::string> sizes_differ;
  for (ExrCompression c : {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips,
                           ExrCompression::Zip, ExrCompression::Piz}) {
    const std::string name = exrCompressionName(c);
    EXPECT_EQ(parseExrCompression(name, "f", "x"), c);
    const fs::path p = dir / (name + ".exr");
    writeExr(p, noisy, {"R", "G", "B"}, ExrOptions{c});
    EXPECT_EQ(readExr(p, {"R", "G", "B"}), noisy) << name;
    sizes_differ.insert(std::to_string(fs::file_size(p)));
    writeExr(dir / "again.exr", noisy, {"R", "G", "B"}, ExrOptions{c});
    EXPECT_EQ(readBytes(p), readBytes(dir / "again.exr")) << name << " is not deterministic";
  }
  EXPECT_GE(sizes_differ.size(), 3u) << "the compressions must really differ";
  EXPECT_THROW(parseExrCompression("dwaa", "f", "storage.exr_compression"), InputError);

  writeExr(dir / "half.exr", noisy, {"R", "G", "B"}, ExrOptions{ExrCompression::Zip, true});
  const ImageF half = readExr(dir / "half.exr", {"R", "G", "B"});
  for (size_t i = 0; i < noisy.data.size(); ++i)
    EXPECT_LE(std::abs(half.data[i] - noisy.data[i]), std::abs(noisy.data[i]) * 0x1p-11f + 1e-7f)
        << i;
  EXPECT_LT(fs::file_size(dir / "half.exr"), fs::file_size(dir / "zip.exr") * 3 / 4);

  const ImageU16 img = pattern<uint16_t>(96, 64, 3, 3);
  size_t previous = 0;
  for (int level : {0, 1, 9}) {
    const fs::path p = dir / ("l" + std::to_string(level) + ".png");
    writePng(p, img, level);
    EXPECT_EQ(readPng16(p), img) << level;
    if (previous) {
      EXPECT_LT(fs::file_size(p), previous) << "level " << level;
    }
    previous = fs::file_size(p);
  }
  EXPECT_THROW(writePng(dir / "bad.png", img, 10), InputError);
}

TEST(ImageIo, ExrIsDeterministicAndReportsMissingChannels) {
  TempDir dir("exrdet");
  ImageF z(64, 40, 1, 1.5f);
  writeExr(dir / "a.exr", z, {"Z"});
  writeExr(dir / "b.exr", z, {"Z"});
  EXPECT_EQ(readBytes(dir / "a.exr"), readBytes(dir / "b.exr"));
  try {
    readExr(dir / "a.exr", {"R"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("lacks channel(s) R"), std::string::npos) << msg;
    EXPECT_NE(msg.find("it has: Z"), std::string::npos) << msg;
  }
  EXPECT_THROW(writeExr(dir / "c.exr", z, {"R", "G"}), InputError);
  EXPECT_THROW(readExr(dir / "missing.exr", {"Z"}), InputError);
  std::ofstream(dir / "junk.exr") << "junk";
  EXPECT_THROW(readExr(dir / "junk.exr", {"Z"}), InputError);
}

/// A smooth colour (or grey) gradient, at most 243 for w <= 40, h <= 24: JPEG at quality 95
/// reproduces it within a few codes.
ImageU8 gradient(int w, int h, int c) {
  ImageU8 img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k)
        img.at(x, y, k) = static_cast<uint8_t>(20 + 3 * x + 2 * y + 30 * k);
  return img;
}

/// Largest absolute difference between two images of equal shape.
int maxAbsDiff(const ImageU8& a, const ImageU8& b) {
  int worst = 0;
  for (size_t i = 0; i < a.data.size(); ++i)
    worst = std::max(worst, std::abs(a.data[i] - b.data[i]));
  return worst;
}

/// Message of the InputError thrown by `f`, or "" when nothing was thrown.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

TEST(ImageIo, JpegReadsColourAndGreyWithinJpegTolerance) {
  TempDir dir("jpeg");
  for (int c : {3, 1}) {
    const ImageU8 src = gradient(40, 24, c);
    const auto p = dir / ("g" + std::to_string(c) + ".jpg");
    test::writeJpegForTest(p, src, 95);
    const ImageU8 img = readJpeg8(p);
    ASSERT_EQ(img.width, 40);
    ASSERT_EQ(img.height, 24);
    ASSERT_EQ(img.channels, c);
    // Quality 95 on a smooth ramp: a few codes at most (chroma subsampling included), and the
    // mean error is well under one code. A transposed or channel-swapped read fails both.
    EXPECT_LE(maxAbsDiff(img, src), 6) << c << " channels";
    double sum = 0.0;
    for (size_t i = 0; i < img.data.size(); ++i) sum += std::abs(img.data[i] - src.data[i]);
    EXPECT_LT(sum / img.data.size(), 1.0) << c << " channels";
  }
}

TEST(ImageIo, JpegReadsRealPhotographFromShared) {
  const auto p = std::filesystem::path(INET_SHARED_DIR) /
                 "data/scenes/bitterli_living_room_mitsuba/textures/wood.jpg";
  if (!std::filesystem::exists(p))
    GTEST_SKIP() << "needs ../shared/data/scenes/bitterli_living_room_mitsuba/textures/wood.jpg";
  const ImageU8 img = readJpeg8(p);
  EXPECT_GT(img.width, 0);
  EXPECT_GT(img.height, 0);
  EXPECT_EQ(img.channels, 3);
  EXPECT_EQ(img.data.size(), img.pixelCount() * 3);
}

TEST(ImageIo, JpegReadErrorsNameTheFile) {
  TempDir dir("jpegerr");
  std::string msg = errorOf([&] { readJpeg8(dir / "missing.jpg"); });
  EXPECT_NE(msg.find("missing.jpg"), std::string::npos) << msg;

  std::ofstream(dir / "text.jpg") << "definitely not a jpeg";
  msg = errorOf([&] { readJpeg8(dir / "text.jpg"); });
  EXPECT_NE(msg.find("text.jpg"), std::string::npos) << msg;

  std::filesystem::create_directories(dir / "folder.jpg");
  msg = errorOf([&] { readJpeg8(dir / "folder.jpg"); });
  EXPECT_NE(msg.find("folder.jpg"), std::string::npos) << msg;

  // Truncated inside the entropy-coded data: libjpeg only warns and pads with grey; we refuse.
  test::writeJpegForTest(dir / "full.jpg", pattern<uint8_t>(64, 64, 3, 37), 95);
  const std::string bytes = readBytes(dir / "full.jpg");
  std::ofstream(dir / "cut.jpg", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  msg = errorOf([&] { readJpeg8(dir / "cut.jpg"); });
  EXPECT_NE(msg.find("cut.jpg"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bad JPEG"), std::string::npos) << msg;
  // Header only (cut before the scan): the error comes from libjpeg's error_exit path.
  std::ofstream(dir / "head.jpg", std::ios::binary) << bytes.substr(0, 40);
  msg = errorOf([&] { readJpeg8(dir / "head.jpg"); });
  EXPECT_NE(msg.find("head.jpg"), std::string::npos) << msg;

  ImageU8 cmyk(8, 8, 4, 100);
  test::writeJpegForTest(dir / "cmyk.jpg", cmyk, 90);
  msg = errorOf([&] { readJpeg8(dir / "cmyk.jpg"); });
  EXPECT_NE(msg.find("cmyk.jpg"), std::string::npos) << msg;
  EXPECT_NE(msg.find("CMYK"), std::string::npos) << msg;
}

}  // namespace
}  // namespace inet
