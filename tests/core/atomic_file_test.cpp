#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

fs::path freshDir(const std::string& name) {
  fs::path d =
      fs::temp_directory_path() / ("inet_atomic_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(AtomicFile, WritesAndCreatesFolders) {
  fs::path d = freshDir("write");
  writeTextAtomic(d / "a/b/c.txt", "hello");
  EXPECT_EQ(readTextFile(d / "a/b/c.txt"), "hello");
  EXPECT_EQ(removeStaleTemporaries(d), 0);
  fs::remove_all(d);
}

TEST(AtomicFile, FailedWriterLeavesNothing) {
  fs::path d = freshDir("fail");
  writeTextAtomic(d / "keep.txt", "old");
  EXPECT_THROW(writeFileAtomic(d / "keep.txt",
                               [](const fs::path& tmp) {
                                 std::ofstream(tmp) << "half";
                                 throw std::runtime_error("disk on fire");
                               }),
               std::runtime_error);
  EXPECT_EQ(readTextFile(d / "keep.txt"), "old");
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(d)) (void)e, ++n;
  EXPECT_EQ(n, 1u) << "temporary left behind";
  fs::remove_all(d);
}

TEST(AtomicFile, RemovesStaleTemporariesOnly) {
  fs::path d = freshDir("stale");
  writeTextAtomic(d / "x/frame.png", "png");
  std::ofstream(d / "x/frame2.png.tmp-12345") << "partial";
  std::ofstream(d / "notes.txt") << "keep";
  EXPECT_EQ(removeStaleTemporaries(d), 1);
  EXPECT_TRUE(fs::exists(d / "x/frame.png"));
  EXPECT_TRUE(fs::exists(d / "notes.txt"));
  EXPECT_FALSE(fs::exists(d / "x/frame2.png.tmp-12345"));
  fs::remove_all(d);
}

TEST(AtomicFile, ReadErrorsNameTheFile) {
  try {
    readTextFile("/nonexistent/inet/file.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/inet/file.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace inet
