// The sequence pipeline (pipeline/sequence_job.h): layout -> trajectory -> render -> sensors ->
// dataset writers, one sequence folder per configuration.
#include "pipeline/sequence_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "assets/catalog_library.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/plot.h"
#include "core/progress.h"
#include "core/stop.h"
#include "core/text.h"
#include "dataset/asl_writer.h"
#include "dataset/boxes_json.h"
#include "dataset/sequence_writer.h"
#include "render/lens.h"
#include "render/neural_denoise.h"
#include "render/renderer.h"
#include "render/shutter.h"
#include "render/tonemap.h"
#include "sensors/imu.h"
#include "sensors/imu_io.h"
#include "sensors/temporal_reuse.h"
#include "trajectory/builtin_trajectory.h"
#include "trajectory/formats.h"
#include "trajectory/free_space.h"
#include "trajectory/place_path.h"
#include "trajectory/random_trajectory.h"
#include "variation/lighting.h"
#include "variation/rearrange.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

/// The camera path of a sequence: one pose per frame, and the finer path that motion blur and
/// rolling shutter interpolate (the frames themselves for a file).
struct CameraPath {
  Trajectory frames;
  Trajectory path;
  std::string description;    ///< for meta.json
  bool leaves_scene = false;  ///< a file's path with cameras outside the scene or in its geometry
};

bool isMotionType(const std::string& s) {
  return s == "two-body" || s == "hand-held" || s == "look-forward";
}

/// A camera path from a file is used as it is, in the scene's world frame (Z up, metres). A
/// path whose cameras sit outside the building or inside its geometry renders the outside of
/// walls or the inside of a slab, which looks like a lighting or import fault: a motion-capture
/// path (TUM, EuRoC) has the origin of its own room. Said once, with both extents, before
/// anything is rendered; not an error (a path from outside may be meant).
bool warnIfOutsideScene(const Trajectory& frames, const FreeSpace& space, const Scene& scene,
                        const SequenceJob& a) {
  if (frames.poses.empty()) return false;
  size_t outside = 0, in_geometry = 0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const TimedPose& p : frames.poses) {
    const Vec3 c = p.T_world_camera.t;
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
    // the inside of a solid (a thick wall, a closed cabinet) is not indoors either: only the
    // big free regions are (free_space.h)
    if (!space.isIndoors(c))
      ++outside;
    else if (space.exactDistance(c) < 0.02)
      ++in_geometry;
  }
  if (outside + in_geometry == 0) return false;
  const auto [slo, shi] = scene.bounds();
  std::fprintf(stderr,
               "warning: %s: %zu of %zu camera positions are outside the scene's indoor space "
               "(outside its walls or inside a solid) and %zu within 2 cm of its geometry: the "
               "path spans x [%.2f, %.2f] y [%.2f, "
               "%.2f] z [%.2f, %.2f] m, the scene x [%.2f, %.2f] y [%.2f, %.2f] z [%.2f, %.2f] "
               "m (a file's poses are used as they are, in the scene's frame: Z up, metres; "
               "--place-trajectory moves the path into the scene)\n",
               a.trajectory.c_str(), outside, frames.poses.size(), in_geometry, lo.x(), hi.x(),
               lo.y(), hi.y(), lo.z(), hi.z(), slo.x(), shi.x(), slo.y(), shi.y(), slo.z(),
               shi.z());
  return true;
}

CameraPath loadTrajectory(const SequenceJob& a, const Scene& scene) {
  CameraPath out;
  if (a.trajectory.empty() && a.scene.isBuiltinRoom()) {
    out.frames = builtinTrajectory(a.frames, a.fps);
    out.path = out.frames;
    out.description = "built-in orbit of the default room";
    return out;
  }
  if (a.trajectory.empty() || isMotionType(a.trajectory)) {
    const MotionType type =
        parseMotionType(a.trajectory.empty() ? "two-body" : a.trajectory, "--trajectory");
    RandomTrajectoryOptions opt = a.motion.options(type, a.seed, a.frames, a.fps);
    FreeSpace space(scene, {}, a.scene.path);
    RandomTrajectory traj;
    try {
      traj = generateRandomTrajectory(space, opt, a.scene.path);
    } catch (const InputError& e) {
      throw InputError(e.file(), e.field(),
                       e.problem() + "; give a camera path: --trajectory FILE");
    }
    out.frames = std::move(traj.frames);
    out.path = std::move(traj.dense);
    out.description = fmt::format(
        "{} random trajectory, seed {}, v_mult {:.4f}, w_mult {:.4f}, "
        "clearance {} m, style {}",
        motionTypeName(type), a.seed, traj.v_mult, traj.w_mult, opt.clearance, a.motion.style);
    return out;
  }
  out.frames = readTrajectoryFile(a.trajectory);
  if (a.frames_set) {
    if (static_cast<size_t>(a.frames) > out.frames.size())
      throw InputError(a.trajectory, "--frames",
                       fmt::format("asks for {} frames but the trajectory has {} poses", a.frames,
                                   out.frames.size()));
    out.frames.poses.resize(a.frames);
  }
  out.description = fs::path(a.trajectory).filename().string();
  const FreeSpace space(scene, {}, a.scene.path);
  if (a.place_trajectory) {
    const PathPlacement placed = placePath(out.frames, space, {}, a.trajectory);
    out.frames = transformed(out.frames, placed.T_scene_file);
    const Vec3& t = placed.T_scene_file.t;
    const std::string what = fmt::format(
        "turned {:.1f} deg about z and moved by ({:.3f}, {:.3f}, {:.3f}) m: {:.0f} % of its poses "
        "at least 0.1 m from the geometry (as given: {:.0f} %)",
        placed.yaw_deg, t.x(), t.y(), t.z(), 100.0 * placed.free_after, 100.0 * placed.free_before);
    if (!placed.moved) {
      std::fprintf(stderr,
                   "%s: left where it is (%.0f %% of its poses at least 0.1 m from the "
                   "geometry; no turn or shift does better)\n",
                   a.trajectory.c_str(), 100.0 * placed.free_before);
    } else {
      std::fprintf(stderr, "%s: placed in the scene: %s\n", a.trajectory.c_str(), what.c_str());
      out.description += ", placed: " + what;
    }
  }
  out.leaves_scene = warnIfOutsideScene(out.frames, space, scene, a);
  out.path = out.frames;
  return out;
}

/// The temporal reuse window in frames: --temporal, else 16, or 1 (off) with motion blur or a
/// rolling shutter, which temporal reuse cannot follow.
int temporalWindow(const SequenceJob& a) {
  if (a.temporal_set) return a.temporal;
  return a.exposure_ms > 0 || a.readout_ms > 0 ? 1 : a.temporal;
}

/// Temporal reuse's options from the job's flags.
TemporalReuseOptions reuseOptions(const SequenceJob& a) {
  TemporalReuseOptions t;
  t.window = temporalWindow(a);
  t.boost = a.history_boost;
  t.boost_edges = a.history_boost_edges;
  t.smooth = a.denoise ? a.temporal_smooth : 1;  // it smooths what the denoiser leaves
  t.firefly_ratio = a.temporal_firefly;
  return t;
}

void validateArgs(const SequenceJob& a) {
  if (a.frames < 1) throw InputError("", "--frames", "must be >= 1");
  if (a.frame_begin >= a.frame_end)
    throw InputError("", "frame range", "the first frame must come before the end");
  if (a.place_trajectory && (a.trajectory.empty() || isMotionType(a.trajectory)))
    throw InputError("", "--place-trajectory", "needs a camera path file: --trajectory FILE");
  if (!(a.fps > 0 && a.fps <= 10000)) throw InputError("", "--fps", "must be in (0, 10000]");
  if (!(a.imu_rate >= 0 && a.imu_rate <= 100000))
    throw InputError("", "--imu", "must be in 0..100000 Hz");
  if (a.spp < 1 || a.spp > 1 << 20) throw InputError("", "--spp", "must be in 1..1048576");
  if (a.max_bounces < 0 || a.max_bounces > 1000)
    throw InputError("", "--max-bounces", "must be in 0..1000");
  if (!(a.exposure_ms >= 0 && a.exposure_ms <= 10000))
    throw InputError("", "--exposure-ms", "must be in 0..10000");
  if (!(a.readout_ms >= 0 && a.readout_ms <= 10000))
    throw InputError("", "--readout-ms", "must be in 0..10000");
  if (a.temporal < 1 || a.temporal > 64)
    throw InputError("", "--temporal", "the window must be in 1..64 frames (1 = off)");
  // --history-boost, --history-boost-edges, --temporal-smooth, --temporal-firefly (even where
  // no denoiser uses them)
  TemporalReuseOptions reuse = reuseOptions(a);
  reuse.smooth = a.temporal_smooth;
  reuse.validate("");
  if (a.temporal_set && a.temporal > 1 && (a.exposure_ms > 0 || a.readout_ms > 0))
    throw InputError("", "--temporal",
                     "needs a global shutter without motion blur (--exposure-ms 0, --readout-ms "
                     "0): a blurred pixel has no single surface point to carry to the next frame");
  if (a.sequence.empty() || a.sequence.find('/') != std::string::npos || a.sequence == "." ||
      a.sequence == "..")
    throw InputError("", "--sequence", "must be a plain folder name");
  if (a.folder == "." || a.folder == ".." || (!a.folder.empty() && a.folder.front() == '/'))
    throw InputError("", "folder", "must be a relative folder below the output root");
}

/// The image size and intrinsics of the lens. Pinhole and thin lens: --width/--height/--fx/...
/// as given. Fisheye (square) and panorama (2:1): the paper's 600x600 and 5000x2500 unless
/// --width and/or --height say otherwise (one given: the other follows from the aspect ratio);
/// their focal length follows from the size, so --fx/--fy/--cx/--cy are refused.
CameraIntrinsics lensIntrinsics(const SequenceJob& a, LensType type) {
  CameraIntrinsics K = a.K;
  if (type == LensType::Pinhole || type == LensType::ThinLens) {
    if (!a.cx_set) K.cx = K.width / 2.0;
    if (!a.cy_set) K.cy = K.height / 2.0;
    return K;
  }
  const std::string name = lensTypeName(type);
  const std::pair<bool, const char*> unused[] = {
      {a.fx_set, "--fx"}, {a.fy_set, "--fy"}, {a.cx_set, "--cx"}, {a.cy_set, "--cy"}};
  for (const auto& [set, flag] : unused)
    if (set)
      throw InputError("", flag,
                       "not used by --lens " + name +
                           ": its intrinsics follow from the image size (--width, --height)" +
                           (type == LensType::Fisheye ? " and --fisheye-fov" : ""));
  const int aspect = type == LensType::Fisheye ? 1 : 2;  // width = aspect * height
  const std::string shape = type == LensType::Fisheye ? "square" : "2:1 (width = 2 x height)";
  if (a.width_set && a.height_set) {
    if (K.width != aspect * K.height)
      throw InputError("", "--height",
                       fmt::format("a {} image is {}: --width {} needs --height {}, not {}", name,
                                   shape, K.width, K.width / aspect, K.height));
  } else if (a.width_set) {
    if (K.width % aspect != 0)
      throw InputError(
          "", "--width",
          fmt::format("a panorama image is 2:1 (width = 2 x height): {} is odd", K.width));
    K.height = K.width / aspect;
  } else if (a.height_set) {
    K.width = aspect * K.height;
  } else {
    K.width = type == LensType::Fisheye ? 600 : 5000;
    K.height = K.width / aspect;
  }
  return K;
}

/// Fisheye and panorama images hold directions at and beyond 90 degrees from the axis, where
/// z-depth is zero or negative: their depth is the ray distance (docs/cameras.md section 4), so
/// the 'depth' pass becomes 'ray_depth' and the depth PNGs hold the ray distance.
PassMask lensPasses(PassMask passes, LensType type) {
  return lensDepthPasses(passes, groundTruthDepthKind(type) == DepthKind::ZDepth);
}

/// The exposure of frame k: centred on the frame's timestamp, poses interpolated along the
/// camera path (held at its ends). A zero shutter gives a static camera.
CameraExposure exposureAt(const CameraPath& cam, size_t k, const Shutter& shutter) {
  const TimedPose& frame = cam.frames.poses[k];
  const TimeNs t = frame.t_ns, half = (shutter.exposure_ns + shutter.readout_ns) / 2;
  // scene time (moving objects) runs from the first frame's timestamp
  CameraExposure ex =
      CameraExposure::fixed(frame.T_world_camera, t - half - cam.frames.poses.front().t_ns);
  ex.shutter = shutter;
  if (half > 0) {
    const TimeNs open = t - half, close = open + shutter.exposure_ns + shutter.readout_ns;
    const auto& path = cam.path.poses;
    interpolatePoseAt(path, open, ex.T_world_camera_open);
    interpolatePoseAt(path, close, ex.T_world_camera_close);
    // the path's own samples inside the window (the frame's pose among them when the path is
    // the frames), so the camera follows the path rather than the chord
    auto first = std::upper_bound(path.begin(), path.end(), open,
                                  [](TimeNs v, const TimedPose& p) { return v < p.t_ns; });
    for (auto it = first; it != path.end() && it->t_ns < close; ++it)
      ex.knots.emplace_back(it->t_ns - open, it->T_world_camera);
  }
  return ex;
}

nlohmann::json provenance(const SequenceJob& a, const Scene& scene, const RenderOptions& opt,
                          const CameraPath& cam) {
  // Only what determines the output bytes: no thread count, no output path, no clock time.
  nlohmann::json m;
  m["tool"] = {{"name", "interiornet"}, {"version", INET_VERSION}};
  m["layout"] = {
      {"name", scene.name},
      {"source", a.scene.isBuiltinRoom() ? std::string("built-in default room")
                 : a.scene.isBuiltinApartment()
                     ? fmt::format("built-in apartment (procedural seed {}, 4 rooms, Sweet Home "
                                   "3D catalog furniture)",
                                   kBuiltinApartmentSeed)
                     : fs::path(a.scene.path).filename().string()}};
  m["trajectory"] = cam.description;
  m["render"] = {{"integrator", opt.integrator},
                 {"spp", opt.spp},
                 {"max_bounces", opt.max_bounces},
                 {"pixel_filter", "box, 1 pixel"},
                 {"rgb", a.hdr ? "linear radiance -> cam0 EXR (float32); -> camera response -> "
                                 "clamp -> sRGB 8-bit PNG"
                               : "linear radiance -> camera response -> clamp -> sRGB 8-bit"}};
  if (opt.light_cache) m["render"]["light_pick"] = "visibility-aware (render/light_cache.h)";
  if (opt.sun_photons)
    m["render"]["sun_photons"] =
        "sunlight through panes connected by way of the surfaces it "
        "lands on (render/path_tracer.cpp, Photons)";
  if (opt.lamp_photons)
    m["render"]["lamp_photons"] =
        "point and spot lights' light connected by way of the surfaces near them it lands on "
        "(render/path_tracer.cpp, Photons)";
  if (opt.radiance_cache)
    m["render"]["radiance_cache"] = {
        {"what", "light past the first rough bounce from a per-frame cache of what rough "
                 "surfaces send on (render/radiance_cache.h)"},
        {"cell_m", opt.radiance_cache_config.cell_m},
        {"train_spp", opt.radiance_cache_config.train_spp},
        {"min_records", opt.radiance_cache_config.min_records}};
  if (!opt.denoise) {
    m["render"]["denoise"] = "off";
  } else if (a.denoiser == "learned") {
    m["render"]["denoise"] = "learned U-Net (render/neural_denoise.h), weights " +
                             fs::path(defaultNeuralDenoiserPath()).filename().string();
  } else {
    m["render"]["denoise"] = opt.denoise_options.describe();
  }
  if (a.save_denoiser_inputs)
    m["render"]["denoiser_inputs"] =
        "denoise_in/<t>.exr: what the learned denoiser reads, per frame (render/neural_denoise.h)";
  if (temporalWindow(a) > 1)
    m["render"]["temporal_reuse"] = reuseOptions(a).describe() + " (sensors/temporal_reuse.h)";
  m["seed"] = opt.seed;
  m["shutter"] = {{"exposure_ms", a.exposure_ms},
                  {"readout_ms", a.readout_ms},
                  {"timestamp",
                   "the middle of the exposure window [t - (readout + exposure)/2, "
                   "t + (readout + exposure)/2]; row y of the ground truth is traced "
                   "at the middle of that row's own exposure"}};
  m["camera_response"] = a.response.describe();
  m["fps"] = a.fps;
  return m;
}

std::string layoutFolder(const SequenceJob& a, const Scene& scene) {
  return a.folder.empty() ? scene.name : a.folder;
}

/// One scene configuration (issue 7): the layout as it is, relit (a random lighting of seed n)
/// or rearranged (physics of seed n). Configurations of one layout share its name, so their
/// sequences sit side by side: <sequence>, <sequence>_lighting_<n>, <sequence>_rearranged_<n>.
struct SceneConfig {
  enum class Kind { Original, Lighting, Rearranged } kind = Kind::Original;
  uint64_t n = 0;
  Scene scene;
  std::string suffix() const {
    if (kind == Kind::Original) return "";
    return fmt::format("_{}_{}", kind == Kind::Lighting ? "lighting" : "rearranged", n);
  }
  std::string describe() const {
    if (kind == Kind::Original) return "original";
    return fmt::format("{}:{}", kind == Kind::Lighting ? "lighting" : "rearranged", n);
  }
};

/// "original,lighting:1,rearranged:2" (no repeats).
std::vector<SceneConfig> parseConfigs(const std::string& list) {
  std::vector<SceneConfig> out;
  for (const std::string& item : splitCommaList(list)) {
    SceneConfig c;
    const size_t colon = item.find(':');
    const std::string kind = item.substr(0, colon);
    if (kind == "original" && colon == std::string::npos) {
      c.kind = SceneConfig::Kind::Original;
    } else if ((kind == "lighting" || kind == "rearranged") && colon != std::string::npos) {
      c.kind = kind == "lighting" ? SceneConfig::Kind::Lighting : SceneConfig::Kind::Rearranged;
      const std::string n = item.substr(colon + 1);
      if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos || n.size() > 9)
        throw InputError("", "--config", "'" + item + "': the number after ':' is a seed 0..");
      c.n = std::stoull(n);
    } else {
      throw InputError("", "--config",
                       "'" + item + "' is not original, lighting:N or rearranged:N");
    }
    for (const SceneConfig& o : out)
      if (o.describe() == c.describe())
        throw InputError("", "--config", "'" + item + "' is listed twice");
    out.push_back(std::move(c));
  }
  if (out.empty()) throw InputError("", "--config", "no configuration given");
  return out;
}

/// The scene of a configuration.
Scene variantOf(const Scene& original, const SceneConfig& c) {
  if (c.kind == SceneConfig::Kind::Original) return original;
  Scene s = original;
  if (c.kind == SceneConfig::Kind::Lighting) {
    RandomLightingOptions o;
    o.seed = c.n;
    applyLightSetup(s, randomLighting(lightSetupOf(original), o), "--config " + c.describe());
    return s;
  }
  RearrangeOptions o;
  o.seed = c.n;
  RearrangeLog log;
  s = rearrange(original, o, &log);
  moveBoundLights(original, s);
  std::fprintf(stderr, "%s: %d of %d movable objects pushed, %d moved\n", c.describe().c_str(),
               log.selected, log.movable, log.moved);
  return s;
}

/// What a job loads before its first frame: the scene, the camera path, every configuration's
/// scene, the IMU and the event camera's spline.
struct Prepared {
  std::string key;
  Scene scene;
  CameraPath cam;
  std::vector<SceneConfig> configs;
  ImuOptions imu;
  std::optional<ImuSequence> imu_seq;
  std::optional<PoseSpline> spline;
};

/// What a job derives from its settings before the first frame, shared by its configurations.
struct JobSetup {
  LensModel lens;
  LensType lens_type = LensType::Pinhole;
  SequencePasses want;
  PassMask passes = 0;  ///< the frame passes written
  RenderOptions opt;
  EventCameraOptions event_opt;
  KinectNoiseOptions depth_noise;
  std::vector<std::string> formats;
};

SequenceJobResult::Sequence renderSequence(const SequenceJob& a, const SceneConfig& c,
                                           const JobSetup& setup, const Prepared& prepared);

/// --contact-sheet: up to 6 frames of cam0 spread over the sequence, at half size, captioned
/// with their time stamps, as one JPEG (.jpg) or PNG.
void writeSequenceSheet(const fs::path& seq, const fs::path& out) {
  std::vector<fs::path> frames;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(seq / "cam0" / "data", ec))
    if (e.path().extension() == ".png") frames.push_back(e.path());
  if (frames.empty()) throw InputError(seq.string(), "--contact-sheet", "no cam0 frames to show");
  std::sort(frames.begin(), frames.end());
  const size_t n = std::min<size_t>(6, frames.size());
  std::vector<SheetTile> tiles;
  for (size_t k = 0; k < n; ++k) {
    const fs::path& f = frames[n == 1 ? 0 : k * (frames.size() - 1) / (n - 1)];
    const ImageU8 full = readPng8(f);
    ImageU8 half(full.width / 2, full.height / 2, 3);
    for (int y = 0; y < half.height; ++y)
      for (int x = 0; x < half.width; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const int c = std::min(ch, full.channels - 1);
          const int sum = full.at(2 * x, 2 * y, c) + full.at(2 * x + 1, 2 * y, c) +
                          full.at(2 * x, 2 * y + 1, c) + full.at(2 * x + 1, 2 * y + 1, c);
          half.at(x, y, ch) = static_cast<uint8_t>((sum + 2) / 4);
        }
    const double t_s = std::stod(f.stem().string()) * 1e-9;  // EuRoC: nanoseconds
    tiles.push_back({std::move(half), fmt::format("t = {:.2f} s", t_s)});
  }
  fs::create_directories(out.parent_path(), ec);
  writeContactSheetPng(out, tiles, n > 3 ? 3 : int(n));
  fmt::print("contact sheet of {} frames: {}\n", n, out.string());
}

/// A scene with no light where the camera looks renders black frames, and a silent black
/// sequence costs a user hours: before anything is written, 5 poses spread over the path are
/// rendered small (80 px wide, 8 spp, the same lens field of view for a pinhole) and their mean
/// linear luminance, at the fixed exposure (--exposure-ev alone), must reach kDarkFloor (sRGB
/// 3/255) unless --allow-dark.
///
/// The same preview meters the sequence's auto exposure (`--exposure auto`, the default), as a
/// camera does before it records: one linear multiplier for the whole sequence (no flicker, and
/// frames stay comparable for photometric SLAM) that puts the log-average luminance of the
/// preview at middle grey (ExposureMeter: sRGB 118/255), in third stops, within +-8 stops.
/// Windows in full daylight then blow out a little, as in a photograph of a room, instead of
/// the room itself clipping at white (42 % of an apartment's pixels at the fixed exposure). The
/// log-average is taken over 2x2 blocks of the preview (32 samples each): the log of a single
/// noisy 8-spp pixel would meter darker than the scene is.
/// A preview a quarter or more clipped at white after the exposure is warned about, with the
/// compensation that fixes it. Returns the multiplier (1 for --exposure fixed).
constexpr double kDarkFloor = 1e-3;

float meterPreview(const SequenceJob& a, const Renderer& renderer, const LensModel& lens,
                   const Trajectory& traj, const RenderOptions& opt, const std::string& where,
                   bool path_leaves_scene) {
  CameraIntrinsics K = lens.K;
  const double s = 80.0 / K.width;
  K = CameraIntrinsics{80,       std::max(2, static_cast<int>(std::lround(K.height * s))),
                       K.fx * s, K.fy * s,
                       K.cx * s, K.cy * s};
  const LensModel preview = lens.type == LensType::Pinhole || lens.type == LensType::ThinLens
                                ? LensModel::pinhole(K)
                                : LensModel::pinhole(CameraIntrinsics::centred(80, 60, 40.0));
  RenderOptions ro = opt;
  ro.spp = 8;
  ro.denoise = false;
  ro.passes = bit(Pass::Rgb);
  CameraResponse fixed;
  fixed.exposure_ev = a.response.exposure_ev;
  double sum = 0.0;
  size_t pixels = 0;
  ExposureMeter meter;
  std::vector<float> peaks;  // brightest channel of each pixel, before any exposure
  Frame f;
  for (int k = 0; k < 5; ++k) {
    const size_t i = (traj.size() - 1) * static_cast<size_t>(k) / 4;
    renderer.render(preview, CameraExposure::fixed(traj.poses[i].T_world_camera), ro,
                    0x40000000u + static_cast<uint32_t>(k), f);
    auto lum = [&](int x, int y) {
      return luminance(Eigen::Vector3f(f.rgb.at(x, y, 0), f.rgb.at(x, y, 1), f.rgb.at(x, y, 2)));
    };
    for (int y = 0; y < f.rgb.height; ++y)
      for (int x = 0; x < f.rgb.width; ++x) {
        sum += lum(x, y);
        peaks.push_back(std::max({f.rgb.at(x, y, 0), f.rgb.at(x, y, 1), f.rgb.at(x, y, 2)}));
        ++pixels;
      }
    meter.add(f.rgb);
  }
  const double mean = fixed.multiplier() * sum / static_cast<double>(std::max<size_t>(pixels, 1));
  if (mean < kDarkFloor && !a.allow_dark)
    throw InputError(
        where, "--allow-dark",
        fmt::format("the colour frames are essentially black (mean brightness {:.1e} "
                    "of white over 5 previewed poses): {}, or pass --allow-dark",
                    mean,
                    path_leaves_scene ? "the camera path leaves the scene (warned above): move "
                                        "the path into it (--place-trajectory)"
                                      : "nothing lights what the camera sees; add lights "
                                        "(--auto-lights on, --lights light.xml), raise "
                                        "--exposure-ev"));
  const float scale = a.exposure == "auto" ? meter.scale() : 1.f;
  // the other way to lose the picture: most of it clipped at white (an open scene in full sun)
  const double m = scale * fixed.multiplier();
  const size_t clipped =
      std::count_if(peaks.begin(), peaks.end(), [m](float v) { return m * v >= 1.0; });
  if (clipped * 4 >= peaks.size()) {
    std::nth_element(peaks.begin(), peaks.begin() + peaks.size() * 9 / 10, peaks.end());
    const double p90 = m * peaks[peaks.size() * 9 / 10];
    std::fprintf(stderr,
                 "warning: %s: %.0f %% of the previewed colour pixels are at white (over-exposed); "
                 "--exposure-ev %.0f would bring 90 %% of them under it\n",
                 where.c_str(), 100.0 * clipped / peaks.size(),
                 a.response.exposure_ev - std::ceil(std::log2(p90 / 0.9)));
  }
  return scale;
}

/// The sequence-level files, once every frame of the sequence is complete (docs/output.md
/// section 8): the formats' indexes, boxes.json, imu0/, then events0/ (the slow one: its own
/// render of the event camera), each handed to the writer, which knows their names.
void writeSequenceFiles(const SequenceJob& a, const JobSetup& setup, const Prepared& prepared,
                        const SceneConfig& c, const Renderer& renderer,
                        const SequenceWriter& writer, const std::vector<InstanceBox>& boxes,
                        const std::vector<std::vector<InstanceVisibility>>& visible) {
  const Trajectory& traj = prepared.cam.frames;
  const std::string dir = writer.spec().dir.string();
  writer.finish();
  if (setup.want.boxes) writer.writeBoxes(c.scene, boxes, visible);
  if (prepared.imu_seq)
    writer.writeImu(*prepared.imu_seq, prepared.imu,
                    "interiornet generate, IMU frame = camera frame");
  stopIfSignalled(fmt::format("after every frame of {} (the events are not written)", dir));
  if (setup.want.events) {
    const PoseSpline& spline = *prepared.spline;
    const TimeNs t0 = std::max(traj.poses.front().t_ns, spline.startNs());
    const TimeNs t1 = std::min(traj.poses.back().t_ns, spline.endNs());
    if (t1 <= t0)
      throw InputError(prepared.cam.description, "--passes",
                       "events need a camera path longer than one spline knot interval");
    if (!writer.eventsComplete()) {
      const EventCameraOptions& o = setup.event_opt;
      const CameraIntrinsics K = eventIntrinsics(setup.lens.K, o.width, o.height);
      const auto events = writer.openEvents(K);
      simulateEvents(*events, renderer, c.scene, K, spline, t0, t1, traj.poses.front().t_ns, o,
                     a.progress, dir);
    }
  }
}

/// One sequence of `generate`: configuration `c`'s scene along the camera path, every sensor.
SequenceJobResult::Sequence renderSequence(const SequenceJob& a, const SceneConfig& c,
                                           const JobSetup& setup, const Prepared& prepared) {
  const LensModel& lens = setup.lens;
  const SequencePasses& want = setup.want;
  const PassMask passes = setup.passes;
  const RenderOptions& opt = setup.opt;
  const EventCameraOptions& event_opt = setup.event_opt;
  const KinectNoiseOptions& depth_noise = setup.depth_noise;
  const std::vector<std::string>& formats = setup.formats;
  const CameraPath& cam = prepared.cam;
  const std::optional<ImuSequence>& imu_seq = prepared.imu_seq;
  const Scene& scene = c.scene;
  const Trajectory& traj = cam.frames;
  fs::path dir = fs::path(a.out) / layoutFolder(a, scene) / (a.sequence + c.suffix());
  SequenceSpec spec;
  spec.dir = dir;
  spec.intrinsics = lens.K;
  spec.lens = lens;
  spec.passes = passes;
  spec.rgb_exr = a.hdr;
  spec.storage = a.storage;
  spec.stereo_baseline_m = a.stereo;
  spec.remove_stale_temporaries = !a.shared_folder;
  spec.imu = imu_seq.has_value();
  spec.boxes = want.boxes;
  spec.events = want.events;
  spec.meta = provenance(a, scene, opt, cam);
  spec.meta["configuration"] = c.describe();
  if (has(passes, Pass::DepthNoisy))
    spec.meta["depth_noise"] = {{"model", "Kinect-like, sensors/depth_noise.h"},
                                {"parameters", depth_noise.toString()}};
  if (want.events) spec.meta["events"] = event_opt.sim.toString();
  Renderer renderer(scene, opt.integrator);
  ResponseSettings response = a.response;
  if (has(passes, Pass::Rgb) && (!a.allow_dark || a.exposure == "auto")) {
    response.exposure_scale =
        meterPreview(a, renderer, lens, traj, opt,
                     a.scene.path.empty() ? "built-in room" : a.scene.path, cam.leaves_scene);
    spec.meta["camera_response"] = response.describe();
    spec.meta["auto_exposure"] =
        a.exposure == "auto" ? fmt::format(
                                   "{:+.2f} EV: log-average luminance of a 5-pose preview to {} "
                                   "(pipeline/sequence_job.cpp meterPreview)",
                                   std::log2(response.exposure_scale), ExposureMeter::kMiddleGrey)
                             : std::string("off (--exposure fixed)");
  }
  SequenceWriter writer(spec, traj, formats);

  const std::vector<InstanceBox> boxes =
      want.boxes ? instanceBoxes(scene) : std::vector<InstanceBox>{};
  std::vector<std::vector<InstanceVisibility>> visible(want.boxes ? traj.size() : 0);
  Shutter shutter;
  shutter.exposure_ns = static_cast<TimeNs>(std::llround(a.exposure_ms * 1e6));
  shutter.readout_ns = static_cast<TimeNs>(std::llround(a.readout_ms * 1e6));

  // which frames a killed run (or another job of the sequence) already finished: checked once
  // (it stats every file of a frame)
  const size_t first = std::min(a.frame_begin, traj.size());
  const size_t last = std::min(a.frame_end, traj.size());
  const bool whole = first == 0 && last == traj.size();
  std::vector<char> complete(traj.size());
  size_t skipped = 0;
  for (size_t k = 0; k < traj.size(); ++k) {
    complete[k] = writer.frameComplete(k);
    if (k >= first && k < last) skipped += complete[k];
  }
  if (skipped > 0 && whole)
    std::fprintf(stderr, "resuming: %zu of %zu frames already complete\n", skipped, traj.size());
  else if (skipped > 0)
    std::fprintf(stderr, "resuming: %zu of frames %zu..%zu already complete\n", skipped, first,
                 last - 1);
  SequenceJobResult::Sequence result;
  result.dir = dir.string();
  result.configuration = c.describe();
  result.assets = assetCredits(scene);
  result.frames = traj.size();
  result.skipped = skipped;

  // Temporal reuse (sensors/temporal_reuse.h), one per camera: frame k's colour depends on
  // frames k - window + 1 .. k, so after a gap (frames a killed run finished) the frames before
  // the next one are rendered again first, and a resumed run writes the same bytes.
  const int window = temporalWindow(a);
  const bool temporal = window > 1 && has(passes, Pass::Rgb);
  std::optional<TemporalReuse> reuse, reuse1;
  const TemporalReuseOptions reuse_opt = reuseOptions(a);
  if (temporal) {
    reuse.emplace(scene, lens, reuse_opt);
    if (a.stereo > 0) reuse1.emplace(scene, lens, reuse_opt);
  }
  size_t reuse_next = 0;  // the frame the reuse windows expect next
  RgbLayers layers;
  Frame warm;
  const Pose T_cam0_cam1{Quat::Identity(), Vec3(a.stereo, 0, 0)};
  auto exposureOf = [&](size_t k, const Pose& T_rig) {
    CameraExposure ex = exposureAt(cam, k, shutter);
    ex.T_world_camera_open = ex.T_world_camera_open * T_rig;
    ex.T_world_camera_close = ex.T_world_camera_close * T_rig;
    for (auto& [dt, pose] : ex.knots) pose = pose * T_rig;
    return ex;
  };
  // The ground truth temporal reuse plans a frame's samples from (its depth, label, instance)
  const bool boosted = reuse_opt.boost > 1 || reuse_opt.boost_edges > 1;
  RenderOptions geometry_only;
  geometry_only.passes = passMask(Pass::DepthZ, Pass::DepthRay, Pass::Label, Pass::Instance);
  Frame geometry;
  // one camera's frame k rendered with `o` into f and passed through its reuse window r, its
  // samples planned by r where the history is short
  auto renderReused = [&](size_t k, const Pose& T_rig, uint32_t idx, const RenderOptions& o,
                          TemporalReuse& r, Frame& f) {
    const CameraExposure ex = exposureOf(k, T_rig);
    const double scene_time_s = static_cast<double>(ex.scene_time_open_ns) * 1e-9;
    if (boosted) {
      renderer.render(lens, ex, geometry_only, idx, geometry);
      RenderOptions planned = o;
      planned.spp_multiplier = &r.plan(geometry, ex.T_world_camera_open, scene_time_s);
      renderer.render(lens, ex, planned, idx, f, &layers);
    } else {
      renderer.render(lens, ex, o, idx, f, &layers);
    }
    r.add(f, layers, ex.T_world_camera_open, scene_time_s);
  };
  // one camera's frame k's geometry only, remembered by r (what later frames' plans count)
  auto rememberGeometry = [&](size_t k, const Pose& T_rig, uint32_t idx, TemporalReuse& r) {
    const CameraExposure ex = exposureOf(k, T_rig);
    renderer.render(lens, ex, geometry_only, idx, geometry);
    r.addGeometry(geometry, ex.T_world_camera_open,
                  static_cast<double>(ex.scene_time_open_ns) * 1e-9);
  };
  // renders one camera's frame k into f (colour filtered as asked: reuse, then the denoiser)
  // the learned denoiser and the training dump need the colour's layers even without reuse
  const bool learned = opt.denoise && a.denoiser == "learned";
  const bool need_layers = has(passes, Pass::Rgb) && (learned || a.save_denoiser_inputs);
  const NeuralDenoiser* net = learned ? &defaultNeuralDenoiser() : nullptr;
  // the denoiser, then (with reuse) the average of the denoised light over the last frames
  // (reuse_opt.smooth is 1 without the denoiser)
  const int smooth_frames = temporal ? reuse_opt.smoothFrames() : 1;
  auto filterColour = [&](Frame& f, TemporalReuse* r) {
    if (net) {
      denoiseRgbLearned(f, layers, *net);
    } else if (opt.denoise) {
      denoiseRgb(f, layers, opt.denoise_options);
    }
    // denoiseRgb filtered the diffuse light apart (layers.diffuse); the network did not
    if (r && smooth_frames > 1) r->smooth(f, layers, !net);
  };
  auto renderColour = [&](size_t k, const Pose& T_rig, uint32_t idx, TemporalReuse* r, Frame& f,
                          const std::string& dump_name) {
    if (!r && !need_layers) {
      renderer.render(lens, exposureOf(k, T_rig), opt, idx, f);
      return;
    }
    if (r) {
      renderReused(k, T_rig, idx, opt, *r, f);
    } else {
      renderer.render(lens, exposureOf(k, T_rig), opt, idx, f, &layers);
    }
    if (a.save_denoiser_inputs)
      writeExr(dir / dump_name / (aslStamp(traj.poses[k].t_ns) + ".exr"), denoiserDump(f, layers),
               denoiserDumpChannels());
    filterColour(f, r);
    if (has(opt.passes, Pass::Shading)) shadingFromRgb(f);  // of the filtered colour
  };
  // the frames before k that k's colour depends on: the reuse window's, and before them those
  // of the frames whose denoised light k's smoothing averages (which are denoised again here)
  auto warmUp = [&](size_t k) {
    if (!temporal || reuse_next == k) return;
    reuse->clear();
    if (reuse1) reuse1->clear();
    RenderOptions colour = opt;
    colour.passes = bit(Pass::Rgb);
    const auto smoothed = static_cast<size_t>(smooth_frames - 1);
    const size_t first_colour =
        k - std::min<size_t>(k, static_cast<size_t>(reuse_opt.warmUpFrames()));
    // the samples of those frames were planned from the geometry of the frames before them
    if (boosted)
      for (size_t j = first_colour - std::min<size_t>(first_colour, static_cast<size_t>(window - 1));
           j < first_colour; ++j) {
        const auto idx = static_cast<uint32_t>(j);
        rememberGeometry(j, Pose{}, idx, *reuse);
        if (reuse1) rememberGeometry(j, T_cam0_cam1, idx | 0x80000000u, *reuse1);
      }
    for (size_t j = first_colour; j < k; ++j) {
      const auto idx = static_cast<uint32_t>(j);
      const bool filtered = j + smoothed >= k;  // its denoised light is smoothed into k's
      renderReused(j, Pose{}, idx, colour, *reuse, warm);
      if (filtered) filterColour(warm, &*reuse);
      if (reuse1) {
        renderReused(j, T_cam0_cam1, idx | 0x80000000u, colour, *reuse1, warm);
        if (filtered) filterColour(warm, &*reuse1);
      }
    }
  };

  ProgressBar bar(static_cast<int64_t>(last - first), "frames", a.progress);
  Frame frame, frame1;   // cam0, cam1
  ImageF shown, shown1;  // the colour after the camera response; frame.rgb stays linear (EXR)
  size_t done = 0;
  std::vector<char> seen(want.boxes ? traj.size() : 0);  // visible[k] is known
  for (size_t k = first; k < last; ++k) {
    if (stopSignal()) {
      bar.finish();
      stopIfSignalled(fmt::format("after {} of {} frames of {}", done, last - first, dir.string()));
    }
    if (!complete[k]) {
      const auto idx = static_cast<uint32_t>(k);
      const bool respond = !response.identity() && has(passes, Pass::Rgb);
      // this frame and its neighbours, for the flow; cam1's are moved by the baseline
      auto neighbour = [&](size_t j, const Pose& T_rig) {
        return NeighbourFrame{traj.poses[j].T_world_camera * T_rig,
                              traj.poses[j].t_ns - traj.poses.front().t_ns};
      };
      auto derive = [&](const Pose& T_rig, uint32_t noise_frame, Frame& f) {
        const NeighbourFrame self = neighbour(k, T_rig);
        std::optional<NeighbourFrame> previous, next;
        if (k > 0) previous = neighbour(k - 1, T_rig);
        if (k + 1 < traj.size()) next = neighbour(k + 1, T_rig);
        deriveFramePasses(renderer, scene, lens, passes, depth_noise, a.seed, noise_frame, self,
                          previous ? &*previous : nullptr, next ? &*next : nullptr, f);
      };
      warmUp(k);
      renderColour(k, Pose{}, idx, temporal ? &*reuse : nullptr, frame, "denoise_in");
      derive(Pose{}, idx, frame);
      if (respond) shown = response.apply(frame.rgb, opt.seed, idx);
      if (a.stereo > 0) {
        // cam1: every pose of the exposure moved by the baseline; its own random numbers
        const uint32_t idx1 = idx | 0x80000000u;
        renderColour(k, T_cam0_cam1, idx1, temporal ? &*reuse1 : nullptr, frame1, "denoise_in1");
        derive(T_cam0_cam1, idx1, frame1);
        if (respond) shown1 = response.apply(frame1.rgb, opt.seed, idx1);
      }
      writer.writeFrame(k, frame, respond ? &shown : nullptr, a.stereo > 0 ? &frame1 : nullptr,
                        respond && a.stereo > 0 ? &shown1 : nullptr);
      reuse_next = k + 1;
      ++result.rendered;
      if (want.boxes) {
        visible[k] = instanceVisibility(frame.instance);
        seen[k] = 1;
      }
    }
    bar.update(static_cast<int64_t>(++done));
  }
  bar.finish();
  // The sequence-level files come from the job that finds every frame complete at its end (jobs
  // over other ranges may have run before or alongside this one).
  bool finishing = a.finish;
  for (size_t k = 0; k < traj.size() && finishing; ++k)
    finishing = (k >= first && k < last) || complete[k] || writer.frameComplete(k);
  // a finished sequence (docs/output.md section 8) has nothing left to write
  const bool already_finished = finishing && writer.finished();
  if (finishing && !already_finished && want.boxes) {
    // frames this job did not render: their instance image again (one ray per pixel)
    RenderOptions ro;
    ro.passes = bit(Pass::Instance);
    for (size_t k = 0; k < traj.size(); ++k) {
      if (seen[k]) continue;
      stopIfSignalled(
          fmt::format("after every frame of {} (boxes.json is not written)", dir.string()));
      const TimeNs scene_t = traj.poses[k].t_ns - traj.poses.front().t_ns;
      renderer.render(lens, CameraExposure::fixed(traj.poses[k].T_world_camera, scene_t), ro, 0,
                      frame);
      visible[k] = instanceVisibility(frame.instance);
    }
  }
  for (size_t k = first; k < last; ++k) {
    SequenceJobResult::Sequence::Frame fr;
    fr.index = k;
    fr.t_ns = traj.poses[k].t_ns;
    for (const fs::path& f : writer.frameFiles(k)) {
      result.files.push_back(f.string());
      fr.files.push_back(f.string());
    }
    std::sort(fr.files.begin(), fr.files.end());
    result.range.push_back(std::move(fr));
  }
  if (!finishing) {
    std::sort(result.files.begin(), result.files.end());
    std::printf("wrote frames %zu..%zu of %zu to %s\n", first, last - 1, traj.size(),
                dir.string().c_str());
    stopIfSignalled(fmt::format("after frames {}..{} of {}", first, last - 1, dir.string()));
    return result;
  }
  if (!already_finished)
    writeSequenceFiles(a, setup, prepared, c, renderer, writer, boxes, visible);
  std::printf("wrote %zu frames to %s\n", traj.size(), dir.string().c_str());
  result.finished = true;
  result.files.clear();
  // (not another job's temporary files: one finishing the same sequence at the same moment)
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && !isTemporaryName(e.path().filename().string()))
      result.files.push_back(e.path().string());
  std::sort(result.files.begin(), result.files.end());
  // a signal during the last step: the sequence is whole, but the job was asked to stop
  stopIfSignalled(fmt::format("after writing {} completely", dir.string()));
  return result;
}

/// Everything of a job that what Prepared holds depends on (a file by its size and time too).
std::string preparedKey(const SequenceJob& a) {
  nlohmann::json k;
  auto file = [](const std::string& path) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    const auto time = fs::last_write_time(path, ec).time_since_epoch().count();
    return ec ? path : fmt::format("{} {} {}", path, size, time);
  };
  k["scene"] = {file(a.scene.path),        a.scene.up,           a.scene.scale,
                file(a.scene.labels),      file(a.scene.lights), a.scene.auto_lights,
                a.scene.default_apartment, a.scene.rooms,        a.scene.furniture};
  k["trajectory"] = {file(a.trajectory),
                     a.motion.v_mult,
                     a.motion.w_mult,
                     a.motion.clearance,
                     a.motion.min_height,
                     a.motion.max_height,
                     a.motion.style,
                     a.place_trajectory,
                     a.frames,
                     a.frames_set,
                     a.fps,
                     a.seed};
  k["sensors"] = {a.passes, a.imu_rate, a.imu_noise, a.config, a.lens.lens, a.readout_ms};
  return k.dump();
}

/// The last job's Prepared, for the next job of the same sequence in this process.
std::mutex g_prepared_mutex;
std::shared_ptr<const Prepared> g_prepared;

std::shared_ptr<const Prepared> preparedFor(const SequenceJob& a, const SequencePasses& want) {
  const std::string key = preparedKey(a);
  {
    std::lock_guard<std::mutex> lock(g_prepared_mutex);
    if (g_prepared && g_prepared->key == key) return g_prepared;
    g_prepared.reset();  // one at a time: a scene may take hundreds of MB
  }
  auto p = std::make_shared<Prepared>();
  p->key = key;
  p->configs = parseConfigs(a.config);
  p->scene = a.scene.load();
  p->cam = loadTrajectory(a, p->scene);
  const CameraPath& cam = p->cam;
  // the IMU and the event camera's path from the camera's continuous path, made before
  // anything is written, so that a path too short for a spline fails cleanly
  // for random trajectories the spline has knots at the 200 Hz samples, through which it passes
  // exactly; for a file, the default spacing (the input's mean, at least 50 ms)
  SplineFitOptions fit;
  if (cam.path.size() > cam.frames.size())
    fit.knot_spacing_ns = cam.path.poses[1].t_ns - cam.path.poses[0].t_ns;
  if (want.events) p->spline = PoseSpline::fit(cam.path, fit, nullptr, cam.description);
  if (want.imu && a.imu_rate > 0) {
    p->imu.rate_hz = a.imu_rate;
    p->imu.noise = imuNoiseFromArg(a.imu_noise, "--imu-noise");
    p->imu.seed = a.seed;
    try {
      p->imu_seq = simulateImu(cam.path, p->imu, fit, nullptr, nullptr, cam.description);
    } catch (const InputError& e) {
      // 'default' and 'all' leave the IMU out of sequences too short for a spline (a few
      // frames); asked for by name, that is an error
      if (want.imu_by_name || e.field() != "trajectory") throw;
    }
  }
  // every configuration's scene before the first file: the same trajectory goes through each
  for (SceneConfig& c : p->configs) c.scene = variantOf(p->scene, c);
  std::lock_guard<std::mutex> lock(g_prepared_mutex);
  g_prepared = p;
  return p;
}

}  // namespace

std::map<int, AssetCredit> assetCredits(const Scene& scene) {
  std::map<int, AssetCredit> credits;
  std::shared_ptr<const CatalogLibrary> library;
  for (const Object& o : scene.objects) {
    if (o.mesh < 0 || credits.count(o.instance)) continue;
    const MeshSource& source = scene.meshes[static_cast<size_t>(o.mesh)].source;
    if (source.kind != MeshSource::Kind::Catalog) continue;
    if (!library) {
      if (!catalogsAvailable()) return credits;
      library = catalogLibrary();
    }
    const auto [catalog, piece] = library->find(source.catalog_piece);
    if (!piece) continue;
    credits[o.instance] = {piece->id, piece->name, piece->creator,
                           piece->license.empty() ? catalog->license : piece->license};
  }
  return credits;
}

int temporalWarmUpFrames(const SequenceJob& job) {
  return temporalWindow(job) > 1 ? reuseOptions(job).warmUpFrames() : 0;
}

SequenceJobResult runSequenceJob(const SequenceJob& a) {
  const auto t0 = std::chrono::steady_clock::now();
  validateArgs(a);
  a.response.validate();
  JobSetup setup;
  setup.lens_type = a.lens.type();
  CameraIntrinsics K = lensIntrinsics(a, setup.lens_type);
  K.validate("generate");
  setup.lens = a.lens.make(K, "generate");
  setup.want = parseSequencePasses(a.passes, setup.lens_type, a.readout_ms > 0);
  setup.passes = lensPasses(setup.want.frame, setup.lens_type);
  if (a.hdr && !has(setup.passes, Pass::Rgb)) throw InputError("", "--hdr", "needs the rgb pass");
  if (!(a.stereo >= 0 && a.stereo <= 10))
    throw InputError("", "--stereo", "the baseline must be in 0..10 m");
  setup.event_opt = a.events.options(a.seed);
  setup.formats = splitCommaList(a.formats);
  a.lens.checkFormats(setup.formats);
  // Load and check every input before anything is written; consecutive jobs of one sequence
  // (the dataset builder's frame ranges) share what they load
  const std::shared_ptr<const Prepared> prepared = preparedFor(a, setup.want);
  const CameraPath& cam = prepared->cam;
  if (a.frame_begin >= cam.frames.size())
    throw InputError(cam.description, "frame range",
                     fmt::format("starts at frame {} but the camera path has {} frames",
                                 a.frame_begin, cam.frames.size()));
  RenderOptions& opt = setup.opt;
  opt.spp = a.spp;
  opt.max_bounces = a.max_bounces;
  opt.seed = a.seed;
  opt.passes = renderPassesFor(setup.passes, setup.lens_type, setup.want.boxes);
  opt.denoise = a.denoise;
  if (temporalWindow(a) > 1) {
    // After temporal reuse the filter is wider than RenderOptions' single-frame default (3
    // levels, sigma_color 2, tuned on the bench room at 48 spp): SVGF's 5 levels and
    // sigma_color 4. Apartment 3's 24-frame sequence, frames 0 / 11 / 23 against two 512-spp
    // references: flat-region error 0.114 / 0.106 / 0.095 -> 0.074 / 0.079 / 0.058, flicker
    // 5.8 -> 3.8 %, whole image unchanged (0.140 / 0.154 / 0.155) once the view through windows
    // is kept out of the filter (docs/denoise.md, section 1b; 4 levels and sigma_color 3 gave
    // 0.080 / 0.084 / 0.065 and 4.3 %)
    opt.denoise_options.iterations = 5;
    opt.denoise_options.sigma_color = 4.f;
  }
  applyDenoiseParams(a.denoise_params, opt.denoise_options, "", "--denoise-params");
  opt.light_cache = a.light_cache;
  opt.sun_photons = a.sun_photons;
  opt.lamp_photons = a.lamp_photons;
  opt.radiance_cache = a.radiance_cache;
  opt.radiance_cache_config.cell_m = static_cast<float>(a.radiance_cell_m);
  opt.radiance_cache_config.train_spp = a.radiance_train;
  stopIfSignalled("before the first frame");
  SequenceJobResult result;
  const auto t1 = std::chrono::steady_clock::now();
  result.setup_s = std::chrono::duration<double>(t1 - t0).count();
  for (const SceneConfig& c : prepared->configs)
    result.sequences.push_back(renderSequence(a, c, setup, *prepared));
  result.sequences_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (!a.contact_sheet.empty() && result.sequences.front().finished)
    writeSequenceSheet(fs::path(a.out) / layoutFolder(a, prepared->scene) /
                           (a.sequence + prepared->configs.front().suffix()),
                       a.contact_sheet);
  return result;
}

}  // namespace inet
