#pragma once
// One on-disk sequence format (ASL/EuRoC, TUM RGB-D, ...) and the registry that creates formats
// by name (STYLE.md 1.3). Several formats write side by side into one sequence folder.
//
// A format is mostly data: the list of image files it writes per frame (FrameOutput: folder,
// file-name suffix, which pass, how it is encoded) and how it names frame k (frameStem). The
// generic code in SequenceWriter writes those files and the format's index, list and
// calibration files (indexFiles), so that it knows every file of the folder.
//
// Adding a format: one new <name>_writer.cpp with a class derived from FormatWriter and a
// factory function, plus one line in the registry table in format_writer.cpp.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "render/camera.h"
#include "render/passes.h"
#include "render/lens.h"
#include "trajectory/trajectory.h"

namespace inet {

/// How the frame files are stored (docs/output.md section 9). Only lossless choices for ground
/// truth; the defaults are the bytes every earlier version wrote.
struct StorageOptions {
  int png_level = kDefaultPngLevel;  ///< zlib level 0..9 of every PNG
  ExrCompression exr = ExrCompression::Zip;
  /// The linear-radiance EXR (SequenceSpec::rgb_exr) in 16-bit half floats: exact enough for
  /// rendered radiance (core/image_io.h ExrOptions::half); depth EXRs stay 32-bit.
  bool rgb_exr_half = false;
  /// Which files hold the optical flow (the occlusion mask is always written): Middlebury .flo
  /// (float32, uncompressed), KITTI 16-bit PNG (1/64 px steps, |flow| < 512 px: not exact) and
  /// float32 EXR with channels U, V (unknown = NaN; exact like .flo, compressed).
  bool flow_flo = true, flow_kitti = true, flow_exr = false;
  bool operator==(const StorageOptions&) const = default;
};

/// Parses a flow file list: "flo", "kitti", "exr" joined by ',' or '+', or "both" (flo and
/// kitti, the default). InputError(file, field) for an unknown or empty entry.
void parseFlowFiles(const std::string& list, StorageOptions& storage, const std::string& file,
                    const std::string& field);
/// The flow file list of `storage` as parseFlowFiles reads it ("flo+kitti").
std::string flowFilesName(const StorageOptions& storage);

/// What to write, and where. Frame k of the sequence is pose k of the trajectory.
struct SequenceSpec {
  std::filesystem::path dir;    ///< the sequence folder (the EuRoC "mav0" equivalent)
  std::string name;             ///< for "# file: '<name>'" lines; empty = last part of dir
  CameraIntrinsics intrinsics;  ///< renderer convention; files state the OpenCV one
  /// The lens the frames were rendered with; unset = the ideal pinhole of `intrinsics`. If set,
  /// its K must equal `intrinsics` (a mismatch is a bug and aborts). It decides the camera model
  /// every calibration file states (docs/output.md section 2) and which depth the depth PNGs
  /// hold: z-depth for pinhole and thin lens, the Euclidean ray distance for fisheye and
  /// panorama, whose frames carry the ray_depth pass instead of depth (docs/cameras.md 4).
  std::optional<LensModel> lens;
  PassMask passes = kRenderPasses;  ///< passes written to disk (the frames must carry them)
  /// Also write the rgb pass (frame.rgb, linear radiance before any camera response) as a
  /// float32 EXR with channels R, G, B next to the colour PNG (ASL cam0/data/<t>.exr).
  bool rgb_exr = false;
  StorageOptions storage;
  /// Caller's provenance (seed, versions, settings), merged into meta.json. Must be an object and
  /// must not use the writer's own keys (docs/output.md section 6); doing so is a bug (aborts).
  nlohmann::json meta = nlohmann::json::object();
  /// > 0: a second camera (cam1, the right one of a stereo pair) at this distance in metres along
  /// cam0's x axis (T_cam0_cam1 = translation (b, 0, 0)), same lens, rendered with every pass;
  /// formats that know stereo (asl) write its images as <folder with 0 -> 1>.
  double stereo_baseline_m = 0.0;
  /// Delete "*.tmp-*" left by a killed run when the writer is created. With several processes
  /// writing one folder at once (MPI ranks), only one of them may do this.
  bool remove_stale_temporaries = true;
  /// The sequence-level sensor files the folder holds besides the frames and the indexes
  /// (SequenceWriter::writeImu, writeBoxes, openEvents): they are part of what "finished" means.
  bool imu = false;     ///< imu0/
  bool boxes = false;   ///< boxes.json
  bool events = false;  ///< events0/
};

/// Everything a format may look at: the spec and the trajectory. Shared, read-only.
struct SequenceContext {
  SequenceSpec spec;
  Trajectory traj;
  /// spec.name, or the sequence folder's last component.
  std::string sequenceName() const;
  /// spec.lens, or the ideal pinhole of spec.intrinsics.
  LensModel lens() const;
  /// The pass the depth PNGs encode: DepthZ for pinhole and thin lens, DepthRay for fisheye
  /// and panorama (groundTruthDepthKind).
  Pass depthPngPass() const;
};

/// What the encoders of one frame read: the frame and the colour image its 8-bit PNGs show.
struct FrameView {
  const Frame& frame;         ///< every pass; frame.rgb is linear radiance
  const ImageF& rgb_display;  ///< frame.rgb after the camera response; frame.rgb if none
  const StorageOptions& storage;  ///< PNG level and EXR compression of every file
};

/// How one frame channel becomes one file. `key` names the resulting bytes: two outputs with the
/// same key are identical files, so the sequence writer encodes once and links (or copies) the
/// result, e.g. ASL cam0 and TUM rgb.
struct FrameEncoder {
  using Write = std::function<void(const std::filesystem::path&, const FrameView&)>;
  Pass pass;        ///< the frame channel it reads
  std::string key;  ///< e.g. "png8-srgb/rgb", "png16-depth-x5000/depth"
  Write write;      ///< encodes the channel and writes the file atomically
};

/// One image file written for every frame: <dir>/<folder>/<stem><suffix>.
struct FrameOutput {
  std::string folder;  ///< relative to the sequence folder, e.g. "cam0/data"
  std::string suffix;  ///< e.g. ".png", "_nyu.png", ".exr"
  FrameEncoder encoder;
  int camera = 0;  ///< 0 = cam0's frame, 1 = the stereo cam1's frame
  /// Every frame but the last (forward flow: frame k -> k + 1 needs a next frame).
  bool needs_next_frame = false;
  /// Every frame but the first (backward flow: frame k -> k - 1).
  bool needs_previous_frame = false;
  /// Is this output written for frame k of n?
  bool writtenFor(size_t k, size_t n) const {
    return (!needs_next_frame || k + 1 < n) && (!needs_previous_frame || k > 0);
  }
};

class FormatWriter {
 public:
  explicit FormatWriter(std::shared_ptr<const SequenceContext> ctx) : ctx_(std::move(ctx)) {}
  virtual ~FormatWriter() = default;
  FormatWriter(const FormatWriter&) = delete;
  FormatWriter& operator=(const FormatWriter&) = delete;

  /// Registry name ("asl", "tum").
  virtual std::string name() const = 0;
  /// File-name stem of frame k: its timestamp in this format's convention.
  virtual std::string frameStem(size_t k) const = 0;
  /// The index, list and calibration files: path relative to the sequence folder and text.
  /// Written (atomically) after every frame exists; deterministic (same inputs, same bytes).
  struct IndexFile {
    std::string path;
    std::string text;
  };
  virtual std::vector<IndexFile> indexFiles() const = 0;

  /// The per-frame image files (only passes in spec.passes), fixed at construction.
  const std::vector<FrameOutput>& outputs() const { return outputs_; }
  /// Paths (spec.dir / folder / stem+suffix) of the files frame k produces.
  std::vector<std::filesystem::path> frameFiles(size_t k) const;

 protected:
  const SequenceContext& ctx() const { return *ctx_; }
  /// Adds an output if its encoder's pass is in spec.passes (flow: for every frame but the last).
  void addOutput(std::string folder, std::string suffix, FrameEncoder encoder, int camera = 0);

 private:
  std::shared_ptr<const SequenceContext> ctx_;
  std::vector<FrameOutput> outputs_;
};

using FormatFactory = std::unique_ptr<FormatWriter> (*)(std::shared_ptr<const SequenceContext>);

/// Registered format names, sorted.
std::vector<std::string> formatNames();
/// Creates a format by name. The constructor validates what this format needs (timestamps,
/// passes) and throws InputError without writing anything. Unknown name: InputError with field
/// "--format" listing the valid names.
std::unique_ptr<FormatWriter> createFormat(const std::string& name,
                                           std::shared_ptr<const SequenceContext> ctx);
/// Splits "asl,tum" (spaces ignored) and checks each name; InputError(field "--format") for an
/// unknown, repeated or empty entry.
std::vector<std::string> parseFormatList(const std::string& list);

// ---- helpers shared by the format writers -------------------------------------------------

/// Encoders (the pass decides which Frame member is read; a pass of the wrong kind is a bug).
/// Rgb (reads FrameView::rgb_display), Albedo, Shading: 8-bit sRGB PNG.
FrameEncoder srgbPng(Pass pass);
FrameEncoder depthPng(Pass pass, double scale);  ///< DepthZ, DepthRay: 16-bit PNG, see depthToU16
FrameEncoder floatExr(Pass pass, std::vector<std::string> channel_names);  ///< float32 EXR
FrameEncoder normalPng(Pass pass);  ///< Normal: 16-bit RGB PNG, see encodeNormal16
FrameEncoder rawPng(Pass pass);     ///< Label (8-bit), Instance (16-bit): as stored
/// Flow or FlowBackward: Middlebury .flo (float32 u, v; no surface = 1e10, "unknown")
FrameEncoder flowFlo(Pass pass);
/// Flow or FlowBackward: KITTI 16-bit RGB PNG (64 u + 2^15, 64 v + 2^15, valid); |flow| >= 512 px
/// clamps
FrameEncoder flowKittiPng(Pass pass);
/// Flow or FlowBackward: float32 EXR, channels U and V, unknown flow = NaN (sensors/flow_io.h)
FrameEncoder flowExr(Pass pass);
/// Flow or FlowBackward: occlusion mask, 8-bit grey: 255 = hidden in the other frame or leaves
/// its image, 0 = seen in both or no surface
FrameEncoder flowOcclusionPng(Pass pass);

/// Fixed-point text with `decimals` digits; never "-0.000" (a tiny negative prints as zero).
std::string formatFixed(double v, int decimals);
/// Shortest round-trip text that always reads back as a float in YAML/JSON ("600.0", "319.5").
std::string formatFloat(double v);

}  // namespace inet
