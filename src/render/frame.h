#pragma once
// One rendered frame: linear RGB and every ground-truth channel, all width x height, all from the
// same primary rays. A pixel that sees nothing has depth 0, normal (0,0,0), label 0, instance 0.
#include <cstdint>
#include <string>

#include "core/image.h"

namespace inet {

/// A set of passes: the bits of render/passes.h's Pass (the table of every pass lives there).
using PassMask = uint32_t;

/// A dense optical flow field with its masks, all width x height (sensors/optical_flow.h).
struct FlowField {
  ImageF flow;       ///< 2 channels (u, v), pixels, +u right, +v down; 0 where valid == 0
  ImageU8 valid;     ///< 1 = the pixel has depth and its point has an image in the other frame
                     ///< (possibly outside the image bounds)
  ImageU8 occluded;  ///< 1 = the pixel has depth but its point is not visible in the other frame
                     ///< (hidden, behind the camera, outside the image); empty when read from a
                     ///< file (neither format stores it)
  int width() const { return flow.width; }
  int height() const { return flow.height; }
  /// Size, valid and occluded pixel counts, largest valid |flow|.
  std::string toString() const;
};

/// The passes of one frame (render/passes.h kPassTable says which member holds which pass).
struct Frame {
  PassMask passes = 0;  ///< which passes the members hold
  ImageF rgb;         ///< 3 channels
  ImageF depth_z;     ///< 1 channel
  ImageF depth_ray;   ///< 1 channel
  ImageF normal;      ///< 3 channels
  ImageU8 label;      ///< 1 channel, NYU40
  ImageU16 instance;  ///< 1 channel
  ImageF albedo;      ///< 3 channels
  ImageF shading;     ///< 3 channels
  ImageF depth_noisy;     ///< 1 channel, metres, 0 = no return
  FlowField flow;      ///< frame k -> k + 1
  FlowField flow_bwd;  ///< frame k -> k - 1
};

}  // namespace inet
