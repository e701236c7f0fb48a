#include "scene/primitives.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {

/// A planar quad a, b, c, d (counter-clockwise seen from its front) with texture coordinates
/// (0,0), (1,0), (1,1), (0,1): each face of a box or quad shows one copy of a texture.
void addQuad(Mesh& m, const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec3f& d) {
  auto base = static_cast<uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {a, b, c, d});
  m.uvs.insert(m.uvs.end(), {Vec2f(0, 0), Vec2f(1, 0), Vec2f(1, 1), Vec2f(0, 1)});
  m.triangles.push_back(Tri(base, base + 1, base + 2));
  m.triangles.push_back(Tri(base, base + 2, base + 3));
}

Mesh box() {
  Mesh m;
  const float h = 0.5f;
  // each face counter-clockwise seen from outside
  addQuad(m, {-h, -h, -h}, {-h, h, -h}, {h, h, -h}, {h, -h, -h});  // -z
  addQuad(m, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h});      // +z
  addQuad(m, {-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h});  // -y
  addQuad(m, {-h, h, -h}, {-h, h, h}, {h, h, h}, {h, h, -h});      // +y
  addQuad(m, {-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h});  // -x
  addQuad(m, {h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h});      // +x
  return m;
}

/// Side: `segments` + 1 columns (the seam is duplicated so u runs 0..1 around), smooth radial
/// normals, v = 0 at the bottom and 1 at the top. Caps: their own vertices with flat normals and
/// planar texture coordinates (x + 0.5, y + 0.5).
Mesh cylinder(int segments) {
  Mesh m;
  const float r = 0.5f, h = 0.5f;
  auto vertex = [&](const Vec3f& p, const Vec3f& n, const Vec2f& uv) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    m.uvs.push_back(uv);
    return static_cast<uint32_t>(m.positions.size() - 1);
  };
  const auto n = static_cast<uint32_t>(segments);
  for (uint32_t i = 0; i <= n; ++i) {  // side: bottom and top vertex of column i
    const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i % n) / segments;
    const Vec3f radial(std::cos(a), std::sin(a), 0.f);
    const float u = static_cast<float>(i) / segments;
    vertex(Vec3f(r * radial.x(), r * radial.y(), -h), radial, Vec2f(u, 0.f));
    vertex(Vec3f(r * radial.x(), r * radial.y(), h), radial, Vec2f(u, 1.f));
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t b0 = 2 * i, t0 = b0 + 1, b1 = 2 * i + 2, t1 = b1 + 1;
    m.triangles.push_back(Tri(b0, b1, t1));
    m.triangles.push_back(Tri(b0, t1, t0));
  }
  for (float z : {-h, h}) {  // caps
    const Vec3f normal(0.f, 0.f, z > 0 ? 1.f : -1.f);
    const uint32_t centre = vertex(Vec3f(0.f, 0.f, z), normal, Vec2f(0.5f, 0.5f));
    for (uint32_t i = 0; i < n; ++i) {
      const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i) / segments;
      vertex(Vec3f(r * std::cos(a), r * std::sin(a), z), normal,
             Vec2f(0.5f + r * std::cos(a), 0.5f + r * std::sin(a)));
    }
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t p = centre + 1 + i, q = centre + 1 + (i + 1) % n;
      m.triangles.push_back(z > 0 ? Tri(centre, p, q) : Tri(centre, q, p));
    }
  }
  return m;
}

/// One fold of cloth: y = cos(2 pi (x + 1/2)) / 2 over x, z in [-1/2, 1/2], back (+y) at both
/// ends and forward at the middle. One two-sided surface of `segments` columns along x with the
/// curve's smooth normals (towards -y, the front), u = x + 1/2, v = z + 1/2. Its ends have slope
/// 0, so folds side by side join into a continuous pleated sheet with continuous normals: a
/// curtain panel without the cracks and the facets of boxes side by side.
Mesh fold(int segments) {
  Mesh m;
  const auto n = static_cast<uint32_t>(segments);
  for (uint32_t i = 0; i <= n; ++i) {
    const float u = static_cast<float>(i) / segments, a = 2.0f * static_cast<float>(M_PI) * u;
    const float x = u - 0.5f, y = 0.5f * std::cos(a);
    const Vec3f normal = Vec3f(-static_cast<float>(M_PI) * std::sin(a), -1.f, 0.f).normalized();
    for (float z : {-0.5f, 0.5f}) {
      m.positions.emplace_back(x, y, z);
      m.normals.push_back(normal);
      m.uvs.emplace_back(u, z + 0.5f);
    }
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t b0 = 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    m.triangles.push_back(Tri(b0, b1, t1));  // geometric normal on the shading normal's side
    m.triangles.push_back(Tri(b0, t1, t0));
  }
  return m;
}

double param(const std::map<std::string, double>& params, const std::string& key, double fallback) {
  auto it = params.find(key);
  return it == params.end() ? fallback : it->second;
}

void rejectUnknown(const std::map<std::string, double>& params,
                   const std::vector<std::string>& allowed, const std::string& where,
                   const std::string& field, const std::string& name) {
  for (const auto& [key, value] : params) {
    bool ok = false;
    for (const auto& a : allowed) ok |= (a == key);
    if (!ok) {
      throw InputError(
          where, field + "." + key,
          fmt::format("unknown parameter for primitive '{}' (valid: {})", name,
                      allowed.empty() ? "none" : fmt::format("{}", fmt::join(allowed, ", "))));
    }
  }
}

/// The only parameter of a tessellated primitive: "segments", an integer in [lo, 256].
int segmentsParam(const std::map<std::string, double>& params, int lo, int fallback,
                  const std::string& where, const std::string& field, const std::string& name) {
  rejectUnknown(params, {"segments"}, where, field, name);
  const double seg = param(params, "segments", fallback);
  if (!(seg >= lo && seg <= 256) || seg != std::floor(seg)) {
    throw InputError(where, field + ".segments",
                     fmt::format("must be an integer in [{}, 256]", lo));
  }
  return static_cast<int>(seg);
}

}  // namespace

const std::vector<std::string>& primitiveNames() {
  static const std::vector<std::string> names = {"box", "cylinder", "fold", "quad", "sphere"};
  return names;
}

Mesh makePrimitive(const std::string& name, const std::map<std::string, double>& params,
                   const std::string& where, const std::string& field) {
  Mesh m;
  if (name == "box") {
    rejectUnknown(params, {}, where, field, name);
    m = box();
  } else if (name == "quad") {
    rejectUnknown(params, {}, where, field, name);
    addQuad(m, {-0.5f, -0.5f, 0.f}, {0.5f, -0.5f, 0.f}, {0.5f, 0.5f, 0.f}, {-0.5f, 0.5f, 0.f});
  } else if (name == "cylinder") {
    m = cylinder(segmentsParam(params, 3, 24, where, field, name));
  } else if (name == "fold") {
    m = fold(segmentsParam(params, 2, 16, where, field, name));
  } else if (name == "sphere") {
    rejectUnknown(params, {"radius"}, where, field, name);
    double r = param(params, "radius", 0.5);
    if (!(r > 0 && std::isfinite(r))) throw InputError(where, field + ".radius", "must be > 0");
    m.sphere_radius = static_cast<float>(r);
  } else {
    throw InputError(
        where, field,
        fmt::format("unknown primitive '{}' (valid: {})", name, fmt::join(primitiveNames(), ", ")));
  }
  m.source.kind = MeshSource::Kind::Primitive;
  m.source.primitive = name;
  m.source.params = params;
  return m;
}

}  // namespace inet
