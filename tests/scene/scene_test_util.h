#pragma once
// Helpers shared by the scene tests: a self-deleting temporary folder, file writing, the fixture
// folder, and a field-by-field Scene comparison (exact: doubles and floats compare bit for bit
// via ==, except that -0.0 and 0.0 are told apart).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../temp_dir.h"
#include "core/error.h"
#include "scene/scene.h"

namespace inet::test {

/// The hand-made fixtures under tests/data/scene.
inline std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(INET_SOURCE_DIR) / "tests" / "data" / "scene" / name;
}

/// ../shared (benchmark scene, public data sets), absent on some machines.
/// Message of the InputError thrown by `f`, or "" when nothing was thrown.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

inline std::filesystem::path sharedDir() {
  return std::filesystem::path(INET_SHARED_DIR);
}

inline bool sameBits(double a, double b) {
  return a == b && std::signbit(a) == std::signbit(b);
}

/// Field-by-field equality with messages naming the first differing field.
inline void expectScenesEqual(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    SCOPED_TRACE("meshes[" + std::to_string(i) + "]");
    const Mesh &x = a.meshes[i], &y = b.meshes[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.source.kind, y.source.kind);
    EXPECT_EQ(x.source.primitive, y.source.primitive);
    EXPECT_EQ(x.source.params, y.source.params);
    EXPECT_EQ(x.source.file, y.source.file);
    EXPECT_TRUE(sameBits(x.source.scale, y.source.scale));
    EXPECT_EQ(x.source.up, y.source.up);
    EXPECT_EQ(x.source.mesh_name, y.source.mesh_name);
    EXPECT_EQ(x.sphere_radius, y.sphere_radius);
    EXPECT_EQ(x.positions, y.positions);
    EXPECT_EQ(x.triangles, y.triangles);
    EXPECT_EQ(x.normals, y.normals);
    EXPECT_EQ(x.uvs, y.uvs);
  }
  ASSERT_EQ(a.rooms.size(), b.rooms.size());
  for (size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_EQ(a.rooms[i].id, b.rooms[i].id);
    EXPECT_EQ(a.rooms[i].type, b.rooms[i].type);
    EXPECT_EQ(a.rooms[i].outline, b.rooms[i].outline);
    EXPECT_TRUE(sameBits(a.rooms[i].floor_z, b.rooms[i].floor_z));
    EXPECT_TRUE(sameBits(a.rooms[i].ceiling_z, b.rooms[i].ceiling_z));
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    SCOPED_TRACE("materials[" + std::to_string(i) + "]");
    EXPECT_EQ(a.materials[i].id, b.materials[i].id);
    EXPECT_EQ(a.materials[i].type, b.materials[i].type);
    EXPECT_EQ(a.materials[i].albedo, b.materials[i].albedo);
    EXPECT_EQ(a.materials[i].emission, b.materials[i].emission);
    EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
    EXPECT_EQ(a.materials[i].ior, b.materials[i].ior);
    EXPECT_EQ(a.materials[i].transmittance, b.materials[i].transmittance);
    if (a.materials[i].type == MaterialType::Conductor) {
      EXPECT_EQ(a.materials[i].metal, b.materials[i].metal);
    }
    EXPECT_EQ(a.materials[i].albedo_texture, b.materials[i].albedo_texture);
    EXPECT_EQ(a.materials[i].roughness_texture, b.materials[i].roughness_texture);
    EXPECT_EQ(a.materials[i].normal_texture, b.materials[i].normal_texture);
    EXPECT_EQ(a.materials[i].uv_scale, b.materials[i].uv_scale);
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    SCOPED_TRACE("objects[" + std::to_string(i) + "]");
    const Object &x = a.objects[i], &y = b.objects[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.mesh, y.mesh);
    EXPECT_EQ(x.material, y.material);
    for (int k = 0; k < 16; ++k)
      EXPECT_TRUE(sameBits(x.T_world_object(k / 4, k % 4), y.T_world_object(k / 4, k % 4)))
          << "transform element " << k;
    EXPECT_EQ(x.nyu40, y.nyu40);
    EXPECT_EQ(x.instance, y.instance);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.part, y.part);
    EXPECT_EQ(x.room, y.room);
    EXPECT_EQ(x.physics, y.physics);
    ASSERT_EQ(x.motion.size(), y.motion.size());
    for (size_t k = 0; k < x.motion.size(); ++k) {
      EXPECT_TRUE(sameBits(x.motion[k].t_s, y.motion[k].t_s));
      EXPECT_EQ(x.motion[k].pose.t, y.motion[k].pose.t);
      EXPECT_EQ(x.motion[k].pose.q.coeffs(), y.motion[k].pose.q.coeffs());
    }
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    SCOPED_TRACE("lights[" + std::to_string(i) + "]");
    const Light &x = a.lights[i], &y = b.lights[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    for (int k = 0; k < 3; ++k) {
      if (x.type != LightType::Sun) {
        EXPECT_TRUE(sameBits(x.position[k], y.position[k]));
      }
      if (x.type != LightType::Point) {
        EXPECT_TRUE(sameBits(x.direction[k], y.direction[k]));
      }
    }
    EXPECT_EQ(x.sky_model, y.sky_model);
    EXPECT_EQ(x.turbidity, y.turbidity);
    EXPECT_EQ(x.color, y.color);
    EXPECT_EQ(x.intensity, y.intensity);
    EXPECT_EQ(x.temperature_k, y.temperature_k);
    EXPECT_EQ(x.max_distance, y.max_distance);
    EXPECT_EQ(x.radius, y.radius);
    EXPECT_EQ(x.on, y.on);
    EXPECT_EQ(x.object, y.object);
  }
}

}  // namespace inet::test
