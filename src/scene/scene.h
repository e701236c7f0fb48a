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
using Vec2f = Eigen::Vector2f;

/// Where a mesh came from, so a layout file can be written back without inlining geometry.
struct MeshSource {
  enum class Kind { Primitive, File, Inline, Catalog };
  Kind kind = Kind::Inline;
  std::string primitive;                 ///< Primitive: "box", "cylinder", "fold", "quad", "sphere"
  std::map<std::string, double> params;  ///< Primitive parameters (see primitives.h)
  std::string file;                      ///< File: path as written in the layout (relative to it)
  double scale = 1.0;                    ///< File: metres per file unit
  char up = 'z';                         ///< File: up axis of the file, 'y' or 'z'
  std::string mesh_name;                 ///< File: pick one mesh by name ("" = all merged)
  std::string catalog_piece;  ///< Catalog: a furniture catalog piece's id (scene/catalog_ref.h)
  int catalog_part = 0;       ///< Catalog: which part of the piece's model
};

/// Geometry in object space: triangles, or one analytic sphere (centre 0, `sphere_radius`).
/// `normals` and `uvs`, when not empty, have one entry per position: smooth shading normals
/// (object space, non-zero; the renderer normalises them) and texture coordinates (OpenGL
/// convention: v points up the image).
struct Mesh {
  std::string id;
  MeshSource source;
  std::vector<Vec3f> positions;
  std::vector<Tri> triangles;
  std::vector<Vec3f> normals;  ///< per-vertex shading normals; empty = flat (geometric) shading
  std::vector<Vec2f> uvs;      ///< per-vertex texture coordinates; empty = untextured
  float sphere_radius = 0.0f;  ///< > 0 marks an analytic sphere; positions/triangles then empty
  bool isSphere() const { return sphere_radius > 0.0f; }
};

/// Material families: the InteriorNet paper's four (Lambertian; microfacet: conductor and
/// coated plastic; dielectric: rough/smooth glass and thin panes; transmission: translucent).
enum class MaterialType { Lambertian, Conductor, Plastic, Dielectric, ThinDielectric, Translucent };

/// An image file a material reads: `file` as written in the layout (relative to the layout's
/// folder, so saving reproduces it) and `path`, the resolved path the renderer opens.
struct TextureRef {
  std::string file;
  std::string path;
  bool empty() const { return path.empty(); }
  bool operator==(const TextureRef&) const = default;
};

struct Material {
  std::string id;
  MaterialType type = MaterialType::Lambertian;
  Vec3f albedo{0.8f, 0.8f, 0.8f};   ///< linear RGB diffuse reflectance (plastic: base colour;
                                    ///< conductor: tint of the specular reflection)
  Vec3f emission{0.f, 0.f, 0.f};    ///< emitted radiance (W sr^-1 m^-2, linear RGB), one-sided
                                    ///< along the geometric normal
  float roughness = 0.f;            ///< perceptual roughness in [0, 1]; GGX alpha = roughness^2
  std::string metal = "aluminium";  ///< conductor: measured preset (see metalNames())
  float ior = 1.5f;                 ///< plastic coating, dielectric (relative index of refraction)
  Vec3f transmittance{1.f, 1.f, 1.f};  ///< dielectric tint / translucent diffuse transmission
  // Textures (need the mesh's uvs; a mesh without uvs reads texel (0, 0)):
  TextureRef albedo_texture;     ///< sRGB-encoded colour image; multiplies `albedo` (as glTF)
  TextureRef roughness_texture;  ///< linear image, grey or the G channel of RGB (glTF's
                                 ///< metallic-roughness layout); multiplies `roughness`
  TextureRef normal_texture;     ///< tangent-space normal map, linear, OpenGL convention (+Y up)
  Vec2f uv_scale{1.f, 1.f};      ///< texture coordinates are multiplied by this (tiling)
  /// A material of a furniture catalog piece's model (scene/catalog_ref.h): layout.json names
  /// it by piece and material instead of writing its values and texture paths. "" = our own.
  std::string catalog_piece, catalog_material;
  bool isTextured() const {
    return !albedo_texture.empty() || !roughness_texture.empty() || !normal_texture.empty();
  }
  bool isEmissive() const { return emission.maxCoeff() > 0.0f; }
};

/// Material type names as written in layout files ("lambertian", "conductor", ...).
const char* materialTypeName(MaterialType t);
/// Conductor presets the renderer knows: gold, silver, copper, aluminium, chromium.
const std::vector<std::string>& metalNames();

/// One keyframe of an object's rigid motion: at scene time `t_s` (seconds since the sequence's
/// first frame) the object sits at `pose * T_world_object`, i.e. `pose` moves its rest placement
/// rigidly in the world. Between keyframes the pose is interpolated (linear translation, slerp
/// rotation); before the first and after the last it holds.
struct ObjectKeyframe {
  double t_s = 0.0;
  Pose pose;
};

/// The physics record of an object (the InteriorNet paper's: mass, friction, movable), for
/// physics-based rearrangement. The same on every part of one instance.
struct PhysicsProps {
  float mass_kg = 1.f;    ///< > 0
  float friction = 0.5f;  ///< Coulomb friction coefficient, >= 0
  bool movable = false;   ///< may a rearrangement move it
  bool operator==(const PhysicsProps&) const = default;
};

struct Object {
  std::string name;
  int mesh = -1;      ///< index into Scene::meshes
  int material = -1;  ///< index into Scene::materials
  Mat4 T_world_object = Mat4::Identity();
  int nyu40 = 0;     ///< NYU40 class id, 0 = void / unlabelled, 1..40
  int instance = 0;  ///< instance id (1..65535), shared by the parts of one object
  std::vector<ObjectKeyframe> motion;  ///< empty: static; else sorted by strictly rising t_s
  std::string kind;  ///< fine-grained category ("sofa", "nightstand"); "" = the NYU40 class
  std::string part;  ///< part of the instance ("seat", "leg_2"); "" = the whole object
  int room = -1;     ///< index into Scene::rooms, -1 = none
  std::optional<PhysicsProps> physics;  ///< absent = unknown (imported scenes)

  bool moving() const { return !motion.empty(); }
  /// An object with the essentials set and every optional field at its default.
  static Object make(std::string name, int mesh, int material, const Mat4& T_world_object,
                     int nyu40, int instance) {
    Object o;
    o.name = std::move(name);
    o.mesh = mesh;
    o.material = material;
    o.T_world_object = T_world_object;
    o.nyu40 = nyu40;
    o.instance = instance;
    return o;
  }
  /// Object-to-world transform at scene time t_s (T_world_object when static).
  Mat4 transformAt(double t_s) const;
};

/// Analytic lights (area lights are emissive materials on geometry).
enum class LightType { Point, Spot, Sun, Sky };

/// How a sky's radiance varies with direction: the same from everywhere (uniform), the
/// clear daylight sky of Preetham, Shirley and Smits 1999 (render/sky.h), or an environment map
/// (an equirectangular image of the radiance from every direction, render/sky.h EnvMapSkyLight).
enum class SkyModel { Uniform, Preetham, EnvMap };

/// A light that is not geometry: isotropic point, spot (cone with a smooth edge), sun (a
/// distant disk) or sky (radiance from every direction no geometry blocks, i.e. seen through
/// windows and openings). Radiometric units: point and spot `intensity` is radiant intensity in
/// W/sr along the axis; sun `intensity` is irradiance in W/m^2 on a surface facing it; a uniform
/// sky's `intensity` is radiance in W sr^-1 m^-2 (from the whole sphere); a Preetham sky's is the
/// irradiance in W/m^2 (luminance of the RGB) it gives an unoccluded horizontal surface: it
/// shines only from above the horizon (world z > 0) and its colour comes from the model. An
/// environment-map sky's `intensity` is a dimensionless factor on the image's values, which are
/// radiance in W sr^-1 m^-2 (linear RGB), from the whole sphere.
struct Light {
  std::string name;
  LightType type = LightType::Point;
  Vec3 position = Vec3::Zero();        ///< point, spot (metres)
  Vec3 direction = -Vec3::UnitZ();     ///< spot, sun, Preetham sky (its sun): unit travel dir.
  Vec3f color{1.f, 1.f, 1.f};          ///< linear RGB tint, used when temperature_k == 0
  float temperature_k = 0.f;           ///< > 0: blackbody colour at this temperature (luminance 1)
  float intensity = 1.f;               ///< W/sr, W/m^2 (sun, Preetham sky), W/(sr m^2) (sky)
  float cone_deg = 30.f;               ///< spot: half-angle of the lit cone
  float falloff_deg = 5.f;             ///< spot: width of the smooth edge inside the cone
  float angular_diameter_deg = 0.53f;  ///< sun: apparent diameter (the real sun: 0.53 deg)
  float max_distance = 0.f;            ///< point, spot: no light beyond this range (m); 0 = none
  /// Point, spot: the radius r of the bulb (m): its light on a surface at distance d is
  /// I / (d^2 + r^2), a glowing disk of radius r facing the surface (as Cycles draws a point
  /// light with a radius), instead of growing without bound as I / d^2 near the centre; 0 =
  /// an ideal point. Sweet Home 3D's lights have a diameter (lightSourceDiameter): a lamp
  /// model's own parts often lie within it, millimetres from the centre.
  float radius = 0.f;
  SkyModel sky_model = SkyModel::Uniform;  ///< sky
  float turbidity = 3.f;                   ///< Preetham sky: haze, 2 (very clear) .. 10 (hazy)
  /// Environment-map sky: the equirectangular (latitude-longitude) image; EXR is linear, PNG
  /// and JPEG are sRGB-encoded. In the map's own frame, texel centre (u, v) = ((x + 0.5) / W,
  /// (y + 0.5) / H) looks along (sin phi sin theta, cos phi sin theta, cos theta) with
  /// phi = 2 pi u, theta = pi v: row 0 is the zenith (+z), u = 0 faces +y, u = 0.25 faces +x.
  /// This is Mitsuba's envmap convention with its +Y up turned to our +Z up.
  TextureRef envmap;
  Mat3 envmap_rotation = Mat3::Identity();  ///< environment-map sky: map frame -> world, a rotation
  bool on = true;
  std::string object;  ///< the object (instance name) this light belongs to, e.g. a lamp; "" = none

  /// Colour times intensity: RGB radiant intensity (point, spot), irradiance (sun) or radiance
  /// (uniform sky). A Preetham sky takes its colour from the model instead.
  Vec3f rgbIntensity() const;
};

/// The daylight of the procedural apartments: a Preetham sky (40 W/m^2 on an unoccluded
/// horizontal surface) and a 5500 K sun (350 W/m^2) towards `to_sun` (unit, world), both times
/// `scale`, named `prefix` + "sky" and `prefix` + "sun". Importers and the automatic lights use
/// it too, so every source of daylight exposes alike.
std::pair<Light, Light> daylightLights(const Vec3& to_sun, float turbidity, float scale = 1.f,
                                       const std::string& prefix = "");

/// Names of light types as written in layout files ("point", "spot", "sun", "sky").
const char* lightTypeName(LightType t);
/// Names of sky models as written in layout files ("uniform", "preetham", "envmap").
const char* skyModelName(SkyModel m);

/// Room types of the interior-design trade, as written in layout files ("living_room", ...).
const std::vector<std::string>& roomTypeNames();

/// A room: its type and its floor outline (a simple polygon, counter-clockwise seen from above,
/// metres), between a floor and a ceiling height.
struct Room {
  std::string id;
  std::string type = "living_room";  ///< one of roomTypeNames()
  std::vector<Eigen::Vector2d> outline;
  double floor_z = 0.0;
  double ceiling_z = 2.7;
  /// Floor area of the outline (m^2).
  double area() const;
  /// Is (x, y) inside the outline?
  bool contains(double x, double y) const;
  /// Inside the outline or at most `tol` metres from it (the distance to its nearest edge).
  bool contains(double x, double y, double tol) const;
};

struct Scene {
  std::string name = "scene";
  std::vector<Room> rooms;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Object> objects;
  std::vector<Light> lights;

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
