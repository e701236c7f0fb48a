#pragma once
// Read-only access to zip archives (Sweet Home 3D's .sh3f catalogs and .sh3d homes) through
// libzip (Debian's libzip-dev). Entry names are as stored: '/'-separated, no leading '/'.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace inet {

/// One file in an archive, as its central directory describes it.
struct ZipEntry {
  std::string name;   ///< as stored ("katorlegaz/futon-couch/futon-couch.obj")
  uint64_t size = 0;  ///< uncompressed bytes
  uint32_t crc = 0;   ///< CRC-32 of the uncompressed bytes
  bool isDirectory() const { return !name.empty() && name.back() == '/'; }
};

/// An open archive. Errors are InputError naming the archive (and the entry, where one is
/// involved) with libzip's message.
class ZipArchive {
 public:
  /// Opens `path` read-only; throws when it is missing or not a zip archive.
  explicit ZipArchive(const std::string& path);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  const std::string& path() const { return path_; }
  /// Every entry, in central-directory order.
  const std::vector<ZipEntry>& entries() const { return entries_; }
  /// The entry named `name` (a leading '/' is ignored), or nullptr.
  const ZipEntry* find(const std::string& name) const;
  /// The uncompressed bytes of entry `name`; throws when it is missing, larger than
  /// `max_bytes`, or cannot be inflated (a corrupt archive, a CRC mismatch).
  std::string read(const std::string& name, uint64_t max_bytes = uint64_t(1) << 31) const;
  /// A checksum of the archive's content: 64-bit FNV-1a over every entry's name, size and
  /// CRC-32, in hex. Cheap (no inflating) and changes whenever any entry does.
  std::string contentChecksum() const;

 private:
  struct Handle;
  std::string path_;
  std::unique_ptr<Handle> handle_;
  std::vector<ZipEntry> entries_;
};

}  // namespace inet
