#include "render/renderer.h"

#include <algorithm>

#include "core/error.h"
#include "render/embree_scene.h"
#include "render/gt_passes.h"

namespace inet {

Renderer::Renderer(const Scene& scene, const std::string& integrator)
    : integrator_(makeIntegrator(integrator, "render options")) {
  scene_ = std::make_unique<EmbreeScene>(scene);
}

Renderer::~Renderer() = default;

void Renderer::render(const LensModel& lens, const CameraExposure& exposure,
                      const RenderOptions& options, uint32_t frame_index, Frame& frame,
                      RgbLayers* layers) const {
  const CameraIntrinsics& K = lens.K;
  const Pose& T_world_camera = exposure.T_world_camera_open;
  // moving objects go where the window puts them; the exposure matters to the integrator and
  // the ground truth when the window has a duration and the camera or an object moves
  scene_->setWindow(exposure.scene_time_open_ns, exposure.span());
  const CameraExposure* moving =
      exposure.span() > 0 && (exposure.moving() || scene_->hasMotion()) ? &exposure : nullptr;
  const bool shading = has(options.passes, Pass::Shading);
  // shading is rgb / albedo: the path tracer runs for it, and the albedo is a helper
  const PassMask shading_needs = passInfo(Pass::Shading).needs;
  const bool rgb = has(options.passes, Pass::Rgb) || shading;
  const bool denoising = rgb && options.denoise && layers == nullptr;
  // Ground truth the RGB stage needs besides what was asked (denoiser guides, the albedo that
  // shading divides by, what the caller's filters need) is traced in the same pass and left
  // unflagged in frame.passes.
  PassMask helpers = 0;
  // (the label: class-edge pixels are demodulated by the albedo pass, denoiseRgb)
  if (denoising) helpers |= passMask(Pass::Albedo, Pass::Normal, Pass::DepthZ, Pass::Label);
  if (rgb && layers)
    helpers |= passMask(Pass::Albedo, Pass::Normal, Pass::DepthZ, Pass::DepthRay, Pass::Instance,
                        Pass::Label);
  if (shading) helpers |= shading_needs & kGroundTruthPasses;
  inet::renderGroundTruth(*scene_, lens, T_world_camera, options.passes | helpers, frame, moving);
  frame.passes &= ~helpers | options.passes;
  frame.passes &= ~passMask(Pass::Rgb, Pass::Shading);
  if (!rgb) {
    frame.rgb = {};
    frame.shading = {};
    return;
  }
  auto allocate = [&](ImageF& image, int channels = 3) {
    if (image.width != K.width || image.height != K.height || image.channels != channels)
      image = ImageF(K.width, K.height, channels);
  };
  allocate(frame.rgb);
  INET_CHECK(!options.spp_multiplier || (options.spp_multiplier->width == K.width &&
                                         options.spp_multiplier->height == K.height));
  RenderContext ctx{*scene_, lens, T_world_camera, moving, options, frame_index, stats_};
  // too few samples for a variance of their own: the neighbourhood's (denoise.h)
  const bool few_samples = options.spp < kNeighbourhoodVarianceBelowSpp;
  auto reflectedOf = [&](const RgbLayers& l) {  // rgb - emission: what the filters see
    ImageF r = frame.rgb;
    for (size_t i = 0; i < r.data.size(); ++i) r.data[i] -= l.emission.data[i];
    return r;
  };
  // the layers' variances from the neighbourhood, on the footprint's albedo, which the filters
  // demodulate by
  auto estimateFromNeighbourhood = [&](RgbLayers& l) {
    const ImageF reflected = reflectedOf(l);
    ImageF rest = reflected;
    for (size_t i = 0; i < rest.data.size(); ++i) rest.data[i] -= l.diffuse.data[i];
    std::vector<ImageF> v = neighbourhoodVariance({&reflected, &l.diffuse, &rest}, l.albedo,
                                                  frame.normal, frame.depth_z,
                                                  options.denoise_options);
    l.variance = std::move(v[0]);
    l.diffuse_variance = std::move(v[1]);
    l.rest_variance = std::move(v[2]);
  };
  // the view through window panes is denoised on its own guides wherever the colour will be
  // (filterWindowView), before anything else reads the layers; a scene without panes has none
  WindowViewLayers window_view;
  WindowViewLayers* const view = options.denoise && scene_->hasPanes() ? &window_view : nullptr;
  if (view) {
    for (ImageF* image : {&view->light, &view->variance, &view->albedo, &view->normal})
      allocate(*image);
    allocate(view->coverage, 1);
    allocate(view->depth, 1);
  }
  auto filterView = [&](ImageF& emission) {
    if (view) filterWindowView(frame.rgb, emission, *view, options.denoise_options, few_samples);
  };
  if (layers) {
    for (ImageF* image : {&layers->emission, &layers->variance, &layers->diffuse,
                          &layers->diffuse_variance, &layers->rest_variance, &layers->albedo})
      allocate(*image);
    allocate(layers->view_alpha, 1);
    integrator_->render(ctx, frame.rgb,
                        {&layers->emission, &layers->variance, &layers->diffuse,
                         &layers->diffuse_variance, &layers->rest_variance, &layers->albedo,
                         &layers->view_alpha, view});
    filterView(layers->emission);
    if (few_samples) estimateFromNeighbourhood(*layers);
  } else if (!denoising) {
    integrator_->render(ctx, frame.rgb, {});
  } else {
    // the layers denoiseRgb reads: the footprint's albedo it demodulates by, and the diffuse
    // light apart from the rest, which it filters without the albedo
    RgbLayers own;
    for (ImageF* image : {&own.emission, &own.variance, &own.diffuse, &own.diffuse_variance,
                          &own.rest_variance, &own.albedo})
      allocate(*image);
    IntegratorOutputs outputs{&own.emission,      &own.variance,      &own.diffuse,
                              &own.diffuse_variance, &own.rest_variance, &own.albedo};
    outputs.window_view = view;
    integrator_->render(ctx, frame.rgb, outputs);
    filterView(own.emission);
    if (few_samples) estimateFromNeighbourhood(own);
    denoiseRgb(frame, own, options.denoise_options);
    if (!has(options.passes, Pass::Label)) frame.label = {};  // a helper only, not asked for
  }
  if (has(options.passes, Pass::Rgb)) frame.passes |= bit(Pass::Rgb);
  if (shading) {
    shadingFromRgb(frame);
  } else {
    frame.shading = {};
  }
}

void shadingFromRgb(Frame& frame) {
  // illumination = rgb / albedo (albedo floored at 1e-3; no surface: 0)
  frame.shading = ImageF(frame.rgb.width, frame.rgb.height, 3);
  for (size_t i = 0; i < frame.shading.data.size(); ++i) {
    float a = frame.albedo.data[i];
    frame.shading.data[i] = a > 0.f ? frame.rgb.data[i] / std::max(a, 1e-3f) : 0.f;
  }
  frame.passes |= bit(Pass::Shading);
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
