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
#include "render/texture.h"
#include "scene/scene.h"

namespace inet {

/// Object-space vertex data of one mesh that shading interpolates (kept only for meshes with
/// vertex normals or texture coordinates on a textured object).
struct MeshAttributes {
  std::vector<Vec3f> positions;
  std::vector<Tri> triangles;
  std::vector<Vec3f> normals;  ///< empty: flat
  std::vector<Vec2f> uvs;      ///< empty: none
};

/// What shading and the ground-truth passes need to know about the object a ray hit.
struct ObjectShading {
  BsdfParams bsdf;
  Vec3f albedo;
  Vec3f emission;
  uint8_t nyu40 = 0;
  uint16_t instance = 0;
  Eigen::Matrix3f normal_to_world = Eigen::Matrix3f::Identity();  ///< for Embree's Ng
  int first_light = -1;  ///< index of this object's first emissive triangle, -1 if none
  // Smooth shading and textures (all null/identity for a flat, untextured object):
  const MeshAttributes* attributes = nullptr;
  Eigen::Matrix3f linear = Eigen::Matrix3f::Identity();  ///< object-to-world linear part
  Eigen::Matrix3f vertex_normal_to_world = Eigen::Matrix3f::Identity();  ///< its inv. transpose
  float sphere_radius = 0.f;  ///< > 0: analytic sphere (texture coordinates from its angles)
  const Texture* albedo_map = nullptr;
  const Texture* roughness_map = nullptr;
  const Texture* normal_map = nullptr;
  Vec2f uv_scale{1.f, 1.f};
  float roughness = 0.f;  ///< the material's, which a roughness map multiplies
  bool plain() const { return attributes == nullptr && sphere_radius == 0.f; }
};

/// A shading point: what the path tracer and the albedo/normal passes read at a hit.
struct SurfacePoint {
  Vec3f ng;      ///< unit geometric normal, world space, on the side the winding makes "out"
  Vec3f ns;      ///< unit shading normal (vertex normals, normal map), on ng's side
  Vec3f albedo;  ///< diffuse reflectance after textures (the albedo pass)
  BsdfParams bsdf;
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

  /// Shading at a hit of `object` (triangle `prim`, barycentrics u, v; unit world geometric
  /// normal `ng`), seen along unit direction `d`. `footprint` is the width in
  /// metres of the pixel's footprint perpendicular to the ray (ray cone, Akenine-Moller et al.
  /// 2019), which picks the texture mip level; 0 reads the finest level. `normal_map` = false
  /// leaves a material's normal map out (the ground-truth normal pass).
  void surface(int object, unsigned prim, float u, float v, const Vec3f& ng, const Vec3f& d,
               float footprint, SurfacePoint& sp, bool normal_map = true) const;
  /// True when some object moves (Object::motion). Every object is then an instance, so that a
  /// new exposure window only rebuilds the top level.
  bool hasMotion() const { return !moving_.empty(); }
  /// True when some object is a thin pane (ThinDielectric): shadow rays must look through them.
  bool hasPanes() const { return has_panes_; }
  /// Places moving objects for an exposure window starting at scene time `open_ns` and lasting
  /// `span_ns` (0: an instant). Rays carry time = (t - open) / span in [0, 1]; Embree
  /// interpolates each moving instance between kMotionSteps transforms spread over the window.
  /// Shading frames (normal matrices) use the transform at the window's middle. Not thread-safe:
  /// call between renders.
  void setWindow(TimeNs open_ns, TimeNs span_ns);
  static constexpr int kMotionSteps = 9;

  /// Memory held by textures.
  size_t textureBytes() const { return textures_.bytes(); }

  /// Every light that is on (emissive triangles first), for next-event estimation.
  const SceneLights& lights() const { return *lights_; }
  double buildMs() const { return build_ms_; }

 private:
  void addTriangleMesh(const Mesh& mesh, const Mat4* T_world_object);
  void setUpShading(const Object& o, const Mesh& mesh, const Material& mat, ObjectShading& s);
  /// Sets the shading transforms (linear part, vertex-normal matrix) of an object's placement.
  static void setObjectTransform(ObjectShading& s, const Mat4& T_world_object);
  RTCScene meshScene(int mesh_index, const Scene& scene);
  void buildLights(const Scene& scene);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;  ///< per mesh, for instanced meshes (nullptr otherwise)
  std::vector<int> geom_to_object_;
  std::vector<ObjectShading> objects_;
  bool has_panes_ = false;
  std::vector<std::unique_ptr<MeshAttributes>> attributes_;  ///< per mesh, or null
  TextureCache textures_;
  struct MovingObject {
    int object;
    RTCGeometry instance;  ///< retained
    Object motion;         ///< a copy: rest transform and keyframes
  };
  std::vector<MovingObject> moving_;
  TimeNs window_open_ = -1, window_span_ = -1;  ///< the window set last
  std::unique_ptr<SceneLights> lights_;
  double build_ms_ = 0;
};

}  // namespace inet
