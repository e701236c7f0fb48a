#include "render/texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/color.h"
#include "core/image_io.h"

namespace fs = std::filesystem;

namespace inet {
namespace {


/// The source texels one destination texel of a halved level averages along one axis.
struct Taps {
  int first = 0;
  int count = 0;
  std::array<double, 3> weight{};
};

/// Destination texel i of m covers source interval [i n/m, (i+1) n/m); each source texel j
/// (covering [j, j+1)) gets weight overlap / (n/m). Working in units of 1/m keeps the overlaps
/// integers, so the weights are exact and every source texel's weights sum to m/n over the
/// destination: the level mean is preserved. Even n gives [1/2, 1/2]; odd n up to 3 taps.
std::vector<Taps> boxTaps(int n, int m) {
  std::vector<Taps> taps(m);
  for (int i = 0; i < m; ++i) {
    const int64_t a = static_cast<int64_t>(i) * n, b = a + n;  // in units of 1/m
    Taps& t = taps[i];
    t.first = static_cast<int>(a / m);
    for (int64_t j = t.first; j * m < b; ++j) {
      const int64_t overlap = std::min(b, (j + 1) * m) - std::max(a, j * m);
      INET_CHECK(t.count < 3);
      t.weight[t.count++] = static_cast<double>(overlap) / n;
    }
  }
  return taps;
}

/// Wraps a texture coordinate into [0, 1) (repeat); non-finite values read 0.
inline float wrap01(float u) {
  if (!std::isfinite(u)) return 0.0f;
  float f = u - std::floor(u);
  return f < 1.0f ? f : 0.0f;  // u a tiny negative number rounds to 1
}

}  // namespace

Texture Texture::fromImage(ImageF linear) {
  INET_CHECK(linear.width > 0 && linear.height > 0);
  INET_CHECK(linear.channels >= 1 && linear.channels <= 4);
  INET_CHECK(linear.data.size() == linear.pixelCount() * linear.channels);
  Texture t;
  t.channels_ = linear.channels >= 3 ? 3 : 1;
  const int C = t.channels_;
  const int src_c = linear.channels;

  // Sizes first, so the texel vector is allocated once.
  size_t total = 0;
  for (int w = linear.width, h = linear.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
    t.levels_.push_back({w, h, total});
    total += static_cast<size_t>(w) * h * C;
    if (w == 1 && h == 1) break;
  }
  t.texels_.resize(total);

  // Level 0, without the alpha channel.
  if (src_c == C) {
    std::copy(linear.data.begin(), linear.data.end(), t.texels_.begin());
  } else {
    for (size_t p = 0; p < linear.pixelCount(); ++p)
      for (int c = 0; c < C; ++c) t.texels_[p * C + c] = linear.data[p * src_c + c];
  }
  std::vector<float>().swap(linear.data);  // free the source before the pyramid grows

  for (size_t l = 1; l < t.levels_.size(); ++l) {
    const Level& src = t.levels_[l - 1];
    const Level& dst = t.levels_[l];
    const std::vector<Taps> tx = boxTaps(src.width, dst.width);
    const std::vector<Taps> ty = boxTaps(src.height, dst.height);
    const float* s = t.texels_.data() + src.offset;
    float* d = t.texels_.data() + dst.offset;
    for (int y = 0; y < dst.height; ++y) {
      for (int x = 0; x < dst.width; ++x) {
        double acc[3] = {0.0, 0.0, 0.0};
        for (int j = 0; j < ty[y].count; ++j) {
          const float* row = s + static_cast<size_t>(ty[y].first + j) * src.width * C;
          for (int i = 0; i < tx[x].count; ++i) {
            const double w = ty[y].weight[j] * tx[x].weight[i];
            const float* p = row + static_cast<size_t>(tx[x].first + i) * C;
            for (int c = 0; c < C; ++c) acc[c] += w * p[c];
          }
        }
        float* out = d + (static_cast<size_t>(y) * dst.width + x) * C;
        for (int c = 0; c < C; ++c) out[c] = static_cast<float>(acc[c]);
      }
    }
  }
  t.log2_size_ =
      0.5f *
      static_cast<float>(std::log2(static_cast<double>(t.levels_[0].width) * t.levels_[0].height));
  return t;
}

Texture Texture::load(const std::string& path, TextureEncoding enc, const std::string& where_file,
                      const std::string& where_field) {
  const std::string what = where_file == path ? std::string() : "'" + path + "': ";
  auto fail = [&](const std::string& problem) {
    return InputError(where_file, where_field, what + problem);
  };
  std::error_code ec;
  if (!fs::exists(path, ec)) throw fail("texture file not found");
  if (fs::is_directory(path, ec)) throw fail("is a folder, expected an image file");
  unsigned char head[32] = {};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fail("cannot open");
    in.read(reinterpret_cast<char*>(head), sizeof head);
  }
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  const bool is_png = std::memcmp(head, kPng, 8) == 0;
  const bool is_jpeg = head[0] == 0xff && head[1] == 0xd8 && head[2] == 0xff;
  const bool is_exr = std::memcmp(head, kExr, 4) == 0;
  if (!is_png && !is_jpeg && !is_exr)
    throw fail("unsupported image format (expected PNG, JPEG or EXR)");

  try {
    if (is_exr) {
      const std::vector<std::string> names = exrChannelNames(path);
      auto has = [&](const char* n) {
        return std::find(names.begin(), names.end(), n) != names.end();
      };
      if (has("R") && has("G") && has("B")) return fromImage(readExr(path, {"R", "G", "B"}));
      if (has("Y")) return fromImage(readExr(path, {"Y"}));
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw fail("EXR texture needs channels R, G, B or Y; it has: " + list);
    }
    // IHDR is the first chunk of every PNG; its bit depth is byte 24 of the file.
    if (is_png && head[24] == 16) {
      const ImageU16 raw = readPng16(path);
      std::vector<float> table(65536);
      for (size_t i = 0; i < table.size(); ++i) {
        const double c = static_cast<double>(i) / 65535.0;
        table[i] = static_cast<float>(enc == TextureEncoding::Srgb ? srgbEotf(c) : c);
      }
      ImageF img(raw.width, raw.height, raw.channels);
      for (size_t i = 0; i < raw.data.size(); ++i) img.data[i] = table[raw.data[i]];
      return fromImage(std::move(img));
    }
    const ImageU8 raw = is_png ? readPng8(path) : readJpeg8(path);
    float table[256];
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      table[i] = static_cast<float>(enc == TextureEncoding::Srgb ? srgbEotf(c) : c);
    }
    ImageF img(raw.width, raw.height, raw.channels);
    for (size_t i = 0; i < raw.data.size(); ++i) img.data[i] = table[raw.data[i]];
    return fromImage(std::move(img));
  } catch (const InputError& e) {
    if (e.file() == where_file && e.field() == where_field) throw;  // already ours
    throw fail(e.problem());  // the image readers name the path as the file
  }
}

ImageF Texture::level(int l) const {
  INET_CHECK(l >= 0 && l < levels());
  const Level& lv = levels_[l];
  ImageF img(lv.width, lv.height, channels_);
  std::copy_n(texels_.begin() + static_cast<std::ptrdiff_t>(lv.offset), img.data.size(),
              img.data.begin());
  return img;
}

void Texture::bilinear(const Level& lv, float u, float v, float* out) const {
  // u, v in [0, 1). Continuous texel coordinates with texel centres at integers.
  const float x = u * static_cast<float>(lv.width) - 0.5f;
  const float y = (1.0f - v) * static_cast<float>(lv.height) - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  const float fx = x - x0f, fy = y - y0f;
  int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);  // in [-1, size - 1]
  if (x0 < 0) x0 += lv.width;
  if (y0 < 0) y0 += lv.height;
  const int x1 = x0 + 1 < lv.width ? x0 + 1 : 0;
  const int y1 = y0 + 1 < lv.height ? y0 + 1 : 0;
  const int C = channels_;
  const float* base = texels_.data() + lv.offset;
  const float* p00 = base + (static_cast<size_t>(y0) * lv.width + x0) * C;
  const float* p10 = base + (static_cast<size_t>(y0) * lv.width + x1) * C;
  const float* p01 = base + (static_cast<size_t>(y1) * lv.width + x0) * C;
  const float* p11 = base + (static_cast<size_t>(y1) * lv.width + x1) * C;
  // a + f (b - a): exactly a at f = 0, so a lookup at a texel centre returns the texel.
  for (int c = 0; c < C; ++c) {
    const float top = p00[c] + fx * (p10[c] - p00[c]);
    const float bottom = p01[c] + fx * (p11[c] - p01[c]);
    out[c] = top + fy * (bottom - top);
  }
}

void Texture::lookup(const Eigen::Vector2f& uv, float footprint, float* out) const {
  const float u = wrap01(uv.x()), v = wrap01(uv.y());
  const int last = levels() - 1;
  float lod = 0.0f;
  if (footprint > 0.0f)  // false for 0 and NaN
    lod = std::clamp(std::log2(footprint) + log2_size_, 0.0f, static_cast<float>(last));
  const int l0 = static_cast<int>(lod);
  const float t = lod - static_cast<float>(l0);
  bilinear(levels_[l0], u, v, out);
  if (t > 0.0f && l0 < last) {
    float next[3];
    bilinear(levels_[l0 + 1], u, v, next);
    for (int c = 0; c < channels_; ++c) out[c] += t * (next[c] - out[c]);
  }
}

Eigen::Vector3f Texture::rgb(const Eigen::Vector2f& uv, float footprint) const {
  float v[3];
  lookup(uv, footprint, v);
  return channels_ == 1 ? Eigen::Vector3f::Constant(v[0]) : Eigen::Vector3f(v[0], v[1], v[2]);
}

float Texture::channel(const Eigen::Vector2f& uv, float footprint, int c) const {
  INET_CHECK(c >= 0 && c < 3);
  float v[3];
  lookup(uv, footprint, v);
  return channels_ == 1 ? v[0] : v[c];
}

const Texture* TextureCache::get(const std::string& path, TextureEncoding enc,
                                 const std::string& where_file, const std::string& where_field) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  auto key = std::make_pair(ec ? path : canonical.string(), enc);
  auto it = textures_.find(key);
  if (it == textures_.end())
    it = textures_
             .emplace(std::move(key),
                      std::make_unique<Texture>(Texture::load(path, enc, where_file, where_field)))
             .first;
  return it->second.get();
}

size_t TextureCache::bytes() const {
  size_t sum = 0;
  for (const auto& [key, tex] : textures_) sum += tex->bytes();
  return sum;
}

}  // namespace inet
