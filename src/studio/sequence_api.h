#pragma once
// "Generate sequence" (issue 18): the designed path rendered through the sequence pipeline
// (pipeline/sequence_job.h, what `interiornet generate` runs) as a background job.
//
// Request (POST /api/jobs/sequence): the design keys (studio/design_api.h) and
//   {"width": 16..4096 (320), "height": 16..4096 (240), "fx": pixels (0, 100000] (300;
//    fy = fx, principal point at the centre; pinhole and thin lens only), "spp": 1..4096 (4),
//    "sequence": a plain folder name (default: the first free studio_NNN),
//    the lens keys (studio/camera_keys.h: "lens", "aperture_m", "focus_m", "fisheye_fov_deg",
//    "distortion": [k1, k2, p1, p2(, k3)]) and the camera response ("exposure": auto | fixed,
//    "exposure_ev", "tone", "sensor_noise"), "stereo": baseline 0..10 m (0 = mono),
//    "exposure_ms", "readout_ms" (rolling shutter): 0..1000, "imu_rate": 0 (none) or Hz (800),
//    "imu_noise": none | euroc (euroc), "passes": as generate --passes ("default"; checked at
//    once), the event camera (with the events pass only; generate's flags as keys):
//    "event_width", "event_height", "event_spp", "contrast", "contrast_pos", "contrast_neg",
//    "threshold_spread", "leak_rate_hz", "contrast_sigma", "refractory_ms",
//    "shot_noise_rate_hz",
//    "config": as generate --config ("original"; lighting:N, rearranged:N, comma lists),
//    "formats": as generate --format ("asl,tum"; a k3 needs formats without asl)}
// The lens is made at once for the image size (a fisheye's square image, a panorama's 2:1, a
// distortion that folds inside the image are 400); the pipeline checks the rest of the
// combination when the job starts (passes' names), its messages naming these keys.
// The path is written as EuRoC (lossless) to <out>/studio/<sequence>_trajectory.csv and the
// sequence goes to <out>/<layout name>/<sequence>/ as `interiornet generate --layout SOURCE
// --trajectory that-file --fps FPS --width W --height H --fx FX --fy FX --spp SPP --sequence
// SEQ --out OUT` would write it (same bytes). It runs in frame ranges (the pipeline's rule:
// ranges give the same bytes as one run), so the job reports progress and can stop between
// ranges. The first range is one frame; the next are long enough that reloading the scene
// costs at most a fifth of one, and re-rendering the frames temporal reuse warms up on at most
// a half.
// Result: {"sequence", "dir" (the first configuration's), "sequences": [{"dir",
//          "configuration"}, ...], "trajectory_file", "contact_sheet" (up to 6 colour frames of
//          the first configuration, PNG, relative to <out>: studio/<sequence>_sheet.png; null
//          without the asl format, whose cam0/ it shows), "frames", "finished", "files",
//          "setup_s", "render_s"}.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "pipeline/sequence_job.h"
#include "studio/design_api.h"
#include "studio/job_queue.h"
#include "studio/studio_layout.h"

namespace inet::studio {

struct SequenceRequest {
  DesignRequest design;
  SequenceJob job;  ///< everything but the trajectory file and the frame range
  std::filesystem::path trajectory_file;
};

/// Parses and checks the request, names the sequence and checks that its folder does not exist
/// yet (InputError("", "sequence", ...) if it does). `out` is the studio's --out folder.
SequenceRequest parseSequenceRequest(const nlohmann::json& body, const StudioLayout& layout,
                                     const std::filesystem::path& out);

/// Writes the trajectory file and renders the sequence, reporting progress to `ctx`.
nlohmann::json runSequenceRequest(const SequenceRequest& req, JobContext& ctx);

}  // namespace inet::studio
