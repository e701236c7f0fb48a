#pragma once
// A plain interleaved image: width x height pixels of `channels` values of type T, row 0 at the
// top, pixel (x, y) covering [x, x+1) x [y, y+1) in the renderer's continuous coordinates.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/error.h"

namespace inet {

template <typename T>
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, int c, T fill = T{})
      : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, fill) {}

  size_t index(int x, int y, int c = 0) const {
    return (static_cast<size_t>(y) * width + x) * channels + c;
  }
  T& at(int x, int y, int c = 0) { return data[index(x, y, c)]; }
  const T& at(int x, int y, int c = 0) const { return data[index(x, y, c)]; }
  T* pixel(int x, int y) { return data.data() + index(x, y); }
  const T* pixel(int x, int y) const { return data.data() + index(x, y); }
  size_t pixelCount() const { return static_cast<size_t>(width) * height; }
  bool empty() const { return data.empty(); }
  bool operator==(const Image&) const = default;
};

/// Channels [first, first + count) of `img`, as an image of their own.
template <typename T>
Image<T> channelRange(const Image<T>& img, int first, int count) {
  INET_CHECK(first >= 0 && count >= 1 && first + count <= img.channels);
  Image<T> out(img.width, img.height, count);
  for (size_t i = 0; i < img.pixelCount(); ++i)
    for (int c = 0; c < count; ++c)
      out.data[i * count + c] = img.data[i * img.channels + first + c];
  return out;
}

using ImageF = Image<float>;
using ImageU8 = Image<uint8_t>;
using ImageU16 = Image<uint16_t>;

}  // namespace inet
