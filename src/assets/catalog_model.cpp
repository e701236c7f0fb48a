#include "assets/catalog_model.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <limits>

#include "assets/zip_archive.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

/// True when an archive entry name stays inside the folder it is extracted to.
bool safeEntryName(const std::string& name) {
  if (name.empty() || name[0] == '/' || name[0] == '\\' || name.find(':') != std::string::npos)
    return false;
  for (const auto& part : fs::path(name))
    if (part == "..") return false;
  return true;
}

/// Density of the piece's bounding box (kg per m^3 of box, so it includes the empty space a
/// chair or a table leaves inside it) and friction on a wooden floor, by NYU40 class.
/// Measured-order figures: a 2 m sofa box (1.5 m^3) at 30 kg/m^3 weighs 45 kg; a 0.45 x 0.5 x
/// 0.85 m chair box at 30 kg/m^3 weighs 6 kg; a 0.6 m^3 fridge at 120 kg/m^3, 70 kg.
struct Physical {
  double density, friction;
};
Physical physicalOf(int nyu40) {
  switch (nyu40) {
    case 4:
    case 6:
    case 18:
    case 20:
    case 21:
    case 28:
      return {30, 0.27};  // soft
    case 5:
    case 7:
    case 14:
    case 32:
      return {30, 0.2};  // seats, tables
    case 3:
    case 10:
    case 12:
    case 15:
    case 17:
    case 39:
      return {60, 0.2};  // case furniture
    case 24:
    case 25:
    case 33:
    case 34:
    case 36:
      return {120, 0.15};  // appliances
    default:
      return {150, 0.2};  // small props
  }
}

Mat3 normalMatrix(const Mat3& L) {
  return L.inverse().transpose();
}

}  // namespace

fs::path catalogModelCache() {
  return userCacheDir("sh3f");
}

fs::path extractCatalogModel(const FurnitureCatalog& catalog, const CatalogPiece& piece,
                             const fs::path& cache_dir) {
  const fs::path root = cache_dir / catalog.checksum;
  const fs::path model_rel(piece.model);
  const fs::path folder_rel = piece.multi_part ? model_rel.parent_path() : model_rel;
  // A home (.sh3d) stores a single-file model as a bare entry ("12"): Assimp picks its reader
  // by extension, so such an entry is written as "12.obj" (every such entry is an OBJ).
  const bool bare = !piece.multi_part && model_rel.extension().empty();
  const fs::path target = root / (bare ? fs::path(model_rel.string() + ".obj") : folder_rel);
  const fs::path obj = bare ? target : root / model_rel;
  std::error_code ec;
  if (fs::exists(target, ec)) return obj;
  // Everything the model needs goes to a temporary folder beside the target first, then one
  // rename publishes it: readers never see a half-extracted model, and two processes racing
  // just both succeed (the loser's copy is dropped).
  const fs::path tmp =
      target.parent_path() / fmt::format("{}.tmp-{}", target.filename().string(), ::getpid());
  fs::remove_all(tmp, ec);
  const ZipArchive zip(catalog.path);
  const std::string prefix = piece.multi_part ? folder_rel.generic_string() + "/" : "";
  auto extract = [&](const std::string& entry, const fs::path& out) {
    if (!safeEntryName(entry))
      throw InputError(catalog.path, entry, "entry name leaves the extraction folder");
    fs::create_directories(out.parent_path());
    const std::string bytes = zip.read(entry);
    std::ofstream f(out, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f) throw InputError(out.string(), "", "cannot write the extracted model file");
  };
  try {
    if (piece.multi_part) {
      for (const auto& e : zip.entries())
        if (!e.isDirectory() && e.name.rfind(prefix, 0) == 0)
          extract(e.name, tmp / e.name.substr(prefix.size()));
    } else {
      extract(piece.model, tmp);
    }
    fs::create_directories(target.parent_path());
    fs::rename(tmp, target, ec);
    if (ec && !fs::exists(target)) throw InputError(target.string(), "", ec.message());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  fs::remove_all(tmp, ec);  // when another process won the rename
  return obj;
}

std::vector<Light> lampLights(const CatalogPiece& piece, const std::string& category) {
  // Catalog positions are cm from the left, FRONT and bottom (HomeLight); our front faces -y.
  const double lamp_total_w_sr = category == "floor_lamp"      ? 4.5
                                 : category == "table_lamp"    ? 2.5
                                 : category == "ceiling_light" ? 6.0
                                 : category == "pendant_light" ? 6.0
                                                               : 2.0;
  std::vector<Light> out;
  for (size_t i = 0; i < piece.lights.size(); ++i) {
    const auto& src = piece.lights[i];
    Light l;
    l.name = fmt::format("{} bulb {}", piece.name, i + 1);
    l.type = LightType::Point;
    l.position = Vec3(src.position_cm.x() - piece.width_cm / 2,
                      src.position_cm.y() - piece.depth_cm / 2, src.position_cm.z()) /
                 100.0;
    // A grey catalog colour (#888888, #555555) is a brightness hint for Sweet Home 3D's
    // renderer, not a tint: such bulbs are warm white (2700 K); a coloured one keeps its hue.
    const Vec3f lin(float(srgbEotf(src.color.x())), float(srgbEotf(src.color.y())),
                    float(srgbEotf(src.color.z())));
    const bool grey = (src.color.maxCoeff() - src.color.minCoeff()) < 0.02f;
    if (grey) {
      l.temperature_k = 2700.f;
    } else {
      const float lum = luminance(lin);
      l.color = lum > 0 ? Vec3f(lin / lum) : Vec3f::Ones();
    }
    l.intensity = static_cast<float>(lamp_total_w_sr / double(piece.lights.size()));
    // the bulb: half the catalog's diameter (4-6 cm for most lamps), 5 cm when not given
    constexpr double kDefaultBulbDiameterCm = 5.0;
    l.radius = static_cast<float>((src.diameter_cm > 0 ? src.diameter_cm : kDefaultBulbDiameterCm) /
                                  200.0);
    out.push_back(l);
  }
  return out;
}

CatalogModel loadCatalogModel(const FurnitureCatalog& catalog, const CatalogPiece& piece,
                              const fs::path& cache_dir) {
  const std::string where_field = fmt::format("model#{}", piece.index);
  const fs::path obj =
      extractCatalogModel(catalog, piece, cache_dir.empty() ? catalogModelCache() : cache_dir);
  CatalogModel m;
  m.id = piece.id;
  m.name = piece.name;
  m.creator = piece.creator;
  m.license = piece.license;
  m.catalog = catalog.name;
  m.label = labelCatalogPiece(piece);
  ImportOptions opt;
  opt.up = 'z';  // the file's own axes: modelRotation and the y-up convention are applied here
  opt.split_shells = false;
  opt.phong_materials = true;
  Scene raw;
  try {
    raw = importMeshScene(obj.string(), opt, &m.report);
  } catch (const NoSurfaceError& e) {  // the same, keeping the type
    throw NoSurfaceError(catalog.path, where_field,
                         fmt::format("{}: {}", piece.model, e.problem()));
  } catch (const InputError& e) {
    throw InputError(catalog.path, where_field, fmt::format("{}: {}", piece.model, e.problem()));
  }

  // Rotate into Sweet Home 3D's frame and measure the box the catalog size refers to.
  const Mat3 R = piece.model_rotation;
  Eigen::AlignedBox3d box;
  for (const auto& o : raw.objects) {
    const Mesh& mesh = raw.meshes[size_t(o.mesh)];
    const Mat3 L = R * o.T_world_object.block<3, 3>(0, 0);
    const Vec3 t = R * o.T_world_object.block<3, 1>(0, 3);
    for (const auto& p : mesh.positions) box.extend(L * p.cast<double>() + t);
  }
  m.natural_extent = box.sizes();
  const Vec3 size_sh(piece.width_cm, piece.height_cm, piece.depth_cm);  // x, y (up), z (front)
  Vec3 scale;
  for (int i = 0; i < 3; ++i)  // a flat model (a rug, a sheet) keeps its zero thickness
    scale[i] = m.natural_extent[i] > 0 ? size_sh[i] / 100.0 / m.natural_extent[i] : 0.0;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (int i = 0; i < 3; ++i)
    if (scale[i] > 0) lo = std::min(lo, scale[i]), hi = std::max(hi, scale[i]);
  m.stretch = hi > 0 ? hi / lo : 1.0;
  // theirs -> ours: (x, y, z) = (x', -z', y'), then the bottom to z = 0
  Mat3 C;
  C << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const Mat3 A = C * scale.asDiagonal() * R;
  const Vec3 shift = -(C * scale.cwiseProduct(box.center())) + Vec3(0, 0, piece.height_cm / 200.0);

  m.size = Vec3(piece.width_cm, piece.depth_cm, piece.height_cm) / 100.0;
  m.elevation_m = piece.elevation_cm / 100.0;
  m.drop_on_top_m = piece.drop_on_top_elevation > 0 ? piece.drop_on_top_elevation / 100.0 : -1.0;
  Scene& out = m.parts;
  out.name = piece.id;
  out.materials = raw.materials;
  for (Material& mat : out.materials) {  // named by piece in layouts (scene/catalog_ref.h)
    mat.catalog_piece = piece.id;
    mat.catalog_material = mat.id;
    mat.id = piece.id + "/" + mat.id;
  }
  for (const auto& o : raw.objects) {
    const Mesh& src = raw.meshes[size_t(o.mesh)];
    const Mat3 L = A * o.T_world_object.block<3, 3>(0, 0);
    const Vec3 t = A * o.T_world_object.block<3, 1>(0, 3) + shift;
    const bool degenerate = std::abs(L.determinant()) < 1e-30;
    const Mat3 N = degenerate ? Mat3::Identity() : normalMatrix(L);
    Mesh mesh;
    mesh.id = fmt::format("{}#{}", piece.id, out.meshes.size());
    mesh.source.kind = MeshSource::Kind::Catalog;
    mesh.source.catalog_piece = piece.id;
    mesh.source.catalog_part = static_cast<int>(out.meshes.size());
    mesh.uvs = src.uvs;
    mesh.triangles = src.triangles;
    mesh.positions.reserve(src.positions.size());
    for (const auto& p : src.positions)
      mesh.positions.push_back((L * p.cast<double>() + t).cast<float>());
    for (const auto& n : src.normals) {
      Vec3 nn = N * n.cast<double>();
      if (nn.squaredNorm() < 1e-30) nn = Vec3::UnitZ();
      mesh.normals.push_back(nn.normalized().cast<float>());
    }
    if (L.determinant() < 0)  // a mirroring map turns the triangles inside out: flip them back
      for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
    Eigen::AlignedBox3d part_box;
    for (const auto& p : mesh.positions) part_box.extend(p.cast<double>());
    m.hulls.push_back(part_box);
    out.meshes.push_back(std::move(mesh));
    Object obj = Object::make(o.name, static_cast<int>(out.meshes.size()) - 1, o.material,
                              Mat4::Identity(), m.label.nyu40, 1);
    obj.kind = m.label.kind;
    obj.part = o.name;
    out.objects.push_back(std::move(obj));
  }

  out.lights = lampLights(piece, m.label.category);

  const Physical phys = physicalOf(m.label.nyu40);
  const double raw_mass = phys.density * m.size.prod();
  m.mass_kg = std::clamp(raw_mass, 0.05, 45.0);  // the paper's range; heavier = unmovable
  m.friction = phys.friction;
  m.movable =
      piece.movable && !piece.door_or_window && raw_mass <= 45.0 && piece.category != "Staircases";
  for (auto& o : out.objects)
    o.physics = PhysicsProps{float(m.mass_kg), float(m.friction), m.movable};
  return m;
}

}  // namespace inet
