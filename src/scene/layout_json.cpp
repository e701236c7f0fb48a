#include "scene/layout_json.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/assimp_importer.h"
#include "scene/label_map.h"
#include "scene/nyu40.h"
#include "scene/catalog_ref.h"
#include "scene/primitives.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using json = nlohmann::json;
using Keys = std::vector<std::string>;

std::string join(const Keys& keys) {
  std::string out;
  for (size_t i = 0; i < keys.size(); ++i) out += (i ? ", " : "") + keys[i];
  return out;
}

std::string dot(const std::string& base, const std::string& key) {
  return base.empty() ? key : base + "." + key;
}

std::string at(const std::string& base, size_t i) {
  return fmt::format("{}[{}]", base, i);
}

/// "string \"abc\"": a JSON value's type and (shortened) text, for messages.
std::string describe(const json& j) {
  std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return std::string(j.type_name()) + " " + text;
}

/// Typed access to parsed JSON; every failure names the file and the field path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(file_, field, problem);
  }

  /// `j` must be an object holding every `required` key and no key outside required + optional.
  void object(const json& j, const std::string& field, const Keys& required,
              const Keys& optional) const {
    if (!j.is_object()) fail(field, "expected an object, got " + describe(j));
    for (const auto& item : j.items()) {
      const std::string& key = item.key();
      if (std::find(required.begin(), required.end(), key) == required.end() &&
          std::find(optional.begin(), optional.end(), key) == optional.end()) {
        Keys all = required;
        all.insert(all.end(), optional.begin(), optional.end());
        fail(dot(field, key), "unknown key (valid keys here: " + join(all) + ")");
      }
    }
    for (const auto& key : required)
      if (!j.contains(key)) fail(dot(field, key), "missing required key");
  }

  const json& array(const json& j, const std::string& field) const {
    if (!j.is_array()) fail(field, "expected an array, got " + describe(j));
    return j;
  }

  std::string string(const json& j, const std::string& field) const {
    if (!j.is_string()) fail(field, "expected a string, got " + describe(j));
    std::string s = j.get<std::string>();
    if (s.empty()) fail(field, "must not be empty");
    return s;
  }

  double number(const json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, "expected a number, got " + describe(j));
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "must be a finite number");
    return v;
  }

  float single(const json& j, const std::string& field) const {
    double v = number(j, field);
    if (!std::isfinite(static_cast<float>(v)))
      fail(field, fmt::format("{} is outside the single-precision range", v));
    return static_cast<float>(v);
  }

  int integer(const json& j, const std::string& field, int lo, int hi) const {
    if (!j.is_number_integer()) fail(field, "expected an integer, got " + describe(j));
    // non-negative integers parse as unsigned and may exceed int64_t
    bool in_range = j.is_number_unsigned() ? (j.get<uint64_t>() <= static_cast<uint64_t>(hi) &&
                                              static_cast<int64_t>(j.get<uint64_t>()) >= lo)
                                           : (j.get<int64_t>() >= lo && j.get<int64_t>() <= hi);
    if (!in_range) fail(field, fmt::format("{} is outside {}..{}", j.dump(), lo, hi));
    return static_cast<int>(j.get<int64_t>());
  }

  const json& fixedArray(const json& j, const std::string& field, size_t n) const {
    if (!j.is_array() || j.size() != n)
      fail(field, fmt::format("expected an array of {} numbers, got {}", n, describe(j)));
    return j;
  }

  Vec3 vec3(const json& j, const std::string& field) const {
    fixedArray(j, field, 3);
    return Vec3(number(j[0], at(field, 0)), number(j[1], at(field, 1)), number(j[2], at(field, 2)));
  }

  Vec3f vec3f(const json& j, const std::string& field) const {
    fixedArray(j, field, 3);
    return Vec3f(single(j[0], at(field, 0)), single(j[1], at(field, 1)),
                 single(j[2], at(field, 2)));
  }

  Vec2f vec2f(const json& j, const std::string& field) const {
    fixedArray(j, field, 2);
    return Vec2f(single(j[0], at(field, 0)), single(j[1], at(field, 1)));
  }

 private:
  std::string file_;
};

/// Text to JSON, with syntax errors located by line and column and duplicate keys rejected
/// (nlohmann would silently keep the last one).
json parseText(const std::string& text, const std::string& file) {
  std::vector<std::set<std::string>> open_objects;
  json::parser_callback_t on_event = [&](int, json::parse_event_t event, json& value) {
    if (event == json::parse_event_t::object_start) {
      open_objects.emplace_back();
    } else if (event == json::parse_event_t::object_end) {
      open_objects.pop_back();
    } else if (event == json::parse_event_t::key && !open_objects.empty()) {
      const std::string key = value.get<std::string>();
      if (!open_objects.back().insert(key).second)
        throw InputError(file, key, "duplicate key in one JSON object");
    }
    return true;
  };
  try {
    return json::parse(text, on_event);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based index of the last character read; locate it ourselves.
    size_t pos = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
    size_t line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n');
    size_t line_start = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
    size_t column = line_start == std::string::npos ? pos + 1 : pos - line_start;
    std::string reason = e.what();
    if (size_t c = reason.find("column "); c != std::string::npos) {
      if (size_t colon = reason.find(": ", c); colon != std::string::npos)
        reason = reason.substr(colon + 2);
    }
    throw InputError(file, fmt::format("line {}, column {}", line, column),
                     "invalid JSON: " + reason);
  } catch (const json::exception& e) {
    std::string reason = e.what();
    if (size_t b = reason.find("] "); b != std::string::npos) reason = reason.substr(b + 2);
    throw InputError(file, "", "invalid JSON: " + reason);
  }
}

Mesh parsePrimitive(const Reader& r, const json& j, const std::string& field) {
  r.object(j, field, {"id", "primitive"}, {"params"});
  const std::string name = r.string(j["primitive"], dot(field, "primitive"));
  const auto& names = primitiveNames();
  if (std::find(names.begin(), names.end(), name) == names.end())
    r.fail(dot(field, "primitive"),
           fmt::format("unknown primitive '{}' (valid: {})", name, join(names)));
  std::map<std::string, double> params;
  if (j.contains("params")) {
    const json& p = j["params"];
    if (!p.is_object()) r.fail(dot(field, "params"), "expected an object, got " + describe(p));
    for (const auto& item : p.items())
      params[item.key()] = r.number(item.value(), dot(dot(field, "params"), item.key()));
  }
  return makePrimitive(name, params, r.file(), dot(field, "params"));
}

Mesh parseFileMesh(const Reader& r, const json& j, const std::string& field,
                   const fs::path& base_dir) {
  r.object(j, field, {"id", "file"}, {"scale", "up", "mesh_name"});
  const std::string file = r.string(j["file"], dot(field, "file"));
  double scale = 1.0;
  if (j.contains("scale")) {
    scale = r.number(j["scale"], dot(field, "scale"));
    if (!(scale > 0)) r.fail(dot(field, "scale"), "must be > 0 (metres per file unit)");
  }
  char up = 'z';
  if (j.contains("up")) {
    const std::string s = r.string(j["up"], dot(field, "up"));
    if (s != "y" && s != "z") r.fail(dot(field, "up"), "must be \"y\" or \"z\", got \"" + s + "\"");
    up = s[0];
  }
  std::string mesh_name;
  if (j.contains("mesh_name")) mesh_name = r.string(j["mesh_name"], dot(field, "mesh_name"));
  fs::path resolved = fs::path(file).is_absolute() ? fs::path(file) : base_dir / file;
  Mesh mesh = loadMeshFile(resolved.string(), scale, up, mesh_name, r.file(), dot(field, "file"));
  mesh.source.file = file;  // as written, so saving reproduces it
  return mesh;
}

/// Optional per-vertex attribute array `key` (one entry per vertex), read by `item`.
template <typename T, typename Item>
std::vector<T> parseVertexAttribute(const Reader& r, const json& j, const std::string& field,
                                    const char* key, size_t vertices, Item item) {
  std::vector<T> out;
  if (!j.contains(key)) return out;
  const std::string f = dot(field, key);
  const json& a = r.array(j[key], f);
  if (a.size() != vertices)
    r.fail(f, fmt::format("{} entries for {} vertices (need one per vertex)", a.size(), vertices));
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) out.push_back(item(a[i], at(f, i)));
  return out;
}

Mesh parseInlineMesh(const Reader& r, const json& j, const std::string& field) {
  r.object(j, field, {"id", "vertices", "triangles"}, {"normals", "uvs"});
  Mesh mesh;
  mesh.source.kind = MeshSource::Kind::Inline;
  const json& verts = r.array(j["vertices"], dot(field, "vertices"));
  mesh.positions.reserve(verts.size());
  for (size_t i = 0; i < verts.size(); ++i)
    mesh.positions.push_back(r.vec3f(verts[i], at(dot(field, "vertices"), i)));
  const json& tris = r.array(j["triangles"], dot(field, "triangles"));
  if (tris.empty()) r.fail(dot(field, "triangles"), "a mesh needs at least one triangle");
  const int max_index = static_cast<int>(std::min<size_t>(mesh.positions.size(), INT32_MAX)) - 1;
  mesh.triangles.reserve(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    const std::string f = at(dot(field, "triangles"), i);
    if (!tris[i].is_array() || tris[i].size() != 3)
      r.fail(f, "expected an array of 3 vertex indices, got " + describe(tris[i]));
    Tri t;
    for (int k = 0; k < 3; ++k) {
      if (max_index < 0) r.fail(f, "the mesh has no vertices");
      t[k] = static_cast<uint32_t>(r.integer(tris[i][k], at(f, k), 0, max_index));
    }
    mesh.triangles.push_back(t);
  }
  const size_t nv = mesh.positions.size();
  // normals are kept as written (normalising here would change the bits on every save and
  // load); the renderer normalises them
  mesh.normals = parseVertexAttribute<Vec3f>(r, j, field, "normals", nv,
                                             [&](const json& e, const std::string& f) {
                                               Vec3f n = r.vec3f(e, f);
                                               if (!(n.norm() > 1e-6f))
                                                 r.fail(f, "a normal must not be zero");
                                               return n;
                                             });
  mesh.uvs = parseVertexAttribute<Vec2f>(
      r, j, field, "uvs", nv, [&](const json& e, const std::string& f) { return r.vec2f(e, f); });
  return mesh;
}

/// The resolver for catalog references, or a located error saying how to get one.
std::shared_ptr<CatalogResolver> needCatalogs(const Reader& r, const std::string& field) {
  auto resolver = catalogResolver();
  if (!resolver)
    r.fail(field, "names a furniture catalog model, but no catalog is available to this program "
                  "(install sweethome3d-furniture: bash scripts/setup.sh)");
  return resolver;
}

Mesh parseCatalogMesh(const Reader& r, const json& j, const std::string& field) {
  r.object(j, field, {"id", "catalog", "part"}, {});
  const std::string piece = r.string(j["catalog"], dot(field, "catalog"));
  const int part = r.integer(j["part"], dot(field, "part"), 0, 1 << 20);
  return needCatalogs(r, dot(field, "catalog"))->mesh(piece, part, r.file(), dot(field, "part"));
}

Mesh parseMesh(const Reader& r, const json& j, const std::string& field, const fs::path& base) {
  if (!j.is_object()) r.fail(field, "expected an object, got " + describe(j));
  const int kinds = j.contains("primitive") + j.contains("file") + j.contains("vertices") +
                    j.contains("catalog");
  if (kinds != 1)
    r.fail(field,
           "a mesh needs exactly one of \"primitive\", \"file\", \"vertices\" or \"catalog\"");
  const std::string id = j.contains("id") ? r.string(j["id"], dot(field, "id")) : std::string();
  Mesh mesh = j.contains("primitive") ? parsePrimitive(r, j, field)
              : j.contains("file")    ? parseFileMesh(r, j, field, base)
              : j.contains("catalog") ? parseCatalogMesh(r, j, field)
                                      : parseInlineMesh(r, j, field);
  mesh.id = id;
  return mesh;
}

/// An image file named by a material key, resolved against the layout's folder.
TextureRef parseTexture(const Reader& r, const json& j, const std::string& field,
                        const fs::path& base_dir) {
  TextureRef t;
  t.file = r.string(j, field);
  t.path = (fs::path(t.file).is_absolute() ? fs::path(t.file) : base_dir / t.file).string();
  std::error_code ec;
  if (!fs::is_regular_file(t.path, ec))
    r.fail(field, fmt::format("'{}': {}", t.path,
                              fs::exists(t.path, ec) ? "is not a file" : "file not found"));
  return t;
}

Material parseMaterial(const Reader& r, const json& j, const std::string& field,
                       const fs::path& base_dir) {
  if (!j.is_object()) r.fail(field, "expected an object, got " + describe(j));
  if (j.contains("catalog")) {
    r.object(j, field, {"id", "catalog", "material"}, {});
    const std::string piece = r.string(j["catalog"], dot(field, "catalog"));
    const std::string name = r.string(j["material"], dot(field, "material"));
    Material m = needCatalogs(r, dot(field, "catalog"))
                     ->material(piece, name, r.file(), dot(field, "material"));
    m.id = r.string(j["id"], dot(field, "id"));
    return m;
  }
  if (!j.contains("type")) r.fail(dot(field, "type"), "missing required key");
  const std::string type = r.string(j["type"], dot(field, "type"));
  Material m;
  // required and optional keys per family
  static const std::vector<std::tuple<std::string, MaterialType, Keys, Keys>> kTypes = {
      {"lambertian",
       MaterialType::Lambertian,
       {"id", "type", "albedo"},
       {"emission", "albedo_texture"}},
      {"conductor",
       MaterialType::Conductor,
       {"id", "type", "metal"},
       {"roughness", "albedo", "emission", "albedo_texture", "roughness_texture"}},
      {"plastic",
       MaterialType::Plastic,
       {"id", "type", "albedo"},
       {"roughness", "ior", "emission", "albedo_texture", "roughness_texture"}},
      {"dielectric",
       MaterialType::Dielectric,
       {"id", "type"},
       {"ior", "roughness", "transmittance", "roughness_texture"}},
      {"thin_dielectric", MaterialType::ThinDielectric, {"id", "type"}, {"ior", "transmittance"}},
      {"translucent",
       MaterialType::Translucent,
       {"id", "type", "albedo", "transmittance"},
       {"emission", "albedo_texture"}},
  };
  bool known = false;
  for (const auto& [name, t, required, optional] : kTypes) {
    if (name != type) continue;
    Keys keys = optional;  // every family may carry a normal map and a uv scale
    keys.insert(keys.end(), {"normal_texture", "uv_scale"});
    r.object(j, field, required, keys);
    m.type = t;
    known = true;
  }
  if (!known)
    r.fail(dot(field, "type"), "unknown material type '" + type +
                                   "' (valid: lambertian, conductor, plastic, dielectric, "
                                   "thin_dielectric, translucent)");
  m.id = r.string(j["id"], dot(field, "id"));
  if (m.type == MaterialType::Conductor) m.albedo = Vec3f::Ones();
  if (j.contains("albedo")) {
    m.albedo = r.vec3f(j["albedo"], dot(field, "albedo"));
    if (m.albedo.minCoeff() < 0.f || m.albedo.maxCoeff() > 1.f)
      r.fail(dot(field, "albedo"), "each channel must be in [0, 1] (linear reflectance)");
  }
  if (j.contains("emission")) {
    m.emission = r.vec3f(j["emission"], dot(field, "emission"));
    if (m.emission.minCoeff() < 0.f)
      r.fail(dot(field, "emission"), "each channel must be >= 0 (radiance, W sr^-1 m^-2)");
  }
  if (j.contains("roughness")) m.roughness = r.single(j["roughness"], dot(field, "roughness"));
  if (j.contains("ior")) m.ior = r.single(j["ior"], dot(field, "ior"));
  if (j.contains("metal")) m.metal = r.string(j["metal"], dot(field, "metal"));
  if (j.contains("transmittance"))
    m.transmittance = r.vec3f(j["transmittance"], dot(field, "transmittance"));
  const std::pair<const char*, TextureRef Material::*> textures[] = {
      {"albedo_texture", &Material::albedo_texture},
      {"roughness_texture", &Material::roughness_texture},
      {"normal_texture", &Material::normal_texture}};
  for (const auto& [key, member] : textures)
    if (j.contains(key)) m.*member = parseTexture(r, j[key], dot(field, key), base_dir);
  if (j.contains("uv_scale")) {
    m.uv_scale = r.vec2f(j["uv_scale"], dot(field, "uv_scale"));
    if (m.uv_scale.cwiseAbs().minCoeff() == 0.f) r.fail(dot(field, "uv_scale"), "must not be 0");
  }
  return m;
}

/// The NYU40 id from "nyu40" and/or "category"; when both are given they must agree.
int parseLabel(const Reader& r, const json& j, const std::string& field) {
  if (!j.contains("nyu40") && !j.contains("category"))
    r.fail(field, "needs \"nyu40\" (an id 0..40) or \"category\" (an NYU40 class name)");
  std::optional<int> by_id, by_name;
  if (j.contains("nyu40")) by_id = r.integer(j["nyu40"], dot(field, "nyu40"), 0, kNyu40Count - 1);
  if (j.contains("category")) {
    const std::string name = r.string(j["category"], dot(field, "category"));
    by_name = nyu40FromName(name);
    if (!by_name)
      r.fail(dot(field, "category"),
             fmt::format("unknown NYU40 class '{}' (valid: {})", name, nyu40NameList()));
  }
  if (by_id && by_name && *by_id != *by_name)
    r.fail(dot(field, "category"),
           fmt::format("'{}' is NYU40 id {}, but \"nyu40\" says {} ('{}')", nyu40Name(*by_name),
                       *by_name, *by_id, nyu40Name(*by_id)));
  return by_id ? *by_id : *by_name;
}

/// Index of `id` in `ids`, or a failure listing the defined ids.
int resolveId(const Reader& r, const std::map<std::string, int>& ids, const std::string& id,
              const std::string& field, const char* what) {
  auto it = ids.find(id);
  if (it != ids.end()) return it->second;
  Keys names;
  for (const auto& [name, index] : ids) names.push_back(name);
  if (names.size() > 20) {
    names.resize(20);
    names.push_back("...");
  }
  r.fail(field, fmt::format("unknown {} id '{}' (defined: {})", what, id,
                            names.empty() ? std::string("none") : join(names)));
}

Object parseObject(const Reader& r, const json& j, const std::string& field,
                   const std::map<std::string, int>& mesh_ids,
                   const std::map<std::string, int>& material_ids,
                   const std::map<std::string, int>& room_ids) {
  r.object(j, field, {"name", "mesh", "material", "instance", "transform"},
           {"nyu40", "category", "motion", "kind", "part", "room", "physics"});
  Object o;
  o.name = r.string(j["name"], dot(field, "name"));
  o.mesh =
      resolveId(r, mesh_ids, r.string(j["mesh"], dot(field, "mesh")), dot(field, "mesh"), "mesh");
  o.material = resolveId(r, material_ids, r.string(j["material"], dot(field, "material")),
                         dot(field, "material"), "material");
  o.nyu40 = parseLabel(r, j, field);
  o.instance = r.integer(j["instance"], dot(field, "instance"), 1, 65535);
  const std::string tf = dot(field, "transform");
  const json& t = r.fixedArray(j["transform"], tf, 16);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      o.T_world_object(row, col) = r.number(t[row * 4 + col], at(tf, row * 4 + col));
  if (j.contains("motion")) {
    const std::string mf = dot(field, "motion");
    const json& keys = r.array(j["motion"], mf);
    if (keys.empty()) r.fail(mf, "needs at least one keyframe (or leave \"motion\" out)");
    for (size_t k = 0; k < keys.size(); ++k) {
      const std::string kf = at(mf, k);
      r.object(keys[k], kf, {"t", "translation", "rotation"}, {});
      ObjectKeyframe key;
      key.t_s = r.number(keys[k]["t"], dot(kf, "t"));
      if (k > 0 && !(key.t_s > o.motion.back().t_s))
        r.fail(dot(kf, "t"), "keyframe times must increase strictly");
      key.pose.t = r.vec3(keys[k]["translation"], dot(kf, "translation"));
      const std::string rf = dot(kf, "rotation");
      const json& q = r.fixedArray(keys[k]["rotation"], rf, 4);
      const Quat quat(r.number(q[0], at(rf, 0)), r.number(q[1], at(rf, 1)),
                      r.number(q[2], at(rf, 2)), r.number(q[3], at(rf, 3)));
      if (std::abs(quat.norm() - 1.0) > 1e-6)
        r.fail(rf, fmt::format("a unit quaternion [w, x, y, z] is needed (norm {})", quat.norm()));
      key.pose.q = quat;
      o.motion.push_back(key);
    }
  }
  if (j.contains("kind")) o.kind = r.string(j["kind"], dot(field, "kind"));
  if (j.contains("part")) o.part = r.string(j["part"], dot(field, "part"));
  if (j.contains("room"))
    o.room =
        resolveId(r, room_ids, r.string(j["room"], dot(field, "room")), dot(field, "room"), "room");
  if (j.contains("physics")) {
    const std::string pf = dot(field, "physics");
    const json& p = j["physics"];
    r.object(p, pf, {"mass_kg", "friction", "movable"}, {});
    PhysicsProps phys;
    phys.mass_kg = r.single(p["mass_kg"], dot(pf, "mass_kg"));
    if (!(phys.mass_kg > 0.f)) r.fail(dot(pf, "mass_kg"), "must be > 0");
    phys.friction = r.single(p["friction"], dot(pf, "friction"));
    if (!(phys.friction >= 0.f)) r.fail(dot(pf, "friction"), "must be >= 0");
    if (!p["movable"].is_boolean())
      r.fail(dot(pf, "movable"), "expected true or false, got " + describe(p["movable"]));
    phys.movable = p["movable"].get<bool>();
    o.physics = phys;
  }
  return o;
}

Room parseRoom(const Reader& r, const json& j, const std::string& field) {
  r.object(j, field, {"id", "type", "outline"}, {"floor_z", "ceiling_z"});
  Room room;
  room.id = r.string(j["id"], dot(field, "id"));
  room.type = r.string(j["type"], dot(field, "type"));
  const auto& types = roomTypeNames();
  if (std::find(types.begin(), types.end(), room.type) == types.end())
    r.fail(dot(field, "type"),
           "unknown room type '" + room.type + "' (valid: " + join(types) + ")");
  const std::string of = dot(field, "outline");
  const json& pts = r.array(j["outline"], of);
  if (pts.size() < 3) r.fail(of, "a room outline needs 3 or more [x, y] points");
  for (size_t k = 0; k < pts.size(); ++k) {
    const std::string pf = at(of, k);
    const json& p = r.fixedArray(pts[k], pf, 2);
    room.outline.emplace_back(r.number(p[0], at(pf, 0)), r.number(p[1], at(pf, 1)));
  }
  if (!(room.area() > 0)) r.fail(of, "must enclose an area, counter-clockwise seen from above");
  if (j.contains("floor_z")) room.floor_z = r.number(j["floor_z"], dot(field, "floor_z"));
  if (j.contains("ceiling_z")) room.ceiling_z = r.number(j["ceiling_z"], dot(field, "ceiling_z"));
  if (!(room.ceiling_z > room.floor_z)) r.fail(dot(field, "ceiling_z"), "must be above floor_z");
  return room;
}

/// A sky's "model" ("uniform" when absent).
SkyModel parseSkyModel(const Reader& r, const json& j, const std::string& field) {
  if (!j.contains("model")) return SkyModel::Uniform;
  const std::string model = r.string(j["model"], dot(field, "model"));
  for (SkyModel m : {SkyModel::Uniform, SkyModel::Preetham, SkyModel::EnvMap})
    if (model == skyModelName(m)) return m;
  r.fail(dot(field, "model"),
         "unknown sky model '" + model + "' (valid: uniform, preetham, envmap)");
}

/// An envmap sky's rotation: 3 rows of 3 numbers (map frame -> world), kept as written; Scene::
/// validate checks that it is a rotation.
Mat3 parseRotation(const Reader& r, const json& j, const std::string& field) {
  const json& rows = r.fixedArray(j, field, 3);
  Mat3 m;
  for (int i = 0; i < 3; ++i) m.row(i) = r.vec3(rows[i], at(field, i)).transpose();
  return m;
}

Light parseLight(const Reader& r, const json& j, const std::string& field,
                 const fs::path& base_dir) {
  if (!j.is_object()) r.fail(field, "expected an object, got " + describe(j));
  if (!j.contains("type"))
    r.fail(dot(field, "type"), "missing required key (point, spot, sun or sky)");
  const std::string type = r.string(j["type"], dot(field, "type"));
  Light l;
  const Keys common = {"color", "temperature_k", "on", "object"};
  auto keys = [&](Keys extra) {
    extra.insert(extra.end(), common.begin(), common.end());
    return extra;
  };
  if (type == "point") {
    l.type = LightType::Point;
    r.object(j, field, {"name", "type", "position", "intensity"}, keys({"max_distance", "radius"}));
  } else if (type == "spot") {
    l.type = LightType::Spot;
    r.object(j, field, {"name", "type", "position", "direction", "intensity", "cone_deg"},
             keys({"falloff_deg", "max_distance", "radius"}));
  } else if (type == "sun") {
    l.type = LightType::Sun;
    r.object(j, field, {"name", "type", "direction", "intensity"}, keys({"angular_diameter_deg"}));
  } else if (type == "sky") {
    l.type = LightType::Sky;
    l.sky_model = parseSkyModel(r, j, field);
    if (l.sky_model == SkyModel::Uniform)
      r.object(j, field, {"name", "type", "intensity"}, keys({"model"}));
    else if (l.sky_model == SkyModel::EnvMap)  // the image gives the colour
      r.object(j, field, {"name", "type", "model", "file", "intensity"},
               {"rotation", "on", "object"});
    else  // the model gives the colour: no color or temperature_k
      r.object(j, field, {"name", "type", "model", "sun_direction", "intensity"},
               {"turbidity", "on", "object"});
  } else {
    r.fail(dot(field, "type"), "unknown light type '" + type + "' (valid: point, spot, sun, sky)");
  }
  l.name = r.string(j["name"], dot(field, "name"));
  if (j.contains("position")) l.position = r.vec3(j["position"], dot(field, "position"));
  if (j.contains("direction")) {
    l.direction = r.vec3(j["direction"], dot(field, "direction"));
    if (l.direction.norm() < 1e-9) r.fail(dot(field, "direction"), "must not be zero");
    // normalise once; a direction already unit to 1e-9 is kept bit for bit (round trips)
    if (std::abs(l.direction.norm() - 1.0) > 1e-9) l.direction.normalize();
  }
  // kept as written (not normalised): Scene::validate insists on a unit vector above the horizon
  if (j.contains("sun_direction"))
    l.direction = r.vec3(j["sun_direction"], dot(field, "sun_direction"));
  if (j.contains("turbidity")) l.turbidity = r.single(j["turbidity"], dot(field, "turbidity"));
  if (j.contains("file")) l.envmap = parseTexture(r, j["file"], dot(field, "file"), base_dir);
  if (j.contains("rotation"))
    l.envmap_rotation = parseRotation(r, j["rotation"], dot(field, "rotation"));
  l.intensity = r.single(j["intensity"], dot(field, "intensity"));
  if (l.intensity < 0.f) r.fail(dot(field, "intensity"), "must be >= 0 (W/sr, or W/m^2 for a sun)");
  if (j.contains("color")) l.color = r.vec3f(j["color"], dot(field, "color"));
  if (j.contains("temperature_k"))
    l.temperature_k = r.single(j["temperature_k"], dot(field, "temperature_k"));
  if (j.contains("cone_deg")) l.cone_deg = r.single(j["cone_deg"], dot(field, "cone_deg"));
  if (j.contains("falloff_deg"))
    l.falloff_deg = r.single(j["falloff_deg"], dot(field, "falloff_deg"));
  if (j.contains("angular_diameter_deg"))
    l.angular_diameter_deg =
        r.single(j["angular_diameter_deg"], dot(field, "angular_diameter_deg"));
  if (j.contains("max_distance"))
    l.max_distance = r.single(j["max_distance"], dot(field, "max_distance"));
  if (j.contains("radius")) l.radius = r.single(j["radius"], dot(field, "radius"));
  if (j.contains("on")) {
    if (!j["on"].is_boolean())
      r.fail(dot(field, "on"), "expected true or false, got " + describe(j["on"]));
    l.on = j["on"].get<bool>();
  }
  if (j.contains("object")) l.object = r.string(j["object"], dot(field, "object"));
  return l;
}

/// Checks "format" and "version" first, so that a file of another kind or a newer version gets
/// that message rather than a complaint about some key it happens to contain.
void checkHeader(const Reader& r, const json& root) {
  if (!root.is_object())
    r.fail("", "expected a JSON object at the top level, got " + describe(root));
  if (!root.contains("format")) {
    // a 3D-FRONT house has "furniture" and "scene": say how to bring it in
    const bool front3d = root.contains("furniture") && root.contains("scene");
    r.fail("format",
           fmt::format("missing; a layout file declares \"format\": \"{}\"{}", kLayoutFormat,
                       front3d ? " (this looks like a 3D-FRONT house: convert it with "
                                 "'interiornet layout import --from 3dfront')"
                               : ""));
  }
  if (!root["format"].is_string() || root["format"].get<std::string>() != kLayoutFormat)
    r.fail("format",
           fmt::format("expected \"{}\", got {}", kLayoutFormat, describe(root["format"])));
  if (!root.contains("version")) r.fail("version", "missing required key");
  const json& v = root["version"];
  const auto& supported = supportedLayoutVersions();
  Keys names;
  for (int s : supported) names.push_back(std::to_string(s));
  bool ok = v.is_number_integer() &&
            std::find(supported.begin(), supported.end(), v.get<int64_t>()) != supported.end();
  if (!ok)
    r.fail("version", fmt::format("unsupported version {} (this build reads version {})",
                                  v.is_number_integer() ? v.dump() : describe(v), join(names)));
}

/// Parses each element of root[key] with `parse`, rejecting duplicate ids; returns id -> index.
template <class T, class Parse>
std::map<std::string, int> parseList(const Reader& r, const json& root, const char* key,
                                     std::vector<T>& out, Parse parse) {
  std::map<std::string, int> ids;
  const json& list = r.array(root[key], key);
  for (size_t i = 0; i < list.size(); ++i) {
    T item = parse(list[i], at(key, i));
    auto [it, inserted] = ids.emplace(item.id, static_cast<int>(i));
    if (!inserted)
      r.fail(at(key, i) + ".id",
             fmt::format("duplicate id '{}' (already used by {})", item.id, at(key, it->second)));
    out.push_back(std::move(item));
  }
  return ids;
}

}  // namespace

Scene parseLayout(const std::string& text, const std::string& path) {
  const Reader r(path);
  const json root = parseText(text, path);
  checkHeader(r, root);
  r.object(root, "", {"format", "version", "meshes", "materials", "objects"},
           {"name", "lights", "rooms"});
  Scene scene;
  if (root.contains("name")) scene.name = r.string(root["name"], "name");
  const fs::path base_dir = fs::path(path).parent_path();
  auto mesh_ids = parseList(r, root, "meshes", scene.meshes, [&](const json& j, const auto& f) {
    return parseMesh(r, j, f, base_dir);
  });
  auto material_ids =
      parseList(r, root, "materials", scene.materials,
                [&](const json& j, const auto& f) { return parseMaterial(r, j, f, base_dir); });
  std::map<std::string, int> room_ids;
  if (root.contains("rooms"))
    room_ids = parseList(r, root, "rooms", scene.rooms,
                         [&](const json& j, const auto& f) { return parseRoom(r, j, f); });
  const json& objects = r.array(root["objects"], "objects");
  for (size_t i = 0; i < objects.size(); ++i)
    scene.objects.push_back(
        parseObject(r, objects[i], at("objects", i), mesh_ids, material_ids, room_ids));
  if (root.contains("lights")) {
    const json& lights = r.array(root["lights"], "lights");
    for (size_t i = 0; i < lights.size(); ++i)
      scene.lights.push_back(parseLight(r, lights[i], at("lights", i), base_dir));
  }
  scene.validate(path);
  return scene;
}

Scene loadLayout(const std::string& path) {
  return parseLayout(readTextFile(path), path);
}

}  // namespace inet
