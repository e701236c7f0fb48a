// Built-in primitives (outward winding, closed surfaces, parameters) and the NYU40 name table.
#include "scene/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "core/error.h"
#include "scene/nyu40.h"
#include "scene_test_util.h"

namespace inet {
namespace {

using test::errorOf;

Vec3 vertex(const Mesh& m, const Tri& t, int k) {
  return m.positions[t[k]].cast<double>();
}

/// Unnormalised geometric normal (b - a) x (c - a): the winding defines which side is "out".
Vec3 faceNormal(const Mesh& m, const Tri& t) {
  return (vertex(m, t, 1) - vertex(m, t, 0)).cross(vertex(m, t, 2) - vertex(m, t, 0));
}

Vec3 meshCentroid(const Mesh& m) {
  Vec3 c = Vec3::Zero();
  for (const auto& p : m.positions) c += p.cast<double>();
  return c / static_cast<double>(m.positions.size());
}

/// Signed volume by the divergence theorem: sum over faces of a . (b x c) / 6. Positive only
/// when every face winds counter-clockwise seen from outside.
double signedVolume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += vertex(m, t, 0).dot(vertex(m, t, 1).cross(vertex(m, t, 2))) / 6.0;
  return v;
}

/// A closed, consistently oriented surface uses every directed edge exactly once and its
/// reverse exactly once.
void expectClosedAndOriented(const Mesh& m) {
  std::map<std::tuple<float, float, float, float, float, float>, int> directed;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3f& a = m.positions[t[k]];
      const Vec3f& b = m.positions[t[(k + 1) % 3]];
      ++directed[{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}];
    }
  }
  for (const auto& [edge, count] : directed) {
    auto [ax, ay, az, bx, by, bz] = edge;
    EXPECT_EQ(count, 1) << "directed edge used twice: faces are not consistently wound";
    auto reverse = directed.find({bx, by, bz, ax, ay, az});
    EXPECT_TRUE(reverse != directed.end()) << "boundary edge: surface is not closed";
  }
}

TEST(Primitives, BoxHasTwelveOutwardTriangles) {
  Mesh box = makePrimitive("box", {}, "test", "box");
  ASSERT_EQ(box.triangles.size(), 12u);
  const Vec3 centre = meshCentroid(box);
  EXPECT_NEAR(centre.norm(), 0.0, 1e-12);
  double area = 0;
  for (const auto& t : box.triangles) {
    const Vec3 tri_centre = (vertex(box, t, 0) + vertex(box, t, 1) + vertex(box, t, 2)) / 3.0;
    EXPECT_GT(faceNormal(box, t).dot(tri_centre - centre), 0.0) << "inward-facing triangle";
    area += 0.5 * faceNormal(box, t).norm();
  }
  EXPECT_NEAR(area, 6.0, 1e-6);  // unit cube
  EXPECT_NEAR(signedVolume(box), 1.0, 1e-6);
  for (const auto& p : box.positions) EXPECT_LE(p.cwiseAbs().maxCoeff(), 0.5f);
  expectClosedAndOriented(box);
  EXPECT_EQ(box.source.kind, MeshSource::Kind::Primitive);
  EXPECT_EQ(box.source.primitive, "box");
}

TEST(Primitives, CylinderIsClosedAndOutward) {
  for (int segments : {3, 24, 256}) {
    SCOPED_TRACE(segments);
    Mesh cyl = makePrimitive("cylinder", {{"segments", segments}}, "test", "cyl");
    EXPECT_EQ(cyl.triangles.size(), static_cast<size_t>(4 * segments));  // 2 side + 2 caps each
    expectClosedAndOriented(cyl);
    for (const auto& t : cyl.triangles) {
      const Vec3 c = (vertex(cyl, t, 0) + vertex(cyl, t, 1) + vertex(cyl, t, 2)) / 3.0;
      EXPECT_GT(faceNormal(cyl, t).dot(c), 0.0);  // axis through the origin: outward = away
    }
    // prism over a regular n-gon of radius 0.5, height 1: area = n/2 r^2 sin(2 pi / n)
    const double polygon = 0.5 * segments * 0.25 * std::sin(2.0 * M_PI / segments);
    EXPECT_NEAR(signedVolume(cyl), polygon, 1e-5);
  }
  EXPECT_EQ(makePrimitive("cylinder", {}, "t", "c").triangles.size(), 4u * 24u);
}

TEST(Primitives, TextureCoordinatesAndCylinderNormals) {
  for (const char* name : {"box", "quad", "cylinder"}) {
    SCOPED_TRACE(name);
    Mesh m = makePrimitive(name, {}, "t", "m");
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    for (const auto& uv : m.uvs) {
      EXPECT_GE(uv.minCoeff(), 0.f);
      EXPECT_LE(uv.maxCoeff(), 1.f);
    }
  }
  // each box face maps the whole texture once: its uv area is 1 (two triangles of 1/2)
  Mesh box = makePrimitive("box", {}, "t", "m");
  double uv_area = 0;
  for (const auto& t : box.triangles) {
    const Vec2f a = box.uvs[t[1]] - box.uvs[t[0]], b = box.uvs[t[2]] - box.uvs[t[0]];
    uv_area += 0.5 * std::fabs(a.x() * b.y() - a.y() * b.x());
  }
  EXPECT_NEAR(uv_area, 6.0, 1e-6);
  EXPECT_TRUE(box.normals.empty()) << "flat faces need no vertex normals";
  // cylinder: side normals radial (smooth), cap normals +-z, all unit and outward
  Mesh cyl = makePrimitive("cylinder", {{"segments", 12}}, "t", "c");
  ASSERT_EQ(cyl.normals.size(), cyl.positions.size());
  for (const auto& t : cyl.triangles) {
    const Vec3 face = faceNormal(cyl, t).normalized();
    for (int k = 0; k < 3; ++k) {
      const Vec3f& n = cyl.normals[t[k]];
      EXPECT_NEAR(n.norm(), 1.f, 1e-6);
      EXPECT_GT(n.cast<double>().dot(face), 0.9) << "vertex normal on the face's side";
      if (std::fabs(face.z()) < 0.5) {  // side triangle: radial, horizontal
        const Vec3f& p = cyl.positions[t[k]];
        EXPECT_NEAR(n.x(), 2 * p.x(), 1e-5);
        EXPECT_NEAR(n.y(), 2 * p.y(), 1e-5);
        EXPECT_EQ(n.z(), 0.f);
      }
    }
  }
}

TEST(Primitives, QuadFacesUp) {
  Mesh quad = makePrimitive("quad", {}, "test", "quad");
  ASSERT_EQ(quad.triangles.size(), 2u);
  for (const auto& t : quad.triangles) {
    Vec3 n = faceNormal(quad, t);
    EXPECT_GT(n.z(), 0.0);
    EXPECT_NEAR(n.x(), 0.0, 1e-12);
    EXPECT_NEAR(n.y(), 0.0, 1e-12);
  }
  for (const auto& p : quad.positions) EXPECT_EQ(p.z(), 0.0f);
}

// A curtain panel is folds side by side: each fold must lie in the unit box on the curve, face
// the front with normals that are the curve's (so shading agrees with the geometry), and end
// where the next begins with the same position and normal (no crack, no crease).
TEST(Primitives, FoldsJoinIntoOneSmoothSheetFacingTheFront) {
  const Mesh f = makePrimitive("fold", {{"segments", 12}}, "test", "fold");
  ASSERT_EQ(f.positions.size(), 26u);
  ASSERT_EQ(f.triangles.size(), 24u);
  ASSERT_EQ(f.normals.size(), f.positions.size());
  for (size_t i = 0; i < f.positions.size(); ++i) {
    const Vec3f& p = f.positions[i];
    EXPECT_NEAR(p.y(), 0.5 * std::cos(2 * M_PI * (p.x() + 0.5)), 1e-6);
    EXPECT_LE(p.cwiseAbs().maxCoeff(), 0.5f + 1e-6f);
    // normal perpendicular to the curve's tangent (1, dy/dx, 0), unit, pointing to -y
    const double slope = -M_PI * std::sin(2 * M_PI * (p.x() + 0.5));
    const Vec3f& n = f.normals[i];
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
    EXPECT_NEAR(n.x() + slope * n.y(), 0.0, 1e-6);
    EXPECT_LT(n.y(), 0.f);
  }
  for (const auto& t : f.triangles) {  // winding on the shading normals' side
    const Vec3 g = faceNormal(f, t);
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 3; ++k) n += f.normals[t[k]].cast<double>();
    EXPECT_GT(g.dot(n), 0.0);
  }
  // the right end of one fold is the left end of the next (shifted by 1 in x)
  int joined = 0;
  for (size_t i = 0; i < f.positions.size(); ++i)
    for (size_t j = 0; j < f.positions.size(); ++j)
      if (f.positions[i].x() == 0.5f && f.positions[j].x() == -0.5f &&
          f.positions[i].z() == f.positions[j].z()) {
        EXPECT_NEAR(f.positions[i].y(), f.positions[j].y(), 1e-7);
        EXPECT_NEAR((f.normals[i] - f.normals[j]).norm(), 0.0, 1e-6);
        ++joined;
      }
  EXPECT_EQ(joined, 2);
  EXPECT_EQ(makePrimitive("fold", {}, "t", "f").triangles.size(), 32u);  // 16 by default
}

TEST(Primitives, SphereIsAnalytic) {
  Mesh s = makePrimitive("sphere", {{"radius", 0.25}}, "test", "s");
  EXPECT_TRUE(s.isSphere());
  EXPECT_EQ(s.sphere_radius, 0.25f);
  EXPECT_TRUE(s.triangles.empty());
  EXPECT_EQ(makePrimitive("sphere", {}, "t", "s").sphere_radius, 0.5f);
}

TEST(Primitives, BadParametersNameTheField) {
  EXPECT_NE(errorOf([] {
              makePrimitive("cylinder", {{"segments", 2}}, "f.json", "m");
            }).find("f.json: m.segments"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              makePrimitive("cylinder", {{"segments", 257}}, "f", "m");
            }).find("m.segments"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              makePrimitive("cylinder", {{"segments", 3.5}}, "f", "m");
            }).find("integer"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              makePrimitive("fold", {{"segments", 1}}, "f", "m");
            }).find("m.segments"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              makePrimitive("sphere", {{"radius", 0}}, "f", "m");
            }).find("m.radius"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              makePrimitive("box", {{"size", 2}}, "f", "m");
            }).find("m.size"),
            std::string::npos);
  std::string unknown = errorOf([] { makePrimitive("torus", {}, "f", "m"); });
  EXPECT_NE(unknown.find("torus"), std::string::npos);
  EXPECT_NE(unknown.find("box, cylinder, fold, quad, sphere"), std::string::npos);
}

TEST(Nyu40, EveryIdRoundTripsThroughItsName) {
  std::set<std::string> names;
  for (int id = 0; id < kNyu40Count; ++id) {
    const std::string name(nyu40Name(id));
    ASSERT_FALSE(name.empty()) << id;
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
    auto back = nyu40FromName(name);
    ASSERT_TRUE(back.has_value()) << name;
    EXPECT_EQ(*back, id) << name;
  }
  EXPECT_EQ(names.size(), 41u);
  EXPECT_TRUE(nyu40Name(-1).empty());
  EXPECT_TRUE(nyu40Name(41).empty());
}

TEST(Nyu40, SpellingVariants) {
  EXPECT_EQ(nyu40FromName("Night stand"), 32);
  EXPECT_EQ(nyu40FromName("night-stand"), 32);
  EXPECT_EQ(nyu40FromName("refrigerator"), 24);
  EXPECT_EQ(nyu40FromName("Floor mat"), 20);
  EXPECT_EQ(nyu40FromName("OTHERPROP"), 40);
  EXPECT_FALSE(nyu40FromName("spaceship").has_value());
}

}  // namespace
}  // namespace inet
