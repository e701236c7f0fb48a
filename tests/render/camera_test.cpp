#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "render/camera.h"
#include "render/passes.h"

namespace inet {
namespace {

TEST(Camera, DefaultsStateBothConventions) {
  CameraIntrinsics K;
  EXPECT_EQ(K.width, 640);
  EXPECT_DOUBLE_EQ(K.cx, 320.0);
  EXPECT_DOUBLE_EQ(K.cxOpenCV(), 319.5);
  EXPECT_DOUBLE_EQ(K.cyOpenCV(), 239.5);
  // the centre of pixel (319, 239) is on the optical axis side: ray through image centre is (0,0,1)
  Vec3 d = K.rayCamera(320.0, 240.0);
  EXPECT_DOUBLE_EQ(d.x(), 0.0);
  EXPECT_DOUBLE_EQ(d.y(), 0.0);
  Eigen::Vector2d uv = K.project(Vec3(0.3, -0.2, 2.0));
  Vec3 back = K.rayCamera(uv.x(), uv.y()) * 2.0;
  EXPECT_NEAR((back - Vec3(0.3, -0.2, 2.0)).norm(), 0.0, 1e-12);
}

TEST(Camera, LookAtGivesOpenCvAxes) {
  Pose p = Pose::lookAt(Vec3(1, 2, 3), Vec3(1, 7, 3), Vec3::UnitZ());
  Mat3 R = p.rotation();
  EXPECT_NEAR((R.col(2) - Vec3(0, 1, 0)).norm(), 0, 1e-12);   // z forward
  EXPECT_NEAR((R.col(1) - Vec3(0, 0, -1)).norm(), 0, 1e-12);  // y down
  EXPECT_NEAR((R.col(0) - Vec3(1, 0, 0)).norm(), 0, 1e-12);   // x right
}

TEST(Camera, LoadsSharedBenchCamera) {
  std::string path = std::string(INET_SHARED_DIR) + "/bench/camera.json";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "../shared/bench/camera.json not found";
  CameraFile c = loadCameraJson(path);
  EXPECT_EQ(c.intrinsics.width, 640);
  EXPECT_DOUBLE_EQ(c.intrinsics.cx, 320.0);
  EXPECT_NEAR((c.T_world_camera.t - Vec3(0.5, 0.45, 1.55)).norm(), 0, 1e-12);
  Vec3 fwd = c.T_world_camera.rotation().col(2);
  EXPECT_NEAR((fwd - (Vec3(3.2, 3.5, 0.85) - Vec3(0.5, 0.45, 1.55)).normalized()).norm(), 0, 1e-12);
}

TEST(Camera, RejectsBadFiles) {
  auto dir = std::filesystem::temp_directory_path() / "inet_camera_test";
  std::filesystem::create_directories(dir);
  const char* cases[] = {
      "{\"width\": 640}",
      "{\"width\": 640, \"height\": 480, \"fx\": -1, \"fy\": 600, \"position\": [0,0,0], "
      "\"look_at\": [1,0,0]}",
      "{\"width\": 640, \"height\": 480, \"fx\": 600, \"fy\": 600, \"position\": [0,0,0], "
      "\"look_at\": [0,0,0]}",
      "not json",
  };
  for (const char* c : cases) {
    auto p = dir / "cam.json";
    std::ofstream(p) << c;
    EXPECT_THROW(loadCameraJson(p.string()), InputError) << c;
  }
}

TEST(Passes, ParseList) {
  EXPECT_EQ(parsePassList("all", "t"), kAllPasses);
  EXPECT_EQ(parsePassList("depth,label", "t"),
            static_cast<PassMask>(Pass::DepthZ) | static_cast<PassMask>(Pass::Label));
  EXPECT_THROW(parsePassList("depth,colour", "t"), InputError);
  EXPECT_THROW(parsePassList("", "t"), InputError);
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {
// Found by fuzz_camera_json: a number too large for a double made nlohmann throw out_of_range,
// which escaped as an unknown exception instead of an InputError.
TEST(Camera, HugeNumberIsAnInputError) {
  EXPECT_THROW(parseCameraJson("{\"width\": 3e3333330}", "cam.json"), InputError);
  EXPECT_THROW(parseCameraJson(
                   "{\"width\": 1e300, \"height\": 4, \"fx\": 1, \"fy\": 1, \"position\": [0,0,0], "
                   "\"look_at\": [1,0,0]}",
                   "cam.json"),
               InputError);
}
}  // namespace
}  // namespace inet
