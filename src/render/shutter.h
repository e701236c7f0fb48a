#pragma once
// Shutter timing (global and rolling, with motion blur) and pose interpolation: pure maths on
// int64 nanoseconds (STYLE.md 1.9).
//
// Timing convention (docs/cameras.md):
//  - frame_t_ns, a frame's timestamp, is the START of exposure of image row 0 (shutter open).
//  - Row j (0 = top) opens at rowStart = frame_t + readout * j / (h - 1) and is exposed for
//    exposure_ns: window [rowStart, rowStart + exposure]. Global shutter: readout = 0, so every
//    row shares [frame_t, frame_t + exposure].
//  - RGB (motion blur): a sample of row j at shutter sample u in [0, 1) is taken at
//    sampleTime = rowStart(j) + u * exposure, i.e. uniformly over the row's window.
//  - Ground truth (depth, normals, labels, flow) shows the scene at the CENTRE of each row's
//    window, groundTruthTime(j) = rowStart(j) + exposure / 2: the time centroid of the blur
//    (SceneNet RGB-D's alpha = 0.5 between shutter-open and shutter-close poses). A frame's
//    single ground-truth pose is the one at frameCentreTime = frame_t + (readout + exposure) / 2,
//    which for a global shutter is exactly the instant of every ground-truth pass.
//  - With the defaults (exposure = readout = 0) all of these times equal frame_t.
#include <string>

#include "core/pose.h"

namespace inet {

struct Shutter {
  TimeNs exposure_ns = 0;  ///< each row's exposure time; 0 = instantaneous (no motion blur)
  TimeNs readout_ns = 0;   ///< rolling shutter: time from first to last row start; 0 = global

  bool global() const { return readout_ns == 0; }
  /// Throws InputError(where, field, ...) unless 0 <= exposure, readout <= 100 s.
  void validate(const std::string& where) const;
  std::string toString() const;
};

/// Exposure start of `row` (0 = top) of an image with `height` rows, rounded to the nearest ns:
/// frame_t + readout * row / (height - 1). Precondition: 0 <= row < height.
TimeNs rowStart(const Shutter& s, TimeNs frame_t_ns, int row, int height);
/// Time of a motion-blur sample of `row`: rowStart + u * exposure, u in [0, 1) (rounded to ns).
TimeNs sampleTime(const Shutter& s, TimeNs frame_t_ns, int row, int height, float u);
/// The instant ground-truth passes show for `row`: the centre of its exposure window.
TimeNs groundTruthTime(const Shutter& s, TimeNs frame_t_ns, int row, int height);
/// The centre of the whole frame's exposure (first row open to last row close): the time of the
/// frame's single ground-truth pose.
TimeNs frameCentreTime(const Shutter& s, TimeNs frame_t_ns);

}  // namespace inet
