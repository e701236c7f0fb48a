#include "core/image_io.h"

#include <png.h>

#include <cstdio>  // before jpeglib.h, which needs FILE and size_t declared

#include <jerror.h>
#include <jpeglib.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/half.h>

#include <bit>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <set>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "core/text.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

// ---- PNG settings --------------------------------------------------------------------------
// zlib level 1 and the UP filter on every row. Measured on a 640x480 frame of the built-in room
// (docs/output.md section 9): against libpng's default (level 6, adaptive choice among all five
// filters per row) this writes the colour image ~6x faster (11 ms vs 67 ms at 64 spp) for a file
// ~5% larger, and depth ~7x faster for 60% more bytes (78 KB vs 49 KB). UP costs what SUB costs
// (one subtraction per byte), beat SUB on every pass and was within 3% of the smallest single
// filter; adaptive filtering cost 1.25-5x the time for 1-3% smaller files. Higher levels
// shrink colour, most of the bytes, by under 2%.
constexpr int kPngFilter = PNG_FILTER_UP;

/// The error_ptr handed to libpng: the message of the first error, then longjmp.
struct PngErrorSink {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngErrorSink*>(png_get_error_ptr(png));
  if (sink) std::snprintf(sink->message, sizeof sink->message, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}  // benign (e.g. unknown ancillary chunks)

/// Owns a FILE* and libpng's read or write structs so that every exit path releases them.
struct PngHandle {
  FILE* fp = nullptr;
  png_structp png = nullptr;
  png_infop info = nullptr;
  bool writing = false;
  PngErrorSink sink;

  ~PngHandle() {
    if (png && writing) png_destroy_write_struct(&png, info ? &info : nullptr);
    if (png && !writing) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (fp) std::fclose(fp);
  }
};

struct PngLayout {
  int width = 0, height = 0, channels = 0, bit_depth = 0;
  const uint8_t* pixels = nullptr;  ///< rows top to bottom, tightly packed
  int zlib_level = kDefaultPngLevel;  ///< writing only
};

// The functions that call setjmp hold no object with a destructor, so libpng's longjmp back into
// them skips none (the C++ rule for mixing longjmp and destructors). They only touch the handle,
// which lives in the caller's frame, and report failure through the return value.
bool encodePng(PngHandle& h, const PngLayout& l) {
  if (setjmp(png_jmpbuf(h.png))) return false;
  png_init_io(h.png, h.fp);
  int color = l.channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB;
  png_set_IHDR(h.png, h.info, static_cast<png_uint_32>(l.width), static_cast<png_uint_32>(l.height),
               l.bit_depth, color, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(h.png, l.zlib_level);
  png_set_filter(h.png, PNG_FILTER_TYPE_BASE, kPngFilter);
  png_write_info(h.png, h.info);
  if (l.bit_depth == 16 && std::endian::native == std::endian::little) png_set_swap(h.png);
  const size_t stride = static_cast<size_t>(l.width) * l.channels * (l.bit_depth / 8);
  for (int y = 0; y < l.height; ++y) png_write_row(h.png, l.pixels + stride * y);
  png_write_end(h.png, nullptr);
  return true;
}

void writePngAny(const fs::path& path, const PngLayout& l) {
  if (l.channels != 1 && l.channels != 3)
    throw InputError(path.string(), "",
                     "PNG writer takes 1 or 3 channels, image has " + std::to_string(l.channels));
  if (l.width < 1 || l.height < 1) throw InputError(path.string(), "", "image is empty");
  if (l.zlib_level < 0 || l.zlib_level > 9)
    throw InputError(path.string(), "png level", "must be 0..9, not " + std::to_string(l.zlib_level));
  writeFileAtomic(path, [&](const fs::path& tmp) {
    PngHandle h;
    h.writing = true;
    h.fp = std::fopen(tmp.c_str(), "wb");
    if (!h.fp)
      throw InputError(path.string(), "",
                       std::string("cannot open for writing: ") + std::strerror(errno));
    h.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &h.sink, onPngError, onPngWarning);
    if (h.png) h.info = png_create_info_struct(h.png);
    if (!h.png || !h.info) throw InputError(path.string(), "", "libpng: out of memory");
    if (!encodePng(h, l))
      throw InputError(path.string(), "", std::string("PNG write failed: ") + h.sink.message);
    FILE* fp = h.fp;
    h.fp = nullptr;
    // fclose flushes; a full disk shows up here rather than in fwrite.
    if (std::fclose(fp) != 0)
      throw InputError(path.string(), "", std::string("write failed: ") + std::strerror(errno));
  });
}

/// Reads the header, installs the transforms and fills `l` (except pixels).
bool readPngHeader(PngHandle& h, PngLayout& l, int& passes, int& file_bit_depth) {
  if (setjmp(png_jmpbuf(h.png))) return false;
  png_init_io(h.png, h.fp);
  png_read_info(h.png, h.info);
  file_bit_depth = png_get_bit_depth(h.png, h.info);
  int color = png_get_color_type(h.png, h.info);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(h.png);
  if (color == PNG_COLOR_TYPE_GRAY && file_bit_depth < 8) png_set_expand_gray_1_2_4_to_8(h.png);
  if (png_get_valid(h.png, h.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(h.png);
  if (file_bit_depth == 16 && std::endian::native == std::endian::little) png_set_swap(h.png);
  passes = png_set_interlace_handling(h.png);
  png_read_update_info(h.png, h.info);
  l.width = static_cast<int>(png_get_image_width(h.png, h.info));
  l.height = static_cast<int>(png_get_image_height(h.png, h.info));
  l.channels = png_get_channels(h.png, h.info);
  l.bit_depth = png_get_bit_depth(h.png, h.info);
  return true;
}

bool readPngRows(PngHandle& h, uint8_t* dst, size_t stride, int height, int passes) {
  if (setjmp(png_jmpbuf(h.png))) return false;
  // For interlaced files every pass refines the same full-size rows.
  for (int p = 0; p < passes; ++p)
    for (int y = 0; y < height; ++y) png_read_row(h.png, dst + stride * y, nullptr);
  png_read_end(h.png, nullptr);
  return true;
}

template <typename T>
Image<T> readPngAny(const fs::path& path) {
  constexpr int want_depth = sizeof(T) * 8;
  PngHandle h;
  h.fp = std::fopen(path.c_str(), "rb");
  if (!h.fp)
    throw InputError(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
  unsigned char sig[8] = {};
  if (std::fread(sig, 1, 8, h.fp) != 8 || png_sig_cmp(sig, 0, 8) != 0)
    throw InputError(path.string(), "", "not a PNG file");
  h.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &h.sink, onPngError, onPngWarning);
  if (h.png) h.info = png_create_info_struct(h.png);
  if (!h.png || !h.info) throw InputError(path.string(), "", "libpng: out of memory");
  png_set_sig_bytes(h.png, 8);
  PngLayout l;
  int passes = 1, file_depth = 0;
  if (!readPngHeader(h, l, passes, file_depth))
    throw InputError(path.string(), "", std::string("bad PNG: ") + h.sink.message);
  if ((want_depth == 16) != (file_depth == 16))
    throw InputError(path.string(), "",
                     "is a " + std::to_string(file_depth) + "-bit PNG, expected " +
                         (want_depth == 16 ? "16-bit" : "8-bit or less"));
  Image<T> img(l.width, l.height, l.channels);
  const size_t stride = static_cast<size_t>(l.width) * l.channels * sizeof(T);
  if (png_get_rowbytes(h.png, h.info) != stride)
    throw InputError(path.string(), "", "unexpected PNG row size");
  if (!readPngRows(h, reinterpret_cast<uint8_t*>(img.data.data()), stride, l.height, passes))
    throw InputError(path.string(), "", std::string("bad PNG: ") + h.sink.message);
  return img;
}

// ---- JPEG ----------------------------------------------------------------------------------

/// libjpeg's error manager plus the jump target and the first message. libjpeg's default
/// error_exit calls exit(); ours longjmps back into the reading function instead.
struct JpegErrorSink {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "unknown libjpeg error";
};

[[noreturn]] void onJpegError(j_common_ptr cinfo) {
  auto* sink = reinterpret_cast<JpegErrorSink*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, sink->message);
  std::longjmp(sink->jump, 1);
}

/// libjpeg only *warns* about missing or garbled entropy-coded data and then pads the image with
/// grey; those warnings are errors for us (a truncated texture must not render silently). Other
/// warnings (e.g. stray bytes before a marker, common in camera files) are ignored.
void onJpegMessage(j_common_ptr cinfo, int level) {
  if (level >= 0) return;  // trace messages
  switch (cinfo->err->msg_code) {
    case JWRN_JPEG_EOF:
    case JWRN_HIT_MARKER:
    case JWRN_HUFF_BAD_CODE:
    case JWRN_MUST_RESYNC:
      onJpegError(cinfo);
    default:
      break;
  }
}

/// Owns the FILE* and the decompressor so that every exit path releases them.
struct JpegHandle {
  FILE* fp = nullptr;
  jpeg_decompress_struct cinfo;
  JpegErrorSink sink;
  bool created = false;

  JpegHandle() { std::memset(&cinfo, 0, sizeof cinfo); }
  ~JpegHandle() {
    if (created) jpeg_destroy_decompress(&cinfo);
    if (fp) std::fclose(fp);
  }
};

// As for PNG: the functions calling setjmp hold no object with a destructor.
bool readJpegHeader(JpegHandle& h) {
  h.cinfo.err = jpeg_std_error(&h.sink.mgr);
  h.sink.mgr.error_exit = onJpegError;
  h.sink.mgr.emit_message = onJpegMessage;
  if (setjmp(h.sink.jump)) return false;
  jpeg_create_decompress(&h.cinfo);
  h.created = true;
  jpeg_stdio_src(&h.cinfo, h.fp);
  jpeg_read_header(&h.cinfo, TRUE);
  return true;
}

bool readJpegPixels(JpegHandle& h, uint8_t* dst, size_t stride) {
  if (setjmp(h.sink.jump)) return false;
  jpeg_start_decompress(&h.cinfo);
  while (h.cinfo.output_scanline < h.cinfo.output_height) {
    JSAMPROW row = dst + stride * h.cinfo.output_scanline;
    jpeg_read_scanlines(&h.cinfo, &row, 1);
  }
  jpeg_finish_decompress(&h.cinfo);
  return true;
}

/// Compresses `rows` (RGB or grey) into `fp`; false (message in the sink) on a libjpeg error.
/// As for reading: this function holds no object with a destructor across setjmp.
bool writeJpegPixels(FILE* fp, const ImageU8& img, int quality, JpegErrorSink& sink) {
  jpeg_compress_struct cinfo;
  std::memset(&cinfo, 0, sizeof cinfo);
  cinfo.err = jpeg_std_error(&sink.mgr);
  sink.mgr.error_exit = onJpegError;
  bool created = false;
  if (setjmp(sink.jump)) {
    if (created) jpeg_destroy_compress(&cinfo);
    return false;
  }
  jpeg_create_compress(&cinfo);
  created = true;
  jpeg_stdio_dest(&cinfo, fp);
  cinfo.image_width = static_cast<JDIMENSION>(img.width);
  cinfo.image_height = static_cast<JDIMENSION>(img.height);
  cinfo.input_components = img.channels;
  cinfo.in_color_space = img.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  const size_t stride = static_cast<size_t>(img.width) * img.channels;
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<uint8_t*>(img.data.data()) + stride * cinfo.next_scanline;
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  return true;
}

// ---- EXR -----------------------------------------------------------------------------------

void checkChannelNames(const fs::path& path, const std::vector<std::string>& names) {
  if (names.empty()) throw InputError(path.string(), "", "no EXR channel names given");
  std::set<std::string> seen;
  for (const auto& n : names)
    if (n.empty() || !seen.insert(n).second)
      throw InputError(path.string(), "", "EXR channel names must be non-empty and distinct");
}

}  // namespace

void writePng(const fs::path& path, const ImageU8& img, int zlib_level) {
  INET_CHECK(img.data.size() == img.pixelCount() * img.channels);
  writePngAny(path, {img.width, img.height, img.channels, 8, img.data.data(), zlib_level});
}

void writePng(const fs::path& path, const ImageU16& img, int zlib_level) {
  INET_CHECK(img.data.size() == img.pixelCount() * img.channels);
  writePngAny(path, {img.width, img.height, img.channels, 16,
                     reinterpret_cast<const uint8_t*>(img.data.data()), zlib_level});
}

ImageU8 readPng8(const fs::path& path) {
  return readPngAny<uint8_t>(path);
}
ImageU16 readPng16(const fs::path& path) {
  return readPngAny<uint16_t>(path);
}

ImageU8 readJpeg8(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path.string(), "", "is a folder, not a JPEG");
  JpegHandle h;
  h.fp = std::fopen(path.c_str(), "rb");
  if (!h.fp)
    throw InputError(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
  if (!readJpegHeader(h))
    throw InputError(path.string(), "", std::string("bad JPEG: ") + h.sink.message);
  switch (h.cinfo.jpeg_color_space) {
    case JCS_GRAYSCALE:
      h.cinfo.out_color_space = JCS_GRAYSCALE;
      break;
    case JCS_YCbCr:
    case JCS_RGB:
      h.cinfo.out_color_space = JCS_RGB;
      break;
    default:
      throw InputError(path.string(), "",
                       "CMYK/YCCK JPEGs are not supported (convert the file to RGB)");
  }
  jpeg_calc_output_dimensions(&h.cinfo);
  ImageU8 img(static_cast<int>(h.cinfo.output_width), static_cast<int>(h.cinfo.output_height),
              h.cinfo.output_components);
  if (!readJpegPixels(h, img.data.data(), static_cast<size_t>(img.width) * img.channels))
    throw InputError(path.string(), "", std::string("bad JPEG: ") + h.sink.message);
  return img;
}

void writeJpeg(const fs::path& path, const ImageU8& img, int quality) {
  INET_CHECK(img.data.size() == img.pixelCount() * img.channels);
  if (img.channels != 1 && img.channels != 3)
    throw InputError(path.string(), "", "a JPEG holds grey or RGB images (1 or 3 channels)");
  if (img.width < 1 || img.height < 1) throw InputError(path.string(), "", "image is empty");
  if (quality < 1 || quality > 100) throw InputError(path.string(), "quality", "must be 1..100");
  writeFileAtomic(path, [&](const fs::path& tmp) {
    FILE* fp = std::fopen(tmp.c_str(), "wb");
    if (!fp)
      throw InputError(path.string(), "", std::string("cannot write: ") + std::strerror(errno));
    JpegErrorSink sink;
    const bool ok = writeJpegPixels(fp, img, quality, sink);
    const bool closed = std::fclose(fp) == 0;
    if (!ok) throw InputError(path.string(), "", std::string("cannot write JPEG: ") + sink.message);
    if (!closed) throw InputError(path.string(), "", "cannot write JPEG: disk full?");
  });
}

const char* exrCompressionName(ExrCompression c) {
  switch (c) {
    case ExrCompression::None: return "none";
    case ExrCompression::Rle: return "rle";
    case ExrCompression::Zips: return "zips";
    case ExrCompression::Zip: return "zip";
    case ExrCompression::Piz: return "piz";
  }
  return "zip";
}

ExrCompression parseExrCompression(const std::string& name, const std::string& file,
                                   const std::string& field) {
  for (ExrCompression c : {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips,
                           ExrCompression::Zip, ExrCompression::Piz})
    if (name == exrCompressionName(c)) return c;
  throw InputError(file, field,
                   "'" + name + "' is not a lossless EXR compression (none, rle, zips, zip, piz)");
}

void writeExr(const fs::path& path, const ImageF& img,
              const std::vector<std::string>& channel_names, const ExrOptions& options) {
  INET_CHECK(img.data.size() == img.pixelCount() * img.channels);
  if (static_cast<int>(channel_names.size()) != img.channels)
    throw InputError(path.string(), "",
                     "EXR writer got " + std::to_string(channel_names.size()) +
                         " channel names for a " + std::to_string(img.channels) + "-channel image");
  if (img.width < 1 || img.height < 1) throw InputError(path.string(), "", "image is empty");
  checkChannelNames(path, channel_names);
  writeFileAtomic(path, [&](const fs::path& tmp) {
    try {
      Imf::Header header(img.width, img.height);
      switch (options.compression) {
        case ExrCompression::None: header.compression() = Imf::NO_COMPRESSION; break;
        case ExrCompression::Rle: header.compression() = Imf::RLE_COMPRESSION; break;
        case ExrCompression::Zips: header.compression() = Imf::ZIPS_COMPRESSION; break;
        case ExrCompression::Zip: header.compression() = Imf::ZIP_COMPRESSION; break;
        case ExrCompression::Piz: header.compression() = Imf::PIZ_COMPRESSION; break;
      }
      header.zipCompressionLevel() = 4;  // fixed, so a library default change cannot alter bytes
      // OpenEXR writes a channel only from a slice of its own type: half samples are converted
      // here (Imath's float -> half rounds to nearest even)
      std::vector<half> halves;
      if (options.half) halves.assign(img.data.begin(), img.data.end());
      const Imf::PixelType stored = options.half ? Imf::HALF : Imf::FLOAT;
      Imf::FrameBuffer fb;
      const size_t xs = (options.half ? sizeof(half) : sizeof(float)) * img.channels;
      const size_t ys = xs * img.width;
      for (int c = 0; c < img.channels; ++c) {
        header.channels().insert(channel_names[c], Imf::Channel(stored));
        // OpenEXR only reads through this pointer when writing.
        char* base = options.half
                         ? reinterpret_cast<char*>(halves.data() + c)
                         : reinterpret_cast<char*>(const_cast<float*>(img.data.data() + c));
        fb.insert(channel_names[c], Imf::Slice(stored, base, xs, ys));
      }
      // No worker threads: the caller parallelises over files and frames.
      Imf::OutputFile out(tmp.c_str(), header, 0);
      out.setFrameBuffer(fb);
      out.writePixels(img.height);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(path.string(), "", std::string("EXR write failed: ") + e.what());
    }
  });
}

std::vector<std::string> exrChannelNames(const fs::path& path) {
  try {
    Imf::InputFile in(path.c_str(), 0);
    std::vector<std::string> names;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
      names.emplace_back(it.name());
    return names;
  } catch (const std::exception& e) {
    throw InputError(path.string(), "", std::string("cannot read EXR: ") + e.what());
  }
}

ImageF readExr(const fs::path& path, const std::vector<std::string>& channel_names) {
  checkChannelNames(path, channel_names);
  std::string missing;
  try {
    Imf::InputFile in(path.c_str(), 0);
    const Imath::Box2i dw = in.header().dataWindow();
    const auto& channels = in.header().channels();
    for (const auto& n : channel_names)
      if (!channels.findChannel(n)) missing += (missing.empty() ? "" : ", ") + n;
    if (missing.empty()) {
      ImageF img(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1,
                 static_cast<int>(channel_names.size()));
      const size_t xs = sizeof(float) * img.channels;
      Imf::FrameBuffer fb;
      for (int c = 0; c < img.channels; ++c)
        fb.insert(channel_names[c],
                  Imf::Slice::Make(Imf::FLOAT, img.data.data() + c, dw, xs, xs * img.width));
      in.setFrameBuffer(fb);
      in.readPixels(dw.min.y, dw.max.y);
      return img;
    }
  } catch (const std::exception& e) {
    throw InputError(path.string(), "", std::string("cannot read EXR: ") + e.what());
  }
  std::string present;
  for (const auto& n : exrChannelNames(path)) present += (present.empty() ? "" : ", ") + n;
  throw InputError(path.string(), "", "EXR lacks channel(s) " + missing + "; it has: " + present);
}

Eigen::Vector3d meanLinearRgb(const fs::path& path) {
  const std::string ext = lowerExtension(path.string());
  const ImageU8 img = ext == ".jpg" || ext == ".jpeg" ? readJpeg8(path) : readPng8(path);
  double table[256];
  for (int i = 0; i < 256; ++i) table[i] = srgbEotf(i / 255.0);
  const int grey = img.channels < 3;  // 1 or 2 channels: grey (+ alpha)
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int k = 0; k < 3; ++k) sum[k] += table[img.at(x, y, grey ? 0 : k)];
  const double n = static_cast<double>(img.width) * img.height;
  return n > 0 ? Eigen::Vector3d(sum / n) : Eigen::Vector3d::Constant(0.5);
}

}  // namespace inet
