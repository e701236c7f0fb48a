#pragma once
// Image file I/O for the dataset writers: PNG (8- and 16-bit, grey or RGB) through libpng and
// single-part scanline EXR (32-bit float channels) through OpenEXR; JPEG reading (textures)
// through libjpeg.
//
// Every writer:
//  - is atomic: it writes "<path>.tmp-<pid>" and renames it into place (core/atomic_file.h), so a
//    file under its final name is always complete;
//  - is deterministic: the same image gives the same bytes (no time chunks, no tool version, no
//    thread-dependent compression);
//  - reports failure (unwritable folder, full disk, bad image shape) as InputError naming the path.
// Readers throw InputError naming the file for a missing, truncated or unexpected file.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace inet {

/// The zlib level the PNG writers use unless told otherwise (image_io.cpp says why 1).
inline constexpr int kDefaultPngLevel = 1;

/// Writes an 8-bit PNG: 1 channel = grey, 3 channels = RGB. `zlib_level` 0..9 (0 = stored, 9 =
/// smallest): every level is lossless, higher ones only trade time for bytes.
void writePng(const std::filesystem::path& path, const ImageU8& img,
              int zlib_level = kDefaultPngLevel);
/// Writes a 16-bit PNG: 1 channel = grey, 3 channels = RGB. Samples are stored big-endian as the
/// PNG standard requires; the caller passes native uint16 values.
void writePng(const std::filesystem::path& path, const ImageU16& img,
              int zlib_level = kDefaultPngLevel);

/// Reads an 8-bit PNG. Palette images are expanded to RGB and grey images below 8 bits to 8 bits;
/// an alpha channel is kept (2 or 4 channels). A 16-bit file is an error (use readPng16): depth
/// and normal images must never be silently truncated.
ImageU8 readPng8(const std::filesystem::path& path);
/// Reads a 16-bit PNG (grey, grey+alpha, RGB or RGBA) into native uint16 values. An 8-bit file is
/// an error.
ImageU16 readPng16(const std::filesystem::path& path);

/// Reads a baseline or progressive JPEG: grey files give 1 channel, colour (YCbCr or RGB) files 3
/// channels of 8-bit values as stored (sRGB-encoded for ordinary photographs). CMYK/YCCK files, a
/// missing, truncated or corrupt file are InputErrors naming the path; libjpeg never exits.
ImageU8 readJpeg8(const std::filesystem::path& path);

/// The mean colour of an 8-bit PNG or JPEG (by extension: .jpg/.jpeg in any case, else PNG) as
/// linear RGB: sRGB-decoded, a grey image's one channel repeated, alpha ignored. Throws as the
/// readers. For statistics of textures (how bright or warm a material looks).
Eigen::Vector3d meanLinearRgb(const std::filesystem::path& path);

/// Writes a baseline JPEG (1 channel grey, 3 channels RGB, sRGB-encoded values as given) at
/// `quality` 1..100, atomically. InputError naming the path for other channel counts or an
/// unwritable file.
void writeJpeg(const std::filesystem::path& path, const ImageU8& img, int quality = 90);

/// The lossless EXR compressions (OpenEXR's lossy B44, DWA and PXR24 are left out on purpose:
/// ground truth must read back exactly). Zip: deflate over 16 scanlines (the default); Zips: one
/// scanline per block; Piz: wavelet + Huffman, often smallest on noisy colour; Rle: run lengths.
enum class ExrCompression { None, Rle, Zips, Zip, Piz };
/// "none", "rle", "zips", "zip", "piz".
const char* exrCompressionName(ExrCompression c);
/// The compression of a name as exrCompressionName gives it; InputError(file, field) otherwise,
/// listing the valid names.
ExrCompression parseExrCompression(const std::string& name, const std::string& file,
                                   const std::string& field);

struct ExrOptions {
  ExrCompression compression = ExrCompression::Zip;
  /// Store 16-bit HALF samples instead of 32-bit FLOAT: 11 significant bits (relative error
  /// <= 2^-11, values up to 65504). Exact enough for rendered radiance, whose Monte Carlo noise
  /// is far larger; never for depth or flow, which are ground truth.
  bool half = false;
};

/// Writes a scanline EXR with one channel per entry of `channel_names` (their count must equal
/// img.channels), by default 32-bit FLOAT with ZIP compression (16 scanlines per block). EXR
/// stores channels sorted by name; readExr puts them back in the order asked for. Typical
/// names: {"Z"}, {"R","G","B"}.
void writeExr(const std::filesystem::path& path, const ImageF& img,
              const std::vector<std::string>& channel_names, const ExrOptions& options = {});
/// Reads the named channels of an EXR (any pixel type, converted to float) into an image with
/// channel_names.size() channels in that order. A missing channel is an InputError listing those
/// present.
ImageF readExr(const std::filesystem::path& path, const std::vector<std::string>& channel_names);
/// Channel names stored in an EXR file (sorted, as EXR keeps them).
std::vector<std::string> exrChannelNames(const std::filesystem::path& path);

}  // namespace inet
