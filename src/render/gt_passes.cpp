#include "render/gt_passes.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace inet {
namespace {

constexpr int kTile = 32;  // pixels per tile side; a multiple of the 4x4 packet block

void allocate(ImageF& img, const CameraIntrinsics& K, int channels, bool on) {
  if (!on) {
    img = {};
    return;
  }
  if (img.width != K.width || img.height != K.height || img.channels != channels)
    img = ImageF(K.width, K.height, channels);
}

template <typename T>
void allocateInt(Image<T>& img, const CameraIntrinsics& K, bool on) {
  if (!on) {
    img = {};
    return;
  }
  if (img.width != K.width || img.height != K.height || img.channels != 1)
    img = Image<T>(K.width, K.height, 1);
}

struct PassWriter {
  const EmbreeScene& scene;
  const CameraIntrinsics& K;
  Eigen::Matrix3f R_camera_world;
  PassMask passes;
  Frame& frame;

  void miss(int x, int y) const {
    if (has(passes, Pass::DepthZ)) frame.depth_z.at(x, y) = 0.f;
    if (has(passes, Pass::DepthRay)) frame.depth_ray.at(x, y) = 0.f;
    if (has(passes, Pass::Normal))
      for (int c = 0; c < 3; ++c) frame.normal.at(x, y, c) = 0.f;
    if (has(passes, Pass::Albedo))
      for (int c = 0; c < 3; ++c) frame.albedo.at(x, y, c) = 0.f;
    if (has(passes, Pass::Label)) frame.label.at(x, y) = 0;
    if (has(passes, Pass::Instance)) frame.instance.at(x, y) = 0;
  }

  void hit(int x, int y, float t, const Eigen::Vector3f& d_cam, int object, const Vec3f& ng) const {
    const ObjectShading& s = scene.object(object);
    if (has(passes, Pass::DepthZ)) frame.depth_z.at(x, y) = t;
    if (has(passes, Pass::DepthRay)) frame.depth_ray.at(x, y) = t * d_cam.norm();
    if (has(passes, Pass::Normal)) {
      Vec3f n = R_camera_world * scene.worldNormal(object, ng);
      if (n.dot(d_cam) > 0) n = -n;
      for (int c = 0; c < 3; ++c) frame.normal.at(x, y, c) = n[c];
    }
    if (has(passes, Pass::Albedo))
      for (int c = 0; c < 3; ++c) frame.albedo.at(x, y, c) = s.albedo[c];
    if (has(passes, Pass::Label)) frame.label.at(x, y) = s.nyu40;
    if (has(passes, Pass::Instance)) frame.instance.at(x, y) = s.instance;
  }
};

}  // namespace

void renderGroundTruth(const EmbreeScene& scene, const CameraIntrinsics& K,
                       const Pose& T_world_camera, PassMask passes, Frame& frame) {
  allocate(frame.depth_z, K, 1, has(passes, Pass::DepthZ));
  allocate(frame.depth_ray, K, 1, has(passes, Pass::DepthRay));
  allocate(frame.normal, K, 3, has(passes, Pass::Normal));
  allocate(frame.albedo, K, 3, has(passes, Pass::Albedo));
  allocateInt(frame.label, K, has(passes, Pass::Label));
  allocateInt(frame.instance, K, has(passes, Pass::Instance));
  frame.passes = (frame.passes & static_cast<PassMask>(Pass::Rgb)) | (passes & kGroundTruthPasses);

  const Eigen::Matrix3f R_world_camera = T_world_camera.rotation().cast<float>();
  const Eigen::Vector3f origin = T_world_camera.t.cast<float>();
  PassWriter writer{scene, K, R_world_camera.transpose(), passes, frame};

  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, K.height, kTile, 0, K.width, kTile),
      [&](const tbb::blocked_range2d<int>& r) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        Eigen::Vector3f d_cam[16];
        for (int by = r.rows().begin(); by < r.rows().end(); by += 4) {
          for (int bx = r.cols().begin(); bx < r.cols().end(); bx += 4) {
            for (int k = 0; k < 16; ++k) {
              int x = bx + (k & 3), y = by + (k >> 2);
              bool in = x < r.cols().end() && y < r.rows().end();
              valid[k] = in ? -1 : 0;
              d_cam[k] = K.rayCamera(x + 0.5, y + 0.5).cast<float>();
              Eigen::Vector3f d = R_world_camera * d_cam[k];
              rh.ray.org_x[k] = origin.x();
              rh.ray.org_y[k] = origin.y();
              rh.ray.org_z[k] = origin.z();
              rh.ray.dir_x[k] = d.x();
              rh.ray.dir_y[k] = d.y();
              rh.ray.dir_z[k] = d.z();
              rh.ray.tnear[k] = 0.f;
              rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
              rh.ray.time[k] = 0.f;
              rh.ray.mask[k] = 0xffffffffu;
              rh.ray.id[k] = static_cast<unsigned>(k);
              rh.ray.flags[k] = 0;
              rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
              rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene.handle(), &ctx, &rh);
            for (int k = 0; k < 16; ++k) {
              if (!valid[k]) continue;
              int x = bx + (k & 3), y = by + (k >> 2);
              if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
                writer.miss(x, y);
                continue;
              }
              int object = scene.objectOf(rh.hit.geomID[k], rh.hit.instID[0][k]);
              writer.hit(x, y, rh.ray.tfar[k], d_cam[k], object,
                         Vec3f(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]));
            }
          }
        }
      });
}

}  // namespace inet
