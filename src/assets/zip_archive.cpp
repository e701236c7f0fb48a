#include "assets/zip_archive.h"

#include <fmt/format.h>
#include <zip.h>

#include "core/error.h"

namespace inet {

struct ZipArchive::Handle {
  zip_t* zip = nullptr;
};

namespace {

std::string stripSlash(const std::string& name) {
  return !name.empty() && name.front() == '/' ? name.substr(1) : name;
}

}  // namespace

ZipArchive::ZipArchive(const std::string& path) : path_(path), handle_(new Handle) {
  int code = 0;
  handle_->zip = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (!handle_->zip) {
    zip_error_t err;
    zip_error_init_with_code(&err, code);
    const std::string msg = zip_error_strerror(&err);
    zip_error_fini(&err);
    throw InputError(path, "", "cannot open as a zip archive: " + msg);
  }
  const zip_int64_t n = zip_get_num_entries(handle_->zip, 0);
  entries_.reserve(static_cast<size_t>(std::max<zip_int64_t>(n, 0)));
  for (zip_int64_t i = 0; i < n; ++i) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(handle_->zip, static_cast<zip_uint64_t>(i), 0, &st) != 0 || !st.name)
      continue;
    ZipEntry e;
    e.name = st.name;
    e.size = (st.valid & ZIP_STAT_SIZE) ? st.size : 0;
    e.crc = (st.valid & ZIP_STAT_CRC) ? st.crc : 0;
    entries_.push_back(std::move(e));
  }
}

ZipArchive::~ZipArchive() {
  if (handle_ && handle_->zip) zip_discard(handle_->zip);
}

const ZipEntry* ZipArchive::find(const std::string& name) const {
  const std::string key = stripSlash(name);
  for (const auto& e : entries_)
    if (e.name == key) return &e;
  return nullptr;
}

std::string ZipArchive::read(const std::string& name, uint64_t max_bytes) const {
  const ZipEntry* e = find(name);
  if (!e) throw InputError(path_, name, "no such entry in the archive");
  if (e->size > max_bytes)
    throw InputError(path_, e->name,
                     fmt::format("entry of {} bytes exceeds the limit of {}", e->size, max_bytes));
  zip_file_t* f = zip_fopen(handle_->zip, e->name.c_str(), 0);
  if (!f)
    throw InputError(path_, e->name,
                     std::string("cannot open entry: ") + zip_strerror(handle_->zip));
  std::string bytes(e->size, '\0');
  uint64_t done = 0;
  while (done < e->size) {
    const zip_int64_t got = zip_fread(f, bytes.data() + done, e->size - done);
    if (got <= 0) break;
    done += static_cast<uint64_t>(got);
  }
  // zip_fread reports a CRC mismatch at the end of the entry as an error
  char extra = 0;
  const bool overrun = done == e->size && zip_fread(f, &extra, 1) != 0;
  const std::string err = zip_file_strerror(f);
  zip_fclose(f);
  if (done != e->size || overrun) throw InputError(path_, e->name, "corrupt entry: " + err);
  return bytes;
}

std::string ZipArchive::contentChecksum() const {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const auto& e : entries_) {
    mix(e.name.data(), e.name.size() + 1);  // with the terminating 0, so names cannot run on
    mix(&e.size, sizeof e.size);
    mix(&e.crc, sizeof e.crc);
  }
  return fmt::format("{:016x}", h);
}

}  // namespace inet
