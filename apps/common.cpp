#include "common.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

#include <fmt/format.h>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "assets/catalog_library.h"
#include "assets/furniture_catalog.h"
#include "assets/sh3d_import.h"
#include "render/sensor_noise.h"
#include "render/tonemap.h"
#include "procedural/apartment.h"
#include "scene/assimp_importer.h"
#include "scene/default_scene.h"
#include "scene/front3d_importer.h"
#include "scene/layout_json.h"
#include "scene/light_xml.h"
#include "variation/auto_lights.h"

namespace inet::app {

void SceneArgs::addTo(CLI::App& cmd, const std::string& without) {
  cmd.add_option("--layout,--scene", path,
                 "layout.json, a Mitsuba scene (.xml, docs/mitsuba.md), a 3D-FRONT house (.json), "
                 "a Sweet Home 3D home (.sh3d, docs/assets.md), a mesh scene (.obj .gltf .glb "
                 ".ply ...) imported with Assimp (docs/import.md), or builtin:room / "
                 "builtin:apartment (4 rooms furnished from the Sweet Home 3D catalogs); "
                 "default: " + without);
  cmd.add_option("--up", up,
                 "up axis of an imported scene: y, z or auto (default: auto for mesh files: "
                 "glTF is Y-up, others by where their floors and ceilings face, said on "
                 "stderr; y for a Mitsuba .xml)")
      ->check(CLI::IsMember({"y", "z", "auto"}));
  cmd.add_option("--scale", scale, "metres per unit of an imported mesh scene (default 1)");
  cmd.add_option("--labels", labels,
                 "CSV 'name,nyu40' mapping object names of an imported scene to NYU40");
  cmd.add_option("--lights", lights,
                 "light.xml lighting setup replacing the scene's lights (switch lamps on or off, "
                 "recolour them, dim the sun); default: the scene's own");
  cmd.add_option("--auto-lights", auto_lights,
                 "auto (default): a scene without any light gets lights: its lamp objects glow, "
                 "enclosed spaces get ceiling lights, glass or an open scene gets daylight "
                 "(docs/import.md); on: always add them; off: never (a scene without lights "
                 "renders black)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
}

Scene SceneArgs::load() const {
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

Scene SceneArgs::loadScene() const {
  if (isBuiltinRoom()) return makeDefaultScene();
  if (isBuiltinApartment()) return builtinApartment();
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

bool SceneArgs::isMitsuba() const {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".xml";
}

MitsubaOptions SceneArgs::mitsubaOptions() const {
  MitsubaOptions opt;
  opt.up = up.empty() || up == "auto" ? 'y' : up[0];
  opt.scale = scale;
  opt.label_map = labels;
  return opt;
}

namespace {
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void onStopSignal(int sig) {
  g_stop_signal = sig;
}
}  // namespace

void installStopHandlers() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}

int stopSignal() {
  return g_stop_signal;
}

void stopIfSignalled(const std::string& done) {
  const int sig = g_stop_signal;
  if (sig == 0) return;
  std::fprintf(stderr, "stopped by %s %s; rerun the same command to resume\n",
               sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "a signal", done.c_str());
  throw CLI::RuntimeError(128 + sig);
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

void ResponseArgs::addTo(CLI::App& cmd) {
  cmd.add_option("--exposure-ev", exposure_ev,
                 "exposure compensation of the RGB image in stops (default 0)");
  cmd.add_option("--tone", tone,
                 "tone curve before sRGB encoding: none (clip), aces, hable (default none)");
  cmd.add_flag("--sensor-noise", sensor_noise,
               "add shot and read noise of a CMOS sensor (Sony IMX250: 10.7 ke- full well, 1.8 e- "
               "read noise, 12-bit ADC) to the RGB image; seeded, deterministic");
}

void ResponseArgs::validate() const {
  if (!std::isfinite(exposure_ev) || std::abs(exposure_ev) > 30)
    throw InputError("", "--exposure-ev", "must be within -30..30 stops");
  parseToneCurve(tone, "", "--tone");
}

ImageF ResponseArgs::apply(const ImageF& linear, uint64_t seed, uint32_t frame) const {
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

std::string ResponseArgs::describe() const {
  return fmt::format("exposure_ev={} exposure_scale={} tone={} sensor_noise={}", exposure_ev,
                     exposure_scale, tone,
                     sensor_noise ? SensorNoise{}.describe() : std::string("off"));
}

void LensArgs::addTo(CLI::App& cmd) {
  cmd.add_option("--lens", lens,
                 "pinhole, thin_lens (depth of field: --aperture, --focus), fisheye (equidistant "
                 "r = f theta, square image, default 600x600 and 180 deg: --fisheye-fov), "
                 "panorama (equirectangular 360 x 180 deg, 2:1 image, default 5000x2500); "
                 "default pinhole, or thin_lens when --aperture > 0");
  cmd.add_option("--aperture", aperture_m,
                 "thin-lens aperture radius in metres: depth of field (default 0)");
  focus_opt_ = cmd.add_option("--focus", focus_m,
                              "thin-lens focus distance (z of the sharp plane) in metres "
                              "(default 2)");
  fov_opt_ = cmd.add_option("--fisheye-fov", fisheye_fov_deg,
                            "fisheye field of view in degrees, in (0, 360] (default 180)");
}

LensType LensArgs::type() const {
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
  if (t != LensType::ThinLens && focus_opt_ && focus_opt_->count() > 0)
    throw InputError("", "--focus", "only used by --lens thin_lens, not " + name);
  if (t != LensType::Fisheye && fov_opt_ && fov_opt_->count() > 0)
    throw InputError("", "--fisheye-fov", "only used by --lens fisheye, not " + name);
  return t;
}

LensModel LensArgs::make(const CameraIntrinsics& K, const std::string& where) const {
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
  m.validate(where);
  return m;
}

struct ThreadLimit::Impl {
  std::unique_ptr<tbb::global_control> control;
};

ThreadLimit::ThreadLimit(int n) : impl_(std::make_unique<Impl>()) {
  if (n < 0) throw InputError("", "--threads", "must be >= 0 (0 = all cores)");
  if (n > 0)
    impl_->control =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, n);
  threads_ = n > 0 ? n : tbb::info::default_concurrency();
}

ThreadLimit::~ThreadLimit() = default;

const char* version() {
  return INET_VERSION;
}

}  // namespace inet::app

namespace inet::app {

void MotionArgs::addTo(CLI::App& cmd) {
  cmd.add_option("--v-mult", v_mult,
                 "speed multiplier of a random trajectory (base 0.3 m/s RMS; default: drawn from "
                 "U(0.5, 5) per trajectory, as the paper)");
  cmd.add_option("--w-mult", w_mult,
                 "turn-rate multiplier of a random trajectory (base 20 deg/s; default: drawn from "
                 "U(0.5, 3) per trajectory)");
  cmd.add_option("--clearance", clearance,
                 "least distance from the camera to any geometry, m (default 0.25)");
  cmd.add_option("--min-height", min_height, "lowest camera height, m (default 1)");
  cmd.add_option("--max-height", max_height, "highest camera height, m (default 2)");
  cmd.add_option("--style", style,
                 "none (default: the smooth base motion) or learned: hand-held jitter from the "
                 "WaveNet style model trained on real camera paths (docs/style.md)");
}

RandomTrajectoryOptions MotionArgs::options(MotionType type, uint64_t seed, int frames,
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
  installCatalogResolver();
  // the procedural textures stay where the renderer reads them; written atomically, so runs in
  // parallel and a run stopped half-way leave whole files
  const std::filesystem::path dir =
      userCacheDir("builtin") / fmt::format("apartment_seed{}", kBuiltinApartmentSeed);
  Scene s = makeApartment(opt, dir, dir / "textures").scene;
  s.name = "apartment";
  return s;
}

void execCompanion(const std::string& tool_name, const std::string& subcommand,
                   const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path tool = (ec ? fs::path(".") : self.parent_path()) / tool_name;
  std::vector<std::string> owned = {tool.string(), subcommand};
  owned.insert(owned.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : owned) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  ::execv(tool.c_str(), argv.data());
  const int err = errno;
  if (err == ENOENT)  // built with `--target interiornet` alone (make demo)
    throw InputError(tool.string(), "",
                     fmt::format("not built: build it with `cmake --build build --target {}` "
                                 "(or `make build`)",
                                 tool_name));
  throw InputError(tool.string(), "", fmt::format("cannot run it: {}", std::strerror(err)));
}

}  // namespace inet::app
