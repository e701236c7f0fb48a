// interiornet layout show: what a layout or mesh scene contains, as the renderer will see it.
// interiornet layout import: a mesh scene (OBJ, glTF, ...) written as a layout.json, to add
// lights, materials or motion to by hand.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "assets/catalog_library.h"
#include "assets/sh3d_import.h"
#include "common.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "core/text.h"
#include "procedural/apartment.h"
#include "render/camera.h"
#include "render/lights.h"
#include "scene/assimp_importer.h"
#include "scene/layout_json.h"
#include "scene/front3d_importer.h"
#include "scene/gltf_export.h"
#include "scene/layout_stats.h"
#include "scene/light_xml.h"
#include "scene/nyu40.h"
#include "variation/auto_lights.h"

namespace inet::app {
namespace {

void showScene(const Scene& s) {
  auto [lo, hi] = s.bounds();
  std::map<int, int> per_class;
  std::map<int, int> instances;
  int emitters = 0;
  for (const auto& o : s.objects) {
    instances[o.instance] = o.nyu40;
    if (s.materials[o.material].isEmissive()) ++emitters;
  }
  for (const auto& [inst, label] : instances) ++per_class[label];
  fmt::print("layout     {}\n", s.name);
  fmt::print("meshes     {} ({} triangles placed in the world)\n", s.meshes.size(),
             s.triangleCount());
  fmt::print("materials  {}\n", s.materials.size());
  fmt::print("objects    {} parts in {} instances, {} emissive, {} analytic lights\n",
             s.objects.size(), instances.size(), emitters, s.lights.size());
  fmt::print("bounds     x [{:.3f}, {:.3f}]  y [{:.3f}, {:.3f}]  z [{:.3f}, {:.3f}] m\n", lo.x(),
             hi.x(), lo.y(), hi.y(), lo.z(), hi.z());
  fmt::print("instances per NYU40 class:\n");
  for (const auto& [label, count] : per_class)
    fmt::print("  {:>2} {:<16} {}\n", label, nyu40Name(label), count);
}

/// Writes `s` to `out` with texture, mesh-file and environment-map paths relative to the
/// output's folder (so the layout keeps working where it is written).
void importScene(Scene s, const std::string& out) {
  namespace fs = std::filesystem;
  if (out.empty()) throw InputError("", "--out", "an output layout.json path is needed");
  const fs::path dir = fs::absolute(fs::path(out)).parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);  // as generate --out does
  if (!fs::is_directory(dir, ec))
    throw InputError(out, "--out", "cannot create the folder " + dir.string());
  // images the file embedded (glTF data URIs, .glb) live in a cache: a copy goes next to the
  // layout, so the folder holds everything it needs
  // (and textures importers extract from archives, .sh3d homes, to the user cache)
  const fs::path cache = fs::absolute(embeddedTextureCache()).lexically_normal();
  fs::path user_cache = fs::absolute(userCacheDir("")).lexically_normal();
  if (!user_cache.has_filename()) user_cache = user_cache.parent_path();  // "…/interiornet/"
  for (Material& m : s.materials)
    for (TextureRef* t : {&m.albedo_texture, &m.roughness_texture, &m.normal_texture}) {
      if (t->empty()) continue;
      const fs::path p = fs::absolute(t->path).lexically_normal();
      const std::string in_cache = p.lexically_relative(user_cache).generic_string();
      if (!in_cache.empty() && in_cache.rfind("..", 0) != 0) {
        fs::create_directories(dir / "textures", ec);
        // embedded images are named by their content hash; files extracted from archives may
        // share a name, so they are named by their place in the cache (the archive's content
        // checksum is a folder of it): the same name on every machine
        std::string name = in_cache;
        std::replace(name.begin(), name.end(), '/', '_');
        const fs::path copy =
            dir / "textures" / (p.parent_path() == cache ? p.filename().string() : name);
        if (!fs::exists(copy, ec)) fs::copy_file(p, copy, ec);
        if (ec) throw InputError(copy.string(), "--out", "cannot write: " + ec.message());
        t->path = copy.string();
      }
      t->file = fs::proximate(fs::absolute(t->path), dir).generic_string();
    }
  for (Mesh& m : s.meshes)  // importers leave the resolved path of a referenced mesh file
    if (m.source.kind == MeshSource::Kind::File)
      m.source.file = fs::proximate(fs::absolute(m.source.file), dir).generic_string();
  for (Light& l : s.lights)
    if (!l.envmap.empty())
      l.envmap.file = fs::proximate(fs::absolute(l.envmap.path), dir).generic_string();
  saveLayout(s, out);
  const auto inline_meshes = std::count_if(s.meshes.begin(), s.meshes.end(), [](const Mesh& m) {
    return m.source.kind == MeshSource::Kind::Inline;
  });
  fmt::print("wrote {} ({} objects, {} materials, {} meshes, {} of them inline)\n", out,
             s.objects.size(), s.materials.size(), s.meshes.size(), inline_meshes);
}

/// A Mitsuba scene to `out`, and its sensor to camera.json in the same folder, so that
/// `interiornet render --layout OUT --camera camera.json` renders the scene's own view.
void importMitsuba(const SceneSource& args, const std::string& out) {
  namespace fs = std::filesystem;
  if (!(args.scale > 0)) throw InputError(args.path, "--scale", "must be > 0");
  const MitsubaOptions opt = args.mitsubaOptions();
  MitsubaScene ms = readMitsubaScene(args.path, opt);
  const std::string warn = ms.report.summary(opt.default_category);
  if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", args.path.c_str(), warn.c_str());
  importScene(std::move(ms.scene), out);
  const fs::path camera = fs::path(out).parent_path() / "camera.json";
  if (!ms.sensor) {
    fmt::print("{} has no perspective sensor: no camera.json written\n", args.path);
    return;
  }
  writeTextAtomic(camera, mitsubaCameraJson(*ms.sensor, fs::path(args.path).filename().string()));
  fmt::print("wrote {} (the scene's sensor: {}x{}, fx {:.2f})\n", camera.string(),
             ms.sensor->width, ms.sensor->height, ms.sensor->fx);
}

/// A Sweet Home 3D home to `out`, and its views (video path, else stored points of view, else
/// the observer) to cameras.tum beside it: one pose a second, for generate --trajectory.
void importHome(const SceneSource& args, const std::string& out) {
  namespace fs = std::filesystem;
  const Sh3dHome home = readSh3dHome(args.path);
  Sh3dImportReport report;
  Scene s = sh3dToScene(home, Sh3dImportOptions{}, &report);
  const std::string warn = report.summary();
  if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", args.path.c_str(), warn.c_str());
  if (!args.lights.empty()) applyLightSetup(s, loadLightXml(args.lights), args.lights);
  fmt::print("{}: {} level(s), {} wall(s) with {} door/window cut-out(s), {} room(s), {} "
             "piece(s) ({} doors and windows), {} lamp bulb(s)\n",
             args.path, report.levels, report.walls, report.holes, report.rooms, report.pieces,
             report.doors_windows, report.lights);
  importScene(std::move(s), out);
  const std::vector<Sh3dView> views = sh3dViews(home);
  if (views.empty()) return;
  std::string tum = fmt::format("# {} views of {} (name per line below), T_world_camera\n",
                                views.size(), fs::path(args.path).filename().string());
  for (size_t i = 0; i < views.size(); ++i) {
    const Pose& T = views[i].T_world_camera;
    tum += fmt::format("# {}: {}\n{:.6f} {:.6f} {:.6f} {:.6f} {:.9f} {:.9f} {:.9f} {:.9f}\n", i,
                       views[i].name, double(i), T.t.x(), T.t.y(), T.t.z(), T.q.x(), T.q.y(),
                       T.q.z(), T.q.w());
  }
  const fs::path cams = fs::path(out).parent_path() / "cameras.tum";
  writeTextAtomic(cams, tum);
  fmt::print("wrote {} ({} view(s))\n", cams.string(), views.size());
}

struct GenerateLayoutArgs {
  uint64_t seed = 0;
  int rooms = 0;
  int count = 1;
  int texture_size = 256;
  bool daylight = true;
  std::string style = "any";
  std::string furniture;  ///< "" = catalog when the catalogs are installed, else parametric
  std::string catalog;
  std::string out;

  FurnitureSource furnitureSource() const {
    if (!furniture.empty()) return parseFurnitureSource(furniture);
    return catalogsAvailable(catalog) ? FurnitureSource::Catalog : FurnitureSource::Parametric;
  }
};

/// One apartment into `dir`: layout.json and light.xml; textures go to `textures` (shared by
/// the apartments of one run: they depend on the material only).
void generateOne(const GenerateLayoutArgs& a, uint64_t seed, const std::filesystem::path& dir,
                 const std::filesystem::path& textures) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  ApartmentOptions opt;
  opt.seed = seed;
  opt.rooms = a.rooms;
  opt.texture_size = a.texture_size;
  opt.daylight = a.daylight;
  opt.random_style = a.style == "random";
  if (!opt.random_style) opt.style = parseDecorStyle(a.style);
  opt.furniture = a.furnitureSource();
  opt.catalog_dir = a.catalog;
  Apartment apt = makeApartment(opt, dir, textures);
  saveLayout(apt.scene, (dir / "layout.json").string());
  saveLightXml(apt.scene, (dir / "light.xml").string());
}

void generateLayouts(const GenerateLayoutArgs& a) {
  namespace fs = std::filesystem;
  if (a.out.empty()) throw InputError("", "--out", "an output folder is needed");
  if (a.count < 1) throw InputError("", "--count", "must be >= 1");
  if (a.style != "random") parseDecorStyle(a.style);  // a bad --style fails before any work
  if (a.furnitureSource() != FurnitureSource::Parametric) catalogLibrary(a.catalog);  // and so
  installCatalogResolver(a.catalog);  // the layouts written are read with the same catalogs
  if (a.count == 1) {
    generateOne(a, a.seed, a.out, fs::path(a.out) / "textures");
    fmt::print("wrote {}/layout.json and light.xml\n", a.out);
    return;
  }
  installStopHandlers();
  ProgressBar bar(a.count, "layouts");
  for (int k = 0; k < a.count; ++k) {
    if (stopSignal()) {
      bar.finish();
      stopIfSignalled(fmt::format("after {} of {} layouts", k, a.count));
    }
    const uint64_t seed = a.seed + static_cast<uint64_t>(k);
    const fs::path dir = fs::path(a.out) / fmt::format("seed_{:06d}", seed);
    if (!fs::exists(dir / "layout.json"))  // a rerun resumes
      generateOne(a, seed, dir, fs::path(a.out) / "textures");
    bar.update(k + 1);
  }
  bar.finish();
  fmt::print("wrote {} layouts under {}\n", a.count, a.out);
}

/// Statistics over every layout.json found in `in` (the folder itself or its sub-folders).
void layoutStats(const std::string& in, const std::string& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(in, ec)) throw InputError(in, "DIR", "not a folder");
  std::vector<fs::path> files;
  if (fs::exists(fs::path(in) / "layout.json")) files.push_back(fs::path(in) / "layout.json");
  for (const auto& e : fs::directory_iterator(in, ec))
    if (e.is_directory() && fs::exists(e.path() / "layout.json"))
      files.push_back(e.path() / "layout.json");
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(in, "DIR", "no layout.json in it or its sub-folders");
  LayoutStats stats;
  ProgressBar bar(static_cast<int64_t>(files.size()), "layouts");
  for (size_t i = 0; i < files.size(); ++i) {
    stats.add(loadLayout(files[i].string()));
    bar.update(static_cast<int64_t>(i + 1));
  }
  bar.finish();
  stats.write(out);
  fmt::print("{} layouts: statistics (CSV tables and PNG charts) in {}\n", stats.layouts, out);
}

/// The radiance of the scene's skies (summed) over every direction, as an equirectangular image
/// in Blender's convention (GltfExportOptions::sky_image); empty when the scene has no sky.
/// The renderer's own environment lookup, with the suns left out: they are exported as lights.
ImageF bakeSky(const Scene& s, int width) {
  Scene skies;
  for (const Light& l : s.lights)
    if (l.type == LightType::Sky && l.on) skies.lights.push_back(l);
  if (skies.lights.empty()) return {};
  const SceneLights lights(skies, {});
  const int height = width / 2;
  ImageF img(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Blender: u = 0.5 - atan2(d.y, d.x) / 2 pi, v (from the top) = 0.5 - elevation / pi
      const double az = (0.5 - (x + 0.5) / width) * 2.0 * M_PI;
      const double el = (0.5 - (y + 0.5) / height) * M_PI;
      const Vec3f d(static_cast<float>(std::cos(el) * std::cos(az)),
                    static_cast<float>(std::cos(el) * std::sin(az)),
                    static_cast<float>(std::sin(el)));
      float pdf;
      const Vec3f L = lights.environmentRadiance(d, nullptr, pdf);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = L[c];
    }
  return img;
}

struct ExportArgs {
  SceneSource scene;
  std::string out, format, camera;
  int sky_width = 1024;
};

void exportLayout(const ExportArgs& a) {
  namespace fs = std::filesystem;
  std::string format = a.format;
  const std::string ext = fs::path(a.out).extension().string();
  if (format.empty()) {
    if (ext != ".gltf" && ext != ".glb")
      throw InputError("", "--out", "name a .gltf or .glb file (or give --format)");
    format = ext.substr(1);
  }
  if (ext != "." + format)
    throw InputError("", "--out", fmt::format("a {} file ends in .{}", format, format));
  if (a.sky_width < 8 || a.sky_width % 2)
    throw InputError("", "--sky-width", "an even number of pixels, at least 8");
  const Scene s = a.scene.load();
  GltfExportOptions opt;
  opt.binary = format == "glb";
  if (!a.camera.empty()) {
    const CameraFile cam = loadCameraJson(a.camera);
    GltfCamera c;
    c.width = cam.intrinsics.width;
    c.height = cam.intrinsics.height;
    c.fx = cam.intrinsics.fx;
    c.fy = cam.intrinsics.fy;
    c.cx = cam.intrinsics.cx;
    c.cy = cam.intrinsics.cy;
    c.T_world_camera = cam.T_world_camera.matrix();
    opt.camera = c;
  }
  const ImageF sky = bakeSky(s, a.sky_width);
  if (!sky.data.empty()) {
    opt.sky_image = fs::path(a.out).stem().string() + "_sky.exr";
    writeExr(fs::absolute(a.out).parent_path() / opt.sky_image, sky, {"R", "G", "B"});
  }
  const GltfExportReport r = exportGltf(s, a.out, opt);
  for (const std::string& n : r.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
  fmt::print("{}: {} nodes, {} meshes, {} materials, {} images, {} lights{}{}{}, {:.1f} MB{}\n",
             a.out, r.nodes, r.meshes, r.materials, r.images, r.lights,
             r.lights_off ? fmt::format(" ({} off, left out)", r.lights_off) : "",
             r.animations ? fmt::format(", {} animations", r.animations) : "",
             opt.camera ? ", a camera" : "", r.bytes / 1e6,
             opt.sky_image.empty() ? "" : "; the sky baked into " + opt.sky_image);
}

}  // namespace

void registerLayout(CLI::App& app) {
  auto* layout = app.add_subcommand("layout", "Generate, import and inspect layouts");
  layout->require_subcommand(1);
  auto* show = layout->add_subcommand(
      "show", "Print a summary of a layout.json or mesh scene: objects, classes, bounds");
  auto args = std::make_shared<SceneSource>();
  addSceneFlags(*show, *args);
  show->callback([args] { showScene(args->load()); });

  auto* gen = layout->add_subcommand(
      "generate",
      "Generate furnished apartments: DIR/layout.json (rooms, walls with doors and windows, "
      "furniture with NYU40 classes, parts and physics), DIR/light.xml and DIR/textures/");
  auto gen_args = std::make_shared<GenerateLayoutArgs>();
  gen->add_option("--seed", gen_args->seed, "seed of the apartment (default 0)");
  gen->add_option("--rooms", gen_args->rooms,
                  "number of rooms, 1 (studio) .. 16; default: drawn like the paper's Fig. 3");
  gen->add_option("--count", gen_args->count,
                  "apartments to make, seeds seed .. seed+count-1, each in OUT/seed_NNNNNN, "
                  "textures shared in OUT/textures (default 1: OUT itself); a rerun skips "
                  "finished ones");
  gen->add_option("--texture-size", gen_args->texture_size,
                  "texels per side of the procedural textures (power of two, default 256)");
  gen->add_flag("!--no-daylight", gen_args->daylight, "no sky or sun through the windows");
  gen->add_option("--style", gen_args->style,
                  "decoration: any (every material variant alike, default), modern, scandinavian, "
                  "classic, industrial, or random (one of the four per seed); changes materials "
                  "and wall and floor colours, not what is placed");
  gen->add_option("--furniture", gen_args->furniture,
                  "parametric (our furniture library), catalog (real Sweet Home 3D models where "
                  "one fits the category, parametric otherwise) or mixed (either, per piece); "
                  "default: catalog when sweethome3d-furniture is installed (docs/assets.md)");
  gen->add_option("--catalog", gen_args->catalog,
                  "folder of .sh3f furniture catalogs (default: $INTERIORNET_CATALOG, else "
                  "/usr/share/sweethome3d/furniture)");
  gen->add_option("--out", gen_args->out, "output folder")->required();
  gen->callback([gen_args] { generateLayouts(*gen_args); });

  auto* stats = layout->add_subcommand(
      "stats",
      "Statistics of many layouts (the paper's Fig. 3): rooms and objects per layout, object "
      "categories, room types; CSV tables and PNG bar charts");
  auto stats_in = std::make_shared<std::string>();
  auto stats_out = std::make_shared<std::string>();
  stats->add_option("DIR", *stats_in, "folder with layout.json or sub-folders with one each")
      ->required();
  stats->add_option("--out", *stats_out, "output folder for the tables and charts")->required();
  stats->callback([stats_in, stats_out] { layoutStats(*stats_in, *stats_out); });

  auto* exp = layout->add_subcommand(
      "export",
      "Write a layout or mesh scene as glTF 2.0 (.gltf + .bin + textures, or one .glb) for "
      "Blender, web viewers and other renderers: PBR materials, KHR_lights_punctual lights, "
      "NYU40 class, instance and part per node in extras, an optional camera, the sky baked into "
      "an equirectangular EXR beside it (docs/gltf.md)");
  auto exp_args = std::make_shared<ExportArgs>();
  exp->add_option("FILE", exp_args->scene.path,
                  "the scene to export (the same as --layout): layout.json or any mesh file; "
                  "default: the built-in furnished room");
  addSceneFlags(*exp, exp_args->scene);
  exp->add_option("--out", exp_args->out, "the .gltf or .glb file to write (atomically)")
      ->required();
  exp->add_option("--format", exp_args->format, "gltf or glb (default: from --out's extension)")
      ->check(CLI::IsMember({"gltf", "glb"}));
  exp->add_option("--camera", exp_args->camera,
                  "a camera.json (render --camera's format) to add as the glTF camera");
  exp->add_option("--sky-width", exp_args->sky_width,
                  "width in pixels of the baked sky image (default 1024; height is half)");
  exp->callback([exp_args] { exportLayout(*exp_args); });

  auto* import = layout->add_subcommand(
      "import",
      "Write a scene as a layout.json: a mesh scene (OBJ, glTF, ... incl. SceneNet layouts: "
      "--from obj) with its materials, textures and NYU40 labels, a 3D-FRONT house JSON "
      "(--from 3dfront, furniture from a 3D-FUTURE folder or as labelled boxes), or a Mitsuba "
      "scene (--from mitsuba: its sensor is written as camera.json beside the layout), or a Sweet "
      "Home 3D home (.sh3d: walls, rooms, doors and windows cut, furniture, lights, daylight "
      "from its compass; its stored views are written as cameras.tum beside the layout), ready "
      "for lights and motion");
  auto import_args = std::make_shared<SceneSource>();
  import->add_option("FILE", import_args->path,
                     "the scene to import (the same as --scene): .json 3D-FRONT house, .xml "
                     "Mitsuba scene, .sh3d Sweet Home 3D home, or any mesh file Assimp reads "
                     "(.obj .gltf .glb .ply .fbx ...)");
  addSceneFlags(*import, *import_args);
  auto out = std::make_shared<std::string>();
  auto from = std::make_shared<std::string>();
  auto models = std::make_shared<std::string>();
  import
      ->add_option("--from", *from,
                   "obj (any Assimp format, SceneNet included), 3dfront, mitsuba or sh3d; "
                   "default: 3dfront for .json, mitsuba for .xml, sh3d for .sh3d, obj otherwise")
      ->check(CLI::IsMember({"obj", "scenenet", "3dfront", "mitsuba", "sh3d"}));
  import->add_option("--models", *models,
                     "3dfront: 3D-FUTURE model folder (<jid>/raw_model.obj); default: none, "
                     "furniture becomes labelled boxes");
  import->add_option("--out", *out, "layout.json to write (atomically)")->required();
  import->callback([import_args, out, from, models] {
    if (import_args->isDefault()) throw InputError("", "FILE", "name the file to import");
    const std::string ext = std::filesystem::path(import_args->path).extension().string();
    const std::string kind = !from->empty()   ? *from
                             : ext == ".json" ? "3dfront"
                             : lowerExtension(import_args->path) == ".sh3d" ? "sh3d"
                             : import_args->isMitsuba() ? "mitsuba"
                                                        : "obj";
    if (kind == "3dfront") {
      Front3dOptions opt;
      opt.models_dir = *models;
      opt.label_map = import_args->labels;
      opt.add_lights = false;  // the automatic lights below, as for every imported scene
      Front3dReport report;
      Scene s = importFront3d(import_args->path, opt, &report);
      const std::string warn = report.summary();
      if (!warn.empty())
        std::fprintf(stderr, "warning: %s: %s\n", import_args->path.c_str(), warn.c_str());
      if (!import_args->lights.empty())
        applyLightSetup(s, loadLightXml(import_args->lights), import_args->lights);
      AutoLightOptions auto_opt;
      auto_opt.mode = parseAutoLightMode(import_args->auto_lights, "--auto-lights");
      const AutoLightReport lights = addAutoLights(s, auto_opt);
      if (!lights.summary().empty())
        std::fprintf(stderr, "warning: %s: %s\n", import_args->path.c_str(),
                     lights.summary().c_str());
      importScene(std::move(s), *out);
    } else if (kind == "sh3d") {
      if (!models->empty()) throw InputError("", "--models", "only for --from 3dfront");
      importHome(*import_args, *out);
    } else if (kind == "mitsuba") {
      if (!models->empty()) throw InputError("", "--models", "only for --from 3dfront");
      importMitsuba(*import_args, *out);
    } else {
      if (!models->empty()) throw InputError("", "--models", "only for --from 3dfront");
      importScene(import_args->load(), *out);  // with --lights and the automatic lights
    }
  });
}

}  // namespace inet::app
