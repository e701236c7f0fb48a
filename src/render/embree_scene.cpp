#include "render/embree_scene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
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
  for (const auto& o : scene.objects) ++uses[o.mesh];
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
    bool instanced = mesh.isSphere() || uses[o.mesh] > 1;
    if (instanced) {
      Eigen::Matrix3d lin = o.T_world_object.block<3, 3>(0, 0);
      s.normal_to_world = lin.inverse().transpose().cast<float>();
      RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(inst, meshScene(o.mesh, scene));
      Eigen::Matrix<float, 3, 4> xfm = o.T_world_object.block<3, 4>(0, 0).cast<float>();
      // column-major 3x4: Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR
      rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
      rtcCommitGeometry(inst);
      rtcAttachGeometry(scene_, inst);
      rtcReleaseGeometry(inst);
    } else {
      addTriangleMesh(mesh, &o.T_world_object);
    }
    geom_to_object_.push_back(static_cast<int>(i));
  }
  rtcCommitScene(scene_);
  checkDevice(device_, "scene build");
  buildLights(scene);
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : mesh_scenes_)
    if (s) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
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

void EmbreeScene::buildLights(const Scene& scene) {
  std::vector<EmissiveTriangle> triangles;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    const Material& mat = scene.materials[o.material];
    const Mesh& mesh = scene.meshes[o.mesh];
    if (!mat.isEmissive() || mesh.isSphere()) continue;  // emissive spheres: not sampled yet
    objects_[i].first_light = static_cast<int>(triangles.size());
    for (const Tri& t : mesh.triangles) {
      Vec3f p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = (o.T_world_object * mesh.positions[t[k]].cast<double>().homogeneous())
                   .head<3>()
                   .cast<float>();
      EmissiveTriangle e;
      e.p0 = p[0];
      e.e1 = p[1] - p[0];
      e.e2 = p[2] - p[0];
      Vec3f c = e.e1.cross(e.e2);
      e.area = 0.5f * c.norm();
      e.normal = c.norm() > 0 ? Vec3f(c.normalized()) : Vec3f(0, 0, 1);
      e.radiance = mat.emission;
      triangles.push_back(e);
    }
  }
  float radius = 1.f;
  if (!scene.objects.empty()) {
    auto [lo, hi] = scene.bounds();
    radius = std::max(radius, static_cast<float>(0.5 * (hi - lo).norm()));
  }
  lights_ = std::make_unique<SceneLights>(scene, std::move(triangles), radius);
}

}  // namespace inet
