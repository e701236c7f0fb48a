// The studio's design routes in-process: the floor plan, the layout's glTF, keyframed paths with
// their free-space warnings, trajectory export and sequence jobs, and their one-line errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <tuple>

#include "../box_mesh.h"
#include "core/error.h"
#include "core/image_io.h"
#include "scene/gltf_export.h"
#include "studio/design_api.h"
#include "studio/floor_plan.h"
#include "studio/server.h"
#include "studio_test_util.h"
#include "trajectory/formats.h"

namespace inet::studio {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::clientOf;
using test::jsonOf;

class StudioDesignTest : public ::testing::Test {
 protected:
  void SetUp() override {
    StudioOptions o = folders.options();
    o.out_dir = folders.tmp / "out";
    o.serve_out = true;
    server = std::make_unique<StudioServer>(o, test::roomLayout());
    server->start();
  }
  httplib::Result post(const std::string& path, const json& body) {
    auto c = clientOf(*server);
    return c.Post(path.c_str(), body.dump(), "application/json");
  }
  /// Two keyframes in the room's open middle (free at 1.5 m: see FreeSpaceIsChecked).
  static json twoKeyframes() {
    return {{"keyframes",
             {{{"t", 0.0}, {"position", {2.5, 1.0, 1.5}}, {"look_at", {3.5, 1.0, 1.5}}},
              {{"t", 1.0}, {"position", {3.3, 1.0, 1.5}}, {"look_at", {3.3, 2.0, 1.2}}}}},
            {"fps", 10}};
  }
  /// A sequence job of 2 frames (0.2 s at 5 fps) of 32 x 24 px at 1 spp, rgb and depth only,
  /// into folder `name`: what each job test changes is all it adds.
  static json tinySequence(const std::string& name) {
    json req = twoKeyframes();
    req["keyframes"][1]["t"] = 0.2;
    req.update({{"fps", 5},
                {"width", 32},
                {"height", 24},
                {"fx", 30},
                {"spp", 1},
                {"imu_rate", 0},
                {"passes", "rgb,depth"},
                {"sequence", name}});
    return req;
  }
  void expectError(const httplib::Result& r, const std::string& field) {
    test::expectJsonError(r, 400, field);
  }
  test::StudioFolders folders;
  std::unique_ptr<StudioServer> server;
};

TEST_F(StudioDesignTest, FloorPlanCoversTheRoom) {
  auto c = clientOf(*server);
  auto r = c.Get("/api/layout/plan");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const json p = jsonOf(r);
  const int nx = p["nx"], ny = p["ny"];
  const auto [lo, hi] = test::roomLayout()->scene.bounds();
  EXPECT_GE(nx * p["cell_m"].get<double>(), hi.x() - lo.x());
  EXPECT_GE(ny * p["cell_m"].get<double>(), hi.y() - lo.y());
  ASSERT_EQ(p["rows"].size(), static_cast<size_t>(ny));
  std::map<char, int> count;
  for (int j = 0; j < ny; ++j) {
    const std::string row = p["rows"][j], tops = p["tops"][j];
    ASSERT_EQ(row.size(), static_cast<size_t>(nx));
    ASSERT_EQ(tops.size(), static_cast<size_t>(nx));
    for (int i = 0; i < nx; ++i) {
      ++count[row[i]];
      EXPECT_EQ(row[i] == 'f', tops[i] != '-') << i << "," << j;
    }
  }
  for (const auto& [code, n] : count) EXPECT_NE(std::string("o#fb.").find(code), std::string::npos);
  EXPECT_GT(count['.'], 100);  // the room's open floor
  EXPECT_GT(count['f'], 50);   // its furniture
  EXPECT_GT(count['#'], 50);   // its walls
  // a free cell is free at its height as the exact check sees it
  const FreeSpace& space = *test::roomLayout()->space;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (p["rows"][j].get<std::string>()[i] == '.') {
        const Vec3 at(p["origin"][0].get<double>() + i * p["cell_m"].get<double>(),
                      p["origin"][1].get<double>() + j * p["cell_m"].get<double>(),
                      p["floor_z"].get<double>() + p["height_m"].get<double>());
        EXPECT_TRUE(space.hasClearance(at, p["clearance_m"])) << at.transpose();
      }
}

/// Two storeys of 8 x 6 m (floors at 0 and 2.9 m, a 0.2 m slab between), a 1 m cube of
/// furniture on the ground floor at (2, 3) and one upstairs at (6, 3).
std::shared_ptr<const StudioLayout> twoStoreys() {
  Mesh m;
  auto storey = [&m](double z0) {
    const double w = 8, d = 6, h = 2.7, t = 0.2;
    inet::test::appendBox(m, {w / 2, d / 2, z0 - t / 2}, {w + 2 * t, d + 2 * t, t});
    inet::test::appendBox(m, {w / 2, d / 2, z0 + h + t / 2}, {w + 2 * t, d + 2 * t, t});
    inet::test::appendBox(m, {-t / 2, d / 2, z0 + h / 2}, {t, d, h});
    inet::test::appendBox(m, {w + t / 2, d / 2, z0 + h / 2}, {t, d, h});
    inet::test::appendBox(m, {w / 2, d + t / 2, z0 + h / 2}, {w, t, h});
    inet::test::appendBox(m, {w / 2, -t / 2, z0 + h / 2}, {w, t, h});
  };
  storey(0.0);
  storey(2.9);
  inet::test::appendBox(m, {2, 3, 0.5}, {1, 1, 1});
  inet::test::appendBox(m, {6, 3, 3.4}, {1, 1, 1});
  auto layout = std::make_shared<StudioLayout>();
  Scene& s = layout->scene;
  s.name = "two_storeys";
  s.materials.push_back(Material{});
  m.id = "storeys";
  s.meshes.push_back(std::move(m));
  s.objects.push_back(Object::make("storeys", 0, 0, Mat4::Identity(), 1, 1));
  layout->source = "two storeys";
  layout->space = std::make_unique<FreeSpace>(s);
  layout->summary = layoutSummary(s, layout->source, layout->space.get());
  layout->plans = floorPlans(s, *layout->space);
  return layout;
}

TEST(StudioPlan, OnePlanPerStorey) {
  test::StudioFolders folders;
  StudioServer server(folders.options(), twoStoreys());
  server.start();
  auto c = clientOf(server);
  // the plan's cell over (x, y)
  auto at = [](const json& p, double x, double y) {
    const int i = static_cast<int>(
        std::lround((x - p["origin"][0].get<double>()) / p["cell_m"].get<double>()));
    const int j = static_cast<int>(
        std::lround((y - p["origin"][1].get<double>()) / p["cell_m"].get<double>()));
    return p["rows"][j].get<std::string>()[i];
  };
  const json ground = jsonOf(c.Get("/api/layout/plan"));
  ASSERT_EQ(ground["levels"].size(), 2u) << ground.dump().substr(0, 300);
  EXPECT_EQ(ground["level"], 0);
  EXPECT_NEAR(ground["floor_z"].get<double>(), 0.0, 0.05);
  const json upper = jsonOf(c.Get("/api/layout/plan?level=1"));
  ASSERT_TRUE(upper.contains("rows")) << upper.dump();
  EXPECT_EQ(upper["level"], 1);
  EXPECT_NEAR(upper["floor_z"].get<double>(), 2.9, 0.05);
  EXPECT_EQ(upper["nx"], ground["nx"]);  // the same grid
  EXPECT_EQ(upper["ny"], ground["ny"]);
  // each storey shows its own furniture and the other's place as free floor
  EXPECT_EQ(at(ground, 2, 3), 'f');
  EXPECT_EQ(at(ground, 6, 3), '.');
  EXPECT_EQ(at(upper, 2, 3), '.');
  EXPECT_EQ(at(upper, 6, 3), 'f');
  EXPECT_EQ(upper["tops"][0].get<std::string>().size(), upper["rows"][0].get<std::string>().size());
  // the level named in the query: 0 and 1 only
  for (const char* bad : {"2", "-1", "x", "", "1000"})
    test::expectJsonError(c.Get((std::string("/api/layout/plan?level=") + bad).c_str()), 400,
                          "level");
}

TEST_F(StudioDesignTest, LayoutGlbIsOurExport) {
  auto c = clientOf(*server);
  auto r = c.Get("/api/layout.glb");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  EXPECT_EQ(r->get_header_value("Content-Type"), "model/gltf-binary");
  ASSERT_GT(r->body.size(), 12u);
  EXPECT_EQ(r->body.substr(0, 4), "glTF");
  // the same bytes as the export of the same scene written here (same layout, same bytes)
  const fs::path mine = folders.tmp / "mine.glb";
  GltfExportOptions opt;
  opt.binary = true;
  exportGltf(test::roomLayout()->scene, mine.string(), opt);
  std::ifstream in(mine, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  EXPECT_TRUE(bytes.str() == r->body) << bytes.str().size() << " vs " << r->body.size();
  auto again = c.Get("/api/layout.glb");
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->body == r->body);
}

TEST_F(StudioDesignTest, PathThroughKeyframes) {
  auto r = post("/api/design/path", twoKeyframes());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json p = jsonOf(r);
  EXPECT_EQ(p["frames"], 11);  // 0, 0.1, ..., 1.0 s
  ASSERT_EQ(p["poses"].size(), 11u);
  EXPECT_EQ(p["poses"][10]["t_ns"], 1000000000);
  EXPECT_TRUE(p["warnings"].empty()) << p["warnings"].dump();
  EXPECT_TRUE(p["keyframes"][0]["free"].get<bool>());
  // the first and last poses are the keyframes: at the position, looking at the point (the
  // camera's z axis), the image's x axis level
  const json keys = twoKeyframes()["keyframes"];
  for (const auto& [pose, key] :
       {std::pair{p["poses"][0], keys[0]}, std::pair{p["poses"][10], keys[1]}}) {
    const Vec3 pos(pose["position"][0], pose["position"][1], pose["position"][2]);
    const Vec3 want(key["position"][0], key["position"][1], key["position"][2]);
    const Vec3 look(key["look_at"][0], key["look_at"][1], key["look_at"][2]);
    EXPECT_LT((pos - want).norm(), 1e-12);
    const auto& q = pose["quaternion_xyzw"];
    const Mat3 R = Quat(q[3], q[0], q[1], q[2]).toRotationMatrix();
    EXPECT_LT((R.col(2) - (look - want).normalized()).norm(), 1e-9);
    EXPECT_NEAR(R.col(0).z(), 0.0, 1e-12);
    EXPECT_GT(q[3].get<double>(), 0.0);
  }
  // speed: 0.8 m in 1 s, a smooth curve between, so at most a little over 0.8 m/s
  EXPECT_GT(p["max_speed_mps"].get<double>(), 0.79);
  EXPECT_LT(p["max_speed_mps"].get<double>(), 1.5);
}

TEST_F(StudioDesignTest, FreeSpaceIsChecked) {
  json req = twoKeyframes();
  // a point in the corner where two walls meet (the room's bounds start at the walls' outside)
  const auto [lo, hi] = test::roomLayout()->scene.bounds();
  req["keyframes"].push_back({{"t", 3.0},
                              {"position", {lo.x() + 0.05, lo.y() + 0.05, 1.5}},
                              {"look_at", {2.0, 2.0, 1.5}}});
  req["max_speed"] = 100;
  req["max_turn_rate"] = 10000;
  const json p = jsonOf(post("/api/design/path", req));
  ASSERT_TRUE(p.contains("keyframes")) << p.dump();
  EXPECT_FALSE(p["keyframes"][2]["free"].get<bool>());
  EXPECT_TRUE(p["keyframes"][0]["free"].get<bool>());
  bool keyframe = false, path = false;
  for (const json& w : p["warnings"]) {
    keyframe |= w["kind"] == "keyframe" && w["index"] == 2;
    if (w["kind"] == "path") {
      path = true;
      EXPECT_LE(w["to_s"].get<double>(), 3.0 + 1e-9);
      EXPECT_GT(w["to_s"].get<double>(), 1.0);  // the stretch towards the corner
    }
  }
  EXPECT_TRUE(keyframe) << p["warnings"].dump();
  EXPECT_TRUE(path) << p["warnings"].dump();
  // limits: 0.8 m in 1 s is over 0.5 m/s
  req = twoKeyframes();
  req["max_speed"] = 0.5;
  const json slow = jsonOf(post("/api/design/path", req));
  ASSERT_EQ(slow["warnings"].size(), 1u) << slow.dump();
  EXPECT_EQ(slow["warnings"][0]["kind"], "speed");
}

TEST_F(StudioDesignTest, ExportWritesTheFormats) {
  const json path = jsonOf(post("/api/design/path", twoKeyframes()));
  for (const std::string format : {"tum", "euroc", "icl", "slambench", "scenenet", "kitti"}) {
    json req = twoKeyframes();
    req["format"] = format;
    auto r = post("/api/design/export", req);
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << format << ": " << r->body;
    EXPECT_NE(r->get_header_value("Content-Disposition").find("attachment; filename="),
              std::string::npos);
    // read back with the library's reader: the path's poses (scenenet keeps no roll; its
    // positions still agree)
    const TrajectoryFormat f = parseTrajectoryFormat(format);
    TrajectoryFormatOptions opt;
    opt.icl_fps = opt.kitti_fps = 10;
    const Trajectory t = parseTrajectory(r->body, format, f, opt);
    ASSERT_EQ(t.size(), path["poses"].size()) << format;
    for (size_t i = 0; i < t.size(); ++i) {
      const json& want = path["poses"][i];
      const Vec3 p(want["position"][0], want["position"][1], want["position"][2]);
      EXPECT_LT((t.poses[i].T_world_camera.t - p).norm(), 1e-6) << format << " pose " << i;
      EXPECT_EQ(t.poses[i].t_ns - t.poses[0].t_ns, want["t_ns"].get<int64_t>()) << format;
    }
  }
  auto c = clientOf(*server);
  json req = twoKeyframes();
  req["format"] = "tum";
  auto r = c.Post("/api/design/export", req.dump(), "application/json");
  EXPECT_EQ(r->get_header_value("Content-Disposition"), "attachment; filename=\"groundtruth.txt\"");
}

TEST_F(StudioDesignTest, BadRequestsNameTheKey) {
  expectError(post("/api/design/path", json::object()), "keyframes");
  expectError(post("/api/design/path", {{"keyframes", json::array()}}), "keyframes");
  json req = twoKeyframes();
  req["keyframes"][1]["t"] = 0.0;
  expectError(post("/api/design/path", req), "keyframes[1].t");
  req = twoKeyframes();
  req["keyframes"][0]["position"] = {1, 2};
  expectError(post("/api/design/path", req), "keyframes[0].position");
  req = twoKeyframes();
  req["keyframes"][0]["look_at"] = {2.5, 1.0, 3.0};  // straight up
  expectError(post("/api/design/path", req), "keyframes[0].look_at");
  req = twoKeyframes();
  req["keyframes"][0]["roll"] = 1;
  expectError(post("/api/design/path", req), "keyframes[0].roll");
  // one bad key at a time: route, key, value
  const std::vector<std::tuple<std::string, std::string, json>> bad = {
      {"/api/design/path", "fps", 0},
      {"/api/design/path", "colour", "red"},
      {"/api/design/export", "format", "bvh"},
      {"/api/jobs/sequence", "sequence", "../up"},
      {"/api/jobs/sequence", "width", 4},
      {"/api/jobs/sequence", "lens", "orthographic"},
      {"/api/jobs/sequence", "aperture_m", 0.01},  // a pinhole has no aperture
      {"/api/jobs/sequence", "stereo", -0.1},
      {"/api/jobs/sequence", "tone", "sepia"},
      {"/api/jobs/sequence", "exposure", "manual"},
      {"/api/jobs/sequence", "imu_rate", 0.5}};
  for (const auto& [route, key, value] : bad) {
    req = twoKeyframes();
    req[key] = value;
    expectError(post(route, req), key);
  }
  req = twoKeyframes();
  req["lens"] = "thin_lens";
  req["fisheye_fov_deg"] = 190;
  expectError(post("/api/jobs/sequence", req), "fisheye_fov_deg");
  // distortion, refused at once (400 naming the key, no job): the shape, the count, a range,
  // a lens without Brown-Conrady terms, a polynomial that folds inside the image, a k3 with
  // the ASL layout
  const std::vector<json> bad_distortion = {
      {{"distortion", "0.1,0,0,0"}},
      {{"distortion", {0.1, 0, 0}}},
      {{"distortion", {0.1, 0, 0, 0, 0, 0}}},
      {{"distortion", {0.1, "0", 0, 0}}},
      {{"distortion", {500, 0, 0, 0}}},
      {{"distortion", {0.1, 0, 0, 0}}, {"lens", "fisheye"}, {"width", 64}, {"height", 64}},
      {{"distortion", {-0.9, 0, 0, 0}}, {"fx", 100}},  // folds at r = 0.61 < 2.0 (the corner)
      {{"distortion", {0.1, 0, 0, 0, 0.01}}},          // k3 and ASL's sensor.yaml
  };
  for (const json& keys : bad_distortion) {
    req = twoKeyframes();
    req.update(keys);
    auto r = post("/api/jobs/sequence", req);
    expectError(r, "distortion");
    EXPECT_EQ(r->body.find("--"), std::string::npos) << r->body;
  }
  // the lens is made for the image at once: a fisheye's square, a panorama's 2:1
  req = twoKeyframes();
  req.update({{"lens", "fisheye"}, {"width", 32}, {"height", 24}});
  auto square = post("/api/jobs/sequence", req);
  expectError(square, "height");
  EXPECT_NE(square->body.find("square"), std::string::npos) << square->body;
  req.update({{"lens", "panorama"}, {"width", 64}, {"height", 64}});
  expectError(post("/api/jobs/sequence", req), "height");
  req = twoKeyframes();
  req["formats"] = "asl,bvh";
  expectError(post("/api/jobs/sequence", req), "formats");
  auto c = clientOf(*server);
  auto r = c.Post("/api/design/path", "{\"keyframes\": [", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

TEST_F(StudioDesignTest, SequenceJobRendersThePath) {
  json req = twoKeyframes();
  req["keyframes"][1]["t"] = 0.4;
  req["fps"] = 5;  // 3 frames
  req.update({{"width", 32}, {"height", 24}, {"fx", 30}, {"spp", 1}, {"sequence", "s1"}});
  auto r = post("/api/jobs/sequence", req);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 202) << r->body;
  const std::string url = jsonOf(r)["status_url"];
  auto c = clientOf(*server);
  // its progress as server-sent events, one per change, the last one when it is done
  std::string stream;
  auto events = c.Get((url + "/events").c_str(), [&](const char* data, size_t n) {
    stream.append(data, n);
    return true;
  });
  ASSERT_TRUE(events);
  EXPECT_EQ(events->status, 200);
  EXPECT_EQ(events->get_header_value("Content-Type"), "text/event-stream");
  std::vector<json> statuses;
  std::istringstream lines(stream);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("data: ", 0) == 0) statuses.push_back(json::parse(line.substr(6)));
  ASSERT_GE(statuses.size(), 2u) << stream;
  for (size_t i = 1; i < statuses.size(); ++i)
    EXPECT_GE(statuses[i]["progress"].get<double>(), statuses[i - 1]["progress"].get<double>());
  const json s = statuses.back();
  ASSERT_EQ(s["state"], "done") << s.dump();
  EXPECT_EQ(s["progress"], 1.0);
  const json& res = s["result"];
  EXPECT_EQ(res["frames"], 3);
  EXPECT_TRUE(res["finished"].get<bool>());
  const fs::path dir = res["dir"].get<std::string>();
  EXPECT_EQ(dir, folders.tmp / "out" / test::roomLayout()->scene.name / "s1");
  EXPECT_TRUE(fs::is_regular_file(dir / "cam0" / "sensor.yaml"));
  // its contact sheet, served from the out folder
  auto sheet = c.Get(("/api/files/out/" + res["contact_sheet"].get<std::string>()).c_str());
  ASSERT_TRUE(sheet);
  EXPECT_EQ(sheet->status, 200);
  EXPECT_EQ(sheet->get_header_value("Content-Type"), "image/png");
  // the poses written are the path's
  const Trajectory written =
      readTrajectory((dir / "state_groundtruth_estimate0/data.csv").string());
  const json path =
      jsonOf(post("/api/design/path", json{{"keyframes", req["keyframes"]}, {"fps", 5}}));
  ASSERT_EQ(written.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const json& p = path["poses"][i]["position"];
    EXPECT_LT((written.poses[i].T_world_camera.t - Vec3(p[0], p[1], p[2])).norm(), 1e-12);
  }
  // the name is taken now
  auto again = post("/api/jobs/sequence", req);
  expectError(again, "sequence");
  // cancelling: a finished job 409, an unknown one 404 (a running one: studio_e2e)
  auto cancel = c.Delete(url.c_str());
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 409) << cancel->body;
  EXPECT_EQ(c.Delete("/api/jobs/0123")->status, 404);
}

TEST_F(StudioDesignTest, FramePreviewPasses) {
  // the first pose of the two-keyframe path: looking along +x across the room
  const json pose = jsonOf(post("/api/design/path", twoKeyframes()))["poses"][0];
  for (const std::string pass : {"rgb", "depth", "normal", "label", "albedo"}) {
    json req = {{"position", pose["position"]},
                {"quaternion_xyzw", pose["quaternion_xyzw"]},
                {"width", 40},
                {"height", 30},
                {"fx", 40},
                {"spp", 2},
                {"pass", pass}};
    auto r = post("/api/preview/frame", req);
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << pass << ": " << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "image/png");
    const fs::path file = folders.tmp / (pass + ".png");
    std::ofstream(file, std::ios::binary) << r->body;
    const ImageU8 img = readPng8(file);
    EXPECT_EQ(img.width, 40);
    EXPECT_EQ(img.height, 30);
    EXPECT_EQ(img.channels, pass == "depth" ? 1 : 3);
    // the centre sees a wall 2.5 m away: something was hit there
    int sum = 0;
    for (int c = 0; c < img.channels; ++c) sum += img.at(20, 15, c);
    EXPECT_GT(sum, 0) << pass;
  }
  expectError(post("/api/preview/frame", {{"position", {1, 1, 1}}}), "quaternion_xyzw");
  expectError(post("/api/preview/frame",
                   {{"position", {1, 1, 1}}, {"quaternion_xyzw", {0, 0, 0, 1}}, {"pass", "flow"}}),
              "pass");
  expectError(
      post("/api/preview/frame", {{"position", {1, 1, 1}}, {"quaternion_xyzw", {0, 0, 0, 2}}}),
      "quaternion_xyzw");
}

TEST_F(StudioDesignTest, FramePreviewThroughTheLens) {
  const json pose = jsonOf(post("/api/design/path", twoKeyframes()))["poses"][0];
  int serial = 0;
  // the preview of the first pose with these keys, as an image
  auto preview = [&](const json& keys) {
    json req = {{"position", pose["position"]},
                {"quaternion_xyzw", pose["quaternion_xyzw"]},
                {"width", 40},
                {"height", 30},
                {"fx", 40},
                {"spp", 2}};
    req.update(keys);
    auto r = post("/api/preview/frame", req);
    EXPECT_TRUE(r && r->status == 200) << req.dump() << ": " << (r ? r->body : "no answer");
    const fs::path file = folders.tmp / fmt::format("lens_{}.png", ++serial);
    std::ofstream(file, std::ios::binary) << (r ? r->body : "");
    return readPng8(file);
  };
  auto differing = [](const ImageU8& a, const ImageU8& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.data.size(); ++i) n += a.data[i] != b.data[i];
    return n;
  };
  auto mean = [](const ImageU8& a) {
    double sum = 0;
    for (uint8_t v : a.data) sum += v;
    return sum / static_cast<double>(a.data.size());
  };
  // a 180-degree fisheye sees nothing outside its image circle (a corner), a pinhole does; its
  // depth is the ray distance (farther than the z-depth off the axis)
  const ImageU8 pinhole = preview({{"pass", "depth"}, {"width", 40}, {"height", 40}});
  const ImageU8 fisheye =
      preview({{"pass", "depth"}, {"width", 40}, {"height", 40}, {"lens", "fisheye"}});
  ASSERT_EQ(fisheye.width, 40);
  ASSERT_EQ(fisheye.height, 40);
  EXPECT_GT(pinhole.at(0, 0, 0), 0);
  EXPECT_EQ(fisheye.at(0, 0, 0), 0);
  EXPECT_GT(fisheye.at(20, 20, 0), 0);
  const ImageU8 panorama =
      preview({{"pass", "label"}, {"width", 64}, {"height", 32}, {"lens", "panorama"}});
  EXPECT_EQ(panorama.width, 64);
  // barrel distortion moves the outer pixels, not the centre
  const ImageU8 straight = preview({{"pass", "normal"}});
  const ImageU8 barrel = preview({{"pass", "normal"}, {"distortion", {-0.3, 0.05, 0, 0}}});
  EXPECT_GT(differing(straight, barrel), 30u);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(straight.at(20, 15, c), barrel.at(20, 15, c));
  // a thin lens's ground truth follows its chief rays: the pinhole's labels, while its colour
  // is defocused
  const json thin = {{"lens", "thin_lens"}, {"aperture_m", 0.05}, {"focus_m", 0.5}};
  json label = thin;
  label["pass"] = "label";
  EXPECT_EQ(differing(preview({{"pass", "label"}}), preview(label)), 0u);
  json rgb = thin;
  rgb.update({{"pass", "rgb"}, {"exposure", "fixed"}});
  EXPECT_GT(differing(preview({{"pass", "rgb"}, {"exposure", "fixed"}}), preview(rgb)), 100u);
  // the camera response: two stops brighter, a tone curve, auto exposure
  const ImageU8 fixed0 = preview({{"pass", "rgb"}, {"exposure", "fixed"}});
  const ImageU8 fixed2 = preview({{"pass", "rgb"}, {"exposure", "fixed"}, {"exposure_ev", 2}});
  EXPECT_GT(mean(fixed2), mean(fixed0) + 10) << mean(fixed0) << " " << mean(fixed2);
  const ImageU8 aces =
      preview({{"pass", "rgb"}, {"exposure", "fixed"}, {"exposure_ev", 2}, {"tone", "aces"}});
  EXPECT_GT(differing(fixed2, aces), 100u);
  const ImageU8 automatic = preview({{"pass", "rgb"}});
  EXPECT_GT(mean(automatic), 20);
  EXPECT_LT(mean(automatic), 235);
  // bad keys: 400 naming the key
  const json at = {{"position", pose["position"]}, {"quaternion_xyzw", pose["quaternion_xyzw"]}};
  const std::vector<std::pair<json, std::string>> bad = {
      {{{"lens", "fisheye"}, {"width", 40}, {"height", 30}}, "height"},
      {{{"lens", "fisheye"}, {"width", 40}, {"height", 40}, {"distortion", {0.1, 0, 0, 0}}},
       "distortion"},
      {{{"distortion", {-0.9, 0, 0, 0}}}, "distortion"},
      {{{"lens", "orthographic"}}, "lens"},
      {{{"aperture_m", 0.01}}, "aperture_m"},
      {{{"tone", "sepia"}}, "tone"},
      {{{"exposure", "manual"}}, "exposure"},
      {{{"exposure_ev", 40}}, "exposure_ev"},
      {{{"sensor_noise", "yes"}}, "sensor_noise"}};
  for (const auto& [keys, key] : bad) {
    json req = at;
    req.update(keys);
    auto r = post("/api/preview/frame", req);
    expectError(r, key);
    EXPECT_EQ(r->body.find("--"), std::string::npos) << r->body;
  }
}

TEST_F(StudioDesignTest, ImuAlongThePath) {
  // a camera standing still, level, looking along +x: the accelerometer reads gravity's
  // reaction along the camera's up, which is -y (OpenCV: y down); the gyroscope reads nothing
  json req = {{"keyframes",
               {{{"t", 0.0}, {"position", {2.5, 1.0, 1.5}}, {"look_at", {3.5, 1.0, 1.5}}},
                {{"t", 1.0}, {"position", {2.5, 1.0, 1.5}}, {"look_at", {3.5, 1.0, 1.5}}}}},
              {"fps", 25},
              {"imu_rate", 100}};
  const json imu = jsonOf(post("/api/design/imu", req));
  ASSERT_TRUE(imu.contains("samples")) << imu.dump();
  EXPECT_EQ(imu["samples"].size(), 101u);  // 0..1 s at 100 Hz
  for (const json& m : imu["samples"]) {
    EXPECT_NEAR(m["accel"][0].get<double>(), 0.0, 1e-6);
    EXPECT_NEAR(m["accel"][1].get<double>(), -9.81, 1e-6);
    EXPECT_NEAR(m["accel"][2].get<double>(), 0.0, 1e-6);
    EXPECT_NEAR(Vec3(m["gyro"][0], m["gyro"][1], m["gyro"][2]).norm(), 0.0, 1e-9);
  }
  req["noise"] = "loud";
  expectError(post("/api/design/imu", req), "noise");
  req["noise"] = "none";
  req["imu_rate"] = 5000;
  expectError(post("/api/design/imu", req), "imu_rate");
}

/// Polls a job until it finishes (60 s at most).
json waitForJob(httplib::Client& c, const std::string& url) {
  json s;
  for (int i = 0; i < 600; ++i) {
    s = jsonOf(c.Get(url.c_str()));
    if (s["state"] != "pending" && s["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return s;
}

TEST_F(StudioDesignTest, SequenceJobConfigurations) {
  json req = tinySequence("configs");
  req["config"] = "original,lighting:1";
  auto c = clientOf(*server);
  const json s = waitForJob(c, jsonOf(post("/api/jobs/sequence", req))["status_url"]);
  ASSERT_EQ(s["state"], "done") << s.dump();
  const json& seqs = s["result"]["sequences"];
  ASSERT_EQ(seqs.size(), 2u) << s.dump();
  EXPECT_EQ(seqs[0]["configuration"], "original");
  EXPECT_EQ(seqs[1]["configuration"], "lighting:1");
  EXPECT_NE(seqs[0]["dir"], seqs[1]["dir"]);
  for (const json& q : seqs)
    EXPECT_TRUE(fs::is_directory(fs::path(q["dir"].get<std::string>()) / "cam0" / "data"));
  // the pipeline's message, with the request's key
  req.update({{"config", "sunset"}, {"sequence", "bad_config"}});
  const json f = waitForJob(c, jsonOf(post("/api/jobs/sequence", req))["status_url"]);
  ASSERT_EQ(f["state"], "failed") << f.dump();
  EXPECT_EQ(f["error"]["field"], "config") << f.dump();
}

TEST(StudioToken, EveryRequestCarriesIt) {
  test::StudioFolders folders;
  StudioOptions o = folders.options();
  o.token = "0123456789abcdef-token";
  StudioServer server(o, test::roomLayout());
  server.start();
  EXPECT_EQ(server.openUrl(), server.url() + "?token=0123456789abcdef-token");
  auto c = clientOf(server);
  for (const char* path : {"/api/health", "/", "/app.js", "/api/layout.glb", "/api/files"})
    test::expectJsonError(c.Get(path), 401, "token");
  test::expectJsonError(c.Post("/api/design/path", "{}", "application/json"), 401, "token");
  // the wrong token, the right one as a bearer, as a cookie, and in the query
  test::expectJsonError(c.Get("/api/health", {{"Authorization", "Bearer 0123456789abcdef-toke"}}),
                        401, "token");
  auto r = c.Get("/api/health", {{"Authorization", "Bearer 0123456789abcdef-token"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  r = c.Get("/app.js", {{"Cookie", "other=1; inet_studio_token=0123456789abcdef-token"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  // the printed URL: the cookie is set and the page is reloaded without the token
  r = c.Get("/?token=0123456789abcdef-token");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 303);
  EXPECT_EQ(r->get_header_value("Location"), "/");
  EXPECT_EQ(r->get_header_value("Set-Cookie"),
            "inet_studio_token=0123456789abcdef-token; Path=/; HttpOnly; SameSite=Strict");
  r = c.Get("/api/health?token=0123456789abcdef-token");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  // a token that is too short is refused at start
  o.token = "short";
  EXPECT_THROW(StudioServer(o, test::roomLayout()), InputError);
}

TEST_F(StudioDesignTest, SequenceJobSensors) {
  json req = tinySequence("stereo");
  req["stereo"] = 0.1;
  auto c = clientOf(*server);
  const json s = waitForJob(c, jsonOf(post("/api/jobs/sequence", req))["status_url"]);
  ASSERT_EQ(s["state"], "done") << s.dump();
  const fs::path dir = s["result"]["dir"].get<std::string>();
  EXPECT_TRUE(fs::is_directory(dir / "cam1" / "data"));  // the stereo camera
  EXPECT_FALSE(fs::exists(dir / "imu0"));                // imu_rate 0
  EXPECT_FALSE(fs::exists(dir / "normal0"));             // passes rgb,depth
  // the passes are read as the pipeline reads them, at once: depth_noisy needs a pinhole
  req.update(
      {{"lens", "fisheye"}, {"width", 32}, {"sequence", "fisheye"}, {"passes", "rgb,depth_noisy"}});
  req["height"] = 32;
  auto r = post("/api/jobs/sequence", req);
  expectError(r, "passes");
  EXPECT_EQ(r->body.find("--"), std::string::npos) << r->body;
  EXPECT_NE(r->body.find("pinhole"), std::string::npos) << r->body;
}

TEST_F(StudioDesignTest, SequenceJobEventsAndImuNoise) {
  json req = tinySequence("events");
  req.update({{"imu_rate", 200},
              {"imu_noise", "none"},
              {"passes", "rgb,depth,imu,events"},
              {"event_width", 16},
              {"event_height", 12},
              {"event_spp", 1},
              {"contrast", 0.3},
              {"refractory_ms", 0.5}});
  auto c = clientOf(*server);
  const json s = waitForJob(c, jsonOf(post("/api/jobs/sequence", req))["status_url"]);
  ASSERT_EQ(s["state"], "done") << s.dump();
  const fs::path dir = s["result"]["dir"].get<std::string>();
  // the event camera's settings and the noise-free IMU reach the sequence
  std::ifstream in(dir / "meta.json");
  const json meta = json::parse(in);
  const std::string events = meta.value("events", "");
  EXPECT_NE(events.find("0.3"), std::string::npos) << meta.dump();
  EXPECT_TRUE(fs::is_directory(dir / "events0")) << dir;
  std::ifstream yaml_in(dir / "imu0" / "sensor.yaml");
  std::stringstream yaml;
  yaml << yaml_in.rdbuf();
  EXPECT_NE(yaml.str().find("gyroscope_noise_density: 0 "), std::string::npos) << yaml.str();
  // bad values and keys: 400 naming the key
  const std::vector<std::pair<json, std::string>> bad = {
      {{{"event_width", 0}}, "event_width"},
      {{{"event_spp", 1.5}}, "event_spp"},
      {{{"contrast", 50}}, "contrast"},
      {{{"contrast_pos", 0.001}}, "contrast_pos"},
      {{{"contrast_sigma", -1}}, "contrast_sigma"},
      {{{"refractory_ms", 2000}}, "refractory_ms"},
      {{{"leak_rate_hz", -1}}, "leak_rate_hz"},
      {{{"passes", "rgb"}, {"event_width", 16}}, "event_width"},  // no events pass
      {{{"passes", "rgb,events"}, {"lens", "fisheye"}, {"width", 32}, {"height", 32}}, "passes"},
      {{{"imu_noise", "loud"}}, "imu_noise"},
      {{{"imu_noise", "/etc/passwd"}}, "imu_noise"}};
  for (const auto& [keys, key] : bad) {
    json one = req;
    for (const char* k : {"event_width", "event_height", "event_spp", "contrast", "refractory_ms"})
      one.erase(k);
    one["sequence"] = "bad";
    one.update(keys);
    auto r = post("/api/jobs/sequence", one);
    expectError(r, key);
    EXPECT_EQ(r->body.find("--"), std::string::npos) << r->body;
  }
}

TEST_F(StudioDesignTest, SequenceJobDistortion) {
  // the coefficients reach the sequence's calibration (generate's own test checks the rays)
  json req = tinySequence("distorted");
  req.update({{"formats", "tum"}, {"distortion", {-0.2, 0.05, 0.001, -0.002, 0.01}}});
  auto c = clientOf(*server);
  const json s = waitForJob(c, jsonOf(post("/api/jobs/sequence", req))["status_url"]);
  ASSERT_EQ(s["state"], "done") << s.dump();
  EXPECT_TRUE(s["result"]["contact_sheet"].is_null()) << s.dump();  // no asl, no cam0/
  const fs::path dir = s["result"]["dir"].get<std::string>();
  std::ifstream in(dir / "meta.json");
  ASSERT_TRUE(in) << dir;
  const json camera = json::parse(in)["camera"];
  EXPECT_EQ(camera["distortion_model"], "radial-tangential") << camera.dump();
  EXPECT_EQ(camera["distortion_coefficients"], json({-0.2, 0.05, 0.001, -0.002, 0.01}))
      << camera.dump();
}

}  // namespace
}  // namespace inet::studio
