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
// The writer knows every file of the sequence folder: meta.json, the frames' files, each
// format's index files and the sequence-level sensor files (imu0/, boxes.json, events0/) that
// the sensor stage computes and hands over (writeImu, writeBoxes, openEvents).
//
// Frame k is pose k of the trajectory and carries its timestamp. Every file is written to a
// temporary name and renamed, so a file that exists is complete. One rule decides what is done
// (docs/output.md section 8): frame k is complete when all of its files exist (frameComplete),
// and the sequence is finished when every frame is complete and every sequence-level file
// exists (finished; events0/ by its sensor.yaml, written last). Sequence-level files are written
// only once every frame is complete. A rerun skips complete frames and a finished sequence. All
// output is byte-deterministic (same inputs, same bytes, whatever the thread count or order).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "dataset/boxes_json.h"
#include "dataset/asl_writer.h"
#include "dataset/format_writer.h"
#include "sensors/event_io.h"
#include "sensors/event_sim.h"
#include "sensors/imu.h"

namespace inet {

class EventsFolder;

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

  /// The sequence-level files whose names are known before they are written: every format's
  /// index files, imu0/'s files (spec.imu), boxes.json (spec.boxes) and events0/sensor.yaml
  /// (spec.events; the last file of events0/, which stands for the folder).
  std::vector<std::filesystem::path> sequenceFiles() const;
  /// Every frame complete and every sequenceFiles() file there: nothing is left to write.
  bool finished() const;

  /// imu0/ (spec.imu): data.csv (measured), data_noise_free.csv, biases.csv, sensor.yaml
  /// (sensors/imu_io.h formats them); `comment` goes into sensor.yaml.
  void writeImu(const ImuSequence& seq, const ImuOptions& opt, const std::string& comment) const;
  /// boxes.json (spec.boxes; dataset/boxes_json.h) with visible[k] the instances of frame k.
  void writeBoxes(const Scene& scene, const std::vector<InstanceBox>& boxes,
                  const std::vector<std::vector<InstanceVisibility>>& visible) const;
  /// events0/ (spec.events): whether it is complete (its sensor.yaml exists), and the folder
  /// to stream the event camera's samples into (times from the first frame).
  bool eventsComplete() const;
  std::unique_ptr<EventsFolder> openEvents(const CameraIntrinsics& K_events) const;

  /// The meta.json text this writer writes (deterministic).
  std::string metaJson() const;

 private:
  std::shared_ptr<const SequenceContext> ctx_;
  std::vector<std::unique_ptr<FormatWriter>> formats_;
};

/// events0/ of a sequence (docs/output.md, events0/), fed sample by sample by the event camera
/// (sensors/event_camera.h): events.txt (RPG: t x y p, t in s from t0), events.h5 (DSEC layout),
/// frames/data/<t>.exr (each sample's linear intensity, channel Y) with frames/data.csv, and
/// sensor.yaml, written last by finish(): a folder with sensor.yaml is complete.
class EventsFolder {
 public:
  /// Creates <dir>/events0/ and opens its event files (temporaries until finish()). `K` is the
  /// event camera's (renderer convention), `t0_ns` the time the files count from.
  EventsFolder(const std::filesystem::path& dir, TimeNs t0_ns, const CameraIntrinsics& K);
  ~EventsFolder();
  EventsFolder(const EventsFolder&) = delete;
  EventsFolder& operator=(const EventsFolder&) = delete;

  /// True if <dir>/events0/ is complete (its sensor.yaml exists).
  static bool complete(const std::filesystem::path& dir);
  /// One sample of the simulation at t_ns: its intensity image and the events since the last.
  void add(TimeNs t_ns, const ImageF& intensity, const std::vector<Event>& events);
  /// Closes the event files, writes frames/data.csv, then sensor.yaml (thresholds and noise of
  /// `sim`, the sample and event counts).
  void finish(const EventOptions& sim, size_t samples, size_t events);

 private:
  std::filesystem::path out_;
  TimeNs t0_ns_;
  CameraIntrinsics K_;
  EventTextWriter txt_;
  EventH5Writer h5_;
  std::string csv_;
};

/// depth0_noisy/ made again for a written ASL sequence (`interiornet depth-noise`): the files
/// generate writes for the depth_noisy pass, data/<t>.png (16-bit mm, each atomic), sensor.yaml
/// (depth0's calibration under depth0_noisy's comment: the bytes generate writes) and data.csv,
/// plus noise.yaml (the model's parameters; generate keeps them in meta.json). Opening removes
/// data.csv, so a folder being rewritten is never taken for complete; finish() writes
/// noise.yaml, sensor.yaml, then data.csv last: a folder with data.csv is complete.
class NoisyDepthFolder {
 public:
  /// Reads <sequence>/depth0/data.csv and depth0/sensor.yaml (InputError naming the file when
  /// missing or malformed; the rows must name <t>.png files), creates depth0_noisy/data/ and
  /// removes depth0_noisy/data.csv.
  explicit NoisyDepthFolder(const std::filesystem::path& sequence);
  /// depth0's frames, in order: frame k is row k.
  const std::vector<SequenceFrame>& frames() const { return frames_; }
  /// Writes frame k (z-depth in metres, 0 = no return) as depth0_noisy/data/<file of row k>.
  void writeFrame(size_t k, const ImageF& depth_m) const;
  /// noise.yaml (`noise_yaml`), sensor.yaml, then data.csv. Every frame must have been written.
  void finish(const std::string& noise_yaml) const;
  /// True if <sequence>/depth0_noisy/ is complete (its data.csv exists).
  static bool complete(const std::filesystem::path& sequence);

 private:
  std::filesystem::path sequence_, out_;
  std::vector<SequenceFrame> frames_;
  std::string depth_yaml_;
};

/// Writes <dir>/imu0/ (the files of SequenceWriter::writeImu) outside a sequence folder
/// (`interiornet imu`).
void writeImuFolder(const std::filesystem::path& dir, const ImuSequence& seq,
                    const ImuOptions& opt, const std::string& comment);

/// Throws InputError(dir, "--out", ...) unless `dir` is a writable folder or could be created
/// (its nearest existing ancestor is a writable folder). Writes nothing.
void checkOutputFolder(const std::filesystem::path& dir);

}  // namespace inet
