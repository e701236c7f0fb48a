#pragma once
// The learned denoiser (issue 14, docs/denoise.md "Learned denoiser"): a small convolutional
// U-Net trained with LibTorch on pairs of our own renders (render/denoise_train.h), run here in
// plain C++ so the renderer needs no torch and gives the same bytes on any thread count.
//
// Why a network after the à-trous filter: à-trous averages with fixed kernels and edge-stopping
// weights, so the low-frequency part of Monte Carlo noise (the mean of a whole wall patch being
// off) passes through it as blotches. A network that sees the noise level, the albedo, normals
// and depth over a receptive field of ~100 px learns how far it may average on each surface.
// OIDN does this; it is not packaged in Debian 12, so the network is ours (it is small: the
// weights and their training record ship in data/denoise/).
//
// Candidates (denoiserCandidates): K = 6 estimates of the demodulated light E per pixel, from
// the noisy input to ever wider filters, all from the à-trous filter of render/denoise.h run on
// the reflected colour with the footprint albedo as its albedo and the frame's variance:
//   C_0 = E itself
//   C_1 = à-trous, 3 levels, sigma_color 2 (the filter --denoiser atrous runs)
//   C_2 = à-trous, 5 levels, sigma_color 4
//   C_3, C_4, C_5 = à-trous without its colour weight (sigma_color 10^4: it stops only at
//         normal, depth and albedo edges), 3, 5 and 7 levels (29, 125 and 509 px wide)
// The network picks, per pixel, how much of each to take: E' = sum_k w_k C_k with softmax
// weights w. A convex combination of estimates cannot shift a colour or invent a value, and
// the widest candidates average a flat wall over hundreds of pixels, which is what removes the
// low-frequency blotches the colour-weighted filter keeps; the network learns where that is
// safe (smooth light) and where it is not (shadow edges, sun patches, texture the footprint
// albedo missed).
//
// Input, per pixel (denoiserFeatures), all from the frame itself:
//   E     = reflected / max(a_fp, eps)           demodulated light; reflected = rgb - emission
//                                                after temporal reuse; a_fp the footprint albedo
//                                                (RgbLayers::albedo); eps = albedo_epsilon
//   m     = exp(mean over surface pixels of log max(lum(E), 1e-6))   one scale per frame, so
//                                                the network never sees the exposure
//   f[0:3]   = log1p(E / m)                      the noisy light
//   f[3:6]   = log1p(sqrt(Var(E)) / m)           its noise level (RgbLayers::variance / a_fp^2)
//   f[6:9]   = albedo pass (the exact centre albedo)
//   f[9:12]  = camera-frame normal
//   f[12]    = log z - mean over surface pixels of log z
//   f[13 + 3 (k - 1) + c] = log1p(C_k,c / m), k = 1..5   the candidates
// Pixels without a surface (z <= 0, zero normal, non-finite colour) have all features 0 and
// keep their own colour.
//
// Network (3x3 convolutions with zero padding, leaky ReLU of slope `leak` after every one but
// the last; C_l = config.channels[l], L levels, F = 28 features):
//   enc_0   = act(conv(act(conv(f, F -> C_0)), C_0 -> C_0))
//   enc_l   = act(conv(act(conv(avgpool2(enc_{l-1}), C_{l-1} -> C_l)), C_l -> C_l)), l = 1..L-1
//   dec_L-1 = enc_L-1
//   dec_l   = act(conv(concat(up2(dec_{l+1}), enc_l), C_{l+1} + C_l -> C_l)),   l = L-2..0
//   logits  = conv1x1(dec_0, C_0 -> K)
// avgpool2 is the 2x2 mean, up2 nearest-neighbour doubling; the image is zero-padded on the
// right and bottom to a multiple of 2^(L-1) first and cropped after. Output:
//   w = softmax(8 tanh(logits / 8)),  E' = sum_k w_k C_k,  reflected' = E' * max(a_fp, eps).
// The soft bound keeps every weight above e^-16 of the largest: a saturated softmax passes no
// gradient, and training stalled on one candidate without it. The head starts at zero (equal
// weights).
//
// Weights file (.bin, little-endian): 8 bytes "INETDNSR", uint32 format version (1), uint32
// header length n, n bytes of JSON header {"config": {"channels": [...], "leak": x,
// "albedo_epsilon": x}, "tensors": [{"name", "shape"}...]}, then each tensor's float32 values in
// header order, torch's layout (a convolution's weight is [out][in][ky][kx], its bias [out]).
// Names: conv{i}.weight, conv{i}.bias for i = 0.. in the order enc_0 (2), enc_1 (2), ...,
// dec_L-2, ..., dec_0, out.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/denoise.h"
#include "render/frame.h"

namespace inet {

inline constexpr int kDenoiserCandidates = 6;
inline constexpr int kDenoiserFeatureCount = 13 + 3 * (kDenoiserCandidates - 1);

struct NeuralDenoiserConfig {
  std::vector<int> channels = {16, 24, 32, 32};  ///< per U-Net level, full resolution first
  float leak = 0.1f;                             ///< slope of the leaky ReLU for x < 0
  float albedo_epsilon = 0.01f;                  ///< demodulation floor, as the à-trous filter's
  /// Throws InputError(where, "config", ...) unless 1..6 levels of 1..256 channels, leak in
  /// [0, 1), albedo_epsilon in (0, 1].
  void validate(const std::string& where) const;
};

/// One convolution: weight [out][in][k][k] (torch's layout), bias [out].
struct ConvLayer {
  int in = 0, out = 0, k = 3;
  std::vector<float> weight, bias;
};

struct NeuralDenoiser {
  NeuralDenoiserConfig config;
  std::vector<ConvLayer> convs;  ///< in the order of the file format above

  /// The convolutions' shapes for `config` (weights empty).
  static std::vector<ConvLayer> shapes(const NeuralDenoiserConfig& config);
  /// Kaiming-uniform weights (leaky ReLU gain), zero biases and a zero head, from a Philox
/// stream of `seed`.
  static NeuralDenoiser random(const NeuralDenoiserConfig& config, uint64_t seed);
  size_t parameterCount() const;
};

/// The network's input for one frame (see the top of this file).
struct DenoiserInput {
  ImageF features;             ///< kDenoiserFeatureCount channels
  /// C_k / m, k = 0..K-1, 3 channels each (0 where there is no surface)
  std::vector<ImageF> candidates;
  std::vector<uint8_t> valid;  ///< 1 where the pixel sees a surface and its colour is finite
  float scale = 1.f;           ///< m
};

/// Builds the features. reflected, variance, footprint_albedo, albedo, normal: 3 channels;
/// depth: 1 (z-depth, 0 = no surface); all the same size (a mismatch is a bug: INET_CHECK).
DenoiserInput denoiserFeatures(const ImageF& reflected, const ImageF& variance,
                               const ImageF& footprint_albedo, const ImageF& albedo,
                               const ImageF& normal, const ImageF& depth, float albedo_epsilon);

/// The candidates C_0..C_5 (3 channels each, demodulated light, not scaled), see the top.
std::vector<ImageF> denoiserCandidates(const ImageF& reflected, const ImageF& variance,
                                       const ImageF& footprint_albedo, const ImageF& normal,
                                       const ImageF& depth, float albedo_epsilon);

/// The network's output (K channels, the logits) for features of any size. Parallel
/// over rows with TBB; every value is a fixed-order sum, so the thread count never changes it.
ImageF runNeuralDenoiser(const NeuralDenoiser& net, const ImageF& features);

/// The denoised reflected colour (3 channels): E' = m sum_k softmax(logits)_k C_k / m,
/// remodulated by max(footprint_albedo, eps);
/// pixels without a surface keep `reflected`.
ImageF neuralDenoise(const NeuralDenoiser& net, const ImageF& reflected, const ImageF& variance,
                     const ImageF& footprint_albedo, const ImageF& albedo, const ImageF& normal,
                     const ImageF& depth);

/// What denoiseRgb does, with the network: frame.rgb - layers.emission is denoised (guided by
/// layers.variance, layers.albedo and the frame's albedo, normal and z-depth) and the emission
/// added back. The frame must carry those passes and `layers` come from Renderer::render.
void denoiseRgbLearned(Frame& frame, const RgbLayers& layers, const NeuralDenoiser& net);

/// Everything the learned denoiser reads for one frame, as one EXR's channels (training data:
/// generate --denoiser-inputs): R G B = rgb - emission, var.R/G/B, afp.R/G/B (footprint albedo),
/// albedo.R/G/B, normal.X/Y/Z, Z (z-depth), emission.R/G/B.
std::vector<std::string> denoiserDumpChannels();
ImageF denoiserDump(const Frame& frame, const RgbLayers& layers);
/// The features of a dump (one EXR read with denoiserDumpChannels()).
DenoiserInput denoiserFeaturesFromDump(const ImageF& dump, float albedo_epsilon);

NeuralDenoiser loadNeuralDenoiser(const std::string& path);  ///< throws InputError
/// The same from the file's bytes; `path` names it in errors (fuzzed: fuzz/fuzz_denoiser_weights).
NeuralDenoiser parseNeuralDenoiser(const std::string& bytes, const std::string& path);
void saveNeuralDenoiser(const NeuralDenoiser& net, const std::string& path);  ///< atomic
/// $INET_DENOISER if set, else data/denoise/unet.bin of the source tree, else of the
/// installed share directory.
std::string defaultNeuralDenoiserPath();
/// loadNeuralDenoiser(defaultNeuralDenoiserPath()), loaded once (thread-safe).
const NeuralDenoiser& defaultNeuralDenoiser();

}  // namespace inet
