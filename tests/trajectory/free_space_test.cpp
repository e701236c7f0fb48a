// Free space: the grid's distance is a lower bound of the exact one and close to it, the exact
// distance agrees with brute force, indoors is what the walls enclose, and a generated
// apartment's rooms are joined by free space through their doorways at camera height.
#include "trajectory/free_space.h"

#include <gtest/gtest.h>

#include <queue>
#include <random>

#include "core/error.h"
#include "procedural/apartment.h"
#include "scene/primitives.h"
#include "../temp_dir.h"

namespace inet {
namespace {

Mat4 boxTransform(const Vec3& centre, const Vec3& size) {
  Mat4 T = Mat4::Identity();
  T.topLeftCorner<3, 3>() = size.asDiagonal();
  T.topRightCorner<3, 1>() = centre;
  return T;
}

/// A closed 4 x 3 x 2.5 m room (a box seen from inside) with a 0.6 m cube and a sphere in it.
Scene closedRoom() {
  Scene s;
  s.meshes.push_back(makePrimitive("box", {}, "", ""));
  s.meshes.push_back(makePrimitive("sphere", {{"radius", 0.3}}, "", ""));
  s.materials.push_back(Material{});
  s.objects.push_back(Object::make("room", 0, 0, boxTransform({2, 1.5, 1.25}, {4, 3, 2.5}), 1, 1));
  s.objects.push_back(Object::make("cube", 0, 0, boxTransform({1, 1, 0.3}, {0.6, 0.6, 0.6}), 5, 2));
  Mat4 T = Mat4::Identity();
  T.topRightCorner<3, 1>() = Vec3(3, 2, 1.2);
  s.objects.push_back(Object::make("ball", 1, 0, T, 40, 3));
  return s;
}

double bruteForceDistance(const WorldTriangles& w, const Vec3& p) {
  double best = 1e30;
  for (const Tri& t : w.triangles) {
    Vec3 q = closestPointOnTriangle(p, w.positions[t[0]].cast<double>(),
                                    w.positions[t[1]].cast<double>(),
                                    w.positions[t[2]].cast<double>());
    best = std::min(best, (q - p).norm());
  }
  return best;
}

TEST(ClosestPointOnTriangle, RegionsOfTheTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(closestPointOnTriangle({0.2, 0.2, 3}, a, b, c).isApprox(Vec3(0.2, 0.2, 0)));
  EXPECT_TRUE(closestPointOnTriangle({-1, -1, 0}, a, b, c).isApprox(a));
  EXPECT_TRUE(closestPointOnTriangle({2, -0.5, 1}, a, b, c).isApprox(b));
  EXPECT_TRUE(closestPointOnTriangle({0.5, -2, 0}, a, b, c).isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(closestPointOnTriangle({1, 1, 0}, a, b, c).isApprox(Vec3(0.5, 0.5, 0)));
}

TEST(ExactDistance, AgreesWithBruteForce) {
  Scene s = closedRoom();
  WorldTriangles w = worldTriangles(s);
  EXPECT_EQ(w.triangles.size(), 12u + 12u + 20u);  // two boxes and the ball's icosahedron
  ExactDistance exact(w);
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-0.5, 4.5);
  for (int i = 0; i < 300; ++i) {
    Vec3 p(u(gen), u(gen) * 0.75, u(gen) * 0.6);
    EXPECT_NEAR(exact.distance(p), bruteForceDistance(w, p), 1e-5) << p.transpose();
  }
}

TEST(FreeSpace, LowerBoundIsBelowTheExactDistanceAndClose) {
  Scene s = closedRoom();
  FreeSpace space(s, {.voxel = 0.05});
  WorldTriangles w = worldTriangles(s);
  std::mt19937 gen(2);
  std::uniform_real_distribution<double> ux(0.05, 3.95), uy(0.05, 2.95), uz(0.05, 2.45);
  int free_points = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec3 p(ux(gen), uy(gen), uz(gen));
    const double exact = bruteForceDistance(w, p);
    const double lb = space.lowerBound(p);
    ASSERT_LE(lb, exact + 1e-6) << p.transpose();
    const bool inside_cube = (p - Vec3(1, 1, 0.3)).cwiseAbs().maxCoeff() < 0.3;
    const bool inside_ball = (p - Vec3(3, 2, 1.2)).norm() < 0.3;
    if (inside_cube || inside_ball) {
      EXPECT_EQ(lb, 0.0) << "inside an object";
      continue;
    }
    // the slack is at most 2 voxel diagonals (h for occupancy and h for the point, twice over
    // for interpolation), and distances near the ball's enclosing polyhedron are smaller
    if (!inside_ball && (p - Vec3(3, 2, 1.2)).norm() > 0.5 && exact > 0.2) {
      EXPECT_GE(lb, exact - 2 * 0.05 * std::sqrt(3.0) - 1e-6) << p.transpose();
      ++free_points;
    }
    EXPECT_EQ(space.hasClearance(p, 0.1), exact >= 0.1) << p.transpose();
  }
  EXPECT_GT(free_points, 1000);
}

TEST(FreeSpace, OutsideTheEnclosureIsNotFree) {
  Scene s = closedRoom();
  // put the room in a bigger open space: a floor plate 10 x 10 m
  s.objects.push_back(
      Object::make("floor", 0, 0, boxTransform({2, 1.5, -0.05}, {10, 10, 0.1}), 2, 4));
  FreeSpace space(s);
  EXPECT_GT(space.lowerBound({1.5, 2.2, 1.5}), 0.5);
  EXPECT_EQ(space.lowerBound({6.0, 1.5, 1.0}), 0.0) << "outside the walls is outdoors";
  EXPECT_FALSE(space.hasClearance({6.0, 1.5, 1.0}, 0.1));
  EXPECT_EQ(space.lowerBound({50, 50, 1}), 0.0) << "outside the grid";
}

TEST(FreeSpace, AnOpenSceneCountsWholeButNotTheInsideOfObjects) {
  Scene s;
  s.meshes.push_back(makePrimitive("box", {}, "", ""));
  s.materials.push_back(Material{});
  s.objects.push_back(Object::make("table", 0, 0, boxTransform({0, 0, 0.4}, {1, 1, 0.8}), 7, 1));
  s.objects.push_back(Object::make("floor", 0, 0, boxTransform({0, 0, -0.05}, {4, 4, 0.1}), 2, 2));
  FreeSpace space(s, {.voxel = 0.02});
  EXPECT_NEAR(space.lowerBound({1.0, 0, 0.6}), 0.5, 2 * 0.02 * std::sqrt(3.0));
  EXPECT_EQ(space.lowerBound({0, 0, 0.4}), 0.0) << "the closed table's inside is unreachable";
}

TEST(FreeSpace, NoGeometryIsAnInputError) {
  Scene s;
  EXPECT_THROW(FreeSpace(s, {}, "empty.json"), InputError);
}

TEST(FreeSpace, GrowsTheVoxelToStayWithinTheBudget) {
  Scene s = closedRoom();
  FreeSpace space(s, {.voxel = 0.01, .max_voxels = 1e5});
  EXPECT_GT(space.voxel(), 0.01);
  EXPECT_LE(double(space.nx()) * space.ny() * space.nz(), 1e5);
}

// Every room of generated apartments is joined to every other by free space at camera height:
// the free voxels (0.25 m clearance, z = 1.5 m) of all rooms form one connected region.
TEST(FreeSpace, ApartmentRoomsAreJoinedThroughDoorways) {
  test::TempDir dir("free_space");
  for (uint64_t seed : {0u, 3u, 7u, 11u}) {
    ApartmentOptions opt;
    opt.seed = seed;
    opt.texture_size = 64;
    Apartment apt = makeApartment(opt, dir.path(), dir.path() / "textures");
    FreeSpace space(apt.scene);
    const double z = 1.5, clearance = 0.25;
    const int k = static_cast<int>(std::lround((z - space.origin().z()) / space.voxel()));
    const int nx = space.nx(), ny = space.ny();
    auto centre = [&](int i, int j) -> Vec3 { return space.origin() + space.voxel() * Vec3(i, j, k); };
    std::vector<int> comp(size_t(nx) * ny, -1);
    std::vector<int> sizes;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (comp[j * nx + i] >= 0 || !space.isFree(centre(i, j), clearance)) continue;
        int id = static_cast<int>(sizes.size());
        sizes.push_back(0);
        std::queue<std::pair<int, int>> q;
        q.push({i, j});
        comp[j * nx + i] = id;
        while (!q.empty()) {
          auto [a, b] = q.front();
          q.pop();
          ++sizes[id];
          const int da[4] = {1, -1, 0, 0}, db[4] = {0, 0, 1, -1};
          for (int n = 0; n < 4; ++n) {
            int a2 = a + da[n], b2 = b + db[n];
            if (a2 < 0 || b2 < 0 || a2 >= nx || b2 >= ny || comp[b2 * nx + a2] >= 0) continue;
            if (!space.isFree(centre(a2, b2), clearance)) continue;
            comp[b2 * nx + a2] = id;
            q.push({a2, b2});
          }
        }
      }
    ASSERT_FALSE(sizes.empty()) << "seed " << seed;
    const int biggest = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    // each room has free voxels in the biggest component
    for (size_t r = 0; r < apt.scene.rooms.size(); ++r) {
      const Room& room = apt.scene.rooms[r];
      bool joined = false;
      for (int j = 0; j < ny && !joined; ++j)
        for (int i = 0; i < nx && !joined; ++i) {
          Vec3 c = centre(i, j);
          Eigen::AlignedBox2d box;
          for (const auto& p : room.outline) box.extend(p);
          joined = comp[j * nx + i] == biggest && box.contains(c.head<2>());
        }
      EXPECT_TRUE(joined) << "seed " << seed << ": room " << room.id << " (" << room.type
                          << ") is cut off at camera height";
    }
  }
}

}  // namespace
}  // namespace inet
