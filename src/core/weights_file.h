#pragma once
// The binary weights files of our learned models (the trajectory style model, the learned
// denoiser), little-endian: 8 bytes of magic, uint32 format version, uint32 header length n,
// n bytes of JSON header (each model's own fields), then float32 values in the order the header
// lists its tensors. This is the framing; each model checks its header and tensor shapes.
#include <cstdint>
#include <string>
#include <vector>

namespace inet {

/// The file's bytes for `magic` (8 characters), `version`, the header text and the values.
std::string encodeWeightsFile(const std::string& magic, uint32_t version,
                              const std::string& header, const std::vector<float>& values);

/// Reads the framing of a weights file held in memory. Every error is an InputError naming
/// `path` and a field: "magic", "version", "header", the field passed to readFloats, or
/// "tensors" for bytes left over.
class WeightsFileReader {
 public:
  /// Checks the magic (`what` names the kind of file in the error, e.g. "a denoiser weights
  /// file") and the version, and reads the header text.
  WeightsFileReader(std::string bytes, std::string path, const std::string& magic,
                    uint32_t version, const std::string& what);
  const std::string& header() const { return header_; }
  /// The next n float32 values; a file that ends first is an error naming `field`.
  std::vector<float> readFloats(size_t n, const std::string& field);
  /// Throws unless every byte was read.
  void finish() const;

 private:
  uint32_t read32(const std::string& field);
  std::string bytes_, path_, header_;
  size_t pos_ = 0;
};

}  // namespace inet
