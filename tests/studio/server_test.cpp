// The studio's server in-process on a free loopback port: what it serves, what it refuses and
// with which status, its JSON errors, its trajectory preview and its background jobs.
#include "studio/server.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "core/error.h"
#include "studio_test_util.h"

namespace inet::studio {
namespace {

using nlohmann::json;
using test::clientOf;
using test::jsonOf;
using test::kSecret;

class StudioServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server = std::make_unique<StudioServer>(folders.options(), test::roomLayout());
    server->start();
  }
  void expectError(const httplib::Result& r, int status, const std::string& field = "") {
    test::expectJsonError(r, status, field);
  }
  test::StudioFolders folders;
  std::unique_ptr<StudioServer> server;
};

TEST_F(StudioServerTest, HealthAndLayout) {
  auto c = clientOf(*server);
  auto r = c.Get("/api/health");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  const json h = jsonOf(r);
  EXPECT_EQ(h["status"], "ok");
  EXPECT_FALSE(h["version"].get<std::string>().empty());
  r = c.Get("/api/layout");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const json l = jsonOf(r);
  const Scene& s = test::roomLayout()->scene;
  EXPECT_EQ(l["name"], s.name);
  EXPECT_EQ(l["objects"], s.objects.size());
  EXPECT_EQ(l["rooms"].size(), s.rooms.size());
  EXPECT_EQ(l["bounds"]["min"].size(), 3u);
  EXPECT_FALSE(l["classes"].empty());
  EXPECT_GT(l["free_space"]["free_volume_m3"].get<double>(), 0.0);
}

TEST_F(StudioServerTest, ServesWebAssetsWithTheirTypes) {
  auto c = clientOf(*server);
  auto r = c.Get("/");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("test page"), std::string::npos);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_EQ(r->get_header_value("X-Content-Type-Options"), "nosniff");
  r = c.Get("/app.js");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  r = c.Get("/model.glb");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->get_header_value("Content-Type"), "model/gltf-binary");
  EXPECT_EQ(r->body, std::string("glTF\x02\x00\x00\x00", 8));
  r = c.Get("/api/files/data/layout.json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "{\"in\": \"data\"}");
  r = c.Get("/api/files/data/sub/frame.exr");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/octet-stream");
  r = c.Get("/api/files/linked/layout.json");  // a root given through a symlink
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(jsonOf(c.Get("/api/files"))["roots"], json::array({"data", "linked"}));
}

TEST_F(StudioServerTest, RefusesEverythingOutsideTheRoots) {
  auto c = clientOf(*server);
  const std::string abs = (folders.tmp / "outside/secret.txt").string();
  const std::vector<std::string> attacks = {
      "/../outside/secret.txt",
      "/%2e%2e/outside/secret.txt",
      "/%2E%2E%2Foutside%2Fsecret.txt",
      "/.env",
      "//" + abs.substr(1),
      "/api/files/data/../../outside/secret.txt",
      "/api/files/data/%2e%2e/%2e%2e/outside/secret.txt",
      "/api/files/data/%2e%2e%2f%2e%2e%2foutside%2fsecret.txt",
      "/api/files/data/%252e%252e/outside/secret.txt",
      "/api/files/data/" + abs,
      "/api/files/data/%2F" + abs.substr(1),
      "/api/files/data/link_out.txt",
      "/api/files/data/dir_out/secret.txt",
      "/api/files/linked/link_out.txt",
      "/api/files/linked/../outside/secret.txt",
      "/api/files/data/layout.json%00.png",
      "/api/files/data/..%5c..%5coutside%5csecret.txt",
      "/api/files/%2e%2e/outside/secret.txt",
      "/api/files/outside/secret.txt",
  };
  for (const std::string& path : attacks) {
    SCOPED_TRACE(path);
    auto r = c.Get(path);
    ASSERT_TRUE(r);
    EXPECT_TRUE(r->status == 403 || r->status == 404) << r->status;
    expectError(r, r->status);
  }
  // the symlinked root was resolved at start: pointing it elsewhere now changes nothing
  std::filesystem::remove(folders.tmp / "linked");
  std::filesystem::create_symlink(folders.tmp / "outside", folders.tmp / "linked");
  auto r = c.Get("/api/files/linked/secret.txt");
  expectError(r, 404);
  r = c.Get("/api/files/linked/layout.json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

TEST_F(StudioServerTest, StatusCodesOfBadRequests) {
  auto c = clientOf(*server);
  expectError(c.Get("/api/nope"), 404);
  expectError(c.Get("/api"), 404);
  expectError(c.Get("/no/such/file.html"), 404);
  expectError(c.Get("/api/jobs/0123456789ab"), 404);
  // wrong methods name the allowed ones
  auto r = c.Get("/api/trajectory/preview");
  expectError(r, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "POST");
  r = c.Post("/api/health", "{}", "application/json");
  expectError(r, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "GET, HEAD");
  expectError(c.Delete("/api/layout"), 405);
  expectError(c.Put("/index.html", "x", "text/plain"), 405);
  expectError(c.Options("/api/trajectory/preview"), 405);  // no CORS preflight passes
  // POST bodies are JSON, of bounded size
  expectError(c.Post("/api/trajectory/preview", "{}", "text/plain"), 415, "Content-Type");
  expectError(c.Post("/api/trajectory/preview", std::string(2 << 20, ' '), "application/json"),
              413);
  r = c.Post("/api/trajectory/preview", "{\"frames\": 10,", "application/json");
  expectError(r, 400);
  EXPECT_NE(jsonOf(r)["error"].get<std::string>().find("malformed JSON"), std::string::npos);
  expectError(c.Post("/api/trajectory/preview", "[1, 2]", "application/json"), 400);
  // a Host that is not the loopback (DNS rebinding)
  expectError(c.Get("/api/health", {{"Host", "evil.example:8080"}}), 403, "Host");
  // a chunked body is read with the same limit
  auto chunked = [&](size_t total) {
    return c.Post(
        "/api/trajectory/preview",
        [total](size_t offset, httplib::DataSink& sink) {
          if (offset == 0) {
            sink.write("{", 1);
          } else if (offset < total) {
            const std::string pad(std::min<size_t>(64 * 1024, total - offset), ' ');
            sink.write(pad.data(), pad.size());
          } else {
            sink.write("}", 1);
            sink.done();
          }
          return true;
        },
        "application/json");
  };
  r = chunked(1000);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  r = chunked(4 << 20);
  // refused: 413, or the connection closed on the rest of the upload before the client read it
  if (r) expectError(r, 413);
}

TEST_F(StudioServerTest, BadFieldsNameTheField) {
  auto c = clientOf(*server);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"frames": 0})", "frames"},
      {R"({"frames": 2.5})", "frames"},
      {R"({"frames": 1000000})", "frames"},
      {R"({"fps": "fast"})", "fps"},
      {R"({"fps": -1})", "fps"},
      {R"({"type": "spiral"})", "type"},
      {R"({"v_mult": -1})", "v_mult"},
      {R"({"w_mult": 1000})", "w_mult"},
      {R"({"seed": -3})", "seed"},
      {R"({"clearance": 9})", "clearance"},
      {R"({"min_height": 3})", "max_height"},
      {R"({"style": "jazzy"})", "style"},
      {R"({"frame": 10})", "frame"},
  };
  for (const auto& [body, field] : cases) {
    SCOPED_TRACE(body);
    auto r = c.Post("/api/trajectory/preview", body, "application/json");
    expectError(r, 400, field);
    // the command line's message, with the request's key for the flag
    const std::string msg = jsonOf(r)["error"];
    EXPECT_EQ(msg.rfind(field + ": ", 0), 0u) << msg;
    EXPECT_EQ(msg.find("--"), std::string::npos) << msg;
  }
  auto r = c.Post("/api/trajectory/preview", R"({"type": "spiral"})", "application/json");
  EXPECT_EQ(jsonOf(r)["error"],
            "type: unknown trajectory type 'spiral' (two-body, hand-held, look-forward)");
  r = c.Post("/api/trajectory/preview", R"({"v_mult": -1})", "application/json");
  EXPECT_EQ(jsonOf(r)["error"], "v_mult: must be in (0, 100]");  // CLI: "--v-mult: must be ..."
}

TEST_F(StudioServerTest, PreviewReturnsTheGeneratorsPoses) {
  auto c = clientOf(*server);
  const std::string body =
      R"({"type": "hand-held", "frames": 20, "fps": 10, "seed": 3, "v_mult": 1.5})";
  auto r = c.Post("/api/trajectory/preview", body, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json t = jsonOf(r);
  EXPECT_EQ(t["type"], "hand-held");
  EXPECT_EQ(t["v_mult"], 1.5);
  ASSERT_EQ(t["poses"].size(), 20u);
  // the library's own trajectory for the same options, pose for pose
  RandomTrajectoryOptions opt;
  opt.type = MotionType::HandHeld;
  opt.frames = 20;
  opt.fps = 10;
  opt.seed = 3;
  opt.v_mult = 1.5;
  const RandomTrajectory ref = generateRandomTrajectory(*test::roomLayout()->space, opt);
  for (size_t k = 0; k < 20; ++k) {
    const json& p = t["poses"][k];
    EXPECT_EQ(p["t_ns"].get<int64_t>(), static_cast<int64_t>(k) * 100'000'000);
    const Pose& T = ref.frames.poses[k].T_world_camera;
    EXPECT_NEAR(p["position"][0].get<double>(), T.t.x(), 1e-12);
    EXPECT_NEAR(p["position"][2].get<double>(), T.t.z(), 1e-12);
    const Quat q(p["quaternion_xyzw"][3].get<double>(), p["quaternion_xyzw"][0].get<double>(),
                 p["quaternion_xyzw"][1].get<double>(), p["quaternion_xyzw"][2].get<double>());
    EXPECT_NEAR(q.angularDistance(T.q), 0.0, 1e-9);
  }
  // same request, same bytes of poses
  EXPECT_EQ(jsonOf(c.Post("/api/trajectory/preview", body, "application/json"))["poses"],
            t["poses"]);
}

TEST_F(StudioServerTest, TrajectoryJobRunsInTheBackground) {
  auto c = clientOf(*server);
  const std::string body = R"({"type": "look-forward", "frames": 30, "seed": 7})";
  auto r = c.Post("/api/jobs/trajectory", body, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 202) << r->body;
  const std::string id = jsonOf(r)["id"];
  EXPECT_EQ(r->get_header_value("Location"), "/api/jobs/" + id);
  json job;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {
    job = jsonOf(c.Get("/api/jobs/" + id));
    if (job["state"] == "done" || job["state"] == "failed") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (std::chrono::steady_clock::now() < deadline);
  ASSERT_EQ(job["state"], "done") << job.dump();
  EXPECT_EQ(job["progress"], 1.0);
  const json preview = jsonOf(c.Post("/api/trajectory/preview", body, "application/json"));
  EXPECT_EQ(job["result"]["poses"], preview["poses"]);
  const json list = jsonOf(c.Get("/api/jobs"));
  ASSERT_EQ(list["jobs"].size(), 1u);
  EXPECT_EQ(list["jobs"][0]["id"], id);
  EXPECT_FALSE(list["jobs"][0].contains("result"));
  // bad input is refused before a job exists
  expectError(c.Post("/api/jobs/trajectory", R"({"frames": -1})", "application/json"), 400,
              "frames");
  EXPECT_EQ(jsonOf(c.Get("/api/jobs"))["jobs"].size(), 1u);
}

TEST(StudioServerBind, LoopbackByDefault) {
  test::StudioFolders folders;
  StudioOptions o = folders.options();
  EXPECT_EQ(StudioOptions{}.host, "127.0.0.1");
  EXPECT_FALSE(StudioOptions{}.allow_remote);
  StudioServer server(o, test::roomLayout());
  EXPECT_EQ(server.boundAddress(), "127.0.0.1");
  EXPECT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
}

TEST(StudioServerBind, OtherAddressesNeedAllowRemote) {
  test::StudioFolders folders;
  StudioOptions o = folders.options();
  for (const std::string host : {"0.0.0.0", "::", "192.0.2.1"}) {
    o.host = host;
    try {
      StudioServer server(o, test::roomLayout());
      ADD_FAILURE() << host << " was bound without allow_remote";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "--host");
      EXPECT_NE(std::string(e.what()).find("--allow-remote"), std::string::npos) << e.what();
    }
  }
  o.host = "0.0.0.0";
  o.allow_remote = true;
  ::testing::internal::CaptureStderr();
  {
    StudioServer server(o, test::roomLayout());  // bound, never started
    EXPECT_EQ(server.boundAddress(), "0.0.0.0");
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("warning: studio: listening on 0.0.0.0"), std::string::npos) << err;
}

TEST(StudioServerBind, BadOptionsAreInputErrors) {
  test::StudioFolders folders;
  StudioOptions o = folders.options();
  o.web_root = folders.tmp / "no_such_web";
  EXPECT_THROW(StudioServer(o, test::roomLayout()), InputError);
  o = folders.options();
  o.data_roots["bad name"] = folders.tmp / "data";
  EXPECT_THROW(StudioServer(o, test::roomLayout()), InputError);
  o = folders.options();
  o.data_roots["missing"] = folders.tmp / "nope";
  EXPECT_THROW(StudioServer(o, test::roomLayout()), InputError);
  // a port already taken
  o = folders.options();
  StudioServer first(o, test::roomLayout());
  o.port = first.port();
  EXPECT_THROW(StudioServer(o, test::roomLayout()), InputError);
}

/// A self-signed certificate for 127.0.0.1 and localhost and its key (PEM), made by the
/// openssl command; false when it cannot be run.
bool makeCertificate(const std::filesystem::path& cert, const std::filesystem::path& key) {
  const std::string cmd =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=localhost -addext "
      "subjectAltName=IP:127.0.0.1,DNS:localhost -keyout '" +
      key.string() + "' -out '" + cert.string() + "' >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0 && std::filesystem::is_regular_file(cert);
}

TEST(StudioServerTls, HttpsOnLoopback) {
  test::StudioFolders folders;
  const auto cert = folders.tmp / "cert.pem", key = folders.tmp / "key.pem";
  if (!makeCertificate(cert, key)) GTEST_SKIP() << "no openssl command to make a certificate";
  StudioOptions o = folders.options();
  o.tls_cert = cert;
  o.tls_key = key;
  o.token = "0123456789abcdef-token";
  StudioServer server(o, test::roomLayout());
  server.start();
  EXPECT_EQ(server.url(), "https://127.0.0.1:" + std::to_string(server.port()) + "/");
  // a client that trusts this certificate alone, and checks the host name against it
  httplib::SSLClient tls("127.0.0.1", server.port());
  tls.set_ca_cert_path(cert.c_str());
  tls.enable_server_certificate_verification(true);
  auto r = tls.Get("/api/health", {{"Authorization", "Bearer 0123456789abcdef-token"}});
  ASSERT_TRUE(r) << httplib::to_string(r.error());
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(jsonOf(r)["status"], "ok");
  test::expectJsonError(tls.Get("/api/health"), 401, "token");
  // the printed URL sets a cookie the browser returns over HTTPS only
  r = tls.Get("/?token=0123456789abcdef-token");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 303);
  EXPECT_EQ(r->get_header_value("Set-Cookie"),
            "inet_studio_token=0123456789abcdef-token; Path=/; HttpOnly; SameSite=Strict; Secure");
  r = tls.Post("/api/design/path", {{"Authorization", "Bearer 0123456789abcdef-token"}},
               R"({"keyframes": [{"t": 0, "position": [2.5, 1, 1.5], "look_at": [3.5, 1, 1.5]},
                   {"t": 1, "position": [3.3, 1, 1.5], "look_at": [3.3, 2, 1.5]}], "fps": 10})",
               "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(jsonOf(r)["frames"], 11);
  // plain HTTP to the HTTPS port gets no HTTP answer
  auto plain = clientOf(server);
  plain.set_read_timeout(5, 0);
  auto p = plain.Get("/api/health", {{"Authorization", "Bearer 0123456789abcdef-token"}});
  EXPECT_FALSE(p && p->status == 200);
  // a client with the system's certificate authorities refuses this self-signed certificate
  httplib::SSLClient strict("127.0.0.1", server.port());
  strict.enable_server_certificate_verification(true);
  EXPECT_FALSE(strict.Get("/api/health"));
}

TEST(StudioServerTls, BadCertificatesAreInputErrors) {
  test::StudioFolders folders;
  StudioOptions o = folders.options();
  auto field = [&](const StudioOptions& opt) {
    try {
      StudioServer server(opt, test::roomLayout());
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("none");
  };
  o.tls_cert = folders.tmp / "web/index.html";
  EXPECT_EQ(field(o), "--tls-key");  // a certificate without its key
  o.tls_key = folders.tmp / "nope.pem";
  EXPECT_EQ(field(o), "--tls-key");  // a key that does not exist
  o.tls_key = folders.tmp / "web/app.js";
  EXPECT_EQ(field(o), "--tls-cert");  // files that are no certificate and key
  o.tls_cert.clear();
  EXPECT_EQ(field(o), "--tls-cert");
}

}  // namespace
}  // namespace inet::studio
