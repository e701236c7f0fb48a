#include "assets/sh3d_import.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "assets/catalog_library.h"
#include "assets/catalog_model.h"
#include "assets/polygon_mesh.h"
#include "assets/svg_path.h"
#include "assets/zip_archive.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "core/text.h"
#include "variation/lighting.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

constexpr double kPi = 3.14159265358979323846;
using V2 = Eigen::Vector2d;

/// Plan centimetres (y down) to world metres (y up).
V2 world(const V2& plan) {
  return V2(plan.x(), -plan.y()) / 100.0;
}

/// World metres back to plan centimetres.
V2 plan(const V2& world_m) {
  return V2(world_m.x(), -world_m.y()) * 100.0;
}

Vec3f linear(const Eigen::Vector3f& srgb) {
  return Vec3f(float(srgbEotf(srgb.x())), float(srgbEotf(srgb.y())), float(srgbEotf(srgb.z())));
}

/// Intersection of the lines p + s d and q + t e; nullopt when (nearly) parallel.
std::optional<V2> lineIntersection(const V2& p, const V2& d, const V2& q, const V2& e) {
  const double den = d.x() * e.y() - d.y() * e.x();
  if (d.norm() < 1e-9 || e.norm() < 1e-9 || std::abs(den) < 1e-9 * d.norm() * e.norm())
    return std::nullopt;
  const V2 w = q - p;
  const double s = (w.x() * e.y() - w.y() * e.x()) / den;
  return p + s * d;
}

/// A wall's centre line and side lines as polylines (one segment for a straight wall), in
/// world metres, with the share of the wall's length at each point (for sloped walls).
struct WallShape {
  std::vector<V2> centre, left, right;
  std::vector<double> along;          ///< 0 at the start, 1 at the end
  double z0 = 0;                      ///< bottom (m)
  double h_start = 2.5, h_end = 2.5;  ///< heights above z0 at the start and the end (m)
  double thickness = 0.1;
  double height(double f) const { return h_start + (h_end - h_start) * f; }
};

/// The unjoined shape: straight, or a round wall as pieces of its arc.
WallShape rawWallShape(const Sh3dWall& w) {
  WallShape s;
  const V2 a = world(w.start), b = world(w.end);
  s.thickness = w.thickness_cm / 100.0;
  const double half = s.thickness / 2;
  const double chord = (b - a).norm();
  if (std::abs(w.arc_extent) > 1e-3 && chord > 1e-6) {
    // Round wall (Sweet Home 3D's Wall.getArcCircleCenter): the centre is at
    // mid + t n with n the left normal and t = -(chord / 2) cot(arcExtent / 2), so a positive
    // extent bulges to the left of start -> end; the path from start to end then turns
    // clockwise seen from above, a sweep of -arcExtent counter-clockwise.
    const double ext = -w.arc_extent;
    const double r = chord / (2 * std::abs(std::sin(w.arc_extent / 2)));
    const V2 mid = (a + b) / 2;
    const V2 dir = (b - a) / chord;
    const V2 perp(-dir.y(), dir.x());  // left of start -> end
    const V2 c = mid + perp * (-(chord / 2) / std::tan(w.arc_extent / 2));
    const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
    const int n = std::max(2, int(std::ceil(std::abs(ext) / (kPi / 24))));
    for (int i = 0; i <= n; ++i) {
      const double f = double(i) / n;
      const double ang = a0 + ext * f;
      const V2 u(std::cos(ang), std::sin(ang));
      s.centre.push_back(c + r * u);
      // left of a counter-clockwise sweep is towards the centre
      const double sign = ext > 0 ? -1 : 1;
      s.left.push_back(c + (r + sign * half) * u);
      s.right.push_back(c + (r - sign * half) * u);
      s.along.push_back(f);
    }
    return s;
  }
  const V2 dir = chord > 1e-9 ? V2((b - a) / chord) : V2(1, 0);
  const V2 nl(-dir.y(), dir.x());
  s.centre = {a, b};
  s.left = {a + nl * half, b + nl * half};
  s.right = {a - nl * half, b - nl * half};
  s.along = {0, 1};
  return s;
}

/// Mitres the ends of walls joined to others, as Sweet Home 3D does: a side line of this wall
/// ends where it meets the matching side line of the wall joined there (left with left when
/// the other wall continues the path, left with right when both start or both end there).
void joinWalls(const std::vector<Sh3dWall>& walls, std::vector<WallShape>& shapes) {
  const std::vector<WallShape> raw = shapes;
  auto sideLine = [&](int wi, bool at_start, bool left) {
    const WallShape& s = raw[size_t(wi)];
    const auto& pts = left ? s.left : s.right;
    const size_t n = pts.size();
    const V2 p = at_start ? pts[0] : pts[n - 1];
    const V2 d = at_start ? V2(pts[1] - pts[0]) : V2(pts[n - 1] - pts[n - 2]);
    return std::pair<V2, V2>(p, d);
  };
  for (size_t i = 0; i < walls.size(); ++i) {
    for (const bool at_start : {true, false}) {
      const int other = at_start ? walls[i].wall_at_start : walls[i].wall_at_end;
      if (other < 0 || size_t(other) == i) continue;
      const Sh3dWall& o = walls[size_t(other)];
      // where the other wall touches this one: its end or its start
      const bool other_end = o.wall_at_end == int(i);
      const bool other_start = o.wall_at_start == int(i);
      if (!other_end && !other_start) continue;  // a one-sided join: left as it is
      bool other_at_start = other_start && !other_end;
      if (other_start && other_end) {  // both ends of the other wall touch this one: nearest
        const V2 mine = at_start ? raw[i].centre.front() : raw[i].centre.back();
        other_at_start = (raw[size_t(other)].centre.front() - mine).norm() <
                         (raw[size_t(other)].centre.back() - mine).norm();
      }
      // same direction of travel through the joint (end -> start): left meets left
      const bool continues = at_start != other_at_start;
      WallShape& s = shapes[i];
      const double limit = 2 * raw[i].thickness;  // as Sweet Home 3D: else unmitred
      for (const bool left : {true, false}) {
        const auto [p, d] = sideLine(int(i), at_start, left);
        const auto [q, e] = sideLine(other, other_at_start, continues ? left : !left);
        const auto x = lineIntersection(p, d, q, e);
        if (!x || (*x - p).norm() > limit) continue;
        auto& pts = left ? s.left : s.right;
        (at_start ? pts.front() : pts.back()) = *x;
      }
    }
  }
}

/// Reads an archive entry to the home's cache folder once (textures), with an extension
/// from its first bytes so image readers recognise it.
class HomeFiles {
 public:
  /// The archive is opened on first use: a home of walls and rooms alone needs none.
  explicit HomeFiles(std::string path) : path_(std::move(path)) {}
  const ZipArchive& zip() {
    if (!zip_) {
      zip_ = std::make_unique<ZipArchive>(path_);
      checksum_ = zip_->contentChecksum();
      dir_ = userCacheDir("sh3d") / checksum_ / "textures";
    }
    return *zip_;
  }
  const std::string& checksum() {
    zip();
    return checksum_;
  }
  TextureRef texture(const std::string& entry) {
    auto it = done_.find(entry);
    if (it != done_.end()) return it->second;
    const std::string bytes = zip().read(entry, uint64_t(256) << 20);
    const bool png = bytes.size() > 4 && bytes.compare(1, 3, "PNG") == 0;
    const bool jpg = bytes.size() > 3 && uint8_t(bytes[0]) == 0xff && uint8_t(bytes[1]) == 0xd8;
    const std::string ext = png ? ".png" : jpg ? ".jpg" : ".bin";
    std::string safe = entry;
    for (char& c : safe)
      if (c == '/' || c == '\\' || c == ':') c = '_';
    const fs::path out = dir_ / (safe + ext);
    std::error_code ec;
    if (!fs::exists(out, ec)) {
      fs::create_directories(dir_, ec);
      writeTextAtomic(out, bytes);  // bytes as they are
    }
    TextureRef t;
    if (png || jpg) t.file = t.path = out.string();
    return done_[entry] = t;
  }

 private:
  std::string path_;
  std::unique_ptr<ZipArchive> zip_;
  std::string checksum_;
  fs::path dir_;
  std::map<std::string, TextureRef> done_;
};

class Builder {
 public:
  Builder(const Sh3dHome& home, const Sh3dImportOptions& opt, Sh3dImportReport& report)
      : home_(home), opt_(opt), report_(report), files_(home.path) {
    scene_.name = fs::path(home.path).stem().string();
  }

  Scene build() {
    levelFilter();
    rooms();
    walls();
    furniture();
    if (opt_.room_lights) roomLights();
    if (opt_.daylight) daylight();
    scene_.validate(home_.path);
    return std::move(scene_);
  }

 private:
  bool shown(int level) const { return level < 0 || level_shown_[size_t(level)]; }

  void levelFilter() {
    level_shown_.assign(home_.levels.size(), true);
    min_elevation_ = 0;
    for (size_t i = 0; i < home_.levels.size(); ++i) {
      level_shown_[i] = opt_.hidden_levels || home_.levels[i].visible;
      report_.levels += level_shown_[i];
      min_elevation_ = std::min(min_elevation_, home_.levels[i].elevation_cm / 100.0);
    }
  }

  int material(const std::string& kind, const Sh3dColor& color,
               const std::optional<Sh3dTexture>& texture, const Vec3f& fallback) {
    std::string key = kind;
    if (color) key += fmt::format("#{:.3f},{:.3f},{:.3f}", color->x(), color->y(), color->z());
    if (texture)
      key += fmt::format("@{}:{}x{}", texture->image, texture->width_cm, texture->height_cm);
    auto it = materials_.find(key);
    if (it != materials_.end()) return it->second;
    Material m;
    m.id = fmt::format("{}_{}", kind, materials_.size());
    m.albedo = color ? linear(*color) : fallback;
    if (texture) {
      m.albedo_texture = files_.texture(texture->image);
      if (!m.albedo_texture.empty()) {
        if (!color) m.albedo = Vec3f::Ones();
        m.uv_scale = Vec2f(float(100.0 / texture->width_cm), float(100.0 / texture->height_cm));
      }
    }
    scene_.materials.push_back(m);
    return materials_[key] = int(scene_.materials.size()) - 1;
  }

  /// Adds a mesh in world coordinates as one object.
  void addObject(const std::string& name, Mesh mesh, int material, int nyu40, int instance,
                 const std::string& kind, int room = -1) {
    if (mesh.triangles.empty()) return;
    mesh.id = fmt::format("{}#{}", name, scene_.meshes.size());
    mesh.source.kind = MeshSource::Kind::Inline;
    scene_.meshes.push_back(std::move(mesh));
    Object o = Object::make(name, int(scene_.meshes.size()) - 1, material, Mat4::Identity(), nyu40,
                            instance);
    o.kind = kind;
    o.room = room;
    scene_.objects.push_back(std::move(o));
  }

  // ---- rooms ----
  /// Rooms for the levels that have walls and no room (some homes draw walls only): the
  /// faces their centre lines close, each line lengthened by the wall's thickness at both
  /// ends so walls that stop at another's side still close a face.
  std::vector<Sh3dRoom> roomsFromWalls() const {
    std::map<int, std::vector<std::array<V2, 2>>> lines;  // world metres, per level
    std::set<int> with_rooms;
    for (const Sh3dRoom& r : home_.rooms) with_rooms.insert(r.level);
    for (const Sh3dWall& w : home_.walls) {
      if (with_rooms.count(w.level) || !shown(w.level)) continue;
      const WallShape s = rawWallShape(w);
      const size_t n = s.centre.size();
      for (size_t k = 0; k + 1 < n; ++k) {
        const V2 d = (s.centre[k + 1] - s.centre[k]).normalized() * s.thickness;
        lines[w.level].push_back({V2(s.centre[k] - d * (k == 0 ? 1.0 : 0.0)),
                                  V2(s.centre[k + 1] + d * (k + 2 == n ? 1.0 : 0.0))});
      }
    }
    std::vector<Sh3dRoom> out;
    for (const auto& [level, segs] : lines)
      for (const Ring& face : enclosedFaces(segs, 1.0)) {  // at least 1 m^2
        Sh3dRoom r;
        r.id = fmt::format("room from walls {}", out.size() + 1);
        r.level = level;
        for (const V2& p : face) r.points.push_back(plan(p));
        out.push_back(r);
      }
    return out;
  }

  void rooms() {
    std::vector<Sh3dRoom> all = home_.rooms;
    const std::vector<Sh3dRoom> derived = roomsFromWalls();
    report_.rooms_from_walls = derived.size();
    all.insert(all.end(), derived.begin(), derived.end());
    for (const Sh3dRoom& r : all) {
      if (!shown(r.level)) continue;
      Ring ring;
      for (const V2& p : r.points) ring.push_back(world(p));
      if (signedArea2(ring) < 0) std::reverse(ring.begin(), ring.end());
      const auto tris = triangulatePolygon(ring);
      if (tris.empty()) continue;
      Room room;
      room.id = r.name.empty() ? r.id : r.name;
      std::string type = sh3dRoomType(r.name);
      if (type.empty()) {
        if (!r.name.empty()) report_.room_names_untyped.push_back(r.name);
        type = "living_room";
      }
      room.type = type;
      room.outline = ring;
      room.floor_z = home_.levelElevation(r.level) / 100.0;
      room.ceiling_z = room.floor_z + home_.levelHeight(r.level) / 100.0;
      scene_.rooms.push_back(room);
      room_level_.push_back(r.level);
      const int room_index = int(scene_.rooms.size()) - 1;
      ++report_.rooms;
      auto slab = [&](double z, bool up) {
        Mesh m;
        for (const auto& t : tris) {
          const uint32_t base = uint32_t(m.positions.size());
          for (const V2& p : t) {
            m.positions.emplace_back(float(p.x()), float(p.y()), float(z));
            m.uvs.emplace_back(float(p.x()), float(p.y()));
            m.normals.emplace_back(0.f, 0.f, up ? 1.f : -1.f);
          }
          m.triangles.push_back(up ? Tri(base, base + 1, base + 2) : Tri(base, base + 2, base + 1));
        }
        return m;
      };
      if (r.floor_visible)
        addObject(fmt::format("floor {}", room.id), slab(room.floor_z, true),
                  material("floor", r.floor_color, r.floor_texture, Vec3f(0.45f, 0.42f, 0.38f)), 2,
                  nextInstance(), "floor", room_index);
      if (r.ceiling_visible)
        addObject(fmt::format("ceiling {}", room.id), slab(room.ceiling_z, false),
                  material("ceiling", r.ceiling_color, r.ceiling_texture, Vec3f(0.8f, 0.8f, 0.8f)),
                  22, nextInstance(), "ceiling", room_index);
    }
  }

  // ---- walls ----
  /// A door or window's cut-out, as points in plan (world metres) and heights.
  struct Opening {
    Ring footprint;                           ///< world xy
    std::vector<std::vector<Vec3>> outlines;  ///< the cut-out shape on the piece's front plane
    double z0 = 0, z1 = 0;
  };

  std::vector<Opening> openings() {
    std::vector<Opening> out;
    for (const Sh3dPiece& p : home_.pieces) {
      if (p.kind != Sh3dPieceKind::DoorOrWindow || !p.visible || !shown(p.level)) continue;
      Opening o;
      const V2 c = world(V2(p.x_cm, p.y_cm));
      const V2 wdir(std::cos(-p.angle), std::sin(-p.angle));  // the piece's width axis
      const V2 ddir(-wdir.y(), wdir.x());                     // towards its back
      const double w = p.width_cm / 100, d = p.depth_cm / 100, h = p.height_cm / 100;
      o.footprint = {c - wdir * w / 2 - ddir * d / 2, c + wdir * w / 2 - ddir * d / 2,
                     c + wdir * w / 2 + ddir * d / 2, c - wdir * w / 2 + ddir * d / 2};
      o.z0 = (home_.levelElevation(p.level) + p.elevation_cm) / 100;
      o.z1 = o.z0 + h;
      std::vector<Outline2d> shapes;
      if (!p.cut_out_shape.empty())
        shapes = parseSvgPath(p.cut_out_shape, 0.01, home_.path,
                              fmt::format("Home.xml <doorOrWindow id='{}'> cutOutShape", p.id));
      if (shapes.empty()) shapes = {{V2(0, 0), V2(1, 0), V2(1, 1), V2(0, 1)}};
      for (const auto& s : shapes) {
        std::vector<Vec3> pts;
        for (const V2& q : s) {
          const double sx = p.mirrored ? 1 - q.x() : q.x();
          const V2 xy = c + wdir * (sx - 0.5) * w;
          pts.emplace_back(xy.x(), xy.y(), o.z0 + (1 - q.y()) * h);
        }
        o.outlines.push_back(pts);
      }
      out.push_back(o);
    }
    return out;
  }

  void walls() {
    std::vector<WallShape> shapes;
    for (const Sh3dWall& w : home_.walls) {
      WallShape s = rawWallShape(w);
      const double level_z = home_.levelElevation(w.level) / 100;
      // walls of an upper level reach down through its floor, closing the slab's edge
      const double below = w.level >= 0 && level_z > min_elevation_ + 1e-6
                               ? home_.levels[size_t(w.level)].floor_thickness_cm / 100
                               : 0.0;
      s.z0 = level_z - below;
      const double h = w.height_cm.value_or(home_.wall_height_cm) / 100;
      s.h_start = h + below;
      s.h_end = w.height_at_end_cm.value_or(h * 100) / 100 + below;
      shapes.push_back(s);
    }
    joinWalls(home_.walls, shapes);
    const std::vector<Opening> holes = openings();
    for (size_t i = 0; i < home_.walls.size(); ++i) {
      const Sh3dWall& w = home_.walls[i];
      if (!shown(w.level)) continue;
      ++report_.walls;
      const WallShape& s = shapes[i];
      const int left_mat =
          material("wall", w.left_color, w.left_texture, Vec3f(0.75f, 0.74f, 0.72f));
      const int right_mat =
          material("wall", w.right_color, w.right_texture, Vec3f(0.75f, 0.74f, 0.72f));
      Mesh left, right, rest;
      for (size_t k = 0; k + 1 < s.centre.size(); ++k) {
        const V2 foot[4] = {s.left[k], s.left[k + 1], s.right[k + 1], s.right[k]};
        const Ring foot_ring(foot, foot + 4);
        const double top_max = std::max(s.height(s.along[k]), s.height(s.along[k + 1]));
        std::vector<const Opening*> mine;
        for (const Opening& o : holes)
          if (o.z1 > s.z0 + 1e-3 && o.z0 < s.z0 + top_max - 1e-3 &&
              intersectionArea(o.footprint, foot_ring) > 1e-6)
            mine.push_back(&o);
        report_.holes += mine.size();
        const V2 nl = V2(s.centre[k + 1] - s.centre[k]).normalized();
        const V2 normal(-nl.y(), nl.x());
        face(left, s, k, s.left, mine, normal, s.thickness);
        face(right, s, k, s.right, mine, -normal, 0.0);
        // top
        const double ha = s.height(s.along[k]), hb = s.height(s.along[k + 1]);
        quad(rest, Vec3(foot[0].x(), foot[0].y(), s.z0 + ha),
             Vec3(foot[1].x(), foot[1].y(), s.z0 + hb), Vec3(foot[2].x(), foot[2].y(), s.z0 + hb),
             Vec3(foot[3].x(), foot[3].y(), s.z0 + ha), Vec3::UnitZ());
      }
      // open ends
      auto cap = [&](const V2& l, const V2& r, double h, const V2& out_dir) {
        quad(rest, Vec3(l.x(), l.y(), s.z0), Vec3(r.x(), r.y(), s.z0), Vec3(r.x(), r.y(), s.z0 + h),
             Vec3(l.x(), l.y(), s.z0 + h), Vec3(out_dir.x(), out_dir.y(), 0));
      };
      const size_t n = s.centre.size();
      if (w.wall_at_start < 0)
        cap(s.left[0], s.right[0], s.h_start, V2(s.centre[0] - s.centre[1]).normalized());
      if (w.wall_at_end < 0)
        cap(s.left[n - 1], s.right[n - 1], s.h_end,
            V2(s.centre[n - 1] - s.centre[n - 2]).normalized());
      const int instance = nextInstance();
      const std::string name = fmt::format("wall {}", w.id);
      addObject(name + " left", std::move(left), left_mat, 1, instance, "wall");
      addObject(name + " right", std::move(right), right_mat, 1, instance, "wall");
      // the top in its own colour where the home gives one (topColor: Sweet Home 3D's "top
      // in 3D view"), else the left side's
      const int top_mat =
          w.top_color ? material("wall", w.top_color, std::nullopt, Vec3f::Zero()) : left_mat;
      addObject(name + " top", std::move(rest), top_mat, 1, instance, "wall");
    }
  }

  /// Appends a planar quad (a, b, c, d) facing `normal` as two triangles (degenerate ones
  /// dropped).
  static void quad(Mesh& m, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                   const Vec3& normal) {
    tri(m, a, b, c, normal);
    tri(m, a, c, d, normal);
  }

  static void tri(Mesh& m, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal) {
    const Vec3 n = (b - a).cross(c - a);
    if (n.norm() < 1e-12) return;
    const uint32_t base = uint32_t(m.positions.size());
    for (const Vec3* p : {&a, &b, &c}) {
      m.positions.push_back(p->cast<float>());
      // wall textures tile by metres along the wall and up
      const double u =
          std::abs(normal.z()) > 0.5 ? p->x() : p->x() * -normal.y() + p->y() * normal.x();
      const double v = std::abs(normal.z()) > 0.5 ? p->y() : p->z();
      m.uvs.emplace_back(float(u), float(v));
    }
    if (n.dot(normal) >= 0)
      m.triangles.emplace_back(base, base + 1, base + 2);
    else
      m.triangles.emplace_back(base, base + 2, base + 1);
  }

  /// One side of piece k of a wall: the quad between side points k and k + 1 up to the
  /// (sloped) top, minus the openings, facing `normal`; with `depth` > 0 also the reveals,
  /// from this side to the other through the wall.
  void face(Mesh& m, const WallShape& s, size_t k, const std::vector<V2>& side,
            const std::vector<const Opening*>& openings, const V2& normal, double depth) {
    const V2 a = side[k], b = side[k + 1];
    const double len = (b - a).norm();
    if (len < 1e-6) return;
    const V2 e = (b - a) / len;
    // the share of the wall's length at a point of this side, for its height
    const double fa = s.along[k], fb = s.along[k + 1];
    const double z0 = s.z0, ha = s.height(fa), hb = s.height(fb);
    const Ring outline = {V2(0, z0), V2(len, z0), V2(len, z0 + hb), V2(0, z0 + ha)};
    std::vector<Ring> holes;
    for (const Opening* o : openings)
      for (const auto& pts : o->outlines) {
        Ring r;
        for (const Vec3& p : pts) r.emplace_back((V2(p.x(), p.y()) - a).dot(e), p.z());
        holes.push_back(r);
      }
    auto to3 = [&](const V2& uv) {
      const V2 xy = a + e * uv.x();
      return Vec3(xy.x(), xy.y(), uv.y());
    };
    const Vec3 n3(normal.x(), normal.y(), 0);
    // a door's edge on the wall's bottom gets no reveal
    const FaceWithHoles f = faceWithHoles(outline, holes, depth > 0, z0);
    for (const auto& t : f.triangles) tri(m, to3(t[0]), to3(t[1]), to3(t[2]), n3);
    for (const RevealEdge& r : f.reveals) {
      const Vec3 p3 = to3(r.a), q3 = to3(r.b);
      const Vec3 through = -n3 * depth;
      const Vec3 inward(e.x() * r.inward.x(), e.y() * r.inward.x(), r.inward.y());
      quad(m, p3, q3, q3 + through, p3 + through, inward);
    }
  }

  // ---- furniture ----
  void furniture() {
    const bool any = std::any_of(home_.pieces.begin(), home_.pieces.end(),
                                 [&](const Sh3dPiece& p) { return p.visible && shown(p.level); });
    report_.hidden += any ? 0 : home_.pieces.size();
    if (!any) return;  // (and the archive is not needed)
    FurnitureCatalog cat;
    cat.path = home_.path;
    cat.id = "sh3d:" + scene_.name;
    cat.name = home_.name.empty() ? scene_.name : home_.name;
    cat.checksum = "home-" + files_.checksum();
    cat.license = home_.license;
    std::shared_ptr<const CatalogLibrary> library;
    try {
      if (catalogsAvailable(opt_.catalog_dir)) library = catalogLibrary(opt_.catalog_dir);
    } catch (const InputError&) {
      library = nullptr;  // labels then come from names alone
    }
    int index = 0;
    for (const Sh3dPiece& p : home_.pieces) {
      ++index;
      if (!p.visible || !shown(p.level)) {
        ++report_.hidden;
        continue;
      }
      CatalogPiece cp;
      cp.index = index;
      cp.id = p.id.empty() ? fmt::format("piece#{}", index) : p.id;
      cp.name = p.name;
      cp.creator = p.creator;
      cp.license = p.license.empty() ? home_.license : p.license;
      cp.model = p.model;
      cp.multi_part = p.model.find('/') != std::string::npos;
      cp.width_cm = p.width_cm;
      cp.depth_cm = p.depth_cm;
      cp.height_cm = p.height_cm;
      cp.elevation_cm = p.elevation_cm;
      cp.model_rotation = p.model_rotation;
      cp.movable = p.movable;
      cp.back_face_shown = p.back_face_shown;
      if (library && !p.catalog_id.empty()) {
        const auto [c, known] = library->find(p.catalog_id);
        if (known) cp.category = known->category;
      }
      if (cp.category.empty())
        cp.category = p.kind == Sh3dPieceKind::DoorOrWindow ? "Doors and windows"
                      : p.kind == Sh3dPieceKind::Light      ? "Lights"
                                                            : "";
      if (p.kind == Sh3dPieceKind::DoorOrWindow) {
        CatalogDoorOrWindow dw;
        dw.wall_thickness_cm = p.wall_thickness * p.depth_cm;
        dw.wall_distance_cm = p.wall_distance * p.depth_cm;
        cp.door_or_window = dw;
      }
      for (const auto& ls : p.light_sources) {
        CatalogLightSource l;
        l.position_cm = Eigen::Vector3d(ls.position.x() * p.width_cm, ls.position.y() * p.depth_cm,
                                        ls.position.z() * p.height_cm);
        l.color = ls.color;
        l.diameter_cm = ls.diameter * p.width_cm;
        cp.lights.push_back(l);
      }
      try {
        place(p, loadCatalogModel(cat, cp), size_t(index - 1));
      } catch (const NoSurfaceError&) {
        // A light source without a body (Sweet Home 3D's "White light source" is drawn as
        // lines in the plan only) still lights; any other piece whose model has no surface
        // is left out and counted.
        if (p.kind == Sh3dPieceKind::Light && !p.light_sources.empty())
          bareLights(p, cp);
        else
          ++report_.empty_models;
      }
    }
  }

  /// Model frame -> world for piece `p`. Sweet Home 3D turns a piece by pitch (about its width
  /// axis) and roll (about its depth axis) around its centre, then by angle (clockwise on
  /// screen, so -angle about our z): world = yaw tilt (v - centre) + target, the turned box
  /// centred on (x, y) with its lowest point (of `meshes`, the model's, when tilted) at the
  /// elevation.
  Mat4 placement(const Sh3dPiece& p, const std::vector<Mesh>* meshes) const {
    const Vec3 centre(0, 0, p.height_cm / 200);
    const Mat3 tilt =
        (Eigen::AngleAxisd(p.roll, Vec3::UnitY()) * Eigen::AngleAxisd(-p.pitch, Vec3::UnitX()))
            .toRotationMatrix();
    const Mat3 yaw = Eigen::AngleAxisd(-p.angle, Vec3::UnitZ()).toRotationMatrix();
    double lo = -centre.z();
    if ((p.pitch != 0 || p.roll != 0) && meshes) {
      lo = std::numeric_limits<double>::infinity();
      for (const Mesh& m : *meshes)
        for (const auto& v : m.positions)
          lo = std::min(lo, (tilt * (v.cast<double>() - centre)).z());
    }
    const V2 c = world(V2(p.x_cm, p.y_cm));
    const double bottom = (home_.levelElevation(p.level) + p.elevation_cm) / 100;
    Mat4 T = Mat4::Identity();
    T.block<3, 3>(0, 0) = yaw * tilt;
    T.block<3, 1>(0, 3) = Vec3(c.x(), c.y(), bottom - lo) - yaw * tilt * centre;
    return T;
  }

  /// A piece's bulbs (model frame) placed by T and dimmed or brightened by its power: Sweet
  /// Home 3D's renderer gives a light 5 power^2 / r^2, and its default power is 0.5.
  void addLights(const Sh3dPiece& p, std::vector<Light> lights, const Mat4& T,
                 const std::string& uid, const std::string& object) {
    const double scale = (p.power / 0.5) * (p.power / 0.5);
    for (Light& l : lights) {
      ++report_.lights;
      l.position = (T * l.position.homogeneous()).head<3>();
      l.radius *= float(std::cbrt(std::abs(T.block<3, 3>(0, 0).determinant())));  // as the model
      l.intensity = float(l.intensity * scale);
      l.on = p.power > 0;
      l.object = object;
      l.name = fmt::format("{} {}", uid, l.name);
      scene_.lights.push_back(l);
    }
  }

  void place(const Sh3dPiece& p, CatalogModel model, size_t piece_index) {
    ++report_.pieces;
    report_.doors_windows += p.kind == Sh3dPieceKind::DoorOrWindow;
    if (model.label.rule.rfind("default", 0) == 0) ++report_.unlabelled;
    Scene& parts = model.parts;
    // mirrored along the width, baked into the mesh (a mirroring transform would turn the
    // triangles inside out)
    if (p.mirrored)
      for (Mesh& m : parts.meshes) {
        for (auto& v : m.positions) v.x() = -v.x();
        for (auto& n : m.normals) n.x() = -n.x();
        for (auto& t : m.triangles) std::swap(t[1], t[2]);
      }
    if (p.mirrored)
      for (Light& l : parts.lights) l.position.x() = -l.position.x();
    const Mat4 T = placement(p, &parts.meshes);
    const V2 c = world(V2(p.x_cm, p.y_cm));

    const std::string uid = fmt::format("{} {}", p.name.empty() ? "piece" : p.name, ++piece_count_);
    // materials: the piece's colour, then per-material overrides
    std::vector<int> mat_index(parts.materials.size());
    for (size_t k = 0; k < parts.materials.size(); ++k) {
      Material m = parts.materials[k];
      const std::string mtl = m.catalog_material;
      auto recolour = [&](const Eigen::Vector3f& srgb) {
        m.albedo = linear(srgb);
        m.albedo_texture = {};
        if (m.type == MaterialType::Conductor) m.type = MaterialType::Plastic;
      };
      if (p.color) recolour(*p.color);
      for (const Sh3dMaterial& o : p.materials)
        if (o.name == mtl && o.color) recolour(*o.color);
      m.catalog_piece.clear();
      m.catalog_material.clear();
      m.id = fmt::format("{}/{}", uid, mtl.empty() ? fmt::format("m{}", k) : mtl);
      scene_.materials.push_back(m);
      mat_index[k] = int(scene_.materials.size()) - 1;
    }
    const int instance = nextInstance();
    report_.piece_instances.emplace_back(piece_index, instance);
    const int room = roomAt(c, p.level);
    const size_t first = scene_.objects.size();
    for (const Object& o : parts.objects) {
      Mesh mesh = parts.meshes[size_t(o.mesh)];
      mesh.id = fmt::format("{}#{}", uid, scene_.meshes.size());
      mesh.source = MeshSource{};
      mesh.source.kind = MeshSource::Kind::Inline;
      scene_.meshes.push_back(std::move(mesh));
      Object obj = o;
      obj.name = fmt::format("{} {}", uid, o.name);
      obj.mesh = int(scene_.meshes.size()) - 1;
      obj.material = mat_index[size_t(o.material)];
      obj.T_world_object = T * o.T_world_object;
      obj.instance = instance;
      obj.room = room;
      if (obj.physics) obj.physics->movable = obj.physics->movable && p.movable;
      scene_.objects.push_back(std::move(obj));
    }
    if (scene_.objects.size() == first) return;
    addLights(p, parts.lights, T, uid, scene_.objects[first].name);
  }

  /// The light sources of a light whose model draws nothing, as point lights.
  void bareLights(const Sh3dPiece& p, const CatalogPiece& cp) {
    ++report_.pieces;
    const std::string uid = fmt::format("{} {}", p.name.empty() ? "light" : p.name, ++piece_count_);
    addLights(p, lampLights(cp, labelCatalogPiece(cp).category), placement(p, nullptr), uid, "");
  }

  /// A ceiling light in every room no lamp of the home lights (many homes have none: Sweet
  /// Home 3D's 3D view lights them with an ambient light): a point light 25 cm under the
  /// ceiling, at a point well inside the room, of 0.35 W/sr per m^2 of floor (what the
  /// procedural apartments' lamps give their rooms: 3-8 W/sr per 12-20 m^2), 1.5 to 8 W/sr.
  void roomLights() {
    for (size_t i = 0; i < scene_.rooms.size(); ++i) {
      const Room& r = scene_.rooms[i];
      const bool lit = std::any_of(scene_.lights.begin(), scene_.lights.end(), [&](const Light& l) {
        return (l.type == LightType::Point || l.type == LightType::Spot) &&
               l.position.z() > r.floor_z && l.position.z() < r.ceiling_z + 0.05 &&
               r.contains(l.position.x(), l.position.y());
      });
      if (lit) continue;
      V2 at = V2::Zero();
      for (const auto& p : r.outline) at += p;
      at /= double(r.outline.size());
      if (!r.contains(at.x(), at.y())) {  // a concave room: the middle of its largest triangle
        double best = -1;
        for (const auto& t : triangulatePolygon(r.outline)) {
          const double a = signedArea2({t[0], t[1], t[2]});
          if (a > best) best = a, at = (t[0] + t[1] + t[2]) / 3;
        }
      }
      Light l;
      l.name = fmt::format("ceiling light {} (added)", r.id);
      l.type = LightType::Point;
      l.position = Vec3(at.x(), at.y(), r.ceiling_z - 0.25);
      l.temperature_k = 3000.f;
      l.intensity = float(std::clamp(0.35 * r.area(), 1.5, 8.0));
      scene_.lights.push_back(l);
      ++report_.added_lights;
    }
  }

  int roomAt(const V2& xy, int level) const {
    for (size_t i = 0; i < scene_.rooms.size(); ++i)
      if (room_level_[i] == level && scene_.rooms[i].contains(xy.x(), xy.y())) return int(i);
    return -1;
  }

  // ---- daylight ----
  void daylight() {
    SunTime when;
    const int64_t ms = home_.observer ? home_.observer->time_ms : 0;
    const std::time_t secs =
        ms > 0 ? std::time_t(ms / 1000) : std::time_t(1782043200);  // 2026-06-21 12:00 UTC
    std::tm utc{};
    gmtime_r(&secs, &utc);
    when.year = utc.tm_year + 1900;
    when.month = utc.tm_mon + 1;
    when.day = utc.tm_mday;
    when.hour = utc.tm_hour + utc.tm_min / 60.0 + utc.tm_sec / 3600.0;
    when.latitude_deg = std::clamp(home_.compass.latitude * 180 / kPi, -89.0, 89.0);
    when.longitude_deg = std::remainder(home_.compass.longitude * 180 / kPi, 360.0);
    // the camera's time is a local clock time in the compass's time zone; its offset is taken
    // from the longitude (the zone database is not consulted)
    when.utc_offset_h = std::round(when.longitude_deg / 15.0);
    // north is drawn clockwise on screen from the plan's up; ours counter-clockwise from +y
    when.north_deg = -home_.compass.north_direction * 180 / kPi;
    SunAngles sun = sunPosition(when);
    if (sun.elevation < 15 * kPi / 180) {
      // a home saved at night (or at dawn) gets the afternoon of the same day: 15:00 local
      // solar time, so that its windows light it
      when.hour = 15.0 - when.longitude_deg / 15.0;
      when.hour = std::fmod(when.hour + 24.0, 24.0);
      sun = sunPosition(when);
    }
    const Vec3 to_sun = sunDirectionWorld(sun, when.north_deg);
    const auto [sky, sun_light] = daylightLights(to_sun, 3.f);
    scene_.lights.push_back(sky);
    if (sun.elevation > 0) scene_.lights.push_back(sun_light);  // (polar night)
    // the ground, under the lowest floor, 30 m around the home
    const auto [lo, hi] = scene_.bounds();
    const double z = min_elevation_ - 0.05;
    Mesh g;
    const Vec3 a(lo.x() - 30, lo.y() - 30, z), b(hi.x() + 30, hi.y() + 30, z);
    quad(g, a, Vec3(b.x(), a.y(), z), b, Vec3(a.x(), b.y(), z), Vec3::UnitZ());
    const int mat =
        material("ground", Eigen::Vector3f(0.35f, 0.42f, 0.25f), std::nullopt, Vec3f::Zero());
    addObject("ground", std::move(g), mat, 38, nextInstance(), "ground");
  }

  int nextInstance() { return ++instance_; }

  const Sh3dHome& home_;
  const Sh3dImportOptions& opt_;
  Sh3dImportReport& report_;
  HomeFiles files_;
  Scene scene_;
  std::vector<bool> level_shown_;
  std::vector<int> room_level_;
  double min_elevation_ = 0;
  std::map<std::string, int> materials_;
  int instance_ = 0, piece_count_ = 0;
};

}  // namespace

std::string sh3dRoomType(const std::string& name) {
  std::string s;
  for (char c : name) s += char(std::tolower(static_cast<unsigned char>(c)));
  auto has = [&](std::initializer_list<const char*> words) {
    for (const char* w : words)
      if (s.find(w) != std::string::npos) return true;
    return false;
  };
  if (has({"master bath", "ensuite", "en-suite"})) return "master_bathroom";
  if (has({"bath", "wc", "toilet", "shower", "salle de bain", "bagno", "bad", "baño", "卫生间",
           "浴室", "厕所", "洗手间"}))
    return "bathroom";
  if (has({"master bed", "parent", "主卧", "matrimoniale"})) return "master_bedroom";
  if (has({"kid", "child", "nursery", "enfant", "bambin", "kinder", "儿童"})) return "kids_room";
  if (has({"guest", "elder", "老人"})) return "elderly_room";
  if (has({"bed", "chambre", "camera", "letto", "schlaf", "dormitorio", "卧", "房间"}))
    return "second_bedroom";
  if (has({"kitchen", "cuisine", "cucina", "küche", "kuche", "cocina", "厨"})) return "kitchen";
  if (has({"dining", "salle à manger", "sala da pranzo", "esszimmer", "comedor", "餐"}))
    return "dining_room";
  if (has({"living", "lounge", "salon", "séjour", "sejour", "soggiorno", "salone", "wohn", "sala",
           "family", "客厅", "起居"}))
    return "living_room";
  if (has({"study", "office", "bureau", "studio", "arbeits", "despacho", "书房"})) return "study";
  if (has({"balcon", "terrace", "terrasse", "terrazzo", "veranda", "阳台", "露台"}))
    return "balcony";
  if (has({"hall", "corridor", "couloir", "landing", "stair", "corridoio", "disimpegno", "flur",
           "diele", "pasillo", "走廊", "过道"}))
    return "corridor";
  if (has({"entr", "foyer", "ingresso", "eingang", "玄关", "门厅"})) return "entrance";
  if (has({"storage", "attic", "garage", "cellar", "basement", "ripostiglio", "cantina", "abstell",
           "keller", "储", "车库"}))
    return "storage";
  if (has({"closet", "cloak", "dressing", "wardrobe", "guardaroba", "衣帽"})) return "cloakroom";
  if (has({"laundry", "buanderie", "lavanderia", "wasch", "洗衣"})) return "laundry";
  return "";
}

std::string Sh3dImportReport::summary() const {
  std::vector<std::string> parts;
  if (hidden > 0)
    parts.push_back(fmt::format("{} piece(s) left out (invisible, or on a hidden level)", hidden));
  if (added_lights > 0)
    parts.push_back(fmt::format("{} room(s) without a lamp got a ceiling light", added_lights));
  if (rooms_from_walls > 0)
    parts.push_back(
        fmt::format("{} room(s) made from the faces the walls close (the home draws "
                    "walls without rooms; no floor or ceiling otherwise)",
                    rooms_from_walls));
  if (empty_models > 0)
    parts.push_back(
        fmt::format("{} piece(s) left out: their models draw no surface", empty_models));
  if (!room_names_untyped.empty()) {
    parts.push_back(fmt::format("{} room name(s) match no room type and became living rooms ({})",
                                room_names_untyped.size(), listNames(room_names_untyped, 5)));
  }
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

Scene sh3dToScene(const Sh3dHome& home, const Sh3dImportOptions& opt, Sh3dImportReport* report) {
  Sh3dImportReport local;
  Builder b(home, opt, report ? *report : local);
  return b.build();
}

Scene importSh3d(const std::string& path, const Sh3dImportOptions& opt, Sh3dImportReport* report) {
  return sh3dToScene(readSh3dHome(path), opt, report);
}

std::vector<Sh3dView> sh3dViews(const Sh3dHome& home) {
  std::vector<Sh3dCamera> cams = home.video_path;
  if (cams.empty()) cams = home.stored_cameras;
  if (cams.empty() && home.observer) cams.push_back(*home.observer);
  std::vector<Sh3dView> out;
  for (const Sh3dCamera& c : cams) {
    // Sweet Home 3D looks along (-sin yaw, cos yaw) in the plan (y down) when level, down by
    // pitch (positive pitch looks down)
    const V2 plan_dir(-std::sin(c.yaw), std::cos(c.yaw));
    const Vec3 dir(plan_dir.x() * std::cos(c.pitch), -plan_dir.y() * std::cos(c.pitch),
                   -std::sin(c.pitch));
    const V2 xy = world(V2(c.x_cm, c.y_cm));
    const Vec3 eye(xy.x(), xy.y(), c.z_cm / 100);
    Sh3dView v;
    v.name = c.name.empty() ? c.attribute : c.name;
    v.T_world_camera = Pose::lookAt(eye, eye + dir, Vec3::UnitZ());
    v.hfov_rad = c.field_of_view;
    out.push_back(v);
  }
  return out;
}

}  // namespace inet
