#include "scene/room_shell.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "scene/nyu40.h"

namespace inet {
namespace {

constexpr double kCosFacing = 0.95;    // 18 degrees
constexpr double kBand = 0.3;          // m from the object's bottom (floor) or top (ceiling)
constexpr double kMinPartArea = 0.5;   // m^2

/// The triangles `tris` of `m` as a mesh of their own (only the vertices they use).
Mesh subMesh(const Mesh& m, const std::vector<size_t>& tris, const std::string& id) {
  Mesh out;
  out.id = id;
  std::vector<int64_t> remap(m.positions.size(), -1);
  for (size_t t : tris) {
    Tri tri;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.triangles[t][k];
      if (remap[v] < 0) {
        remap[v] = static_cast<int64_t>(out.positions.size());
        out.positions.push_back(m.positions[v]);
        if (!m.normals.empty()) out.normals.push_back(m.normals[v]);
        if (!m.uvs.empty()) out.uvs.push_back(m.uvs[v]);
      }
      tri[k] = static_cast<uint32_t>(remap[v]);
    }
    out.triangles.push_back(tri);
  }
  return out;
}

}  // namespace

size_t splitRoomShells(Scene& scene) {
  const int wall = *nyu40FromName("wall"), floor = *nyu40FromName("floor"),
            ceiling = *nyu40FromName("ceiling");
  std::vector<int> users(scene.meshes.size(), 0);
  for (const Object& o : scene.objects)
    if (o.mesh >= 0) ++users[o.mesh];
  int next_instance = 0;
  for (const Object& o : scene.objects) next_instance = std::max(next_instance, o.instance);
  size_t split = 0;
  const size_t n_objects = scene.objects.size();
  for (size_t oi = 0; oi < n_objects; ++oi) {
    const Object o = scene.objects[oi];  // a copy: objects grows below
    if (o.nyu40 != wall || o.mesh < 0 || users[o.mesh] != 1 || o.moving()) continue;
    const Mesh& m = scene.meshes[o.mesh];
    if (m.isSphere() || m.triangles.empty()) continue;
    std::vector<std::array<Vec3, 3>> world(m.triangles.size());
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        world[t][k] = (o.T_world_object * m.positions[m.triangles[t][k]].cast<double>().homogeneous()).head<3>();
        lo = std::min(lo, world[t][k].z());
        hi = std::max(hi, world[t][k].z());
      }
    std::vector<size_t> parts[3];  // wall, floor, ceiling
    double area[3] = {0, 0, 0};
    for (size_t t = 0; t < world.size(); ++t) {
      const Vec3 n = (world[t][1] - world[t][0]).cross(world[t][2] - world[t][0]);
      const double len = n.norm();
      int part = 0;
      if (len > 0) {
        const double zmin = std::min({world[t][0].z(), world[t][1].z(), world[t][2].z()});
        const double zmax = std::max({world[t][0].z(), world[t][1].z(), world[t][2].z()});
        // level triangles, whichever way they face (an outward box's floor faces down)
        if (std::abs(n.z()) >= kCosFacing * len)
          part = zmin <= lo + kBand ? 1 : zmax >= hi - kBand ? 2 : 0;
      }
      parts[part].push_back(t);
      area[part] += 0.5 * len;
    }
    // too little floor or ceiling to be one: those triangles stay wall
    for (int p = 1; p < 3; ++p)
      if (area[p] < kMinPartArea) {
        parts[0].insert(parts[0].end(), parts[p].begin(), parts[p].end());
        parts[p].clear();
      }
    if (parts[1].empty() && parts[2].empty()) continue;
    const Mesh source = m;  // meshes grows below
    const char* names[3] = {"wall", "floor", "ceiling"};
    const int labels[3] = {wall, floor, ceiling};
    // the object keeps its walls, or (a slab named wall) the first part it has
    int keep = 0;
    while (parts[keep].empty()) ++keep;
    for (int p = keep + 1; p < 3; ++p) {
      if (parts[p].empty()) continue;
      scene.meshes.push_back(subMesh(source, parts[p], source.id + "_" + names[p]));
      Object part = o;
      part.name = o.name + "_" + names[p];
      part.mesh = static_cast<int>(scene.meshes.size()) - 1;
      part.nyu40 = labels[p];
      part.instance = ++next_instance;
      part.kind = names[p];
      scene.objects.push_back(std::move(part));
    }
    scene.meshes[o.mesh] = subMesh(source, parts[keep], source.id);
    scene.objects[oi].nyu40 = labels[keep];
    ++split;
  }
  return split;
}

}  // namespace inet
