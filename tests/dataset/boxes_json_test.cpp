// boxes.json: visibility counting, the file's structure, and that every box holds what the
// camera sees of its instance (the instance pixels of real renders lie inside the projection of
// the instance's box, which also checks the camera-frame transform).
#include "dataset/boxes_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "render/renderer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"

namespace inet {
namespace {

TEST(InstanceVisibility, CountsPixelsAndBoxes) {
  ImageU16 img(6, 4, 1, 0);
  img.at(1, 1) = 7;
  img.at(4, 2) = 7;
  img.at(5, 3) = 3;
  const auto v = instanceVisibility(img);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].instance, 3);
  EXPECT_EQ(v[0].pixels, 1);
  EXPECT_EQ(v[1].instance, 7);
  EXPECT_EQ(v[1].pixels, 2);
  EXPECT_EQ(v[1].x0, 1);
  EXPECT_EQ(v[1].y0, 1);
  EXPECT_EQ(v[1].x1, 4);
  EXPECT_EQ(v[1].y1, 2);
}

TEST(BoxesJson, BoxesContainTheirVisiblePixelsInRealRenders) {
  const Scene scene = makeDefaultScene();
  const auto boxes = instanceBoxes(scene);
  const Trajectory traj = builtinTrajectory(4, 2.0);  // four views half a second apart
  const CameraIntrinsics K = CameraIntrinsics::centred(160, 120, 150);
  Renderer r(scene);
  std::vector<std::vector<InstanceVisibility>> visible;
  std::vector<ImageU16> instance_images;
  for (const auto& p : traj.poses) {
    Frame f;
    r.renderGroundTruth(K, p.T_world_camera, static_cast<PassMask>(Pass::Instance), f);
    visible.push_back(instanceVisibility(f.instance));
    instance_images.push_back(f.instance);
  }
  const nlohmann::json j = nlohmann::json::parse(boxesJson(scene, boxes, traj, visible));
  EXPECT_EQ(j["format"], "interiornet boxes 1");
  ASSERT_EQ(j["objects"].size(), boxes.size());
  ASSERT_EQ(j["frames"].size(), traj.size());
  int checked = 0;
  for (size_t k = 0; k < traj.size(); ++k) {
    const auto& jf = j["frames"][k];
    EXPECT_EQ(jf["t_ns"].get<int64_t>(), traj.poses[k].t_ns);
    ASSERT_EQ(jf["visible"].size(), visible[k].size());
    int64_t sum = 0;
    for (const auto& e : jf["visible"]) {
      sum += e["pixels"].get<int64_t>();
      const int id = e["instance"];
      const auto c = e["centre_cam"].get<std::vector<double>>();
      const auto q = e["q_cam_box"].get<std::vector<double>>();
      const Quat q_cb(q[0], q[1], q[2], q[3]);
      const InstanceBox* b = nullptr;
      for (const auto& x : boxes)
        if (x.instance == id) b = &x;
      ASSERT_NE(b, nullptr);
      // the box's corners in the camera: from the json's camera-frame pose
      double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
      bool all_in_front = true;
      for (int i = 0; i < 8; ++i) {
        const Vec3 s(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
        const Vec3 p = Vec3(c[0], c[1], c[2]) + q_cb * s.cwiseProduct(b->box.size);
        // and the same corner from the world box and the pose
        const Vec3 pw = b->box.corners()[i];
        EXPECT_NEAR((traj.poses[k].T_world_camera.inverse() * pw - p).norm(), 0, 1e-5);
        if (p.z() <= 0.01) {
          all_in_front = false;
          break;
        }
        const double u = K.fx * p.x() / p.z() + K.cx, v = K.fy * p.y() / p.z() + K.cy;
        u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
      }
      if (!all_in_front) continue;  // a box through the image plane projects unbounded
      // every pixel of the instance (pixel (x, y) spans [x, x+1) x [y, y+1)) touches the
      // projected box, to 1e-3 px
      const ImageU16& inst = instance_images[k];
      for (int y = 0; y < inst.height; ++y)
        for (int x = 0; x < inst.width; ++x)
          if (inst.at(x, y) == id) {
            ASSERT_GE(x + 0.5, u0 - 1e-3) << "instance " << id << " frame " << k;
            ASSERT_LE(x + 0.5, u1 + 1e-3) << "instance " << id << " frame " << k;
            ASSERT_GE(y + 0.5, v0 - 1e-3) << "instance " << id << " frame " << k;
            ASSERT_LE(y + 0.5, v1 + 1e-3) << "instance " << id << " frame " << k;
          }
      ++checked;
    }
    // every labelled pixel is counted once
    int64_t labelled = 0;
    for (uint16_t v : instance_images[k].data) labelled += v != 0;
    EXPECT_EQ(sum, labelled);
  }
  EXPECT_GE(checked, 8) << "too few boxes wholly in front of the camera to check";
}

TEST(BoxesJson, SameInputsSameBytes) {
  const Scene scene = makeDefaultScene();
  const auto boxes = instanceBoxes(scene);
  const Trajectory traj = builtinTrajectory(2, 25.0);
  std::vector<std::vector<InstanceVisibility>> visible(2);
  EXPECT_EQ(boxesJson(scene, boxes, traj, visible), boxesJson(scene, boxes, traj, visible));
}

}  // namespace
}  // namespace inet
