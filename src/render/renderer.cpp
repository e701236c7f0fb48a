#include "render/renderer.h"

#include <algorithm>

#include "render/embree_scene.h"
#include "render/gt_passes.h"

namespace inet {

Renderer::Renderer(const Scene& scene, const std::string& integrator)
    : integrator_(makeIntegrator(integrator, "render options")) {
  scene_ = std::make_unique<EmbreeScene>(scene);
}

Renderer::~Renderer() = default;

void Renderer::render(const LensModel& lens, const CameraExposure& exposure,
                      const RenderOptions& options, uint32_t frame_index, Frame& frame) const {
  const CameraIntrinsics& K = lens.K;
  const Pose& T_world_camera = exposure.T_world_camera_open;
  // moving objects go where the window puts them; the exposure matters to the integrator and
  // the ground truth when the window has a duration and the camera or an object moves
  scene_->setWindow(exposure.scene_time_open_ns, exposure.span());
  const CameraExposure* moving =
      exposure.span() > 0 && (exposure.moving() || scene_->hasMotion()) ? &exposure : nullptr;
  const PassMask kAlbedo = static_cast<PassMask>(Pass::Albedo);
  const bool shading = has(options.passes, Pass::Shading);
  const bool rgb = has(options.passes, Pass::Rgb) || shading;  // shading is derived from rgb
  // Ground truth the RGB stage needs besides what was asked (denoiser guides, the albedo that
  // shading divides by) is traced in the same pass and left unflagged in frame.passes.
  PassMask helpers = 0;
  if (rgb && options.denoise)
    helpers |= kAlbedo | static_cast<PassMask>(Pass::Normal) | static_cast<PassMask>(Pass::DepthZ);
  if (shading) helpers |= kAlbedo;
  inet::renderGroundTruth(*scene_, lens, T_world_camera, options.passes | helpers, frame, moving);
  frame.passes &= ~helpers | options.passes;
  frame.passes &= ~(static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Shading));
  if (!rgb) {
    frame.rgb = {};
    frame.shading = {};
    return;
  }
  if (frame.rgb.width != K.width || frame.rgb.height != K.height || frame.rgb.channels != 3)
    frame.rgb = ImageF(K.width, K.height, 3);
  RenderContext ctx{*scene_, lens, T_world_camera, moving, options, frame_index, stats_};
  if (!options.denoise) {
    integrator_->render(ctx, frame.rgb, nullptr, nullptr);
  } else {
    ImageF variance(K.width, K.height, 3), emission(K.width, K.height, 3);
    integrator_->render(ctx, frame.rgb, &variance, &emission);
    // filter only the light reflected by the surfaces; lights in view stay sharp
    for (size_t i = 0; i < frame.rgb.data.size(); ++i) frame.rgb.data[i] -= emission.data[i];
    frame.rgb = denoise(frame.rgb, frame.albedo, frame.normal, frame.depth_z, &variance,
                        options.denoise_options);
    for (size_t i = 0; i < frame.rgb.data.size(); ++i) frame.rgb.data[i] += emission.data[i];
  }
  if (has(options.passes, Pass::Rgb)) frame.passes |= static_cast<PassMask>(Pass::Rgb);
  if (shading) {
    // illumination = rgb / albedo (albedo floored at 1e-3; no surface: 0)
    frame.shading = ImageF(K.width, K.height, 3);
    for (size_t i = 0; i < frame.shading.data.size(); ++i) {
      float a = frame.albedo.data[i];
      frame.shading.data[i] = a > 0.f ? frame.rgb.data[i] / std::max(a, 1e-3f) : 0.f;
    }
    frame.passes |= static_cast<PassMask>(Pass::Shading);
  } else {
    frame.shading = {};
  }
}

void Renderer::renderGroundTruth(const LensModel& lens, const Pose& T_world_camera, PassMask passes,
                                 Frame& frame) const {
  inet::renderGroundTruth(*scene_, lens, T_world_camera, passes, frame);
}

double Renderer::sceneBuildMs() const {
  return scene_->buildMs();
}
size_t Renderer::emissiveTriangleCount() const {
  return scene_->lights().triangleCount();
}

}  // namespace inet
