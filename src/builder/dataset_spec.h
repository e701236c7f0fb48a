#pragma once
// The dataset spec (issue 16, docs/dataset.md): one versioned YAML or JSON file that says what a
// whole dataset holds: which layouts (procedural seeds, folders of layout.json, 3D-FRONT houses),
// the train/validation/test shares, how many sequences per layout with which trajectory mix and
// scene configurations, the sparse set (one view per layout and configuration), and the camera,
// render, pass, sensor, format and storage settings every sequence shares.
//
//   version: 1
//   name: tiny
//   layouts: {procedural: {count: 3}}
//   sequences: {frames: 50, configurations: [original, "lighting:1"]}
//
// Reading validates everything before returning (STYLE.md section 4): unknown keys (the error
// lists the valid ones), duplicate keys, wrong types (a quoted "12" is a string, not a number),
// ranges and names. Every problem is an InputError(file, field, problem) whose field is the
// dotted key path with the line, e.g. "sequences.frames (line 12)". Nothing touches the file
// system here: folders are listed and layout files read when the plan is made (dataset_plan.h).
//
// The spec is plain data with every default filled in, so specToJson() can store the effective
// spec in the plan and parse it back (YAML reads JSON) to the same struct.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace inet {

/// The spec versions this build reads.
inline constexpr int kDatasetSpecVersion = 1;

/// A scene configuration of a layout (as `generate --config`): the layout as it is, relit by a
/// random lighting of seed n, or rearranged by physics of seed n. Without ":n" in the spec
/// ("lighting") the seed is `derived`: drawn per layout (DatasetPlan's lighting_seed,
/// rearranged_seed), so every layout gets its own variant.
struct SceneConfiguration {
  enum class Kind { Original, Lighting, Rearranged };
  Kind kind = Kind::Original;
  bool derived = false;  ///< seed drawn per layout (spec text without ":n")
  uint64_t seed = 0;     ///< the fixed seed n (0..999999999) when not derived
  /// The spec text: "original", "lighting:3", or "lighting" for a derived seed.
  std::string text() const;
  bool operator==(const SceneConfiguration&) const = default;
};

/// Parses one configuration: original, lighting[:N], rearranged[:N] (N a seed of at most 9
/// digits, as `generate --config`). Throws InputError(file, field, ...) otherwise.
SceneConfiguration parseSceneConfiguration(const std::string& text, const std::string& file,
                                           const std::string& field);

/// A layout file or folder named in the spec: the text as given, the path it resolves to (a
/// relative path is relative to the spec file's folder) and the field it came from (with its
/// line), so errors found at plan time still point into the spec.
struct SpecPath {
  std::string given;
  std::filesystem::path resolved;
  std::string field;  ///< e.g. "layouts.folders[0] (line 7)"
  bool operator==(const SpecPath& o) const { return given == o.given && resolved == o.resolved; }
};

struct ProceduralLayoutsSpec {
  int64_t count = 0;        ///< how many procedural apartments (seeds first_seed, +1, ...)
  uint64_t first_seed = 0;  ///< the first apartment seed
  int rooms_min = 1;        ///< room count drawn per layout uniformly in [rooms_min, rooms_max]
  int rooms_max = 8;
  std::string furniture = "catalog";  ///< catalog, parametric or mixed (procedural/apartment.h)
  bool operator==(const ProceduralLayoutsSpec&) const = default;
};

struct LayoutsSpec {
  ProceduralLayoutsSpec procedural;
  std::vector<SpecPath> folders;  ///< every *.json directly inside each folder is a layout
  std::vector<SpecPath> front3d;  ///< 3D-FRONT house json files
  bool operator==(const LayoutsSpec&) const = default;
};

/// Shares of the layouts in each split; they sum to 1.
struct SplitShares {
  double train = 0.8, validation = 0.1, test = 0.1;
  bool operator==(const SplitShares&) const = default;
};

/// Relative weights of the three random trajectory types (trajectory/random_trajectory.h).
struct TrajectoryMix {
  double two_body = 1.0, hand_held = 1.0, look_forward = 1.0;
  bool operator==(const TrajectoryMix&) const = default;
};

struct SequencesSpec {
  int per_layout = 1;     ///< sequences per layout (0 = none)
  int frames = 1000;      ///< frames per sequence
  double fps = 25.0;      ///< frame rate (Hz)
  int unit_frames = 100;  ///< frames per work unit
  TrajectoryMix trajectory;
  /// Per-trajectory speed and turn-rate multipliers, drawn uniformly from these ranges; the
  /// defaults are what `generate` draws (random_trajectory.h).
  double v_mult_min = 0.5, v_mult_max = 5.0;
  double w_mult_min = 0.5, w_mult_max = 3.0;
  std::vector<SceneConfiguration> configurations = {SceneConfiguration{}};
  bool operator==(const SequencesSpec&) const = default;
};

struct SparseSpec {
  int per_layout = 1;  ///< 0 or 1: one random view per layout in each configuration
  std::vector<SceneConfiguration> configurations = {
      SceneConfiguration{}, SceneConfiguration{SceneConfiguration::Kind::Lighting, true, 0},
      SceneConfiguration{SceneConfiguration::Kind::Rearranged, true, 0}};
  int batch = 64;  ///< layouts per sparse work unit (each with its view in every configuration)
  bool operator==(const SparseSpec&) const = default;
};

struct CameraSpec {
  int width = 640, height = 480;  ///< fisheye: 600 x 600, panorama: 5000 x 2500 by default
  double fx = 600, fy = 600;      ///< pixels; 0 for fisheye and panorama (set by the size)
  std::string lens = "pinhole";   ///< pinhole, thin_lens, fisheye, panorama (render/lens.h)
  double stereo = 0.0;            ///< > 0: a right camera at this baseline (m)
  bool operator==(const CameraSpec&) const = default;
};

struct RenderSpec {
  int spp = 16;
  bool denoise = true;
  int max_bounces = 8;
  bool operator==(const RenderSpec&) const = default;
};

/// How files are stored. Only lossless choices: ground truth must read back exactly. The
/// defaults are what the sequence writer writes today (core/image_io.cpp, dataset/asl_writer).
struct StorageSpec {
  std::string exr_compression = "zip";  ///< none, rle, zips, zip, piz
  int png_level = 1;                    ///< zlib level 0..9
  /// flo (Middlebury float32), kitti (16-bit PNG, 1/64 px: not exact), exr (float32 U V,
  /// compressed), joined by '+', or both (= flo+kitti)
  std::string flow = "both";
  /// The linear radiance cam0/data/<t>.exr next to the colour PNG: none, float (32-bit) or
  /// half (16-bit: exact enough for rendered radiance, about half the bytes)
  std::string rgb_exr = "none";
  bool operator==(const StorageSpec&) const = default;
};

/// Optional WebDataset tar shards of the built dataset (builder/shards.h), written by `dataset
/// build` right after manifest.jsonl when enabled; `dataset shards DIR` writes them on demand
/// with these settings as defaults.
struct ShardsSpec {
  bool enabled = false;
  double max_mb = 1024;  ///< a shard's bound in MB (10^6 bytes) of tar, in [0.001, 10^7]
  /// Pass keys of the manifest's "files" (cam0, depth0.exr, label0_nyu, ...), or [all]
  std::vector<std::string> passes = {"all"};
  bool operator==(const ShardsSpec&) const = default;
};

struct DatasetSpec {
  std::string file;      ///< where it was read from (for messages and the plan's header)
  std::string checksum;  ///< specChecksum() of the text it was read from
  int version = kDatasetSpecVersion;
  std::string name;   ///< the dataset's name, a plain folder-safe name
  uint64_t seed = 0;  ///< the dataset seed: every random draw of the plan is keyed by it
  LayoutsSpec layouts;
  SplitShares splits;
  SequencesSpec sequences;
  SparseSpec sparse;
  CameraSpec camera;
  RenderSpec render;
  std::vector<std::string> passes = {"default"};  ///< as `generate --passes`, one per item
  double imu = 800.0;                             ///< IMU rate (Hz), 0 = no IMU
  std::vector<std::string> formats = {"asl", "tum"};
  StorageSpec storage;
  ShardsSpec shards;
  /// Equal content (file and checksum are provenance and not compared).
  bool operator==(const DatasetSpec& o) const;
};

/// Reads and validates the spec file `file` (YAML or JSON). Relative layout paths are relative
/// to the file's folder. Throws InputError(file, field, problem) on any problem.
DatasetSpec parseDatasetSpec(const std::filesystem::path& file);

/// Same as parseDatasetSpec for text already in memory; `name` is the file named in errors,
/// and relative layout paths are relative to its folder.
DatasetSpec parseDatasetSpecText(const std::string& text, const std::string& name);

/// The effective spec (every key, defaults filled in) as JSON in the spec's own schema:
/// parseDatasetSpecText(specToJson(s).dump(), s.file) == s. Layout paths are written as given.
nlohmann::ordered_json specToJson(const DatasetSpec& spec);

/// A 64-bit hash that never changes across library versions or platforms: FNV-1a over the
/// bytes, then the splitmix64 finaliser so that every output bit depends on every input bit
/// (FNV-1a alone mixes its last bytes poorly: ids that differ only in their last digit would
/// land in neighbouring buckets). Used for the split of a layout and the keys of its draws.
uint64_t stableHash64(std::string_view bytes);

/// The spec checksum stored in plans: stableHash64 of the text as 16 hex digits.
std::string specChecksum(const std::string& text);

}  // namespace inet
