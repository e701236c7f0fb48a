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
// image edge) and an edge pixel keep exactly what frame k rendered. Light emitted by what the
// pixel sees is never reused.
//
// View-dependent light (the `rest` layer: a varnished floor's coating, brushed metal) moves with
// the viewer, but a rough lobe changes little while the view turns by a fraction of its width.
// Frame j's rest is averaged in (same weights, its own total, not demodulated) where the
// direction from the point to the camera has turned between frames j and k by at most
// `view_turn` x alpha, alpha the least GGX alpha of the pixel's first surfaces
// (RgbLayers::view_alpha; a GGX lobe is about 2 alpha radians wide in reflected directions). The
// past frames all lie behind along the path, so what they add lags: on a rough metal ball (alpha
// 0.36) turning 0.02 rad per frame, a tolerance of 0.5 alpha raised its mean 2.5 % and its error
// above the raw frame's; 0.1 alpha (the default) cut its squared error 3.2x with the mean as the
// frame's own (test RoughGlossyLightIsReusedOnlyWhileTheViewTurnsLittle). Delta lobes (mirrors,
// smooth coatings) and glass have alpha 0: their rest is never reused. Points on a moving object
// count as turned too far (their rest stays as rendered).
//
// Fireflies (`firefly_ratio`): a sample that found a small, bright path (the sun reflected by a
// smooth coating or a pane, which only a BSDF sample finds) can make a pixel's own light
// thousands of times that of the pixels around it; once in the window, later frames read it
// through their bilinear taps, spread over 4 pixels and each about as bright as its neighbours,
// which the denoiser's one-pixel firefly test no longer sees: the filter spread one such sample
// of a 64-spp frame of apartment 3 over a 3,900-px blotch that lasted the window. So before
// frame k's own light is used or remembered, an interior pixel (one surface around it) whose
// demodulated luminance is more than firefly_ratio times that of all 8 neighbours takes the
// irradiance and variance of the neighbour of median luminance (its output too, where the
// window gives it reused light). Texture is divided out and the neighbours are the same
// surface, so real detail is never that far from all of them; the light it drops is that
// sample's, a bias toward darker that is 0 in frames without such samples (docs/denoise.md
// gives its size on apartment 3).
//
// Smoothing after the denoiser (`smooth`, M frames): the filtered light still changes from frame
// to frame (the filter's colour weights follow the noise). smooth() replaces the filtered,
// demodulated light of an interior pixel by its mean over the last M frames' filtered light at
// the same point (the same taps). Where the denoiser filtered the diffuse light apart
// (denoiseRgb), the diffuse light takes every such frame and the rest only the frames whose
// view is within the tolerance above, as in add(); otherwise the whole light takes only those
// (or any frame where the surface has no view-dependent lobe). The filtered frames share most of
// their reused samples, so their errors are alike: the mean changes slowly, which is what it is for
// (frame to frame flicker of apartment 3's walls 2.4 % -> 1.1 % at M = 4, docs/denoise.md 1b).
//
// Exactness: each I_j estimates the same quantity (for a static scene and static lights), so
// the mean is unbiased and its noise variance falls as 1/n. What can lag: the shadow of a
// moving object cast on a static surface (the surface is static, its lighting is not) lasts up
// to window - 1 frames; the Plastic base's Fresnel factor changes by well under 1 % over the
// angles a window covers.
//
// Samples where the history is short (`plan`, RenderOptions::spp_multiplier): a point frame k
// sees for the first time (the first frame, a disocclusion, the image border) has only its own
// samples, and was what the window could not reduce (13-15 % of an apartment frame's pixels).
// plan() counts, before frame k is rendered, how many remembered frames will give each pixel
// reused light (from frame k's ground truth: geometry only), and asks for
// max(1, boost - count) times the samples there (boost_edges for pixels on a class or depth
// edge, which never take reused light). The weights above then count samples: frame k's own
// estimate weighs its multiplier m_k(x), a past frame's interpolation
// 1 / sum_taps (w^2 / m_j(tap)), both still geometry only, so the mean stays unbiased.
//
// Determinism: the output of frame k depends only on frames k - window + 1 .. k, each rendered
// from its own seed with a multiplier that depends on the geometry of the window - 1 frames
// before it; with smoothing on frames k - warmUpFrames() .. k. A caller that starts at frame s >
// 0 (a resumed run, a frame range of a larger job) first adds the geometry of the window - 1
// frames before s - warmUpFrames() (addGeometry), then frames max(0, s - warmUpFrames()) ..
// s - 1 (plan, render them, call add, and for the last smooth - 1 of them denoise and smooth,
// discarding the result) and gets the same bytes as a run from frame 0.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/pose.h"
#include "render/frame.h"
#include "render/lens.h"
#include "render/denoise.h"
#include "sensors/optical_flow.h"

namespace inet {

struct Scene;

struct TemporalReuseOptions {
  int window = 16;               ///< frames per output, the current one included (1 = off)
  /// Most samples multiplier plan() asks for (a point no remembered frame saw); 1 = every pixel
  /// takes the frame's spp.
  int boost = 4;
  /// The multiplier of pixels on a class or depth edge (they keep their own samples).
  int boost_edges = 2;
  float albedo_epsilon = 0.01f;  ///< demodulation floor, as the denoiser's
  /// How far the view at a point may turn for its view-dependent light to be reused, in units of
  /// its lobe's GGX alpha (0: never).
  float view_turn = 0.1f;
  /// Frames smooth() averages the filtered light over, the current one included (1 = off); a
  /// window shorter than this shortens it (smoothFrames()).
  int smooth = 4;
  /// A pixel whose own demodulated diffuse light is more than this many times as bright as that
  /// of every one of its 8 neighbours (an interior pixel: one surface) is one rare sample of a
  /// bright path; before the window keeps it, it takes the light of its neighbour of median
  /// brightness (see add()). 0 = off.
  float firefly_ratio = 16.f;
  FlowOptions flow;              ///< the visibility test's depth tolerances

  /// Throws InputError(where, "--temporal", ...) for a window outside 1..64, and names the
  /// other fields for bad tolerances.
  void validate(const std::string& where) const;
  /// The frames before frame s that a caller starting at s renders again (see the top of this
  /// file): window - 1, plus smooth - 1 when smoothing.
  int warmUpFrames() const { return window - 1 + smoothFrames() - 1; }
  /// The frames smooth() averages over: `smooth`, at most the window (1 when reuse is off).
  int smoothFrames() const { return std::max(1, std::min(smooth, window)); }
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
  /// frame.rgb = emission + reused diffuse + reused rest, layers.diffuse, diffuse_variance and
  /// rest_variance are the reused ones, and layers.variance = diffuse_variance + rest_variance
  /// (what the denoiser should assume). `layers` needs view_alpha (Renderer::render with
  /// layers). `used`, if not null, receives per pixel how many frames were averaged
  /// (1 .. window). Consecutive calls must be consecutive frames (clear() between
  /// sequences).
  void add(Frame& frame, RgbLayers& layers, const Pose& T_world_camera, double scene_time_s,
           ImageU8* used = nullptr);
  /// Before the next frame is rendered: from its ground truth `gt` (the depth of the flow's
  /// kind, label, and instance where objects move) at T_world_camera and scene_time_s, the
  /// per-pixel samples multiplier to render it with (RenderOptions::spp_multiplier; see the top
  /// of this file). The reprojection it computes is kept for the add() of the same pose and
  /// time. Without plan(), add() takes every pixel as rendered at multiplier 1.
  const ImageU8& plan(const Frame& gt, const Pose& T_world_camera, double scene_time_s);
  /// After add() and the denoiser, for the same frame: `frame.rgb` (emission + filtered light)
  /// becomes emission + the filtered light averaged over the last `smooth` frames (see the top of
  /// this file). A no-op when smooth is 1. Must follow add() of this frame, and the frames before
  /// it must have been smoothed too for them to count (the ones that were not are left out).
  /// `split`: layers.diffuse is the filtered diffuse light (denoiseRgb), averaged apart from the
  /// rest (rgb - emission - diffuse).
  void smooth(Frame& frame, const RgbLayers& layers, bool split);
  /// Remembers a frame's geometry only (no colour): what plan() counts for the frames after it.
  /// For a caller that starts late (see the top of this file).
  void addGeometry(const Frame& gt, const Pose& T_world_camera, double scene_time_s);
  /// Forgets every earlier frame.
  void clear() {
    past_.clear();
    planned_.reset();
    added_ = Added{};
  }
  /// Frames remembered (at most window - 1).
  int remembered() const { return static_cast<int>(past_.size()); }
  /// What the firefly test (TemporalReuseOptions::firefly_ratio) took from a frame.
  struct Fireflies {
    size_t pixels = 0;         ///< pixels whose own diffuse light it replaced
    double light_share = 0.0;  ///< their excess luminance over the frame's demodulated total
  };
  /// The last add()ed frame's.
  const Fireflies& fireflies() const { return fireflies_; }

 private:
  struct Past {
    Pose T_world_camera;
    double scene_time_s = 0;
    ImageF depth;        ///< of the flow's DepthKind
    ImageU16 instance;   ///< empty unless objects move
    ImageU8 label;
    ImageF irradiance;   ///< diffuse / max(albedo, eps), 3 channels (empty: geometry only)
    ImageF variance;     ///< of the irradiance, 3 channels
    ImageU8 interior;    ///< 1 = the 3x3 neighbourhood is one surface (see the .cpp)
    ImageU8 multiplier;  ///< the samples multiplier it was rendered with (empty: 1)
    ImageF rest;         ///< the view-dependent light (rgb - emission - diffuse), 3 channels
    ImageF rest_variance;
    ImageF filtered;     ///< the denoiser's (diffuse) light / max(albedo, eps) (smooth(); empty: none)
    ImageF filtered_rest;  ///< split smooth(): the denoiser's rest, not demodulated
  };
  /// Where pixel i lands in a remembered frame: the (up to) 4 bilinear taps around the landing
  /// point that the reuse may read, weights summing to 1; count 0 where it is not seen there.
  struct Taps {
    int32_t index[4];
    float weight[4];
    int count = 0;
  };
  /// A frame's geometry and where its pixels land in each remembered frame (oldest first).
  struct Reprojection {
    Past self;  ///< the frame's geometry (colour fields empty)
    std::vector<std::vector<Taps>> source;
    /// How far the view at each pixel with taps has turned since each remembered frame: the
    /// angle (radians) between the directions from its point to the two cameras; infinite on a
    /// moving object.
    std::vector<std::vector<float>> turn;
  };
  /// add()'s reprojection, for the smooth() of the same frame: its source[j] and turn[j] are
  /// past_[j - popped]'s (`popped` frames left the window when the frame was added).
  struct Added {
    Reprojection reprojection;
    size_t popped = 0;
  };
  /// Frame f's geometry (its depth, label, instance where objects move, interior pixels).
  Past geometryOf(const Frame& f, const Pose& T_world_camera, double scene_time_s) const;
  Reprojection reproject(const Frame& f, const Pose& T_world_camera, double scene_time_s) const;
  /// How far the view may turn for a pixel of this view_alpha (RgbLayers) to take a past
  /// frame's view-dependent light: view_turn x alpha, infinite where it has none.
  float maxTurn(float view_alpha) const;
  /// The depth of the flow's kind in f.
  const ImageF& depthOf(const Frame& f) const;
  void remember(Past&& p);

  const Scene& scene_;
  LensModel lens_;
  TemporalReuseOptions options_;
  bool has_motion_ = false;  ///< some object of the scene moves
  std::deque<Past> past_;  ///< oldest first
  std::unique_ptr<Reprojection> planned_;  ///< plan()'s, for the next add()
  ImageU8 planned_multiplier_;             ///< plan()'s answer
  Added added_;                            ///< the last add()'s
  Fireflies fireflies_;                    ///< fireflies()
};

}  // namespace inet
