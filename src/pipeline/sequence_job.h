#pragma once
// The sequence pipeline as one function: a SequenceJob (plain data: layout source,
// configurations, trajectory, camera, passes, sensors, formats, seed, frame range) goes
// layout -> trajectory -> render -> sensors -> dataset writers into one sequence folder per
// configuration. `interiornet generate` is a thin shell over runSequenceJob (its flags fill a
// SequenceJob), and the dataset builder (issue 16) calls the same function for its work units.
//
// Everything is validated before the first ray; frames stream to disk one at a time (memory stays
// flat); files are written atomically, so a killed run leaves only whole files and a rerun of the
// same job skips finished frames and ends with the same bytes. A job may cover a frame range of
// its sequence: jobs over disjoint ranges, run in any order, in one process or many, write the
// same bytes as one job over every frame, and the sequence-level files (indexes, imu0/,
// boxes.json, events0/) are written by the run that finds every frame complete; a finished
// sequence is left alone (the one rule: docs/output.md section 8, dataset/sequence_writer.h).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "dataset/format_writer.h"
#include "pipeline/sensor_outputs.h"
#include "pipeline/settings.h"
#include "render/camera.h"

namespace inet {

struct SequenceJob {
  SceneSource scene;
  /// "" (default: the built-in orbit for the built-in room, two-body otherwise), two-body,
  /// hand-held, look-forward (a random trajectory through the free space), or a trajectory file.
  std::string trajectory;
  MotionSettings motion;
  bool place_trajectory = false;  ///< move a trajectory file into the scene (placePath)
  double imu_rate = 800.0;        ///< rate of imu0/ when the imu pass is on; 0 = no imu
  std::string imu_noise = "euroc";
  int frames = 25;
  bool frames_set = false;  ///< frames was given (a trajectory file keeps its first `frames`)
  double fps = 25.0;
  int spp = 16;
  int max_bounces = 8;
  uint64_t seed = 0;
  std::string passes = "default";  ///< as generate --passes
  double stereo = 0.0;             ///< > 0: cam1 at this baseline (m)
  EventSettings events;
  std::string formats = "asl,tum";
  std::string sequence = "seq_000";
  std::string config = "original";  ///< comma list: original, lighting:N, rearranged:N
  std::string out = "out";  ///< sequences go to <out>/<folder>/<sequence><suffix>/
  std::string folder;       ///< the layout's folder under `out`; "" = the scene's name
  std::string contact_sheet;        ///< "" = none
  bool progress = true;
  bool denoise = true;
  bool light_cache = true;
  bool sun_photons = true;
  bool lamp_photons = true;
  bool radiance_cache = true;
  double radiance_cell_m = 0.25;  ///< edge of the radiance cache's cells
  int radiance_train = 16;        ///< its training paths per pixel of every 2nd row and column
  std::string denoiser = "atrous";    ///< atrous or learned (render/neural_denoise.h)
  /// "key=value,..." over the à-trous filter's defaults (applyDenoiseParams); empty = defaults
  std::string denoise_params;
  bool save_denoiser_inputs = false;  ///< denoise_in/<t>.exr per frame (training data)
  int temporal = 16;  ///< temporal reuse window in frames (1 = off); see temporalWindow()
  bool temporal_set = false;
  /// Temporal reuse's samples multiplier where no earlier frame saw a point, and on edges
  /// (TemporalReuseOptions::boost, boost_edges); 1 = the same spp everywhere.
  int history_boost = 4;
  int history_boost_edges = 2;
  /// Frames the denoised light is averaged over after temporal reuse
  /// (TemporalReuseOptions::smooth); 1 = off.
  int temporal_smooth = 4;
  /// Temporal reuse's firefly test (TemporalReuseOptions::firefly_ratio); 0 = off.
  float temporal_firefly = 16.f;
  double exposure_ms = 0.0;
  double readout_ms = 0.0;
  LensSettings lens;
  bool hdr = false;
  StorageOptions storage;  ///< PNG level, EXR compression, flow files, half-float radiance
  bool allow_dark = false;
  ResponseSettings response;
  std::string exposure = "auto";  ///< auto: metered per sequence; fixed
  CameraIntrinsics K;
  bool width_set = false, height_set = false, fx_set = false, fy_set = false;
  bool cx_set = false, cy_set = false;

  /// The frames this job renders: [frame_begin, min(frame_end, frames of the path)).
  size_t frame_begin = 0;
  size_t frame_end = std::numeric_limits<size_t>::max();
  /// Several jobs write the same sequence at once (disjoint frame ranges): nobody removes a
  /// killed run's temporary files, which may be another job's files in flight.
  bool shared_folder = false;
  /// Writes every configuration's sequence-level files (indexes, imu0/, boxes.json, events0/,
  /// the contact sheet) when every frame is complete at the end of the job.
  bool finish = true;
};

/// Who made a piece of furniture in a scene, and under which licence (Sweet Home 3D catalog
/// pieces: the piece's own licence, else its catalog's).
struct AssetCredit {
  std::string id;  ///< the catalog piece id, e.g. "Blend Swap CC-0#armchair"
  std::string name, creator, license;
  bool operator==(const AssetCredit&) const = default;
};

/// The credits of the instances of `scene` whose meshes are catalog pieces: instance id ->
/// credit. Empty when the scene holds no catalog piece (or the catalogs are not installed).
std::map<int, AssetCredit> assetCredits(const Scene& scene);

/// What a job did, per configuration in the order of `config`.
struct SequenceJobResult {
  struct Sequence {
    std::string dir;        ///< the sequence folder
    std::string configuration;  ///< original, lighting:N or rearranged:N
    size_t frames = 0;      ///< frames of the whole sequence
    size_t rendered = 0;    ///< frames this job rendered
    size_t skipped = 0;     ///< frames of the range already complete
    bool finished = false;  ///< the sequence-level files are written: the sequence is whole
    /// The files this job is answerable for: every file of the range's frames, and when it
    /// finished the sequence, every file of the folder. Sorted.
    std::vector<std::string> files;
    /// Every frame of the job's range (rendered now or before): its index, timestamp and files.
    struct Frame {
      size_t index = 0;
      int64_t t_ns = 0;
      std::vector<std::string> files;
    };
    std::vector<Frame> range;
    /// The credits of the scene's catalog pieces by instance id (assetCredits): with the
    /// instance image of a frame, the licences of what it shows.
    std::map<int, AssetCredit> assets;
  };
  std::vector<Sequence> sequences;
  /// Wall time before the first frame (scene, trajectory, configurations, IMU) and in the
  /// sequences (frames, then the sequence-level files), in seconds.
  double setup_s = 0.0, sequences_s = 0.0;
};

/// Runs `job` (see above). Throws InputError for bad input, before anything is written where it
/// can be known then; StopRequested (core/stop.h) at the next frame after SIGINT or SIGTERM when
/// stop handlers are installed. Uses the calling thread's TBB limits (ThreadLimit in apps/).
SequenceJobResult runSequenceJob(const SequenceJob& job);

/// The frames before a frame range's first that `job` renders again so that the range gives the
/// bytes of a whole run (temporal reuse's window and smoothing: TemporalReuseOptions::
/// warmUpFrames; 0 without reuse).
int temporalWarmUpFrames(const SequenceJob& job);

}  // namespace inet
