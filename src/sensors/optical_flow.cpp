#include "sensors/optical_flow.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "scene/scene.h"
#include "sensors/so3.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;

bool sameMotion(const Pose& a, const Pose& b) {
  return (a.t - b.t).norm() < 1e-9 && so3::angleBetween(a.q, b.q) < 1e-9;
}

void checkSize(const char* field, int w, int h, const CameraIntrinsics& K) {
  if (w != K.width || h != K.height)
    throw InputError("optical flow", field,
                     fmt::format("is {}x{}, the lens is {}x{}", w, h, K.width, K.height));
}

void checkView(const FlowFrameView& f, const char* which, const CameraIntrinsics& K) {
  const std::string d = std::string(which) + ".depth", i = std::string(which) + ".instance";
  if (f.depth.channels != 1) throw InputError("optical flow", d, "needs 1 channel");
  checkSize(d.c_str(), f.depth.width, f.depth.height, K);
  if (!f.instance.empty()) {
    if (f.instance.channels != 1) throw InputError("optical flow", i, "needs 1 channel");
    checkSize(i.c_str(), f.instance.width, f.instance.height, K);
  }
}

double depthOf(DepthKind kind, const Vec3& p) {
  return kind == DepthKind::ZDepth ? p.z() : p.norm();
}

/// The visibility test of the header comment at continuous point uv of frame `to`.
/// check_instance: both frames have instance images.
bool visibleAt(const FlowFrameView& to, bool check_instance, bool wrap_u, const Eigen::Vector2d& uv,
               double z_pred, uint16_t inst, const FlowOptions& opt) {
  const int W = to.depth.width, H = to.depth.height;
  double u = uv.x();
  if (wrap_u) u -= W * std::floor(u / W);
  if (!(u >= 0 && u < W && uv.y() >= 0 && uv.y() < H)) return false;
  auto wrapX = [&](int x) { return wrap_u ? (x + W) % W : x; };
  // the nearest pixel must show the point's instance
  if (check_instance) {
    const int xn = std::min(static_cast<int>(u), W - 1),
              yn = std::min(static_cast<int>(uv.y()), H - 1);
    if (to.instance.at(xn, yn) != inst) return false;
  }
  // depth range of the same-instance taps of the bilinear footprint (taps of weight 0 left out)
  const double fx = u - 0.5, fy = uv.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const int nx = fx > x0 ? 2 : 1, ny = fy > y0 ? 2 : 1;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int dy = 0; dy < ny; ++dy)
    for (int dx = 0; dx < nx; ++dx) {
      const int x = wrapX(x0 + dx), y = y0 + dy;
      if (x < 0 || y < 0 || x >= W || y >= H) continue;
      if (check_instance && to.instance.at(x, y) != inst) continue;
      const double z = to.depth.at(x, y);
      if (!(z > 0) || !std::isfinite(z)) continue;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  if (!(hi > 0)) return false;
  return z_pred >= lo * (1 - opt.occlusion_rel_tol) - opt.occlusion_abs_tol_m &&
         z_pred <= hi * (1 + opt.occlusion_rel_tol) + opt.occlusion_abs_tol_m;
}

}  // namespace

bool backProjectPixel(const LensModel& lens, DepthKind kind, int x, int y, double d, Vec3& p) {
  CameraRay ray;
  if (!generateRay(lens, x + 0.5, y + 0.5, kLensCentre, ray)) return false;
  if (kind == DepthKind::ZDepth) {
    if (!(ray.dir.z() > 0)) return false;
    p = ray.origin + ray.dir * (d / ray.dir.z());
  } else {
    p = ray.origin + ray.dir.normalized() * d;
  }
  return true;
}

ObjectMotion ObjectMotion::inverse() const {
  ObjectMotion inv;
  for (const auto& [id, d] : delta) inv.delta.emplace(id, d.inverse());
  return inv;
}

std::string ObjectMotion::toString() const {
  std::string s = fmt::format("ObjectMotion[{} moving instance(s)", delta.size());
  for (const auto& [id, d] : delta) s += fmt::format("; {}: {}", id, d.toString());
  return s + "]";
}

ObjectMotion objectMotionBetween(const Scene& scene, double t0_s, double t1_s,
                                 const std::string& where) {
  std::map<int, bool> moving_instance;
  for (const Object& o : scene.objects)
    if (o.moving()) moving_instance[o.instance] = true;
  ObjectMotion m;
  std::map<int, std::string> first_part;  // instance -> name of the part that set its delta
  for (const Object& o : scene.objects) {
    if (!moving_instance.count(o.instance)) continue;
    // T(t1) T(t0)^-1 cancels the rest placement (and any scale in it): a rigid motion
    const Mat4 D = o.transformAt(t1_s) * o.transformAt(t0_s).inverse();
    const Pose d = Pose::fromMatrix(D);
    const auto id = static_cast<uint16_t>(o.instance);
    auto [it, inserted] = m.delta.emplace(id, d);
    if (inserted) {
      first_part[o.instance] = o.name;
    } else if (!sameMotion(it->second, d)) {
      throw InputError(where, "objects['" + o.name + "'].motion",
                       fmt::format("moves differently from '{}', another part of instance {}, "
                                   "between t = {} s and {} s (flow needs one rigid motion per "
                                   "instance id)",
                                   first_part[o.instance], o.instance, t0_s, t1_s));
    }
  }
  return m;
}

void FlowOptions::validate(const std::string& where) const {
  if (!(occlusion_rel_tol >= 0) || !std::isfinite(occlusion_rel_tol))
    throw InputError(where, "occlusion_rel_tol", "must be finite and >= 0");
  if (!(occlusion_abs_tol_m >= 0) || !std::isfinite(occlusion_abs_tol_m))
    throw InputError(where, "occlusion_abs_tol_m", "must be finite and >= 0");
}

FlowField forwardFlow(const FlowFrameView& from, const FlowFrameView& to, const LensModel& lens,
                      const ObjectMotion& motion, const FlowOptions& opt) {
  opt.validate("optical flow");
  const CameraIntrinsics& K = lens.K;
  checkView(from, "from", K);
  checkView(to, "to", K);
  const int W = K.width, H = K.height;
  // camera k -> camera k+1, for static points and for each moving instance
  const Pose T_to_world = to.T_world_camera.inverse();
  const Pose T_to_from = T_to_world * from.T_world_camera;
  std::vector<Pose> moving_T;
  std::vector<int> slot;  // instance id -> index into moving_T, -1 = static
  if (!motion.empty() && !from.instance.empty()) {
    slot.assign(65536, -1);
    for (const auto& [id, d] : motion.delta) {
      slot[id] = static_cast<int>(moving_T.size());
      moving_T.push_back(T_to_world * d * from.T_world_camera);
    }
  }
  const bool wrap_u = lens.type == LensType::Panorama;
  const bool use_instances = !from.instance.empty() && !to.instance.empty();
  const double period_u = 2 * kPi * K.fx;
  FlowField out{ImageF(W, H, 2, 0.f), ImageU8(W, H, 1, 0), ImageU8(W, H, 1, 0)};
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const double d = from.depth.at(x, y);
        Vec3 p;
        if (!(d > 0) || !std::isfinite(d) || !backProjectPixel(lens, opt.depth_kind, x, y, d, p))
          continue;  // no surface: neither valid nor occluded
        const uint16_t inst = from.instance.empty() ? 0 : from.instance.at(x, y);
        const int s = slot.empty() ? -1 : slot[inst];
        const Vec3 q = (s < 0 ? T_to_from : moving_T[s]) * p;
        Eigen::Vector2d uv;
        if (!project(lens, q, uv)) {
          out.occluded.at(x, y) = 1;  // no image in k+1 (behind the camera, outside the field)
          continue;
        }
        double du = uv.x() - (x + 0.5);
        if (wrap_u) du -= period_u * std::floor(du / period_u + 0.5);
        out.flow.at(x, y, 0) = static_cast<float>(du);
        out.flow.at(x, y, 1) = static_cast<float>(uv.y() - (y + 0.5));
        out.valid.at(x, y) = 1;
        if (!visibleAt(to, use_instances, wrap_u, uv, depthOf(opt.depth_kind, q), inst, opt))
          out.occluded.at(x, y) = 1;
      }
  });
  return out;
}

FlowField backwardFlow(const FlowFrameView& prev, const FlowFrameView& next, const LensModel& lens,
                       const ObjectMotion& motion, const FlowOptions& opt) {
  return forwardFlow(next, prev, lens, motion.inverse(), opt);
}

CameraVelocity cameraVelocity(const SplineState& s) {
  return {s.q_world_body.conjugate() * s.v_world, s.w_body};
}

namespace {

/// Instantaneous flow (px/s) at pixel (x, y) with depth z (already defaulted).
Eigen::Vector2d instFlowAt(const CameraIntrinsics& K, const CameraVelocity& vel, int x, int y,
                           double z) {
  const Vec3 X = z * K.rayCamera(x + 0.5, y + 0.5);
  const Vec3 Xd = -vel.v_cam - vel.w_cam.cross(X);
  const double Z2 = X.z() * X.z();
  return {K.fx * (Xd.x() * X.z() - X.x() * Xd.z()) / Z2,
          K.fy * (Xd.y() * X.z() - X.y() * Xd.z()) / Z2};
}

double depthOrDefault(const ImageF& depth, int x, int y, double no_depth_m) {
  const double z = depth.at(x, y);
  return z > 0 && std::isfinite(z) ? z : no_depth_m;
}

void checkInst(const ImageF& depth, const CameraIntrinsics& K, double no_depth_m) {
  if (depth.channels != 1) throw InputError("instantaneous flow", "depth", "needs 1 channel");
  checkSize("depth", depth.width, depth.height, K);
  if (!(no_depth_m > 0) || !std::isfinite(no_depth_m))
    throw InputError("instantaneous flow", "no_depth_m", "must be finite and > 0");
}

}  // namespace

ImageF instantaneousFlow(const ImageF& depth_z, const CameraIntrinsics& K,
                         const CameraVelocity& vel, double no_depth_m) {
  checkInst(depth_z, K, no_depth_m);
  ImageF out(K.width, K.height, 2);
  tbb::parallel_for(tbb::blocked_range<int>(0, K.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < K.width; ++x) {
        const Eigen::Vector2d f =
            instFlowAt(K, vel, x, y, depthOrDefault(depth_z, x, y, no_depth_m));
        out.at(x, y, 0) = static_cast<float>(f.x());
        out.at(x, y, 1) = static_cast<float>(f.y());
      }
  });
  return out;
}

double maxFlowSpeed(const ImageF& depth_z, const CameraIntrinsics& K, const CameraVelocity& vel,
                    double no_depth_m) {
  checkInst(depth_z, K, no_depth_m);
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, K.height), 0.0,
      [&](const tbb::blocked_range<int>& r, double m) {
        for (int y = r.begin(); y < r.end(); ++y)
          for (int x = 0; x < K.width; ++x)
            m = std::max(
                m, instFlowAt(K, vel, x, y, depthOrDefault(depth_z, x, y, no_depth_m)).norm());
        return m;
      },
      [](double a, double b) { return std::max(a, b); });
}

ImageF warpBackward(const ImageF& img_next, const FlowField& flow) {
  const int W = img_next.width, H = img_next.height, C = img_next.channels;
  INET_CHECK(flow.flow.width == W && flow.flow.height == H && flow.flow.channels == 2);
  INET_CHECK(flow.valid.width == W && flow.valid.height == H);
  ImageF out(W, H, C, 0.f);
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < W; ++x) {
        if (!flow.valid.at(x, y)) continue;
        // target in continuous coordinates is (x + 0.5 + u, y + 0.5 + v); taps at centres
        const double u = x + 0.5 + flow.flow.at(x, y, 0), v = y + 0.5 + flow.flow.at(x, y, 1);
        if (!(u >= 0 && u < W && v >= 0 && v < H)) continue;
        const double fx = u - 0.5, fy = v - 0.5;
        const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        const int xa = std::clamp(x0, 0, W - 1), xb = std::clamp(x0 + 1, 0, W - 1);
        const int ya = std::clamp(y0, 0, H - 1), yb = std::clamp(y0 + 1, 0, H - 1);
        for (int c = 0; c < C; ++c) {
          const double v00 = img_next.at(xa, ya, c), v10 = img_next.at(xb, ya, c);
          const double v01 = img_next.at(xa, yb, c), v11 = img_next.at(xb, yb, c);
          out.at(x, y, c) = static_cast<float>((1 - ty) * ((1 - tx) * v00 + tx * v10) +
                                               ty * ((1 - tx) * v01 + tx * v11));
        }
      }
  });
  return out;
}

namespace {

/// The Middlebury colour wheel (colorcode.cpp, makecolorwheel), RGB 0..255.
std::vector<std::array<int, 3>> colorWheel() {
  std::vector<std::array<int, 3>> w;
  constexpr int RY = 15, YG = 6, GC = 4, CB = 11, BM = 13, MR = 6;
  for (int i = 0; i < RY; ++i) w.push_back({255, 255 * i / RY, 0});
  for (int i = 0; i < YG; ++i) w.push_back({255 - 255 * i / YG, 255, 0});
  for (int i = 0; i < GC; ++i) w.push_back({0, 255, 255 * i / GC});
  for (int i = 0; i < CB; ++i) w.push_back({0, 255 - 255 * i / CB, 255});
  for (int i = 0; i < BM; ++i) w.push_back({255 * i / BM, 0, 255});
  for (int i = 0; i < MR; ++i) w.push_back({255, 0, 255 - 255 * i / MR});
  return w;
}

}  // namespace

ImageU8 flowToColor(const FlowField& flow, double max_px) {
  const int W = flow.flow.width, H = flow.flow.height;
  INET_CHECK(flow.flow.channels == 2 && flow.valid.width == W && flow.valid.height == H);
  if (!(max_px > 0)) {
    max_px = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (flow.valid.at(x, y))
          max_px = std::max(
              max_px, std::hypot(double{flow.flow.at(x, y, 0)}, double{flow.flow.at(x, y, 1)}));
    if (!(max_px > 0)) max_px = 1;
  }
  static const std::vector<std::array<int, 3>> wheel = colorWheel();
  const int ncols = static_cast<int>(wheel.size());
  ImageU8 out(W, H, 3, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!flow.valid.at(x, y)) continue;
      const double fu = flow.flow.at(x, y, 0) / max_px, fv = flow.flow.at(x, y, 1) / max_px;
      const double rad = std::hypot(fu, fv);
      const double a = std::atan2(-fv, -fu) / kPi;
      const double fk = (a + 1.0) / 2.0 * (ncols - 1);
      const int k0 = static_cast<int>(fk), k1 = (k0 + 1) % ncols;
      const double f = fk - k0;
      for (int b = 0; b < 3; ++b) {
        double col = ((1 - f) * wheel[k0][b] + f * wheel[k1][b]) / 255.0;
        col = rad <= 1 ? 1 - rad * (1 - col) : col * 0.75;
        out.at(x, y, b) = static_cast<uint8_t>(255.0 * col);
      }
    }
  return out;
}

}  // namespace inet
