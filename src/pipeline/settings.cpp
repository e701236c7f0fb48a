#include "pipeline/settings.h"

#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "assets/catalog_library.h"
#include "assets/furniture_catalog.h"
#include "assets/sh3d_import.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "procedural/apartment.h"
#include "render/sensor_noise.h"
#include "render/tonemap.h"
#include "scene/assimp_importer.h"
#include "scene/default_scene.h"
#include "scene/front3d_importer.h"
#include "scene/layout_json.h"
#include "scene/light_xml.h"
#include "variation/auto_lights.h"

namespace inet {

namespace {

/// The apartment of `opt` named `name`, its textures in `dir` (kept: the renderer reads them
/// there). They are written atomically and depend on the options alone, so jobs of the same
/// apartment in parallel and a job stopped half-way leave whole files.
Scene cachedApartment(const ApartmentOptions& opt, const std::filesystem::path& dir,
                      const std::string& name) {
  if (opt.furniture != FurnitureSource::Parametric) installCatalogResolver();
  Scene s = makeApartment(opt, dir, dir / "textures").scene;
  s.name = name;
  return s;
}

/// The apartment of a "procedural:<seed>" source; its textures are made once per machine.
Scene proceduralApartment(const SceneSource& src) {
  const std::string digits = src.path.substr(std::string("procedural:").size());
  if (digits.empty() || digits.size() > 18 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(src.path, "--layout", "procedural:<seed> needs a seed 0..");
  if (src.rooms < 0 || src.rooms > 16)
    throw InputError(src.path, "rooms", "must be in 0..16 (0 = drawn)");
  ApartmentOptions opt;
  opt.seed = std::stoull(digits);
  opt.rooms = src.rooms;
  opt.furniture = src.furniture.empty() ? (catalogsAvailable() ? FurnitureSource::Catalog
                                                               : FurnitureSource::Parametric)
                                        : parseFurnitureSource(src.furniture, "furniture");
  if (opt.furniture != FurnitureSource::Parametric) catalogLibrary();  // a clear error without
  return cachedApartment(
      opt,
      userCacheDir("procedural") /
          fmt::format("seed{}_rooms{}_{}", opt.seed, opt.rooms, furnitureSourceName(opt.furniture)),
      fmt::format("procedural_{}", opt.seed));
}

}  // namespace

Scene SceneSource::load() const {
  const AutoLightMode mode = parseAutoLightMode(auto_lights, "--auto-lights");
  Scene s = loadScene();
  if (!lights.empty()) applyLightSetup(s, loadLightXml(lights), lights);
  AutoLightOptions opt;
  opt.mode = mode;
  const AutoLightReport r = addAutoLights(s, opt);
  const std::string where = path.empty() ? std::string("built-in room") : path;
  if (!r.summary().empty())
    std::fprintf(stderr, "warning: %s: %s\n", where.c_str(), r.summary().c_str());
  else if (!sceneHasLight(s))
    std::fprintf(stderr,
                 "warning: %s: the scene has no light (no lamp, no emissive material, no sun or "
                 "sky) and renders black; --auto-lights auto adds lights\n",
                 where.c_str());
  return s;
}

Scene SceneSource::loadScene() const {
  if (isBuiltinRoom()) return makeDefaultScene();
  if (isBuiltinApartment()) return builtinApartment();
  if (isProcedural()) return proceduralApartment(*this);
  std::filesystem::path p(path);
  if (p.extension() == ".json") {
    try {
      return loadLayout(path);
    } catch (const InputError& e) {
      // a 3D-FRONT house works as it is too (layout import writes it as a layout once)
      if (e.field() != "format" || e.problem().find("3D-FRONT") == std::string::npos) throw;
    }
    Front3dOptions opt;
    opt.label_map = labels;
    opt.add_lights = false;  // the automatic lights (load) light it, as every imported scene
    Front3dReport report;
    Scene s = importFront3d(path, opt, &report);
    const std::string warn = report.summary();
    if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
    return s;
  }
  if (lowerExtension(path) == ".sh3d") {  // a Sweet Home 3D home
    Sh3dImportReport report;
    Scene s = importSh3d(path, Sh3dImportOptions{}, &report);
    const std::string warn = report.summary();
    if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
    return s;
  }
  if (!(scale > 0)) throw InputError(path, "--scale", "must be > 0");
  if (isMitsuba()) {
    MitsubaReport report;
    Scene s = importMitsubaScene(path, mitsubaOptions(), &report);
    const std::string warn = report.summary(mitsubaOptions().default_category);
    if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
    return s;
  }
  ImportOptions opt;
  opt.scale = scale;
  opt.up = up.empty() || up == "auto" ? 'a' : up[0];
  opt.label_map = labels;
  ImportReport report;
  Scene s = importMeshScene(path, opt, &report);
  if (!report.up_reason.empty())
    std::fprintf(stderr, "note: %s: read as %s; --up %c to override\n", path.c_str(),
                 report.up_reason.c_str(), report.up == 'y' ? 'z' : 'y');
  std::string warn = report.summary(opt.default_category);
  if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
  return s;
}

bool SceneSource::isMitsuba() const {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".xml";
}

MitsubaOptions SceneSource::mitsubaOptions() const {
  MitsubaOptions opt;
  opt.up = up.empty() || up == "auto" ? 'y' : up[0];
  opt.scale = scale;
  opt.label_map = labels;
  return opt;
}

Trajectory readTrajectoryFile(const std::string& path, std::optional<TrajectoryFormat> fmt,
                              const TrajectoryFormatOptions& opt) {
  TrajectoryReadReport report;
  Trajectory traj = readTrajectory(path, fmt, opt, &report);
  warnTrajectoryRead(path, report);
  return traj;
}

void warnTrajectoryRead(const std::string& path, const TrajectoryReadReport& report) {
  const std::string w = report.summary();
  if (!w.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), w.c_str());
}

Scene defaultApartment() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       fmt::format("interiornet-apartment-{}", static_cast<long>(::getpid()));
  ApartmentOptions opt;
  opt.seed = 0;
  opt.texture_size = 64;
  Scene scene;
  try {
    scene = makeApartment(opt, dir, dir / "textures").scene;
  } catch (...) {
    fs::remove_all(dir);
    throw;
  }
  fs::remove_all(dir);
  return scene;
}

Scene builtinApartment() {
  if (!catalogsAvailable())
    throw InputError(catalogDir(), "--layout builtin:apartment",
                     "the apartment is furnished from Sweet Home 3D's catalogs, which are not "
                     "installed (bash scripts/setup.sh installs sweethome3d-furniture)");
  ApartmentOptions opt;
  opt.seed = kBuiltinApartmentSeed;
  opt.rooms = 4;
  opt.furniture = FurnitureSource::Catalog;
  return cachedApartment(
      opt, userCacheDir("builtin") / fmt::format("apartment_seed{}", kBuiltinApartmentSeed),
      "apartment");
}

void ResponseSettings::validate() const {
  if (!std::isfinite(exposure_ev) || std::abs(exposure_ev) > 30)
    throw InputError("", "--exposure-ev", "must be within -30..30 stops");
  parseToneCurve(tone, "", "--tone");
}

ImageF ResponseSettings::apply(const ImageF& linear, uint64_t seed, uint32_t frame) const {
  CameraResponse r;
  r.exposure_ev = exposure_ev;
  r.exposure_scale = exposure_scale;
  ImageF img = applyExposure(linear, r.multiplier());
  if (sensor_noise) img = applySensorNoise(img, SensorNoise{}, seed, frame);
  r.exposure_ev = 0.f;
  r.exposure_scale = 1.f;
  r.curve = parseToneCurve(tone, "", "--tone");
  return applyExposureAndCurve(img, r);
}

std::string ResponseSettings::describe() const {
  return fmt::format("exposure_ev={} exposure_scale={} tone={} sensor_noise={}", exposure_ev,
                     exposure_scale, tone,
                     sensor_noise ? SensorNoise{}.describe() : std::string("off"));
}

LensType LensSettings::type() const {
  LensType t = lens.empty() ? (aperture_m > 0 ? LensType::ThinLens : LensType::Pinhole)
                            : parseLensType(lens, "", "--lens");
  if (!(aperture_m >= 0 && aperture_m < 1))
    throw InputError("", "--aperture", "must be in [0, 1) metres");
  if (!(focus_m > 0 && std::isfinite(focus_m)))
    throw InputError("", "--focus", "must be > 0 metres");
  if (!(fisheye_fov_deg > 0 && fisheye_fov_deg <= 360))
    throw InputError("", "--fisheye-fov", "must be in (0, 360] degrees");
  const std::string name = lensTypeName(t);
  if (t != LensType::ThinLens && aperture_m > 0)
    throw InputError("", "--aperture", "only used by --lens thin_lens, not " + name);
  if (t != LensType::ThinLens && focus_set)
    throw InputError("", "--focus", "only used by --lens thin_lens, not " + name);
  if (t != LensType::Fisheye && fisheye_fov_set)
    throw InputError("", "--fisheye-fov", "only used by --lens fisheye, not " + name);
  if (!distortion.empty()) {
    if (distortion.size() != 4 && distortion.size() != 5)
      throw InputError("", "--distortion",
                       fmt::format("needs 4 or 5 values k1,k2,p1,p2[,k3], not {}",
                                   distortion.size()));
    for (double k : distortion)
      if (!(std::isfinite(k) && std::abs(k) <= 100))
        throw InputError("", "--distortion", fmt::format("{} is not a coefficient in [-100, 100]", k));
    if (t != LensType::Pinhole && t != LensType::ThinLens)
      throw InputError("", "--distortion",
                       "only used by --lens pinhole and thin_lens, not " + name +
                           " (whose projection has no Brown-Conrady terms)");
  }
  return t;
}

LensModel LensSettings::make(const CameraIntrinsics& K, const std::string& where) const {
  LensModel m;
  switch (type()) {
    case LensType::Pinhole:
      m = LensModel::pinhole(K);
      break;
    case LensType::ThinLens:
      m = LensModel::thinLens(K, aperture_m, focus_m);
      break;
    case LensType::Fisheye:
      INET_CHECK_MSG(K.width == K.height, "a fisheye image is square");
      m = LensModel::fisheye(K.width, fisheye_fov_deg);
      break;
    case LensType::Panorama:
      m = LensModel::panorama(K.width, K.height);
      break;
  }
  if (!distortion.empty()) {
    m.k1 = distortion[0];
    m.k2 = distortion[1];
    m.p1 = distortion[2];
    m.p2 = distortion[3];
    m.k3 = distortion.size() == 5 ? distortion[4] : 0.0;
  }
  try {
    m.validate(where);
  } catch (const InputError& e) {
    // the coefficients came from one flag: name it rather than the model's field names
    if (m.hasDistortion() && e.field() == "k1..k3, p1, p2")
      throw InputError("", "--distortion", e.problem());
    throw;
  }
  return m;
}

void LensSettings::checkFormats(const std::vector<std::string>& formats) const {
  if (distortion.size() == 5 && distortion[4] != 0 &&
      std::find(formats.begin(), formats.end(), "asl") != formats.end())
    throw InputError("", "--distortion",
                     "the ASL sensor.yaml (Kalibr radial-tangential) holds k1 k2 p1 p2 only: give "
                     "4 values, or a fifth (k3) with --format tum");
}

RandomTrajectoryOptions MotionSettings::options(MotionType type, uint64_t seed, int frames,
                                                double fps) const {
  if (v_mult != 0 && !(v_mult > 0 && v_mult <= 100))
    throw InputError("", "--v-mult", "must be in (0, 100]");
  if (w_mult != 0 && !(w_mult > 0 && w_mult <= 100))
    throw InputError("", "--w-mult", "must be in (0, 100]");
  if (!(clearance >= 0 && clearance <= 5)) throw InputError("", "--clearance", "must be in 0..5");
  if (!(min_height >= 0 && min_height < max_height && max_height <= 100))
    throw InputError("", "--max-height", "need 0 <= --min-height < --max-height <= 100");
  if (style != "none" && style != "learned")
    throw InputError("", "--style", "must be none or learned, not '" + style + "'");
  RandomTrajectoryOptions o;
  o.learned_style = style == "learned";
  o.type = type;
  o.seed = seed;
  o.frames = frames;
  o.fps = fps;
  o.v_mult = v_mult;
  o.w_mult = w_mult;
  o.clearance = clearance;
  o.min_height = min_height;
  o.max_height = max_height;
  return o;
}

}  // namespace inet
