// interiornet assets: the Sweet Home 3D furniture catalogs (assets/furniture_catalog.h):
// `list` prints what the installed catalogs hold and how each piece is labelled; `sheet`
// renders every matching model alone on a floor under a sky into one contact sheet (PNG).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "assets/catalog_labels.h"
#include "assets/catalog_model.h"
#include "assets/furniture_catalog.h"
#include "common.h"
#include "core/color.h"
#include "core/error.h"
#include "core/plot.h"
#include "core/progress.h"
#include "render/renderer.h"
#include "render/tonemap.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace inet::app {
namespace {

struct AssetsArgs {
  std::string catalog_dir;
  std::string category;  ///< Sweet Home 3D category ("" = all)
  std::string match;     ///< substring of id or name, case-insensitive ("" = all)
  bool all = false;      ///< include exterior pieces and vehicles
  bool json = false;
  std::string out;
  int size = 160;
  int spp = 16;
  int columns = 10;
  int threads = 0;
};

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct Selected {
  const FurnitureCatalog* catalog;
  const CatalogPiece* piece;
};

std::vector<Selected> select(const std::vector<FurnitureCatalog>& catalogs, const AssetsArgs& a) {
  std::vector<Selected> out;
  for (const auto& c : catalogs)
    for (const auto& p : c.pieces) {
      if (!a.all && !p.isInterior()) continue;
      if (!a.category.empty() && lower(p.category) != lower(a.category)) continue;
      if (!a.match.empty() && lower(p.id + " " + p.name).find(lower(a.match)) == std::string::npos)
        continue;
      out.push_back({&c, &p});
    }
  return out;
}

void runList(const AssetsArgs& a) {
  const auto catalogs = readFurnitureCatalogs(catalogDir(a.catalog_dir));
  const auto sel = select(catalogs, a);
  if (a.json) {
    nlohmann::json arr = nlohmann::json::array();
    for (const auto& s : sel) {
      const CatalogPiece& p = *s.piece;
      const CatalogLabel l = labelCatalogPiece(p);
      arr.push_back({{"id", p.id},
                     {"name", p.name},
                     {"category", p.category},
                     {"size_cm", {p.width_cm, p.depth_cm, p.height_cm}},
                     {"elevation_cm", p.elevation_cm},
                     {"nyu40", l.nyu40},
                     {"nyu40_name", std::string(nyu40Name(l.nyu40))},
                     {"furniture_category", l.category},
                     {"kind", l.kind},
                     {"rule", l.rule},
                     {"lights", p.lights.size()},
                     {"door_or_window", p.door_or_window.has_value()},
                     {"movable", p.movable},
                     {"creator", p.creator},
                     {"license", p.license},
                     {"catalog", s.catalog->name}});
    }
    fmt::print("{}\n", arr.dump(1));
    return;
  }
  fmt::print("{:<40} {:<28} {:<18} {:>17}  {:<16} {:<20} {}\n", "id", "name", "category",
             "size (cm)", "nyu40", "ours", "creator");
  for (const auto& s : sel) {
    const CatalogPiece& p = *s.piece;
    const CatalogLabel l = labelCatalogPiece(p);
    fmt::print("{:<40} {:<28} {:<18} {:>5.0f}x{:>5.0f}x{:>5.0f}  {:<16} {:<20} {}\n", p.id, p.name,
               p.category, p.width_cm, p.depth_cm, p.height_cm, nyu40Name(l.nyu40),
               l.category.empty() ? "-" : l.category, p.creator);
  }
  fmt::print("{} pieces in {} catalogs ({})\n", sel.size(), catalogs.size(),
             catalogDir(a.catalog_dir));
}

/// The model alone: on a light grey floor under a uniform sky, with a sun from the front left,
/// seen from the front left and a little above, framed to its bounding sphere.
ImageU8 renderThumbnail(const CatalogModel& m, const AssetsArgs& a, uint32_t index) {
  Scene s = m.parts;
  s.lights.clear();  // lamps unlit: the sheet shows shapes and materials
  Material floor;
  floor.id = "sheet_floor";
  floor.albedo = Vec3f::Constant(0.6f);
  s.materials.push_back(floor);
  Mesh quad = makePrimitive("quad", {}, "sheet", "floor");
  quad.id = "sheet_floor";
  s.meshes.push_back(std::move(quad));
  const double extent = std::max(m.size.maxCoeff(), 0.05);
  Mat4 T = Mat4::Identity();
  T.block<3, 3>(0, 0) *= 40.0 * extent;
  s.objects.push_back(
      Object::make("sheet_floor", int(s.meshes.size()) - 1, int(s.materials.size()) - 1, T, 2, 2));
  Light sky;
  sky.name = "sheet_sky";
  sky.type = LightType::Sky;
  sky.intensity = 0.6f;
  s.lights.push_back(sky);
  Light sun;
  sun.name = "sheet_sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0.45, 0.6, -0.66).normalized();
  sun.intensity = 3.0f;
  s.lights.push_back(sun);
  const Vec3 centre(0, 0, m.size.z() / 2);
  const double radius = 0.5 * m.size.norm();
  const double fov = 40.0 * M_PI / 180.0;
  const Vec3 dir = Vec3(-0.45, -0.8, 0.4).normalized();  // from the model to the camera
  const Vec3 eye = centre + dir * (radius / std::sin(fov / 2) * 1.02);
  const Pose T_wc = Pose::lookAt(eye, centre, Vec3::UnitZ());
  const double f = a.size / 2.0 / std::tan(fov / 2);
  const CameraIntrinsics K = CameraIntrinsics::centred(a.size, a.size, f);
  Renderer renderer(s);
  RenderOptions opt;
  opt.spp = a.spp;
  opt.denoise = true;
  opt.passes = bit(Pass::Rgb);
  opt.seed = index;
  Frame frame;
  renderer.render(K, T_wc, opt, 0, frame);
  CameraResponse response;
  response.curve = ToneCurve::Aces;
  return applyCameraResponse(frame.rgb, response);
}

void runSheet(const AssetsArgs& a) {
  if (a.out.empty()) throw InputError("", "--out", "required: the contact sheet's PNG path");
  if (a.size < 16 || a.size > 1024) throw InputError("", "--size", "must be in 16..1024");
  if (a.spp < 1) throw InputError("", "--spp", "must be >= 1");
  const auto catalogs = readFurnitureCatalogs(catalogDir(a.catalog_dir));
  const auto sel = select(catalogs, a);
  if (sel.empty()) throw InputError("", "--category/--match", "no catalog piece matches");
  ThreadLimit limit(a.threads);
  ProgressBar bar(static_cast<int64_t>(sel.size()), "models");
  std::vector<SheetTile> tiles;
  for (size_t i = 0; i < sel.size(); ++i) {
    const CatalogModel m = loadCatalogModel(*sel[i].catalog, *sel[i].piece);
    tiles.push_back({renderThumbnail(m, a, static_cast<uint32_t>(i)), m.name});
    bar.update(static_cast<int64_t>(i + 1));
  }
  bar.finish();
  writeContactSheetPng(a.out, tiles, a.columns);
  fmt::print("{} models -> {}\n", tiles.size(), a.out);
}

void addSelection(CLI::App* cmd, AssetsArgs& a) {
  cmd->add_option("--catalog", a.catalog_dir,
                  "Folder of .sh3f catalogs (default: $INTERIORNET_CATALOG, else "
                  "/usr/share/sweethome3d/furniture from Debian's sweethome3d-furniture)");
  cmd->add_option(
      "--category", a.category,
      "Only this Sweet Home 3D category (\"Living room\", \"Kitchen\", \"Lights\", ...)");
  cmd->add_option("--match", a.match, "Only pieces whose id or name contains this text");
  cmd->add_flag("--all", a.all, "Include exterior pieces and vehicles");
}

}  // namespace

void registerAssets(CLI::App& app) {
  auto* assets = app.add_subcommand(
      "assets",
      "Sweet Home 3D furniture catalogs: list the models (with their NYU40 class and "
      "our furniture category) or render them into a contact sheet (docs/assets.md)");
  assets->require_subcommand(1);
  auto args = std::make_shared<AssetsArgs>();
  auto* list = assets->add_subcommand(
      "list",
      "One line per catalog piece: id, name, category, size, NYU40 class, our category, "
      "creator (--json: every field, with licence and the labelling rule)");
  addSelection(list, *args);
  list->add_flag("--json", args->json, "Print JSON");
  list->callback([args] { runList(*args); });
  auto* sheet = assets->add_subcommand(
      "sheet", "Render every selected model alone (floor, sky, sun) into one PNG contact sheet");
  addSelection(sheet, *args);
  sheet->add_option("--out", args->out, "Output PNG")->required();
  sheet->add_option("--size", args->size, "Thumbnail side in pixels")->capture_default_str();
  sheet->add_option("--spp", args->spp, "Samples per pixel (denoised)")->capture_default_str();
  sheet->add_option("--columns", args->columns, "Thumbnails per row")->capture_default_str();
  sheet->add_option("--threads", args->threads, "Render threads (0 = all cores)");
  sheet->callback([args] { runSheet(*args); });
}

}  // namespace inet::app
