#pragma once
// Reads back a sequence folder that `interiornet generate` wrote in the ASL layout
// (docs/output.md), for the evaluations that run on the images themselves
// (eval/feature_consistency.h, eval/rgbd_odometry.h).
//
// Frame k is row k of cam0/data.csv. Every other folder names frame k's file by the same stamp
// <t> (docs/output.md section 4), so the reader builds paths from the stamp and never needs the
// other data.csv files; it only checks that the flow and label folders exist at all, to say
// which pass is missing before the first image is read.
//
// Conventions, as written (docs/output.md section 3):
//   cam0/data/<t>.png         8-bit sRGB, RGB order
//   depth0/data/<t>.png       uint16 z-depth in mm (pinhole, thin lens; ray distance for the
//                             others), 0 = none
//   label0/data/<t>_nyu.png   uint8 NYU40 id, 0 = void
//   flow0/data/<t>.flo        forward flow frame k -> k+1 in pixels, stored at frame k (every
//                             frame but the last), unknown = no surface; or, when the sequence
//                             was stored without .flo, <t>.exr (same floats) or <t>.png (KITTI)
//   flow0/data/<t>_occ.png    255 where frame k's point is hidden in frame k+1 or leaves it
//   meta.json                 camera.width/height, camera.renderer {fx, fy, cx, cy} (pixel
//                             centres at +0.5; camera.opencv holds cx - 0.5), camera.lens
// Every reader throws InputError naming the file and, where there is one, the field (a
// missing file, a malformed row, an image of the wrong size).
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/pose.h"
#include "dataset/asl_writer.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/lens.h"
#include "trajectory/trajectory.h"

namespace inet {

class SequenceReader {
 public:
  /// Reads meta.json and cam0/data.csv (InputError naming the file: a missing folder or file,
  /// a meta.json without the camera fields or of another meta_format_version, a malformed or
  /// empty data.csv, stamps that do not increase).
  explicit SequenceReader(const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }
  /// The folder's name (meta.json "sequence" names the same thing).
  std::string name() const;
  /// Intrinsics in the renderer convention; cxOpenCV()/cyOpenCV() give the files' convention.
  const CameraIntrinsics& intrinsics() const { return K_; }
  LensType lens() const { return lens_; }
  const std::vector<SequenceFrame>& frames() const { return frames_; }
  size_t frameCount() const { return frames_.size(); }

  /// Is there a label0 folder (the NYU40 pass)?
  bool hasLabels() const;
  /// InputError naming flow0/data.csv when the sequence has no forward flow.
  void requireFlow() const;

  /// cam0 colour of frame k: 3 channels, sRGB codes.
  ImageU8 colour(size_t k) const;
  /// depth0 of frame k in metres (z-depth for pinhole and thin lens), 0 = no depth.
  ImageF depth(size_t k) const;
  /// label0 NYU40 ids of frame k.
  ImageU8 labels(size_t k) const;
  /// Forward flow frame k -> k+1 (k + 1 < frameCount()) with its occlusion mask: `valid` from
  /// the flow file's known pixels (.flo, else .exr, else the KITTI .png), `occluded` (1 = hidden
  /// in k+1) from <t>_occ.png.
  FlowField flow(size_t k) const;

  /// Ground-truth T_world_camera of every frame, in frame order, stamped as the frames:
  /// state_groundtruth_estimate0/data.csv, or groundtruth.txt when the sequence has only the
  /// TUM layout's. InputError naming the file when a frame's stamp has no pose there.
  Trajectory groundTruth() const;

 private:
  std::filesystem::path framePath(const char* folder, size_t k, const char* suffix) const;
  /// Frame k's 8-bit PNG in `folder` with `suffix`, checked to be `channels` x the camera size.
  ImageU8 png8(const char* folder, size_t k, const char* suffix, int channels) const;
  template <class Img>
  void checkSize(const Img& img, int channels, const std::filesystem::path& path) const;

  std::filesystem::path dir_;
  CameraIntrinsics K_;
  LensType lens_ = LensType::Pinhole;
  std::vector<SequenceFrame> frames_;
};

}  // namespace inet
