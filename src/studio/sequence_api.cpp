#include "studio/sequence_api.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "dataset/format_writer.h"
#include "pipeline/sensor_outputs.h"
#include "render/lens.h"
#include "studio/camera_keys.h"
#include "studio/json_fields.h"
#include "trajectory/formats.h"

namespace inet::studio {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// The event camera's keys: generate's flags (apps/common.cpp, addEventFlags) as flagToKey
/// names them.
const std::set<std::string>& eventKeys() {
  static const std::set<std::string> keys = {
      "event_width",    "event_height",  "event_spp",         "contrast",
      "contrast_pos",   "contrast_neg",  "threshold_spread",  "leak_rate_hz",
      "contrast_sigma", "refractory_ms", "shot_noise_rate_hz"};
  return keys;
}

/// The event keys of `body` over generate's defaults, checked as generate checks its flags.
EventSettings parseEventKeys(const json& body) {
  EventSettings e;
  e.opt.width = integerIn(body, "event_width", e.opt.width, 1, 65535);
  e.opt.height = integerIn(body, "event_height", e.opt.height, 1, 65535);
  e.opt.spp = integerIn(body, "event_spp", e.opt.spp, 1, 65536);
  e.contrast = number(body, "contrast", e.contrast);
  e.contrast_pos = number(body, "contrast_pos", e.contrast_pos);
  e.contrast_neg = number(body, "contrast_neg", e.contrast_neg);
  e.opt.sim.threshold_spread = number(body, "threshold_spread", e.opt.sim.threshold_spread);
  e.opt.sim.leak_rate_hz = number(body, "leak_rate_hz", e.opt.sim.leak_rate_hz);
  e.opt.sim.sigma_c = number(body, "contrast_sigma", e.opt.sim.sigma_c);
  e.refractory_ms = number(body, "refractory_ms", e.refractory_ms);
  e.opt.sim.shot_noise_rate_hz = number(body, "shot_noise_rate_hz", e.opt.sim.shot_noise_rate_hz);
  try {
    e.options(0);
  } catch (const InputError& error) {
    throw asRequestError(error);
  }
  return e;
}

/// The first studio_NNN with no folder under `parent`.
std::string freeSequenceName(const fs::path& parent) {
  for (int i = 0; i < 100000; ++i) {
    const std::string name = fmt::format("studio_{:03d}", i);
    if (!fs::exists(parent / name)) return name;
  }
  throw InputError(parent.string(), "sequence", "no free studio_NNN name left");
}

/// Renders `job`'s n frames in ranges (see the header), reporting progress; the result JSON.
json renderInRanges(const SequenceRequest& req, SequenceJob job, size_t n, JobContext& ctx) {
  size_t done = 0, chunk = 1;
  double setup_s = 0, render_s = 0;
  SequenceJobResult last;
  ctx.progress(0.0, fmt::format("rendering {} frames", n));
  while (done < n) {
    if (ctx.cancelled())
      throw InputError("", "", fmt::format("stopped after {} of {} frames", done, n));
    job.frame_begin = done;
    job.frame_end = std::min(n, done + chunk);
    last = runSequenceJob(job);
    setup_s += last.setup_s;
    render_s += last.sequences_s;
    const size_t rendered = job.frame_end - done;
    done = job.frame_end;
    ctx.progress(static_cast<double>(done) / n, fmt::format("rendered {} of {} frames", done, n));
    // the next range: long enough that loading the scene again costs at most a fifth of it,
    // and that the frames a range renders again to warm up temporal reuse cost at most half of it
    const double per_frame = std::max(1e-3, last.sequences_s / rendered);
    chunk = std::max<size_t>({size_t{1}, 2 * static_cast<size_t>(temporalWarmUpFrames(job)),
                              static_cast<size_t>(std::ceil(4 * last.setup_s / per_frame))});
  }
  const auto& s = last.sequences.front();
  json dirs = json::array();
  for (const auto& q : last.sequences)
    dirs.push_back({{"dir", q.dir}, {"configuration", q.configuration}});
  return {{"sequence", job.sequence},
          {"dir", s.dir},
          {"sequences", std::move(dirs)},
          {"trajectory_file", req.trajectory_file.string()},
          {"contact_sheet",
           job.contact_sheet.empty() ? json() : json("studio/" + job.sequence + "_sheet.png")},
          {"frames", s.frames},
          {"finished", s.finished},
          {"files", s.files.size()},
          {"setup_s", std::round(setup_s * 100) / 100},
          {"render_s", std::round(render_s * 100) / 100}};
}

}  // namespace

SequenceRequest parseSequenceRequest(const json& body, const StudioLayout& layout,
                                     const fs::path& out) {
  std::set<std::string> keys = {"width",    "height", "fx",          "spp",
                                "sequence", "stereo", "exposure_ms", "readout_ms",
                                "imu_rate", "passes", "config",      "formats"};
  keys.insert(lensKeys().begin(), lensKeys().end());
  keys.insert(responseKeys().begin(), responseKeys().end());
  keys.insert(eventKeys().begin(), eventKeys().end());
  keys.insert("imu_noise");
  checkDesignKeys(body, keys);
  SequenceRequest r;
  r.design = parseDesignRequest(body);
  SequenceJob& job = r.job;
  job.scene = layout.scene_source;
  job.fps = r.design.fps;
  job.K.width = integerIn(body, "width", 320, 16, 4096);
  job.K.height = integerIn(body, "height", 240, 16, 4096);
  job.K.fx = job.K.fy = number(body, "fx", 300.0);
  if (!(job.K.fx > 0 && job.K.fx <= 100000)) throw InputError("", "fx", "must be in (0, 100000]");
  job.width_set = job.height_set = true;
  job.spp = integerIn(body, "spp", 4, 1, 4096);
  // the camera and sensors, as generate's flags, checked here (the lens is made for the
  // image size: a fisheye's square, a panorama's 2:1, a distortion that does not fold)
  job.lens = parseLensKeys(body);
  const LensType lens = job.lens.type();
  lensModelOf(job.lens, CameraIntrinsics::centred(job.K.width, job.K.height, job.K.fx));
  const ResponseKeys response = parseResponseKeys(body);
  job.response = response.response;
  job.exposure = response.exposure;
  job.formats = text(body, "formats", job.formats);
  try {
    // the pipeline's check, at once: Kalibr's radial-tangential model has no k3
    job.lens.checkFormats(parseFormatList(job.formats));
  } catch (const InputError& e) {
    throw asRequestError(e);
  }
  // a fisheye's and a panorama's focal length follows from the image size
  job.fx_set = job.fy_set = lens == LensType::Pinhole || lens == LensType::ThinLens;
  job.stereo = number(body, "stereo", 0.0);
  if (!(job.stereo >= 0 && job.stereo <= 10)) throw InputError("", "stereo", "must be in 0..10 m");
  job.exposure_ms = number(body, "exposure_ms", 0.0);
  if (!(job.exposure_ms >= 0 && job.exposure_ms <= 1000))
    throw InputError("", "exposure_ms", "must be in 0..1000 ms");
  job.readout_ms = number(body, "readout_ms", 0.0);
  if (!(job.readout_ms >= 0 && job.readout_ms <= 1000))
    throw InputError("", "readout_ms", "must be in 0..1000 ms");
  job.imu_rate = number(body, "imu_rate", job.imu_rate);
  if (!(job.imu_rate == 0 || (job.imu_rate >= 1 && job.imu_rate <= 100000)))
    throw InputError("", "imu_rate", "must be 0 (no IMU) or in 1..100000 Hz");
  // IMU noise as generate --imu-noise, but no yaml file: the studio reads no file it was not
  // given
  job.imu_noise = text(body, "imu_noise", job.imu_noise);
  if (job.imu_noise != "none" && job.imu_noise != "euroc")
    throw InputError("", "imu_noise",
                     "must be none or euroc (ADIS16448), not '" + job.imu_noise +
                         "' (a Kalibr imu yaml is read by interiornet generate only)");
  job.passes = text(body, "passes", job.passes);
  // the passes as the pipeline reads them, at once; the event camera's settings only with
  // its pass, as a lens's settings only with that lens
  SequencePasses passes;
  try {
    passes = parseSequencePasses(job.passes, lens, job.readout_ms > 0);
  } catch (const InputError& e) {
    throw asRequestError(e);
  }
  job.events = parseEventKeys(body);
  if (!passes.events)
    for (const std::string& key : eventKeys())
      if (body.contains(key))
        throw InputError("", key, "only used with the events pass (passes \"default,events\")");
  job.config = text(body, "config", job.config);  // original, lighting:N, rearranged:N, ...
  job.out = out.string();
  job.progress = false;
  const fs::path parent = out / layout.scene.name;
  job.sequence = text(body, "sequence", "");
  if (job.sequence.empty()) job.sequence = freeSequenceName(parent);
  if (job.sequence.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                     "0123456789-_") != std::string::npos ||
      job.sequence.size() > 100)
    throw InputError("", "sequence", "use up to 100 letters, digits, '-' and '_'");
  if (fs::exists(parent / job.sequence))
    throw InputError((parent / job.sequence).string(), "sequence",
                     "exists already: choose another name");
  r.trajectory_file = out / "studio" / (job.sequence + "_trajectory.csv");
  // the pipeline's contact sheet shows the ASL layout's cam0/ frames
  if (job.formats.find("asl") != std::string::npos)
    job.contact_sheet = (out / "studio" / (job.sequence + "_sheet.png")).string();
  return r;
}

json runSequenceRequest(const SequenceRequest& req, JobContext& ctx) {
  Trajectory path = designTrajectory(req.design);
  const TimeNs t0 = path.poses.front().t_ns;
  for (TimedPose& p : path.poses) p.t_ns -= t0;
  fs::create_directories(req.trajectory_file.parent_path());
  writeTrajectory(req.trajectory_file.string(), path, TrajectoryFormat::Euroc);
  SequenceJob job = req.job;
  job.trajectory = req.trajectory_file.string();
  job.frames = static_cast<int>(path.size());
  job.frames_set = true;
  try {
    return renderInRanges(req, job, path.size(), ctx);
  } catch (const InputError& e) {  // the pipeline words its checks as generate's flags
    throw asRequestError(e);
  }
}

}  // namespace inet::studio
