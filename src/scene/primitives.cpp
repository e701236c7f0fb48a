#include "scene/primitives.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {

void addQuad(Mesh& m, const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec3f& d) {
  auto base = static_cast<uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {a, b, c, d});
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

Mesh cylinder(int segments) {
  Mesh m;
  const float r = 0.5f, h = 0.5f;
  auto ring = [&](float z) {
    for (int i = 0; i < segments; ++i) {
      float a = 2.0f * static_cast<float>(M_PI) * i / segments;
      m.positions.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  };
  ring(-h);
  ring(h);
  auto bottom_c = static_cast<uint32_t>(m.positions.size());
  m.positions.emplace_back(0.f, 0.f, -h);
  m.positions.emplace_back(0.f, 0.f, h);
  auto n = static_cast<uint32_t>(segments);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t j = (i + 1) % n;
    m.triangles.push_back(Tri(i, j, n + j));
    m.triangles.push_back(Tri(i, n + j, n + i));
    m.triangles.push_back(Tri(bottom_c, j, i));
    m.triangles.push_back(Tri(bottom_c + 1, n + i, n + j));
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

}  // namespace

const std::vector<std::string>& primitiveNames() {
  static const std::vector<std::string> names = {"box", "cylinder", "quad", "sphere"};
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
    rejectUnknown(params, {"segments"}, where, field, name);
    double seg = param(params, "segments", 24);
    if (!(seg >= 3 && seg <= 256) || seg != std::floor(seg)) {
      throw InputError(where, field + ".segments", "must be an integer in [3, 256]");
    }
    m = cylinder(static_cast<int>(seg));
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
