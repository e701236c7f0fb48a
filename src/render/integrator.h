#pragma once
// The integrator interface (how the RGB pass is computed) and its registry. Issue 3 grows the
// path tracer behind this interface; a new integrator is one .cpp plus one line in
// integrator.cpp's table.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/pose.h"
#include "render/camera.h"
#include "render/denoise.h"
#include "render/passes.h"
#include "render/radiance_cache.h"
#include "render/lens.h"
#include "render/shutter.h"

namespace inet {

class EmbreeScene;
struct WindowViewLayers;

/// Everything that controls how a frame is rendered. Part of a dataset's provenance.
struct RenderOptions {
  int spp = 16;         ///< samples per pixel for the RGB pass
  /// Per-pixel multiplier of spp (values 0 and 1 both mean 1), or nullptr: pixel (x, y) takes
  /// spp x multiplier samples, drawn exactly as a render at that spp would draw them. Not owned;
  /// the image must have the camera's size. Temporal reuse (sensors/temporal_reuse.h) gives
  /// the points a sequence has not seen before more samples than those it has.
  const ImageU8* spp_multiplier = nullptr;
  int max_bounces = 8;  ///< scattering events per path (1 = direct light only)
  uint64_t seed = 0;    ///< global seed of the counter-based RNG
  PassMask passes = kRenderPasses;
  std::string integrator = "path";
  bool denoise = false;  ///< edge-aware denoising of the RGB pass (never of ground truth)
  /// Visibility-aware light picks (light_cache.h): a sparse training pass per frame learns
  /// what share of each light's shadow rays gets through, region by region. Unbiased.
  bool light_cache = false;
  /// Sunlight through windows by way of the surfaces it lands on (path_tracer.cpp, "sun
  /// photons"): each frame traces photons from the sun through the window panes, and every
  /// path vertex also connects to one of the sunlit points they found, weighed by MIS against
  /// finding that point by BSDF sampling. Unbiased; a no-op without a sun or panes.
  bool sun_photons = false;
  /// Lamp light by way of the surfaces near the lamp it lands on (path_tracer.cpp, "lamp
  /// photons"): each frame traces photons from every point and spot light, keeps those that
  /// land within half a metre (a lamp's own shade, back plate or reflector), and every path
  /// vertex also connects to one of them, weighed by MIS. Unbiased; a no-op without such lights.
  bool lamp_photons = false;
  /// Light past a path's first rough vertex from a per-frame cache (radiance_cache.h): a
  /// sparse training pass of full paths records what rough surfaces send on, cell by cell, and
  /// the frame's paths stop at the vertex after their first rough scattering when it is rough
  /// and its cell is trained, taking the cell's mean. The cache's noise is shared by the whole
  /// frame, so not unbiased for one frame; optional. The paths' first rough vertex stays exact.
  bool radiance_cache = false;
  RadianceCache::Config radiance_cache_config;
  /// Tuned on ../shared/bench against the 1024-spp Cycles reference (sweep of iterations 3-7
  /// and sigma_color 1-8 at 32 spp: 3 and 2 gave the lowest RMSE, 0.00465 vs 0.00565 for the
  /// filter's generic defaults).
  /// mean_levels 5: the output keeps the input's light over 125-px surface means; default
  /// sequence walls and floors of an apartment were 4.6-5.7 % dark without it (denoise.h).
  DenoiseOptions denoise_options = [] {
    DenoiseOptions d;
    d.iterations = 3;
    d.sigma_color = 2.f;
    d.mean_levels = 5;
    return d;
  }();
};

/// How the camera moves while a frame is exposed: the pose when row 0 starts its exposure and
/// the pose when the last row ends it, interpolated (linear position, slerp rotation) in
/// between. A static camera has open == close and a zero shutter.
struct CameraExposure {
  Pose T_world_camera_open;
  Pose T_world_camera_close;
  Shutter shutter;  ///< exposure and rolling-shutter readout times
  /// Optional poses inside the window (time since the window opened, pose), sorted, e.g. the
  /// trajectory's own samples; `at` then interpolates piecewise through open, these, close.
  std::vector<std::pair<TimeNs, Pose>> knots;
  /// Scene time (ns since the sequence's first frame) at which row 0 starts its exposure; moving
  /// objects (Object::motion) are placed by it.
  TimeNs scene_time_open_ns = 0;

  static CameraExposure fixed(const Pose& T_world_camera, TimeNs scene_time_ns = 0) {
    return {T_world_camera, T_world_camera, {}, {}, scene_time_ns};
  }
  TimeNs span() const { return shutter.readout_ns + shutter.exposure_ns; }
  bool moving() const {
    if (span() <= 0) return false;
    auto same = [&](const Pose& p) {
      return p.t == T_world_camera_open.t && p.q.coeffs() == T_world_camera_open.q.coeffs();
    };
    if (!same(T_world_camera_close)) return true;
    for (const auto& k : knots)
      if (!same(k.second)) return true;
    return false;
  }
  /// Pose at `dt_ns` after the exposure of row 0 started.
  Pose at(TimeNs dt_ns) const {
    if (span() <= 0) return T_world_camera_open;
    TimeNs t0 = 0;
    Pose p0 = T_world_camera_open;
    for (const auto& [tk, pk] : knots) {
      if (dt_ns <= tk) return tk == t0 ? pk : interpolatePose(p0, t0, pk, tk, dt_ns);
      t0 = tk;
      p0 = pk;
    }
    return span() == t0 ? T_world_camera_close
                        : interpolatePose(p0, t0, T_world_camera_close, span(), dt_ns);
  }
  /// Pose for the ground truth of row `row` (the middle of that row's exposure).
  Pose groundTruthPose(int row, int height) const {
    return at(groundTruthTime(shutter, 0, row, height));
  }
};

/// Work counters of a render (for `interiornet bench`); filled when a RenderContext points here.
struct RenderStats {
  std::atomic<uint64_t> rays{0};     ///< closest-hit plus shadow rays traced
  std::atomic<uint64_t> samples{0};  ///< camera samples (paths)
};

/// The inputs of one frame's render.
struct RenderContext {
  const EmbreeScene& scene;
  const LensModel& lens;
  const Pose& T_world_camera;      ///< the pose of a static camera
  const CameraExposure* exposure;  ///< motion blur / rolling shutter, or nullptr if static
  const RenderOptions& options;
  uint32_t frame_index;  ///< keys the RNG, so each frame gets its own independent samples
  RenderStats* stats = nullptr;
};

/// What an integrator writes besides the colour, each optional (nullptr: not wanted). Every image
/// has 3 channels and the camera's size and is allocated by the caller. With e = emission and
/// d = diffuse, rgb = e + d + rest, where
///   e    is the light emitted by the first surface seen (lights in view: never filtered),
///   d    is the light the first surface reflects through its view-independent (diffuse) lobes
///        (bsdf.h evalBsdfDiffuse): what temporal reuse may carry from frame to frame,
///   rest is what it reflects or transmits through specular lobes (mirrors, coatings, glass).
/// Variances are per-pixel variances of the mean, from the same samples.
struct IntegratorOutputs {
  ImageF* emission = nullptr;
  ImageF* variance = nullptr;          ///< of rgb - emission (the denoiser's guide)
  ImageF* diffuse = nullptr;
  ImageF* diffuse_variance = nullptr;  ///< of diffuse
  ImageF* rest_variance = nullptr;     ///< of rgb - emission - diffuse
  /// The mean over the pixel's samples of the first surface's diffuse reflectance (0 where a
  /// sample sees nothing): the footprint's albedo, which `diffuse` divides by exactly (the
  /// albedo pass is the pixel centre's only).
  ImageF* albedo = nullptr;
  /// 1 channel: the least over the pixel's samples of their first surface's viewDependentAlpha
  /// (bsdf.h; kNoViewDependentLobe where no sample has a view-dependent lobe): how far the view
  /// may turn before `rest` changes.
  ImageF* view_alpha = nullptr;
  /// The view straight through window panes, with its own guides (denoise.h WindowViewLayers;
  /// its light is also in `emission`). Allocated by the caller at the camera's size.
  WindowViewLayers* window_view = nullptr;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  /// Renders linear RGB radiance into `rgb` (3 channels, camera size, already allocated) and the
  /// layers `out` asks for. Must be deterministic whatever the thread count.
  virtual void render(const RenderContext& ctx, ImageF& rgb, const IntegratorOutputs& out) const = 0;
};

/// Names of the registered integrators.
std::vector<std::string> integratorNames();
/// Creates a registered integrator; throws InputError(where, "--integrator", ...) listing the
/// valid names for an unknown one.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const std::string& where);

/// Factory of the unidirectional path tracer (path_tracer.cpp).
std::unique_ptr<Integrator> makePathTracer();

}  // namespace inet
