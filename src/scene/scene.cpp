#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "core/color.h"
#include "core/error.h"

namespace inet {

Vec3f Light::rgbIntensity() const {
  Vec3f c = temperature_k > 0.f ? blackbodyRgb(temperature_k) : color;
  return c * intensity;
}

const char* materialTypeName(MaterialType t) {
  switch (t) {
    case MaterialType::Lambertian:
      return "lambertian";
    case MaterialType::Conductor:
      return "conductor";
    case MaterialType::Plastic:
      return "plastic";
    case MaterialType::Dielectric:
      return "dielectric";
    case MaterialType::ThinDielectric:
      return "thin_dielectric";
    case MaterialType::Translucent:
      return "translucent";
  }
  return "?";
}

const std::vector<std::string>& metalNames() {
  static const std::vector<std::string> names = {"gold", "silver", "copper", "aluminium",
                                                 "chromium"};
  return names;
}

std::pair<Light, Light> daylightLights(const Vec3& to_sun, float turbidity, float scale,
                                       const std::string& prefix) {
  Light sky;
  sky.name = prefix + "sky";
  sky.type = LightType::Sky;
  sky.sky_model = SkyModel::Preetham;
  sky.direction = -to_sun;
  sky.turbidity = turbidity;
  sky.intensity = 40.f * scale;
  Light sun;
  sun.name = prefix + "sun";
  sun.type = LightType::Sun;
  sun.direction = -to_sun;
  sun.temperature_k = 5500.f;
  sun.intensity = 350.f * scale;
  return {sky, sun};
}

const char* lightTypeName(LightType t) {
  switch (t) {
    case LightType::Point:
      return "point";
    case LightType::Spot:
      return "spot";
    case LightType::Sun:
      return "sun";
    case LightType::Sky:
      return "sky";
  }
  return "?";
}

const char* skyModelName(SkyModel m) {
  switch (m) {
    case SkyModel::Uniform:
      return "uniform";
    case SkyModel::Preetham:
      return "preetham";
    case SkyModel::EnvMap:
      return "envmap";
  }
  return "?";
}

namespace {

/// The ranges in which the Preetham sky model was fitted (render/sky.h).
void validatePreetham(const Light& l, const std::string& where, const std::string& field) {
  if (!(l.turbidity >= 2.f && l.turbidity <= 10.f))
    throw InputError(
        where, field + ".turbidity",
        fmt::format("{} is outside 2..10 (2: very clear, 3: clear, 10: hazy)", l.turbidity));
  const double norm = l.direction.norm();
  if (!(std::abs(norm - 1.0) <= 1e-6))
    throw InputError(where, field + ".sun_direction",
                     fmt::format("must be a unit vector (its length is {})", norm));
  if (!(l.direction.z() < 0.0))
    throw InputError(where, field + ".sun_direction",
                     "the sun must be above the horizon (z < 0: its light travels downwards)");
}

/// An environment map needs its image and a proper rotation (kept as written, so checked here).
void validateEnvMap(const Light& l, const std::string& where, const std::string& field) {
  if (l.envmap.empty()) throw InputError(where, field + ".file", "an envmap sky needs an image");
  const Mat3& R = l.envmap_rotation;
  if (!R.allFinite() || (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      !(R.determinant() > 0.0))
    throw InputError(where, field + ".rotation",
                     "must be a rotation matrix (orthonormal to 1e-6, determinant +1)");
}

}  // namespace

int Scene::findMesh(const std::string& id) const {
  for (size_t i = 0; i < meshes.size(); ++i)
    if (meshes[i].id == id) return static_cast<int>(i);
  return -1;
}

int Scene::findMaterial(const std::string& id) const {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].id == id) return static_cast<int>(i);
  return -1;
}

std::pair<Vec3, Vec3> Scene::bounds() const {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const auto& o : objects) {
    const Mesh& m = meshes[o.mesh];
    auto grow = [&](const Vec3& p) {
      Vec3 w = (o.T_world_object * p.homogeneous()).head<3>();
      lo = lo.cwiseMin(w);
      hi = hi.cwiseMax(w);
    };
    if (m.isSphere()) {
      double r = m.sphere_radius;
      for (int c = 0; c < 8; ++c) grow(Vec3((c & 1) ? r : -r, (c & 2) ? r : -r, (c & 4) ? r : -r));
    } else {
      for (const auto& p : m.positions) grow(p.cast<double>());
    }
  }
  return {lo, hi};
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const auto& o : objects) n += meshes[o.mesh].triangles.size();
  return n;
}

const std::vector<std::string>& roomTypeNames() {
  // the 16 room types of the interior-design trade (issue 4)
  static const std::vector<std::string> names = {
      "living_room",  "dining_room", "kitchen",   "master_bedroom",  "second_bedroom", "kids_room",
      "elderly_room", "study",       "bathroom",  "master_bathroom", "balcony",        "corridor",
      "entrance",     "storage",     "cloakroom", "laundry"};
  return names;
}

double Room::area() const {
  double a = 0;
  for (size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& p = outline[i];
    const Eigen::Vector2d& q = outline[(i + 1) % outline.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

bool Room::contains(double x, double y) const {
  bool in = false;  // even-odd crossing test
  for (size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
    const Eigen::Vector2d &a = outline[i], &b = outline[j];
    if ((a.y() > y) != (b.y() > y) && x < (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

bool Room::contains(double x, double y, double tol) const {
  if (contains(x, y)) return true;
  const Eigen::Vector2d p(x, y);
  for (size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
    const Eigen::Vector2d &a = outline[j], ab = outline[i] - outline[j];
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    if ((a + t * ab - p).norm() <= tol) return true;
  }
  return false;
}

Mat4 Object::transformAt(double t_s) const {
  if (motion.empty()) return T_world_object;
  Pose p;
  if (t_s <= motion.front().t_s) {
    p = motion.front().pose;
  } else if (t_s >= motion.back().t_s) {
    p = motion.back().pose;
  } else {
    auto hi = std::upper_bound(motion.begin(), motion.end(), t_s,
                               [](double t, const ObjectKeyframe& k) { return t < k.t_s; });
    const ObjectKeyframe& a = *(hi - 1);
    const ObjectKeyframe& b = *hi;
    const double alpha = (t_s - a.t_s) / (b.t_s - a.t_s);
    p.q = a.pose.q.slerp(alpha, b.pose.q);
    p.t = (1.0 - alpha) * a.pose.t + alpha * b.pose.t;
  }
  return p.matrix() * T_world_object;
}

void Scene::validate(const std::string& where) const {
  for (size_t i = 0; i < rooms.size(); ++i) {
    const Room& r = rooms[i];
    const std::string field = fmt::format("rooms[{}] ('{}')", i, r.id);
    if (r.id.empty()) throw InputError(where, field + ".id", "must not be empty");
    const auto& types = roomTypeNames();
    if (std::find(types.begin(), types.end(), r.type) == types.end())
      throw InputError(
          where, field + ".type",
          fmt::format("unknown room type '{}' (valid: {})", r.type, fmt::join(types, ", ")));
    if (r.outline.size() < 3) throw InputError(where, field + ".outline", "needs 3 or more points");
    for (const auto& p : r.outline)
      if (!p.allFinite()) throw InputError(where, field + ".outline", "non-finite point");
    if (!(r.area() > 0))
      throw InputError(where, field + ".outline",
                       "must enclose an area, counter-clockwise seen from above");
    if (!(std::isfinite(r.floor_z) && std::isfinite(r.ceiling_z) && r.ceiling_z > r.floor_z))
      throw InputError(where, field + ".ceiling_z", "must be finite and above floor_z");
  }
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Mesh& m = meshes[i];
    std::string field = fmt::format("meshes[{}] ('{}')", i, m.id);
    if (!m.isSphere() && m.triangles.empty())
      throw InputError(where, field, "mesh has no triangles");
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] >= m.positions.size())
          throw InputError(where, field, "triangle index out of range");
    for (const auto& p : m.positions)
      if (!p.allFinite()) throw InputError(where, field, "non-finite vertex position");
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
      throw InputError(where, field + ".normals",
                       fmt::format("{} normals for {} vertices (need one per vertex)",
                                   m.normals.size(), m.positions.size()));
    for (const auto& n : m.normals)
      if (!n.allFinite() || !(n.norm() > 1e-6f))
        throw InputError(where, field + ".normals", "normals must be finite and non-zero");
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
      throw InputError(where, field + ".uvs",
                       fmt::format("{} texture coordinates for {} vertices (need one per vertex)",
                                   m.uvs.size(), m.positions.size()));
    for (const auto& uv : m.uvs)
      if (!uv.allFinite()) throw InputError(where, field + ".uvs", "non-finite texture coordinate");
  }
  for (size_t i = 0; i < objects.size(); ++i) {
    const Object& o = objects[i];
    std::string field = fmt::format("objects[{}] ('{}')", i, o.name);
    if (o.mesh < 0 || o.mesh >= static_cast<int>(meshes.size()))
      throw InputError(where, field + ".mesh", "no such mesh");
    if (o.material < 0 || o.material >= static_cast<int>(materials.size()))
      throw InputError(where, field + ".material", "no such material");
    if (o.nyu40 < 0 || o.nyu40 > 40)
      throw InputError(where, field + ".nyu40",
                       fmt::format("{} is not an NYU40 id (0..40)", o.nyu40));
    if (o.instance < 1 || o.instance > 65535)
      throw InputError(where, field + ".instance",
                       fmt::format("{} is outside 1..65535", o.instance));
    if (!o.T_world_object.allFinite())
      throw InputError(where, field + ".transform", "non-finite value");
    if (o.T_world_object.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
      throw InputError(where, field + ".transform", "last row must be 0 0 0 1");
    double det = o.T_world_object.block<3, 3>(0, 0).determinant();
    if (!(det > 1e-12))
      throw InputError(
          where, field + ".transform",
          "linear part must have a positive determinant (no zero, negative or mirror scale)");
    for (size_t k = 0; k < o.motion.size(); ++k) {
      const ObjectKeyframe& kf = o.motion[k];
      const std::string f = fmt::format("{}.motion[{}]", field, k);
      if (!std::isfinite(kf.t_s) || (k > 0 && !(kf.t_s > o.motion[k - 1].t_s)))
        throw InputError(where, f + ".t", "times must be finite and strictly increasing");
      if (!kf.pose.t.allFinite() || !kf.pose.q.coeffs().allFinite() ||
          std::abs(kf.pose.q.norm() - 1.0) > 1e-6)
        throw InputError(where, f, "needs a finite translation and a unit quaternion");
    }
    if (o.room < -1 || o.room >= static_cast<int>(rooms.size()))
      throw InputError(where, field + ".room", "no such room");
    if (o.physics && !(std::isfinite(o.physics->mass_kg) && o.physics->mass_kg > 0.f &&
                       std::isfinite(o.physics->friction) && o.physics->friction >= 0.f))
      throw InputError(where, field + ".physics",
                       "needs a finite mass_kg > 0 and a finite friction >= 0");
    if (o.moving() && materials[o.material].isEmissive())
      throw InputError(where, field + ".motion",
                       "an emissive object cannot move (area lights are sampled where they rest)");
  }
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (!l.object.empty() && std::none_of(objects.begin(), objects.end(),
                                          [&](const Object& o) { return o.name == l.object; }))
      throw InputError(where, fmt::format("lights[{}] ('{}').object", i, l.name),
                       fmt::format("no object is named '{}'", l.object));
    std::string field = fmt::format("lights[{}] ('{}')", i, l.name);
    if (!l.position.allFinite()) throw InputError(where, field + ".position", "must be finite");
    if (!(l.intensity >= 0.f && std::isfinite(l.intensity)))
      throw InputError(where, field + ".intensity", "must be finite and >= 0");
    if (!l.color.allFinite() || l.color.minCoeff() < 0.f)
      throw InputError(where, field + ".color", "each channel must be finite and >= 0");
    if (l.temperature_k != 0.f && !(l.temperature_k >= 1000.f && l.temperature_k <= 40000.f))
      throw InputError(where, field + ".temperature_k",
                       "must be 0 (use color) or in 1000..40000 K");
    if ((l.type == LightType::Spot || l.type == LightType::Sun) &&
        std::abs(l.direction.norm() - 1.0) > 1e-6)
      throw InputError(where, field + ".direction", "must be a unit vector");
    if (l.type == LightType::Spot && !(l.cone_deg > 0.f && l.cone_deg < 90.f &&
                                       l.falloff_deg >= 0.f && l.falloff_deg <= l.cone_deg))
      throw InputError(where, field + ".cone_deg",
                       "need 0 < cone_deg < 90 and 0 <= falloff_deg <= cone_deg");
    if (l.type == LightType::Sun &&
        !(l.angular_diameter_deg > 0.f && l.angular_diameter_deg < 30.f))
      throw InputError(where, field + ".angular_diameter_deg", "must be in (0, 30) degrees");
    if (!(l.max_distance >= 0.f)) throw InputError(where, field + ".max_distance", "must be >= 0");
    if (!(l.radius >= 0.f && l.radius < 1e3f))
      throw InputError(where, field + ".radius", "must be >= 0 (metres)");
    if (l.type == LightType::Sky && l.sky_model == SkyModel::Preetham)
      validatePreetham(l, where, field);
    if (l.type == LightType::Sky && l.sky_model == SkyModel::EnvMap)
      validateEnvMap(l, where, field);
  }
  for (const auto& m : materials) {
    const std::string field = "materials['" + m.id + "']";
    if (!m.albedo.allFinite() || m.albedo.minCoeff() < 0 || m.albedo.maxCoeff() > 1)
      throw InputError(where, field + ".albedo", "each channel must be in [0, 1]");
    if (!(m.roughness >= 0.f && m.roughness <= 1.f))
      throw InputError(where, field + ".roughness", "must be in [0, 1]");
    if (!(m.ior >= 1.0f && m.ior <= 4.0f))
      throw InputError(where, field + ".ior", "must be in [1, 4]");
    if (!m.transmittance.allFinite() || m.transmittance.minCoeff() < 0 ||
        m.transmittance.maxCoeff() > 1)
      throw InputError(where, field + ".transmittance", "each channel must be in [0, 1]");
    if (m.type == MaterialType::Translucent && (m.albedo + m.transmittance).maxCoeff() > 1.f)
      throw InputError(where, field, "albedo + transmittance must be <= 1 per channel (energy)");
    if (m.type == MaterialType::Conductor &&
        std::find(metalNames().begin(), metalNames().end(), m.metal) == metalNames().end())
      throw InputError(
          where, field + ".metal",
          fmt::format("unknown metal '{}' (valid: {})", m.metal, fmt::join(metalNames(), ", ")));
    if (!m.emission.allFinite() || m.emission.minCoeff() < 0)
      throw InputError(where, "materials['" + m.id + "'].emission", "must be finite and >= 0");
    if (!m.uv_scale.allFinite() || m.uv_scale.cwiseAbs().minCoeff() == 0.f)
      throw InputError(where, field + ".uv_scale", "must be finite and non-zero");
    const std::pair<const TextureRef*, const char*> textures[] = {
        {&m.albedo_texture, ".albedo_texture"},
        {&m.roughness_texture, ".roughness_texture"},
        {&m.normal_texture, ".normal_texture"}};
    for (const auto& [tex, key] : textures) {
      std::error_code ec;
      if (!tex->empty() && !std::filesystem::is_regular_file(tex->path, ec))
        throw InputError(where, field + key,
                         fmt::format("'{}': {}", tex->path,
                                     std::filesystem::exists(tex->path, ec) ? "is not a file"
                                                                            : "file not found"));
    }
  }
}

}  // namespace inet
