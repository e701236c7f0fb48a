#pragma once
// A minimal JPEG encoder for tests (the project itself only reads JPEG): writes interleaved 8-bit
// samples with libjpeg. Used by tests/dataset and tests/render.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include <jpeglib.h>  // after <cstdio>: it needs FILE and size_t

#include "core/image.h"

namespace inet::test {

/// Encodes `img` (1 channel = grey, 3 = RGB, 4 = CMYK) at `quality` into `path`.
inline void writeJpegForTest(const std::filesystem::path& path, const ImageU8& img,
                             int quality = 95) {
  FILE* fp = std::fopen(path.c_str(), "wb");
  ASSERT_NE(fp, nullptr) << path;
  jpeg_compress_struct cinfo;
  jpeg_error_mgr err;
  cinfo.err = jpeg_std_error(&err);  // exits on error: acceptable for a test's own encoder
  jpeg_create_compress(&cinfo);
  jpeg_stdio_dest(&cinfo, fp);
  cinfo.image_width = static_cast<JDIMENSION>(img.width);
  cinfo.image_height = static_cast<JDIMENSION>(img.height);
  cinfo.input_components = img.channels;
  cinfo.in_color_space = img.channels == 1 ? JCS_GRAYSCALE : img.channels == 3 ? JCS_RGB : JCS_CMYK;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  std::vector<uint8_t> row;
  while (cinfo.next_scanline < cinfo.image_height) {
    const uint8_t* src = img.pixel(0, static_cast<int>(cinfo.next_scanline));
    row.assign(src, src + static_cast<size_t>(img.width) * img.channels);
    JSAMPROW p = row.data();
    jpeg_write_scanlines(&cinfo, &p, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  std::fclose(fp);
}

}  // namespace inet::test
