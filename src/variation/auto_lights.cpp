#include "variation/auto_lights.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "core/color.h"
#include "core/error.h"
#include "core/text.h"
#include "core/image_io.h"
#include "scene/nyu40.h"
#include "scene/occupancy.h"
#include "scene/primitives.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

/// Lower-case letter runs of a name, split at non-letters and camelCase boundaries
/// ("CeilingLight_02" -> ceiling, light).
std::vector<std::string> letterTokens(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const bool boundary = !std::isalpha(c) ||
                          (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(s[i - 1])));
    if (boundary && !cur.empty()) out.push_back(std::move(cur)), cur.clear();
    if (std::isalpha(c)) cur += static_cast<char>(std::tolower(c));
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

/// Free runs of one voxel column between an occupied voxel below (floor) and above (ceiling).
struct Run {
  int k0 = 0, k1 = 0;  ///< first and last free voxel
  int space = -1;
};

/// Union-find over runs.
int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

/// Height of the lowest triangle above (x, y, z) along +z, or NaN (Moller-Trumbore on a
/// vertical ray; brute force: it runs for a handful of panels).
double ceilingAbove(const WorldTriangles& tris, double x, double y, double z) {
  double best = std::numeric_limits<double>::infinity();
  for (const Tri& t : tris.triangles) {
    const Vec3 a = tris.positions[t[0]].cast<double>(), b = tris.positions[t[1]].cast<double>(),
               c = tris.positions[t[2]].cast<double>();
    if (std::max({a.z(), b.z(), c.z()}) < z) continue;
    // barycentric test in the xy plane
    const double d = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(d) < 1e-12) continue;  // vertical or degenerate
    const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / d;
    const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / d;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double hit = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if (hit > z && hit < best) best = hit;
  }
  return std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN();
}

/// One enclosed space: its columns (grid i, j, run) and floor area.
struct Space {
  std::vector<std::array<int, 3>> cells;  ///< i, j, index of the run in its column
  double area = 0.0;
  double flux = 0.0;      ///< W to spread over its lights
  int luminaires = 0;
};

/// k-means (Lloyd) over the cells' xy, deterministic (farthest-point start from the cell
/// nearest the centroid); returns, per cluster, the cell nearest its mean (inside the space).
std::vector<size_t> clusterCells(const std::vector<Eigen::Vector2d>& xy, size_t n) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : xy) centroid += p;
  centroid /= static_cast<double>(xy.size());
  auto nearest = [&](const Eigen::Vector2d& q) {
    size_t best = 0;
    for (size_t i = 1; i < xy.size(); ++i)
      if ((xy[i] - q).squaredNorm() < (xy[best] - q).squaredNorm()) best = i;
    return best;
  };
  std::vector<Eigen::Vector2d> centres{xy[nearest(centroid)]};
  std::vector<double> d2(xy.size(), std::numeric_limits<double>::infinity());
  while (centres.size() < n) {
    for (size_t i = 0; i < xy.size(); ++i)
      d2[i] = std::min(d2[i], (xy[i] - centres.back()).squaredNorm());
    centres.push_back(xy[std::max_element(d2.begin(), d2.end()) - d2.begin()]);
  }
  std::vector<size_t> label(xy.size(), 0);
  for (int iter = 0; iter < 12; ++iter) {
    for (size_t i = 0; i < xy.size(); ++i)
      for (size_t c = 1; c < n; ++c)
        if ((xy[i] - centres[c]).squaredNorm() < (xy[i] - centres[label[i]]).squaredNorm())
          label[i] = c;
    std::vector<Eigen::Vector2d> sum(n, Eigen::Vector2d::Zero());
    std::vector<size_t> count(n, 0);
    for (size_t i = 0; i < xy.size(); ++i) sum[label[i]] += xy[i], ++count[label[i]];
    for (size_t c = 0; c < n; ++c)
      if (count[c] > 0) centres[c] = sum[c] / static_cast<double>(count[c]);
  }
  std::vector<size_t> out;
  for (const Eigen::Vector2d& c : centres) out.push_back(nearest(c));
  return out;
}

/// Per voxel, the volume (m^3) of the connected set of free voxels it belongs to (6-neighbour
/// flood fill; 0 for occupied voxels).
std::vector<double> freeVolumes(const OccupancyGrid& g) {
  std::vector<int> comp(g.size(), -1);
  std::vector<size_t> count, stack;
  for (size_t start = 0; start < g.size(); ++start) {
    if (g.occupied[start] || comp[start] >= 0) continue;
    const int id = static_cast<int>(count.size());
    count.push_back(0);
    comp[start] = id;
    stack.push_back(start);
    while (!stack.empty()) {
      const size_t v = stack.back();
      stack.pop_back();
      ++count[id];
      const int i = static_cast<int>(v % g.nx), j = static_cast<int>((v / g.nx) % g.ny),
                k = static_cast<int>(v / (static_cast<size_t>(g.nx) * g.ny));
      for (const auto& [di, dj, dk] : {std::array{1, 0, 0}, std::array{-1, 0, 0},
                                       std::array{0, 1, 0}, std::array{0, -1, 0},
                                       std::array{0, 0, 1}, std::array{0, 0, -1}}) {
        if (!g.inside(i + di, j + dj, k + dk)) continue;
        const size_t u = g.index(i + di, j + dj, k + dk);
        if (g.occupied[u] || comp[u] >= 0) continue;
        comp[u] = id;
        stack.push_back(u);
      }
    }
  }
  const double cell = g.voxel * g.voxel * g.voxel;
  std::vector<double> out(g.size(), 0.0);
  for (size_t v = 0; v < g.size(); ++v)
    if (comp[v] >= 0) out[v] = static_cast<double>(count[comp[v]]) * cell;
  return out;
}

/// The spaces of the grid (see the header comment) and, per column, its runs.
struct SpaceAnalysis {
  OccupancyGrid grid;
  std::vector<std::vector<Run>> runs;  ///< per column i + nx * j
  std::vector<Space> spaces;

  const std::vector<Run>& column(int i, int j) const { return runs[i + static_cast<size_t>(grid.nx) * j]; }
};

SpaceAnalysis findSpaces(const WorldTriangles& tris, const Vec3& lo, const Vec3& hi,
                         const AutoLightOptions& opt) {
  SpaceAnalysis a;
  a.grid = voxelizeTriangles(tris, lo, hi, opt.voxel_m, 8e6);
  const OccupancyGrid& g = a.grid;
  const int min_run = static_cast<int>(std::ceil(opt.min_room_height_m / g.voxel)) - 1;
  a.runs.resize(static_cast<size_t>(g.nx) * g.ny);
  // the free voxels' connected volumes: the inside of a closed wardrobe taller than a room's
  // 1.9 m has floor-to-ceiling runs too, but its few m^3 are shut off from everything
  const std::vector<double> volume = freeVolumes(g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      std::vector<Run>& col = a.runs[i + static_cast<size_t>(g.nx) * j];
      for (int k = 1; k < g.nz; ++k) {
        if (!g.occupied[g.index(i, j, k - 1)] || g.occupied[g.index(i, j, k)]) continue;
        int e = k;
        while (e < g.nz && !g.occupied[g.index(i, j, e)]) ++e;
        if (e < g.nz && e - k >= min_run && (e - k) * g.voxel <= 15.0 &&
            volume[g.index(i, j, k)] >= opt.min_space_volume_m3)
          col.push_back({k, e - 1});
        k = e;
      }
    }
  // join neighbouring runs that overlap and whose ceilings agree within 0.2 m
  std::vector<size_t> first(a.runs.size() + 1, 0);
  for (size_t c = 0; c < a.runs.size(); ++c) first[c + 1] = first[c] + a.runs[c].size();
  std::vector<int> parent(first.back());
  std::iota(parent.begin(), parent.end(), 0);
  const int ceil_tol = static_cast<int>(std::lround(0.2 / g.voxel));
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = i + static_cast<size_t>(g.nx) * j;
      for (auto [ni, nj] : {std::pair{i + 1, j}, std::pair{i, j + 1}}) {
        if (ni >= g.nx || nj >= g.ny) continue;
        const size_t n = ni + static_cast<size_t>(g.nx) * nj;
        for (size_t r = 0; r < a.runs[c].size(); ++r)
          for (size_t s = 0; s < a.runs[n].size(); ++s) {
            const Run &x = a.runs[c][r], &y = a.runs[n][s];
            if (x.k0 > y.k1 || y.k0 > x.k1 || std::abs(x.k1 - y.k1) > ceil_tol) continue;
            parent[findRoot(parent, static_cast<int>(first[c] + r))] =
                findRoot(parent, static_cast<int>(first[n] + s));
          }
      }
    }
  // spaces of at least 1 m^2, in the order of their first cell (deterministic)
  std::vector<int> space_of_root(parent.size(), -1);
  std::vector<Space> all;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = i + static_cast<size_t>(g.nx) * j;
      for (size_t r = 0; r < a.runs[c].size(); ++r) {
        const int root = findRoot(parent, static_cast<int>(first[c] + r));
        if (space_of_root[root] < 0) space_of_root[root] = static_cast<int>(all.size()), all.emplace_back();
        Space& s = all[space_of_root[root]];
        s.cells.push_back({i, j, static_cast<int>(r)});
        s.area += g.voxel * g.voxel;
        a.runs[c][r].space = space_of_root[root];
      }
    }
  std::vector<int> renumber(all.size(), -1);
  for (size_t s = 0; s < all.size(); ++s)
    if (all[s].area >= 1.0) renumber[s] = static_cast<int>(a.spaces.size()), a.spaces.push_back(std::move(all[s]));
  for (auto& col : a.runs)
    for (Run& r : col) r.space = r.space >= 0 ? renumber[r.space] : -1;
  return a;
}

/// The space whose run holds world point p (searching columns within 0.5 m: a floor lamp's own
/// pole fills its centre column), or -1.
int spaceAt(const SpaceAnalysis& a, const Vec3& p) {
  const OccupancyGrid& g = a.grid;
  const int ci = static_cast<int>(std::lround((p.x() - g.origin.x()) / g.voxel));
  const int cj = static_cast<int>(std::lround((p.y() - g.origin.y()) / g.voxel));
  const int reach = static_cast<int>(std::ceil(0.5 / g.voxel));
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int j = cj - reach; j <= cj + reach; ++j)
    for (int i = ci - reach; i <= ci + reach; ++i) {
      if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
      const double d = std::hypot(i - ci, j - cj);
      if (d >= best_d) continue;
      for (const Run& r : a.column(i, j)) {
        const double z0 = g.centre(i, j, r.k0).z() - g.voxel, z1 = g.centre(i, j, r.k1).z();
        if (r.space >= 0 && p.z() >= z0 && p.z() <= z1 + 0.5) best = r.space, best_d = d;
      }
    }
  return best;
}

/// The procedural apartments' sky and sun (`indoors`: seen through windows, where the walls take
/// most of it), or the same light 1/100 as strong for a scene in the open, so that a sunlit
/// white surface is not far past white at the default exposure (0.8 x 3.9 W/m^2 / pi = 1.0).
/// A material's diffuse albedo as a luminance: its albedo times its texture's mean (linear; the
/// image read once and remembered in `means`; 0.5 when it cannot be read).
double albedoLuminance(const Material& m, std::map<std::string, double>& means) {
  double t = 1.0;
  if (!m.albedo_texture.empty()) {
    auto it = means.find(m.albedo_texture.path);
    if (it == means.end()) {
      double mean = 0.5;
      try {
        mean = luminance(meanLinearRgb(m.albedo_texture.path));
      } catch (const std::exception&) {
      }
      it = means.emplace(m.albedo_texture.path, mean).first;
    }
    t = it->second;
  }
  if (m.type == MaterialType::Dielectric || m.type == MaterialType::ThinDielectric) return 0.0;
  return std::clamp(luminance(m.albedo) * t, 0.0, 1.0);
}

void addDaylight(Scene& scene, bool indoors) {
  const float scale = indoors ? 1.f : 0.01f;
  // the sun 40 degrees up from the south-east, as a late-morning apartment
  const double el = 40.0 * M_PI / 180.0, az = -45.0 * M_PI / 180.0;
  const Vec3 to_sun(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const auto [sky, sun] = daylightLights(to_sun, 3.f, scale, "auto_");
  scene.lights.push_back(sky);
  scene.lights.push_back(sun);
}

}  // namespace

AutoLightMode parseAutoLightMode(const std::string& name, const std::string& field) {
  if (name == "auto") return AutoLightMode::Auto;
  if (name == "on") return AutoLightMode::On;
  if (name == "off") return AutoLightMode::Off;
  throw InputError("", field, "must be auto, on or off, not '" + name + "'");
}

bool isLuminaireName(const std::string& name) {
  static const std::set<std::string> kLight = {
      "light", "lights", "lamp", "lamps", "lampshade", "lampshades", "lightbulb", "lightbulbs",
      "bulb", "bulbs", "chandelier", "chandeliers", "sconce", "sconces", "luminaire",
      "luminaires", "lighting", "downlight", "downlights", "spotlight", "spotlights"};
  static const std::set<std::string> kNot = {"switch", "switches", "lightswitch", "sensor"};
  bool light = false;
  for (const std::string& t : letterTokens(name)) {
    if (kNot.count(t)) return false;
    light = light || kLight.count(t) > 0;
  }
  return light;
}

bool sceneHasLight(const Scene& scene) {
  for (const Light& l : scene.lights)
    if (l.on && l.intensity > 0.f) return true;
  for (const Object& o : scene.objects)
    if (o.material >= 0 && scene.materials[o.material].isEmissive()) return true;
  return false;
}

std::string AutoLightReport::summary() const {
  if (no_room)
    return "the scene has no light, and no place for one: every object is wider than 50 m (in "
           "centimetres or millimetres? give --scale 0.01 or 0.001)";
  if (luminaires.empty() && ceiling_panels == 0 && !daylight) return "";
  std::vector<std::string> parts;
  if (!luminaires.empty()) {
    parts.push_back(fmt::format("{} lamp object(s) made to glow ({})", luminaires.size(),
                                listNames(luminaires, 6)));
  }
  if (ceiling_panels > 0)
    parts.push_back(fmt::format("{} ceiling light(s) added", ceiling_panels));
  if (daylight) parts.push_back("a daylight sky and sun added");
  std::string out = "the scene has no light: ";
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + parts[i];
  return out + fmt::format(" ({} enclosed space(s), {:.1f} m^2 of floor; --auto-lights off to "
                           "render it as it is)",
                           spaces, space_area_m2);
}

AutoLightReport addAutoLights(Scene& scene, const AutoLightOptions& opt) {
  AutoLightReport report;
  report.had_light = sceneHasLight(scene);
  if (opt.mode == AutoLightMode::Off || (opt.mode == AutoLightMode::Auto && report.had_light))
    return report;
  const WorldTriangles tris = worldTriangles(scene);
  if (tris.triangles.empty()) return report;
  auto [lo, hi] = boundsWithoutHugePlanes(scene, tris);
  if (!(lo.x() <= hi.x())) {
    report.no_room = true;
    return report;
  }
  lo -= Vec3::Constant(0.2);
  hi += Vec3::Constant(0.2);
  SpaceAnalysis a = findSpaces(tris, lo, hi, opt);
  report.spaces = a.spaces.size();
  const Vec3f colour = blackbodyRgb(opt.temperature_k);

  // 1. luminaires: their world area and the space each lights
  std::vector<double> area(scene.objects.size(), 0.0);
  std::vector<Vec3> lo_o(scene.objects.size(), Vec3::Constant(1e30)), hi_o(scene.objects.size(), Vec3::Constant(-1e30));
  for (size_t t = 0; t < tris.triangles.size(); ++t) {
    const Tri& tri = tris.triangles[t];
    const int o = tris.object[t];
    const Vec3 p0 = tris.positions[tri[0]].cast<double>(), p1 = tris.positions[tri[1]].cast<double>(),
               p2 = tris.positions[tri[2]].cast<double>();
    area[o] += 0.5 * (p1 - p0).cross(p2 - p0).norm();
    lo_o[o] = lo_o[o].cwiseMin(p0).cwiseMin(p1).cwiseMin(p2);
    hi_o[o] = hi_o[o].cwiseMax(p0).cwiseMax(p1).cwiseMax(p2);
  }
  // light bounces between bright surfaces: a room of 0.9 albedo is 1 / (1 - 0.9) = 10 times as
  // bright as the direct light, one of 0.5 twice. The flux is scaled by (1 - rho) / (1 - 0.5),
  // rho the scene's area-weighted albedo (textures by their mean), so that both expose alike.
  double weighted = 0.0, total = 0.0;
  std::map<std::string, double> texture_mean;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    if (scene.objects[o].material < 0 || !(area[o] > 0)) continue;
    weighted += area[o] * albedoLuminance(scene.materials[scene.objects[o].material], texture_mean);
    total += area[o];
  }
  report.mean_albedo = total > 0 ? weighted / total : 0.5;
  const double bounce = std::clamp((1.0 - report.mean_albedo) / 0.5, 0.2, 2.0);
  for (Space& s : a.spaces) {
    s.flux = opt.flux_per_m2 * bounce * s.area;
    report.space_area_m2 += s.area;
  }
  const int lamp = *nyu40FromName("lamp");
  std::vector<int> lum_space;  // per luminaire object index in `lums`
  std::vector<size_t> lums;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& obj = scene.objects[o];
    const std::string& mat = obj.material >= 0 ? scene.materials[obj.material].id : obj.name;
    if (!(area[o] > 0) || !(obj.nyu40 == lamp || isLuminaireName(obj.name) || isLuminaireName(mat)))
      continue;
    lums.push_back(o);
    const int s = spaceAt(a, 0.5 * (lo_o[o] + hi_o[o]));
    lum_space.push_back(s);
    if (s >= 0) ++a.spaces[s].luminaires;
  }
  for (size_t k = 0; k < lums.size(); ++k) {
    Object& obj = scene.objects[lums[k]];
    const int s = lum_space[k];
    const double flux = s >= 0 ? a.spaces[s].flux / a.spaces[s].luminaires
                               : opt.flux_per_m2 * bounce * opt.area_per_light_m2;
    const double radiance = std::clamp(flux / (M_PI * area[lums[k]]), 0.5, 2000.0);
    Material m = obj.material >= 0 ? scene.materials[obj.material] : Material{};
    m.id = "auto_glow_" + obj.name;
    m.emission = colour * static_cast<float>(radiance);
    scene.materials.push_back(m);
    obj.material = static_cast<int>(scene.materials.size()) - 1;
    report.luminaires.push_back(obj.name);
  }

  // 2. ceiling panels for the spaces no luminaire lights
  int next_instance = 0;
  for (const Object& o : scene.objects) next_instance = std::max(next_instance, o.instance);
  int panel_mesh = -1;
  for (size_t si = 0; si < a.spaces.size(); ++si) {
    const Space& s = a.spaces[si];
    if (s.luminaires > 0) continue;
    const size_t n = std::max<size_t>(1, static_cast<size_t>(std::lround(s.area / opt.area_per_light_m2)));
    std::vector<Eigen::Vector2d> xy;
    for (const auto& c : s.cells) xy.push_back(a.grid.centre(c[0], c[1], 0).head<2>());
    const double panel_flux = s.flux / static_cast<double>(n);
    Material m;
    m.id = fmt::format("auto_ceiling_light_{}", si);
    m.albedo = Vec3f::Constant(0.8f);
    m.emission = colour * static_cast<float>(panel_flux / (M_PI * opt.panel_m * opt.panel_m));
    scene.materials.push_back(m);
    const int mat = static_cast<int>(scene.materials.size()) - 1;
    for (size_t cell : clusterCells(xy, n)) {
      const auto& c = s.cells[cell];
      const Run& r = a.column(c[0], c[1])[c[2]];
      const Vec3 mid = a.grid.centre(c[0], c[1], (r.k0 + r.k1) / 2);
      const double ceiling = ceilingAbove(tris, mid.x(), mid.y(), mid.z());
      if (!std::isfinite(ceiling) || next_instance >= 65535) continue;
      if (panel_mesh < 0) {
        Mesh quad = makePrimitive("quad", {}, "", "");
        quad.id = "auto_ceiling_panel";
        scene.meshes.push_back(std::move(quad));
        panel_mesh = static_cast<int>(scene.meshes.size()) - 1;
      }
      Mat4 T = Mat4::Identity();  // the quad faces +z: turned over (about x) to face down
      T.block<3, 3>(0, 0) = Vec3(opt.panel_m, -opt.panel_m, -1.0).asDiagonal();
      T.block<3, 1>(0, 3) = Vec3(mid.x(), mid.y(), ceiling - 0.005);
      Object o = Object::make(fmt::format("auto_ceiling_light_{}", report.ceiling_panels + 1),
                              panel_mesh, mat, T, lamp, ++next_instance);
      o.kind = "ceiling_light";
      scene.objects.push_back(std::move(o));
      ++report.ceiling_panels;
    }
  }

  // 3. daylight: through glass, or for a scene open to the sky
  bool glass = false;
  for (const Object& o : scene.objects)
    if (o.material >= 0) {
      const MaterialType t = scene.materials[o.material].type;
      glass = glass || t == MaterialType::Dielectric || t == MaterialType::ThinDielectric;
    }
  if (glass || a.spaces.empty()) {
    addDaylight(scene, !a.spaces.empty());
    report.daylight = true;
  }
  return report;
}

}  // namespace inet
