#pragma once
// Temporal reuse along a sequence (issue 14): the light a surface reflects diffusely does not
// depend on where it is seen from, and the exact ground truth of every frame (depth, instance,
// pose, object motion) tells where each point of frame k was seen in the frames before it. So
// frame k's diffuse layer (render/renderer.h RgbLayers: the light reflected through the first
// surface's diffuse lobes) is replaced by the mean of that point's diffuse light over the last
// `window` frames that saw it, every one an independent estimate of the same value:
//
//   I_j(x)  = diffuse_j(x) / max(albedo_j(x), eps)        irradiance-like, texture divided out,
//             albedo_j the mean first-surface albedo of the pixel's own samples (RgbLayers): the
//             centre's albedo (the albedo pass) would bias it where texture varies in a pixel
//   x_j     = where frame k's pixel x lands in frame j (sensors/optical_flow.h forwardFlow: the
//             point X from frame k's depth, moved by the object motion between the two scene
//             times, projected by frame j's pose and lens); used when frame j sees the point
//             (forwardFlow's occlusion rule: depth within 1 % + 1 cm of the pixels around x_j;
//             and the same instance where objects move) and lands inside the image; I_j(x_j)
//             interpolates the (up to) 4 pixel centres around x_j bilinearly, over those of the
//             same NYU40 class (and instance, where objects move)
//   out(x)  = max(albedo_k(x), eps) * sum_j v_j I_j(x_j) / sum_j v_j over the usable frames j in
//             [k - window + 1, k], v_j = 1 / sum_taps w^2 (1 for frame k's own pixel): each
//             estimate weighted by the inverse of its variance factor, which depends on the
//             geometry only (never on the samples), so the mean stays unbiased
//   Var     = max(albedo_k, eps)^2 * sum_j v_j^2 Var(I_j) / (sum_j v_j)^2
// Only interior pixels (the 3x3 neighbourhood is one surface: one class, depths within 5 %) give
// or take: an edge pixel's samples, spread over its footprint, mix two surfaces in proportions
// that change from frame to frame (the wall behind a mirror's rim would leak into the mirror).
//
// Frame k's own samples always count, so a point seen for the first time (disocclusion, the
// image edge) and an edge pixel keep exactly what frame k rendered. Light through specular lobes (mirrors,
// glass, the coating of a varnished floor: the `rest` layer) moves with the viewer and is never
// reused; nor is light emitted by what the pixel sees.
//
// Exactness: each I_j estimates the same quantity (for a static scene and static lights), so
// the mean is unbiased and its noise variance falls as 1/n. What can lag: the shadow of a
// moving object cast on a static surface (the surface is static, its lighting is not) lasts up
// to window - 1 frames; the Plastic base's Fresnel factor changes by well under 1 % over the
// angles a window covers.
//
// Determinism: the output of frame k depends only on frames k - window + 1 .. k, each rendered
// from its own seed. A caller that starts at frame s > 0 (a resumed run, a frame range of a
// larger job) first adds frames max(0, s - window + 1) .. s - 1 (render them, call add and
// discard the result) and gets the same bytes as a run from frame 0.
#include <cstdint>
#include <deque>
#include <string>

#include "core/image.h"
#include "core/pose.h"
#include "render/frame.h"
#include "render/lens.h"
#include "render/denoise.h"
#include "sensors/optical_flow.h"

namespace inet {

struct Scene;

struct TemporalReuseOptions {
  int window = 8;                ///< frames per output, the current one included (1 = off)
  float albedo_epsilon = 0.01f;  ///< demodulation floor, as the denoiser's
  FlowOptions flow;              ///< the visibility test's depth tolerances

  /// Throws InputError(where, "--temporal", ...) for a window outside 1..64, and names the
  /// other fields for bad tolerances.
  void validate(const std::string& where) const;
  /// "window=8 albedo_epsilon=0.01 ..." for provenance.
  std::string describe() const;
};

class TemporalReuse {
 public:
  /// `scene` gives the object motion between frames (it must outlive this); `lens` is every
  /// frame's lens. Throws InputError for bad options.
  TemporalReuse(const Scene& scene, const LensModel& lens, const TemporalReuseOptions& options);

  /// Adds the next frame of the sequence and filters it in place: `frame` (raw rgb, with the
  /// albedo, label, instance and depth guides of Renderer::render with layers) at camera pose
  /// T_world_camera (its ground-truth instant) and scene time scene_time_s. Afterwards
  /// frame.rgb = emission + reused diffuse + rest, layers.diffuse and layers.diffuse_variance
  /// are the reused ones, and layers.variance = diffuse_variance + rest_variance (what the
  /// denoiser should assume). `used`, if not null, receives per pixel how many frames were
  /// averaged (1 .. window). Consecutive calls must be consecutive frames (clear() between
  /// sequences).
  void add(Frame& frame, RgbLayers& layers, const Pose& T_world_camera, double scene_time_s,
           ImageU8* used = nullptr);
  /// Forgets every earlier frame.
  void clear() { past_.clear(); }
  /// Frames remembered (at most window - 1).
  int remembered() const { return static_cast<int>(past_.size()); }

 private:
  struct Past {
    Pose T_world_camera;
    double scene_time_s = 0;
    ImageF depth;        ///< of the flow's DepthKind
    ImageU16 instance;   ///< empty unless objects move
    ImageU8 label;
    ImageF irradiance;   ///< diffuse / max(albedo, eps), 3 channels
    ImageF variance;     ///< of the irradiance, 3 channels
    ImageU8 interior;    ///< 1 = the 3x3 neighbourhood is one surface (see the .cpp)
  };
  const Scene& scene_;
  LensModel lens_;
  TemporalReuseOptions options_;
  bool has_motion_ = false;  ///< some object of the scene moves
  std::deque<Past> past_;  ///< oldest first
};

}  // namespace inet
