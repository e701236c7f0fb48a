#pragma once
// The in-memory scene model every stage reads (DESIGN.md section 2).
//
// Meshes are shared: many objects may point at one mesh with different transforms (the renderer
// builds each mesh once and instances it). An object is one mesh placed in the world with one
// material, one NYU40 class and one instance id; several objects may share an instance id when
// they are parts of one piece of furniture (a table top and its legs).
// Units: metres. World frame: right-handed, Z up, floor at z = 0.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"

namespace inet {

using Vec3f = Eigen::Vector3f;
using Tri = Eigen::Matrix<uint32_t, 3, 1>;

/// Where a mesh came from, so a layout file can be written back without inlining geometry.
struct MeshSource {
  enum class Kind { Primitive, File, Inline };
  Kind kind = Kind::Inline;
  std::string primitive;                 ///< Primitive: "box", "cylinder", "quad", "sphere"
  std::map<std::string, double> params;  ///< Primitive parameters (see primitives.h)
  std::string file;                      ///< File: path as written in the layout (relative to it)
  double scale = 1.0;                    ///< File: metres per file unit
  char up = 'z';                         ///< File: up axis of the file, 'y' or 'z'
  std::string mesh_name;                 ///< File: pick one mesh by name ("" = all merged)
};

/// Geometry in object space: triangles, or one analytic sphere (centre 0, `sphere_radius`).
struct Mesh {
  std::string id;
  MeshSource source;
  std::vector<Vec3f> positions;
  std::vector<Tri> triangles;
  float sphere_radius = 0.0f;  ///< > 0 marks an analytic sphere; positions/triangles then empty
  bool isSphere() const { return sphere_radius > 0.0f; }
};

/// Material families (issue 3 adds microfacet, dielectric and transmission).
enum class MaterialType { Lambertian };

struct Material {
  std::string id;
  MaterialType type = MaterialType::Lambertian;
  Vec3f albedo{0.8f, 0.8f, 0.8f};  ///< linear RGB reflectance
  Vec3f emission{0.f, 0.f, 0.f};   ///< emitted radiance (W sr^-1 m^-2, linear RGB), one-sided
                                   ///< along the geometric normal
  bool isEmissive() const { return emission.maxCoeff() > 0.0f; }
};

struct Object {
  std::string name;
  int mesh = -1;      ///< index into Scene::meshes
  int material = -1;  ///< index into Scene::materials
  Mat4 T_world_object = Mat4::Identity();
  int nyu40 = 0;     ///< NYU40 class id, 0 = void / unlabelled, 1..40
  int instance = 0;  ///< instance id (1..65535), shared by the parts of one object
};

/// A point light (isotropic): radiant intensity in W/sr per RGB channel.
struct PointLight {
  std::string name;
  Vec3 position = Vec3::Zero();
  Vec3f intensity{0.f, 0.f, 0.f};
};

struct Scene {
  std::string name = "scene";
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Object> objects;
  std::vector<PointLight> point_lights;

  int findMesh(const std::string& id) const;
  int findMaterial(const std::string& id) const;
  /// Axis-aligned bounds of all objects in world space (min, max).
  std::pair<Vec3, Vec3> bounds() const;
  size_t triangleCount() const;  ///< counted per object (instanced triangles count each time)
  /// Checks indices, NYU40 range, instance range, finite transforms. Throws InputError naming
  /// `where` (the source file) and the offending object.
  void validate(const std::string& where) const;
};

}  // namespace inet
