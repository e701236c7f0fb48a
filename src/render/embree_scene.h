#pragma once
// The renderer's view of a Scene: an Embree BVH plus the per-object shading table that maps a
// hit back to its object (geomID -> object, as Embree's tutorials recommend), and the list of
// emissive triangles for light sampling. Internal to src/render: no rtc handle leaves it.
//
// Meshes used by one object are baked into world space in the top-level BVH (one level of
// traversal, fastest for imported scenes); meshes shared by several objects, and analytic
// spheres, are built once and instanced.
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "render/bsdf.h"
#include "render/lights.h"
#include "scene/scene.h"

namespace inet {

/// What shading and the ground-truth passes need to know about the object a ray hit.
struct ObjectShading {
  BsdfParams bsdf;
  Vec3f albedo;
  Vec3f emission;
  uint8_t nyu40 = 0;
  uint16_t instance = 0;
  Eigen::Matrix3f normal_to_world = Eigen::Matrix3f::Identity();  ///< inverse transpose
  int first_light = -1;  ///< index of this object's first emissive triangle, -1 if none
};

/// The BSDF of a scene material (roughness -> GGX alpha, metal preset -> complex IOR).
BsdfParams bsdfOf(const Material& m);

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  /// Index of the object hit; call only for a valid hit.
  int objectOf(const RTCHit& hit) const {
    unsigned top = hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? hit.instID[0] : hit.geomID;
    return geom_to_object_[top];
  }
  int objectOf(unsigned geom_id, unsigned inst_id) const {
    return geom_to_object_[inst_id != RTC_INVALID_GEOMETRY_ID ? inst_id : geom_id];
  }
  const ObjectShading& object(int i) const { return objects_[i]; }
  /// Unit world-space geometric normal from an object-space Ng.
  Vec3f worldNormal(int object, const Vec3f& ng_object) const {
    return (objects_[object].normal_to_world * ng_object).normalized();
  }

  /// Every light that is on (emissive triangles first), for next-event estimation.
  const SceneLights& lights() const { return *lights_; }
  double buildMs() const { return build_ms_; }

 private:
  void addTriangleMesh(const Mesh& mesh, const Mat4* T_world_object);
  RTCScene meshScene(int mesh_index, const Scene& scene);
  void buildLights(const Scene& scene);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;  ///< per mesh, for instanced meshes (nullptr otherwise)
  std::vector<int> geom_to_object_;
  std::vector<ObjectShading> objects_;
  std::unique_ptr<SceneLights> lights_;
  double build_ms_ = 0;
};

}  // namespace inet
