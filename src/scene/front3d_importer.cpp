#include "scene/front3d_importer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "scene/assimp_importer.h"
#include "scene/label_map.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using json = nlohmann::json;

/// y-up file coordinates to z-up world: x -> x, y -> z, z -> -y.
Mat4 yUpToZUp() {
  Mat4 c = Mat4::Zero();
  c(0, 0) = 1;
  c(1, 2) = -1;
  c(2, 1) = 1;
  c(3, 3) = 1;
  return c;
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(file_, field, problem);
  }
  /// A number, or a string holding one (3D-FRONT writes some coordinates as strings).
  double number(const json& j, const std::string& field) const {
    if (j.is_number()) return j.get<double>();
    if (j.is_string()) {
      const std::string s = j.get<std::string>();
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (!s.empty() && *end == '\0' && std::isfinite(v)) return v;
    }
    fail(field, "expected a number, got " + j.dump().substr(0, 40));
  }
  const json& array(const json& j, const char* key, const std::string& field) const {
    if (!j.is_object() || !j.contains(key) || !j[key].is_array())
      fail(field + "." + key, "missing array");
    return j[key];
  }
  Vec3 vec3(const json& j, const std::string& field) const {
    if (!j.is_array() || j.size() != 3) fail(field, "expected 3 numbers");
    return Vec3(number(j[0], field), number(j[1], field), number(j[2], field));
  }

 private:
  std::string file_;
};

/// NYU40 class of an architecture mesh type.
int archClass(const std::string& type) {
  static const std::map<std::string, int> table = {{"WallInner", 1},
                                                   {"WallOuter", 1},
                                                   {"WallTop", 1},
                                                   {"WallBottom", 1},
                                                   {"Pocket", 1},
                                                   {"Baseboard", 1},
                                                   {"CustomizedFeatureWall", 1},
                                                   {"Front", 1},
                                                   {"Back", 1},
                                                   {"SlabSide", 1},
                                                   {"Floor", 2},
                                                   {"Ceiling", 22},
                                                   {"CustomizedCeiling", 22},
                                                   {"SlabTop", 22},
                                                   {"SlabBottom", 2},
                                                   {"Door", 8},
                                                   {"Window", 9},
                                                   {"Cabinet", 3},
                                                   {"CustomizedPlatform", 38}};
  auto it = table.find(type);
  return it == table.end() ? 38 : it->second;  // otherstructure
}

/// Our room type for a 3D-FRONT room type.
std::string roomType(const std::string& t) {
  std::string s = t;
  std::transform(s.begin(), s.end(), s.begin(), ::tolower);
  auto has = [&](const char* w) { return s.find(w) != std::string::npos; };
  if (has("masterbathroom")) return "master_bathroom";
  if (has("bathroom")) return "bathroom";
  if (has("masterbedroom")) return "master_bedroom";
  if (has("kidsroom")) return "kids_room";
  if (has("elderlyroom")) return "elderly_room";
  if (has("bedroom")) return "second_bedroom";
  if (has("library") || has("study")) return "study";
  if (has("kitchen")) return "kitchen";
  if (has("diningroom") && !has("living")) return "dining_room";
  if (has("balcony") || has("terrace")) return "balcony";
  if (has("hallway") || has("aisle") || has("corridor") || has("stair")) return "corridor";
  if (has("entrance") || has("foyer")) return "entrance";
  if (has("storage")) return "storage";
  if (has("cloak")) return "cloakroom";
  if (has("laundry")) return "laundry";
  return "living_room";
}

/// NYU40 class of a 3D-FUTURE category by keywords (the label map, if any, first).
std::optional<int> furnitureClass(const std::string& category) {
  std::string s = category;
  std::transform(s.begin(), s.end(), s.begin(), ::tolower);
  auto has = [&](const char* w) { return s.find(w) != std::string::npos; };
  const std::pair<const char*, const char*> table[] = {{"nightstand", "night_stand"},
                                                       {"sofa", "sofa"},
                                                       {"bed", "bed"},
                                                       {"chair", "chair"},
                                                       {"stool", "chair"},
                                                       {"table", "table"},
                                                       {"desk", "desk"},
                                                       {"wardrobe", "cabinet"},
                                                       {"cabinet", "cabinet"},
                                                       {"shelf", "shelves"},
                                                       {"bookcase", "bookshelf"},
                                                       {"lamp", "lamp"},
                                                       {"lighting", "lamp"},
                                                       {"tv", "television"},
                                                       {"mirror", "mirror"},
                                                       {"dresser", "dresser"},
                                                       {"curtain", "curtain"},
                                                       {"refrigerator", "refridgerator"},
                                                       {"sink", "sink"},
                                                       {"toilet", "toilet"},
                                                       {"bath", "bathtub"}};
  for (const auto& [key, name] : table)
    if (has(key)) return nyu40FromName(name);
  return std::nullopt;
}

}  // namespace

std::string Front3dReport::summary() const {
  std::vector<std::string> parts;
  if (placeholders > 0)
    parts.push_back(fmt::format(
        "{} of {} furniture piece(s) have no 3D-FUTURE model file and are placed as labelled "
        "boxes of their bounding box",
        placeholders, furniture));
  if (missing_refs > 0)
    parts.push_back(
        fmt::format("{} room child(ren) name nothing in the file and were skipped", missing_refs));
  if (!unmatched_categories.empty()) {
    std::string names;
    for (size_t i = 0; i < unmatched_categories.size() && i < 10; ++i)
      names += (i ? ", " : "") + unmatched_categories[i];
    parts.push_back(
        fmt::format("{} furniture categor(y/ies) matched no NYU40 class and were "
                    "labelled 'otherprop': {}",
                    unmatched_categories.size(), names));
  }
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

Scene importFront3d(const std::string& path, const Front3dOptions& opt, Front3dReport* out) {
  const Reader r(path);
  json root;
  try {
    root = json::parse(readTextFile(path));
  } catch (const json::parse_error& e) {
    throw InputError(path, "", fmt::format("malformed JSON (byte {})", e.byte));
  }
  if (!root.is_object() || !root.contains("scene") || !root["scene"].is_object())
    r.fail("scene", "missing: not a 3D-FRONT house file");
  const LabelMap labels = opt.label_map.empty() ? LabelMap() : LabelMap::load(opt.label_map);
  Front3dReport report;
  Scene scene;
  scene.name = fs::path(path).stem().string();
  const Mat4 C = yUpToZUp();

  // materials
  std::map<std::string, int> material_of;
  if (root.contains("material") && root["material"].is_array()) {
    const json& mats = root["material"];
    for (size_t i = 0; i < mats.size(); ++i) {
      const json& m = mats[i];
      if (!m.is_object() || !m.contains("uid") || !m["uid"].is_string()) continue;
      Material mat;
      mat.id = fmt::format("m{}_{}", i, m["uid"].get<std::string>());
      if (m.contains("color") && m["color"].is_array() && m["color"].size() >= 3) {
        Vec3f c;
        for (int k = 0; k < 3; ++k) {
          const double v = std::clamp(
              r.number(m["color"][k], fmt::format("material[{}].color[{}]", i, k)) / 255.0, 0.0,
              1.0);
          c[k] = static_cast<float>(srgbEotf(v));
        }
        mat.albedo = c.cwiseMin(0.9f);  // keep pure white paint from being a perfect reflector
      }
      material_of[m["uid"].get<std::string>()] = static_cast<int>(scene.materials.size());
      scene.materials.push_back(mat);
    }
  }
  auto defaultMaterial = [&]() {
    int i = scene.findMaterial("default_grey");
    if (i >= 0) return i;
    Material m;
    m.id = "default_grey";
    m.albedo = Vec3f::Constant(0.6f);
    scene.materials.push_back(m);
    return static_cast<int>(scene.materials.size()) - 1;
  };

  // architecture meshes (kept in y-up world; objects carry C)
  struct Arch {
    int mesh = -1, material = -1, nyu40 = 38;
    std::string type;
  };
  std::map<std::string, Arch> arch;
  if (root.contains("mesh") && root["mesh"].is_array()) {
    const json& meshes = root["mesh"];
    for (size_t i = 0; i < meshes.size(); ++i) {
      const json& m = meshes[i];
      const std::string f = fmt::format("mesh[{}]", i);
      if (!m.is_object() || !m.contains("uid")) r.fail(f + ".uid", "missing");
      const json& xyz = r.array(m, "xyz", f);
      const json& faces = r.array(m, "faces", f);
      if (xyz.size() % 3 != 0) r.fail(f + ".xyz", "length is not a multiple of 3");
      if (faces.size() % 3 != 0) r.fail(f + ".faces", "length is not a multiple of 3");
      Mesh mesh;
      mesh.id = fmt::format("mesh{}", i);
      for (size_t k = 0; k < xyz.size(); k += 3)
        mesh.positions.emplace_back(
            static_cast<float>(r.number(xyz[k], fmt::format("{}.xyz[{}]", f, k))),
            static_cast<float>(r.number(xyz[k + 1], fmt::format("{}.xyz[{}]", f, k + 1))),
            static_cast<float>(r.number(xyz[k + 2], fmt::format("{}.xyz[{}]", f, k + 2))));
      for (size_t k = 0; k < faces.size(); k += 3) {
        Tri t;
        for (int c = 0; c < 3; ++c) {
          const double v = r.number(faces[k + c], fmt::format("{}.faces[{}]", f, k + c));
          if (!(v >= 0 && v < static_cast<double>(mesh.positions.size())) || v != std::floor(v))
            r.fail(fmt::format("{}.faces[{}]", f, k + c), "vertex index out of range");
          t[c] = static_cast<uint32_t>(v);
        }
        // skip degenerate triangles (3D-FRONT has some)
        const Vec3f a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        if ((b - a).cross(c - a).norm() > 1e-10f) mesh.triangles.push_back(t);
      }
      if (mesh.triangles.empty()) continue;
      Arch a;
      a.type = m.contains("type") && m["type"].is_string() ? m["type"].get<std::string>() : "";
      if (a.type == "Hole") continue;  // openings, not geometry
      a.nyu40 = archClass(a.type);
      const std::string mat = m.contains("material") && m["material"].is_string()
                                  ? m["material"].get<std::string>()
                                  : "";
      auto it = material_of.find(mat);
      a.material = it != material_of.end() ? it->second : defaultMaterial();
      a.mesh = static_cast<int>(scene.meshes.size());
      scene.meshes.push_back(std::move(mesh));
      arch[m["uid"].get<std::string>()] = a;
      ++report.meshes;
    }
  }

  // furniture entries
  struct Furn {
    std::string jid, category;
    Vec3 size = Vec3::Zero();  // y-up: width, height, depth
  };
  std::map<std::string, Furn> furniture;
  if (root.contains("furniture") && root["furniture"].is_array()) {
    const json& fs_ = root["furniture"];
    for (size_t i = 0; i < fs_.size(); ++i) {
      const json& f = fs_[i];
      if (!f.is_object() || !f.contains("uid") || !f["uid"].is_string()) continue;
      Furn fu;
      if (f.contains("jid") && f["jid"].is_string()) fu.jid = f["jid"].get<std::string>();
      if (f.contains("category") && f["category"].is_string())
        fu.category = f["category"].get<std::string>();
      const std::string fld = fmt::format("furniture[{}]", i);
      if (f.contains("bbox") && f["bbox"].is_array() && !f["bbox"].empty()) {
        const json& b = f["bbox"][0].is_array() ? f["bbox"][0] : f["bbox"];
        fu.size = r.vec3(b, fld + ".bbox");
      } else if (f.contains("size")) {
        // "size" lists width, depth, height (the shared house's bed: size 1.947 2.262 0.966,
        // bbox 1.956 0.966 2.268): reorder to the model frame's x, y (up), z
        const Vec3 s3 = r.vec3(f["size"], fld + ".size");
        fu.size = Vec3(s3.x(), s3.z(), s3.y());
      }
      furniture[f["uid"].get<std::string>()] = fu;
    }
  }

  // rooms and their children
  const json& rooms = root["scene"].contains("room") ? root["scene"]["room"] : json::array();
  if (!rooms.is_array()) r.fail("scene.room", "expected an array");
  int instance = 0;
  std::set<std::string> unmatched;
  for (size_t ri = 0; ri < rooms.size(); ++ri) {
    const json& room = rooms[ri];
    const std::string rf = fmt::format("scene.room[{}]", ri);
    Room out_room;
    out_room.id = fmt::format("room_{}", ri);
    out_room.type = roomType(room.value("type", std::string()));
    Eigen::AlignedBox2d floor_box;
    double floor_z = 0, ceiling_z = 0;
    const int room_index = static_cast<int>(scene.rooms.size());
    const json& children = room.contains("children") ? room["children"] : json::array();
    for (size_t ci = 0; ci < children.size(); ++ci) {
      const json& c = children[ci];
      const std::string cf = fmt::format("{}.children[{}]", rf, ci);
      if (!c.is_object() || !c.contains("ref") || !c["ref"].is_string()) continue;
      const std::string ref = c["ref"].get<std::string>();
      Vec3 pos = c.contains("pos") ? r.vec3(c["pos"], cf + ".pos") : Vec3::Zero();
      Vec3 scale = c.contains("scale") ? r.vec3(c["scale"], cf + ".scale") : Vec3::Ones();
      Quat q = Quat::Identity();
      if (c.contains("rot") && c["rot"].is_array() && c["rot"].size() == 4) {
        q = Quat(r.number(c["rot"][3], cf + ".rot"), r.number(c["rot"][0], cf + ".rot"),
                 r.number(c["rot"][1], cf + ".rot"), r.number(c["rot"][2], cf + ".rot"));
        if (!(q.norm() > 1e-9)) r.fail(cf + ".rot", "zero quaternion");
        q.normalize();
      }
      // a negative scale mirrors a model (3D-FRONT uses it for left/right variants); boxes are
      // symmetric, and imported models keep their handedness (mirrors are rare), so the
      // magnitude is taken
      scale = scale.cwiseAbs();
      if (!(scale.minCoeff() > 0)) r.fail(cf + ".scale", "must not be 0");
      Mat4 T = Mat4::Identity();
      T.block<3, 3>(0, 0) = q.toRotationMatrix() * scale.asDiagonal();
      T.block<3, 1>(0, 3) = pos;
      auto a = arch.find(ref);
      if (a != arch.end()) {
        Object o =
            Object::make(fmt::format("{}_{}", a->second.type.empty() ? "mesh" : a->second.type, ci),
                         a->second.mesh, a->second.material, C * T, a->second.nyu40, ++instance);
        o.kind = a->second.type;
        o.room = room_index;
        scene.objects.push_back(o);
        if (a->second.type == "Floor" || a->second.type == "Ceiling") {
          for (const Vec3f& p : scene.meshes[a->second.mesh].positions) {
            const Vec3 w = (C * T * p.cast<double>().homogeneous()).head<3>();
            if (a->second.type == "Floor") {
              floor_box.extend(w.head<2>());
              floor_z = w.z();
            } else {
              ceiling_z = std::max(ceiling_z, w.z());
            }
          }
        }
        continue;
      }
      auto f = furniture.find(ref);
      if (f == furniture.end()) {
        ++report.missing_refs;
        continue;
      }
      ++report.furniture;
      const Furn& fu = f->second;
      int nyu40 = 40;
      const std::string category = fu.category.empty() ? std::string("unknown") : fu.category;
      if (auto id = labels.lookup(category)) {
        nyu40 = *id;
      } else if (auto kw = furnitureClass(category)) {
        nyu40 = *kw;
      } else if (unmatched.insert(category).second) {
        report.unmatched_categories.push_back(category);
      }
      const std::string name = fmt::format("{}_{}", category, ci);
      const fs::path model = fs::path(opt.models_dir) / fu.jid / "raw_model.obj";
      std::error_code ec;
      if (!opt.models_dir.empty() && !fu.jid.empty() && fs::exists(model, ec)) {
        Mesh m = loadMeshFile(model.string(), 1.0, 'z', "", path, cf + ".ref");
        m.id = fmt::format("model_{}_{}", fu.jid, ci);
        scene.meshes.push_back(std::move(m));
        Object o = Object::make(name, static_cast<int>(scene.meshes.size()) - 1, defaultMaterial(),
                                C * T, nyu40, ++instance);
        o.kind = category;
        o.room = room_index;
        scene.objects.push_back(o);
        continue;
      }
      if (!(fu.size.minCoeff() > 0)) {
        ++report.missing_refs;
        continue;
      }
      ++report.placeholders;
      if (scene.findMesh("box") < 0) {
        Mesh box = makePrimitive("box", {}, path, "placeholder");
        box.id = "box";
        scene.meshes.push_back(box);
      }
      // the 3D-FUTURE model frame: origin at the bottom centre, y up
      Mat4 M = Mat4::Identity();
      M.block<3, 3>(0, 0) = fu.size.asDiagonal();
      M(1, 3) = fu.size.y() / 2;
      Object o = Object::make(name, scene.findMesh("box"), defaultMaterial(), C * T * M, nyu40,
                              ++instance);
      o.kind = category;
      o.part = "placeholder_box";
      o.room = room_index;
      scene.objects.push_back(o);
    }
    if (!floor_box.isEmpty() && floor_box.volume() > 0.25) {
      out_room.outline = {{floor_box.min().x(), floor_box.min().y()},
                          {floor_box.max().x(), floor_box.min().y()},
                          {floor_box.max().x(), floor_box.max().y()},
                          {floor_box.min().x(), floor_box.max().y()}};
      out_room.floor_z = floor_z;
      out_room.ceiling_z = ceiling_z > floor_z + 1.5 ? ceiling_z : floor_z + 2.8;
      scene.rooms.push_back(out_room);
      ++report.rooms;
      if (opt.add_lights) {
        Light l;
        l.name = out_room.id + "_light";
        l.type = LightType::Point;
        const Eigen::Vector2d c = floor_box.center();
        l.position = Vec3(c.x(), c.y(), out_room.ceiling_z - 0.4);
        l.intensity = static_cast<float>(std::clamp(0.4 * floor_box.volume(), 3.0, 20.0));
        l.temperature_k = 3500.f;
        scene.lights.push_back(l);
      }
    } else {
      // no floor: its objects keep no room
      for (Object& o : scene.objects)
        if (o.room == room_index) o.room = -1;
    }
  }
  if (scene.objects.empty()) r.fail("scene.room", "no geometry: nothing to import");
  scene.validate(path);
  if (out) *out = std::move(report);
  return scene;
}

}  // namespace inet
