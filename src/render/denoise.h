#pragma once
// Edge-avoiding à-trous wavelet denoiser for the path-traced colour pass, guided by the exact
// ground-truth passes of the same frame (albedo, camera-frame normal, z-depth).
//
// References: H. Dammertz, D. Sewtz, J. Hanika, H. Lensch, "Edge-Avoiding À-Trous Wavelet
// Transform for fast Global Illumination Filtering", HPG 2010; C. Schied et al.,
// "Spatiotemporal Variance-Guided Filtering" (SVGF), HPG 2017 (variance-guided luminance weight
// and variance propagation). Only the spatial part of SVGF is used: we filter single frames.
//
// Pipeline (docs/denoise.md has the why and the measured speed):
//  0. (after 1 and 2) Fireflies: a pixel more than 4x brighter in demodulated luminance than
//     each of its 8 neighbours takes the colour of the neighbour of median luminance.
//  1. Demodulate: E_c = rgb_c / max(albedo_c, eps), so the filter sees irradiance, which is
//     smooth across texture edges; the result is remodulated by the same max(albedo_c, eps).
//  2. Noise level: sigma_E(p), the standard deviation of the luminance of E at p. From the
//     caller's variance image (variance of the pixel *mean*, per channel or one value for all
//     three), assuming fully correlated channels: sigma_E = sum_c w_c sqrt(var_c) / max(a_c, eps)
//     with Rec. 709 weights w. Without it, a robust estimate: per 16x16 tile, 1.4826 x the median
//     absolute residual of E's luminance against its 4-neighbour mean (Donoho & Johnstone 1994),
//     bilinearly interpolated between tile centres.
//  3. N passes i = 0..N-1 of the 5x5 B3-spline kernel h = (1, 4, 6, 4, 1)/16 with holes,
//     tap spacing 2^i pixels:
//        E'(p) = sum_q w(p,q) E(q) / sum_q w(p,q),  Var'(p) = sum_q w^2 Var(q) / (sum_q w)^2,
//        w(p,q) = h(dx) h(dy) exp(-(e_n + e_z + e_a + e_l)), with
//        e_n = sigma_normal (1 - n_p . n_q)                                 (~ SVGF's (n.n)^128)
//        e_z = |iz_q - (iz_p + grad(iz)_p . (q - p))| / (sigma_depth iz_p),  iz = 1 / z
//        e_a = |a_p - a_q|^2 / (2 sigma_albedo^2)
//        e_l = |l_p - l_q| / (sigma_color sqrt(g3x3(Var)(p)) + 1e-8)     (l = luminance of E)
//     Inverse z-depth is affine in pixel coordinates on any plane seen by a pinhole camera, so
//     e_z is 0 on planes at any slant and measures the jump at occlusion boundaries. The
//     gradient is the smaller one-sided difference, so it never straddles an occlusion edge.
//  3b. (mean_levels > 0) Keep the light: E' is scaled per pixel by lum(M(E)) / lum(M(E')),
//     clamped to [1/2, 2], where M is mean_levels levels of step 3 with e_l = 0 (a linear filter
//     of the surface), since the colour stop loses light where the noise is skewed.
//  4. Remodulate; pixels without a surface (depth <= 0, zero normal) or with non-finite colour
//     are never used as neighbours and are copied through unchanged.
//
// Deterministic: every output pixel is a fixed-order sum over its own taps, so 1 or N threads
// give identical bytes. Never apply it to ground-truth passes (they are exact), and it is off by
// default in the renderer: it trades noise for bias.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/frame.h"

namespace inet {

/// Parameters of the filter. Defaults follow SVGF where it has one (sigma_normal 128, sigma_color
/// 4, 5 iterations); sigma_depth and sigma_albedo are ours (see docs/denoise.md).
struct DenoiseOptions {
  int iterations = 5;            ///< à-trous levels, 1..10; support is 1 + 4 (2^N - 1) px wide
  float sigma_normal = 128.f;    ///< normal sharpness: weight exp(-sigma_normal (1 - cos angle))
  float sigma_depth = 0.01f;     ///< tolerated deviation from p's tangent plane, relative to z
  float sigma_albedo = 0.1f;     ///< albedo difference (linear reflectance, L2) at weight e^-1/2
  float sigma_color = 4.f;       ///< luminance difference, in noise standard deviations
  float albedo_epsilon = 0.01f;  ///< demodulation floor: rgb / max(albedo, albedo_epsilon)
  /// 0, or keep the light of the input: the output is scaled per pixel so that its surface mean
  /// (this many à-trous levels with the guides' stops only, no colour stop: a linear filter,
  /// 1 + 4 (2^N - 1) px wide) equals the input's. The colour stop is biased where the noise is
  /// skewed (indoors most samples are dark and a few bright; a dark pixel rejects its bright
  /// neighbours more than the reverse), and walls of a default sequence came out 3-6 % dark.
  int mean_levels = 0;
  /// 0, or pixels on a class edge (another NYU40 class in their 3x3 label neighbourhood) take
  /// the result after this many levels when `iterations` is more (denoiseRgb, with the label
  /// pass). The coarse levels lit a one-pixel seam there: floors next to curtains came out 40 %
  /// bright at 5 levels and flat at 3 (docs/rendering.md, "Class edges").
  int edge_iterations = 3;

  /// "iterations=5 sigma_normal=128 ..." for logs and dataset provenance.
  std::string describe() const;
};

/// Sets the fields named in `text`, "key=value[,key=value...]" with describe()'s keys (e.g.
/// "iterations=4,sigma_color=3"), on top of `options`, then validates them. InputError(where,
/// field, ...) for an unknown key, a value that is not a number, or a value out of range.
void applyDenoiseParams(const std::string& text, DenoiseOptions& options, const std::string& where,
                        const std::string& field);

/// Throws InputError(where, "denoise.<field>", ...) if a parameter is out of range (iterations
/// outside 1..10, a sigma not finite and > 0, albedo_epsilon not in (0, 1]).
void validateDenoiseOptions(const DenoiseOptions& options, const std::string& where);

/// Denoises `rgb` (3 channels, linear). albedo (3), normal (3, unit, camera frame, (0,0,0) = no
/// surface) and depth (1, z-depth in metres, 0 = no surface) come from the same frame and must
/// have rgb's size (a mismatch is a bug: INET_CHECK). `variance`, if not null, is the per-pixel
/// variance of the mean of rgb, 1 channel (same for R, G, B) or 3; it steers the colour weight.
/// Without it the noise level is estimated robustly (see above). Runs in parallel over rows with
/// TBB; the output does not depend on the thread count.
ImageF denoise(const ImageF& rgb, const ImageF& albedo, const ImageF& normal, const ImageF& depth,
               const ImageF* variance, const DenoiseOptions& options);

/// denoise() stopped after each of `levels` (ascending, in 1..10) à-trous levels:
/// one image per entry, each equal to denoise() with options.iterations = that level (the
/// levels are computed once; options.iterations is ignored).
std::vector<ImageF> denoiseLevels(const ImageF& rgb, const ImageF& albedo, const ImageF& normal,
                                  const ImageF& depth, const ImageF* variance,
                                  const DenoiseOptions& options, const std::vector<int>& levels);

/// Variance of the mean of two independent half-sample buffers A and B (same spp each), per
/// channel: ((A - B) / 2)^2, the one-degree-of-freedom unbiased estimate of Var((A + B) / 2).
/// It is very noisy; denoise() smooths the variance with a 3x3 Gaussian before using it.
ImageF varianceFromHalfBuffers(const ImageF& half_a, const ImageF& half_b);

/// Renders below this many samples per pixel estimate their variance from the neighbourhood
/// (neighbourhoodVariance): one sample has no variance of its own (the sample variance is 0 and
/// the filter took the image for exact). At 2 spp the pixels' own rough estimate did better in
/// sequences (docs/rendering.md, "Time to Cycles' 256-spp error").
constexpr int kNeighbourhoodVarianceBelowSpp = 2;

/// Per-pixel variance of each of `values` (3-channel images) estimated from its 7x7
/// neighbourhood on the same surface, for renders with too few samples per pixel to give their
/// own (SVGF's spatial estimate): with weights w_q from the filter's normal, depth-plane and
/// albedo stops (no colour stop), the weighted variance of the demodulated values
/// E_q = value_q / max(albedo_q, eps), bias-corrected for the weights' effective count, times
/// max(albedo_p, eps)^2. The light's own variation over the window counts as noise, so the
/// estimate errs toward more smoothing. A pixel without a neighbour on its surface gets value^2
/// (as noisy as it is bright); pixels without a surface get 0. The weights are computed once for
/// all the images. Same bytes on any thread count.
std::vector<ImageF> neighbourhoodVariance(const std::vector<const ImageF*>& values,
                                          const ImageF& albedo, const ImageF& normal,
                                          const ImageF& depth, const DenoiseOptions& options);

/// The colour pass in the layers of IntegratorOutputs (render/integrator.h): rgb = emission +
/// diffuse + rest, for a caller that filters them itself (temporal reuse along a sequence, then the
/// denoiser). Every image has the frame's size and 3 channels, view_alpha 1.
struct RgbLayers {
  ImageF emission;          ///< light emitted by the first surface seen (kept out of filters)
  ImageF variance;          ///< variance of the mean of rgb - emission (the denoiser's guide)
  ImageF diffuse;           ///< reflected through the first surface's diffuse lobes
  ImageF diffuse_variance;  ///< variance of the mean of diffuse
  ImageF rest_variance;     ///< variance of the mean of rgb - emission - diffuse
  ImageF albedo;            ///< mean first-surface albedo over the pixel's samples
  ImageF view_alpha;        ///< 1 channel: IntegratorOutputs::view_alpha
};

/// The view straight through window panes (IntegratorOutputs::window_view): the light of a
/// pixel's samples whose camera ray crossed a pane and then hit a surface (outdoors, the sunlit
/// ground and facades), with that surface's guides. Its light is part of the emission layer,
/// because the frame's guides there are the pane's and say nothing about what lies behind it;
/// left raw it was 94 % of a 1-spp sequence frame's squared error on an apartment with a large
/// window (docs/rendering.md). filterWindowView denoises it on its own guides. Samples that
/// reach the sky stay out of it: the sky is exact per direction and may have detail (an
/// environment map) that no guide describes.
struct WindowViewLayers {
  ImageF light;     ///< 3: mean light of those samples (0 where there are none)
  ImageF variance;  ///< 3: variance of that mean
  ImageF coverage;  ///< 1: their share of the pixel's samples
  ImageF albedo;    ///< 3: mean albedo of the surfaces they hit
  ImageF normal;    ///< 3: unit mean normal of those surfaces (world frame; 0: none)
  ImageF depth;     ///< 1: mean z-depth of those surfaces in metres (0: none)
};

/// Denoises the window view and puts it back where it was: rgb and emission both hold
/// coverage x light, which is replaced by coverage x denoise(light) with the view's own guides
/// (denoise(); pixels without a surface behind a pane keep their samples). `few_samples`: the
/// variance comes from the neighbourhood on the same outdoor surface (neighbourhoodVariance),
/// as for renders below kNeighbourhoodVarianceBelowSpp.
void filterWindowView(ImageF& rgb, ImageF& emission, const WindowViewLayers& view,
                      const DenoiseOptions& options, bool few_samples);

/// A pixel and the pixel whose value replaces it (loneBrightPixels).
struct PixelSwap {
  size_t pixel = 0, with = 0;
};

/// One-sample fireflies of a `width` x `height` image of luminances `lum` (row-major): each pixel
/// p with centre[p] != 0 whose luminance is more than `ratio` times that of every one of its
/// 8-neighbours q with neighbour[q] != 0 (at least `min_neighbours` of them), paired with the
/// neighbour of median luminance (ties broken by index). A null mask takes every pixel. In row
/// order, whatever the thread count. With ratio >= 1 and every listed pixel a usable neighbour
/// of its own neighbours, no pixel's replacement is itself listed, so a caller may replace in
/// place. Used by the denoiser's step 0 and by temporal reuse before its window keeps a frame
/// (sensors/temporal_reuse.h).
std::vector<PixelSwap> loneBrightPixels(int width, int height, const float* lum,
                                        const uint8_t* centre, const uint8_t* neighbour,
                                        float ratio, int min_neighbours);

/// Denoises frame.rgb - layers.emission, guided by the frame's normal and z-depth, by
/// layers.variance and by the footprint's albedo (layers.albedo; the frame's albedo pass where
/// the layers have none, and on class edges of the label pass), and adds the emission back
/// (what Renderer::render does with RenderOptions::denoise). The frame must carry those guides
/// (rendered with layers). Where the frame has its label pass, class-edge pixels take
/// options.edge_iterations levels. Where the layers split the light (diffuse, diffuse_variance
/// and rest_variance all of the frame's size), the diffuse light is filtered demodulated by
/// the albedo and the rest (rgb - emission - diffuse) as it is, each on its own variance, and
/// layers.diffuse becomes the filtered diffuse light (what TemporalReuse::smooth reads).
void denoiseRgb(Frame& frame, RgbLayers& layers, const DenoiseOptions& options);

}  // namespace inet
