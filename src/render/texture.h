#pragma once
// Image textures for materials: a float mip pyramid with trilinear, repeat-wrapped lookups, and a
// cache that loads each (file, encoding) once.
//
// Why hand-written: no Debian-packaged library does mip-mapped texture lookup for a CPU path
// tracer. OpenImageIO's TextureSystem does, but it is a heavy dependency (its own caching, tiling
// and thread machinery) for ~150 lines of code here. The lookup is called for every ray hit, so
// it allocates nothing and calls nothing indirectly.
//
// Conventions: uv follows OpenGL (u right, v up). Texel (x, y) of a level of size W x H (row 0 at
// the top of the image file) has its centre at u = (x + 0.5) / W, v = 1 - (y + 0.5) / H. Values
// are linear (sRGB-encoded files are decoded at load time), stored as 32-bit floats: memory is
// about 4/3 x W x H x channels x 4 bytes (the pyramid adds a third).
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace inet {

/// How 8- and 16-bit file values map to linear values.
enum class TextureEncoding {
  Srgb,    ///< sRGB-encoded colour (albedo maps): decoded with the exact sRGB EOTF
  Linear,  ///< data (roughness, normal maps): value / 255 or / 65535
};

/// A mip-mapped image with 1 (grey / data) or 3 (colour) float channels.
class Texture {
 public:
  /// Builds the mip pyramid of a linear float image with 1-4 channels; alpha is dropped (2 -> 1,
  /// 4 -> 3 channels). Each level halves width and height (floor, min 1) with a box filter that
  /// covers the source area exactly (3 taps for odd sizes), so every level has the mean of level 0.
  static Texture fromImage(ImageF linear);
  /// Loads a PNG (8 or 16 bit), JPEG or EXR (channels R, G, B or else Y) found by its content.
  /// EXR values are taken as linear whatever `enc`. Errors are InputError(where_file,
  /// where_field, "'path': problem") (the path is left out when it equals where_file).
  static Texture load(const std::string& path, TextureEncoding enc, const std::string& where_file,
                      const std::string& where_field);

  int width() const { return levels_[0].width; }
  int height() const { return levels_[0].height; }
  int channels() const { return channels_; }
  int levels() const { return static_cast<int>(levels_.size()); }
  /// Level `l` (0 = full size) as an image, for tests and debugging (copies).
  ImageF level(int l) const;

  /// Trilinearly filtered lookup with repeat wrapping; writes channels() floats to `out`.
  /// `footprint` is the width of the pixel's footprint in uv units (>= 0; NaN counts as 0): the
  /// mip level is log2(footprint * sqrt(width * height)), clamped to [0, levels - 1]. Non-finite
  /// uv reads u = 0 or v = 0.
  void lookup(const Eigen::Vector2f& uv, float footprint, float* out) const;
  /// RGB at uv (grey textures replicate their channel).
  Eigen::Vector3f rgb(const Eigen::Vector2f& uv, float footprint) const;
  /// Channel c (0..2) at uv; a grey texture returns its one channel for every c.
  float channel(const Eigen::Vector2f& uv, float footprint, int c) const;

  /// Bytes of texel memory held.
  size_t bytes() const { return texels_.size() * sizeof(float); }

 private:
  struct Level {
    int width = 0, height = 0;
    size_t offset = 0;  ///< first float of the level in texels_
  };
  Texture() = default;
  void bilinear(const Level& lv, float u, float v, float* out) const;

  int channels_ = 0;
  float log2_size_ = 0.0f;  ///< log2(sqrt(width * height)) of level 0
  std::vector<Level> levels_;
  std::vector<float> texels_;  ///< all levels, each row-major and interleaved
};

/// Loads each (path, encoding) once and hands out stable pointers, valid for the cache's lifetime.
/// get() is not thread-safe (fill the cache while building the scene); lookups on the returned
/// textures are const and may run from any thread.
class TextureCache {
 public:
  /// The texture of `path` decoded with `enc`, loaded on first use (see Texture::load for the
  /// errors; a failed load caches nothing). Paths are compared after weakly_canonical.
  const Texture* get(const std::string& path, TextureEncoding enc, const std::string& where_file,
                     const std::string& where_field);
  /// Number of textures held.
  size_t size() const { return textures_.size(); }
  /// Sum of Texture::bytes() over the cache.
  size_t bytes() const;

 private:
  std::map<std::pair<std::string, TextureEncoding>, std::unique_ptr<Texture>> textures_;
};

}  // namespace inet
