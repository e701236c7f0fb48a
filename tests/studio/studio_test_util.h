#pragma once
// Shared by the studio's server tests: the built-in room loaded once per test process, a web
// folder and data folders with symlinks out of them, and a server on a free loopback port.
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <string>

#include "../temp_dir.h"
#include "studio/server.h"
#include "studio/studio_layout.h"

namespace inet::studio::test {

/// The text of the file outside every root: no response may ever contain it.
inline const std::string kSecret = "TOPSECRET-outside-the-roots";

/// builtin:room with its free space, loaded once.
inline std::shared_ptr<const StudioLayout> roomLayout() {
  static const std::shared_ptr<const StudioLayout> layout = [] {
    SceneSource src;
    src.path = "builtin:room";
    return loadStudioLayout(src);
  }();
  return layout;
}

/// tmp/web (index.html, app.js, model.glb, .env), tmp/data (layout.json, a symlink to the secret
/// and one to its folder), tmp/outside/secret.txt, tmp/linked -> data (a symlinked root).
struct StudioFolders {
  inet::test::TempDir tmp{"studio"};
  StudioFolders() {
    namespace fs = std::filesystem;
    tmp.write("web/index.html", "<!doctype html><title>test page</title>");
    tmp.write("web/app.js", "console.log(1);");
    tmp.write("web/model.glb", std::string("glTF\x02\x00\x00\x00", 8));
    tmp.write("web/.env", kSecret);
    tmp.write("data/layout.json", "{\"in\": \"data\"}");
    tmp.write("data/sub/frame.exr", "EXR");
    tmp.write("outside/secret.txt", kSecret);
    fs::create_symlink(tmp / "outside/secret.txt", tmp / "data/link_out.txt");
    fs::create_symlink(tmp / "outside", tmp / "data/dir_out");
    fs::create_symlink(tmp / "data", tmp / "linked");
  }
  StudioOptions options() const {
    StudioOptions o;
    o.port = 0;
    o.web_root = tmp / "web";
    o.data_roots = {{"data", tmp / "data"}, {"linked", tmp / "linked"}};
    return o;
  }
};

/// A client of `server` that sends paths exactly as written.
inline httplib::Client clientOf(const StudioServer& server) {
  httplib::Client c("127.0.0.1", server.port());
  c.set_url_encode(false);
  c.set_read_timeout(60, 0);
  return c;
}

inline nlohmann::json jsonOf(const httplib::Result& r) {
  return r ? nlohmann::json::parse(r->body, nullptr, false) : nlohmann::json();
}

/// Checks a JSON error response: the status, {"error": one line, "file", "field"} with the field
/// named (when given), and never the secret.
inline void expectJsonError(const httplib::Result& r, int status, const std::string& field = "") {
  ASSERT_TRUE(r) << "no response (" << httplib::to_string(r.error()) << "), expected " << status;
  EXPECT_EQ(r->status, status) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json");
  const nlohmann::json j = jsonOf(r);
  ASSERT_TRUE(j.is_object() && j.contains("error")) << r->body;
  const std::string msg = j["error"];
  EXPECT_FALSE(msg.empty());
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_TRUE(j.contains("file") && j.contains("field")) << r->body;
  if (!field.empty()) {
    EXPECT_EQ(j["field"], field) << r->body;
  }
  EXPECT_EQ(r->body.find(kSecret), std::string::npos);
}

/// VmRSS of this process in KiB (/proc/self/status).
inline long rssKib() {
  std::ifstream in("/proc/self/status");
  std::string key;
  long value = 0;
  while (in >> key) {
    if (key == "VmRSS:") {
      in >> value;
      return value;
    }
    std::getline(in, key);
  }
  return -1;
}

}  // namespace inet::studio::test
