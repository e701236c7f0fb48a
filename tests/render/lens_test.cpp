// Lens models: round trips, exactness against CameraIntrinsics, distortion against an
// independent transcription of OpenCV's documented model and exact rational values, thin-lens
// focus geometry, fisheye angles and panorama coverage of the sphere.
#include "render/lens.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"

namespace inet {
namespace {

constexpr double kPi = std::numbers::pi;

/// TUM RGB-D fr1 (freiburg1) calibration, OpenCV convention: fx fy cx cy d0..d4.
LensModel tumFr1() {
  CameraIntrinsics K;
  K.fx = 517.3;
  K.fy = 516.5;
  K.cx = 318.6 + 0.5;  // renderer convention: pixel centres at +0.5
  K.cy = 255.3 + 0.5;
  LensModel L = LensModel::pinhole(K);
  L.k1 = 0.2624;
  L.k2 = -0.9531;
  L.p1 = -0.0054;
  L.p2 = 0.0026;
  L.k3 = 1.1633;
  return L;
}

/// OpenCV's projectPoints, written down from its documentation (camera calibration page),
/// in OpenCV pixel coordinates: an independent reference for the forward model.
Eigen::Vector2d opencvProjectPoint(double fx, double fy, double cx_cv, double cy_cv,
                                   const double (&d)[5], const Vec3& P) {
  double xp = P.x() / P.z(), yp = P.y() / P.z();
  double r2 = xp * xp + yp * yp;
  double radial = 1 + d[0] * r2 + d[1] * r2 * r2 + d[4] * r2 * r2 * r2;
  double xpp = xp * radial + 2 * d[2] * xp * yp + d[3] * (r2 + 2 * xp * xp);
  double ypp = yp * radial + d[2] * (r2 + 2 * yp * yp) + 2 * d[3] * xp * yp;
  return {fx * xpp + cx_cv, fy * ypp + cy_cv};
}

/// 9 x 9 image points from corner to corner, inclusive: both image edges and all 4 corners.
std::vector<Eigen::Vector2d> cornerGrid(const CameraIntrinsics& K, int n = 9) {
  std::vector<Eigen::Vector2d> pts;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) pts.emplace_back(K.width * i / (n - 1.0), K.height * j / (n - 1.0));
  return pts;
}

CameraRay ray(const LensModel& L, double u, double v, Eigen::Vector2d lens_uv = kLensCentre) {
  CameraRay r;
  EXPECT_TRUE(generateRay(L, u, v, lens_uv, r)) << L.toString() << " at " << u << ", " << v;
  return r;
}

TEST(Lens, PinholeWithoutDistortionEqualsRayCameraExactly) {
  CameraIntrinsics K;
  K.fx = 577.7;
  K.fy = 581.1;
  K.cx = 321.3;
  K.cy = 238.9;
  LensModel L = LensModel::pinhole(K);
  for (double v : {0.0, 0.5, 17.25, 239.5, 479.999, 480.0})
    for (double u : {0.0, 0.5, 3.75, 319.5, 639.5, 640.0}) {
      CameraRay r = ray(L, u, v, {0.9, 0.1});
      Vec3 expected = K.rayCamera(u, v);
      EXPECT_EQ(r.dir.x(), expected.x());
      EXPECT_EQ(r.dir.y(), expected.y());
      EXPECT_EQ(r.dir.z(), 1.0);
      EXPECT_EQ(r.origin, Vec3::Zero());
      Vec3 p(u / 100 - 3, v / 200 - 1, 2.5);
      Eigen::Vector2d uv;
      ASSERT_TRUE(project(L, p, uv));
      EXPECT_NEAR((uv - K.project(p)).norm(), 0, 1e-10);
    }
  Eigen::Vector2d uv;
  EXPECT_FALSE(project(L, Vec3(0.1, 0.2, 0.0), uv));
  EXPECT_FALSE(project(L, Vec3(0.1, 0.2, -1.0), uv));
}

/// generateRay then project, for every model over corner-to-corner grids. Points are placed on
/// the ray at the thin lens's focus distance (the only depth where a thin lens ray images back
/// to its own pixel).
TEST(Lens, EveryModelRoundTripsBelowMicroPixel) {
  CameraIntrinsics K;
  LensModel fisheye220 = LensModel::fisheye(480, 220);
  fisheye220.K.width = 640;  // non-square image: the circle spans the shorter side
  fisheye220.K.cx = 320;
  std::vector<LensModel> lenses = {
      LensModel::pinhole(K),      tumFr1(),   LensModel::thinLens(K, 0.02, 1.7),
      LensModel::fisheye(),       fisheye220, LensModel::panorama(),
      LensModel::panorama(64, 32)};
  LensModel thin_distorted = tumFr1();
  thin_distorted.type = LensType::ThinLens;
  thin_distorted.aperture_radius_m = 0.05;
  thin_distorted.focus_distance_m = 3;
  lenses.push_back(thin_distorted);
  for (const LensModel& L : lenses) {
    ASSERT_NO_THROW(L.validate("test"));
    double max_err = 0;
    int rays = 0;
    for (const Eigen::Vector2d& px : cornerGrid(L.K, 33)) {
      for (Eigen::Vector2d lens_uv : {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.1, 0.93)}) {
        CameraRay r;
        if (!generateRay(L, px.x(), px.y(), lens_uv, r)) {
          // only the fisheye has image points without a ray: outside its circle
          ASSERT_EQ(L.type, LensType::Fisheye) << L.toString() << " at " << px.transpose();
          double rad = std::hypot(px.x() - L.K.cx, px.y() - L.K.cy);
          EXPECT_GT(rad, L.K.fx * L.fisheye_fov_deg * kPi / 360);
          continue;
        }
        double t = L.type == LensType::ThinLens ? L.focus_distance_m : 2.5;
        Eigen::Vector2d uv;
        ASSERT_TRUE(project(L, r.origin + t * r.dir, uv)) << L.toString() << px.transpose();
        Eigen::Vector2d err = uv - px;
        if (L.type == LensType::Panorama) {
          err.x() = std::remainder(err.x(), L.K.width);  // u = 0 and u = width are one meridian
          if (px.y() == 0 || px.y() == L.K.height) err.x() = 0;  // longitude is void at a pole
        }
        max_err = std::max(max_err, err.norm());
        ++rays;
      }
    }
    EXPECT_GT(rays, 1000) << L.toString();
    EXPECT_LT(max_err, 1e-6) << L.toString();
    std::printf("round trip %-10s %4dx%-4d distortion=%d: max error %.2e px over %d rays\n",
                lensTypeName(L.type), L.K.width, L.K.height, L.hasDistortion(), max_err, rays);
  }
}

TEST(Lens, ProjectMatchesOpenCvModelAndExactValue) {
  LensModel L = tumFr1();
  // exact rational arithmetic (Python fractions) of the documented model, OpenCV pixels
  Eigen::Vector2d uv;
  ASSERT_TRUE(project(L, Vec3(0.3, -0.2, 1.5), uv));
  EXPECT_NEAR(uv.x() - 0.5, 423.6568707731925, 1e-9);
  EXPECT_NEAR(uv.y() - 0.5, 185.26097770099943, 1e-9);
  const double d[5] = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  for (double z : {0.7, 2.0})
    for (double y : {-0.5, -0.1, 0.0, 0.33})
      for (double x : {-0.6, -0.05, 0.0, 0.41}) {
        Vec3 P(x * z, y * z, z);
        ASSERT_TRUE(project(L, P, uv));
        Eigen::Vector2d ref = opencvProjectPoint(517.3, 516.5, 318.6, 255.3, d, P);
        EXPECT_NEAR((uv - Eigen::Vector2d(0.5, 0.5) - ref).norm(), 0, 1e-9) << P.transpose();
      }
}

/// Every pixel corner and centre of a TUM fr1 image: undistort (generateRay), then distort with
/// the independent reference; the result must land on the pixel again.
TEST(Lens, DistortionInversionErrorBelowMicroPixelOverWholeImage) {
  LensModel L = tumFr1();
  const double d[5] = {L.k1, L.k2, L.p1, L.p2, L.k3};
  double max_err = 0;
  for (int j = 0; j <= 2 * L.K.height; ++j)
    for (int i = 0; i <= 2 * L.K.width; ++i) {
      double u = 0.5 * i, v = 0.5 * j;
      CameraRay r;
      ASSERT_TRUE(generateRay(L, u, v, kLensCentre, r)) << u << ", " << v;
      EXPECT_EQ(r.dir.z(), 1.0);
      Eigen::Vector2d px =
          opencvProjectPoint(L.K.fx, L.K.fy, L.K.cxOpenCV(), L.K.cyOpenCV(), d, r.dir) +
          Eigen::Vector2d(0.5, 0.5);
      max_err = std::max(max_err, (px - Eigen::Vector2d(u, v)).norm());
    }
  EXPECT_LT(max_err, 1e-6);
  std::printf("TUM fr1 undistortion: max error %.2e px over %d image points\n", max_err,
              (2 * L.K.height + 1) * (2 * L.K.width + 1));
}

TEST(Lens, NoRayBeyondTheFoldOfTheDistortion) {
  // r (1 - 0.5 r^2) rises to its maximum 0.5443 at r = sqrt(2/3) = 0.8165, then falls
  CameraIntrinsics K;
  K.fx = K.fy = 100;
  LensModel L = LensModel::pinhole(K);
  L.k1 = -0.5;
  CameraRay r;
  ASSERT_TRUE(generateRay(L, K.cx + 50, K.cy, kLensCentre, r));  // distorted radius 0.5
  EXPECT_LT(r.dir.x(), std::sqrt(2.0 / 3.0));  // the unfolded root (0.6527), not 1.0
  EXPECT_NEAR(r.dir.x() * (1 - 0.5 * r.dir.x() * r.dir.x()), 0.5, 1e-14);
  EXPECT_FALSE(generateRay(L, K.cx + 60, K.cy, kLensCentre, r));       // radius 0.6: no root
  EXPECT_FALSE(generateRay(L, K.cx + 40, K.cy + 40, kLensCentre, r));  // radius 0.566
  Eigen::Vector2d uv;
  EXPECT_TRUE(project(L, Vec3(0.8, 0, 1), uv));
  EXPECT_FALSE(project(L, Vec3(1.0, 0, 1), uv));  // projectPoints would fold it back to 0.5
  EXPECT_FALSE(project(L, Vec3(0.6, 0.6, 1), uv));
  // r - 0.5 r^3 + 0.1 r^5 falls between r = 1 and sqrt(2) and rises again beyond: a third
  // branch where the Jacobian is positive again but points are not imaged by the real lens
  LensModel k2 = L;
  k2.k2 = 0.1;
  ASSERT_TRUE(generateRay(k2, K.cx + 50, K.cy, kLensCentre, r));
  EXPECT_LT(r.dir.x(), 1.0);
  EXPECT_FALSE(generateRay(k2, K.cx + 150, K.cy, kLensCentre, r));  // its root is r = 2.08
  EXPECT_TRUE(project(k2, Vec3(0.9, 0, 1), uv));
  EXPECT_FALSE(project(k2, Vec3(1.2, 0, 1), uv));  // inside the falling part
  EXPECT_FALSE(project(k2, Vec3(1.5, 0, 1), uv));  // rising again, but beyond the fold
  // with k3: 1 - 1.8 s + 0.35 s^3 (the radial slope, s = r^2) is negative around s = 1.31
  LensModel k3 = LensModel::pinhole(K);
  k3.k1 = -0.6;
  k3.k3 = 0.05;
  EXPECT_TRUE(project(k3, Vec3(0.7, 0, 1), uv));
  EXPECT_FALSE(project(k3, Vec3(2.0, 0, 1), uv));
  // validate catches a calibration that folds inside the image (corner radius 4 here)
  try {
    L.validate("cam.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "k1..k3, p1, p2");
    EXPECT_NE(e.problem().find("folds"), std::string::npos) << e.what();
  }
}

TEST(Lens, DistortionJacobianMatchesFiniteDifferences) {
  LensModel L = tumFr1();
  for (Eigen::Vector2d xy : {Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d(-0.55, 0.41),
                             Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.6, 0.45)}) {
    Eigen::Matrix2d J;
    distortNormalised(L, xy, &J);
    const double h = 1e-6;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d e = Eigen::Vector2d::Unit(k) * h;
      Eigen::Vector2d fd = (distortNormalised(L, xy + e) - distortNormalised(L, xy - e)) / (2 * h);
      EXPECT_NEAR((J.col(k) - fd).norm(), 0, 1e-8) << xy.transpose() << " column " << k;
    }
    Eigen::Vector2d back;
    ASSERT_TRUE(undistortNormalised(L, distortNormalised(L, xy), back));
    EXPECT_NEAR((back - xy).norm(), 0, 1e-13);
  }
  Eigen::Matrix2d J;
  LensModel plain = LensModel::pinhole(CameraIntrinsics{});
  EXPECT_EQ(distortNormalised(plain, {0.3, -0.7}, &J), Eigen::Vector2d(0.3, -0.7));
  EXPECT_EQ(J, Eigen::Matrix2d::Identity());
}

TEST(Lens, ThinLensWithZeroApertureIsThePinholeExactly) {
  for (LensModel pin : {LensModel::pinhole(CameraIntrinsics{}), tumFr1()}) {
    LensModel thin = pin;
    thin.type = LensType::ThinLens;
    thin.focus_distance_m = 0.8;
    for (const Eigen::Vector2d& px : cornerGrid(pin.K))
      for (Eigen::Vector2d lens_uv :
           {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0, 0), Eigen::Vector2d(0.99, 0.3)}) {
        CameraRay a = ray(pin, px.x(), px.y()), b = ray(thin, px.x(), px.y(), lens_uv);
        EXPECT_EQ(a.origin, b.origin);
        EXPECT_EQ(a.dir, b.dir);
      }
  }
}

TEST(Lens, ThinLensRaysOfOnePixelMeetOnTheFocusPlane) {
  LensModel L = tumFr1();
  L.type = LensType::ThinLens;
  L.aperture_radius_m = 0.03;
  L.focus_distance_m = 2.2;
  for (const Eigen::Vector2d& px : cornerGrid(L.K, 5)) {
    // where the pinhole ray of the pixel crosses the focus plane, derived from CameraIntrinsics
    // and the exact OpenCV forward model rather than from the thin lens code
    LensModel pin = L;
    pin.type = LensType::Pinhole;
    pin.aperture_radius_m = 0;
    Vec3 focus_point = ray(pin, px.x(), px.y()).dir * L.focus_distance_m;
    for (int sy = 0; sy < 8; ++sy)
      for (int sx = 0; sx < 8; ++sx) {
        CameraRay r = ray(L, px.x(), px.y(), {(sx + 0.5) / 8, (sy + 0.37) / 8});
        EXPECT_EQ(r.origin.z(), 0.0);
        EXPECT_LE(r.origin.norm(), L.aperture_radius_m * (1 + 1e-12));
        EXPECT_EQ(r.dir.z(), 1.0);  // ray parameter = z-depth
        double t = (L.focus_distance_m - r.origin.z()) / r.dir.z();
        EXPECT_NEAR((r.origin + t * r.dir - focus_point).norm(), 0, 1e-9);
      }
  }
}

TEST(Lens, ThinLensSamplesTheApertureDiskUniformly) {
  LensModel L = LensModel::thinLens(CameraIntrinsics{}, 0.01, 1.5);
  CameraRay r = ray(L, 100, 100, kLensCentre);
  EXPECT_EQ(r.origin, Vec3::Zero());
  r = ray(L, 100, 100, {1.0, 0.5});  // the edge of the square maps to the rim
  EXPECT_NEAR((r.origin - Vec3(0.01, 0, 0)).norm(), 0, 1e-15);
  const int n = 128;
  double sum_r2 = 0, max_r = 0;
  Vec3 mean = Vec3::Zero();
  int quadrant[4] = {0, 0, 0, 0};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      r = ray(L, 100, 100, {(i + 0.5) / n, (j + 0.5) / n});
      sum_r2 += r.origin.squaredNorm();
      max_r = std::max(max_r, r.origin.norm());
      mean += r.origin;
      ++quadrant[(r.origin.x() > 0) + 2 * (r.origin.y() > 0)];
    }
  // uniform on a disk of radius R: E[r^2] = R^2 / 2, centroid 0, equal quadrants
  EXPECT_NEAR(sum_r2 / (n * n), 0.5 * 0.01 * 0.01, 1e-3 * 0.5 * 0.01 * 0.01);
  EXPECT_NEAR(mean.norm() / (n * n), 0, 1e-12);
  EXPECT_GT(max_r, 0.0099);
  for (int q : quadrant) EXPECT_EQ(q, n * n / 4);
  // equal-area sectors: 12 of them, not aligned with the map's octants; and the radial
  // moment E[r^4] = 1/3 of a uniform unit disk (a ring count would only see the square rings
  // of the stratified grid)
  int sector[12] = {};
  double sum_r4 = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      Vec3 o = ray(L, 100, 100, {(i + 0.5) / n, (j + 0.5) / n}).origin / 0.01;
      double angle = std::atan2(o.y(), o.x()) + kPi + 0.1;
      ++sector[static_cast<int>(angle / (2 * kPi / 12)) % 12];
      sum_r4 += o.squaredNorm() * o.squaredNorm();
    }
  for (int c : sector) EXPECT_NEAR(c, n * n / 12.0, 0.01 * n * n / 12);
  EXPECT_NEAR(sum_r4 / (n * n), 1.0 / 3, 1e-3);
}

TEST(Lens, BlurRadiusMatchesThinLensRayGeometry) {
  LensModel L = LensModel::thinLens(CameraIntrinsics{}, 0.004, 1.0);
  for (double z : {0.4, 1.0, 3.0}) {
    double expected = L.K.fx * 0.004 * std::abs(1 / z - 1 / 1.0);
    EXPECT_NEAR(blurRadiusPx(L, z), expected, 1e-12);
    // a rim ray of pixel (200, 300) crosses plane z at a point whose pinhole image is that
    // radius away from the pixel
    for (double a : {0.0, 0.25, 0.5}) {
      CameraRay r = ray(L, 200, 300, {a == 0.5 ? 0.5 : 1.0, a == 0.5 ? 1.0 : 0.5 + a});
      Eigen::Vector2d uv = L.K.project(r.origin + z * r.dir);
      EXPECT_NEAR((uv - Eigen::Vector2d(200, 300)).norm(), expected, 1e-9) << z << " " << a;
    }
  }
  EXPECT_EQ(blurRadiusPx(LensModel::fisheye(), 2.0), 0.0);
}

TEST(Lens, FisheyeCentreAxisAndCircleEdge) {
  LensModel L = LensModel::fisheye();  // 600x600, 180 deg
  ASSERT_NO_THROW(L.validate("test"));
  EXPECT_EQ(L.K.width, 600);
  EXPECT_NEAR(L.K.fx, 300 / (kPi / 2), 1e-12);  // the circle's radius 300 px is 90 degrees
  EXPECT_NEAR((ray(L, 300, 300).dir - Vec3(0, 0, 1)).norm(), 0, 1e-15);
  EXPECT_NEAR((ray(L, 600, 300).dir - Vec3(1, 0, 0)).norm(), 0, 1e-12);  // right edge: +x
  EXPECT_NEAR((ray(L, 300, 0).dir - Vec3(0, -1, 0)).norm(), 0, 1e-12);   // top edge: up
  EXPECT_NEAR((ray(L, 0, 300).dir - Vec3(-1, 0, 0)).norm(), 0, 1e-12);   // left edge: -x
  EXPECT_NEAR((ray(L, 300, 600).dir - Vec3(0, 1, 0)).norm(), 0, 1e-12);  // bottom: down
  double s = std::sqrt(0.5);  // equidistant: half the radius is half the angle, 45 degrees
  EXPECT_NEAR((ray(L, 450, 300).dir - Vec3(s, 0, s)).norm(), 0, 1e-12);
  EXPECT_NEAR(
      (ray(L, 300 - 75 * std::sqrt(2.0), 300 + 75 * std::sqrt(2.0)).dir - Vec3(-0.5, 0.5, s))
          .norm(),
      0, 1e-12);
  CameraRay r;
  EXPECT_FALSE(generateRay(L, 600.01, 300, kLensCentre, r));
  for (double u : {0.0, 600.0})
    for (double v : {0.0, 600.0}) EXPECT_FALSE(generateRay(L, u, v, kLensCentre, r));
  Eigen::Vector2d uv;
  ASSERT_TRUE(project(L, Vec3(2, 0, 0), uv));
  EXPECT_NEAR((uv - Eigen::Vector2d(600, 300)).norm(), 0, 1e-9);
  EXPECT_FALSE(project(L, Vec3(1, 0, -0.01), uv));  // behind a 180 degree lens
  EXPECT_FALSE(project(L, Vec3::Zero(), uv));
  LensModel wide = LensModel::fisheye(600, 220);  // sees 10 degrees behind the image plane
  ASSERT_TRUE(project(wide, Vec3(std::cos(10 * kPi / 180), 0, -std::sin(10 * kPi / 180)), uv));
  EXPECT_NEAR(uv.x(), 300 + 300 * 100.0 / 110.0, 1e-9);
}

TEST(Lens, PanoramaCardinalDirections) {
  LensModel L = LensModel::panorama();  // 5000 x 2500
  ASSERT_NO_THROW(L.validate("test"));
  // longitude runs left to right across 5000 px = 360 deg, with +z in the middle and +x (right)
  // a quarter turn later; latitude runs top (up, -y) to bottom (down, +y) across 2500 px
  struct Case {
    Vec3 dir;
    double u, v;
  } cases[] = {{{0, 0, 1}, 2500, 1250}, {{1, 0, 0}, 3750, 1250}, {{-1, 0, 0}, 1250, 1250},
               {{0, 0, -1}, 0, 1250},   {{0, -1, 0}, 2500, 0},   {{0, 1, 0}, 2500, 2500},
               {{1, 0, 1}, 3125, 1250}, {{0, -1, 1}, 2500, 625}};
  for (const Case& c : cases) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(project(L, 3 * c.dir, uv));
    EXPECT_NEAR(uv.y(), c.v, 1e-9) << c.dir.transpose();
    if (c.dir.x() != 0 || c.dir.z() != 0) {  // longitude is void at the poles
      EXPECT_NEAR(uv.x(), c.u, 1e-9) << c.dir.transpose();
    }
    EXPECT_NEAR((ray(L, c.u, c.v).dir - c.dir.normalized()).norm(), 0, 1e-12) << c.dir.transpose();
  }
  EXPECT_NEAR((ray(L, 5000, 1250).dir - Vec3(0, 0, -1)).norm(), 0, 1e-12);  // the seam again
}

/// Solid angle of the spherical triangle (a, b, c) of unit vectors (Van Oosterom & Strackee).
double triangleSolidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  double num = std::abs(a.dot(b.cross(c)));
  double den = 1 + a.dot(b) + b.dot(c) + c.dot(a);
  return 2 * std::atan2(num, den);
}

TEST(Lens, PanoramaPixelsTileTheSphere) {
  LensModel L = LensModel::panorama(720, 360);
  const int w = L.K.width, h = L.K.height;
  double total = 0, z2 = 0, y1 = 0, max_rel = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      // the pixel's footprint: the quad of its four corner rays
      Vec3 a = ray(L, i, j).dir, b = ray(L, i + 1, j).dir;
      Vec3 c = ray(L, i + 1, j + 1).dir, d = ray(L, i, j + 1).dir;
      double omega = triangleSolidAngle(a, b, c) + triangleSolidAngle(a, c, d);
      total += omega;
      Vec3 centre = ray(L, i + 0.5, j + 0.5).dir;
      z2 += omega * centre.z() * centre.z();
      y1 += omega * centre.y();
      // against the lat-long cell's area dlon (sin lat1 - sin lat0), away from the poles
      double lat0 = kPi * j / h - kPi / 2, lat1 = kPi * (j + 1) / h - kPi / 2;
      double cell = (2 * kPi / w) * (std::sin(lat1) - std::sin(lat0));
      if (j > 0 && j < h - 1) max_rel = std::max(max_rel, std::abs(omega / cell - 1));
    }
  EXPECT_NEAR(total, 4 * kPi, 1e-3);
  EXPECT_NEAR(z2, 4 * kPi / 3, 1e-3);  // integral of z^2 over the sphere
  EXPECT_NEAR(y1, 0, 1e-3);
  EXPECT_LT(max_rel, 1e-3);
  std::printf("panorama %dx%d: sum of pixel solid angles - 4 pi = %.2e, max cell deviation %.1e\n",
              w, h, total - 4 * kPi, max_rel);
}

TEST(Lens, GroundTruthDepthIsTheRayParameter) {
  EXPECT_EQ(groundTruthDepthKind(LensType::Pinhole), DepthKind::ZDepth);
  EXPECT_EQ(groundTruthDepthKind(LensType::ThinLens), DepthKind::ZDepth);
  EXPECT_EQ(groundTruthDepthKind(LensType::Fisheye), DepthKind::RayDistance);
  EXPECT_EQ(groundTruthDepthKind(LensType::Panorama), DepthKind::RayDistance);
  std::vector<LensModel> lenses = {tumFr1(), LensModel::thinLens(CameraIntrinsics{}, 0.05, 2),
                                   LensModel::fisheye(), LensModel::panorama(200, 100)};
  for (const LensModel& L : lenses)
    for (const Eigen::Vector2d& px : cornerGrid(L.K, 7)) {
      CameraRay r;
      if (!generateRay(L, px.x(), px.y(), {0.2, 0.7}, r)) continue;
      const double t = 3.7;
      Vec3 p = r.origin + t * r.dir;
      EXPECT_NEAR(groundTruthDepth(L, p), t, 1e-12) << L.toString();
      if (L.type == LensType::Fisheye || L.type == LensType::Panorama) {
        EXPECT_NEAR(r.dir.norm(), 1, 1e-15);
      }
    }
}

InputError validateError(const LensModel& L) {
  try {
    L.validate("rig.json");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for " << L.toString();
  return InputError("", "", "");
}

TEST(Lens, ValidateNamesTheField) {
  LensModel L = LensModel::fisheye();
  L.k1 = 0.1;
  EXPECT_EQ(validateError(L).field(), "k1");
  L = LensModel::pinhole(CameraIntrinsics{});
  L.aperture_radius_m = 0.01;
  EXPECT_EQ(validateError(L).field(), "aperture_radius_m");
  L = LensModel::thinLens(CameraIntrinsics{}, -0.01, 1);
  EXPECT_EQ(validateError(L).field(), "aperture_radius_m");
  L = LensModel::thinLens(CameraIntrinsics{}, 0.01, 0);
  EXPECT_EQ(validateError(L).field(), "focus_distance_m");
  EXPECT_EQ(validateError(LensModel::fisheye(600, 0)).field(), "fisheye_fov_deg");
  EXPECT_EQ(validateError(LensModel::fisheye(600, 400)).field(), "fisheye_fov_deg");
  L = tumFr1();
  L.p2 = std::nan("");
  EXPECT_EQ(validateError(L).field(), "p2");
  L = tumFr1();
  L.K.fx = -1;
  EXPECT_EQ(validateError(L).field(), "fx");
  L.type = static_cast<LensType>(7);
  EXPECT_EQ(validateError(L).field(), "type");
  EXPECT_NO_THROW(LensModel::fisheye(600, 360).validate("x"));
  EXPECT_NO_THROW(LensModel::thinLens(CameraIntrinsics{}, 0.01, 2).validate("x"));
  EXPECT_NO_THROW(tumFr1().validate("x"));
}

TEST(Lens, NamesAndOpenCvExport) {
  for (LensType t : {LensType::Pinhole, LensType::ThinLens, LensType::Fisheye, LensType::Panorama})
    EXPECT_EQ(parseLensType(lensTypeName(t), "cli"), t);
  try {
    parseLensType("fish", "cli", "--lens");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--lens");
    EXPECT_NE(e.problem().find("pinhole, thin_lens, fisheye, panorama"), std::string::npos);
  }
  OpenCvCamera c = toOpenCv(tumFr1());
  EXPECT_EQ(c.model, "radtan");
  EXPECT_NEAR(c.cx, 318.6, 1e-12);  // the published calibration again
  EXPECT_NEAR(c.cy, 255.3, 1e-12);
  EXPECT_EQ(c.distortion, (std::vector<double>{0.2624, -0.9531, -0.0054, 0.0026, 1.1633}));
  c = toOpenCv(LensModel::fisheye());
  EXPECT_EQ(c.model, "equidistant");
  EXPECT_NEAR(c.cx, 299.5, 1e-12);
  EXPECT_EQ(c.distortion, (std::vector<double>(4, 0.0)));
  EXPECT_EQ(toOpenCv(LensModel::panorama()).model, "equirectangular");
  EXPECT_NE(tumFr1().toString().find("k3=1.1633"), std::string::npos);
}

}  // namespace
}  // namespace inet
