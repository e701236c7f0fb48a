#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {

bool isTemporaryName(const std::string& name) {
  return name.find(".tmp-") != std::string::npos;
}

void writeFileAtomic(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec)
      throw InputError(path.parent_path().string(), "", "cannot create folder: " + ec.message());
  }
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path.string(), "", "cannot rename temporary into place: " + ec.message());
  }
}

void writeTextAtomic(const fs::path& path, const std::string& contents) {
  writeFileAtomic(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out)
      throw InputError(path.string(), "", std::string("cannot write: ") + std::strerror(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) throw InputError(path.string(), "", "write failed (disk full?)");
  });
}

int removeStaleTemporaries(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  int removed = 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_regular_file(ec) && isTemporaryName(it->path().filename().string())) {
      if (fs::remove(it->path(), ec)) ++removed;
    }
  }
  return removed;
}

std::filesystem::path userCacheDir(const std::string& name) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    candidates.push_back(fs::path(xdg) / "interiornet" / name);
  if (const char* home = std::getenv("HOME"); home && *home)
    candidates.push_back(fs::path(home) / ".cache" / "interiornet" / name);
  candidates.push_back(fs::temp_directory_path() / ("interiornet-" + name));
  for (const fs::path& dir : candidates) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (fs::is_directory(dir, ec) && access(dir.c_str(), W_OK) == 0) return dir;
  }
  throw InputError(candidates.back().string(), "", "no writable folder for the " + name + " cache");
}

std::string readTextFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path.string(), "", "file not found");
  if (fs::is_directory(path, ec))
    throw InputError(path.string(), "", "is a folder, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", std::string("cannot read: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace inet
