#include "render/gt_passes.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace inet {
namespace {

constexpr int kTile = 32;  // pixels per tile side; a multiple of the 4x4 packet block

/// (Re)allocates `img` to the camera size with `channels`, or frees it when the pass is off.
template <typename T>
void allocate(Image<T>& img, const CameraIntrinsics& K, int channels, bool on) {
  if (!on) {
    img = {};
    return;
  }
  if (img.width != K.width || img.height != K.height || img.channels != channels)
    img = Image<T>(K.width, K.height, channels);
}

/// Writes one pixel of every selected pass. Pointers are resolved once per frame so the per-pixel
/// work is a handful of stores (this loop, not Embree, used to be a third of the frame time).
struct PassWriter {
  const EmbreeScene& scene;
  float* depth_z;
  float* depth_ray;
  float* normal;
  float* albedo;
  uint8_t* label;
  uint16_t* instance;

  void miss(size_t i) const {
    if (depth_z) depth_z[i] = 0.f;
    if (depth_ray) depth_ray[i] = 0.f;
    if (normal) normal[3 * i] = normal[3 * i + 1] = normal[3 * i + 2] = 0.f;
    if (albedo) albedo[3 * i] = albedo[3 * i + 1] = albedo[3 * i + 2] = 0.f;
    if (label) label[i] = 0;
    if (instance) instance[i] = 0;
  }

  /// One hit. t: ray parameter; z_per_t: camera-frame z per unit t (1 for pinhole rays, whose
  /// direction has z = 1, so the z-depth is exactly t); d_len: |d_camera|; d_world: the
  /// world ray's direction; prim, u, v, ng_object: Embree's hit; R_cw: world-to-camera rotation of the pose
  /// this pixel was traced from; spread: the angle of one pixel (texture footprint).
  void hit(size_t i, float t, float z_per_t, float d_len, const Eigen::Vector3f& d_world, int object, unsigned prim, float u, float v,
           const Vec3f& ng_object, const Eigen::Matrix3f& R_cw, float spread) const {
    const ObjectShading& s = scene.object(object);
    if (depth_z) depth_z[i] = z_per_t == 1.f ? t : std::max(0.f, t * z_per_t);
    if (depth_ray) depth_ray[i] = t * d_len;
    Vec3f a = s.albedo;
    if (!normal && !albedo) return writeIds(i, s);
    // the geometric normal decides which side faces the camera; a smooth normal near a
    // silhouette may point away while the surface itself faces the camera
    // (unnormalised: the flat common case normalises once, below)
    Vec3f n = s.normal_to_world * ng_object;
    const float flip = n.dot(d_world) > 0 ? -1.f : 1.f;
    if (!s.plain()) {
      const Vec3f ng = n.normalized();
      // smooth normals and textured albedo; the normal pass leaves normal maps out (they fake
      // detail the depth pass does not have)
      SurfacePoint sp;
      const float dist = t * d_len;
      scene.surface(object, prim, u, v, ng, d_world / d_len, spread * dist, sp,
                    /*normal_map=*/false);
      n = sp.ns;
      a = sp.albedo;
    }
    if (normal) {
      n = (R_cw * (flip * n)).normalized();
      normal[3 * i] = n.x();
      normal[3 * i + 1] = n.y();
      normal[3 * i + 2] = n.z();
    }
    if (albedo) {
      albedo[3 * i] = a.x();
      albedo[3 * i + 1] = a.y();
      albedo[3 * i + 2] = a.z();
    }
    writeIds(i, s);
  }

  void writeIds(size_t i, const ObjectShading& s) const {
    if (label) label[i] = s.nyu40;
    if (instance) instance[i] = s.instance;
  }
};

template <typename T>
T* dataOrNull(Image<T>& img) {
  return img.empty() ? nullptr : img.data.data();
}

}  // namespace

void renderGroundTruth(const EmbreeScene& scene, const LensModel& lens, const Pose& T_world_camera,
                       PassMask passes, Frame& frame, const CameraExposure* exposure) {
  const CameraIntrinsics& K = lens.K;
  allocate(frame.depth_z, K, 1, has(passes, Pass::DepthZ));
  allocate(frame.depth_ray, K, 1, has(passes, Pass::DepthRay));
  allocate(frame.normal, K, 3, has(passes, Pass::Normal));
  allocate(frame.albedo, K, 3, has(passes, Pass::Albedo));
  allocate(frame.label, K, 1, has(passes, Pass::Label));
  allocate(frame.instance, K, 1, has(passes, Pass::Instance));
  frame.passes = (frame.passes & bit(Pass::Rgb)) | (passes & kGroundTruthPasses);
  if ((passes & kGroundTruthPasses) == 0) return;

  const Eigen::Matrix3f R_world_camera = T_world_camera.rotation().cast<float>();
  const Eigen::Vector3f origin = T_world_camera.t.cast<float>();
  PassWriter writer{scene,
                    dataOrNull(frame.depth_z),
                    dataOrNull(frame.depth_ray),
                    dataOrNull(frame.normal),
                    dataOrNull(frame.albedo),
                    dataOrNull(frame.label),
                    dataOrNull(frame.instance)};
  // Plain pinhole: the camera-frame direction through pixel centre (x, y) is
  // (ax*x + bx, ay*y + by, 1), computed incrementally. Other lenses ask generateRay.
  const bool simple = lens.type == LensType::Pinhole && !lens.hasDistortion();
  const bool moving = exposure != nullptr && exposure->moving();
  // moving objects: each row's rays carry the time of that row's ground truth in the window
  const bool timed = exposure != nullptr && exposure->span() > 0 && scene.hasMotion();
  std::vector<float> row_time(timed ? K.height : 0, 0.f);
  for (int y = 0; timed && y < K.height; ++y)
    row_time[y] = static_cast<float>(groundTruthTime(exposure->shutter, 0, y, K.height)) /
                  static_cast<float>(exposure->span());
  std::vector<Eigen::Matrix3f> row_R;  // per-row camera pose of a moving (rolling) exposure
  std::vector<Eigen::Vector3f> row_t;
  std::vector<Eigen::Matrix3f> row_Rt;  // their transposes (world to camera)
  const Eigen::Matrix3f R_camera_world = R_world_camera.transpose();
  if (moving) {
    for (int y = 0; y < K.height; ++y) {
      Pose p = exposure->groundTruthPose(y, K.height);
      row_R.push_back(p.rotation().cast<float>());
      row_Rt.push_back(row_R.back().transpose());
      row_t.push_back(p.t.cast<float>());
    }
  }
  const auto spread = static_cast<float>(1.0 / std::sqrt(K.fx * K.fy));  // radians per pixel
  const float ax = static_cast<float>(1.0 / K.fx), bx = static_cast<float>((0.5 - K.cx) / K.fx);
  const float ay = static_cast<float>(1.0 / K.fy), by = static_cast<float>((0.5 - K.cy) / K.fy);

  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, K.height, kTile, 0, K.width, kTile),
      [&](const tbb::blocked_range2d<int>& r) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        float d_len[16], z_per_t[16];
        bool has_ray[16];
        for (int k = 0; k < 16; ++k) {
          rh.ray.time[k] = 0.f;
          rh.ray.mask[k] = 0xffffffffu;
          rh.ray.id[k] = static_cast<unsigned>(k);
          rh.ray.flags[k] = 0;
        }
        for (int by0 = r.rows().begin(); by0 < r.rows().end(); by0 += 4) {
          for (int bx0 = r.cols().begin(); bx0 < r.cols().end(); bx0 += 4) {
            for (int k = 0; k < 16; ++k) {
              int x = bx0 + (k & 3), y = by0 + (k >> 2);
              bool inside = x < r.cols().end() && y < r.rows().end();
              Eigen::Vector3f o_cam = Eigen::Vector3f::Zero(), d_cam(ax * x + bx, ay * y + by, 1.f);
              has_ray[k] = true;
              if (!simple && inside) {
                CameraRay cr;
                has_ray[k] = generateRay(lens, x + 0.5, y + 0.5, kLensCentre, cr);
                o_cam = cr.origin.cast<float>();
                d_cam = cr.dir.cast<float>();
              }
              valid[k] = (inside && has_ray[k]) ? -1 : 0;
              d_len[k] = d_cam.norm();
              z_per_t[k] = simple ? 1.f : d_cam.z();
              const Eigen::Matrix3f& Rr = moving && inside ? row_R[y] : R_world_camera;
              const Eigen::Vector3f& tr = moving && inside ? row_t[y] : origin;
              Eigen::Vector3f d = Rr * d_cam, o = Rr * o_cam + tr;
              rh.ray.org_x[k] = o.x();
              rh.ray.org_y[k] = o.y();
              rh.ray.org_z[k] = o.z();
              rh.ray.dir_x[k] = d.x();
              rh.ray.dir_y[k] = d.y();
              rh.ray.dir_z[k] = d.z();
              rh.ray.tnear[k] = 0.f;
              rh.ray.time[k] = timed && inside ? row_time[y] : 0.f;
              rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
              rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
              rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene.handle(), &ctx, &rh);
            for (int k = 0; k < 16; ++k) {
              int x = bx0 + (k & 3), y = by0 + (k >> 2);
              if (x >= r.cols().end() || y >= r.rows().end()) continue;
              size_t i = static_cast<size_t>(y) * K.width + x;
              if (!has_ray[k] || rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
                writer.miss(i);
                continue;
              }
              int object = scene.objectOf(rh.hit.geomID[k], rh.hit.instID[0][k]);
              writer.hit(i, rh.ray.tfar[k], z_per_t[k], d_len[k],
                         Eigen::Vector3f(rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]), object,
                         rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k],
                         Vec3f(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]),
                         moving ? row_Rt[y] : R_camera_world, spread);
            }
          }
        }
      });
}

}  // namespace inet
