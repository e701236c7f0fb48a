#include "procedural/apartment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <queue>
#include <set>

#include <fmt/format.h>

#include "assets/catalog_library.h"
#include "assets/polygon_mesh.h"
#include "assets/svg_path.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/text.h"
#include "procedural/furniture.h"
#include "procedural/procedural_textures.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDoorZone = 1.0;      ///< floor kept clear in front of a doorway (m)
constexpr double kMaxOccupied = 0.35;  ///< share of a room's floor furniture may cover
constexpr double kRobotRadius = 0.25;  ///< clearance kept for cameras (reachableRooms)
constexpr double kGridCell = 0.1;
constexpr double kInWallOverlap = 0.005;  ///< doors and windows reach this far into the wall

bool known(const std::string& category) {
  static const std::set<std::string> names(furnitureCategories().begin(),
                                           furnitureCategories().end());
  return names.count(category) > 0;
}

/// 2D box helpers (room coordinates: world x, y).
using Box2 = Eigen::AlignedBox2d;
bool overlaps(const Box2& a, const Box2& b, double margin = 0.0) {
  return a.min().x() < b.max().x() - margin && b.min().x() < a.max().x() - margin &&
         a.min().y() < b.max().y() - margin && b.min().y() < a.max().y() - margin;
}

/// A wall of a room interior: 0 = x-min (west), 1 = x-max (east), 2 = y-min (south),
/// 3 = y-max (north). Yaw that turns a model's back (+y) towards that wall.
double wallYaw(int side) {
  switch (side) {
    case 0:
      return kPi / 2;  // +y -> -x
    case 1:
      return -kPi / 2;  // +y -> +x
    case 2:
      return kPi;  // +y -> -y
    default:
      return 0.0;
  }
}

Mat4 placement(const Vec3& position, double yaw) {
  Mat4 T = Mat4::Identity();
  T.block<3, 3>(0, 0) = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  T.block<3, 1>(0, 3) = position;
  return T;
}

/// World-space axis-aligned box of a model-frame box under a yaw that is a multiple of 90 deg.
Eigen::AlignedBox3d transformBox(const Eigen::AlignedBox3d& b, const Mat4& T) {
  Eigen::AlignedBox3d out;
  for (int k = 0; k < 8; ++k) {
    Vec3 c = b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
    out.extend((T * c.homogeneous()).head<3>());
  }
  return out;
}

struct RoomState {
  int index = -1;
  Box2 interior;
  std::vector<Box2> door_zones;
  std::vector<Box2> window_zones;    ///< strips in front of windows (tall pieces stay out)
  std::vector<double> window_clear;  ///< per zone: floor pieces taller than this stay out
  std::vector<Box2> floor_boxes;     ///< footprints of floor pieces (not rugs)
  double occupied = 0;
  std::vector<int> supports;  ///< piece indices with support surfaces
};

class Builder {
 public:
  Builder(const ApartmentOptions& opt, const fs::path& layout_dir, const fs::path& texture_dir)
      : opt_(opt),
        rng_(opt.seed, RngStream::Layout, 1, 0, 0),
        layout_dir_(fs::absolute(layout_dir)),
        texture_dir_(fs::absolute(texture_dir)) {
    style_ = opt.style;
    if (opt.furniture != FurnitureSource::Parametric) library_ = catalogLibrary(opt.catalog_dir);
    if (opt.random_style) {  // its own stream, so the rest of the apartment draws the same numbers
      CounterRng style_rng(opt.seed, RngStream::Layout, 2, 0, 0);
      const auto& all = decorStyles();
      style_ = all[std::min(all.size() - 1,
                            static_cast<size_t>(style_rng.uniformDouble() * all.size()))];
    }
  }

  Apartment build() {
    CounterRng plan_rng(opt_.seed, RngStream::Layout, 0, 0, 0);
    const int k = opt_.rooms > 0 ? opt_.rooms : sampleRoomCount(plan_rng);
    apt_.plan = makeFloorPlan(roomProgram(k, plan_rng), plan_rng);
    apt_.scene.name = fmt::format("apartment_{}", opt_.seed);
    const FloorPlan& plan = apt_.plan;
    for (size_t i = 0; i < plan.rooms.size(); ++i) {
      Room r;
      r.id = fmt::format("{}_{}", plan.rooms[i].type, i);
      r.type = plan.rooms[i].type;
      const Box2& b = plan.rooms[i].box;
      const double h = plan.wall_thickness / 2;
      r.outline = {{b.min().x() + h, b.min().y() + h},
                   {b.max().x() - h, b.min().y() + h},
                   {b.max().x() - h, b.max().y() - h},
                   {b.min().x() + h, b.max().y() - h}};
      r.floor_z = 0.0;
      r.ceiling_z = plan.ceiling;
      apt_.scene.rooms.push_back(r);
    }
    if (library_) catalogOpenings();
    shell();
    for (size_t i = 0; i < plan.rooms.size(); ++i) furnish(static_cast<int>(i));
    if (opt_.daylight) daylight();
    apt_.scene.validate(apt_.scene.name);
    return std::move(apt_);
  }

 private:
  // ---- materials and meshes ----

  int material(const MaterialSpec& spec) {
    auto it = materials_.find(spec.name);
    if (it != materials_.end()) return it->second;
    Material m;
    m.id = spec.name;
    m.type = spec.type;
    m.albedo = spec.albedo.cwiseMax(0.f).cwiseMin(1.f);
    m.roughness = spec.roughness;
    m.metal = spec.metal;
    m.ior = spec.ior;
    m.transmittance = spec.transmittance;
    m.emission = spec.emission;
    if (spec.type == MaterialType::Dielectric || spec.type == MaterialType::ThinDielectric)
      m.albedo = Vec3f::Constant(0.8f);  // not used by glass; keep the default
    if (spec.texture != TextureKind::None && spec.type != MaterialType::Dielectric &&
        spec.type != MaterialType::ThinDielectric && !m.isEmissive()) {
      // Textures depend on the material name and the size only, so apartments written to one
      // folder share them: a file already there (writers are atomic) is reused as is.
      fs::create_directories(texture_dir_);
      std::array<std::string, 3> files;
      if (fs::exists(texture_dir_ / (spec.name + "_albedo.png"))) {
        const char* suffix[3] = {"_albedo.png", "_roughness.png", "_normal.png"};
        for (int k = 0; k < 3; ++k) {
          const fs::path f = texture_dir_ / (spec.name + suffix[k]);
          files[k] = fs::exists(f) ? f.string() : std::string();
        }
      } else {
        const TextureSet set =
            makeTexture(spec.texture, m.albedo, stableHash(spec.name), opt_.texture_size);
        files = writeTexture(set, texture_dir_, spec.name);
      }
      auto ref = [&](const std::string& path) {
        TextureRef r;
        r.path = path;
        r.file = fs::proximate(path, layout_dir_).generic_string();
        return r;
      };
      // the image carries the colour (its mean is spec.albedo); a translucent material keeps its
      // plain albedo, since albedo + transmittance must stay <= 1
      if (!files[0].empty() && m.type != MaterialType::Translucent) {
        m.albedo = Vec3f::Ones();
        m.albedo_texture = ref(files[0]);
      }
      const bool rough = m.type == MaterialType::Conductor || m.type == MaterialType::Plastic;
      if (rough && !files[1].empty()) {
        m.roughness_texture = ref(files[1]);
        m.roughness = 1.f;  // the image holds the roughness
      }
      if (!files[2].empty()) m.normal_texture = ref(files[2]);
      tile_[spec.name] = spec.texture_scale_m;
    }
    apt_.scene.materials.push_back(m);
    return materials_[spec.name] = static_cast<int>(apt_.scene.materials.size()) - 1;
  }

  /// A primitive with `scale` baked into its vertices (and texture coordinates in units of
  /// `tile` metres when tile > 0), shared by every part of that shape. Spheres stay analytic:
  /// returns -1 for them (the caller keeps the scale in the transform).
  int mesh(const std::string& primitive, const Vec3& scale, double tile) {
    if (primitive == "sphere") return -1;
    const std::string key = fmt::format("{}_{:.4f}x{:.4f}x{:.4f}_t{:.3f}", primitive, scale.x(),
                                        scale.y(), scale.z(), tile);
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
    Mesh m = makePrimitive(primitive, {}, "procedural", "mesh");
    const Vec3f s = scale.cast<float>();
    for (Vec3f& p : m.positions) p = p.cwiseProduct(s);
    for (Vec3f& n : m.normals) n = n.cwiseQuotient(s).normalized();
    if (tile > 0 && !m.uvs.empty()) {
      const float t = static_cast<float>(tile);
      if (primitive == "cylinder") {  // side: around x height; caps: planar
        const float around = static_cast<float>(kPi * 0.5 * (scale.x() + scale.y()));
        for (size_t i = 0; i < m.uvs.size(); ++i) {
          if (std::fabs(m.normals[i].z()) > 0.5f)
            m.uvs[i] = Vec2f(m.positions[i].x(), m.positions[i].y()) / t;
          else
            m.uvs[i] = Vec2f(m.uvs[i].x() * around, m.uvs[i].y() * s.z()) / t;
        }
      } else if (primitive == "fold") {  // u: arc length along the cloth (bottom, top per column)
        float along = 0.f;
        for (size_t i = 0; i + 1 < m.positions.size(); i += 2) {
          if (i > 0) along += (m.positions[i] - m.positions[i - 2]).norm();
          m.uvs[i] = Vec2f(along, 0.f) / t;
          m.uvs[i + 1] = Vec2f(along, s.z()) / t;
        }
      } else {  // box and quad: quads of 4 vertices, uv (0,0) (1,0) (1,1) (0,1)
        for (size_t q = 0; q + 3 < m.positions.size(); q += 4) {
          const float a = (m.positions[q + 1] - m.positions[q]).norm() / t;
          const float b = (m.positions[q + 3] - m.positions[q]).norm() / t;
          for (size_t k = 0; k < 4; ++k) m.uvs[q + k] = m.uvs[q + k].cwiseProduct(Vec2f(a, b));
        }
      }
    } else {
      m.uvs.clear();
    }
    m.id = key;
    m.source = MeshSource();  // inline: the baked scale is part of the geometry
    apt_.scene.meshes.push_back(std::move(m));
    return meshes_[key] = static_cast<int>(apt_.scene.meshes.size()) - 1;
  }

  int sphereMesh() {
    if (sphere_ < 0) {
      Mesh m = makePrimitive("sphere", {}, "procedural", "mesh");
      m.id = "sphere";
      apt_.scene.meshes.push_back(m);
      sphere_ = static_cast<int>(apt_.scene.meshes.size()) - 1;
    }
    return sphere_;
  }

  // ---- pieces ----

  /// Adds every part of `model` placed by T_world_model; returns the piece index.
  int add(const FurnitureModel& model, const Mat4& T_world_model, int room, bool on_floor) {
    const std::string name = fmt::format("{}_{}", model.category, ++count_[model.category]);
    const int instance = ++instances_;
    PhysicsProps phys;
    phys.mass_kg = static_cast<float>(model.mass_kg);
    phys.friction = static_cast<float>(model.friction);
    phys.movable = model.movable;
    if (model.catalog) addCatalogParts(*model.catalog, name, instance, room, phys, T_world_model);
    for (const FurniturePart& part : model.parts) {
      const MaterialSpec& spec = model.materials[part.material];
      const int mat = material(spec);
      auto tile = tile_.find(spec.name);
      const Mat4 T = T_world_model * part.T_model_part;
      Object o;
      o.name = name;
      o.kind = model.category;
      o.part = part.name;
      o.room = room;
      o.physics = phys;
      o.material = mat;
      o.nyu40 = part.nyu40 > 0 ? part.nyu40 : model.nyu40;
      o.instance = instance;
      const Mat3 L = T.block<3, 3>(0, 0);
      const Vec3 scale(L.col(0).norm(), L.col(1).norm(), L.col(2).norm());
      const int mi = mesh(part.primitive, scale, tile == tile_.end() ? 0.0 : tile->second);
      if (mi < 0) {
        o.mesh = sphereMesh();
        o.T_world_object = T;
      } else {
        o.mesh = mi;
        o.T_world_object = T;
        o.T_world_object.block<3, 3>(0, 0) = L * scale.cwiseInverse().asDiagonal();
      }
      apt_.scene.objects.push_back(o);
    }
    if (model.light) {
      const LightSpec& ls = *model.light;
      Light l;
      l.name = name + "_light";
      l.type = ls.type;
      l.position = (T_world_model * ls.position.homogeneous()).head<3>();
      l.direction = (T_world_model.block<3, 3>(0, 0) * ls.direction).normalized();
      l.intensity = ls.intensity_w_sr;
      l.temperature_k = ls.temperature_k;
      l.cone_deg = ls.cone_deg;
      l.falloff_deg = std::min(l.falloff_deg, l.cone_deg);
      l.max_distance = ls.max_distance;
      l.object = name;
      apt_.scene.lights.push_back(l);
    }
    PlacedPiece p;
    p.name = name;
    p.category = model.category;
    if (model.catalog) p.catalog_piece = model.catalog->id;
    p.room = room;
    p.instance = instance;
    for (const auto& h : model.hulls) p.hulls.push_back(transformBox(h, T_world_model));
    p.on_floor = on_floor;
    p.flat = model.category == "rug";
    apt_.pieces.push_back(p);
    return static_cast<int>(apt_.pieces.size()) - 1;
  }

  /// The objects and bulbs of catalog model `c` placed by T_world_model. Its meshes and
  /// materials enter the scene once per apartment (named by piece in layout.json).
  void addCatalogParts(const CatalogModel& c, const std::string& name, int instance, int room,
                       const PhysicsProps& phys, const Mat4& T_world_model) {
    for (const Object& part : c.parts.objects) {
      const Mesh& src_mesh = c.parts.meshes[size_t(part.mesh)];
      const std::string mesh_key = "catalog:" + src_mesh.id;
      auto mit = meshes_.find(mesh_key);
      if (mit == meshes_.end()) {
        apt_.scene.meshes.push_back(src_mesh);
        mit = meshes_.emplace(mesh_key, int(apt_.scene.meshes.size()) - 1).first;
      }
      const Material& src_mat = c.parts.materials[size_t(part.material)];
      const std::string mat_key = "catalog:" + src_mat.id;
      auto tit = materials_.find(mat_key);
      if (tit == materials_.end()) {
        apt_.scene.materials.push_back(src_mat);
        tit = materials_.emplace(mat_key, int(apt_.scene.materials.size()) - 1).first;
      }
      Object o = Object::make(name, mit->second, tit->second, T_world_model, part.nyu40, instance);
      o.kind = part.kind;
      o.part = part.part;
      o.room = room;
      o.physics = phys;
      apt_.scene.objects.push_back(std::move(o));
    }
    for (size_t i = 0; i < c.parts.lights.size(); ++i) {
      Light l = c.parts.lights[i];
      l.name =
          c.parts.lights.size() == 1 ? name + "_light" : fmt::format("{}_light_{}", name, i + 1);
      l.position = (T_world_model * l.position.homogeneous()).head<3>();
      l.radius *= static_cast<float>(std::cbrt(std::abs(T_world_model.block<3, 3>(0, 0).determinant())));
      l.object = name;
      apt_.scene.lights.push_back(l);
    }
  }

  /// Removes the last piece (its objects and light), restoring the counters.
  void undo(size_t objects_before, size_t lights_before) {
    apt_.scene.objects.resize(objects_before);
    apt_.scene.lights.resize(lights_before);
    --count_[apt_.pieces.back().category];
    --instances_;
    apt_.pieces.pop_back();
  }

  // ---- the shell: walls with openings, floors, ceilings, skirting, front door, windows ----

  MaterialSpec plain(const std::string& name, Vec3f albedo, TextureKind tex, float tile,
                     MaterialType type = MaterialType::Lambertian, float roughness = 0.6f) {
    MaterialSpec s;
    s.name = name;
    s.type = type;
    s.albedo = albedo;
    s.texture = tex;
    s.texture_scale_m = tile;
    s.roughness = roughness;
    return s;
  }

  void box(const std::string& name, const std::string& kind, int nyu40, int room,
           const MaterialSpec& spec, const Vec3& lo, const Vec3& hi) {
    if ((hi - lo).minCoeff() <= 1e-4) return;
    FurnitureModel m;
    m.category = kind;
    m.nyu40 = nyu40;
    m.materials = {spec};
    FurniturePart part;
    part.name = name;
    part.primitive = "box";
    part.T_model_part = Mat4::Identity();
    part.T_model_part.diagonal().head<3>() = hi - lo;
    part.T_model_part.block<3, 1>(0, 3) = 0.5 * (lo + hi);
    m.parts = {part};
    m.hulls = {Eigen::AlignedBox3d(lo, hi)};
    m.mass_kg = 45;
    m.friction = 0.2;
    m.movable = false;
    add(m, Mat4::Identity(), room, false);
  }

  void shell() {
    const FloorPlan& plan = apt_.plan;
    const double t = plan.wall_thickness, H = plan.ceiling;
    // wall paint: lightness range and warmth (blue share) by style; three draws in every style
    double lo = 0.55, hi = 0.8, blue_lo = 0.85, blue_hi = 0.98;
    switch (style_) {
      case DecorStyle::Scandinavian: lo = 0.75, hi = 0.85, blue_lo = 0.95, blue_hi = 1.0; break;
      case DecorStyle::Modern: lo = 0.45, hi = 0.75, blue_lo = 0.97, blue_hi = 1.03; break;
      case DecorStyle::Classic: lo = 0.55, hi = 0.72, blue_lo = 0.72, blue_hi = 0.85; break;
      case DecorStyle::Industrial: lo = 0.35, hi = 0.5, blue_lo = 0.95, blue_hi = 1.0; break;
      case DecorStyle::Any: break;
    }
    const float paint = static_cast<float>(rng_.uniformDouble(lo, hi));
    const MaterialSpec wall =
        plain("wall_paint",
              Vec3f(paint, paint * static_cast<float>(rng_.uniformDouble(0.95, 1.0)),
                    paint * static_cast<float>(rng_.uniformDouble(blue_lo, blue_hi))),
              TextureKind::Plaster, 1.5f);
    const MaterialSpec ceiling =
        plain("ceiling_white", Vec3f(0.8f, 0.8f, 0.8f), TextureKind::None, 1.f);
    const MaterialSpec skirting = plain("skirting_white", Vec3f(0.75f, 0.75f, 0.72f),
                                        TextureKind::None, 1.f, MaterialType::Plastic, 0.4f);
    // walls: the union of room sides per line, cut at doors and windows
    struct Line {
      bool vertical;
      double at;
      std::vector<std::pair<double, double>> spans;
    };
    std::vector<Line> lines;
    auto addSpan = [&](bool vertical, double at, double lo, double hi) {
      for (Line& l : lines)
        if (l.vertical == vertical && std::fabs(l.at - at) < 1e-9) {
          l.spans.push_back({lo, hi});
          return;
        }
      lines.push_back({vertical, at, {{lo, hi}}});
    };
    for (const PlanRoom& r : plan.rooms) {
      addSpan(true, r.box.min().x(), r.box.min().y(), r.box.max().y());
      addSpan(true, r.box.max().x(), r.box.min().y(), r.box.max().y());
      addSpan(false, r.box.min().y(), r.box.min().x(), r.box.max().x());
      addSpan(false, r.box.max().y(), r.box.min().x(), r.box.max().x());
    }
    for (Line& l : lines) {
      std::sort(l.spans.begin(), l.spans.end());
      std::vector<std::pair<double, double>> merged;
      for (auto s : l.spans) {
        if (!merged.empty() && s.first <= merged.back().second + 1e-9)
          merged.back().second = std::max(merged.back().second, s.second);
        else
          merged.push_back(s);
      }
      for (auto [lo, hi] : merged) {
        // openings on this stretch: (from, to, bottom, top) and a catalog piece's cut-out
        // shape when it is not the whole rectangle
        struct Hole {
          double from, to, bottom, top;
          const std::vector<Ring>* shape;
        };
        std::vector<Hole> holes;
        for (size_t i = 0; i < plan.doors.size(); ++i) {
          const PlanDoor& d = plan.doors[i];
          if (d.vertical == l.vertical && std::fabs(d.line - l.at) < 1e-9 && d.from >= lo &&
              d.to <= hi)
            holes.push_back({d.from, d.to, 0.0, d.height, cutOut(door_openings_, i)});
        }
        for (size_t i = 0; i < plan.windows.size(); ++i) {
          const PlanWindow& w = plan.windows[i];
          if (w.vertical == l.vertical && std::fabs(w.line - l.at) < 1e-9 && w.from >= lo &&
              w.to <= hi)
            holes.push_back({w.from, w.to, w.sill, w.top, cutOut(window_openings_, i)});
        }
        std::sort(holes.begin(), holes.end(),
                  [](const Hole& a, const Hole& b) { return a.from < b.from; });
        auto piece = [&](double a, double b, double z0, double z1) {
          const Vec3 lo3 = l.vertical ? Vec3(l.at - t / 2, a, z0) : Vec3(a, l.at - t / 2, z0);
          const Vec3 hi3 = l.vertical ? Vec3(l.at + t / 2, b, z1) : Vec3(b, l.at + t / 2, z1);
          box("wall", "wall", 1, -1, wall, lo3, hi3);
        };
        double cursor = lo - t / 2;  // close the corners
        for (const Hole& h : holes) {
          piece(cursor, h.from, 0, H);
          if (h.bottom > 0) piece(h.from, h.to, 0, h.bottom);
          piece(h.from, h.to, h.top, H);
          if (h.shape)
            shapedOpening(l.vertical, l.at, h.from, h.to, h.bottom, h.top, *h.shape, wall);
          cursor = h.to;
        }
        piece(cursor, hi + t / 2, 0, H);
      }
    }
    for (size_t i = 0; i < plan.rooms.size(); ++i) {
      const PlanRoom& r = plan.rooms[i];
      const std::string& type = r.type;
      const bool wet = type == "kitchen" || type == "bathroom" || type == "master_bathroom" ||
                       type == "laundry" || type == "balcony" || type == "storage";
      const bool carpet = type == "kids_room" || type == "elderly_room";
      MaterialSpec floor;
      if (wet) {
        const float g = static_cast<float>(rng_.uniformDouble(0.35, 0.75));
        floor = plain(fmt::format("floor_tiles_{}", i % 3), Vec3f(g, g * 0.97f, g * 0.92f),
                      TextureKind::Tiles, 1.2f, MaterialType::Plastic, 0.3f);
      } else if (carpet) {
        floor = plain("floor_carpet", Vec3f(0.35f, 0.3f, 0.28f), TextureKind::Carpet, 1.f);
      } else {
        floor = plain("floor_wood", woodFloorColour(), TextureKind::Wood, 1.5f,
                      MaterialType::Plastic, 0.45f);
      }
      const Vec3 lo(r.box.min().x(), r.box.min().y(), -0.05),
          hi(r.box.max().x(), r.box.max().y(), 0);
      box("floor", "floor", 2, static_cast<int>(i), floor, lo, hi);
      box("ceiling", "ceiling", 22, static_cast<int>(i), ceiling,
          Vec3(r.box.min().x(), r.box.min().y(), plan.ceiling),
          Vec3(r.box.max().x(), r.box.max().y(), plan.ceiling + 0.05));
      // skirting along the interior faces, cut at doors
      const Box2 in(r.box.min() + Eigen::Vector2d::Constant(t / 2),
                    r.box.max() - Eigen::Vector2d::Constant(t / 2));
      for (int side = 0; side < 4; ++side) {
        const bool vertical = side < 2;
        const double line = side == 0   ? r.box.min().x()
                            : side == 1 ? r.box.max().x()
                            : side == 2 ? r.box.min().y()
                                        : r.box.max().y();
        std::vector<std::pair<double, double>> spans = {
            {vertical ? in.min().y() : in.min().x(), vertical ? in.max().y() : in.max().x()}};
        for (const PlanDoor& d : plan.doors) {
          if (d.vertical != vertical || std::fabs(d.line - line) > 1e-9) continue;
          std::vector<std::pair<double, double>> next;
          for (auto [a, b] : spans) {
            if (d.to <= a || d.from >= b) {
              next.push_back({a, b});
              continue;
            }
            if (d.from > a) next.push_back({a, d.from});
            if (d.to < b) next.push_back({d.to, b});
          }
          spans = std::move(next);
        }
        const double inner = side == 0   ? in.min().x()
                             : side == 1 ? in.max().x()
                             : side == 2 ? in.min().y()
                                         : in.max().y();
        const double depth = (side % 2 == 0) ? 0.012 : -0.012;
        for (auto [a, b] : spans) {
          if (b - a < 0.05) continue;
          const double c0 = std::min(inner, inner + depth), c1 = std::max(inner, inner + depth);
          const Vec3 lo3 = vertical ? Vec3(c0, a, 0) : Vec3(a, c0, 0);
          const Vec3 hi3 = vertical ? Vec3(c1, b, 0.08) : Vec3(b, c1, 0.08);
          box("skirting", "skirting", 1, static_cast<int>(i), skirting, lo3, hi3);
        }
      }
    }
    // front door (closed) and windows, reaching 5 mm into the wall round their openings: a gap
    // of even 1 cm (or a crack between coincident faces) lets daylight leak in and shows the
    // void outside as unlabelled pixels
    for (size_t i = 0; i < plan.doors.size(); ++i) {
      const PlanDoor& d = plan.doors[i];
      if (d.b >= 0 || !known("door")) continue;
      if (auto it = door_openings_.find(i); it != door_openings_.end()) {
        inWallCatalog(it->second, "door", d.vertical, d.line, 0.5 * (d.from + d.to), 0.0,
                      d.to - d.from + 2 * kInWallOverlap, d.height + kInWallOverlap, d.a);
        continue;
      }
      FurnitureSizeHint hint;
      hint.width = d.to - d.from + 2 * kInWallOverlap;
      hint.height = d.height + kInWallOverlap;
      FurnitureModel m = make("door", hint);
      inWall(m, d.vertical, d.line, 0.5 * (d.from + d.to), 0.0, d.a);
    }
    for (size_t i = 0; i < plan.windows.size(); ++i) {
      const PlanWindow& w = plan.windows[i];
      if (!known("window")) continue;
      if (auto it = window_openings_.find(i); it != window_openings_.end()) {
        const double below = w.sill > 0 ? kInWallOverlap : 0.0;
        inWallCatalog(it->second, "window", w.vertical, w.line, 0.5 * (w.from + w.to),
                      w.sill - below, w.to - w.from + 2 * kInWallOverlap,
                      w.top - w.sill + kInWallOverlap + below, w.room);
        continue;
      }
      FurnitureSizeHint hint;
      hint.width = w.to - w.from + 2 * kInWallOverlap;
      hint.height = w.top - w.sill + 2 * kInWallOverlap;
      FurnitureModel m = make("window", hint);
      inWall(m, w.vertical, w.line, 0.5 * (w.from + w.to), w.sill - kInWallOverlap, w.room);
    }
  }

  /// Places an InWall model centred in a wall opening, its front towards room `room`.
  void inWall(const FurnitureModel& m, bool vertical, double line, double centre, double z,
              int room) {
    const Box2& rb = apt_.plan.rooms[room].box;
    // which side of the line the room is on decides the yaw (front = -y faces the room)
    int side;
    if (vertical)
      side = std::fabs(line - rb.min().x()) < 1e-9 ? 0 : 1;
    else
      side = std::fabs(line - rb.min().y()) < 1e-9 ? 2 : 3;
    const Vec3 pos = vertical ? Vec3(line, centre, z) : Vec3(centre, line, z);
    const int piece = add(m, placement(pos, wallYaw(side)), room, false);
    apt_.pieces[piece].rests_on = "wall";
  }

  // ---- catalog doors and windows ----

  /// A Sweet Home 3D door or window chosen for a plan opening: its model and catalog entry,
  /// and its cut-out shape (unit square, y down) when that is not the whole rectangle.
  struct CatalogOpening {
    std::shared_ptr<const CatalogModel> model;
    const CatalogPiece* piece = nullptr;
    std::vector<Ring> shape;  ///< empty: the rectangle
  };

  static const std::vector<Ring>* cutOut(const std::map<size_t, CatalogOpening>& openings,
                                         size_t i) {
    auto it = openings.find(i);
    return it == openings.end() || it->second.shape.empty() ? nullptr : &it->second.shape;
  }

  /// Chooses catalog windows for the plan's windows and a catalog front door (all of them
  /// with FurnitureSource::Catalog, each with even odds with Mixed) and fits the openings to
  /// them: the width stays the plan's, the height becomes the model's within -15 % .. +20 %
  /// of its own, under the same top for a window (the sill moves; a French window reaches
  /// down to the floor) and from the floor for a door. Interior doorways stay open: a closed
  /// door would block the camera paths through them.
  void catalogOpenings() {
    FloorPlan& plan = apt_.plan;
    for (size_t i = 0; i < plan.windows.size(); ++i) {
      PlanWindow& w = plan.windows[i];
      double h = w.top - w.sill;
      auto o = catalogOpening("window", w.to - w.from, h, w.top);
      if (!o) continue;
      w.sill = w.top - h < 0.03 ? 0.0 : w.top - h;
      window_openings_[i] = std::move(*o);
    }
    for (size_t i = 0; i < plan.doors.size(); ++i) {
      PlanDoor& d = plan.doors[i];
      if (d.b >= 0) continue;
      double h = d.height;
      auto o = catalogOpening("door", d.to - d.from, h, plan.ceiling - 0.3);
      if (!o) continue;
      d.height = h;
      door_openings_[i] = std::move(*o);
    }
  }

  /// A catalog door or window of our `category` for an opening `width` wide: among the
  /// pieces with door-or-window data whose own width is within 1/1.4 .. 1/0.75 of it and whose
  /// height, moved towards `height` by at most -15 % / +20 %, stays under `max_height`.
  /// Sets `height` to the chosen piece's. Draws from its own stream.
  std::optional<CatalogOpening> catalogOpening(const std::string& category, double width,
                                               double& height, double max_height) {
    CounterRng pick(opt_.seed, RngStream::Layout, 5, static_cast<uint32_t>(++opening_draws_), 0);
    if (opt_.furniture == FurnitureSource::Mixed && pick.uniform() < 0.5f) return std::nullopt;
    std::vector<std::pair<const CatalogPiece*, double>> fits;
    for (const CatalogPiece* p : library_->byCategory(category)) {
      if (!p->door_or_window) continue;
      const double sw = width / (p->width_cm / 100), mh = p->height_cm / 100;
      const double h = std::clamp(height, 0.85 * mh, 1.2 * mh);
      if (sw < 0.75 || sw > 1.4 || h > max_height) continue;
      fits.push_back({p, h});
    }
    if (fits.empty()) return std::nullopt;
    const auto& [piece, h] =
        fits[std::min(fits.size() - 1, static_cast<size_t>(pick.uniformDouble() * fits.size()))];
    CatalogOpening o;
    o.piece = piece;
    o.model = library_->model(piece->id, library_->dir(), "--furniture catalog");
    const std::string& svg = piece->door_or_window->cut_out_shape;
    if (!svg.empty()) {
      for (const Outline2d& r :
           parseSvgPath(svg, 0.01, library_->dir(), piece->id + " cutOutShape"))
        o.shape.push_back(r);
      // the whole unit square is the plain rectangular hole
      if (o.shape.size() == 1 && std::abs(std::abs(outlineArea(o.shape[0])) - 1.0) < 1e-6)
        o.shape.clear();
    }
    height = h;
    return o;
  }

  /// Places catalog door or window `o` in its opening (`width` along the wall at `centre`,
  /// bottom `z`, `height` tall), scaled to it, its wall part (CatalogDoorOrWindow: thickness
  /// and distance from its back) scaled to the wall's thickness and centred in it, its front
  /// towards room `room`, as Sweet Home 3D fits a door or window to the wall it is dropped in.
  void inWallCatalog(const CatalogOpening& o, const std::string& category, bool vertical,
                     double line, double centre, double z, double width, double height, int room) {
    const CatalogModel& c = *o.model;
    const CatalogDoorOrWindow& dw = *o.piece->door_or_window;
    const double depth = c.size.y();
    const double thick = dw.wall_thickness_cm > 0 ? dw.wall_thickness_cm / 100 : depth;
    const double sy = std::clamp(apt_.plan.wall_thickness / thick, 0.25, 4.0);
    // the wall part's centre in the model frame (front -y, back +y)
    const double y_wall = depth / 2 - dw.wall_distance_cm / 100 - thick / 2;
    const Box2& rb = apt_.plan.rooms[room].box;
    const int side = vertical ? (std::fabs(line - rb.min().x()) < 1e-9 ? 0 : 1)
                              : (std::fabs(line - rb.min().y()) < 1e-9 ? 2 : 3);
    const double yaw = wallYaw(side);
    const Vec3 on_line = vertical ? Vec3(line, centre, z) : Vec3(centre, line, z);
    const Vec3 origin = on_line - Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Vec3(0, sy * y_wall, 0);
    Mat4 S = Mat4::Identity();
    S.diagonal().head<3>() = Vec3(width / c.size.x(), sy, height / c.size.z());
    const int piece = add(catalogOnly(category, o.model), placement(origin, yaw) * S, room, false);
    apt_.pieces[piece].rests_on = "wall";
  }

  /// The wall round a shaped cut-out: [a, b] x [z0, z1] of the wall on line `at` minus
  /// `shape` (unit square, y down, stretched over it), both faces and the reveals through the
  /// wall, in the wall's material.
  void shapedOpening(bool vertical, double at, double a, double b, double z0, double z1,
                     const std::vector<Ring>& shape, const MaterialSpec& spec) {
    using V2 = Eigen::Vector2d;
    const double t = apt_.plan.wall_thickness;
    const Ring outline = {V2(a, z0), V2(b, z0), V2(b, z1), V2(a, z1)};
    std::vector<Ring> holes;
    for (const Ring& r : shape) {
      Ring h;
      for (const V2& q : r) h.emplace_back(a + q.x() * (b - a), z1 - q.y() * (z1 - z0));
      holes.push_back(std::move(h));
    }
    const FaceWithHoles f = faceWithHoles(outline, holes, true, 0.0);
    const int mat = material(spec);
    auto tile_it = tile_.find(spec.name);
    const float tile = tile_it == tile_.end() ? 1.f : static_cast<float>(tile_it->second);
    // (u, v) of the face at `off` across the wall, in world space
    auto at3 = [&](const V2& p, double off) {
      return vertical ? Vec3(at + off, p.x(), p.y()) : Vec3(p.x(), at + off, p.y());
    };
    const Vec3 across = vertical ? Vec3::UnitX() : Vec3::UnitY();
    Mesh mesh;
    // a triangle facing `normal`; texture coordinates in metres along the wall and up
    auto tri = [&](const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& normal) {
      const Vec3 n = (q - p).cross(r - p);
      if (n.norm() < 1e-12) return;
      const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
      for (const Vec3* x : {&p, &q, &r}) {
        mesh.positions.push_back(x->cast<float>());
        const double u = vertical ? x->y() + x->x() - at : x->x() + x->y() - at;
        mesh.uvs.emplace_back(static_cast<float>(u) / tile, static_cast<float>(x->z()) / tile);
      }
      if (n.dot(normal) >= 0)
        mesh.triangles.emplace_back(base, base + 1, base + 2);
      else
        mesh.triangles.emplace_back(base, base + 2, base + 1);
    };
    for (const Triangle2& tr : f.triangles)
      for (double sgn : {-1.0, 1.0})
        tri(at3(tr[0], sgn * t / 2), at3(tr[1], sgn * t / 2), at3(tr[2], sgn * t / 2),
            sgn * across);
    for (const RevealEdge& r : f.reveals) {
      const Vec3 inward = at3(r.inward, 0) - at3(V2::Zero(), 0);
      const Vec3 p0 = at3(r.a, t / 2), p1 = at3(r.b, t / 2), q0 = at3(r.a, -t / 2),
                 q1 = at3(r.b, -t / 2);
      tri(p0, p1, q1, inward);
      tri(p0, q1, q0, inward);
    }
    if (mesh.triangles.empty()) return;
    const std::string name = fmt::format("wall_{}", ++count_["wall"]);
    mesh.id = name;
    apt_.scene.meshes.push_back(std::move(mesh));
    Object obj = Object::make(name, static_cast<int>(apt_.scene.meshes.size()) - 1, mat,
                              Mat4::Identity(), 1, ++instances_);
    obj.kind = "wall";
    obj.part = "wall";
    PhysicsProps phys;
    phys.mass_kg = 45;
    phys.friction = 0.2f;
    obj.physics = phys;
    apt_.scene.objects.push_back(std::move(obj));
    PlacedPiece p;
    p.name = name;
    p.category = "wall";
    p.instance = instances_;
    Eigen::AlignedBox3d hull(at3(V2(a, z0), -t / 2));
    hull.extend(at3(V2(b, z1), t / 2));
    p.hulls = {hull};
    apt_.pieces.push_back(p);
  }

  // ---- furnishing ----

  RoomState roomState(int i) {
    const FloorPlan& plan = apt_.plan;
    const double t = plan.wall_thickness / 2 + 0.015;  // + skirting
    RoomState s;
    s.index = i;
    const Box2& b = plan.rooms[i].box;
    s.interior =
        Box2(b.min() + Eigen::Vector2d::Constant(t), b.max() - Eigen::Vector2d::Constant(t));
    auto zone = [&](bool vertical, double line, double from, double to, double depth) {
      Box2 z;
      if (vertical) {
        const double dir = std::fabs(line - b.min().x()) < 1e-9 ? 1 : -1;
        z.extend(Eigen::Vector2d(line, from));
        z.extend(Eigen::Vector2d(line + dir * depth, to));
      } else {
        const double dir = std::fabs(line - b.min().y()) < 1e-9 ? 1 : -1;
        z.extend(Eigen::Vector2d(from, line));
        z.extend(Eigen::Vector2d(to, line + dir * depth));
      }
      return z;
    };
    for (const PlanDoor& d : plan.doors)
      if (d.a == i || d.b == i) {
        s.door_zones.push_back(zone(d.vertical, d.line, d.from - 0.15, d.to + 0.15, kDoorZone));
      }
    for (size_t k = 0; k < plan.windows.size(); ++k) {
      const PlanWindow& w = plan.windows[k];
      if (w.room != i) continue;
      s.window_zones.push_back(zone(w.vertical, w.line, w.from, w.to, 0.45));
      // below a catalog window's sill (French windows reach nearly to the floor)
      s.window_clear.push_back(window_openings_.count(k) ? std::min(0.85, w.sill - 0.02) : 0.85);
    }
    return s;
  }

  /// Footprint of a model of size (w, d) placed at `c` with a multiple-of-90 yaw.
  static Box2 footprint(const Eigen::Vector2d& c, double w, double d, double yaw) {
    const bool turned = std::fabs(std::sin(yaw)) > 0.5;
    const Eigen::Vector2d half =
        turned ? Eigen::Vector2d(d / 2, w / 2) : Eigen::Vector2d(w / 2, d / 2);
    return Box2(c - half, c + half);
  }

  bool floorFree(const RoomState& s, const Box2& fp, double height, bool flat) const {
    const double eps = 0.005;
    if (fp.min().x() < s.interior.min().x() - eps || fp.min().y() < s.interior.min().y() - eps ||
        fp.max().x() > s.interior.max().x() + eps || fp.max().y() > s.interior.max().y() + eps)
      return false;
    if (flat) return true;
    for (const Box2& z : s.door_zones)
      if (overlaps(fp, z)) return false;
    for (const Box2& o : s.floor_boxes)
      if (overlaps(fp, o, -0.02)) return false;  // 2 cm gap at least
    for (size_t k = 0; k < s.window_zones.size(); ++k)
      if (height > s.window_clear[k] && overlaps(fp, s.window_zones[k])) return false;
    return true;
  }

  /// Keeps the piece when every room stays reachable from the front door through free floor
  /// (the very check the tests make, reachableRooms); else undoes it.
  bool commitFloor(RoomState& s, const Box2& fp, bool flat, size_t objects_before,
                   size_t lights_before) {
    if (!flat) {
      const std::vector<bool> reached = reachableRooms(apt_, kGridCell, kRobotRadius);
      if (std::find(reached.begin(), reached.end(), false) != reached.end()) {
        undo(objects_before, lights_before);
        return false;
      }
      s.floor_boxes.push_back(fp);
      s.occupied += fp.volume();
    }
    return true;
  }

  /// Parquet colour by style: light ash, grey oak, dark walnut, smoked oak; oak otherwise.
  Vec3f woodFloorColour() const {
    switch (style_) {
      case DecorStyle::Scandinavian: return {0.62f, 0.50f, 0.36f};
      case DecorStyle::Modern: return {0.36f, 0.32f, 0.28f};
      case DecorStyle::Classic: return {0.22f, 0.12f, 0.06f};
      case DecorStyle::Industrial: return {0.16f, 0.12f, 0.09f};
      case DecorStyle::Any: break;
    }
    return {0.38f, 0.24f, 0.13f};
  }

  /// A model of `category` in the apartment's decoration style: parametric, or a catalog
  /// model that fits (ApartmentOptions::furniture), with the parametric one it stands in for.
  struct Drawn {
    FurnitureModel model;
    std::optional<FurnitureModel> parametric;  ///< set when `model` is a catalog model
  };
  Drawn draw(const std::string& category, FurnitureSizeHint hint) {
    hint.style = style_;
    Drawn d{makeFurnitureSized(category, hint, rng_), std::nullopt};
    // pieces cut to an opening (doors, windows, curtains: the only hinted ones) stay parametric
    const bool hinted = hint.width || hint.depth || hint.height;
    if (!library_ || hinted) return d;
    // the catalog's own stream: which model is chosen draws nothing from rng_
    CounterRng pick(opt_.seed, RngStream::Layout, 3, static_cast<uint32_t>(++catalog_draws_), 0);
    if (opt_.furniture == FurnitureSource::Mixed && pick.uniform() < 0.5f) return d;
    const auto& fits = catalogFits(*library_, category);
    if (fits.empty()) return d;
    // a category the catalogs hold one model of (the living-room rug) is not that model in
    // every home: our parametric one, itself varied, keeps half of them
    if (fits.size() == 1 && pick.uniform() < 0.5f) return d;
    size_t k = std::min(fits.size() - 1, static_cast<size_t>(pick.uniformDouble() * fits.size()));
    if (style_ != DecorStyle::Any) {  // drawn in proportion to how the style likes them
      std::vector<double> weight(fits.size());
      for (size_t i = 0; i < fits.size(); ++i) weight[i] = catalogStyleWeight(*fits[i], style_);
      double u = pick.uniformDouble() * std::accumulate(weight.begin(), weight.end(), 0.0);
      for (k = 0; k + 1 < fits.size() && u >= weight[k]; ++k) u -= weight[k];
    }
    const auto& chosen = fits[k];
    d.parametric = std::move(d.model);
    d.model = fromCatalog(*d.parametric, chosen);
    return d;
  }
  FurnitureModel make(const std::string& category, FurnitureSizeHint hint = {}) {
    return draw(category, hint).model;
  }

  /// Places a model of `category` with `place`; when a catalog model does not fit where the
  /// parametric one drawn with it might (a long sofa, a deep bed), tries that one instead.
  template <class Place>
  int withFallback(const std::string& category, const FurnitureSizeHint& hint, Place place) {
    const Drawn d = draw(category, hint);
    const int piece = place(d.model);
    return piece >= 0 || !d.parametric ? piece : place(*d.parametric);
  }

  /// The catalog models of `library` that may stand for `category`: the fit rule of
  /// FurnitureSource. The same for every apartment, so computed once per process (keyed by the
  /// library, which catalogLibrary() keeps for the life of the process).
  static const std::vector<std::shared_ptr<const CatalogModel>>& catalogFits(
      const CatalogLibrary& library, const std::string& category) {
    static std::mutex mutex;
    static std::map<std::pair<const CatalogLibrary*, std::string>,
                    std::vector<std::shared_ptr<const CatalogModel>>>
        cache;
    std::lock_guard lock(mutex);
    auto it = cache.find({&library, category});
    if (it != cache.end()) return it->second;
    // the category's parametric size range, from its own stream
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = Eigen::Vector3d::Zero();
    for (uint32_t i = 0; i < 24; ++i) {
      CounterRng r(0, RngStream::Layout, 4, i, 0);
      const Eigen::Vector3d sz = makeFurniture(category, r).size;
      lo = lo.cwiseMin(sz), hi = hi.cwiseMax(sz);
    }
    std::vector<std::shared_ptr<const CatalogModel>> fits;
    for (const CatalogPiece* p : library.byCategory(category)) {
      if (!domestic(*p)) continue;
      const Eigen::Vector3d sz = Eigen::Vector3d(p->width_cm, p->depth_cm, p->height_cm) / 100;
      if (library.label(p->id).slot) {  // any small thing that stands on a support
        if (sz.head<2>().maxCoeff() > 0.45 || sz.z() > 0.5 || sz.minCoeff() < 0.005) continue;
      } else {
        // 5 cm of slack, less on thin sides (a 5.5 cm tatami is no 1 cm rug)
        const Eigen::Vector3d slack = (0.5 * hi).cwiseMin(Eigen::Vector3d::Constant(0.05));
        if ((sz.array() < (0.7 * lo - slack).array()).any() ||
            (sz.array() > (1.4 * hi + slack).array()).any())
          continue;
        // rugs are walked over and lie under furniture: thinner than the 2 cm that the
        // physics (variation/rearrange.h) treats as a floor covering
        if (category == "rug" && sz.z() >= 0.02) continue;
      }
      auto model = library.model(p->id, library.dir(), "--furniture catalog");
      if (model->stretch <= 1.6) fits.push_back(std::move(model));
    }
    return cache[{&library, category}] = std::move(fits);
  }

  /// How much decoration `style` likes catalog model `c`: styleWeight (furniture.h) of each of
  /// its materials, with the albedo times its texture's mean colour, averaged over the area of
  /// the surfaces made of it; glass is left out. A texture that cannot be read counts as mid
  /// grey. The materials and their areas are gathered once per model (the textures read once).
  static double catalogStyleWeight(const CatalogModel& c, DecorStyle style) {
    static std::mutex mutex;
    static std::map<const CatalogModel*, std::vector<std::pair<double, MaterialSpec>>> cache;
    std::lock_guard lock(mutex);
    auto it = cache.find(&c);
    if (it == cache.end()) {
      std::vector<std::pair<double, MaterialSpec>> surfaces;
      for (const Object& o : c.parts.objects) {
        const Material& mat = c.parts.materials[size_t(o.material)];
        if (mat.type == MaterialType::Dielectric || mat.type == MaterialType::ThinDielectric)
          continue;
        const Mesh& mesh = c.parts.meshes[size_t(o.mesh)];
        double area = 0;
        for (const Tri& t : mesh.triangles)
          area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]])
                            .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                            .norm();
        MaterialSpec spec;
        spec.type = mat.type;
        spec.albedo = mat.albedo;
        if (!mat.albedo_texture.empty()) {
          Eigen::Vector3d mean = Eigen::Vector3d::Constant(0.5);
          try {
            mean = meanLinearRgb(mat.albedo_texture.path);
          } catch (const InputError&) {
          }
          spec.albedo = spec.albedo.cwiseProduct(mean.cast<float>());
        }
        surfaces.emplace_back(area, spec);
      }
      it = cache.emplace(&c, std::move(surfaces)).first;
    }
    double area_sum = 0, weighted = 0;
    for (const auto& [area, spec] : it->second) {
      area_sum += area;
      weighted += area * styleWeight(style, spec);
    }
    return area_sum > 0 ? weighted / area_sum : 1.0;
  }

  /// False for the catalog pieces that are labelled right but do not belong in a home (a
  /// hospital bed is a bed, a urinal a toilet, a street lamp a floor lamp): the furnisher
  /// passes over them. By name, in lower case.
  static bool domestic(const CatalogPiece& p) {
    static const char* const kNotAtHome[] = {"hospital", "street", "urinal", "outdoor",
                                             "class seat", "locker", "abdominal"};
    const std::string name = lowerCase(p.name);
    for (const char* w : kNotAtHome)
      if (name.find(w) != std::string::npos) return false;
    return true;
  }

  /// Puts catalog model `c`'s geometry, label, size, hulls and physics in `m` (its parametric
  /// parts, materials and light dropped).
  static void takeCatalog(FurnitureModel& m, const std::shared_ptr<const CatalogModel>& c) {
    m.catalog = c;
    m.parts.clear();
    m.materials.clear();
    m.light.reset();
    m.nyu40 = c->label.nyu40;
    m.size = c->size;
    m.hulls = c->hulls;
    m.mass_kg = c->mass_kg;
    m.friction = c->friction;
    m.movable = c->movable;
  }

  /// Catalog model `c` as a piece of our `category` with no parametric stand-in (doors,
  /// windows, people), which rearrangements leave where it is.
  static FurnitureModel catalogOnly(const std::string& category,
                                    const std::shared_ptr<const CatalogModel>& c) {
    FurnitureModel m;
    m.category = category;
    takeCatalog(m, c);
    m.movable = false;
    return m;
  }

  /// `parametric` with the catalog model's geometry, size, hulls and physics in its place.
  static FurnitureModel fromCatalog(const FurnitureModel& parametric,
                                    const std::shared_ptr<const CatalogModel>& c) {
    FurnitureModel m = parametric;
    takeCatalog(m, c);
    if (m.placement == FurnitureModel::Placement::Wall && c->elevation_m > 0)
      m.mount_height = c->elevation_m;
    if (m.is_support) {  // the top, or where the catalog says things are dropped on it
      const double drop = c->drop_on_top_m;
      m.support_heights = {drop > 0.02 && drop < m.size.z() ? drop : m.size.z()};
    }
    return m;
  }

  /// Tries to stand `category` against a wall (sides in `sides`, or all); returns the piece
  /// index or -1. `along` fixes the position along the wall when >= 0 (0..1 of the free span).
  int againstWall(RoomState& s, const std::string& category, std::vector<int> sides = {},
                  const FurnitureSizeHint& hint = {}) {
    if (!known(category)) return -1;
    return withFallback(category, hint,
                        [&](const FurnitureModel& m) { return againstWallModel(s, m, sides); });
  }

  int againstWallModel(RoomState& s, const FurnitureModel& m, std::vector<int> sides) {
    const double w = m.size.x(), d = m.size.y(), h = m.size.z();
    if (s.occupied + w * d > kMaxOccupied * s.interior.volume()) return -1;
    if (sides.empty()) sides = {0, 1, 2, 3};
    // random order of sides and positions, deterministic in the RNG
    for (size_t i = sides.size(); i > 1; --i)
      std::swap(sides[i - 1], sides[static_cast<size_t>(rng_.uniform() * i)]);
    const Box2& in = s.interior;
    for (int side : sides) {
      const bool vertical = side < 2;
      const double lo = vertical ? in.min().y() : in.min().x();
      const double hi = vertical ? in.max().y() : in.max().x();
      const int steps = std::max(1, static_cast<int>((hi - lo - w) / 0.1));
      const int start = static_cast<int>(rng_.uniform() * steps);
      for (int k = 0; k <= steps; ++k) {
        const double u = lo + w / 2 + ((start + k) % (steps + 1)) * 0.1;
        if (u + w / 2 > hi + 1e-9) continue;
        const double yaw = wallYaw(side);
        Eigen::Vector2d c;
        if (side == 0) c = {in.min().x() + d / 2, u};
        if (side == 1) c = {in.max().x() - d / 2, u};
        if (side == 2) c = {u, in.min().y() + d / 2};
        if (side == 3) c = {u, in.max().y() - d / 2};
        const Box2 fp = footprint(c, w, d, yaw);
        if (!floorFree(s, fp, h, false) ||
            hullsPenetrate(m, placement(Vec3(c.x(), c.y(), 0), yaw), s.index))
          continue;
        const size_t ob = apt_.scene.objects.size(), lb = apt_.scene.lights.size();
        const int piece = add(m, placement(Vec3(c.x(), c.y(), 0), yaw), s.index, true);
        if (!commitFloor(s, fp, false, ob, lb)) continue;
        if (m.is_support) s.supports.push_back(piece);
        wall_side_[piece] = side;
        models_[piece] = m;
        return piece;
      }
    }
    return -1;
  }

  /// Places `category` at `c` with `yaw` if the floor is free there.
  int at(RoomState& s, const std::string& category, const Eigen::Vector2d& c, double yaw,
         const FurnitureSizeHint& hint = {}) {
    if (!known(category)) return -1;
    return withFallback(category, hint,
                        [&](const FurnitureModel& m) { return atModel(s, category, m, c, yaw); });
  }

  int atModel(RoomState& s, const std::string& category, const FurnitureModel& m,
              const Eigen::Vector2d& c, double yaw) {
    const bool flat = category == "rug";
    const Box2 fp = footprint(c, m.size.x(), m.size.y(), yaw);
    if (!flat && s.occupied + fp.volume() > kMaxOccupied * s.interior.volume()) return -1;
    if (!floorFree(s, fp, m.size.z(), flat)) return -1;
    if (!flat && hullsPenetrate(m, placement(Vec3(c.x(), c.y(), 0), yaw), s.index)) return -1;
    const size_t ob = apt_.scene.objects.size(), lb = apt_.scene.lights.size();
    const int piece = add(m, placement(Vec3(c.x(), c.y(), 0), yaw), s.index, true);
    if (!commitFloor(s, fp, flat, ob, lb)) return -1;
    if (m.is_support) s.supports.push_back(piece);
    models_[piece] = m;
    yaw_[piece] = yaw;
    return piece;
  }

  Box2 footprintOf(int piece) const {
    Box2 b;
    for (const auto& h : apt_.pieces[piece].hulls)
      b.extend(Box2(h.min().head<2>(), h.max().head<2>()));
    return b;
  }

  /// In front of `piece` (its front = -y of its model frame) at `gap` metres, facing it when
  /// `facing`, else facing the same way.
  int inFront(RoomState& s, int piece, const std::string& category, double gap, bool facing) {
    if (piece < 0 || !known(category)) return -1;
    const double yaw = pieceYaw(piece);
    const Eigen::Vector2d front(std::sin(yaw), -std::cos(yaw));  // model -y in world
    FurnitureModel m = make(category);
    const Box2 fp = footprintOf(piece);
    const double depth = std::fabs(front.x()) > 0.5 ? fp.sizes().x() : fp.sizes().y();
    const Eigen::Vector2d c = fp.center() + front * (depth / 2 + gap + m.size.y() / 2);
    return at(s, category, c, facing ? yaw + kPi : yaw);
  }

  /// Beside `piece` along its wall, left (-1) or right (+1), with a small gap.
  int beside(RoomState& s, int piece, const std::string& category, int dir) {
    if (piece < 0 || !known(category)) return -1;
    const double yaw = pieceYaw(piece);
    const Eigen::Vector2d right(std::cos(yaw), std::sin(yaw));  // model +x in world
    FurnitureModel m = make(category);
    const Box2 fp = footprintOf(piece);
    const double width = std::fabs(right.x()) > 0.5 ? fp.sizes().x() : fp.sizes().y();
    const double depth = std::fabs(right.x()) > 0.5 ? fp.sizes().y() : fp.sizes().x();
    const Eigen::Vector2d back(-std::sin(yaw), std::cos(yaw));  // model +y: towards the wall
    const Eigen::Vector2d c = fp.center() + right * dir * (width / 2 + 0.05 + m.size.x() / 2) +
                              back * (depth / 2 - m.size.y() / 2);
    return at(s, category, c, yaw);
  }

  double pieceYaw(int piece) const {
    auto it = wall_side_.find(piece);
    if (it != wall_side_.end()) return wallYaw(it->second);
    auto jt = yaw_.find(piece);
    return jt == yaw_.end() ? 0.0 : jt->second;
  }

  /// Does world box `b` sink more than 5 mm into any solid piece of room `room`?
  bool penetrates(const Eigen::AlignedBox3d& b, int room) const {
    for (const PlacedPiece& p : apt_.pieces) {
      if (p.room != room || p.flat) continue;
      for (const auto& h : p.hulls) {
        const Eigen::AlignedBox3d i = b.intersection(h);
        if (!i.isEmpty() && i.sizes().minCoeff() > 0.005) return true;
      }
    }
    return false;
  }

  /// Would `m` placed by T sink into a solid piece of the room (wall-mounted ones included)?
  bool hullsPenetrate(const FurnitureModel& m, const Mat4& T, int room) const {
    for (const auto& h : m.hulls)
      if (penetrates(transformBox(h, T), room)) return true;
    return false;
  }

  /// A small item on a support piece's top (or a given support level), if there is room.
  int onSurface(int support, const std::string& category, int level = -1) {
    if (support < 0 || !known(category) || !models_.count(support)) return -1;
    const FurnitureModel& sm = models_.at(support);
    if (!sm.is_support || sm.support_heights.empty()) return -1;
    return withFallback(category, {},
                        [&](const FurnitureModel& m) { return onSurfaceModel(support, m, level); });
  }

  int onSurfaceModel(int support, const FurnitureModel& m, int level) {
    const FurnitureModel& sm = models_.at(support);
    const double z =
        level < 0 ? sm.support_heights.back()
                  : sm.support_heights[std::min<size_t>(level, sm.support_heights.size() - 1)];
    const Box2 top = footprintOf(support);
    const double margin = 0.03;
    const double yaw = pieceYaw(support) + (rng_.uniform() < 0.5f ? 0.0 : kPi / 2);
    for (int tries = 0; tries < 12; ++tries) {
      const Eigen::Vector2d half =
          footprint(Eigen::Vector2d::Zero(), m.size.x(), m.size.y(), yaw).max();
      const Eigen::Vector2d lo = top.min() + half + Eigen::Vector2d::Constant(margin);
      const Eigen::Vector2d hi = top.max() - half - Eigen::Vector2d::Constant(margin);
      if ((hi - lo).minCoeff() < 0) return -1;
      const Eigen::Vector2d c(rng_.uniformDouble(lo.x(), hi.x()),
                              rng_.uniformDouble(lo.y(), hi.y()));
      const Box2 fp = footprint(c, m.size.x(), m.size.y(), yaw);
      bool clash = false;
      for (const Box2& o : on_support_[support]) clash = clash || overlaps(fp, o, -0.01);
      const int room = apt_.pieces[support].room;
      // in 3D too: a cushion must not sink into the sofa's back or arms
      const Mat4 T = placement(Vec3(c.x(), c.y(), z + 0.001), yaw);
      for (const auto& h : m.hulls) clash = clash || penetrates(transformBox(h, T), room);
      if (clash) continue;
      const int piece = add(m, T, room, false);
      apt_.pieces[piece].rests_on = "support";
      apt_.pieces[piece].support = support;
      apt_.pieces[piece].support_z = z;
      on_support_[support].push_back(fp);
      models_[piece] = m;
      yaw_[piece] = yaw;
      return piece;
    }
    return -1;
  }

  /// A wall-mounted item (picture, mirror, upper cabinet) centred above `below` (a piece whose
  /// wall it shares) or on a free stretch of wall.
  int onWall(RoomState& s, const std::string& category, int below = -1, double height = -1) {
    if (!known(category)) return -1;
    return withFallback(category, {},
                        [&](const FurnitureModel& m) { return onWallModel(s, m, below, height); });
  }

  int onWallModel(RoomState& s, const FurnitureModel& m, int below, double height) {
    const double z = height >= 0 ? height : m.mount_height;
    const Box2& in = s.interior;
    std::vector<int> sides = {0, 1, 2, 3};
    if (below >= 0 && wall_side_.count(below)) sides = {wall_side_.at(below)};
    for (int side : sides) {
      const bool vertical = side < 2;
      double u;
      if (below >= 0 && wall_side_.count(below)) {
        const Eigen::Vector2d c = footprintOf(below).center();
        u = vertical ? c.y() : c.x();
      } else {
        const double lo = vertical ? in.min().y() : in.min().x();
        const double hi = vertical ? in.max().y() : in.max().x();
        if (hi - lo < m.size.x() + 0.2) continue;
        u = rng_.uniformDouble(lo + m.size.x() / 2 + 0.1, hi - m.size.x() / 2 - 0.1);
      }
      const double d = m.size.y();
      Eigen::Vector2d c;
      if (side == 0) c = {in.min().x() + d / 2, u};
      if (side == 1) c = {in.max().x() - d / 2, u};
      if (side == 2) c = {u, in.min().y() + d / 2};
      if (side == 3) c = {u, in.max().y() - d / 2};
      const Box2 fp = footprint(c, m.size.x(), d, wallYaw(side));
      // clear of doors, windows and of whatever stands below it higher than its bottom
      bool clash = fp.min().x() < in.min().x() - 1e-3 || fp.max().x() > in.max().x() + 1e-3 ||
                   fp.min().y() < in.min().y() - 1e-3 || fp.max().y() > in.max().y() + 1e-3;
      for (const Box2& zbox : s.door_zones) clash = clash || overlaps(fp, zbox);
      for (const Box2& zbox : s.window_zones) clash = clash || overlaps(fp, zbox);
      const Eigen::AlignedBox3d me(Vec3(fp.min().x(), fp.min().y(), z),
                                   Vec3(fp.max().x(), fp.max().y(), z + m.size.z()));
      for (const PlacedPiece& p : apt_.pieces) {
        if (p.room != s.index) continue;
        for (const auto& h : p.hulls) {
          const auto o = me.intersection(h);
          clash = clash || (!o.isEmpty() && o.sizes().minCoeff() > 0.005);
        }
      }
      if (z + m.size.z() > apt_.plan.ceiling - 0.05) clash = true;
      if (clash) continue;
      const int piece = add(m, placement(Vec3(c.x(), c.y(), z), wallYaw(side)), s.index, false);
      apt_.pieces[piece].rests_on = "wall";
      wall_side_[piece] = side;
      models_[piece] = m;
      return piece;
    }
    return -1;
  }

  void ceilingLight(RoomState& s) {
    const std::string cat = known("ceiling_light") ? "ceiling_light" : "pendant_light";
    if (!known(cat)) return;
    FurnitureModel m = make(cat);
    const Eigen::Vector2d c = s.interior.center();
    const double z = apt_.plan.ceiling - m.size.z();
    const int piece = add(m, placement(Vec3(c.x(), c.y(), z), 0.0), s.index, false);
    apt_.pieces[piece].rests_on = "ceiling";
  }

  void curtains(RoomState& s) {
    if (!known("curtain")) return;
    const FloorPlan& plan = apt_.plan;
    for (const PlanWindow& w : plan.windows) {
      if (w.room != s.index) continue;
      FurnitureSizeHint hint;
      hint.width = std::min(w.to - w.from + 0.4, 3.0);
      hint.height = std::max(0.5, std::min(plan.ceiling - 0.15, w.top + 0.1) - 0.05);
      FurnitureModel m = make("curtain", hint);
      const Box2& in = s.interior;
      const Box2& rb = plan.rooms[s.index].box;
      int side;
      if (w.vertical)
        side = std::fabs(w.line - rb.min().x()) < 1e-9 ? 0 : 1;
      else
        side = std::fabs(w.line - rb.min().y()) < 1e-9 ? 2 : 3;
      const double centre = std::clamp(0.5 * (w.from + w.to),
                                       (w.vertical ? in.min().y() : in.min().x()) + m.size.x() / 2,
                                       (w.vertical ? in.max().y() : in.max().x()) - m.size.x() / 2);
      const double d = m.size.y();
      Eigen::Vector2d c;
      if (side == 0) c = {in.min().x() + d / 2, centre};
      if (side == 1) c = {in.max().x() - d / 2, centre};
      if (side == 2) c = {centre, in.min().y() + d / 2};
      if (side == 3) c = {centre, in.max().y() - d / 2};
      const double z = std::max(0.02, std::min(plan.ceiling - 0.05, w.top + 0.15) - m.size.z());
      const Mat4 T = placement(Vec3(c.x(), c.y(), z), wallYaw(side));
      bool clash = false;
      for (const auto& h : m.hulls) clash = clash || penetrates(transformBox(h, T), s.index);
      if (clash) continue;
      const int piece = add(m, T, s.index, false);
      apt_.pieces[piece].rests_on = "wall";
      // it hangs down to the floor: floor pieces keep out of its footprint
      s.floor_boxes.push_back(footprint(c, m.size.x(), m.size.y(), wallYaw(side)));
    }
  }

  void clutter(RoomState& s, int count, std::initializer_list<const char*> items) {
    if (s.supports.empty()) return;
    std::vector<std::string> list(items.begin(), items.end());
    for (int k = 0; k < count; ++k) {
      const int support = s.supports[static_cast<size_t>(rng_.uniform() * s.supports.size())];
      onSurface(support, list[static_cast<size_t>(rng_.uniform() * list.size())]);
    }
  }

  void furnish(int i) {
    RoomState s = roomState(i);
    const std::string& type = apt_.plan.rooms[i].type;
    const bool studio = apt_.plan.rooms.size() == 1;
    auto longWalls = [&]() {
      const Eigen::Vector2d sz = s.interior.sizes();
      return sz.x() >= sz.y() ? std::vector<int>{2, 3} : std::vector<int>{0, 1};
    };
    auto opposite = [](int side) { return side ^ 1; };
    if (type == "living_room") {
      curtains(s);
      if (rng_.uniform() < 0.7f) at(s, "rug", s.interior.center(), 0.0);
      const int sofa = againstWall(s, "sofa", longWalls());
      const int table = inFront(s, sofa, "coffee_table", 0.4, false);
      if (sofa >= 0) {
        const int stand = againstWall(s, "tv_stand", {opposite(wall_side_[sofa])});
        onSurface(stand, "television");
        onWall(s, "picture", sofa);
        onSurface(sofa, "cushion");
        onSurface(sofa, "cushion");
      }
      onSurface(table, "vase");
      onSurface(table, "books");
      if (rng_.uniform() < 0.7f) againstWall(s, "armchair");
      if (rng_.uniform() < 0.7f) {
        const int shelf = againstWall(s, "bookshelf");
        for (int k = 0; k < 3; ++k) onSurface(shelf, "books", k);
      }
      if (rng_.uniform() < 0.6f) againstWall(s, "floor_lamp");
      if (rng_.uniform() < 0.6f) againstWall(s, "potted_plant");
      if (studio) {
        const int bed = againstWall(s, "bed_double");
        beside(s, bed, "nightstand", 1);
        againstWall(s, "kitchen_counter");
        againstWall(s, "refrigerator");
      }
    } else if (type == "dining_room") {
      const int table =
          at(s, "dining_table", s.interior.center(), rng_.uniform() < 0.5f ? 0 : kPi / 2);
      if (table >= 0) {
        for (int k = 0; k < 6; ++k) chairAround(s, table, k);
        onSurface(table, "vase");
        onSurface(table, "bowl");
      }
      againstWall(s, "cabinet");
      onWall(s, "picture");
    } else if (type == "kitchen") {
      const std::vector<int> wall = longWalls();
      const int sink = againstWall(s, "kitchen_sink_counter", wall);
      int side = sink >= 0 ? wall_side_[sink] : wall[0];
      for (int k = 0; k < 3; ++k) {
        const int c = againstWall(s, "kitchen_counter", {side});
        if (c >= 0) onWall(s, "upper_cabinet", c, 1.45);
      }
      againstWall(s, "stove", {side});
      againstWall(s, "refrigerator");
      clutter(s, 4, {"bowl", "mug", "vase", "box"});
      if (s.interior.volume() > 9.0) {
        const int t = at(s, "dining_table", s.interior.center(), 0.0);
        if (t >= 0)
          for (int k = 0; k < 2; ++k) chairAround(s, t, k);
      }
    } else if (type == "master_bedroom" || type == "second_bedroom" || type == "elderly_room" ||
               type == "kids_room") {
      const bool big = type == "master_bedroom" || type == "elderly_room";
      curtains(s);
      const int bed = againstWall(s, big ? "bed_double" : "bed_single");
      const int left = beside(s, bed, "nightstand", -1);
      const int right = big ? beside(s, bed, "nightstand", 1) : -1;
      onSurface(left, "table_lamp");
      onSurface(right, "table_lamp");
      onSurface(bed, "pillow");
      if (big) onSurface(bed, "pillow");
      onWall(s, "picture", bed);
      againstWall(s, "wardrobe");
      if (type == "kids_room") {
        const int desk = againstWall(s, "desk");
        inFront(s, desk, "office_chair", 0.05, true);
        const int shelf = againstWall(s, "bookshelf");
        onSurface(shelf, "books", 1);
        onSurface(shelf, "box", 0);
        at(s, "rug", s.interior.center(), 0.0);
      } else if (rng_.uniform() < 0.6f) {
        const int dresser = againstWall(s, "dresser");
        onSurface(dresser, "clothes");
        onSurface(dresser, "vase");
      }
    } else if (type == "study") {
      curtains(s);
      const int desk = againstWall(s, "desk");
      inFront(s, desk, "office_chair", 0.05, true);
      onSurface(desk, rng_.uniform() < 0.5f ? "monitor" : "laptop");
      onSurface(desk, "mug");
      for (int k = 0; k < 2; ++k) {
        const int shelf = againstWall(s, "bookshelf");
        for (int l = 0; l < 4; ++l) onSurface(shelf, "books", l);
      }
      againstWall(s, "floor_lamp");
    } else if (type == "bathroom" || type == "master_bathroom") {
      const Eigen::Vector2d sz = s.interior.sizes();
      if (sz.maxCoeff() >= 1.75 && rng_.uniform() < 0.6f) {
        againstWall(s, "bathtub", longWalls());
      } else {
        againstWall(s, "shower");
      }
      againstWall(s, "toilet");
      const int basin = againstWall(s, "bathroom_basin");
      onWall(s, "mirror", basin, 1.2);
      onWall(s, "towel");
      if (type == "bathroom" && rng_.uniform() < 0.4f) againstWall(s, "washing_machine");
    } else if (type == "balcony") {
      againstWall(s, "potted_plant");
      againstWall(s, "potted_plant");
      againstWall(s, rng_.uniform() < 0.5f ? "bench" : "stool");
    } else if (type == "corridor") {
      onWall(s, "picture");
      if (rng_.uniform() < 0.5f) onWall(s, "picture");
      againstWall(s, "shoe_rack");
    } else if (type == "entrance") {
      const int rack = againstWall(s, "shoe_rack");
      onSurface(rack, "shoes");
      againstWall(s, "coat_rack");
      onWall(s, "mirror");
    } else if (type == "storage") {
      for (int k = 0; k < 2; ++k) {
        const int shelf = againstWall(s, "bookshelf");
        for (int l = 0; l < 3; ++l) onSurface(shelf, "box", l);
      }
      againstWall(s, "cabinet");
    } else if (type == "cloakroom") {
      againstWall(s, "wardrobe");
      againstWall(s, "wardrobe");
      const int bench = againstWall(s, "bench");
      onSurface(bench, "bag");
    } else if (type == "laundry") {
      againstWall(s, "washing_machine");
      const int cab = againstWall(s, "cabinet");
      onSurface(cab, "box");
      onWall(s, "towel");
    }
    ceilingLight(s);
    if (library_) people(s, type);  // after the light, which may hang low
  }

  /// The catalog's people (NYU40 person) a furnisher may stand in a room: `adults` standing
  /// (taller than 1.4 m) and `kids` ("boy", "girl": standing, or sitting on the floor, under
  /// 1 m tall). Figures sitting on a seat or lying on a bed, and mannequins, are left out.
  /// Computed once per library, in catalog order.
  struct People {
    std::vector<std::shared_ptr<const CatalogModel>> adults, kids;
  };
  static const People& catalogPeople(const CatalogLibrary& library) {
    static std::mutex mutex;
    static std::map<const CatalogLibrary*, People> cache;
    std::lock_guard lock(mutex);
    auto it = cache.find(&library);
    if (it != cache.end()) return it->second;
    People people;
    const int person = *nyu40FromName("person");
    for (const FurnitureCatalog& cat : library.catalogs())
      for (const CatalogPiece& p : cat.pieces) {
        if (!p.isInterior() || library.label(p.id).nyu40 != person) continue;
        const std::string name = lowerCase(p.name);
        auto has = [&](const char* w) { return name.find(w) != std::string::npos; };
        if (has("mannequin") || has("lying")) continue;
        const bool kid = has("boy") || has("girl"), sitting = has("sitting");
        if (kid && (!sitting || p.height_cm < 100))
          people.kids.push_back(library.model(p.id, library.dir(), "--furniture catalog"));
        else if (!kid && !sitting && p.height_cm > 140)
          people.adults.push_back(library.model(p.id, library.dir(), "--furniture catalog"));
      }
    return cache[&library] = std::move(people);
  }

  /// Sometimes someone is at home: in a living room, dining room, kitchen, bedroom or study,
  /// with odds 0.35, one catalog person (a child in a kids' room) stands on free floor 0.4 m
  /// or more from the walls, facing the room's centre, under every floor rule (free floor,
  /// reachability). People are not moved by rearrangements. Draws from its own stream.
  void people(RoomState& s, const std::string& type) {
    static const std::set<std::string> lived_in = {
        "living_room",    "dining_room", "kitchen",      "master_bedroom",
        "second_bedroom", "kids_room",   "elderly_room", "study"};
    if (!lived_in.count(type)) return;
    CounterRng r(opt_.seed, RngStream::Layout, 6, static_cast<uint32_t>(s.index), 0);
    if (r.uniform() >= 0.35f) return;
    const People& all = catalogPeople(*library_);
    const auto& pool = type == "kids_room" ? all.kids : all.adults;
    if (pool.empty()) return;
    const auto& c =
        pool[std::min(pool.size() - 1, static_cast<size_t>(r.uniform() * pool.size()))];
    const FurnitureModel m = catalogOnly("person", c);
    const Box2 area(s.interior.min() + Eigen::Vector2d::Constant(0.4),
                    s.interior.max() - Eigen::Vector2d::Constant(0.4));
    if (area.isEmpty()) return;
    for (int attempt = 0; attempt < 24; ++attempt) {
      const Eigen::Vector2d p(r.uniformDouble(area.min().x(), area.max().x()),
                              r.uniformDouble(area.min().y(), area.max().y()));
      // of the four turns, the one whose front (model -y) points most towards the centre
      const Eigen::Vector2d to_centre = s.interior.center() - p;
      double yaw = 0, best = -1e9;
      for (int k = 0; k < 4; ++k) {
        const double y = k * kPi / 2;
        const double along = Eigen::Vector2d(std::sin(y), -std::cos(y)).dot(to_centre);
        if (along > best) best = along, yaw = y;
      }
      if (atModel(s, "person", m, p, yaw) >= 0) return;
    }
  }

  void chairAround(RoomState& s, int table, int k) {
    const Box2 fp = footprintOf(table);
    const Eigen::Vector2d c = fp.center(), half = fp.sizes() / 2;
    const bool along_x = half.x() >= half.y();
    const int per_side =
        std::max(1, static_cast<int>((along_x ? 2 * half.x() : 2 * half.y()) / 0.6));
    const int side = k % 2 == 0 ? 1 : -1;
    const int slot = (k / 2) % per_side;
    if (k / 2 >= per_side) return;
    if (!known("dining_chair")) return;
    FurnitureModel probe = make("dining_chair");
    const double offset = -0.5 * (per_side - 1) * 0.6 + slot * 0.6;
    Eigen::Vector2d pos;
    double yaw;
    const double gap = 0.12 + probe.size.y() / 2;
    if (along_x) {
      pos = {c.x() + offset, c.y() + side * (half.y() + gap)};
      yaw = side > 0 ? 0.0 : kPi;  // front (-y) towards the table
    } else {
      pos = {c.x() + side * (half.x() + gap), c.y() + offset};
      yaw = side > 0 ? -kPi / 2 : kPi / 2;
    }
    const int chair = at(s, "dining_chair", pos, yaw);
    if (chair >= 0) yaw_[chair] = yaw;
  }

  void daylight() {
    // the ground outside, seen through the windows below the horizon (the sky has nothing
    // there). 60 m across: a camera 1.5 m up sees it to within 3 degrees of the horizon, and
    // the scene stays small enough that light selection (which weighs a sky by the scene's
    // size) keeps most samples for the lights inside
    const Eigen::Vector2d c = apt_.plan.footprint.center();
    box("ground", "ground", 0, -1,
        plain("ground_grass", Vec3f(0.12f, 0.16f, 0.08f), TextureKind::None, 1.f),
        Vec3(c.x() - 30, c.y() - 30, -0.30), Vec3(c.x() + 30, c.y() + 30, -0.25));
    const double elevation = rng_.uniformDouble(25, 55) * kPi / 180;
    const double azimuth = rng_.uniformDouble(0, 2 * kPi);
    const Vec3 to_sun(std::cos(elevation) * std::cos(azimuth),
                      std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
    const float turbidity = static_cast<float>(rng_.uniformDouble(2.5, 4));
    const auto [sky, sun] = daylightLights(to_sun, turbidity);
    apt_.scene.lights.push_back(sky);
    apt_.scene.lights.push_back(sun);
  }

  const ApartmentOptions& opt_;
  CounterRng rng_;
  DecorStyle style_ = DecorStyle::Any;
  fs::path layout_dir_, texture_dir_;
  Apartment apt_;
  std::map<std::string, int> materials_, meshes_, count_;
  std::map<std::string, double> tile_;
  std::map<int, int> wall_side_;
  std::map<int, double> yaw_;
  std::map<int, FurnitureModel> models_;
  std::map<int, std::vector<Box2>> on_support_;
  std::shared_ptr<const CatalogLibrary> library_;  ///< null: parametric furniture only
  uint64_t catalog_draws_ = 0;
  uint64_t opening_draws_ = 0;
  std::map<size_t, CatalogOpening> window_openings_;  ///< by plan window
  std::map<size_t, CatalogOpening> door_openings_;    ///< by plan door (the front door)
  int instances_ = 0;
  int sphere_ = -1;
};

}  // namespace

FurnitureSource parseFurnitureSource(const std::string& name, const std::string& field) {
  for (FurnitureSource f :
       {FurnitureSource::Parametric, FurnitureSource::Catalog, FurnitureSource::Mixed})
    if (name == furnitureSourceName(f)) return f;
  throw InputError("", field,
                   fmt::format("unknown furniture source '{}' (parametric, catalog, mixed)", name));
}

const char* furnitureSourceName(FurnitureSource s) {
  switch (s) {
    case FurnitureSource::Parametric:
      return "parametric";
    case FurnitureSource::Catalog:
      return "catalog";
    case FurnitureSource::Mixed:
      return "mixed";
  }
  return "?";
}

Apartment makeApartment(const ApartmentOptions& opt, const fs::path& layout_dir,
                        const fs::path& texture_dir) {
  if (opt.rooms < 0 || opt.rooms > 16)
    throw InputError("", "--rooms",
                     fmt::format("must be in 1..16 (0 = random), got {}", opt.rooms));
  if (opt.texture_size < 64 || opt.texture_size > 1024 ||
      (opt.texture_size & (opt.texture_size - 1)) != 0)
    throw InputError("", "--texture-size", "must be a power of two in 64..1024");
  return Builder(opt, layout_dir, texture_dir).build();
}

std::vector<bool> reachableRooms(const Apartment& apt, double cell, double radius,
                                 std::vector<double>* free_fraction) {
  const FloorPlan& plan = apt.plan;
  const Box2& fpb = plan.footprint;
  const int nx = static_cast<int>(std::ceil(fpb.sizes().x() / cell));
  const int ny = static_cast<int>(std::ceil(fpb.sizes().y() / cell));
  const double t = plan.wall_thickness / 2;
  std::vector<int> room_of(static_cast<size_t>(nx) * ny, -1);
  std::vector<uint8_t> walkable(room_of.size(), 0), blocked(room_of.size(), 0),
      blocked_grown(room_of.size(), 0);
  auto centre = [&](int x, int y) {
    return Eigen::Vector2d(fpb.min().x() + (x + 0.5) * cell, fpb.min().y() + (y + 0.5) * cell);
  };
  // calls f(k) for every cell whose centre lies in b (closed box)
  auto raster = [&](const Box2& b, auto f) {
    const int x0 =
        std::max(0, static_cast<int>(std::ceil((b.min().x() - fpb.min().x()) / cell - 0.5)));
    const int x1 =
        std::min(nx - 1, static_cast<int>(std::floor((b.max().x() - fpb.min().x()) / cell - 0.5)));
    const int y0 =
        std::max(0, static_cast<int>(std::ceil((b.min().y() - fpb.min().y()) / cell - 0.5)));
    const int y1 =
        std::min(ny - 1, static_cast<int>(std::floor((b.max().y() - fpb.min().y()) / cell - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) f(static_cast<size_t>(y) * nx + x);
  };
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    const Box2& b = plan.rooms[r].box;
    raster(Box2(b.min() + Eigen::Vector2d::Constant(t), b.max() - Eigen::Vector2d::Constant(t)),
           [&](size_t k) {
             room_of[k] = static_cast<int>(r);
             walkable[k] = 1;
           });
  }
  for (const PlanDoor& d : plan.doors) {
    if (d.b < 0) continue;
    const Box2 z = d.vertical ? Box2(Eigen::Vector2d(d.line - t - cell, d.from),
                                     Eigen::Vector2d(d.line + t + cell, d.to))
                              : Box2(Eigen::Vector2d(d.from, d.line - t - cell),
                                     Eigen::Vector2d(d.to, d.line + t + cell));
    raster(z, [&](size_t k) { walkable[k] = 1; });
  }
  for (const PlacedPiece& p : apt.pieces) {
    if (!p.on_floor || p.flat) continue;
    Box2 b;
    for (const auto& h : p.hulls) b.extend(Box2(h.min().head<2>(), h.max().head<2>()));
    raster(b, [&](size_t k) { blocked[k] = 1; });
    raster(Box2(b.min() - Eigen::Vector2d::Constant(radius),
                b.max() + Eigen::Vector2d::Constant(radius)),
           [&](size_t k) { blocked_grown[k] = 1; });
  }
  std::vector<uint8_t> free(room_of.size(), 0);
  std::vector<double> room_cells(plan.rooms.size(), 0), room_free(plan.rooms.size(), 0);
  for (size_t k = 0; k < free.size(); ++k) {
    if (!walkable[k]) continue;
    if (room_of[k] >= 0) {
      room_cells[room_of[k]] += 1;
      room_free[room_of[k]] += blocked[k] ? 0 : 1;
    }
    free[k] = blocked_grown[k] ? 0 : 1;
  }
  // start: free cells of the room with the front door, nearest the door
  int start = -1;
  for (const PlanDoor& d : plan.doors)
    if (d.b < 0) {
      const Eigen::Vector2d mid = d.vertical ? Eigen::Vector2d(d.line, 0.5 * (d.from + d.to))
                                             : Eigen::Vector2d(0.5 * (d.from + d.to), d.line);
      double best = 1e9;
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const size_t k = static_cast<size_t>(y) * nx + x;
          if (!free[k] || room_of[k] != d.a) continue;
          const double dist = (centre(x, y) - mid).norm();
          if (dist < best) {
            best = dist;
            start = static_cast<int>(k);
          }
        }
    }
  std::vector<bool> reached(plan.rooms.size(), false);
  if (free_fraction) {
    free_fraction->resize(plan.rooms.size());
    for (size_t r = 0; r < plan.rooms.size(); ++r)
      (*free_fraction)[r] = room_cells[r] > 0 ? room_free[r] / room_cells[r] : 0.0;
  }
  if (start < 0) return reached;
  std::vector<uint8_t> seen(free.size(), 0);
  std::queue<int> q;
  q.push(start);
  seen[start] = 1;
  while (!q.empty()) {
    const int c = q.front();
    q.pop();
    if (room_of[c] >= 0) reached[room_of[c]] = true;
    const int x = c % nx, y = c / nx;
    const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
    for (const auto& n : nb) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= nx || n[1] >= ny) continue;
      const int k = n[1] * nx + n[0];
      if (free[k] && !seen[k]) {
        seen[k] = 1;
        q.push(k);
      }
    }
  }
  return reached;
}

}  // namespace inet
