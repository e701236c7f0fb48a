#pragma once
// A preview of one frame of the designed path (POST /api/preview/frame): a ground-truth pass
// at once (one coherent ray per pixel) or the path-traced colour at a few samples per pixel, as
// an 8-bit PNG the page shows beside the path. The renderer (render/renderer.h) is built for the
// layout at the first request and kept.
//
// Request: {"position": [x, y, z], "quaternion_xyzw": [x, y, z, w]   (a pose of the path:
//           T_world_camera, OpenCV camera axes),
//           "width": 16..1024 (160), "height": 16..1024 (120), "fx": pixels (150; fy = fx,
//           principal point at the centre; pinhole and thin lens), "spp": 1..64 (4, rgb only),
//           "pass": rgb | depth | normal | label | albedo (rgb),
//           the sequence's lens and camera response (studio/camera_keys.h: "lens",
//           "aperture_m", "focus_m", "fisheye_fov_deg", "distortion"; "exposure", "exposure_ev",
//           "tone", "sensor_noise")}
// Every pass goes through the lens (ground truth along its chief rays, as the sequence's).
// Images: rgb denoised (the renderer's edge-aware filter), exposed as the sequence would be
// (auto: this frame metered by the sequence's rule, its log-average luminance to middle grey in
// third stops; fixed: radiance 1 is white), then exposure_ev, sensor noise and the tone curve
// (ResponseSettings::apply), sRGB-encoded; depth the sequence's depth (z-depth; the ray
// distance for a fisheye or panorama) as grey, near white, 0 where nothing was hit (outside a
// fisheye's circle); normal (n + 1) / 2 in the camera frame's colours as written by the
// dataset; label the NYU40 class colours; albedo sRGB.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "pipeline/settings.h"
#include "render/camera.h"
#include "render/lens.h"
#include "render/passes.h"
#include "studio/studio_layout.h"

namespace inet {
class Renderer;
}

namespace inet::studio {

struct FramePreviewRequest {
  Pose T_world_camera;
  LensModel lens = LensModel::pinhole(CameraIntrinsics::centred(160, 120, 150));
  ResponseSettings response;
  bool auto_exposure = true;
  int spp = 4;
  Pass pass = Pass::Rgb;
};

/// Checks the request (InputError("", key, problem)).
FramePreviewRequest parseFramePreview(const nlohmann::json& body);

class FramePreviewer {
 public:
  /// Previews of `layout`; PNGs pass through files in `tmp_dir` (private to the server).
  FramePreviewer(std::shared_ptr<const StudioLayout> layout, std::filesystem::path tmp_dir);
  ~FramePreviewer();
  /// The PNG's bytes.
  std::string png(const FramePreviewRequest& req);

 private:
  const Renderer& renderer();
  std::shared_ptr<const StudioLayout> layout_;
  std::filesystem::path tmp_dir_;
  std::mutex mutex_;
  std::unique_ptr<Renderer> renderer_;
  uint64_t serial_ = 0;
};

}  // namespace inet::studio
