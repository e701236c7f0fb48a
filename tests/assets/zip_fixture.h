#pragma once
// Writes a zip archive from name -> bytes with libzip, for tests that need a catalog (.sh3f) or
// a home (.sh3d) of their own.
#include <gtest/gtest.h>
#include <zip.h>

#include <filesystem>
#include <map>
#include <string>

namespace inet::test {

inline void writeZip(const std::filesystem::path& path,
                     const std::map<std::string, std::string>& files) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(z, nullptr);
  for (const auto& [name, bytes] : files) {
    zip_source_t* src = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    ASSERT_NE(src, nullptr);
    ASSERT_GE(zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE), 0) << name;
  }
  ASSERT_EQ(zip_close(z), 0);
}

}  // namespace inet::test
