#pragma once
// Helpers for end-to-end tests: run the interiornet binary, capture its output, compare folders.
#include <filesystem>
#include <map>
#include <string>

namespace inet::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
  long peak_rss_kb = 0;  ///< of the child process (wait4)
};

/// Runs INET_BINARY with `args` (shell-quoted by the caller where needed) and waits for it.
RunResult runInterinet(const std::string& args);

/// A fresh empty temporary folder for one test, removed by the destructor.
class TempDir {
 public:
  explicit TempDir(const std::string& name);
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& s) const { return path_ / s; }

 private:
  std::filesystem::path path_;
};

/// Relative path -> file contents for every regular file under `dir`.
std::map<std::string, std::string> readTree(const std::filesystem::path& dir);
void writeFile(const std::filesystem::path& p, const std::string& text);

/// The dataset spec of the `dataset` tests: two procedural apartments with parametric
/// furniture, a 4-frame sequence each in 2-frame units, their sparse views in three
/// configurations, 48x36 at 1 spp, IMU at 200 Hz. Tests append keys (e.g. shards) to it.
inline const std::string kTinyDatasetSpec = R"(version: 1
name: tiny
seed: 3
layouts:
  procedural: {count: 2, rooms: [2, 3], furniture: parametric}
sequences: {per_layout: 1, frames: 4, unit_frames: 2}
sparse: {batch: 2}
camera: {width: 48, height: 36, fx: 45, fy: 45}
render: {spp: 1}
imu: 200
)";
/// Number of regular files under `dir` (0 if it does not exist).
size_t countFiles(const std::filesystem::path& dir);

}  // namespace inet::test
