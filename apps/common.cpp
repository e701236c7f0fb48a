#include "common.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"

namespace inet::app {

void addSceneFlags(CLI::App& cmd, SceneSource& x, const std::string& without) {
  cmd.add_option("--layout,--scene", x.path,
                 "layout.json, a Mitsuba scene (.xml, docs/mitsuba.md), a 3D-FRONT house (.json), "
                 "a Sweet Home 3D home (.sh3d, docs/assets.md), a mesh scene (.obj .gltf .glb "
                 ".ply ...) imported with Assimp (docs/import.md), or builtin:room / "
                 "builtin:apartment (4 rooms furnished from the Sweet Home 3D catalogs); "
                 "default: " +
                     without);
  cmd.add_option("--up", x.up,
                 "up axis of an imported scene: y, z or auto (default: auto for mesh files: "
                 "glTF is Y-up, others by where their floors and ceilings face, said on "
                 "stderr; y for a Mitsuba .xml)")
      ->check(CLI::IsMember({"y", "z", "auto"}));
  cmd.add_option("--scale", x.scale, "metres per unit of an imported mesh scene (default 1)");
  cmd.add_option("--labels", x.labels,
                 "CSV 'name,nyu40' mapping object names of an imported scene to NYU40");
  cmd.add_option("--lights", x.lights,
                 "light.xml lighting setup replacing the scene's lights (switch lamps on or off, "
                 "recolour them, dim the sun); default: the scene's own");
  cmd.add_option("--auto-lights", x.auto_lights,
                 "auto (default): a scene without any light gets lights: its lamp objects glow, "
                 "enclosed spaces get ceiling lights, glass or an open scene gets daylight "
                 "(docs/import.md); on: always add them; off: never (a scene without lights "
                 "renders black)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
}

void addRadianceCacheFlags(CLI::App& cmd, bool& on, double& cell_m, bool on_by_default) {
  const std::string help =
      "radiance cache: a sparse training pass of full paths records, in 25 cm cells, what the "
      "rough surfaces of the view send on; paths then stop after their first rough bounce and "
      "take the cell's mean instead of bouncing on. Less noise in less time; the cache's own "
      "noise is shared by the frame (its mean within about 0.5 %). " +
      std::string(on_by_default ? "On by default; --no-radiance-cache bounces on" : "Off by default") +
      " (docs/rendering.md)";
  cmd.add_flag(on_by_default ? "--radiance-cache,!--no-radiance-cache" : "--radiance-cache", on,
               help);
  cmd.add_option("--radiance-cell", cell_m,
                 "edge of the radiance cache's cells in metres (default 0.25)")
      ->check(CLI::Range(0.02, 5.0));
}

void addResponseFlags(CLI::App& cmd, ResponseSettings& x) {
  cmd.add_option("--exposure-ev", x.exposure_ev,
                 "exposure compensation of the RGB image in stops (default 0)");
  cmd.add_option("--tone", x.tone,
                 "tone curve before sRGB encoding: none (clip), aces, hable (default none)");
  cmd.add_flag("--sensor-noise", x.sensor_noise,
               "add shot and read noise of a CMOS sensor (Sony IMX250: 10.7 ke- full well, 1.8 e- "
               "read noise, 12-bit ADC) to the RGB image; seeded, deterministic");
}

void addLensFlags(CLI::App& cmd, LensSettings& x) {
  cmd.add_option("--lens", x.lens,
                 "pinhole, thin_lens (depth of field: --aperture, --focus), fisheye (equidistant "
                 "r = f theta, square image, default 600x600 and 180 deg: --fisheye-fov), "
                 "panorama (equirectangular 360 x 180 deg, 2:1 image, default 5000x2500); "
                 "default pinhole, or thin_lens when --aperture > 0");
  cmd.add_option("--aperture", x.aperture_m,
                 "thin-lens aperture radius in metres: depth of field (default 0)");
  cmd.add_option("--focus", x.focus_m,
                 "thin-lens focus distance (z of the sharp plane) in metres (default 2)")
      ->each([&x](const std::string&) { x.focus_set = true; });
  cmd.add_option("--fisheye-fov", x.fisheye_fov_deg,
                 "fisheye field of view in degrees, in (0, 360] (default 180)")
      ->each([&x](const std::string&) { x.fisheye_fov_set = true; });
  cmd.add_option("--distortion", x.distortion,
                 "lens distortion k1,k2,p1,p2[,k3]: Brown-Conrady radial-tangential coefficients "
                 "in OpenCV's order, as cv::projectPoints applies them (pinhole and thin_lens; "
                 "written to sensor.yaml / camera.json; default none)")
      ->delimiter(',');
}

void addEventFlags(CLI::App& cmd, EventSettings& x) {
  cmd.add_option("--event-width", x.opt.width,
                 "event camera width in pixels (default 240, DAVIS240)");
  cmd.add_option("--event-height", x.opt.height, "event camera height in pixels (default 180)");
  cmd.add_option("--event-spp", x.opt.spp,
                 "path-traced samples per pixel of each event-camera sample (default 16)");
  cmd.add_option("--contrast", x.contrast,
                 "ON and OFF contrast thresholds in log intensity (default 0.2, as v2e)");
  cmd.add_option("--contrast-pos", x.contrast_pos, "ON threshold alone (default: --contrast)");
  cmd.add_option("--contrast-neg", x.contrast_neg, "OFF threshold alone (default: --contrast)");
  cmd.add_option("--threshold-spread", x.opt.sim.threshold_spread,
                 "std of each pixel's fixed threshold around the nominal one (v2e's mismatch, "
                 "0.03 there; default 0)");
  cmd.add_option("--leak-rate-hz", x.opt.sim.leak_rate_hz,
                 "leak events per pixel and second (v2e 0.01-0.2; default 0)");
  cmd.add_option("--contrast-sigma", x.opt.sim.sigma_c,
                 "threshold noise per pixel and interval, std (default 0.021, ESIM)");
  cmd.add_option("--refractory-ms", x.refractory_ms,
                 "refractory period per pixel in ms (default 0, ESIM; v2e uses 0.5)");
  cmd.add_option("--shot-noise-rate-hz", x.opt.sim.shot_noise_rate_hz,
                 "shot-noise events per pixel and second (default 0 = none; v2e 0.001)");
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

void addMotionFlags(CLI::App& cmd, MotionSettings& x) {
  cmd.add_option("--v-mult", x.v_mult,
                 "speed multiplier of a random trajectory (base 0.3 m/s RMS; default: drawn from "
                 "U(0.5, 5) per trajectory, as the paper)");
  cmd.add_option("--w-mult", x.w_mult,
                 "turn-rate multiplier of a random trajectory (base 20 deg/s; default: drawn from "
                 "U(0.5, 3) per trajectory)");
  cmd.add_option("--clearance", x.clearance,
                 "least distance from the camera to any geometry, m (default 0.25)");
  cmd.add_option("--min-height", x.min_height, "lowest camera height, m (default 1)");
  cmd.add_option("--max-height", x.max_height, "highest camera height, m (default 2)");
  cmd.add_option("--style", x.style,
                 "none (default: the smooth base motion) or learned: hand-held jitter from the "
                 "WaveNet style model trained on real camera paths (docs/style.md)");
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
