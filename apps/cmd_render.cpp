// interiornet render: one image of a scene from a camera.json, for comparisons with other
// renderers (../shared/bench) and for looking at a scene.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "common.h"
#include "core/error.h"
#include "core/image_io.h"
#include "dataset/image_encode.h"
#include "render/lens.h"
#include "render/renderer.h"
#include "trajectory/builtin_trajectory.h"

namespace inet::app {
namespace {

struct RenderArgs {
  SceneSource scene;
  std::string camera;
  int spp = 16;
  int max_bounces = 8;
  uint64_t seed = 0;
  int threads = 0;
  std::string pass = "rgb";
  LensSettings lens;
  bool denoise = false;
  bool light_cache = false;
  bool sun_photons = false;
  bool lamp_photons = false;
  bool radiance_cache = false;
  double radiance_cell_m = 0.25;
  ResponseSettings response;
  std::string camera_end;
  double exposure_ms = 0.0;
  double time_s = 0.0;
  double readout_ms = 0.0;
  std::string out;
};

/// The lens of the command line around the camera.json intrinsics. Fisheye and panorama use
/// their own image sizes (the paper's 600x600 fisheye, 5000x2500 panorama) unless the camera
/// file is square (fisheye) or 2:1 (panorama).
LensModel makeLens(const RenderArgs& a, CameraIntrinsics K) {
  const LensType type = a.lens.type();
  if (type == LensType::Fisheye && K.width != K.height) K.width = K.height = 600;
  if (type == LensType::Panorama && K.width != 2 * K.height) {
    K.width = 5000;
    K.height = 2500;
  }
  return a.lens.make(K, "render");
}

void runRender(const RenderArgs& a) {
  std::filesystem::path out(a.out);
  std::string ext = out.extension().string();
  if (ext != ".png" && ext != ".exr")
    throw InputError(a.out, "--out", "must end in .png (sRGB 8-bit) or .exr (linear float)");
  if (a.spp < 1) throw InputError("", "--spp", "must be >= 1");
  if (a.max_bounces < 0) throw InputError("", "--max-bounces", "must be >= 0");
  PassMask pass = parsePassList(a.pass, "render");
  if (__builtin_popcount(pass) != 1) throw InputError("", "--pass", "name exactly one pass");
  CameraFile cam;
  if (!a.camera.empty()) {
    cam = loadCameraJson(a.camera);
  } else if (a.scene.isBuiltinRoom()) {
    cam.T_world_camera = builtinTrajectory(1, 25.0).poses[0].T_world_camera;
  } else {
    throw InputError("", "--camera", "required with --scene/--layout");
  }
  LensModel lens = makeLens(a, cam.intrinsics);
  // fisheye and panorama have no z-depth: their depth is the ray distance (docs/cameras.md 4)
  pass = lensDepthPasses(pass, groundTruthDepthKind(lens.type) == DepthKind::ZDepth);
  const PassInfo& info = passInfo(static_cast<Pass>(pass));
  if (info.source == PassSource::SensorStage)
    throw InputError("", "--pass",
                     fmt::format("'{}' is made by the sensor stage: use 'generate'", info.name));
  if (info.pixel != PixelType::Float)
    throw InputError("", "--pass", "label/instance images: use 'generate' (integer PNGs)");
  a.response.validate();
  ThreadLimit limit(a.threads);
  Scene scene = a.scene.load();
  Renderer renderer(scene);
  RenderOptions opt;
  opt.spp = a.spp;
  opt.max_bounces = a.max_bounces;
  opt.seed = a.seed;
  opt.passes = pass;
  opt.denoise = a.denoise;
  opt.light_cache = a.light_cache;
  opt.sun_photons = a.sun_photons;
  opt.lamp_photons = a.lamp_photons;
  opt.radiance_cache = a.radiance_cache;
  opt.radiance_cache_config.cell_m = static_cast<float>(a.radiance_cell_m);
  Frame f;
  CameraExposure exposure = CameraExposure::fixed(cam.T_world_camera);
  if (!a.camera_end.empty()) {
    if (!(a.exposure_ms > 0 || a.readout_ms > 0))
      throw InputError("", "--camera-end", "needs --exposure-ms and/or --readout-ms > 0");
    exposure.T_world_camera_close = loadCameraJson(a.camera_end).T_world_camera;
  }
  if (a.exposure_ms < 0 || a.readout_ms < 0)
    throw InputError("", "--exposure-ms", "exposure and readout times must be >= 0");
  exposure.shutter.exposure_ns = static_cast<TimeNs>(a.exposure_ms * 1e6);
  exposure.shutter.readout_ns = static_cast<TimeNs>(a.readout_ms * 1e6);
  if (!std::isfinite(a.time_s) || std::fabs(a.time_s) > 1e6)
    throw InputError("", "--time", "must be a finite number of seconds (|t| <= 1e6)");
  exposure.scene_time_open_ns = static_cast<TimeNs>(std::llround(a.time_s * 1e9));
  renderer.render(lens, exposure, opt, 0, f);
  const ImageF& img = floatImage(f, info.pass);
  if (ext == ".exr") {
    std::vector<std::string> names =
        img.channels == 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Z"};
    writeExr(out, img, names);
  } else if (img.channels == 3 && !has(pass, Pass::Normal)) {
    writePng(out, encodeSrgb8(has(pass, Pass::Rgb) ? a.response.apply(img, a.seed, 0) : img));
  } else if (has(pass, Pass::Normal)) {
    writePng(out, encodeNormal16(img));
  } else {
    writePng(out, encodeDepth16(img, 1000.0));
  }
  fmt::print("wrote {} ({}x{}, {} spp)\n", a.out, img.width, img.height, a.spp);
}

}  // namespace

void registerRender(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render one image of a scene from a camera.json");
  auto a = std::make_shared<RenderArgs>();
  addSceneFlags(*cmd, a->scene);
  cmd->add_option("--camera", a->camera,
                  "camera.json (width, height, fx, fy, cx, cy with pixel centres at +0.5, and "
                  "position/look_at/up or cam_to_world); default: the built-in room's first pose");
  cmd->add_option("--spp", a->spp, "samples per pixel (default 16)");
  cmd->add_option("--max-bounces", a->max_bounces,
                  "maximum scattering events per path (default 8)");
  cmd->add_option("--seed", a->seed, "random seed (default 0)");
  cmd->add_option("--threads", a->threads, "worker threads, 0 = all cores (default 0)");
  cmd->add_option("--pass,--passes", a->pass,
                  "which image: rgb, albedo, normal, depth, ray_depth (default rgb)");
  addLensFlags(*cmd, a->lens);
  addResponseFlags(*cmd, a->response);
  cmd->add_flag("--denoise", a->denoise,
                "edge-aware a-trous denoising of the RGB image guided by albedo, normals and depth "
                "(docs/denoise.md); trades a little bias for much less noise; off by default");
  cmd->add_flag("--light-cache", a->light_cache,
                "visibility-aware light picks (a sparse training pass learns what share of each "
                "light's shadow rays gets through, region by region; unbiased; docs/rendering.md)");
  cmd->add_flag("--sun-photons", a->sun_photons,
                "sunlight through windows by way of the surfaces it lands on: photons from the "
                "sun through the panes, each path vertex connected to one (unbiased; "
                "docs/rendering.md)");
  cmd->add_flag("--lamp-photons", a->lamp_photons,
                "lamp light by way of the surfaces near a lamp it lands on: photons from every "
                "point and spot light, those within half a metre kept, each path vertex "
                "connected to one (unbiased; docs/rendering.md)");
  addRadianceCacheFlags(*cmd, a->radiance_cache, a->radiance_cell_m, false);
  cmd->add_option("--camera-end", a->camera_end,
                  "camera.json of the pose when the exposure ends (motion blur); the pose of "
                  "--camera is where it starts");
  cmd->add_option("--exposure-ms", a->exposure_ms, "exposure time of each row in ms (default 0)");
  cmd->add_option("--time", a->time_s,
                  "scene time in seconds when the exposure opens: where moving objects (layout "
                  "'motion') are (default 0)");
  cmd->add_option(
      "--readout-ms", a->readout_ms,
      "rolling shutter: time from the first to the last row's start in ms (default 0 = global)");
  cmd->add_option("--out", a->out, "output image: .exr (linear float) or .png (sRGB 8-bit)")
      ->required();
  cmd->callback([a] { runRender(*a); });
}

}  // namespace inet::app
