// The layout.json writer: a Scene back to schema-v1 text (docs/layout.md), in a fixed key order
// and number format so that load -> save -> load -> save is byte-stable. The reader is
// layout_json.cpp.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/layout_json.h"
#include "scene/nyu40.h"

namespace inet {
namespace {

std::string at(const std::string& base, size_t i) {
  return fmt::format("{}[{}]", base, i);
}
using ojson = nlohmann::ordered_json;

/// A double as JSON: integral values as integers ("1" rather than "1.0"; reads back identical),
/// others as nlohmann's shortest round-trip text. -0.0 keeps its sign.
ojson jsonNumber(double v) {
  const bool negative_zero = (v == 0.0 && std::signbit(v));
  if (v == std::floor(v) && std::fabs(v) < 1e15 && !negative_zero) return static_cast<int64_t>(v);
  return v;
}

/// A float as JSON: the shortest decimal that reads back (double, then cast to float) as the
/// same float, e.g. 0.72f -> 0.72 instead of its widened 0.7200000286102295.
ojson jsonNumber(float f) {
  const std::string text = fmt::format("{}", f);
  double d = std::strtod(text.c_str(), nullptr);
  if (static_cast<float>(d) != f) d = static_cast<double>(f);  // guard against double rounding
  return jsonNumber(d);
}

template <class V>
ojson jsonArray(const V& v) {
  ojson a = ojson::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(jsonNumber(v[i]));
  return a;
}

ojson lightToJson(const Light& l) {
  ojson j;
  j["name"] = l.name;
  j["type"] = lightTypeName(l.type);
  const bool directional = l.type == LightType::Sun || l.type == LightType::Sky;
  // a uniform sky writes no model (files from before the Preetham sky keep their bytes)
  const bool preetham = l.type == LightType::Sky && l.sky_model == SkyModel::Preetham;
  const bool envmap = l.type == LightType::Sky && l.sky_model == SkyModel::EnvMap;
  if (preetham) {
    j["model"] = skyModelName(l.sky_model);
    j["sun_direction"] = jsonArray(l.direction);
    j["turbidity"] = jsonNumber(l.turbidity);
  }
  if (envmap) {
    j["model"] = skyModelName(l.sky_model);
    j["file"] = l.envmap.file;
    ojson rows = ojson::array();
    for (int i = 0; i < 3; ++i) rows.push_back(jsonArray(Vec3(l.envmap_rotation.row(i))));
    j["rotation"] = std::move(rows);
  }
  if (!directional) j["position"] = jsonArray(l.position);
  if (l.type == LightType::Spot || l.type == LightType::Sun)
    j["direction"] = jsonArray(l.direction);
  j["intensity"] = jsonNumber(l.intensity);
  if (!preetham && !envmap) {  // the model (the image) gives a Preetham (envmap) sky's colour
    j["color"] = jsonArray(l.color);
    j["temperature_k"] = jsonNumber(l.temperature_k);
  }
  if (l.type == LightType::Spot) {
    j["cone_deg"] = jsonNumber(l.cone_deg);
    j["falloff_deg"] = jsonNumber(l.falloff_deg);
  }
  if (l.type == LightType::Sun) j["angular_diameter_deg"] = jsonNumber(l.angular_diameter_deg);
  if (!directional) j["max_distance"] = jsonNumber(l.max_distance);
  if (!directional && l.radius > 0.f) j["radius"] = jsonNumber(l.radius);
  j["on"] = l.on;
  if (!l.object.empty()) j["object"] = l.object;
  return j;
}

ojson materialToJson(const Material& m) {
  ojson j;
  j["id"] = m.id;
  if (!m.catalog_piece.empty()) {  // named, not written out (scene/catalog_ref.h)
    j["catalog"] = m.catalog_piece;
    j["material"] = m.catalog_material;
    return j;
  }
  j["type"] = materialTypeName(m.type);
  const MaterialType t = m.type;
  if (t != MaterialType::Dielectric && t != MaterialType::ThinDielectric)
    j["albedo"] = jsonArray(m.albedo);
  if (t == MaterialType::Conductor) j["metal"] = m.metal;
  if (t == MaterialType::Conductor || t == MaterialType::Plastic || t == MaterialType::Dielectric)
    j["roughness"] = jsonNumber(m.roughness);
  if (t == MaterialType::Plastic || t == MaterialType::Dielectric ||
      t == MaterialType::ThinDielectric)
    j["ior"] = jsonNumber(m.ior);
  if (t == MaterialType::Dielectric || t == MaterialType::ThinDielectric ||
      t == MaterialType::Translucent)
    j["transmittance"] = jsonArray(m.transmittance);
  if (t != MaterialType::Dielectric && t != MaterialType::ThinDielectric)
    j["emission"] = jsonArray(m.emission);
  if (!m.albedo_texture.empty()) j["albedo_texture"] = m.albedo_texture.file;
  if (!m.roughness_texture.empty()) j["roughness_texture"] = m.roughness_texture.file;
  if (!m.normal_texture.empty()) j["normal_texture"] = m.normal_texture.file;
  if (m.uv_scale != Vec2f(1.f, 1.f)) j["uv_scale"] = jsonArray(m.uv_scale);
  return j;
}

ojson meshToJson(const Mesh& m, const std::string& where, const std::string& field) {
  ojson j;
  j["id"] = m.id;
  const MeshSource& s = m.source;
  switch (s.kind) {
    case MeshSource::Kind::Primitive: {
      j["primitive"] = s.primitive;
      if (!s.params.empty()) {
        ojson params = ojson::object();
        for (const auto& [key, value] : s.params) params[key] = jsonNumber(value);
        j["params"] = params;
      }
      break;
    }
    case MeshSource::Kind::File:
      j["file"] = s.file;
      j["scale"] = jsonNumber(s.scale);
      j["up"] = std::string(1, s.up);
      if (!s.mesh_name.empty()) j["mesh_name"] = s.mesh_name;
      break;
    case MeshSource::Kind::Catalog:
      j["catalog"] = s.catalog_piece;
      j["part"] = s.catalog_part;
      break;
    case MeshSource::Kind::Inline: {
      if (m.isSphere())
        throw InputError(where, field,
                         "an analytic sphere must have a \"sphere\" primitive source");
      ojson verts = ojson::array(), tris = ojson::array();
      for (const auto& p : m.positions) verts.push_back(jsonArray(p));
      for (const auto& t : m.triangles) tris.push_back({t[0], t[1], t[2]});
      j["vertices"] = std::move(verts);
      j["triangles"] = std::move(tris);
      if (!m.normals.empty()) {
        ojson normals = ojson::array();
        for (const auto& n : m.normals) normals.push_back(jsonArray(n));
        j["normals"] = std::move(normals);
      }
      if (!m.uvs.empty()) {
        ojson uvs = ojson::array();
        for (const auto& uv : m.uvs) uvs.push_back(jsonArray(uv));
        j["uvs"] = std::move(uvs);
      }
      break;
    }
  }
  return j;
}

ojson objectToJson(const Scene& scene, const Object& o) {
  ojson j;
  j["name"] = o.name;
  j["mesh"] = scene.meshes[o.mesh].id;
  j["material"] = scene.materials[o.material].id;
  j["nyu40"] = o.nyu40;
  j["category"] = std::string(nyu40Name(o.nyu40));
  j["instance"] = o.instance;
  ojson t = ojson::array();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) t.push_back(jsonNumber(o.T_world_object(row, col)));
  j["transform"] = std::move(t);
  if (o.moving()) {
    ojson keys = ojson::array();
    for (const ObjectKeyframe& k : o.motion) {
      ojson key;
      key["t"] = jsonNumber(k.t_s);
      key["translation"] = jsonArray(k.pose.t);
      key["rotation"] = {jsonNumber(k.pose.q.w()), jsonNumber(k.pose.q.x()),
                         jsonNumber(k.pose.q.y()), jsonNumber(k.pose.q.z())};
      keys.push_back(std::move(key));
    }
    j["motion"] = std::move(keys);
  }
  if (!o.kind.empty()) j["kind"] = o.kind;
  if (!o.part.empty()) j["part"] = o.part;
  if (o.room >= 0) j["room"] = scene.rooms[o.room].id;
  if (o.physics) {
    ojson p;
    p["mass_kg"] = jsonNumber(o.physics->mass_kg);
    p["friction"] = jsonNumber(o.physics->friction);
    p["movable"] = o.physics->movable;
    j["physics"] = std::move(p);
  }
  return j;
}

ojson roomToJson(const Room& r) {
  ojson j;
  j["id"] = r.id;
  j["type"] = r.type;
  ojson pts = ojson::array();
  for (const auto& p : r.outline) pts.push_back({jsonNumber(p.x()), jsonNumber(p.y())});
  j["outline"] = std::move(pts);
  j["floor_z"] = jsonNumber(r.floor_z);
  j["ceiling_z"] = jsonNumber(r.ceiling_z);
  return j;
}

/// Ids must be present and unique for objects to refer to them and for the file to load again.
template <class T>
void checkIds(const std::vector<T>& items, const std::string& where, const char* list) {
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].id.empty()) throw InputError(where, at(list, i) + ".id", "empty id");
    auto [it, inserted] = seen.emplace(items[i].id, i);
    if (!inserted)
      throw InputError(
          where, at(list, i) + ".id",
          fmt::format("duplicate id '{}' (already used by {})", items[i].id, at(list, it->second)));
  }
}

/// Everything the reader requires that Scene::validate does not check, so that what we write
/// always loads again.
void checkWritable(const Scene& scene, const std::string& where) {
  scene.validate(where);
  checkIds(scene.meshes, where, "meshes");
  checkIds(scene.materials, where, "materials");
  checkIds(scene.rooms, where, "rooms");
  if (scene.name.empty()) throw InputError(where, "name", "empty scene name");
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshSource& src = scene.meshes[i].source;
    if (src.kind == MeshSource::Kind::File &&
        (src.file.empty() || !(src.scale > 0) || (src.up != 'y' && src.up != 'z')))
      throw InputError(where, at("meshes", i), "file source needs a path, scale > 0, up y or z");
  }
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name.empty()) throw InputError(where, at("objects", i) + ".name", "empty");
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].name.empty()) throw InputError(where, at("lights", i) + ".name", "empty");
}

bool isScalar(const ojson& j) {
  return !j.is_object() && !j.is_array();
}

std::string dumpScalar(const ojson& j) {
  return j.dump(-1, ' ', false, ojson::error_handler_t::replace);
}

/// 2-space indented JSON with arrays of scalars kept on one line ("[1, 0, 0]").
void writePretty(const ojson& j, int indent, std::string& out) {
  const bool nested = j.is_object() || (j.is_array() && !std::all_of(j.begin(), j.end(), isScalar));
  if (!nested || j.empty()) {
    if (j.is_array()) {
      out += '[';
      for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + dumpScalar(j[i]);
      out += ']';
    } else {
      out += j.is_object() ? std::string("{}") : dumpScalar(j);
    }
    return;
  }
  out += j.is_object() ? "{\n" : "[\n";
  size_t i = 0;
  for (auto it = j.begin(); it != j.end(); ++it, ++i) {
    out.append(static_cast<size_t>(indent) + 2, ' ');
    if (j.is_object()) out += dumpScalar(ojson(it.key())) + ": ";
    writePretty(it.value(), indent + 2, out);
    out += (i + 1 < j.size()) ? ",\n" : "\n";
  }
  out.append(static_cast<size_t>(indent), ' ');
  out += j.is_object() ? '}' : ']';
}

}  // namespace

std::string layoutToJson(const Scene& scene) {
  const std::string where = fmt::format("scene '{}'", scene.name);
  checkWritable(scene, where);
  ojson root;
  root["format"] = kLayoutFormat;
  root["version"] = supportedLayoutVersions().back();
  root["name"] = scene.name;
  if (!scene.rooms.empty()) {  // layouts without rooms keep their bytes
    root["rooms"] = ojson::array();
    for (const auto& r : scene.rooms) root["rooms"].push_back(roomToJson(r));
  }
  root["meshes"] = ojson::array();
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    root["meshes"].push_back(meshToJson(scene.meshes[i], where, at("meshes", i)));
  root["materials"] = ojson::array();
  for (const auto& m : scene.materials) root["materials"].push_back(materialToJson(m));
  root["objects"] = ojson::array();
  for (const auto& o : scene.objects) root["objects"].push_back(objectToJson(scene, o));
  root["lights"] = ojson::array();
  for (const auto& l : scene.lights) root["lights"].push_back(lightToJson(l));
  std::string out;
  writePretty(root, 0, out);
  out += '\n';
  return out;
}

void saveLayout(const Scene& scene, const std::string& path) {
  writeTextAtomic(path, layoutToJson(scene));
}

}  // namespace inet
