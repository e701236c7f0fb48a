#include "common.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <filesystem>

#include "core/error.h"
#include "render/sensor_noise.h"
#include "render/tonemap.h"
#include "scene/assimp_importer.h"
#include "scene/default_scene.h"
#include "scene/layout_json.h"

namespace inet::app {

void SceneArgs::addTo(CLI::App& cmd) {
  cmd.add_option("--layout,--scene", path,
                 "layout.json, or a mesh scene (.obj .gltf .glb .ply ...) imported with Assimp; "
                 "default: the built-in furnished room");
  cmd.add_option("--up", up, "up axis of an imported mesh scene (y or z; default z)")
      ->check(CLI::IsMember({"y", "z"}));
  cmd.add_option("--scale", scale, "metres per unit of an imported mesh scene (default 1)");
  cmd.add_option("--labels", labels,
                 "CSV 'name,nyu40' mapping object names of an imported scene to NYU40");
}

Scene SceneArgs::load() const {
  if (path.empty()) return makeDefaultScene();
  std::filesystem::path p(path);
  if (p.extension() == ".json") return loadLayout(path);
  if (!(scale > 0)) throw InputError(path, "--scale", "must be > 0");
  ImportOptions opt;
  opt.scale = scale;
  opt.up = up[0];
  opt.label_map = labels;
  ImportReport report;
  Scene s = importMeshScene(path, opt, &report);
  std::string warn = report.summary(opt.default_category);
  if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
  return s;
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
  ImageF img = applyExposure(linear, r.multiplier());
  if (sensor_noise) img = applySensorNoise(img, SensorNoise{}, seed, frame);
  r.exposure_ev = 0.f;
  r.curve = parseToneCurve(tone, "", "--tone");
  return applyExposureAndCurve(img, r);
}

std::string ResponseArgs::describe() const {
  return fmt::format("exposure_ev={} tone={} sensor_noise={}", exposure_ev, tone,
                     sensor_noise ? SensorNoise{}.describe() : std::string("off"));
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
