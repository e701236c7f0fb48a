#pragma once
// glTF 2.0 export of a scene (`interiornet layout export`), for other renderers (Blender Cycles,
// bench/cycles_gltf.py), web viewers and any tool that reads glTF.
//
// What is written (docs/gltf.md has the full table, exact vs approximate):
//  - one node per object under a root node "interiornet_world" that turns our Z-up world into
//    glTF's Y-up (a rotation of -90 degrees about x), so every child keeps our coordinates;
//    node extras: nyu40, nyu40_name, instance, kind, part, room, mass_kg, friction, movable;
//  - meshes shared between objects as in the scene (one glTF mesh per mesh and material);
//    analytic spheres are tessellated; texture coordinates get the material's uv_scale and
//    glTF's v-down convention (v' = 1 - v);
//  - materials as metallic-roughness PBR with KHR_materials_ior, _transmission, _volume,
//    _emissive_strength and _diffuse_transmission where they apply, and our own parameters in
//    the material's extras ("interiornet_type", ...) so a reader can rebuild them exactly;
//  - point, spot and sun lights as KHR_lights_punctual, photometric as that extension asks:
//    candela = 683 x W/sr, lux = 683 x W/m^2 (Blender's importer divides by the same 683);
//    emission (radiance, W sr^-1 m^-2) as emissiveFactor x emissiveStrength unchanged, as
//    Blender reads it;
//  - the sky (not expressible in glTF) in the scene's extras, with an optional baked
//    equirectangular image of it (see GltfExportOptions::sky_image);
//  - an optional camera (pinhole, yfov from fy; the full intrinsics in its extras);
//  - moving objects as glTF animations (linear translation, slerp rotation: our interpolation).
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// A pinhole camera to export: image size, focal lengths and principal point in pixels
/// (renderer convention, see render/camera.h), and its pose (OpenCV axes: x right, y down,
/// z forward).
struct GltfCamera {
  int width = 640, height = 480;
  double fx = 600, fy = 600, cx = 320, cy = 240;
  Mat4 T_world_camera = Mat4::Identity();
  std::string name = "camera";
};

struct GltfExportOptions {
  bool binary = false;               ///< .glb (one file, images embedded) instead of .gltf
  std::optional<GltfCamera> camera;  ///< a camera node, when given
  /// Path (relative to the output's folder) of an equirectangular image of the sky's radiance
  /// already written there, recorded in the scene extras; "" = none. Its convention is
  /// Blender's: u = 0.5 looks along +x, u = 0.25 along +y, row 0 is the zenith, in our Z-up world
  /// (which is Blender's world after its glTF import).
  std::string sky_image;
};

struct GltfExportReport {
  int nodes = 0, meshes = 0, materials = 0, lights = 0, images = 0, animations = 0;
  int spheres_tessellated = 0;
  int lights_off = 0;        ///< lights switched off: not exported
  int skipped_textures = 0;  ///< textures glTF cannot hold (EXR): left out
  std::vector<std::string> notes;  ///< one line per approximation made
  size_t bytes = 0;                ///< size of what was written (all files)
};

/// Writes `scene` to `path` (.gltf: JSON + `<stem>.bin` + images copied to `<stem>_textures/`;
/// .glb: one binary file), every file atomically, the .gltf/.glb last. Throws InputError naming
/// `path` when a texture cannot be read or the file cannot be written.
GltfExportReport exportGltf(const Scene& scene, const std::string& path,
                            const GltfExportOptions& opt = {});

/// Normal-incidence reflectance (linear RGB) of a conductor preset (Material::metal), the
/// base colour a metallic glTF material gets; the figures of render/fresnel.h's metalIor.
Vec3f metalBaseColor(const std::string& metal);

}  // namespace inet
