#include "core/weights_file.h"

#include <cstring>

#include "core/error.h"

namespace inet {

namespace {

void put32(std::string& bytes, uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

}  // namespace

std::string encodeWeightsFile(const std::string& magic, uint32_t version,
                              const std::string& header, const std::vector<float>& values) {
  INET_CHECK(magic.size() == 8);
  std::string bytes = magic;
  put32(bytes, version);
  put32(bytes, static_cast<uint32_t>(header.size()));
  bytes += header;
  for (float f : values) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    put32(bytes, u);
  }
  return bytes;
}

WeightsFileReader::WeightsFileReader(std::string bytes, std::string path, const std::string& magic,
                                     uint32_t version, const std::string& what)
    : bytes_(std::move(bytes)), path_(std::move(path)) {
  INET_CHECK(magic.size() == 8);
  if (bytes_.size() < 8 || bytes_.compare(0, 8, magic) != 0)
    throw InputError(path_, "magic", "not " + what + " (expected " + magic + ")");
  pos_ = 8;
  if (const uint32_t v = read32("version"); v != version)
    throw InputError(path_, "version", "format version " + std::to_string(v) + ", expected " +
                                           std::to_string(version));
  const uint32_t n = read32("header");
  if (n > bytes_.size() - pos_) throw InputError(path_, "header", "file is truncated");
  header_ = bytes_.substr(pos_, n);
  pos_ += n;
}

uint32_t WeightsFileReader::read32(const std::string& field) {
  if (bytes_.size() - pos_ < 4) throw InputError(path_, field, "file is truncated");
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= static_cast<uint32_t>(static_cast<uint8_t>(bytes_[pos_ + i])) << (8 * i);
  pos_ += 4;
  return v;
}

std::vector<float> WeightsFileReader::readFloats(size_t n, const std::string& field) {
  if ((bytes_.size() - pos_) / 4 < n) throw InputError(path_, field, "file is truncated");
  std::vector<float> out(n);
  for (float& f : out) {
    const uint32_t u = read32(field);
    std::memcpy(&f, &u, 4);
  }
  return out;
}

void WeightsFileReader::finish() const {
  if (pos_ != bytes_.size()) throw InputError(path_, "tensors", "trailing bytes after the weights");
}

}  // namespace inet
