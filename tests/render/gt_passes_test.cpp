// Ground-truth passes against an independent double-precision reference tracer on an analytic
// scene: a wall plane, an axis-aligned box, a rotated non-uniformly scaled box (instanced: the box
// mesh is shared) and an analytic sphere. Depth and ray depth must be exact to 1e-4 m and normals
// to 1e-4 at every pixel; labels and instance ids exactly as assigned.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include "render/renderer.h"
#include "scene/primitives.h"

namespace inet {
namespace {

struct RefHit {
  double t = std::numeric_limits<double>::infinity();
  Vec3 n_world = Vec3::Zero();
  int object = -1;
  bool ambiguous = false;  // the pixel centre ray grazes an edge: label may go either way
};

// Ray against the unit cube [-0.5, 0.5]^3 placed by affine A (slab test in object space).
std::optional<RefHit> hitBox(const Mat4& A, const Vec3& o, const Vec3& d) {
  Mat4 inv = A.inverse();
  Vec3 lo = (inv * o.homogeneous()).head<3>(), ld = inv.block<3, 3>(0, 0) * d;
  double t0 = -1e30, t1 = 1e30;
  int axis = -1;
  double sign = 0;
  for (int k = 0; k < 3; ++k) {
    double a = (-0.5 - lo[k]) / ld[k], b = (0.5 - lo[k]) / ld[k];
    double s = -1;
    if (a > b) {
      std::swap(a, b);
      s = 1;
    }
    if (a > t0) {
      t0 = a;
      axis = k;
      sign = s;
    }
    t1 = std::min(t1, b);
  }
  if (t0 > t1 || t0 <= 0) return std::nullopt;
  RefHit h;
  h.t = t0;
  Vec3 n_local = Vec3::Zero();
  n_local[axis] = sign;
  h.n_world = (inv.block<3, 3>(0, 0).transpose() * n_local).normalized();
  Vec3 p = lo + t0 * ld;
  for (int k = 0; k < 3; ++k)
    if (k != axis && std::abs(std::abs(p[k]) - 0.5) < 1e-4) h.ambiguous = true;
  if (t1 - t0 < 1e-4) h.ambiguous = true;
  return h;
}

std::optional<RefHit> hitSphere(const Vec3& c, double r, const Vec3& o, const Vec3& d) {
  Vec3 oc = o - c;
  double a = d.squaredNorm(), b = 2 * oc.dot(d), cc = oc.squaredNorm() - r * r;
  double disc = b * b - 4 * a * cc;
  if (disc < 0) return std::nullopt;
  double t = (-b - std::sqrt(disc)) / (2 * a);
  if (t <= 0) return std::nullopt;
  RefHit h;
  h.t = t;
  h.n_world = (o + t * d - c).normalized();
  h.ambiguous = disc < 1e-6 * b * b;
  return h;
}

class GroundTruthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Mesh box = makePrimitive("box", {}, "test", "box");
    box.id = "box";
    Mesh quad = makePrimitive("quad", {}, "test", "quad");
    quad.id = "quad";
    Mesh sphere = makePrimitive("sphere", {{"radius", 1.0}}, "test", "sphere");
    sphere.id = "sphere";
    scene_.meshes = {box, quad, sphere};
    Material m;
    m.id = "grey";
    m.albedo = {0.25f, 0.5f, 0.75f};
    scene_.materials = {m};
    // camera at (0,0,1) looking along +y; wall plane at y = 3 facing the camera
    wall_ = (Eigen::Translation3d(0, 3, 1) * Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()) *
             Eigen::Scaling(Vec3(20, 20, 1)))
                .matrix();
    box_ = (Eigen::Translation3d(-0.6, 2.0, 0.8) * Eigen::Scaling(Vec3(0.5, 0.4, 0.6))).matrix();
    rbox_ =
        (Eigen::Translation3d(0.1, 1.6, 1.3) * Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) *
         Eigen::Scaling(Vec3(0.3, 0.2, 0.25)))
            .matrix();
    sphere_c_ = Vec3(0.7, 2.2, 0.9);
    sphere_r_ = 0.35;
    Mat4 sph = (Eigen::Translation3d(sphere_c_) * Eigen::Scaling(sphere_r_)).matrix();
    add("wall", 1, 1, wall_, 1);
    add("box", 0, 7, box_, 2);
    add("rbox", 0, 29, rbox_, 3);
    add("ball", 2, 40, sph, 300);
    pose_ = Pose::lookAt(Vec3(0, 0, 1), Vec3(0, 5, 1), Vec3::UnitZ());
  }

  void add(const char* name, int mesh, int label, const Mat4& T, int instance) {
    Object o;
    o.name = name;
    o.mesh = mesh;
    o.material = 0;
    o.nyu40 = label;
    o.instance = instance;
    o.T_world_object = T;
    scene_.objects.push_back(o);
  }

  RefHit reference(const Vec3& o, const Vec3& d) const {
    RefHit best;
    auto consider = [&](std::optional<RefHit> h, int object) {
      if (!h) return;
      if (std::abs(h->t - best.t) < 1e-4) h->ambiguous = best.ambiguous = true;
      if (h->t < best.t) {
        bool amb = h->ambiguous || (best.object >= 0 && std::abs(h->t - best.t) < 1e-4);
        best = *h;
        best.object = object;
        best.ambiguous = amb;
      }
    };
    // wall: plane y = 3
    if (d.y() > 0) {
      RefHit h;
      h.t = (3.0 - o.y()) / d.y();
      h.n_world = Vec3(0, -1, 0);
      consider(h, 0);
    }
    consider(hitBox(box_, o, d), 1);
    consider(hitBox(rbox_, o, d), 2);
    consider(hitSphere(sphere_c_, sphere_r_, o, d), 3);
    return best;
  }

  Scene scene_;
  Mat4 wall_, box_, rbox_;
  Vec3 sphere_c_;
  double sphere_r_;
  Pose pose_;
};

TEST_F(GroundTruthTest, DepthNormalsLabelsMatchAnalyticReference) {
  Renderer r(scene_);
  CameraIntrinsics K;
  Frame f;
  r.renderGroundTruth(K, pose_, kGroundTruthPasses, f);
  ASSERT_EQ(f.depth_z.width, 640);
  const Mat3 R = pose_.rotation();
  int ambiguous = 0, checked = 0, seen[4] = {0, 0, 0, 0};
  double max_dz = 0, max_dn = 0;
  for (int y = 0; y < K.height; ++y) {
    for (int x = 0; x < K.width; ++x) {
      Vec3 d_cam((x + 0.5 - K.cx) / K.fx, (y + 0.5 - K.cy) / K.fy, 1.0);
      RefHit h = reference(pose_.t, R * d_cam);
      ASSERT_GE(h.object, 0) << "reference misses at " << x << "," << y;
      if (h.ambiguous) {
        ++ambiguous;
        continue;
      }
      ++checked;
      ++seen[h.object];
      const Object& o = scene_.objects[h.object];
      ASSERT_EQ(f.label.at(x, y), o.nyu40) << "pixel " << x << "," << y;
      ASSERT_EQ(f.instance.at(x, y), o.instance) << "pixel " << x << "," << y;
      max_dz = std::max(max_dz, std::abs(f.depth_z.at(x, y) - h.t));
      max_dz = std::max(max_dz, std::abs(f.depth_ray.at(x, y) - h.t * d_cam.norm()));
      Vec3 n_cam = R.transpose() * h.n_world;
      if (n_cam.dot(d_cam) > 0) n_cam = -n_cam;
      for (int c = 0; c < 3; ++c)
        max_dn = std::max(max_dn, std::abs(f.normal.at(x, y, c) - n_cam[c]));
      EXPECT_FLOAT_EQ(f.albedo.at(x, y, 1), 0.5f);
    }
  }
  EXPECT_LT(max_dz, 1e-4) << "depth error (m)";
  EXPECT_LT(max_dn, 1e-4) << "normal error";
  EXPECT_LT(ambiguous, K.width * K.height / 200) << "too many edge pixels skipped";
  for (int i = 0; i < 4; ++i) EXPECT_GT(seen[i], 1000) << "object " << i << " barely visible";
}

TEST_F(GroundTruthTest, MissesAreZero) {
  Scene empty_view = scene_;
  Renderer r(empty_view);
  CameraIntrinsics K;
  Frame f;
  // look away from everything (towards -y)
  r.renderGroundTruth(K, Pose::lookAt(Vec3(0, 0, 1), Vec3(0, -5, 1), Vec3::UnitZ()),
                      kGroundTruthPasses, f);
  for (size_t i = 0; i < f.depth_z.pixelCount(); ++i) {
    ASSERT_EQ(f.depth_z.data[i], 0.f);
    ASSERT_EQ(f.label.data[i], 0);
    ASSERT_EQ(f.instance.data[i], 0);
  }
}

TEST_F(GroundTruthTest, OddImageSizesAndOffCentrePrincipalPoint) {
  Renderer r(scene_);
  CameraIntrinsics K;
  K.width = 67;
  K.height = 35;
  K.fx = 50;
  K.fy = 45;
  K.cx = 30.25;
  K.cy = 20.5;
  Frame f;
  r.renderGroundTruth(K, pose_, kGroundTruthPasses, f);
  const Mat3 R = pose_.rotation();
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      Vec3 d_cam((x + 0.5 - K.cx) / K.fx, (y + 0.5 - K.cy) / K.fy, 1.0);
      RefHit h = reference(pose_.t, R * d_cam);
      if (h.ambiguous) continue;
      ASSERT_NEAR(f.depth_z.at(x, y), h.t, 1e-4) << x << "," << y;
    }
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

// Rolling shutter: with the camera moving during readout, row y of the ground truth must equal
// row y of a static render from the pose at the middle of that row's exposure.
TEST_F(GroundTruthTest, RollingShutterRowsUseTheirOwnPose) {
  Renderer r(scene_);
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 60);
  CameraExposure ex;
  ex.T_world_camera_open = pose_;
  ex.T_world_camera_close = Pose::lookAt(Vec3(0.3, 0.1, 1.05), Vec3(0.5, 5, 1), Vec3::UnitZ());
  ex.shutter.exposure_ns = 2000000;
  ex.shutter.readout_ns = 30000000;
  RenderOptions opt;
  opt.passes = kGroundTruthPasses;
  Frame rolling;
  r.render(LensModel::pinhole(K), ex, opt, 0, rolling);
  for (int y : {0, 17, 47}) {
    Frame still;
    r.renderGroundTruth(K, ex.groundTruthPose(y, K.height), kGroundTruthPasses, still);
    for (int x = 0; x < K.width; ++x) {
      ASSERT_EQ(rolling.depth_z.at(x, y), still.depth_z.at(x, y)) << x << "," << y;
      ASSERT_EQ(rolling.instance.at(x, y), still.instance.at(x, y)) << x << "," << y;
      for (int c = 0; c < 3; ++c) ASSERT_EQ(rolling.normal.at(x, y, c), still.normal.at(x, y, c));
    }
  }
  // and the first and last rows really come from different poses
  Frame first;
  r.renderGroundTruth(K, ex.groundTruthPose(0, K.height), kGroundTruthPasses, first);
  int differ = 0;
  for (int x = 0; x < K.width; ++x) differ += first.depth_z.at(x, 47) != rolling.depth_z.at(x, 47);
  EXPECT_GT(differ, K.width / 2);
}

// A shutter without motion changes nothing: same bytes as the static camera.
TEST_F(GroundTruthTest, StillExposureEqualsStaticCamera) {
  Renderer r(scene_);
  const CameraIntrinsics K = CameraIntrinsics::centred(40, 30, 40);
  RenderOptions opt;
  opt.spp = 4;
  CameraExposure ex = CameraExposure::fixed(pose_);
  ex.shutter.exposure_ns = 10000000;
  Frame a, b;
  r.render(LensModel::pinhole(K), ex, opt, 3, a);
  r.render(K, pose_, opt, 3, b);
  EXPECT_EQ(a.rgb.data, b.rgb.data);
  EXPECT_EQ(a.depth_z.data, b.depth_z.data);
}

}  // namespace
}  // namespace inet
