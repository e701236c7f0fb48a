#include "render/embree_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {

void errorCallback(void*, RTCError code, const char* str) {
  std::fprintf(stderr, "embree error %d: %s\n", static_cast<int>(code), str ? str : "");
}

void checkDevice(RTCDevice device, const char* what) {
  RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE)
    throw std::runtime_error(
        fmt::format("Embree failed in {} (error {})", what, static_cast<int>(err)));
}

Metal metalByName(const std::string& name) {
  for (Metal m : {Metal::Gold, Metal::Silver, Metal::Copper, Metal::Aluminium, Metal::Chromium})
    if (metalName(m) == name) return m;
  INET_CHECK_MSG(false, "unknown metal " + name + " (Scene::validate lets only known names in)");
  return Metal::Aluminium;
}

}  // namespace

BsdfParams bsdfOf(const Material& m) {
  const float alpha = roughnessToAlpha(m.roughness);
  switch (m.type) {
    case MaterialType::Lambertian:
      return makeLambertian(m.albedo);
    case MaterialType::Conductor: {
      BsdfParams p = makeMetal(metalByName(m.metal), alpha);
      p.specular_tint = m.albedo;
      return p;
    }
    case MaterialType::Plastic:
      return makePlastic(m.albedo, alpha, m.ior);
    case MaterialType::Dielectric:
      return makeDielectric(m.ior, alpha, m.transmittance);
    case MaterialType::ThinDielectric:
      return makeThinDielectric(m.ior, m.transmittance);
    case MaterialType::Translucent:
      return makeTranslucent(m.albedo, m.transmittance);
  }
  return makeLambertian(m.albedo);
}

EmbreeScene::EmbreeScene(const Scene& scene) {
  auto t0 = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create device");
  rtcSetDeviceErrorFunction(device_, errorCallback, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);

  std::vector<int> uses(scene.meshes.size(), 0);
  bool any_motion = false;
  for (const auto& o : scene.objects) {
    ++uses[o.mesh];
    any_motion = any_motion || o.moving();
  }
  mesh_scenes_.assign(scene.meshes.size(), nullptr);

  objects_.resize(scene.objects.size());
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    const Mesh& mesh = scene.meshes[o.mesh];
    const Material& mat = scene.materials[o.material];
    ObjectShading& s = objects_[i];
    s.albedo = mat.albedo;
    s.bsdf = bsdfOf(mat);
    s.emission = mat.emission;
    s.nyu40 = static_cast<uint8_t>(o.nyu40);
    s.instance = static_cast<uint16_t>(o.instance);
    setUpShading(o, mesh, mat, s);
    // with moving objects every object is an instance: a new window then rebuilds only the top
    // level over a few hundred instances, not every triangle of the static scene
    bool instanced = mesh.isSphere() || uses[o.mesh] > 1 || any_motion;
    if (instanced) {
      Eigen::Matrix3d lin = o.T_world_object.block<3, 3>(0, 0);
      s.normal_to_world = lin.inverse().transpose().cast<float>();
      RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(inst, meshScene(o.mesh, scene));
      Eigen::Matrix<float, 3, 4> xfm = o.T_world_object.block<3, 4>(0, 0).cast<float>();
      if (o.moving()) {
        rtcSetGeometryTimeStepCount(inst, kMotionSteps);
        for (int k = 0; k < kMotionSteps; ++k)
          rtcSetGeometryTransform(inst, k, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
        rtcRetainGeometry(inst);
        moving_.push_back({static_cast<int>(i), inst, o});
      } else {
        // column-major 3x4: Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
      }
      rtcCommitGeometry(inst);
      rtcAttachGeometry(scene_, inst);
      rtcReleaseGeometry(inst);
    } else {
      addTriangleMesh(mesh, &o.T_world_object);
    }
    geom_to_object_.push_back(static_cast<int>(i));
  }
  if (any_motion) {
    setWindow(0, 0);
  } else {
    rtcCommitScene(scene_);
  }
  checkDevice(device_, "scene build");
  for (const ObjectShading& s : objects_) has_panes_ = has_panes_ || s.bsdf.type == BsdfType::ThinDielectric;
  buildLights(scene);
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::~EmbreeScene() {
  for (MovingObject& m : moving_) rtcReleaseGeometry(m.instance);
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : mesh_scenes_)
    if (s) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::setWindow(TimeNs open_ns, TimeNs span_ns) {
  if (moving_.empty() || (open_ns == window_open_ && span_ns == window_span_)) return;
  window_open_ = open_ns;
  window_span_ = span_ns;
  for (MovingObject& m : moving_) {
    for (int k = 0; k < kMotionSteps; ++k) {
      const double t_s =
          1e-9 * (static_cast<double>(open_ns) +
                  static_cast<double>(span_ns) * k / static_cast<double>(kMotionSteps - 1));
      Eigen::Matrix<float, 3, 4> xfm = m.motion.transformAt(t_s).block<3, 4>(0, 0).cast<float>();
      rtcSetGeometryTransform(m.instance, k, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
    }
    rtcCommitGeometry(m.instance);
    const Mat4 T_mid = m.motion.transformAt(
        1e-9 * (static_cast<double>(open_ns) + 0.5 * static_cast<double>(span_ns)));
    ObjectShading& s = objects_[m.object];
    setObjectTransform(s, T_mid);
    s.normal_to_world = s.vertex_normal_to_world;  // an instance: Embree's Ng is in object space
  }
  rtcCommitScene(scene_);
  checkDevice(device_, "moving objects");
}

void EmbreeScene::setObjectTransform(ObjectShading& s, const Mat4& T_world_object) {
  const Mat3 L = T_world_object.block<3, 3>(0, 0);
  s.linear = L.cast<float>();
  s.vertex_normal_to_world = L.inverse().transpose().cast<float>();
}

void EmbreeScene::setUpShading(const Object& o, const Mesh& mesh, const Material& mat,
                               ObjectShading& s) {
  setObjectTransform(s, o.T_world_object);
  s.uv_scale = mat.uv_scale;
  s.roughness = mat.roughness;
  const std::string field = "materials['" + mat.id + "']";
  auto texture = [&](const TextureRef& ref, TextureEncoding enc, const char* key) {
    return ref.empty() ? nullptr : textures_.get(ref.path, enc, "", field + key);
  };
  s.albedo_map = texture(mat.albedo_texture, TextureEncoding::Srgb, ".albedo_texture");
  s.roughness_map = texture(mat.roughness_texture, TextureEncoding::Linear, ".roughness_texture");
  s.normal_map = texture(mat.normal_texture, TextureEncoding::Linear, ".normal_texture");
  const bool textured = mat.isTextured();
  if (mesh.isSphere()) {
    if (textured) s.sphere_radius = mesh.sphere_radius;
    return;
  }
  if (mesh.normals.empty() && !(textured && !mesh.uvs.empty())) return;
  if (attributes_.size() <= static_cast<size_t>(o.mesh)) attributes_.resize(o.mesh + 1);
  auto& a = attributes_[o.mesh];
  if (!a) {
    a = std::make_unique<MeshAttributes>();
    a->positions = mesh.positions;
    a->triangles = mesh.triangles;
    a->normals = mesh.normals;
    for (Vec3f& n : a->normals) n.normalize();
    a->uvs = mesh.uvs;
  }
  s.attributes = a.get();
}

void EmbreeScene::surface(int object, unsigned prim, float u, float v, const Vec3f& ng,
                          const Vec3f& d, float footprint, SurfacePoint& sp,
                          bool normal_map) const {
  const ObjectShading& s = objects_[object];
  sp.ng = ng;
  sp.ns = ng;
  sp.albedo = s.albedo;
  sp.bsdf = s.bsdf;
  if (s.plain()) return;
  Vec2f uv = Vec2f::Zero();
  float uv_per_metre = 0.f;  // sqrt(texture-space area / world area) of the surface
  Vec3f dpdu = Vec3f::Zero(), dpdv = Vec3f::Zero();
  if (s.sphere_radius > 0.f) {
    // object-space unit normal = direction from the centre; u = longitude, v = up the sphere
    const Vec3f n = (s.linear.transpose() * ng).normalized();
    const float phi = std::atan2(n.y(), n.x()), theta = std::acos(std::clamp(n.z(), -1.f, 1.f));
    const float r = s.sphere_radius, two_pi = 2.f * static_cast<float>(M_PI);
    uv = Vec2f(phi / two_pi + 0.5f, 1.f - theta / static_cast<float>(M_PI));
    const float scale = std::cbrt(std::fabs(s.linear.determinant()));
    uv_per_metre = 1.f / (std::sqrt(4.f * static_cast<float>(M_PI)) * r * scale);
    dpdu = s.linear * Vec3f(-n.y(), n.x(), 0.f) * (two_pi * r);
    dpdv = s.linear * Vec3f(n.z() * std::cos(phi), n.z() * std::sin(phi), -std::sin(theta)) *
           (-static_cast<float>(M_PI) * r);
  } else {
    const MeshAttributes& a = *s.attributes;
    const Tri& t = a.triangles[prim];
    const float w = 1.f - u - v;
    if (!a.normals.empty()) {
      Vec3f n = s.vertex_normal_to_world *
                (w * a.normals[t[0]] + u * a.normals[t[1]] + v * a.normals[t[2]]);
      if (n.squaredNorm() > 1e-12f) sp.ns = n.normalized();
    }
    if (!a.uvs.empty()) {
      const Vec2f uv0 = a.uvs[t[0]], duv1 = a.uvs[t[1]] - uv0, duv2 = a.uvs[t[2]] - uv0;
      uv = uv0 + u * duv1 + v * duv2;
      const Vec3f e1 = s.linear * (a.positions[t[1]] - a.positions[t[0]]);
      const Vec3f e2 = s.linear * (a.positions[t[2]] - a.positions[t[0]]);
      const float det = duv1.x() * duv2.y() - duv1.y() * duv2.x();
      const float area2 = e1.cross(e2).norm();
      if (area2 > 0.f) uv_per_metre = std::sqrt(std::fabs(det) / area2);
      if (std::fabs(det) > 1e-20f) {
        dpdu = (e1 * duv2.y() - e2 * duv1.y()) / det;
        dpdv = (e2 * duv1.x() - e1 * duv2.x()) / det;
      }
    }
  }
  if (sp.ns.dot(ng) < 0.f) sp.ns = -sp.ns;  // vertex normals only bend the surface, never flip it
  // texture lookups: tiling scales texture space, so both the coordinates and the footprint
  uv = uv.cwiseProduct(s.uv_scale);
  const float tiling = std::sqrt(std::fabs(s.uv_scale.x() * s.uv_scale.y()));
  const float cos_view = std::max(std::fabs(d.dot(ng)), 0.05f);  // grazing: cap the stretch
  const float fp = footprint / cos_view * uv_per_metre * tiling;
  if (s.albedo_map) {
    const Vec3f c = s.albedo_map->rgb(uv, fp).cwiseMax(0.f).cwiseMin(1.f);
    sp.albedo = s.albedo.cwiseProduct(c);
    switch (sp.bsdf.type) {
      case BsdfType::Conductor:
        sp.bsdf.specular_tint = sp.bsdf.specular_tint.cwiseProduct(c);
        break;
      case BsdfType::Lambertian:
      case BsdfType::Plastic:
      case BsdfType::Translucent:
        sp.bsdf.albedo = sp.bsdf.albedo.cwiseProduct(c);
        break;
      default:
        break;
    }
  }
  if (s.roughness_map) {
    const int c = s.roughness_map->channels() >= 3 ? 1 : 0;  // glTF: roughness in G
    const float r = std::clamp(s.roughness * s.roughness_map->channel(uv, fp, c), 0.f, 1.f);
    sp.bsdf.alpha_x = sp.bsdf.alpha_y = roughnessToAlpha(r);
  }
  if (normal_map && s.normal_map && dpdu.squaredNorm() > 0.f && dpdv.squaredNorm() > 0.f) {
    const Vec3f m = s.normal_map->rgb(uv, fp) * 2.f - Vec3f::Ones();
    const Vec3f& n = sp.ns;
    const Vec3f T = (dpdu - n * n.dot(dpdu)).normalized();
    const Vec3f B = (dpdv - n * n.dot(dpdv) - T * T.dot(dpdv)).normalized();
    Vec3f mapped = T * m.x() + B * m.y() + n * std::max(m.z(), 0.f);
    // a mapped normal may not tip below the surface: keep it at least ~3 degrees above
    if (mapped.allFinite() && mapped.squaredNorm() > 1e-12f) {
      mapped.normalize();
      const float c = mapped.dot(ng);
      if (c < 0.05f) mapped = (mapped + (0.05f - c) * ng).normalized();
      sp.ns = mapped;
    }
  }
}

void EmbreeScene::addTriangleMesh(const Mesh& mesh, const Mat4* T_world_object) {
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                        mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    Vec3f p = mesh.positions[i];
    if (T_world_object)
      p = (*T_world_object * p.cast<double>().homogeneous()).head<3>().cast<float>();
    v[3 * i] = p.x();
    v[3 * i + 1] = p.y();
    v[3 * i + 2] = p.z();
  }
  auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                             mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.triangles[i][k];
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
}

RTCScene EmbreeScene::meshScene(int mesh_index, const Scene& scene) {
  if (mesh_scenes_[mesh_index]) return mesh_scenes_[mesh_index];
  const Mesh& mesh = scene.meshes[mesh_index];
  RTCScene sub = rtcNewScene(device_);
  RTCGeometry geom;
  if (mesh.isSphere()) {
    geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* p = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    p[0] = p[1] = p[2] = 0.f;
    p[3] = mesh.sphere_radius;
  } else {
    geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.positions.size()));
    std::copy_n(mesh.positions.front().data(), 3 * mesh.positions.size(), v);
    auto* idx = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), mesh.triangles.size()));
    std::copy_n(mesh.triangles.front().data(), 3 * mesh.triangles.size(), idx);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(sub, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(sub);
  checkDevice(device_, "mesh build");
  mesh_scenes_[mesh_index] = sub;
  return sub;
}

namespace {

/// Triangle t of object o's mesh in world space; a degenerate one has area 0 and normal +z.
WorldTriangle worldTriangle(const Object& o, const Mesh& mesh, const Tri& t) {
  Vec3f p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = (o.T_world_object * mesh.positions[t[k]].cast<double>().homogeneous())
               .head<3>()
               .cast<float>();
  WorldTriangle w;
  w.p0 = p[0];
  w.e1 = p[1] - p[0];
  w.e2 = p[2] - p[0];
  const Vec3f c = w.e1.cross(w.e2);
  w.area = 0.5f * c.norm();
  w.normal = c.norm() > 0 ? Vec3f(c.normalized()) : Vec3f(0, 0, 1);
  return w;
}


/// A glass object is a window pane only when it is simple: at most this many triangles.
/// Glassware, vases and lamp shades of furniture models (hundreds of triangles) are no way to
/// the sky, and the portal pick is linear in the portals: a catalog apartment's glasses made
/// its frames 80x slower when they counted.
constexpr size_t kMaxPaneTriangles = 64;

/// A probe of the scene from one side of a plane: ray k of `count` leaving the plane's
/// triangles (a point by area, R2 sequence) cosine-distributed about unit normal n (Fibonacci
/// lattice). Deterministic: a fixed point set and no random state.
struct PlaneProbe {
  const std::vector<WorldTriangle>& triangles;
  const std::vector<size_t>& members;
  float area;

  Vec3f point(int k) const {
    const float u0 = std::fmod(0.5f + 0.7548776662f * float(k), 1.f);
    const float u1 = std::fmod(0.5f + 0.5698402910f * float(k), 1.f);
    const float u2 = std::fmod(0.5f + 0.6180339887f * float(k), 1.f);
    float target = u0 * area;
    size_t pick = members.back();
    for (size_t i : members)
      if ((target -= triangles[i].area) < 0.f) {
        pick = i;
        break;
      }
    return triangles[pick].point({u1, u2});
  }
};

/// Direction k of `count` cosine-distributed about unit n (Fibonacci lattice).
Vec3f cosineLattice(const Vec3f& n, int k, int count) {
  const Vec3f a = std::abs(n.x()) < 0.9f ? Vec3f::UnitX() : Vec3f::UnitY();
  const Vec3f b1 = n.cross(a).normalized(), b2 = n.cross(b1);
  const float r = std::sqrt((float(k) + 0.5f) / float(count));
  const float phi = 2.39996323f * float(k);
  return (b1 * (r * std::cos(phi)) + b2 * (r * std::sin(phi)) +
          n * std::sqrt(std::max(0.f, 1.f - r * r)))
      .normalized();
}

/// The first surface along o + t d: false when the ray leaves the scene. With `through_glass`
/// it goes straight through thin dielectrics (at most 8). `p` and `n` receive the hit point
/// and its unit geometric normal.
bool firstSurface(const EmbreeScene& es, Vec3f o, const Vec3f& d, bool through_glass, Vec3f& p,
                  Vec3f& n) {
  RTCIntersectContext ictx;
  rtcInitIntersectContext(&ictx);
  for (int glass = 0; glass <= 8; ++glass) {
    RTCRayHit rh;
    rh.ray.org_x = o.x(), rh.ray.org_y = o.y(), rh.ray.org_z = o.z();
    rh.ray.dir_x = d.x(), rh.ray.dir_y = d.y(), rh.ray.dir_z = d.z();
    rh.ray.tnear = 0.f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0.f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(es.handle(), &ictx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    const int object = es.objectOf(rh.hit);
    p = o + rh.ray.tfar * d;
    n = es.worldNormal(object, Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    if (!through_glass || es.object(object).bsdf.type != BsdfType::ThinDielectric) return true;
    o = p + n * (n.dot(d) > 0.f ? 1.f : -1.f) * (1e-4f * (1.f + p.cwiseAbs().maxCoeff()));
  }
  return true;
}

/// The faces of a simple glass object (world triangles) that are windows onto the sky: the
/// sky portals and the sun photons' starting faces (lights.h, path_tracer.cpp Photons), each
/// triangle's normal turned to face the inside. The triangles are grouped into planes (normals
/// within 0.8 degrees, offsets within 0.25 mm); a plane with at least a quarter of the largest
/// one's area is a face. A flat pane is one face that looks both ways; a glass sheet modelled
/// as a thin box (Sweet Home 3D's windows, 1 mm thick) has two large faces, each looking away
/// from the box's centre, and four narrow edges. A face is a window when, looking out on such
/// a side:
///   - it sees the sky: of kProbeRays rays leaving it, at least kSkyShare hit nothing, panes
///     included. That is the outer face of a window's outermost glass: its inner face, the
///     glass of a second glazing behind it, a cabinet's glass door and a glass table top
///     indoors see walls or other glass (their samples would find the sky only through the
///     outer face, which already offers those directions, and a photon starting on an inner
///     face is stopped by the outer one);
///   - and what lies behind it is enclosed: from the first surfaces kInsideRays rays into the
///     other side meet (straight through glass), at most kOpenShare of kInsideRays x
///     kBackRays rays see the sky directly (glass counting as opaque). A room sees the sky only
///     through its windows; glass standing in the open (a pane before a wall under the sky)
///     is no window, and sky samples sent through it would be wasted on a wall the whole sky
///     lights.
std::vector<PortalTriangle> skyFacingFaces(const EmbreeScene& es,
                                           const std::vector<WorldTriangle>& glass) {
  constexpr float kCosSamePlane = 0.9999f, kSamePlane = 2.5e-4f;
  constexpr int kProbeRays = 64, kInsideRays = 16, kBackRays = 8;
  constexpr float kSkyShare = 0.125f, kOpenShare = 0.1f;
  struct Plane {
    Vec3f normal, point;
    float area = 0.f;
    std::vector<size_t> triangles;
  };
  std::vector<Plane> planes;
  Vec3f centre = Vec3f::Zero();
  float total_area = 0.f;
  for (size_t i = 0; i < glass.size(); ++i) {
    const WorldTriangle& t = glass[i];
    if (!(t.area > 0.f)) continue;
    centre += t.area * (t.p0 + (t.e1 + t.e2) * (1.f / 3.f));
    total_area += t.area;
    auto on = [&](const Plane& pl) {
      if (std::abs(pl.normal.dot(t.normal)) < kCosSamePlane) return false;
      for (const Vec3f& q : {t.p0, Vec3f(t.p0 + t.e1), Vec3f(t.p0 + t.e2)})
        if (std::abs(pl.normal.dot(q - pl.point)) > kSamePlane) return false;
      return true;
    };
    auto it = std::find_if(planes.begin(), planes.end(), on);
    if (it == planes.end()) {
      planes.push_back({t.normal, t.p0, 0.f, {}});
      it = planes.end() - 1;
    }
    it->area += t.area;
    it->triangles.push_back(i);
  }
  std::vector<PortalTriangle> out;
  if (!(total_area > 0.f)) return out;
  centre /= total_area;
  float largest = 0.f;
  for (const Plane& pl : planes) largest = std::max(largest, pl.area);
  auto offset = [](const Vec3f& q, const Vec3f& n) {
    return Vec3f(q + n * (2e-4f * (1.f + q.cwiseAbs().maxCoeff())));
  };
  for (const Plane& pl : planes) {
    if (pl.area < 0.25f * largest) continue;
    const PlaneProbe probe{glass, pl.triangles, pl.area};
    // the sides to look from: away from the object's centre (both for a flat pane)
    const float centre_side = pl.normal.dot(centre - pl.point);
    std::vector<Vec3f> sides;
    if (centre_side <= kSamePlane) sides.push_back(pl.normal);
    if (centre_side >= -kSamePlane) sides.push_back(-pl.normal);
    for (const Vec3f& n : sides) {
      Vec3f p, ng;
      int sky = 0;
      for (int k = 0; k < kProbeRays; ++k)
        sky += !firstSurface(es, offset(probe.point(k), n), cosineLattice(n, k, kProbeRays),
                             false, p, ng);
      if (sky < static_cast<int>(kSkyShare * kProbeRays)) continue;
      int open = 0;
      for (int k = 0; k < kInsideRays; ++k) {
        const Vec3f d = cosineLattice(-n, k, kInsideRays);
        if (!firstSurface(es, offset(probe.point(k), -n), d, true, p, ng)) {
          open += kBackRays;  // out into the open on the far side too
          continue;
        }
        const Vec3f facing = ng.dot(d) < 0.f ? ng : Vec3f(-ng);
        Vec3f q, nq;
        for (int j = 0; j < kBackRays; ++j)
          open += !firstSurface(es, offset(p, facing),
                                cosineLattice(facing, k * kBackRays + j, kInsideRays * kBackRays),
                                false, q, nq);
      }
      if (open > static_cast<int>(kOpenShare * kInsideRays * kBackRays)) continue;
      for (size_t i : pl.triangles) {
        PortalTriangle t = glass[i];
        if (t.normal.dot(n) > 0.f) t.normal = -t.normal;  // facing the inside
        out.push_back(t);
      }
      break;
    }
  }
  return out;
}
}  // namespace

void EmbreeScene::buildLights(const Scene& scene) {
  std::vector<EmissiveTriangle> triangles;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    const Material& mat = scene.materials[o.material];
    const Mesh& mesh = scene.meshes[o.mesh];
    if (!mat.isEmissive() || mesh.isSphere()) continue;  // emissive spheres: not sampled yet
    objects_[i].first_light = static_cast<int>(triangles.size());
    for (const Tri& t : mesh.triangles) {
      EmissiveTriangle e;
      static_cast<WorldTriangle&>(e) = worldTriangle(o, mesh, t);
      e.radiance = mat.emission;
      e.group = static_cast<int>(i);
      triangles.push_back(e);
    }
  }
  // window panes: skies are also sampled through them (lights.h, sky portals), and sun photons
  // start on them, at their rest placement (a moving pane would only make the portal less apt,
  // never the image biased); SceneLights drops degenerate triangles. See skyFacingFaces.
  std::vector<PortalTriangle> portals;
  for (const Object& o : scene.objects) {
    const Mesh& mesh = scene.meshes[o.mesh];
    if (scene.materials[o.material].type != MaterialType::ThinDielectric || mesh.isSphere() ||
        mesh.triangles.size() > kMaxPaneTriangles)
      continue;
    std::vector<WorldTriangle> glass;
    for (const Tri& t : mesh.triangles) glass.push_back(worldTriangle(o, mesh, t));
    const std::vector<PortalTriangle> faces = skyFacingFaces(*this, glass);
    portals.insert(portals.end(), faces.begin(), faces.end());
  }
  lights_ = std::make_unique<SceneLights>(scene, std::move(triangles), std::move(portals));
}

}  // namespace inet
