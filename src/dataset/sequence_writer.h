#pragma once
// Writes one sequence folder in one or more formats side by side (docs/output.md).
//
// Typical use from `interiornet generate`:
//
//   SequenceSpec spec;
//   spec.dir = out_dir;  spec.intrinsics = K;  spec.passes = parsePassList(passes, "--passes");
//   spec.meta = {{"seed", seed}, {"spp", spp}, {"command_line", argv_joined}, ...};
//   SequenceWriter writer(spec, trajectory, parseFormatList(format_list));  // validates, meta.json
//   for (size_t k = 0; k < writer.frameCount(); ++k)          // or a parallel loop over k
//     if (!writer.frameComplete(k)) writer.writeFrame(k, renderer.render(trajectory.poses[k]));
//   writer.finish();                                           // data.csv, rgb.txt, ... last
//
// Frame k is pose k of the trajectory and carries its timestamp. Every file is written to a
// temporary name and renamed, so a file that exists is complete: a rerun skips frames with
// frameComplete(k) and only redoes what a killed run left unfinished. All output is
// byte-deterministic (same inputs, same bytes, whatever the thread count or frame order).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "dataset/format_writer.h"

namespace inet {

class SequenceWriter {
 public:
  /// Validates everything before writing anything: format names (InputError field "--format"
  /// listing the valid ones), trajectory (non-empty, finite poses, timestamps >= 0 and strictly
  /// increasing), intrinsics and lens (no z-depth pass for fisheye or panorama, field
  /// "--passes"), rgb_exr (needs the rgb pass and the asl format, field "--hdr"), what each
  /// format needs (e.g. TUM: rgb + depth passes, 1 us apart),
  /// and that spec.dir can be created and written (InputError naming it, field "--out"). Then
  /// creates the folders, removes stale "*.tmp-*" files of a killed run (if
  /// spec.remove_stale_temporaries) and writes meta.json.
  SequenceWriter(SequenceSpec spec, const Trajectory& traj,
                 const std::vector<std::string>& formats);
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  size_t frameCount() const;
  const SequenceSpec& spec() const;
  /// Names of the formats being written, in the order given.
  std::vector<std::string> formats() const;

  /// Every file frame k produces, over all formats.
  std::vector<std::filesystem::path> frameFiles(size_t k) const;
  /// True if every file of frame k exists (files are atomic, so existing means complete).
  bool frameComplete(size_t k) const;
  /// Encodes and writes every file of frame k, files in parallel (TBB). Thread-safe for
  /// different k; writing the same k from two threads at once is not allowed. The frame must
  /// carry every pass of spec.passes at the size of spec.intrinsics (a violation is a bug and
  /// aborts). frame.rgb is linear radiance (what spec.rgb_exr writes); `rgb_display`, if given,
  /// is the same image after the camera response (exposure, noise, tone curve), which the 8-bit
  /// colour PNGs encode instead of frame.rgb. File errors throw InputError naming the file.
  /// With spec.stereo_baseline_m > 0, `right` (and `right_display`, as rgb_display) is cam1's
  /// frame, which must then be given; the flow pass is not expected in the last frame.
  void writeFrame(size_t k, const Frame& frame, const ImageF* rgb_display = nullptr,
                  const Frame* right = nullptr, const ImageF* right_display = nullptr) const;
  /// Writes the index, list and calibration files of every format, atomically. Call once after
  /// all frames; throws InputError naming the first missing frame file if a frame is incomplete.
  void finish() const;

  /// The meta.json text this writer writes (deterministic).
  std::string metaJson() const;

 private:
  std::shared_ptr<const SequenceContext> ctx_;
  std::vector<std::unique_ptr<FormatWriter>> formats_;
};

/// Throws InputError(dir, "--out", ...) unless `dir` is a writable folder or could be created
/// (its nearest existing ancestor is a writable folder). Writes nothing.
void checkOutputFolder(const std::filesystem::path& dir);

}  // namespace inet
