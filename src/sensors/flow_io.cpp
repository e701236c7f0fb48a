#include "sensors/flow_io.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

constexpr float kFloTag = 202021.25f;
constexpr float kFloUnknown = 1e10f;
constexpr double kFloUnknownThreshold = 1e9;
constexpr size_t kFloHeader = 12;
/// Larger sides are refused as corrupt headers rather than attempted as allocations.
constexpr int32_t kMaxSide = 1 << 20;
constexpr double kKittiScale = 64.0, kKittiOffset = 32768.0;

static_assert(std::endian::native == std::endian::little ||
              std::endian::native == std::endian::big);

template <typename T>
void putLe(std::string& buf, T value) {
  static_assert(sizeof(T) == 4);
  uint32_t bits = std::bit_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) buf.push_back(static_cast<char>((bits >> (8 * i)) & 0xffu));
}

template <typename T>
T getLe(const std::string& buf, size_t at) {
  static_assert(sizeof(T) == 4);
  uint32_t bits = 0;
  for (int i = 0; i < 4; ++i)
    bits |= static_cast<uint32_t>(static_cast<uint8_t>(buf[at + i])) << (8 * i);
  return std::bit_cast<T>(bits);
}

/// Is pixel i written as valid? Checks the masks' shapes (InputError naming the path).
class WriteMask {
 public:
  WriteMask(const fs::path& path, const FlowField& f, bool non_occluded_only)
      : f_(f), noc_(non_occluded_only) {
    const int W = f.flow.width, H = f.flow.height;
    if (f.flow.channels != 2 || W <= 0 || H <= 0)
      throw InputError(
          path.string(), "flow",
          fmt::format("needs a non-empty 2-channel image, got {}x{}x{}", W, H, f.flow.channels));
    if (f.valid.width != W || f.valid.height != H || f.valid.channels != 1)
      throw InputError(path.string(), "valid", "must be 1 channel of the flow's size");
    if (noc_ && (f.occluded.width != W || f.occluded.height != H || f.occluded.channels != 1))
      throw InputError(path.string(), "occluded",
                       "must be 1 channel of the flow's size to write non-occluded flow only");
  }
  bool operator()(size_t i) const {
    return f_.valid.data[i] != 0 && !(noc_ && f_.occluded.data[i] != 0);
  }

 private:
  const FlowField& f_;
  bool noc_;
};

FlowField emptyField(int W, int H) {
  return FlowField{ImageF(W, H, 2, 0.f), ImageU8(W, H, 1, 0), ImageU8()};
}

std::string readBinary(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path.string(), "", "is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
  std::string buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path.string(), "", "read failed");
  return buf;
}

}  // namespace

void writeFlo(const fs::path& path, const FlowField& flow, bool non_occluded_only) {
  const WriteMask valid(path, flow, non_occluded_only);
  const int W = flow.flow.width, H = flow.flow.height;
  std::string buf;
  buf.reserve(kFloHeader + flow.flow.pixelCount() * 8);
  putLe(buf, kFloTag);
  putLe(buf, static_cast<int32_t>(W));
  putLe(buf, static_cast<int32_t>(H));
  for (size_t i = 0; i < flow.flow.pixelCount(); ++i) {
    const bool ok = valid(i);
    putLe(buf, ok ? flow.flow.data[2 * i] : kFloUnknown);
    putLe(buf, ok ? flow.flow.data[2 * i + 1] : kFloUnknown);
  }
  writeTextAtomic(path, buf);
}

FlowField readFlo(const fs::path& path) {
  const std::string buf = readBinary(path);
  const std::string p = path.string();
  if (buf.size() < kFloHeader)
    throw InputError(p, "size",
                     fmt::format("{} bytes, shorter than the 12-byte header", buf.size()));
  const float tag = getLe<float>(buf, 0);
  if (tag != kFloTag)
    throw InputError(p, "tag",
                     fmt::format("is {} (bytes '{}'), expected 202021.25 ('PIEH'): not a "
                                 "little-endian Middlebury .flo file",
                                 tag, buf.substr(0, 4)));
  const int32_t W = getLe<int32_t>(buf, 4), H = getLe<int32_t>(buf, 8);
  if (W <= 0 || W > kMaxSide) throw InputError(p, "width", fmt::format("{} is out of range", W));
  if (H <= 0 || H > kMaxSide) throw InputError(p, "height", fmt::format("{} is out of range", H));
  const size_t want = kFloHeader + static_cast<size_t>(W) * H * 8;
  if (buf.size() != want)
    throw InputError(
        p, "size",
        fmt::format("{} bytes, expected {} for {}x{} (12 + 8 per pixel)", buf.size(), want, W, H));
  FlowField f = emptyField(W, H);
  for (size_t i = 0; i < f.flow.pixelCount(); ++i) {
    const float u = getLe<float>(buf, kFloHeader + 8 * i);
    const float v = getLe<float>(buf, kFloHeader + 8 * i + 4);
    const bool known = std::isfinite(u) && std::isfinite(v) &&
                       std::abs(u) <= kFloUnknownThreshold && std::abs(v) <= kFloUnknownThreshold;
    if (!known) continue;
    f.flow.data[2 * i] = u;
    f.flow.data[2 * i + 1] = v;
    f.valid.data[i] = 1;
  }
  return f;
}

void writeKittiFlowPng(const fs::path& path, const FlowField& flow, bool non_occluded_only,
                       int png_level) {
  const WriteMask valid(path, flow, non_occluded_only);
  const int W = flow.flow.width, H = flow.flow.height;
  auto encode = [](float f) {
    const double e = std::round(kKittiScale * f + kKittiOffset);
    return static_cast<uint16_t>(std::clamp(std::isfinite(e) ? e : 0.0, 0.0, 65535.0));
  };
  ImageU16 img(W, H, 3, 0);
  for (size_t i = 0; i < flow.flow.pixelCount(); ++i) {
    if (!valid(i)) continue;
    img.data[3 * i] = encode(flow.flow.data[2 * i]);
    img.data[3 * i + 1] = encode(flow.flow.data[2 * i + 1]);
    img.data[3 * i + 2] = 1;
  }
  writePng(path, img, png_level);  // atomic, deterministic (core/image_io.h)
}

FlowField readKittiFlowPng(const fs::path& path) {
  const ImageU16 img = readPng16(path);
  if (img.channels != 3)
    throw InputError(path.string(), "channels",
                     fmt::format("{} channel(s), a KITTI flow PNG is 16-bit RGB", img.channels));
  FlowField f = emptyField(img.width, img.height);
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    if (img.data[3 * i + 2] == 0) continue;
    f.flow.data[2 * i] = static_cast<float>((img.data[3 * i] - kKittiOffset) / kKittiScale);
    f.flow.data[2 * i + 1] = static_cast<float>((img.data[3 * i + 1] - kKittiOffset) / kKittiScale);
    f.valid.data[i] = 1;
  }
  return f;
}

void writeFlowExr(const fs::path& path, const FlowField& flow, ExrCompression compression) {
  const WriteMask valid(path, flow, false);
  ImageF uv(flow.flow.width, flow.flow.height, 2, 0.0f);
  for (size_t i = 0; i < flow.flow.pixelCount(); ++i) {
    const bool ok = valid(i);
    uv.data[2 * i] = ok ? flow.flow.data[2 * i] : std::nanf("");
    uv.data[2 * i + 1] = ok ? flow.flow.data[2 * i + 1] : std::nanf("");
  }
  writeExr(path, uv, {"U", "V"}, ExrOptions{compression});
}

FlowField readFlowExr(const fs::path& path) {
  const ImageF uv = readExr(path, {"U", "V"});
  FlowField f = emptyField(uv.width, uv.height);
  for (size_t i = 0; i < uv.pixelCount(); ++i) {
    const float u = uv.data[2 * i], v = uv.data[2 * i + 1];
    if (!std::isfinite(u) || !std::isfinite(v)) continue;
    f.flow.data[2 * i] = u;
    f.flow.data[2 * i + 1] = v;
    f.valid.data[i] = 1;
  }
  return f;
}

}  // namespace inet
