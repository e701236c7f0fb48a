// glTF 2.0 export: the scene model turned into tinygltf's document model, serialised by tinygltf
// (Debian's libtinygltf), written atomically.
#include "scene/gltf_export.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "scene/nyu40.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using tinygltf::Value;

constexpr double kLumensPerWatt = 683.0;  // KHR_lights_punctual's photometric units
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUint = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

Value num(double v) { return Value(v); }
Value vec(const Vec3f& v) { return Value(Value::Array{num(v.x()), num(v.y()), num(v.z())}); }
Value vec(const Vec3& v) { return Value(Value::Array{num(v.x()), num(v.y()), num(v.z())}); }
Value str(const std::string& s) { return Value(s); }
std::vector<double> quatXyzw(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }

/// A UV sphere of `radius` (48 x 24 quads) with exact normals, for analytic spheres.
Mesh tessellateSphere(const Mesh& in) {
  constexpr int kSlices = 48, kStacks = 24;
  Mesh m;
  m.id = in.id;
  for (int i = 0; i <= kStacks; ++i) {
    const double theta = M_PI * i / kStacks;
    for (int j = 0; j <= kSlices; ++j) {
      const double phi = 2.0 * M_PI * j / kSlices;
      const Vec3f n(static_cast<float>(std::sin(theta) * std::cos(phi)),
                    static_cast<float>(std::sin(theta) * std::sin(phi)),
                    static_cast<float>(std::cos(theta)));
      m.positions.push_back(n * in.sphere_radius);
      m.normals.push_back(n);
      m.uvs.emplace_back(static_cast<float>(j) / kSlices, 1.0f - static_cast<float>(i) / kStacks);
    }
  }
  const auto at = [](int i, int j) { return static_cast<uint32_t>(i * (kSlices + 1) + j); };
  for (int i = 0; i < kStacks; ++i)
    for (int j = 0; j < kSlices; ++j) {
      if (i > 0) m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + 1 < kStacks) m.triangles.emplace_back(at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
    }
  return m;
}

std::string mimeOf(const fs::path& p) {
  const std::string ext = lowerExtension(p.string());
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  return "";
}

std::vector<unsigned char> readBytes(const fs::path& p, const std::string& where) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(where, "texture", "cannot read the image " + p.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Exporter {
 public:
  Exporter(const Scene& s, const fs::path& out, const GltfExportOptions& opt)
      : s_(s), out_(out), opt_(opt) {
    model_.asset.generator = "interiornet";
    model_.buffers.emplace_back();
    tinygltf::Sampler sampler;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    model_.samplers.push_back(sampler);
  }

  GltfExportReport run() {
    tinygltf::Node root;
    root.name = "interiornet_world";
    // Our Z-up world in glTF's Y-up: (x, y, z) -> (x, z, -y), a -90 degree turn about x.
    root.rotation = quatXyzw(Quat(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX())));
    model_.nodes.push_back(root);  // index 0; children filled below
    for (size_t i = 0; i < s_.objects.size(); ++i) addObject(static_cast<int>(i));
    for (const Light& l : s_.lights) addLight(l);
    if (opt_.camera) addCamera(*opt_.camera);
    model_.nodes[0].children = children_;

    tinygltf::Scene scene;
    scene.name = s_.name;
    scene.nodes = {0};
    scene.extras = sceneExtras();
    model_.scenes.push_back(scene);
    model_.defaultScene = 0;
    model_.extensionsUsed.assign(extensions_.begin(), extensions_.end());

    report_.nodes = static_cast<int>(model_.nodes.size());
    report_.meshes = static_cast<int>(model_.meshes.size());
    report_.materials = static_cast<int>(model_.materials.size());
    report_.lights = static_cast<int>(model_.lights.size());
    report_.images = static_cast<int>(model_.images.size());
    report_.animations = static_cast<int>(model_.animations.size());
    write();
    return report_;
  }

 private:
  // --- buffer ------------------------------------------------------------------------------
  int addView(const void* data, size_t bytes, int target) {
    auto& buf = model_.buffers[0].data;
    while (buf.size() % 4) buf.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  template <typename V>
  int addVectors(const std::vector<V>& v, int type, bool bounds) {
    constexpr int n = V::RowsAtCompileTime;
    std::vector<float> flat;
    flat.reserve(v.size() * n);
    for (const V& x : v)
      for (int k = 0; k < n; ++k) flat.push_back(x[k]);
    tinygltf::Accessor a;
    a.bufferView = addView(flat.data(), flat.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = kFloat;
    a.count = v.size();
    a.type = type;
    if (bounds && !v.empty()) {  // POSITION needs min and max
      a.minValues.assign(n, std::numeric_limits<double>::max());
      a.maxValues.assign(n, -std::numeric_limits<double>::max());
      for (const V& x : v)
        for (int k = 0; k < n; ++k) {
          a.minValues[k] = std::min<double>(a.minValues[k], x[k]);
          a.maxValues[k] = std::max<double>(a.maxValues[k], x[k]);
        }
    }
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  // --- meshes ------------------------------------------------------------------------------
  struct MeshAccessors {
    int position = -1, normal = -1, indices = -1;
    std::map<std::pair<float, float>, int> uv;  // per uv_scale
  };

  const Mesh& meshGeometry(int index) {
    const Mesh& m = s_.meshes[index];
    if (!m.isSphere()) return m;
    auto it = spheres_.find(index);
    if (it == spheres_.end()) {
      it = spheres_.emplace(index, tessellateSphere(m)).first;
      ++report_.spheres_tessellated;
    }
    return it->second;
  }

  MeshAccessors& accessorsOf(int index) {
    auto [it, fresh] = mesh_accessors_.try_emplace(index);
    if (!fresh) return it->second;
    const Mesh& m = meshGeometry(index);
    MeshAccessors& a = it->second;
    a.position = addVectors(m.positions, TINYGLTF_TYPE_VEC3, true);
    if (!m.normals.empty()) {
      std::vector<Vec3f> unit(m.normals.size());
      for (size_t i = 0; i < unit.size(); ++i) {
        const float len = m.normals[i].norm();
        unit[i] = len > 0 ? Vec3f(m.normals[i] / len) : Vec3f::UnitZ();
      }
      a.normal = addVectors(unit, TINYGLTF_TYPE_VEC3, false);
    }
    std::vector<uint32_t> idx;
    idx.reserve(m.triangles.size() * 3);
    for (const Tri& t : m.triangles) idx.insert(idx.end(), {t[0], t[1], t[2]});
    tinygltf::Accessor acc;
    acc.bufferView =
        addView(idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    acc.componentType = kUint;
    acc.count = idx.size();
    acc.type = TINYGLTF_TYPE_SCALAR;
    model_.accessors.push_back(acc);
    a.indices = static_cast<int>(model_.accessors.size()) - 1;
    return a;
  }

  /// The texture coordinates of mesh `index` for a material tiling by `scale`, in glTF's
  /// convention (v down the image): (u sx, 1 - v sy).
  int uvAccessor(int index, const Vec2f& scale) {
    MeshAccessors& a = accessorsOf(index);
    const auto key = std::make_pair(scale.x(), scale.y());
    if (auto it = a.uv.find(key); it != a.uv.end()) return it->second;
    const Mesh& m = meshGeometry(index);
    std::vector<Vec2f> uv(m.uvs.size());
    for (size_t i = 0; i < uv.size(); ++i)
      uv[i] = Vec2f(m.uvs[i].x() * scale.x(), 1.0f - m.uvs[i].y() * scale.y());
    return a.uv[key] = addVectors(uv, TINYGLTF_TYPE_VEC2, false);
  }

  int gltfMesh(int mesh, int material) {
    const auto key = std::make_pair(mesh, material);
    if (auto it = gltf_mesh_.find(key); it != gltf_mesh_.end()) return it->second;
    const MeshAccessors& a = accessorsOf(mesh);
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = a.position;
    if (a.normal >= 0) prim.attributes["NORMAL"] = a.normal;
    if (!meshGeometry(mesh).uvs.empty())
      prim.attributes["TEXCOORD_0"] = uvAccessor(mesh, s_.materials[material].uv_scale);
    prim.indices = a.indices;
    prim.material = gltfMaterial(material);
    tinygltf::Mesh gm;
    gm.name = s_.meshes[mesh].id;
    gm.primitives.push_back(prim);
    model_.meshes.push_back(gm);
    return gltf_mesh_[key] = static_cast<int>(model_.meshes.size()) - 1;
  }

  // --- textures ----------------------------------------------------------------------------
  /// The glTF texture of an image file, or -1 when glTF cannot hold it (only PNG and JPEG).
  int texture(const TextureRef& ref) {
    if (ref.empty()) return -1;
    if (auto it = texture_of_.find(ref.path); it != texture_of_.end()) return it->second;
    const std::string mime = mimeOf(ref.path);
    if (mime.empty()) {
      ++report_.skipped_textures;
      note(fmt::format("texture {} left out: glTF holds PNG and JPEG images only", ref.file));
      return texture_of_[ref.path] = -1;
    }
    tinygltf::Image img;
    img.name = fs::path(ref.path).stem().string();
    std::vector<unsigned char> bytes = readBytes(ref.path, out_.string());
    if (opt_.binary) {
      img.mimeType = mime;
      img.bufferView = addView(bytes.data(), bytes.size(), 0);
    } else {
      // a unique file name in <stem>_textures/, copied there at write time
      std::string name = fs::path(ref.path).filename().string();
      for (int k = 2; !image_names_.insert(name).second; ++k)
        name = fmt::format("{}_{}{}", fs::path(ref.path).stem().string(), k,
                           fs::path(ref.path).extension().string());
      img.uri = texturesFolder() + "/" + name;
      copies_.push_back({ref.path, out_.parent_path() / img.uri, std::move(bytes)});
    }
    model_.images.push_back(img);
    tinygltf::Texture tex;
    tex.sampler = 0;
    tex.source = static_cast<int>(model_.images.size()) - 1;
    model_.textures.push_back(tex);
    return texture_of_[ref.path] = static_cast<int>(model_.textures.size()) - 1;
  }

  std::string texturesFolder() const { return out_.stem().string() + "_textures"; }

  // --- materials ---------------------------------------------------------------------------
  void extension(tinygltf::Material& gm, const std::string& name, Value::Object v) {
    gm.extensions[name] = Value(std::move(v));
    extensions_.insert(name);
  }

  int gltfMaterial(int index) {
    if (auto it = material_of_.find(index); it != material_of_.end()) return it->second;
    const Material& m = s_.materials[index];
    tinygltf::Material gm;
    gm.name = m.id;
    gm.doubleSided = true;  // our reflection BSDFs are two-sided
    auto& pbr = gm.pbrMetallicRoughness;
    const auto base = [&](const Vec3f& c) { pbr.baseColorFactor = {c.x(), c.y(), c.z(), 1.0}; };
    Value::Object extras{{"interiornet_type", str(materialTypeName(m.type))},
                         {"albedo", vec(m.albedo)},
                         {"roughness", num(m.roughness)}};
    base(m.albedo);
    pbr.metallicFactor = 0.0;
    pbr.roughnessFactor = m.roughness;
    switch (m.type) {
      case MaterialType::Lambertian:
        pbr.roughnessFactor = 1.0;
        extension(gm, "KHR_materials_specular", {{"specularFactor", num(0.0)}});
        break;
      case MaterialType::Conductor:
        pbr.metallicFactor = 1.0;
        base(m.albedo.cwiseProduct(metalBaseColor(m.metal)));
        extras["metal"] = str(m.metal);
        break;
      case MaterialType::Plastic:
        extension(gm, "KHR_materials_ior", {{"ior", num(m.ior)}});
        extras["ior"] = num(m.ior);
        break;
      case MaterialType::Dielectric:
      case MaterialType::ThinDielectric:
        base(m.transmittance);
        extension(gm, "KHR_materials_transmission", {{"transmissionFactor", num(1.0)}});
        extension(gm, "KHR_materials_ior", {{"ior", num(m.ior)}});
        if (m.type == MaterialType::Dielectric)  // a volume (thin-walled otherwise)
          extension(gm, "KHR_materials_volume", {{"thicknessFactor", num(0.01)}});
        extras["ior"] = num(m.ior);
        extras["transmittance"] = vec(m.transmittance);
        break;
      case MaterialType::Translucent: {
        pbr.roughnessFactor = 1.0;
        extension(gm, "KHR_materials_specular", {{"specularFactor", num(0.0)}});
        // ours: reflectance A, transmittance T (A + T <= 1); glTF splits one diffuse lobe
        // between reflection (1 - f) base and transmission f colour.
        const float a = m.albedo.mean(), t = m.transmittance.mean();
        const float f = a + t > 0 ? t / (a + t) : 0.f;
        if (f < 1.f) base((m.albedo / (1.f - f)).cwiseMin(1.f));
        const Vec3f tc = f > 0 ? Vec3f((m.transmittance / f).cwiseMin(1.f)) : Vec3f::Zero();
        extension(gm, "KHR_materials_diffuse_transmission",
                  {{"diffuseTransmissionFactor", num(f)},
                   {"diffuseTransmissionColorFactor", vec(tc)}});
        extras["transmittance"] = vec(m.transmittance);
        break;
      }
    }
    if (m.isEmissive()) {
      const float peak = m.emission.maxCoeff();
      const Vec3f e = m.emission / peak;
      gm.emissiveFactor = {e.x(), e.y(), e.z()};
      if (peak != 1.f) extension(gm, "KHR_materials_emissive_strength", {{"emissiveStrength", num(peak)}});
      extras["emission"] = vec(m.emission);
    }
    if (int t = texture(m.albedo_texture); t >= 0) pbr.baseColorTexture.index = t;
    if (int t = texture(m.roughness_texture); t >= 0) pbr.metallicRoughnessTexture.index = t;
    if (int t = texture(m.normal_texture); t >= 0) gm.normalTexture.index = t;
    if (m.type == MaterialType::Conductor && !m.roughness_texture.empty())
      note(fmt::format("material {}: a grey roughness image also scales metalness (glTF reads "
                       "it from the blue channel)", m.id));
    gm.extras = Value(std::move(extras));
    model_.materials.push_back(gm);
    return material_of_[index] = static_cast<int>(model_.materials.size()) - 1;
  }

  // --- nodes -------------------------------------------------------------------------------
  static std::vector<double> columnMajor(const Mat4& T) {
    std::vector<double> m(16);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c * 4 + r] = T(r, c);
    return m;
  }

  int pushNode(tinygltf::Node n) {
    model_.nodes.push_back(std::move(n));
    return static_cast<int>(model_.nodes.size()) - 1;
  }

  void addObject(int index) {
    const Object& o = s_.objects[index];
    tinygltf::Node n;
    n.name = o.name;
    n.mesh = gltfMesh(o.mesh, o.material);
    if (!o.T_world_object.isIdentity()) n.matrix = columnMajor(o.T_world_object);
    Value::Object ex{{"nyu40", Value(o.nyu40)},
                     {"nyu40_name", str(std::string(nyu40Name(o.nyu40)))},
                     {"instance", Value(o.instance)}};
    if (!o.kind.empty()) ex["kind"] = str(o.kind);
    if (!o.part.empty()) ex["part"] = str(o.part);
    if (o.room >= 0 && o.room < static_cast<int>(s_.rooms.size()))
      ex["room"] = str(s_.rooms[o.room].id);
    if (o.physics) {
      ex["mass_kg"] = num(o.physics->mass_kg);
      ex["friction"] = num(o.physics->friction);
      ex["movable"] = Value(o.physics->movable);
    }
    n.extras = Value(std::move(ex));
    const int node = pushNode(std::move(n));
    if (!o.moving()) {
      children_.push_back(node);
      return;
    }
    // A rigid parent carries the motion (pose * T_world_object, see ObjectKeyframe).
    tinygltf::Node parent;
    parent.name = o.name + "_motion";
    parent.children = {node};
    const int p = pushNode(std::move(parent));
    children_.push_back(p);
    std::vector<float> t, xyz, xyzw;
    for (const ObjectKeyframe& k : o.motion) {
      t.push_back(static_cast<float>(k.t_s));
      for (int i = 0; i < 3; ++i) xyz.push_back(static_cast<float>(k.pose.t[i]));
      for (double c : quatXyzw(k.pose.q.normalized())) xyzw.push_back(static_cast<float>(c));
    }
    const auto accessor = [&](const std::vector<float>& v, int type, int n_comp, bool bounds) {
      tinygltf::Accessor a;
      a.bufferView = addView(v.data(), v.size() * 4, 0);
      a.componentType = kFloat;
      a.count = v.size() / n_comp;
      a.type = type;
      if (bounds) a.minValues = {t.front()}, a.maxValues = {t.back()};
      model_.accessors.push_back(a);
      return static_cast<int>(model_.accessors.size()) - 1;
    };
    tinygltf::Animation anim;
    anim.name = o.name;
    const int input = accessor(t, TINYGLTF_TYPE_SCALAR, 1, true);
    for (const auto& [path, data, type, nc] :
         {std::tuple{"translation", &xyz, TINYGLTF_TYPE_VEC3, 3},
          std::tuple{"rotation", &xyzw, TINYGLTF_TYPE_VEC4, 4}}) {
      tinygltf::AnimationSampler smp;
      smp.input = input;
      smp.output = accessor(*data, type, nc, false);
      smp.interpolation = "LINEAR";  // rotation: slerp, as ours
      anim.samplers.push_back(smp);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
      ch.target_node = p;
      ch.target_path = path;
      anim.channels.push_back(ch);
    }
    model_.animations.push_back(anim);
  }

  void addLight(const Light& l) {
    if (l.type == LightType::Sky) return;  // in the scene extras
    if (!l.on) {
      ++report_.lights_off;
      return;
    }
    const Vec3f rgb = l.rgbIntensity();
    const float peak = rgb.maxCoeff();
    tinygltf::Light gl;
    gl.name = l.name;
    gl.color = peak > 0 ? std::vector<double>{rgb.x() / peak, rgb.y() / peak, rgb.z() / peak}
                        : std::vector<double>{1, 1, 1};
    gl.intensity = kLumensPerWatt * peak;
    Value::Object ex{{"interiornet_type", str(lightTypeName(l.type))},
                     {"rgb_intensity", vec(rgb)}};
    if (!l.object.empty()) ex["object"] = str(l.object);
    tinygltf::Node n;
    n.name = l.name;
    // glTF lights shine along their node's -z
    const Quat q = Quat::FromTwoVectors(-Vec3::UnitZ(), l.direction.normalized());
    switch (l.type) {
      case LightType::Point:
        gl.type = "point";
        n.translation = {l.position.x(), l.position.y(), l.position.z()};
        break;
      case LightType::Spot:
        gl.type = "spot";
        n.translation = {l.position.x(), l.position.y(), l.position.z()};
        n.rotation = quatXyzw(q);
        gl.spot.outerConeAngle = l.cone_deg * M_PI / 180.0;
        gl.spot.innerConeAngle = std::max(0.0, (l.cone_deg - l.falloff_deg) * M_PI / 180.0);
        ex["cone_deg"] = num(l.cone_deg);
        ex["falloff_deg"] = num(l.falloff_deg);
        note("spot lights: glTF's smooth cone edge is not our smoothstep over falloff_deg");
        break;
      case LightType::Sun:
        gl.type = "directional";
        n.rotation = quatXyzw(q);
        ex["angular_diameter_deg"] = num(l.angular_diameter_deg);
        break;
      case LightType::Sky:
        break;
    }
    if (l.max_distance > 0) gl.range = l.max_distance;
    if (l.radius > 0) ex["radius"] = num(l.radius);  // the bulb (Blender: shadow_soft_size)
    gl.extras = Value(std::move(ex));
    model_.lights.push_back(gl);
    n.extensions["KHR_lights_punctual"] =
        Value(Value::Object{{"light", Value(static_cast<int>(model_.lights.size()) - 1)}});
    children_.push_back(pushNode(std::move(n)));
  }

  void addCamera(const GltfCamera& c) {
    tinygltf::Camera cam;
    cam.type = "perspective";
    cam.name = c.name;
    cam.perspective.yfov = 2.0 * std::atan(c.height / (2.0 * c.fy));
    cam.perspective.aspectRatio = c.width * c.fy / (c.height * c.fx);
    cam.perspective.znear = 0.01;
    // glTF allows no zfar (an infinite projection), but Assimp 5.2 then rejects the file
    // ("mClipPlaneFar must be >= mClipPlaneNear"): say 1 km
    cam.perspective.zfar = 1000.0;
    cam.extras = Value(Value::Object{{"width", Value(c.width)},
                                     {"height", Value(c.height)},
                                     {"fx", num(c.fx)},
                                     {"fy", num(c.fy)},
                                     {"cx", num(c.cx)},
                                     {"cy", num(c.cy)}});
    if (std::abs(c.cx - c.width / 2.0) > 1e-6 || std::abs(c.cy - c.height / 2.0) > 1e-6)
      note("camera: glTF has no principal-point offset (it is in the camera's extras)");
    model_.cameras.push_back(cam);
    tinygltf::Node n;
    n.name = c.name;
    n.camera = static_cast<int>(model_.cameras.size()) - 1;
    // OpenCV axes (x right, y down, z forward) to glTF's (x right, y up, looking along -z)
    Mat3 R = c.T_world_camera.block<3, 3>(0, 0) * Eigen::Vector3d(1, -1, -1).asDiagonal();
    n.rotation = quatXyzw(Quat(R).normalized());
    const Vec3 t = c.T_world_camera.block<3, 1>(0, 3);
    n.translation = {t.x(), t.y(), t.z()};
    children_.push_back(pushNode(std::move(n)));
  }

  Value sceneExtras() const {
    Value::Array skies;
    for (const Light& l : s_.lights) {
      if (l.type != LightType::Sky || !l.on) continue;
      Value::Object sky{{"model", str(skyModelName(l.sky_model))},
                        {"intensity", num(l.intensity)},
                        {"rgb", vec(l.rgbIntensity())}};
      if (l.sky_model == SkyModel::Preetham) {
        sky["turbidity"] = num(l.turbidity);
        sky["sun_direction"] = vec(l.direction);
      }
      if (l.sky_model == SkyModel::EnvMap) sky["envmap"] = str(l.envmap.file);
      skies.push_back(Value(std::move(sky)));
    }
    Value::Array rooms;
    for (const Room& r : s_.rooms) {
      Value::Array outline;
      for (const auto& p : r.outline) outline.push_back(Value(Value::Array{num(p.x()), num(p.y())}));
      rooms.push_back(Value(Value::Object{{"id", str(r.id)},
                                          {"type", str(r.type)},
                                          {"floor_z", num(r.floor_z)},
                                          {"ceiling_z", num(r.ceiling_z)},
                                          {"outline", Value(std::move(outline))}}));
    }
    Value::Object ex{{"format", str("interiornet glTF export 1")},
                     {"units", str("metres; lights photometric (683 lm/W), emission radiance")},
                     {"frame", str("children of interiornet_world are in our Z-up world")},
                     {"skies", Value(std::move(skies))},
                     {"rooms", Value(std::move(rooms))}};
    if (!opt_.sky_image.empty()) ex["sky_image"] = str(opt_.sky_image);
    return Value(Value::Object{{"interiornet", Value(std::move(ex))}});
  }

  void note(const std::string& line) {
    if (std::find(report_.notes.begin(), report_.notes.end(), line) == report_.notes.end())
      report_.notes.push_back(line);
  }

  // --- output ------------------------------------------------------------------------------
  void write() {
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(nullptr, nullptr);  // images are copied or embedded by us
    std::vector<unsigned char> bin;
    if (!opt_.binary) bin.swap(model_.buffers[0].data);  // a .bin file beside the .gltf
    std::ostringstream ss;
    if (!writer.WriteGltfSceneToStream(&model_, ss, !opt_.binary, opt_.binary))
      throw InputError(out_.string(), "", "tinygltf could not serialise the scene");
    std::string doc = ss.str();
    if (!opt_.binary) {
      const std::string bin_name = out_.stem().string() + ".bin";
      nlohmann::ordered_json j = nlohmann::ordered_json::parse(doc);
      j["buffers"][0]["uri"] = bin_name;
      j["buffers"][0]["byteLength"] = bin.size();
      doc = j.dump(1);
      for (const auto& c : copies_) {
        writeFileAtomic(c.to, [&](const fs::path& tmp) {
          std::ofstream f(tmp, std::ios::binary);
          f.write(reinterpret_cast<const char*>(c.bytes.data()),
                  static_cast<std::streamsize>(c.bytes.size()));
          if (!f) throw InputError(c.to.string(), "", "cannot write");
        });
        report_.bytes += c.bytes.size();
      }
      writeFileAtomic(out_.parent_path() / bin_name, [&](const fs::path& tmp) {
        std::ofstream f(tmp, std::ios::binary);
        f.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
        if (!f) throw InputError(out_.string(), "", "cannot write " + bin_name);
      });
      report_.bytes += bin.size();
    }
    writeTextAtomic(out_, doc);
    report_.bytes += doc.size();
  }

  struct Copy {
    std::string from;
    fs::path to;
    std::vector<unsigned char> bytes;
  };

  const Scene& s_;
  const fs::path out_;
  const GltfExportOptions& opt_;
  tinygltf::Model model_;
  GltfExportReport report_;
  std::vector<int> children_;
  std::set<std::string> extensions_;
  std::map<int, Mesh> spheres_;
  std::map<int, MeshAccessors> mesh_accessors_;
  std::map<std::pair<int, int>, int> gltf_mesh_;
  std::map<int, int> material_of_;
  std::map<std::string, int> texture_of_;
  std::set<std::string> image_names_;
  std::vector<Copy> copies_;
};

}  // namespace

Vec3f metalBaseColor(const std::string& metal) {
  // Normal-incidence reflectance ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2) of render/fresnel.h's
  // metalIor; the scene stage cannot call the renderer, a test checks the two agree.
  static const std::map<std::string, Vec3f> f0 = {{"gold", {0.97f, 0.80f, 0.32f}},
                                                  {"silver", {0.97f, 0.96f, 0.91f}},
                                                  {"copper", {0.95f, 0.62f, 0.51f}},
                                                  {"aluminium", {0.93f, 0.92f, 0.91f}},
                                                  {"chromium", {0.69f, 0.65f, 0.69f}}};
  auto it = f0.find(metal);
  return it == f0.end() ? Vec3f(0.9f, 0.9f, 0.9f) : it->second;
}

GltfExportReport exportGltf(const Scene& scene, const std::string& path,
                            const GltfExportOptions& opt) {
  const fs::path out = fs::absolute(path);
  if (lowerExtension(path) != (opt.binary ? ".glb" : ".gltf"))
    throw InputError(path, "--out", opt.binary ? "a binary glTF file ends in .glb"
                                               : "a glTF file ends in .gltf");
  std::error_code ec;
  fs::create_directories(out.parent_path(), ec);
  return Exporter(scene, out, opt).run();
}

}  // namespace inet
