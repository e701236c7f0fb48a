#pragma once
// One rendered frame: linear RGB and every ground-truth channel, all width x height, all from the
// same primary rays. A pixel that sees nothing has depth 0, normal (0,0,0), label 0, instance 0.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace inet {

/// The channels a frame can carry. Ground truth passes are exact (never filtered): they come
/// from the ray through the pixel centre.
enum class Pass : uint32_t {
  Rgb = 1u << 0,       ///< linear RGB radiance, path traced, 3 x float
  DepthZ = 1u << 1,    ///< z-depth along the optical axis, metres, 1 x float
  DepthRay = 1u << 2,  ///< Euclidean distance camera centre -> surface (paper's depth), metres
  Normal = 1u << 3,    ///< unit surface normal in the camera frame, facing the camera, 3 x float
  Label = 1u << 4,     ///< NYU40 class id, 1 x uint8
  Instance = 1u << 5,  ///< instance id, 1 x uint16
  Albedo = 1u << 6,    ///< linear diffuse reflectance ("pure texture"), 3 x float
  Shading = 1u << 7,   ///< illumination only: rgb / albedo per channel (the paper's "shading"
                       ///< RGB variation), 3 x float; derived from the RGB pass, not exact
  // Derived by the sensor stage from the passes above (the renderer ignores these bits):
  DepthNoisy = 1u << 8,  ///< Kinect-like z-depth (sensors/depth_noise.h), metres, 0 = no return
  Flow = 1u << 9,        ///< forward optical flow to the next frame (sensors/optical_flow.h)
  FlowBackward = 1u << 10,  ///< backward optical flow to the previous frame
};
using PassMask = uint32_t;
/// What the renderer makes: RGB, the exact ground truth and shading.
constexpr PassMask kRenderPasses = 0xff;
/// Every pass, the derived ones included.
constexpr PassMask kAllPasses = 0x7ff;
/// The exact passes: one ray through each pixel centre (everything but rgb and shading).
constexpr PassMask kGroundTruthPasses = 0x7e;
inline bool has(PassMask m, Pass p) {
  return (m & static_cast<PassMask>(p)) != 0;
}

/// Name of a pass as used on the command line ("rgb", "depth", "ray_depth", "normal", "label",
/// "instance", "albedo", "shading", "depth_noisy", "flow", "flow_bwd").
std::string passName(Pass p);
/// Parses "rgb,depth,..." or "all" into a mask; throws InputError(where, "--passes", ...).
PassMask parsePassList(const std::string& list, const std::string& where);

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

struct Frame {
  PassMask passes = 0;
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
