// interiornet depth-noise: Kinect-like noisy depth (sensors/depth_noise.h) for a written ASL
// sequence: reads depth0/ (16-bit mm z-depth PNGs) and normal0/ (if present) and writes
// depth0_noisy/ through dataset/'s NoisyDepthFolder (data/<t>.png, noise.yaml, sensor.yaml,
// data.csv last).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "dataset/asl_writer.h"
#include "dataset/image_encode.h"
#include "dataset/sequence_writer.h"
#include "render/lens.h"
#include "sensors/depth_noise.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct DepthNoiseArgs {
  std::string sequence;
  uint64_t seed = 0;
  KinectNoiseOptions opts;
  bool no_shadow = false;
};

/// The intrinsics of meta.json (renderer convention) after checking the depth PNGs hold z-depth.
CameraIntrinsics readIntrinsics(const fs::path& meta_path) {
  const std::string where = meta_path.string();
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(readTextFile(meta_path));
    const auto& cam = meta.at("camera");
    const LensType lens = parseLensType(cam.at("lens").get<std::string>(), where, "camera.lens");
    if (groundTruthDepthKind(lens) != DepthKind::ZDepth)
      throw InputError(where, "camera.lens",
                       fmt::format("the {} lens stores ray distance in depth0, not z-depth; the "
                                   "Kinect model needs a pinhole or thin_lens sequence",
                                   lensTypeName(lens)));
    CameraIntrinsics K;
    K.width = cam.at("width").get<int>();
    K.height = cam.at("height").get<int>();
    const auto& r = cam.at("renderer");
    K.fx = r.at("fx").get<double>();
    K.fy = r.at("fy").get<double>();
    K.cx = r.at("cx").get<double>();
    K.cy = r.at("cy").get<double>();
    K.validate(where);
    for (double k : cam.value("distortion_coefficients", std::vector<double>{}))
      if (k != 0) {
        fmt::print(stderr,
                   "warning: {}: lens distortion is ignored by the depth-noise model (it only "
                   "changes viewing angles and the projector-shadow width slightly)\n",
                   where);
        break;
      }
    return K;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "camera", std::string("missing or malformed: ") + e.what());
  }
}

std::string noiseYaml(const DepthNoiseArgs& a, const CameraIntrinsics& K, bool normals) {
  const KinectNoiseOptions& o = a.opts;
  return fmt::format(
      "# interiornet depth-noise {}: Kinect-like noise on depth0 (docs/sensors.md). <t>.png: "
      "noisy z-depth, 16-bit mm, 0 = no return.\n"
      "model: nguyen2012+disparity_quantisation\n"
      "seed: {}\nframe_index: row of depth0/data.csv, 0-based\n"
      "normals: {}\n"
      "baseline_m: {}\ndisparity_focal_px: {}\ndisparity_step_px: {}\nmin_range_m: {}\n"
      "max_range_m: {}\nmax_angle_deg: {}\nedge_dropout_px: {}\nedge_dropout_prob: {}\n"
      "edge_jump_ratio: {}\nlateral_scale: {}\naxial_scale: {}\n"
      "axial_sigma_includes_quantisation: {}\nprojector_shadow: {}\n",
      version(), a.seed, normals ? "normal0" : "estimated from depth0", o.baseline_m,
      o.disparity_focal_px > 0 ? o.disparity_focal_px : K.fx, o.disparity_step_px, o.min_range_m,
      o.max_range_m, o.max_angle_deg, o.edge_dropout_px, o.edge_dropout_prob, o.edge_jump_ratio,
      o.lateral_scale, o.axial_scale, o.axial_sigma_includes_quantisation, o.projector_shadow);
}

void runDepthNoise(DepthNoiseArgs a) {
  a.opts.projector_shadow = !a.no_shadow;
  a.opts.validate("depth-noise options");
  const fs::path seq = a.sequence;
  const CameraIntrinsics K = readIntrinsics(seq / "meta.json");
  const bool have_normals = fs::is_directory(seq / "normal0" / "data");
  const NoisyDepthFolder out(seq);  // dataset/ owns the folder and its "complete" rule
  const std::vector<SequenceFrame>& frames = out.frames();
  ProgressBar progress(static_cast<int64_t>(frames.size()), "frames");
  for (size_t k = 0; k < frames.size(); ++k) {
    const fs::path depth_path = seq / "depth0" / "data" / frames[k].file;
    const ImageF depth = decodeDepth16(readPng16(depth_path), kDepthScaleMm);
    if (depth.channels != 1 || depth.width != K.width || depth.height != K.height)
      throw InputError(depth_path.string(), "",
                       fmt::format("expected a {}x{} grey depth image (meta.json), got {}x{}x{}",
                                   K.width, K.height, depth.width, depth.height, depth.channels));
    ImageF normal;
    if (have_normals) {
      const fs::path normal_path = seq / "normal0" / "data" / (frames[k].stamp + ".png");
      normal = decodeNormal16(readPng16(normal_path));
      if (normal.channels != 3 || normal.width != K.width || normal.height != K.height)
        throw InputError(normal_path.string(), "",
                         "expected an RGB normal image of the depth's size");
    }
    out.writeFrame(k, kinectNoisyDepth(depth, normal, K, a.opts, a.seed, static_cast<uint32_t>(k)));
    progress.update(static_cast<int64_t>(k + 1));
  }
  progress.finish();
  out.finish(noiseYaml(a, K, have_normals));
  fmt::print("wrote {} noisy depth frames ({}normals from {}) to {}/\n", frames.size(),
             a.opts.projector_shadow ? "projector shadow, " : "",
             have_normals ? "normal0" : "depth0", (seq / "depth0_noisy").string());
}

}  // namespace

void registerDepthNoise(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "depth-noise",
      "Kinect-like noisy depth for an ASL sequence (docs/sensors.md): projector shadow, "
      "grazing-angle, range and edge dropouts, lateral and axial noise (Nguyen et al. 2012), "
      "1/8 px disparity quantisation; reads SEQ/depth0 (+ SEQ/normal0), writes "
      "SEQ/depth0_noisy/{data/<t>.png, noise.yaml, sensor.yaml, data.csv}");
  auto a = std::make_shared<DepthNoiseArgs>();
  cmd->add_option("--sequence", a->sequence,
                  "sequence folder with meta.json and depth0/ (interiornet generate, asl format)")
      ->required();
  cmd->add_option("--seed", a->seed,
                  "seed of the noise (default 0); frame k of depth0/data.csv "
                  "draws from (seed, k)");
  cmd->add_option("--baseline", a->opts.baseline_m,
                  "camera -> projector along camera +x, metres (default 0.075; negative = "
                  "projector on the left)");
  cmd->add_option("--disparity-focal", a->opts.disparity_focal_px,
                  "focal length of the disparity model in px (default 0 = the camera's fx)");
  cmd->add_option("--min-range", a->opts.min_range_m, "nearest return, metres (default 0.4)");
  cmd->add_option("--max-range", a->opts.max_range_m, "farthest return, metres (default 4.5)");
  cmd->add_option("--max-angle", a->opts.max_angle_deg,
                  "largest angle between surface normal and viewing ray, degrees (default 85)");
  cmd->add_option("--edge-width", a->opts.edge_dropout_px,
                  "width of the random dropout band at depth edges, pixels (default 3; 0 = off)");
  cmd->add_flag("--no-shadow", a->no_shadow, "do not remove projector-shadowed pixels");
  cmd->callback([a] { runDepthNoise(*a); });
}

}  // namespace inet::app
