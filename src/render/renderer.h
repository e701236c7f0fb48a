#pragma once
// The render stage's public face: build once per scene, then render frames (RGB by the chosen
// integrator, ground-truth passes from the same camera). Downstream stages see only Frames.
#include <memory>

#include "render/camera.h"
#include "render/passes.h"
#include "render/integrator.h"
#include "render/lens.h"
#include "scene/scene.h"

namespace inet {

class EmbreeScene;

/// The shading pass from the frame's rgb and albedo (rgb / albedo, albedo floored at 1e-3; 0
/// where there is no surface), flagged in frame.passes. Renderer::render calls it; a caller that
/// filters the colour afterwards (temporal reuse, the denoiser) calls it again.
void shadingFromRgb(Frame& frame);

class Renderer {
 public:
  /// Builds the acceleration structure; throws InputError for an unknown integrator name.
  Renderer(const Scene& scene, const std::string& integrator = "path");
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders the passes in options.passes into `frame` (buffers are reused across calls).
  /// A moving `exposure` gives motion blur (and rolling shutter when its readout time is set) in
  /// RGB; ground truth is traced per row from the pose at the middle of that row's exposure.
  void render(const LensModel& lens, const CameraExposure& exposure, const RenderOptions& options,
              uint32_t frame_index, Frame& frame) const {
    render(lens, exposure, options, frame_index, frame, nullptr);
  }
  /// The same, and with `layers` not null: frame.rgb is left unfiltered (options.denoise is
  /// ignored), `layers` receives its parts, and the frame also carries the guides the caller's
  /// filters need (albedo, normal, z-depth, ray depth, label, instance), flagged in frame.passes only
  /// when options.passes asked for them.
  void render(const LensModel& lens, const CameraExposure& exposure, const RenderOptions& options,
              uint32_t frame_index, Frame& frame, RgbLayers* layers) const;
  void render(const LensModel& lens, const Pose& T_world_camera, const RenderOptions& options,
              uint32_t frame_index, Frame& frame) const {
    render(lens, CameraExposure::fixed(T_world_camera), options, frame_index, frame);
  }
  /// The same for a plain pinhole camera.
  void render(const CameraIntrinsics& K, const Pose& T_world_camera, const RenderOptions& options,
              uint32_t frame_index, Frame& frame) const {
    render(LensModel::pinhole(K), T_world_camera, options, frame_index, frame);
  }
  /// Only the ground-truth passes (cheap: one coherent ray per pixel).
  void renderGroundTruth(const LensModel& lens, const Pose& T_world_camera, PassMask passes,
                         Frame& frame) const;
  void renderGroundTruth(const CameraIntrinsics& K, const Pose& T_world_camera, PassMask passes,
                         Frame& frame) const {
    renderGroundTruth(LensModel::pinhole(K), T_world_camera, passes, frame);
  }
  /// Counts rays and samples of subsequent renders into `stats` (nullptr: stop counting).
  void setStats(RenderStats* stats) { stats_ = stats; }
  double sceneBuildMs() const;
  size_t emissiveTriangleCount() const;

 private:
  std::unique_ptr<EmbreeScene> scene_;
  std::unique_ptr<Integrator> integrator_;
  RenderStats* stats_ = nullptr;
};

}  // namespace inet
