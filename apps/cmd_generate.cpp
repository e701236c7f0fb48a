// interiornet generate: layout -> trajectory -> render -> dataset writers, one sequence folder.
// Everything is validated before the first ray; frames stream to disk one at a time (memory
// stays flat); files are written atomically, so a killed run leaves only whole files and a rerun
// of the same command skips finished frames and ends with the same bytes.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/error.h"
#include "core/progress.h"
#include "dataset/sequence_writer.h"
#include "render/lens.h"
#include "render/renderer.h"
#include "render/shutter.h"
#include "trajectory/builtin_trajectory.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void onSignal(int) {
  g_stop = 1;
}

struct GenerateArgs {
  SceneArgs scene;
  std::string trajectory;
  int frames = 25;
  bool frames_set = false;
  double fps = 25.0;
  int spp = 16;
  int max_bounces = 8;
  uint64_t seed = 0;
  int threads = 0;
  std::string passes = "all";
  std::string formats = "asl,tum";
  std::string sequence = "seq_000";
  std::string out = "out";
  bool progress = true;
  bool denoise = false;
  double exposure_ms = 0.0;
  double readout_ms = 0.0;
  double aperture = 0.0;
  double focus = 2.0;
  ResponseArgs response;
  CameraIntrinsics K;
  bool cx_set = false, cy_set = false;
};

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

Trajectory loadTrajectory(const GenerateArgs& a) {
  if (a.trajectory.empty()) {
    if (!a.scene.isDefault())
      throw InputError(
          a.scene.path, "--trajectory",
          "required with --layout (the built-in camera path only fits the built-in room)");
    return builtinTrajectory(a.frames, a.fps);
  }
  Trajectory traj = readTumTrajectory(a.trajectory);
  if (a.frames_set) {
    if (static_cast<size_t>(a.frames) > traj.size())
      throw InputError(
          a.trajectory, "--frames",
          fmt::format("asks for {} frames but the trajectory has {} poses", a.frames, traj.size()));
    traj.poses.resize(a.frames);
  }
  return traj;
}

void validateArgs(const GenerateArgs& a) {
  if (a.frames < 1) throw InputError("", "--frames", "must be >= 1");
  if (!(a.fps > 0 && a.fps <= 10000)) throw InputError("", "--fps", "must be in (0, 10000]");
  if (a.spp < 1 || a.spp > 1 << 20) throw InputError("", "--spp", "must be in 1..1048576");
  if (a.max_bounces < 0 || a.max_bounces > 1000)
    throw InputError("", "--max-bounces", "must be in 0..1000");
  if (!(a.exposure_ms >= 0 && a.exposure_ms <= 10000))
    throw InputError("", "--exposure-ms", "must be in 0..10000");
  if (!(a.readout_ms >= 0 && a.readout_ms <= 10000))
    throw InputError("", "--readout-ms", "must be in 0..10000");
  if (!(a.aperture >= 0 && a.aperture < 1))
    throw InputError("", "--aperture", "must be in [0, 1) metres");
  if (!(a.focus > 0)) throw InputError("", "--focus", "must be > 0 metres");
  if (a.sequence.empty() || a.sequence.find('/') != std::string::npos || a.sequence == "." ||
      a.sequence == "..")
    throw InputError("", "--sequence", "must be a plain folder name");
}

/// The exposure of frame k: centred on the frame's timestamp, poses interpolated along the
/// trajectory (held at its ends). A zero shutter gives a static camera.
CameraExposure exposureAt(const Trajectory& traj, size_t k, const Shutter& shutter) {
  const TimeNs t = traj.poses[k].t_ns, half = (shutter.exposure_ns + shutter.readout_ns) / 2;
  CameraExposure ex = CameraExposure::fixed(traj.poses[k].T_world_camera);
  ex.shutter = shutter;
  if (half > 0) {
    const TimeNs open = t - half, close = open + shutter.exposure_ns + shutter.readout_ns;
    interpolatePoseAt(traj.poses, open, ex.T_world_camera_open);
    interpolatePoseAt(traj.poses, close, ex.T_world_camera_close);
    // the trajectory's own samples inside the window (the frame's pose among them), so the
    // camera follows the path rather than the chord and the mid-exposure pose is exact; the
    // poses are sorted, so walk out from frame k instead of scanning the whole trajectory
    size_t first = k;
    while (first > 0 && traj.poses[first - 1].t_ns > open) --first;
    for (size_t i = first; i < traj.size() && traj.poses[i].t_ns < close; ++i)
      ex.knots.emplace_back(traj.poses[i].t_ns - open, traj.poses[i].T_world_camera);
  }
  return ex;
}

nlohmann::json provenance(const GenerateArgs& a, const Scene& scene, const RenderOptions& opt) {
  // Only what determines the output bytes: no thread count, no output path, no clock time.
  nlohmann::json m;
  m["tool"] = {{"name", "interiornet"}, {"version", version()}};
  m["layout"] = {{"name", scene.name},
                 {"source", a.scene.isDefault() ? std::string("built-in default room")
                                                : fs::path(a.scene.path).filename().string()}};
  m["trajectory"] = a.trajectory.empty() ? std::string("built-in orbit of the default room")
                                         : fs::path(a.trajectory).filename().string();
  m["render"] = {{"integrator", opt.integrator},
                 {"spp", opt.spp},
                 {"max_bounces", opt.max_bounces},
                 {"pixel_filter", "box, 1 pixel"},
                 {"rgb", "linear radiance -> clamp -> sRGB 8-bit"}};
  m["seed"] = opt.seed;
  m["shutter"] = {{"exposure_ms", a.exposure_ms},
                  {"readout_ms", a.readout_ms},
                  {"timestamp",
                   "the middle of the exposure window [t - (readout + exposure)/2, "
                   "t + (readout + exposure)/2]; row y of the ground truth is traced "
                   "at the middle of that row's own exposure"}};
  m["lens"] = {{"type", a.aperture > 0 ? "thin_lens" : "pinhole"},
               {"aperture_radius_m", a.aperture},
               {"focus_distance_m", a.focus}};
  m["camera_response"] = a.response.describe();
  m["fps"] = a.fps;
  return m;
}

void runGenerate(const GenerateArgs& a) {
  validateArgs(a);
  a.response.validate();
  ThreadLimit limit(a.threads);
  PassMask passes = parsePassList(a.passes, "generate");
  std::vector<std::string> formats = splitList(a.formats);
  // Load and check every input before anything is written.
  Scene scene = a.scene.load();
  Trajectory traj = loadTrajectory(a);
  CameraIntrinsics K = a.K;
  if (!a.cx_set) K.cx = K.width / 2.0;
  if (!a.cy_set) K.cy = K.height / 2.0;
  K.validate("generate");
  RenderOptions opt;
  opt.spp = a.spp;
  opt.max_bounces = a.max_bounces;
  opt.seed = a.seed;
  opt.passes = passes;
  opt.denoise = a.denoise;

  fs::path dir = fs::path(a.out) / scene.name / a.sequence;
  SequenceSpec spec;
  spec.dir = dir;
  spec.intrinsics = K;
  spec.passes = passes;
  spec.meta = provenance(a, scene, opt);
  SequenceWriter writer(spec, traj, formats);

  Renderer renderer(scene, opt.integrator);
  LensModel lens =
      a.aperture > 0 ? LensModel::thinLens(K, a.aperture, a.focus) : LensModel::pinhole(K);
  lens.validate("generate");
  Shutter shutter;
  shutter.exposure_ns = static_cast<TimeNs>(std::llround(a.exposure_ms * 1e6));
  shutter.readout_ns = static_cast<TimeNs>(std::llround(a.readout_ms * 1e6));
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  // which frames a killed run already finished: checked once (it stats every file of a frame)
  std::vector<char> complete(traj.size());
  size_t skipped = 0;
  for (size_t k = 0; k < traj.size(); ++k) skipped += complete[k] = writer.frameComplete(k);
  if (skipped > 0)
    std::fprintf(stderr, "resuming: %zu of %zu frames already complete\n", skipped, traj.size());

  ProgressBar bar(static_cast<int64_t>(traj.size()), "frames", a.progress);
  Frame frame;
  size_t done = 0;
  for (size_t k = 0; k < traj.size(); ++k) {
    if (g_stop) {
      bar.finish();
      std::fprintf(stderr,
                   "interrupted after %zu of %zu frames; rerun the same command to resume\n", done,
                   traj.size());
      throw CLI::RuntimeError(130);
    }
    if (!complete[k]) {
      renderer.render(lens, exposureAt(traj, k, shutter), opt, static_cast<uint32_t>(k), frame);
      if (!a.response.identity() && has(passes, Pass::Rgb))
        frame.rgb = a.response.apply(frame.rgb, opt.seed, static_cast<uint32_t>(k));
      writer.writeFrame(k, frame);
    }
    bar.update(static_cast<int64_t>(++done));
  }
  bar.finish();
  writer.finish();
  std::printf("wrote %zu frames to %s\n", traj.size(), dir.string().c_str());
}

}  // namespace

void registerGenerate(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "generate",
      "Render a sequence: RGB + ground truth (depth, ray depth, normals, NYU40 labels, instances, "
      "albedo) along a camera trajectory, written as ASL/EuRoC and TUM RGB-D folders");
  auto a = std::make_shared<GenerateArgs>();
  a->scene.addTo(*cmd);
  cmd->add_option("--trajectory", a->trajectory,
                  "TUM trajectory file 'timestamp tx ty tz qx qy qz qw' (T_world_camera, OpenCV "
                  "camera axes); default: the built-in orbit of the built-in room");
  cmd->add_option("--frames", a->frames,
                  "number of frames (default 25; with --trajectory: the first N poses)")
      ->each([a](const std::string&) { a->frames_set = true; });
  cmd->add_option("--fps", a->fps, "frame rate of the built-in trajectory (default 25)");
  cmd->add_option("--spp", a->spp, "path-traced samples per pixel (default 16)");
  cmd->add_option("--max-bounces", a->max_bounces,
                  "maximum scattering events per path (default 8)");
  cmd->add_option("--seed", a->seed, "random seed; same seed, same bytes (default 0)");
  cmd->add_option("--threads", a->threads,
                  "worker threads, 0 = all cores (default 0); never changes the output");
  cmd->add_option("--passes", a->passes,
                  "comma list of rgb, depth, ray_depth, normal, label, instance, albedo, shading, "
                  "or all (default all)");
  cmd->add_option("--format", a->formats,
                  "comma list of output layouts: asl, tum (default asl,tum)");
  cmd->add_option("--width", a->K.width, "image width in pixels (default 640)");
  cmd->add_option("--height", a->K.height, "image height in pixels (default 480)");
  cmd->add_option("--fx", a->K.fx, "focal length in pixels (default 600)");
  cmd->add_option("--fy", a->K.fy, "focal length in pixels (default 600)");
  cmd->add_option("--cx", a->K.cx,
                  "principal point with pixel (i,j) centred at (i+0.5, j+0.5) (default width/2; "
                  "files for SLAM tools state cx-0.5, the OpenCV convention)")
      ->each([a](const std::string&) { a->cx_set = true; });
  cmd->add_option("--cy", a->K.cy, "principal point, as --cx (default height/2)")
      ->each([a](const std::string&) { a->cy_set = true; });
  cmd->add_option("--sequence", a->sequence, "sequence folder name (default seq_000)");
  cmd->add_option("--out", a->out,
                  "output root; frames go to OUT/<layout>/<sequence>/ (default out)");
  a->response.addTo(*cmd);
  cmd->add_option("--exposure-ms", a->exposure_ms,
                  "exposure time per row in ms: motion blur along the trajectory (default 0)");
  cmd->add_option("--readout-ms", a->readout_ms,
                  "rolling shutter readout, first to last row, in ms (default 0 = global shutter); "
                  "ground truth follows each row's own pose");
  cmd->add_option("--aperture", a->aperture,
                  "thin-lens aperture radius in metres: depth of field (default 0)");
  cmd->add_option("--focus", a->focus, "thin-lens focus distance in metres (default 2)");
  cmd->add_flag("--denoise", a->denoise,
                "denoise the RGB pass (edge-aware, guided by albedo/normal/depth; ground truth is "
                "never filtered); off by default");
  cmd->add_flag("--no-progress{false}", a->progress, "do not draw the progress bar");
  cmd->callback([a] { runGenerate(*a); });
}

}  // namespace inet::app
