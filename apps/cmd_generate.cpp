// interiornet generate: one sequence (per configuration) from the command line. The flags fill a
// SequenceJob; the pipeline itself is pipeline/sequence_job.h.
#include <memory>
#include <string>

#include "assets/catalog_library.h"
#include "common.h"
#include "core/error.h"
#include "pipeline/sequence_job.h"

namespace inet::app {
namespace {

/// generate's flags fill a SequenceJob; --threads is the process's, not the job's.
struct GenerateArgs : SequenceJob {
  int threads = 0;
  std::string frame_range;  ///< "B:E" = frames B..E-1; "" = every frame
};

/// --frame-range B:E (E > B >= 0; E may pass the last frame).
void parseFrameRange(const std::string& s, SequenceJob& job) {
  const size_t colon = s.find(':');
  auto number = [&](const std::string& t) {
    if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("", "--frame-range", "'" + s + "' is not B:E (frames B..E-1)");
    return static_cast<size_t>(std::stoull(t));
  };
  if (colon == std::string::npos)
    throw InputError("", "--frame-range", "'" + s + "' is not B:E (frames B..E-1)");
  job.frame_begin = number(s.substr(0, colon));
  job.frame_end = number(s.substr(colon + 1));
  if (job.frame_end <= job.frame_begin)
    throw InputError("", "--frame-range", "'" + s + "': E must be greater than B");
}

void runGenerate(GenerateArgs a) {
  installStopHandlers();  // before the scene loads: a scheduler may stop us at any time
  if (!a.frame_range.empty()) {
    parseFrameRange(a.frame_range, a);
    // other ranges may be running into the same folder: their temporary files are not stale
    a.shared_folder = true;
  }
  ThreadLimit limit(a.threads);
  runSequenceJob(a);
}

}  // namespace

void registerGenerate(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "generate",
      "Render a sequence: RGB + ground truth (depth, ray depth, normals, NYU40 labels, instances, "
      "albedo) along a camera trajectory, written as ASL/EuRoC and TUM RGB-D folders. With "
      "--lens fisheye or panorama, 'depth' is the ray distance (there is no z-depth)");
  auto a = std::make_shared<GenerateArgs>();
  addSceneFlags(*cmd, a->scene,
                "a 4-room apartment furnished from the Sweet Home 3D catalogs (builtin:apartment) "
                "where they are installed, else the built-in furnished room (builtin:room)");
  cmd->add_option("--trajectory", a->trajectory,
                  "two-body, hand-held or look-forward: a random trajectory through the layout's "
                  "free space (--seed, --v-mult, ...); or a trajectory file (tum, euroc, icl, "
                  "slambench, scenenet; T_world_camera, OpenCV camera axes). Default: the built-in "
                  "orbit for the built-in room, two-body otherwise");
  addMotionFlags(*cmd, a->motion);
  cmd->add_option("--imu", a->imu_rate,
                  "rate in Hz of imu0/ (EuRoC csv, noise-free stream, biases, sensor.yaml), from "
                  "a B-spline through the camera path (IMU frame = camera frame); default 800; "
                  "0 = no IMU");
  cmd->add_option("--imu-noise", a->imu_noise,
                  "none, euroc (ADIS16448, default) or a Kalibr/EuRoC imu yaml");
  cmd->add_option("--frames", a->frames,
                  "number of frames (default 25; with --trajectory: the first N poses)")
      ->each([a](const std::string&) { a->frames_set = true; });
  cmd->add_option("--fps", a->fps, "frame rate of built-in and random trajectories (default 25)");
  cmd->add_option("--spp", a->spp, "path-traced samples per pixel (default 16)");
  cmd->add_option("--max-bounces", a->max_bounces,
                  "maximum scattering events per path (default 8)");
  cmd->add_option("--seed", a->seed, "random seed; same seed, same bytes (default 0)");
  cmd->add_option("--threads", a->threads,
                  "worker threads, 0 = all cores (default 0); never changes the output");
  cmd->add_option("--passes", a->passes,
                  "comma list of frame passes (rgb, depth, ray_depth, normal, label, instance, "
                  "albedo, shading, depth_noisy = Kinect-like depth, flow = forward optical flow, "
                  "flow_bwd = backward optical flow) "
                  "and sequence sensors (imu, events, boxes = boxes.json); 'default' = every "
                  "frame pass, imu and boxes; 'all' = default and events (default: default)");
  cmd->add_option("--stereo", a->stereo,
                  "also render cam1, this many metres right of cam0 (same lens, every pass): "
                  "cam1/, depth1/, ... with sensor.yaml T_BS (default 0 = mono)");
  addEventFlags(*cmd, a->events);
  cmd->add_option("--format", a->formats,
                  "comma list of output layouts: asl, tum (default asl,tum)");
  cmd->add_option("--width", a->K.width,
                  "image width in pixels (default 640; fisheye 600, panorama 5000)")
      ->each([a](const std::string&) { a->width_set = true; });
  cmd->add_option("--height", a->K.height,
                  "image height in pixels (default 480; fisheye = width, panorama = width / 2)")
      ->each([a](const std::string&) { a->height_set = true; });
  cmd->add_option("--fx", a->K.fx, "focal length in pixels (default 600; pinhole, thin_lens)")
      ->each([a](const std::string&) { a->fx_set = true; });
  cmd->add_option("--fy", a->K.fy, "focal length in pixels (default 600; pinhole, thin_lens)")
      ->each([a](const std::string&) { a->fy_set = true; });
  cmd->add_option("--cx", a->K.cx,
                  "principal point with pixel (i,j) centred at (i+0.5, j+0.5) (default width/2; "
                  "files for SLAM tools state cx-0.5, the OpenCV convention)")
      ->each([a](const std::string&) { a->cx_set = true; });
  cmd->add_option("--cy", a->K.cy, "principal point, as --cx (default height/2)")
      ->each([a](const std::string&) { a->cy_set = true; });
  cmd->add_option("--sequence", a->sequence, "sequence folder name (default seq_000)");
  cmd->add_option("--frame-range", a->frame_range,
                  "B:E renders frames B..E-1 of the sequence only (default: every frame); runs "
                  "over disjoint ranges, in any order or at once, write the same bytes as one "
                  "run, and the run that finds every frame done writes the indexes, imu0/, "
                  "boxes.json and events0/");
  cmd->add_option("--config", a->config,
                  "comma list of scene configurations, each rendered along the same camera path: "
                  "original, lighting:N (random lighting, seed N), rearranged:N (physics, seed "
                  "N); e.g. original,lighting:1,rearranged:1 for the paper's three-way "
                  "sequence; folders <sequence>_lighting_N, ... (default original)");
  cmd->add_option("--out", a->out,
                  "output root; frames go to OUT/<layout>/<sequence>/ (default out)");
  addResponseFlags(*cmd, a->response);
  cmd->add_option("--exposure", a->exposure,
                  "auto (default): one exposure per sequence, metered on a preview of 5 poses so "
                  "that the log-average brightness is middle grey (0.18), in third stops, as a "
                  "camera's auto exposure; --exposure-ev compensates it; meta.json says what it "
                  "chose. fixed: radiance 1 is white (--exposure-ev alone)")
      ->check(CLI::IsMember({"auto", "fixed"}));
  cmd->add_option("--exposure-ms", a->exposure_ms,
                  "exposure time per row in ms: motion blur along the trajectory (default 0)");
  cmd->add_option("--readout-ms", a->readout_ms,
                  "rolling shutter readout, first to last row, in ms (default 0 = global shutter); "
                  "ground truth follows each row's own pose");
  addLensFlags(*cmd, a->lens);
  cmd->add_flag("--hdr", a->hdr,
                "also write the linear RGB radiance (before exposure, noise, tone curve, sRGB) as "
                "float32 EXR, channels R G B: cam0/data/<t>.exr next to the PNG");
  cmd->add_flag_function(
      "--hdr-half",
      [a](int64_t) {
        a->hdr = true;
        a->storage.rgb_exr_half = true;
      },
      "as --hdr in 16-bit half floats (11 significant bits, about half the bytes): exact enough "
      "for rendered radiance, whose noise is larger");
  cmd->add_option_function<int>(
      "--png-level",
      [a](int level) {
        if (level < 0 || level > 9) throw InputError("", "--png-level", "must be 0..9");
        a->storage.png_level = level;
      },
      "zlib level of every PNG, 0..9: all lossless, higher = smaller and slower (default 1; "
      "docs/output.md section 9 has the measured trade)");
  cmd->add_option_function<std::string>(
      "--exr-compression",
      [a](const std::string& v) {
        a->storage.exr = parseExrCompression(v, "", "--exr-compression");
      },
      "lossless compression of every EXR: none, rle, zips, zip, piz (default zip)");
  cmd->add_option_function<std::string>(
      "--flow-files",
      [a](const std::string& v) { parseFlowFiles(v, a->storage, "", "--flow-files"); },
      "which files hold the optical flow: flo (Middlebury float32), kitti (16-bit PNG, 1/64 px "
      "steps), exr (float32 U V, compressed: exact like .flo at a fraction of its size), joined "
      "by '+', or both = flo+kitti (default both)");
  cmd->add_flag("--denoise,!--no-denoise", a->denoise,
                "denoise the RGB pass (edge-aware, guided by albedo/normal/depth; ground truth is "
                "never filtered; docs/denoise.md). On by default: it trades a little bias for "
                "much less noise; --no-denoise keeps the unbiased path-traced colour");
  cmd->add_flag("--light-cache,!--no-light-cache", a->light_cache,
                "visibility-aware light picks: a sparse training pass per frame learns, region "
                "by region, what share of each light's shadow rays gets through (the sun behind "
                "walls), and next-event estimation picks lights by that. Unbiased; on by "
                "default, --no-light-cache gives the plain pick (docs/rendering.md)");
  cmd->add_flag("--sun-photons,!--no-sun-photons", a->sun_photons,
                "sun photons: each frame traces photons from the sun through the window panes, "
                "and every path vertex also connects to a sunlit point they found, so the light "
                "the sun patch on the floor throws onto walls and ceilings is found by a shadow "
                "ray instead of by chance. Unbiased (MIS); on by default, a no-op without a sun "
                "or panes (docs/rendering.md)");
  cmd->add_flag("--lamp-photons,!--no-lamp-photons", a->lamp_photons,
                "lamp photons: each frame traces photons from every point and spot light, and "
                "every path vertex also connects to a point within half a metre of a lamp that "
                "they lit (its shade, back plate or reflector), whose light otherwise reaches "
                "the room by rare paths (fireflies). Unbiased (MIS); on by default, a no-op "
                "without point or spot lights (docs/rendering.md)");
  addRadianceCacheFlags(*cmd, a->radiance_cache, a->radiance_cell_m, true);
  cmd->add_option("--radiance-train", a->radiance_train,
                  "the radiance cache's training paths per pixel of every second row and column "
                  "(default 16: a quarter of a 16-spp frame's paths, but full ones)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--denoiser", a->denoiser,
                  "which denoiser --denoise runs: atrous (edge-avoiding wavelets guided by the "
                  "noise level, default) or learned (a small U-Net trained on our own renders, "
                  "data/denoise/unet.bin; docs/denoise.md)")
      ->check(CLI::IsMember({"atrous", "learned"}));
  cmd->add_option("--denoise-params", a->denoise_params,
                  "the atrous filter's parameters over its defaults, key=value[,key=value]: "
                  "iterations (levels, 1..10), sigma_color (luminance stop in noise standard "
                  "deviations), sigma_normal, sigma_depth, sigma_albedo, albedo_epsilon, "
                  "mean_levels (docs/denoise.md); e.g. iterations=4,sigma_color=3");
  cmd->add_flag("--save-denoiser-inputs", a->save_denoiser_inputs,
                "also write what the learned denoiser reads for each frame (the colour after "
                "temporal reuse, its variance, albedos, normal, depth, emission) as "
                "denoise_in/<t>.exr: training data for 'interiornet denoiser train'");
  cmd->add_option("--temporal", a->temporal,
                  "temporal reuse window N: average each surface point's diffuse light over the "
                  "last N frames that saw it, reprojected exactly through the ground truth (depth, "
                  "classes, object motion), and its glossy light over those whose view turned "
                  "by less than a tenth of the lobe's roughness; mirrors, glass, lights in view, "
                  "edges and newly seen points keep their own frame's samples; before the "
                  "denoiser (docs/denoise.md). Default 16, or 1 (off) with --exposure-ms or "
                  "--readout-ms, which it cannot follow; 1 = off")
      ->each([a](const std::string&) { a->temporal_set = true; });
  cmd->add_option("--history-boost", a->history_boost,
                  "with temporal reuse: render points no earlier frame of the window saw (the "
                  "first frame, disocclusions, the image border) with up to N times --spp, N - k "
                  "times where k earlier frames saw them (default 4; 1 = the same spp everywhere)");
  cmd->add_option("--history-boost-edges", a->history_boost_edges,
                  "with temporal reuse: times --spp on class and depth edges, which keep their "
                  "own samples (default 2)");
  cmd->add_option("--temporal-smooth", a->temporal_smooth,
                  "with temporal reuse and the denoiser: average each surface point's denoised "
                  "light over the last N frames (at most the --temporal window), so that what the "
                  "filter leaves changes slowly from frame to frame (default 4; 1 = off)");
  cmd->add_option(
      "--temporal-firefly", a->temporal_firefly,
      "with temporal reuse: a pixel whose own diffuse light (texture divided out) is "
      "more than this many times that of all 8 neighbours on its surface is one rare bright "
      "sample; it takes its median neighbour's light before the window keeps it, "
      "so that later frames do not spread it into a blotch (default 16; 0 = off)");
  cmd->add_flag("--allow-dark", a->allow_dark,
                "write the sequence even when its colour frames are essentially black (mean "
                "below 1/1000 of white, checked on a preview of 5 poses before anything is "
                "written); without it that is an error");
  cmd->add_flag("--place-trajectory", a->place_trajectory,
                "move a --trajectory FILE into the scene: the turn about z and horizontal shift "
                "(heights above the floor kept) that put the most of its poses 0.1 m from the "
                "geometry, for a motion-capture path (TUM, EuRoC) recorded in another room; said "
                "on stderr and in meta.json, and the ground truth is the moved path");
  cmd->add_flag("--no-progress{false}", a->progress, "do not draw the progress bar");
  cmd->add_option("--contact-sheet", a->contact_sheet,
                  "also write a contact sheet of up to 6 colour frames spread over the sequence "
                  "(half size, with their times) to this .jpg or .png");
  cmd->callback([a] {
    // without --layout: the catalog-furnished apartment where the catalogs are installed
    a->scene.default_apartment = catalogsAvailable();
    runGenerate(*a);
  });
}

}  // namespace inet::app
