#include "scene/mitsuba_importer.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "scene/assimp_importer.h"
#include "scene/label_map.h"
#include "scene/mitsuba_materials.h"
#include "scene/mitsuba_xml.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using mitsuba::Document;
using mitsuba::MaterialContext;
using mitsuba::Notes;
using mitsuba::Plugin;
using mitsuba::Slot;

constexpr double kPi = 3.14159265358979323846;
/// Tessellation of the shapes we have no primitive for (disk, cylinder, emissive sphere).
constexpr int kSegments = 64;

/// The rotation that turns a file's up axis into +Z (x -> x, y -> z, z -> -y for 'y').
Mat3 upRotation(char up) {
  Mat3 r = Mat3::Identity();
  if (up == 'y') r << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  return r;
}

/// The nearest rotation to a matrix's linear part (polar decomposition); `mirrored` tells
/// whether it had to drop a reflection.
Mat3 nearestRotation(const Mat3& m, bool& mirrored) {
  Eigen::JacobiSVD<Mat3> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 d = Mat3::Identity();
  mirrored = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0;
  if (mirrored) d(2, 2) = -1;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

/// Reverses every triangle's winding and every normal (Mitsuba's flip_normals).
void flipMesh(Mesh& mesh) {
  for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
  for (Vec3f& n : mesh.normals) n = -n;
}

/// Applies an affine map to a mesh's vertices (normals by its inverse transpose), keeping the
/// winding outward when the map mirrors.
void bakeTransform(Mesh& mesh, const Mat4& T) {
  const Mat3 N = T.block<3, 3>(0, 0).inverse().transpose();
  for (Vec3f& p : mesh.positions) p = (T * p.cast<double>().homogeneous()).head<3>().cast<float>();
  for (Vec3f& n : mesh.normals) n = (N * n.cast<double>()).normalized().cast<float>();
  if (T.block<3, 3>(0, 0).determinant() < 0)
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
}

/// Mitsuba's disk: radius 1 in the z = 0 plane, normal +z, as a fan.
Mesh diskMesh() {
  Mesh m;
  m.positions.emplace_back(0.f, 0.f, 0.f);
  m.uvs.emplace_back(0.f, 0.f);
  for (int k = 0; k < kSegments; ++k) {
    const double a = 2.0 * kPi * k / kSegments;
    m.positions.emplace_back(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.f);
    m.uvs.emplace_back(1.f, static_cast<float>(k) / kSegments);
    m.triangles.emplace_back(0, 1 + k, 1 + (k + 1) % kSegments);
  }
  m.normals.assign(m.positions.size(), Vec3f::UnitZ());
  return m;
}

/// Mitsuba's cylinder: an open tube of `radius` from p0 to p1, normals outward.
Mesh tubeMesh(const Vec3& p0, const Vec3& p1, double radius) {
  const Vec3 axis = (p1 - p0).normalized();
  const Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
  Mesh m;
  for (int k = 0; k <= kSegments; ++k) {
    const double a = 2.0 * kPi * k / kSegments;
    const Vec3 radial = std::cos(a) * u + std::sin(a) * v;
    for (int end = 0; end < 2; ++end) {
      m.positions.push_back(((end ? p1 : p0) + radius * radial).cast<float>());
      m.normals.push_back(radial.cast<float>());
      m.uvs.emplace_back(static_cast<float>(k) / kSegments, static_cast<float>(end));
    }
    if (k == kSegments) break;
    const uint32_t a0 = 2 * k, a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
    m.triangles.emplace_back(a0, b0, b1);  // counter-clockwise seen from outside
    m.triangles.emplace_back(a0, b1, a1);
  }
  return m;
}

/// A unit-radius latitude-longitude sphere, for emissive spheres (our analytic spheres are not
/// light-sampled).
Mesh sphereMesh() {
  Mesh m;
  const int rows = kSegments / 2;
  for (int i = 0; i <= rows; ++i)
    for (int k = 0; k <= kSegments; ++k) {
      const double th = kPi * i / rows, ph = 2.0 * kPi * k / kSegments;
      const Vec3f p(static_cast<float>(std::sin(th) * std::cos(ph)),
                    static_cast<float>(std::sin(th) * std::sin(ph)), static_cast<float>(std::cos(th)));
      m.positions.push_back(p);
      m.normals.push_back(p);
      m.uvs.emplace_back(static_cast<float>(k) / kSegments, 1.f - static_cast<float>(i) / rows);
    }
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < kSegments; ++k) {
      const uint32_t a = i * (kSegments + 1) + k, b = a + kSegments + 1;
      if (i > 0) m.triangles.emplace_back(a, b, a + 1);
      if (i + 1 < rows) m.triangles.emplace_back(a + 1, b, b + 1);
    }
  return m;
}

/// An RGB value as a light's colour (max channel 1) and intensity.
void splitColour(const Vec3f& rgb, Light& l) {
  const float peak = rgb.cwiseMax(0.f).maxCoeff();
  l.intensity = peak;
  l.color = peak > 0.f ? Vec3f(rgb.cwiseMax(0.f) / peak) : Vec3f::Ones();
}

struct Importer {
  Importer(const Document& doc, const MitsubaOptions& opt, Notes& notes, const LabelMap& labels,
           int default_id)
      : doc(doc), opt(opt), notes(notes), labels(labels), default_id(default_id),
        R_up(upRotation(opt.up)), materials(scene, notes, opt.read_files) {}

  const Document& doc;
  const MitsubaOptions& opt;
  Notes& notes;
  const LabelMap& labels;
  const int default_id;
  const Mat3 R_up;
  Scene scene;
  MaterialContext materials;
  std::map<std::string, int> mesh_cache;  // file + flags, or primitive key -> mesh index
  std::set<std::string> mesh_ids, object_names, unmatched_seen;
  std::optional<MitsubaSensor> sensor;
  MitsubaReport report;

  /// C = scale * R_up: Mitsuba world -> our world.
  Mat4 C() const {
    Mat4 c = Mat4::Identity();
    c.block<3, 3>(0, 0) = opt.scale * R_up;
    return c;
  }

  void run() {
    for (pugi::xml_node n : doc.topLevel()) {
      const Plugin p(doc, n);
      const std::string tag = p.tag();
      if (tag == "shape") {
        if (p.type() != "shapegroup") addShape(p, Mat4::Identity());
      } else if (tag == "emitter") {
        addEmitter(p);
      } else if (tag == "sensor") {
        addSensor(p);
      } else if (tag == "medium" || tag == "phase" || tag == "subsurface" || tag == "volume") {
        notes.add("participating media not supported: ignored", p.where());
      } else if (tag != "bsdf" && tag != "texture" && tag != "integrator" && tag != "sampler" &&
                 tag != "film" && tag != "rfilter" && tag != "spectrum" && tag != "rgb") {
        notes.add(fmt::format("unknown element <{}> ignored", tag), p.where());
      }
    }
  }

  std::string uniqueName(std::set<std::string>& used, const std::string& base) {
    std::string name = base;
    for (int k = 2; used.count(name); ++k) name = fmt::format("{}_{}", base, k);
    used.insert(name);
    return name;
  }

  /// The mesh a file shape loads, shared by shapes that load it the same way; -1 when files are
  /// not read. Changes Mitsuba makes to the file's data turn it into an inline mesh.
  int fileMesh(const Plugin& s) {
    const std::string file = s.string("filename", "");
    if (file.empty()) s.fail(fmt::format("a {} shape needs a filename", s.type()));
    const bool face_normals = s.boolean("face_normals", false);
    // Mitsuba's images have v = 0 at the top: OBJ files are flipped on load (by default), PLY
    // files not, so PLY texture coordinates are flipped here into ours (v up)
    const bool flip_v = s.type() == "ply" ? true : !s.boolean("flip_tex_coords", true);
    s.ignore("max_smooth_angle");
    if (!opt.read_files) {
      notes.add("shapes that load a mesh file skipped (files are not read in this mode)", file);
      return -1;
    }
    const fs::path path =
        fs::path(file).is_absolute() ? fs::path(file) : fs::path(doc.folderOf(s.node())) / file;
    const std::string key = fmt::format("{}|{}|{}", path.string(), face_normals, flip_v);
    if (auto it = mesh_cache.find(key); it != mesh_cache.end()) return it->second;
    Mesh mesh = loadMeshFile(path.string(), opt.scale, opt.up, "", doc.fileOf(s.node()),
                             doc.where(s.node()));
    bool changed = false;
    if (face_normals && !mesh.normals.empty()) {
      mesh.normals.clear();
      changed = true;
    }
    if (flip_v && !mesh.uvs.empty()) {
      for (Vec2f& uv : mesh.uvs) uv.y() = 1.f - uv.y();
      changed = true;
    }
    if (changed) mesh.source = MeshSource{};  // inline: the file alone no longer gives it
    mesh.id = uniqueName(mesh_ids, path.stem().string());
    scene.meshes.push_back(std::move(mesh));
    return mesh_cache[key] = static_cast<int>(scene.meshes.size()) - 1;
  }

  int sharedMesh(const std::string& key, const std::function<Mesh()>& make) {
    if (auto it = mesh_cache.find(key); it != mesh_cache.end()) return it->second;
    Mesh mesh = make();
    mesh.id = uniqueName(mesh_ids, key.substr(0, key.find(':')));
    scene.meshes.push_back(std::move(mesh));
    return mesh_cache[key] = static_cast<int>(scene.meshes.size()) - 1;
  }

  /// Geometry of shape `s`: the mesh index and the matrix from its vertices to Mitsuba's world
  /// *before* `to_world` (so T_world = C to_world local, or C to_world C^-1 for file meshes, whose
  /// vertices are already in our axes). Returns false for shapes left out.
  bool geometry(const Plugin& s, bool emissive, int& mesh, Mat4& local, bool& file_mesh) {
    const std::string type = s.type();
    local = Mat4::Identity();
    file_mesh = type == "obj" || type == "ply";
    if (file_mesh) {
      mesh = fileMesh(s);
      return mesh >= 0;
    }
    if (type == "rectangle" || type == "cube") {
      const bool quad = type == "rectangle";
      mesh = sharedMesh(quad ? "rectangle" : "cube", [&] {
        return makePrimitive(quad ? "quad" : "box", {}, doc.fileOf(s.node()), doc.where(s.node()));
      });
      local.block<3, 3>(0, 0) = Vec3(2, 2, quad ? 1 : 2).asDiagonal();  // ours are unit-sized
      return true;
    }
    if (type == "disk") {
      mesh = sharedMesh("disk", diskMesh);
      return true;
    }
    if (type == "cylinder") {
      const Vec3 p0 = s.vector("p0", Vec3::Zero()), p1 = s.vector("p1", Vec3::UnitZ());
      const double r = s.number("radius", 1.0);
      if (!((p1 - p0).norm() > 1e-12 && r > 0)) s.fail("a cylinder needs p0 != p1 and radius > 0");
      mesh = sharedMesh(fmt::format("cylinder:{},{},{}:{},{},{}:{}", p0.x(), p0.y(), p0.z(),
                                    p1.x(), p1.y(), p1.z(), r),
                        [&] { return tubeMesh(p0, p1, r); });
      return true;
    }
    if (type == "sphere") {
      const Vec3 centre = s.vector("center", Vec3::Zero());
      const double r = s.number("radius", 1.0);
      if (!(r > 0)) s.fail("a sphere needs radius > 0");
      local.block<3, 1>(0, 3) = centre;
      local.block<3, 3>(0, 0) *= r;
      if (emissive) {
        mesh = sharedMesh("sphere_mesh", sphereMesh);
        return true;
      }
      mesh = sharedMesh("sphere", [&] {
        return makePrimitive("sphere", {{"radius", 1.0}}, doc.fileOf(s.node()), doc.where(s.node()));
      });
      return true;
    }
    notes.add(fmt::format("shape type '{}' not supported: left out", type), s.where());
    return false;
  }

  /// An area emitter nested in a shape: a copy of the material that emits its radiance.
  int emissiveMaterial(const Plugin& s, int material, const std::string& name) {
    auto emitters = s.children("emitter");
    if (emitters.empty()) return material;
    if (emitters.size() > 1) s.fail("a shape takes one emitter");
    const Plugin& e = emitters.front();
    if (e.type() != "area") {
      notes.add(fmt::format("emitter '{}' inside a shape ignored", e.type()), name);
      return material;
    }
    const Slot r = e.slot("radiance", Vec3f::Ones(), notes);
    if (r.texture) notes.add("area emitter with a radiance texture: radiance 1 used", name);
    for (const std::string& p : e.unused())
      notes.add(fmt::format("area emitter property '{}' ignored", p), name);
    Material m = scene.materials[material];
    m.id = materials.uniqueId(m.id + "@" + name);
    m.emission = r.texture ? Vec3f::Ones() : Vec3f(r.value.cwiseMax(0.f));
    scene.materials.push_back(std::move(m));
    return static_cast<int>(scene.materials.size()) - 1;
  }

  /// NYU40 class of the first of `names` a label matches; unmatched ones are reported by the
  /// first non-empty name (else the object's).
  int label(const std::vector<std::string>& names, const std::string& object) {
    for (const std::string& n : names)
      if (!n.empty())
        if (auto id = labels.lookup(n)) return *id;
    std::string shown = object;
    for (auto it = names.rbegin(); it != names.rend(); ++it)
      if (!it->empty()) shown = *it;
    ++report.unmatched_objects;
    if (unmatched_seen.insert(shown).second) report.unmatched_names.push_back(shown);
    return default_id;
  }

  void addShape(const Plugin& s, const Mat4& T_parent, bool in_group = false) {
    if (s.type() == "instance") {
      if (in_group) s.fail("an instance inside a shapegroup (Mitsuba does not nest instances)");
      auto groups = s.children("shape");
      if (groups.size() != 1 || groups.front().type() != "shapegroup")
        s.fail("an instance needs one <ref> to a shapegroup");
      const Mat4 T = T_parent * s.transform("to_world");
      for (const Plugin& child : groups.front().children("shape")) addShape(child, T, true);
      return;
    }
    if (s.type() == "shapegroup") s.fail("a shapegroup inside a shapegroup or shape");
    auto bsdfs = s.children("bsdf");
    if (bsdfs.size() > 1) s.fail("a shape takes one BSDF");
    const std::string file = s.has("filename") ? s.string("filename", "") : "";
    const std::string stem = fs::path(file).stem().string();
    const std::string bsdf_id = bsdfs.empty() ? std::string() : bsdfs.front().id();
    const std::string base = !s.id().empty()    ? s.id()
                             : !bsdf_id.empty() ? bsdf_id
                             : !stem.empty()    ? stem
                                                : s.type();
    int material = bsdfs.empty() ? mitsuba::defaultMaterial(materials)
                                 : mitsuba::materialOf(bsdfs.front(), materials, base);
    if (material < 0) return;  // null BSDF: nothing to see
    const bool emissive = !s.children("emitter").empty();
    int mesh;
    Mat4 local;
    bool file_mesh;
    if (!geometry(s, emissive, mesh, local, file_mesh)) return;
    const std::string name = uniqueName(object_names, base);
    material = emissiveMaterial(s, material, name);
    const Mat4 T_m = T_parent * s.transform("to_world") * local;
    Mat4 T = file_mesh ? Mat4(C() * T_m * C().inverse()) : Mat4(C() * T_m);
    if (s.boolean("flip_normals", false)) mesh = flippedCopy(mesh, s, name);
    const double det = T.block<3, 3>(0, 0).determinant();
    if (!(std::abs(det) > 1e-12)) {
      notes.add("shape with a degenerate (flat or zero) transform left out", name);
      return;
    }
    if (det < 0) mesh = bakedCopy(mesh, T, name);  // our transforms cannot mirror
    if (det < 0) T = Mat4::Identity();
    for (const std::string& p : s.unused())
      notes.add(fmt::format("shape property '{}' ignored", p), name);
    Object o = Object::make(name, mesh, material, T, label({s.id(), bsdf_id, stem}, name),
                            static_cast<int>(scene.objects.size()) + 1);
    if (o.instance > 65535) s.fail("more than 65535 shapes (instance ids)");
    scene.objects.push_back(std::move(o));
  }

  int flippedCopy(int mesh, const Plugin& s, const std::string& name) {
    Mesh m = scene.meshes[mesh];
    if (m.isSphere()) {
      notes.add("flip_normals on an analytic sphere ignored", name);
      return mesh;
    }
    flipMesh(m);
    m.source = MeshSource{};
    m.id = uniqueName(mesh_ids, m.id + "_flipped");
    scene.meshes.push_back(std::move(m));
    return static_cast<int>(scene.meshes.size()) - 1;
  }

  int bakedCopy(int mesh, const Mat4& T, const std::string& name) {
    Mesh m = scene.meshes[mesh];
    if (m.isSphere()) {  // a mirrored sphere is the same sphere: bake only the scale
      notes.add("mirrored sphere transform: not supported, left out", name);
      return mesh;
    }
    bakeTransform(m, T);
    m.source = MeshSource{};
    m.id = uniqueName(mesh_ids, m.id + "_" + name);
    scene.meshes.push_back(std::move(m));
    return static_cast<int>(scene.meshes.size()) - 1;
  }

  void addEmitter(const Plugin& e);
  void addSky(const Plugin& e, const std::string& name);
  void addEnvMap(const Plugin& e, const std::string& name);
  void addSensor(const Plugin& s);
  void setIntrinsics(const Plugin& s, MitsubaSensor& cam);
};

void Importer::addEmitter(const Plugin& e) {
  const std::string type = e.type();
  const std::string name =
      e.id().empty() ? uniqueName(object_names, "mitsuba_" + type) : uniqueName(object_names, e.id());
  Light l;
  l.name = name;
  const Mat4 T = e.transform("to_world");
  const Vec3 z_world = (R_up * T.block<3, 3>(0, 0) * Vec3::UnitZ()).normalized();
  if (type == "point" || type == "spot") {
    l.type = type == "point" ? LightType::Point : LightType::Spot;
    const Vec3 p = e.has("position") ? e.vector("position", Vec3::Zero()) : Vec3(T.block<3, 1>(0, 3));
    l.position = opt.scale * (R_up * p);
    const Slot i = e.slot("intensity", Vec3f::Ones(), notes);
    if (i.texture) e.fail("the intensity must be a colour");
    splitColour(i.value, l);
    if (l.type == LightType::Spot) {
      l.direction = z_world;
      const double cutoff = e.number("cutoff_angle", 20.0);
      const double beam = e.number("beam_width", cutoff * 0.75);
      if (!(cutoff > 0 && cutoff < 90 && beam >= 0 && beam <= cutoff))
        e.fail("need 0 < cutoff_angle < 90 and 0 <= beam_width <= cutoff_angle (degrees)");
      l.cone_deg = static_cast<float>(cutoff);
      l.falloff_deg = static_cast<float>(cutoff - beam);
      notes.add("spot edge: Mitsuba's linear falloff rendered as a smooth step", name);
      e.ignore("texture");
    }
  } else if (type == "directional") {
    l.type = LightType::Sun;
    const Vec3 d = e.has("direction") ? Vec3(R_up * e.vector("direction", Vec3::UnitZ())) : z_world;
    if (!(d.norm() > 1e-12)) e.fail("the direction is zero");
    l.direction = d.normalized();
    const Slot i = e.slot("irradiance", Vec3f::Ones(), notes);
    if (i.texture) e.fail("the irradiance must be a colour");
    splitColour(i.value, l);
    notes.add("directional light rendered as a sun disk of 0.53 degrees", name);
  } else if (type == "constant") {
    l.type = LightType::Sky;
    const Slot r = e.slot("radiance", Vec3f::Ones(), notes);
    if (r.texture) e.fail("the radiance must be a colour");
    splitColour(r.value, l);
  } else if (type == "envmap") {
    return addEnvMap(e, name);
  } else if (type == "sun" || type == "sky" || type == "sunsky") {
    return addSky(e, name);
  } else {
    notes.add(fmt::format("emitter type '{}' not supported: left out", type), e.where());
    return;
  }
  for (const std::string& p : e.unused())
    notes.add(fmt::format("{} emitter property '{}' ignored", type, p), name);
  scene.lights.push_back(l);
}

void Importer::addEnvMap(const Plugin& e, const std::string& name) {
  const std::string file = e.string("filename", "");
  if (file.empty()) e.fail("an envmap needs a filename");
  const fs::path path =
      fs::path(file).is_absolute() ? fs::path(file) : fs::path(doc.folderOf(e.node())) / file;
  std::error_code ec;
  if (opt.read_files && !fs::is_regular_file(path, ec))
    e.fail(fmt::format("'{}': file not found", path.string()));
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext != ".exr" && ext != ".png" && ext != ".jpg" && ext != ".jpeg")
    e.fail(fmt::format("'{}': the environment map must be EXR, PNG or JPEG (convert an .hdr "
                       "file with e.g. oiiotool)",
                       path.string()));
  Light l;
  l.name = name;
  l.type = LightType::Sky;
  l.sky_model = SkyModel::EnvMap;
  l.envmap.file = l.envmap.path = path.lexically_normal().string();
  l.intensity = static_cast<float>(e.number("scale", 1.0));
  if (!(l.intensity >= 0)) e.fail("the scale must be >= 0");
  bool mirrored = false;
  const Mat3 L = e.transform("to_world").block<3, 3>(0, 0);
  const Mat3 R = nearestRotation(L, mirrored);
  if (mirrored || (L - R).cwiseAbs().maxCoeff() > 1e-4)
    notes.add("envmap to_world that is not a rotation: its nearest rotation is used", name);
  // map frame (ours, Z up) -> Mitsuba's map frame (Y up) -> Mitsuba world -> our world
  l.envmap_rotation = R_up * R * upRotation('y').transpose();
  for (const std::string& p : e.unused())
    notes.add(fmt::format("envmap property '{}' ignored", p), name);
  scene.lights.push_back(l);
}

void Importer::addSky(const Plugin& e, const std::string& name) {
  const std::string type = e.type();
  Vec3 to_sun(0.0, std::sqrt(0.5), std::sqrt(0.5));  // 45 degrees up, in Mitsuba's Y-up world
  if (e.has("sun_direction")) {
    to_sun = e.vector("sun_direction", to_sun);
  } else {
    for (const char* p : {"year", "month", "day", "hour", "minute", "second", "latitude",
                          "longitude", "timezone"})
      e.ignore(p);
    notes.add("sun position from date, time and place not computed: 45 degrees elevation", name);
  }
  if (opt.up == 'z' && !e.has("sun_direction")) to_sun = upRotation('y') * to_sun;
  to_sun = R_up * to_sun;
  if (!(to_sun.norm() > 1e-12)) e.fail("sun_direction is zero");
  to_sun.normalize();
  if (!(to_sun.z() > 0.01)) {
    notes.add("sun below the horizon: the sky and sun are left out", name);
    return;
  }
  const double turbidity = e.number("turbidity", 3.0);
  if (!(turbidity >= 2 && turbidity <= 10)) notes.add("turbidity clamped to 2..10", name);
  const double scale = e.number("scale", 1.0);
  const double sun_scale = e.number("sun_scale", scale), sky_scale = e.number("sky_scale", scale);
  if (!(sun_scale >= 0 && sky_scale >= 0)) e.fail("the scales must be >= 0");
  notes.add("sun/sky: our Preetham sky (100 W/m^2 x sky scale) and a 1000 W/m^2 x sun scale sun",
            name);
  if (type != "sun") {
    Light sky;
    sky.name = name + (type == "sunsky" ? "_sky" : "");
    sky.type = LightType::Sky;
    sky.sky_model = SkyModel::Preetham;
    sky.direction = -to_sun;
    sky.turbidity = static_cast<float>(std::clamp(turbidity, 2.0, 10.0));
    sky.intensity = static_cast<float>(100.0 * sky_scale);
    scene.lights.push_back(sky);
  }
  if (type != "sky") {
    Light sun;
    sun.name = name + (type == "sunsky" ? "_sun" : "");
    sun.type = LightType::Sun;
    sun.direction = -to_sun;
    sun.temperature_k = 5778.f;
    sun.intensity = static_cast<float>(1000.0 * sun_scale);
    sun.angular_diameter_deg = static_cast<float>(0.53 * e.number("sun_radius_scale", 1.0));
    scene.lights.push_back(sun);
  }
  for (const std::string& p : e.unused())
    notes.add(fmt::format("{} property '{}' ignored", type, p), name);
}

void Importer::setIntrinsics(const Plugin& s, MitsubaSensor& cam) {
  const double W = cam.width, H = cam.height;
  double tan_x;
  if (s.has("fov")) {
    const double fov = s.number("fov", 90.0);
    if (!(fov > 0 && fov < 180)) s.fail("fov must be in (0, 180) degrees");
    const double t = std::tan(0.5 * fov * kPi / 180.0);
    const std::string axis = s.string("fov_axis", "x");
    const bool along_x = axis == "x" || (axis == "smaller" && W <= H) || (axis == "larger" && W >= H);
    const bool along_y = axis == "y" || (axis == "smaller" && W > H) || (axis == "larger" && W < H);
    if (along_x) tan_x = t;
    else if (along_y) tan_x = t * W / H;
    else if (axis == "diagonal") tan_x = t * W / std::hypot(W, H);
    else s.fail("fov_axis '" + axis + "' is unknown (valid: x, y, diagonal, smaller, larger)");
  } else {
    // 35 mm film equivalent along the diagonal (36 x 24 mm), Mitsuba's default 50mm
    std::string f = s.string("focal_length", "50mm");
    if (f.size() > 2 && f.substr(f.size() - 2) == "mm") f.resize(f.size() - 2);
    char* end = nullptr;
    const double mm = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !(mm > 0 && std::isfinite(mm)))
      s.fail("focal_length must be like '50mm'");
    tan_x = std::hypot(36.0, 24.0) / (2.0 * mm) * W / std::hypot(W, H);
  }
  cam.fx = cam.fy = 0.5 * W / tan_x;
  cam.cx = 0.5 * W;
  cam.cy = 0.5 * H;
  if (!(std::isfinite(cam.fx) && cam.fx > 0)) s.fail("the field of view gives no finite focal length");
}

void Importer::addSensor(const Plugin& s) {
  if (sensor) {
    notes.add("more than one sensor: the first is used", s.where());
    return;
  }
  if (s.type() != "perspective" && s.type() != "thinlens") {
    notes.add(fmt::format("sensor type '{}' not supported: no camera", s.type()), s.where());
    return;
  }
  if (s.type() == "thinlens") {
    s.ignore("aperture_radius");
    s.ignore("focus_distance");
    notes.add("thinlens sensor rendered as a pinhole (no depth of field)", s.where());
  }
  MitsubaSensor cam;
  for (const Plugin& film : s.children("film")) {
    cam.width = film.integer("width", cam.width);
    cam.height = film.integer("height", cam.height);
  }
  if (cam.width < 1 || cam.width > 32768 || cam.height < 1 || cam.height > 32768)
    s.fail("the film size must be in 1..32768 pixels");
  for (const Plugin& sampler : s.children("sampler")) cam.spp = sampler.integer("sample_count", 0);
  setIntrinsics(s, cam);
  const Mat4 T = s.transform("to_world");
  // Mitsuba's camera looks along +z with +y up and image x to the left: OpenCV x = -x, y = -y
  const Mat3 L = T.block<3, 3>(0, 0);
  if (!(L.col(2).norm() > 1e-12 && L.col(1).norm() > 1e-12)) s.fail("degenerate to_world");
  const Vec3 z = L.col(2).normalized();
  const Vec3 y = (-L.col(1) + L.col(1).dot(z) * z).normalized();
  if (!y.allFinite()) s.fail("degenerate to_world (up parallel to the view direction)");
  const Vec3 x = y.cross(z);
  if (x.dot(-L.col(0)) < 0)
    notes.add("mirrored sensor to_world: our image is its mirror image", s.where());
  Mat3 R;
  R << x, y, z;
  Mat4 M = Mat4::Identity();
  M.block<3, 3>(0, 0) = R_up * R;
  M.block<3, 1>(0, 3) = opt.scale * (R_up * T.block<3, 1>(0, 3));
  cam.T_world_camera = Pose::fromMatrix(M);
  for (const char* p : {"near_clip", "far_clip", "shutter_open", "shutter_close"}) s.ignore(p);
  for (const std::string& p : s.unused())
    notes.add(fmt::format("sensor property '{}' ignored", p), s.where());
  sensor = cam;
}

}  // namespace

std::string MitsubaReport::summary(const std::string& default_category) const {
  std::vector<std::string> parts;
  if (unmatched_objects > 0) {
    parts.push_back(fmt::format(
        "{} shape(s) ({} distinct name(s)) matched no label and were labelled '{}': {}",
        unmatched_objects, unmatched_names.size(), default_category,
        listNames(unmatched_names, 10)));
  }
  parts.insert(parts.end(), approximations.begin(), approximations.end());
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

MitsubaScene parseMitsubaScene(const std::string& text, const std::string& path,
                               const MitsubaOptions& opt) {
  if (opt.up != 'y' && opt.up != 'z')
    throw InputError(path, "import options", fmt::format("up axis must be 'y' or 'z', got '{}'", opt.up));
  if (!(std::isfinite(opt.scale) && opt.scale > 0))
    throw InputError(path, "import options", "scale must be a finite number > 0");
  auto default_id = nyu40FromName(opt.default_category);
  if (!default_id)
    throw InputError(path, "default_category",
                     fmt::format("unknown NYU40 class '{}' (valid: {})", opt.default_category,
                                 nyu40NameList()));
  const LabelMap labels = opt.label_map.empty() ? LabelMap() : LabelMap::load(opt.label_map);
  Notes notes;
  const Document doc(text, path, opt.parameters, opt.read_files, notes);
  Importer imp(doc, opt, notes, labels, *default_id);
  imp.run();
  MitsubaScene out;
  out.scene = std::move(imp.scene);
  out.scene.name = fs::path(path).stem().string();
  if (out.scene.objects.empty())
    throw InputError(path, "", opt.read_files ? "the scene has no shape we can render"
                                              : "the scene has no shape we can render without "
                                                "reading files");
  out.scene.validate(path);
  out.sensor = imp.sensor;
  out.report = std::move(imp.report);
  out.report.objects = out.scene.objects.size();
  out.report.approximations = notes.lines();
  return out;
}

MitsubaScene readMitsubaScene(const std::string& path, const MitsubaOptions& opt) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "", "file not found");
  return parseMitsubaScene(readTextFile(path), path, opt);
}

Scene importMitsubaScene(const std::string& path, const MitsubaOptions& opt,
                         MitsubaReport* report) {
  MitsubaScene s = readMitsubaScene(path, opt);
  if (report) *report = std::move(s.report);
  return std::move(s.scene);
}

std::string mitsubaCameraJson(const MitsubaSensor& cam, const std::string& source) {
  // written by hand so that each matrix row stays on one line
  const std::string comment = nlohmann::json(fmt::format(
      "the perspective sensor of {} (Mitsuba), in our world (metres, Z up) and OpenCV camera "
      "axes; cx, cy in the renderer convention (pixel centres at +0.5)",
      source)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out = fmt::format(
      "{{\n  \"comment\": {},\n  \"width\": {},\n  \"height\": {},\n  \"fx\": {},\n"
      "  \"fy\": {},\n  \"cx\": {},\n  \"cy\": {},\n",
      comment, cam.width, cam.height, cam.fx, cam.fy, cam.cx, cam.cy);
  if (cam.spp > 0) out += fmt::format("  \"mitsuba_spp\": {},\n", cam.spp);
  const Mat4 M = cam.T_world_camera.matrix();
  out += "  \"cam_to_world\": [\n";
  for (int r = 0; r < 4; ++r)
    out += fmt::format("    [{}, {}, {}, {}]{}\n", M(r, 0), M(r, 1), M(r, 2), M(r, 3),
                       r < 3 ? "," : "");
  return out + "  ]\n}\n";
}

}  // namespace inet
