// interiornet bench: performance figures of this build on this machine, as JSON or text.
// Uses ../shared/bench (room.obj + camera.json) when present, else the built-in default room.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/error.h"
#include "render/renderer.h"
#include "scene/assimp_importer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct BenchArgs {
  std::string bench_dir = "../shared/bench";
  int gt_frames = 100;
  int spp = 4;
  int threads = 0;
  bool json = false;
};

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double peakRssMb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux reports KiB
}

void runBench(const BenchArgs& a) {
  if (a.gt_frames < 1) throw InputError("", "--gt-frames", "must be >= 1");
  if (a.spp < 1) throw InputError("", "--spp", "must be >= 1");
  ThreadLimit limit(a.threads);
  nlohmann::json out;
  fs::path dir(a.bench_dir);
  Scene scene;
  CameraFile cam;
  auto t0 = Clock::now();
  if (fs::exists(dir / "room.obj") && fs::exists(dir / "camera.json")) {
    scene = importMeshScene((dir / "room.obj").string(), ImportOptions{});
    cam = loadCameraJson((dir / "camera.json").string());
    out["scene"] = (dir / "room.obj").string();
  } else {
    scene = makeDefaultScene();
    cam.T_world_camera = builtinTrajectory(1, 25.0).poses[0].T_world_camera;
    out["scene"] = "built-in default room (" + a.bench_dir + " not found)";
  }
  auto t1 = Clock::now();
  Renderer renderer(scene);
  auto t2 = Clock::now();
  const CameraIntrinsics& K = cam.intrinsics;

  Frame frame;
  renderer.renderGroundTruth(K, cam.T_world_camera, kGroundTruthPasses, frame);  // warm-up
  auto t3 = Clock::now();
  for (int i = 0; i < a.gt_frames; ++i)
    renderer.renderGroundTruth(K, cam.T_world_camera, kGroundTruthPasses, frame);
  auto t4 = Clock::now();

  RenderOptions opt;
  opt.spp = a.spp;
  opt.passes = bit(Pass::Rgb);
  RenderStats stats;
  renderer.setStats(&stats);
  renderer.render(K, cam.T_world_camera, opt, 0, frame);
  auto t5 = Clock::now();
  renderer.setStats(nullptr);

  double gt_s = seconds(t3, t4), pt_s = seconds(t4, t5);
  out["width"] = K.width;
  out["height"] = K.height;
  out["threads"] = limit.threads();
  out["triangles"] = scene.triangleCount();
  out["scene_load_ms"] = seconds(t0, t1) * 1e3;
  out["scene_build_ms"] = seconds(t1, t2) * 1e3;
  out["gt_frames"] = a.gt_frames;
  out["gt_fps"] = a.gt_frames / gt_s;
  out["gt_passes"] = "depth, ray_depth, normal, label, instance, albedo";
  out["pt_spp"] = a.spp;
  out["pt_seconds"] = pt_s;
  out["pt_samples_per_s"] = static_cast<double>(K.width) * K.height * a.spp / pt_s;
  out["pt_rays_per_s"] = static_cast<double>(stats.rays.load()) / pt_s;
  out["pt_rays_per_sample"] = static_cast<double>(stats.rays.load()) / stats.samples.load();
  out["peak_rss_mb"] = peakRssMb();
  out["version"] = version();
  if (a.json) {
    std::printf("%s\n", out.dump(2).c_str());
  } else {
    fmt::print("scene            {}\n", out["scene"].get<std::string>());
    fmt::print("scene load/build {:.1f} ms / {:.1f} ms ({} triangles)\n", seconds(t0, t1) * 1e3,
               seconds(t1, t2) * 1e3, scene.triangleCount());
    fmt::print("ground truth     {:.1f} frames/s at {}x{} (6 passes, {} threads)\n",
               a.gt_frames / gt_s, K.width, K.height, limit.threads());
    fmt::print("path tracing     {:.3f} Msamples/s, {:.2f} Mrays/s ({} spp in {:.2f} s)\n",
               K.width * K.height * a.spp / pt_s / 1e6, stats.rays.load() / pt_s / 1e6, a.spp,
               pt_s);
    fmt::print("peak memory      {:.0f} MB\n", peakRssMb());
  }
}

}  // namespace

void registerBench(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("bench", "Measure scene build, ground-truth and path-tracing speed");
  auto a = std::make_shared<BenchArgs>();
  cmd->add_option("--bench-dir", a->bench_dir,
                  "folder with room.obj and camera.json (default ../shared/bench)");
  cmd->add_option("--gt-frames", a->gt_frames, "ground-truth frames to time (default 100)");
  cmd->add_option("--spp", a->spp, "samples per pixel of the timed path-traced frame (default 4)");
  cmd->add_option("--threads", a->threads, "worker threads, 0 = all cores (default 0)");
  cmd->add_flag(
      "--json", a->json,
      "print one JSON object (gt_fps, pt_samples_per_s, scene_build_ms, peak_rss_mb, ...)");
  cmd->callback([a] { runBench(*a); });
}

}  // namespace inet::app
