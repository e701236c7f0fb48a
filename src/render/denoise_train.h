#pragma once
// Training of the learned denoiser (render/neural_denoise.h) with LibTorch. Only this header and
// denoise_train.cpp see torch (library inet_denoise_train); the renderer runs the plain C++
// forward pass of neural_denoise.h.
//
// Data: pairs of folders of denoiser dumps (`generate --save-denoiser-inputs` writes
// denoise_in/<t>.exr): an input folder (the default pipeline: 16 spp, temporal reuse) and a
// target folder (the same poses rendered with many samples, no reuse, another seed). Files with
// the same name in both make a training pair. The features are denoiserFeaturesFromDump's, the
// very function inference uses; the target is the target dump's reflected colour divided by the
// input's frame scale m.
//
// Loss: relative squared error of the remodulated colour (Noise2Noise, Lehtinen et al. 2018:
// an unbiased noisy target gives the same minimiser as a clean one under an L2 loss, so targets
// need not be converged; the denominator uses the prediction without its gradient so it does
// not pull towards dark):
//   L = mean over surface pixels p and channels c of (y'_pc - y_pc)^2 / (sg(y'_pc)^2 + f)
//   y' = sum_k softmax(8 tanh(logits / 8))_k C_k / m * max(a_fp, eps),  y = min(target reflected / m, 64)
// (the clamp keeps single-sample fireflies of the targets, up to 10^4 m, out of the loss).
// Training draws `batch` random crops of `crop` x `crop` pixels per step (Philox, keyed by seed
// and step), each flipped at random horizontally and vertically (the normal's x or y negated
// with it); Adam, learning rate lr with cosine decay to lr / 20, gradient norm clipped to 1.
// Weights start from NeuralDenoiser::random(config, seed); torch is seeded and limited to
// `threads` threads.
//
// Reported on the held-out pairs, whole frames: the loss and the relative RMSE on surface
// pixels, sqrt(mean (x - y)^2) / mean y over every pixel and channel of every held-out frame, of
// the input itself (candidate C_0), of the à-trous filter (C_1, what --denoiser atrous gives)
// and of the network, clamped at 64 m as y is; y is the target, whose own noise is included.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/neural_denoise.h"

namespace inet {

struct DenoiseTrainPairs {
  std::string input_dir, target_dir;
};

struct DenoiseTrainOptions {
  std::vector<DenoiseTrainPairs> train, holdout;
  NeuralDenoiserConfig config;
  int steps = 2000;
  int batch = 8;
  int crop = 96;  ///< a multiple of 2^(levels - 1)
  double lr = 5e-4;
  /// f in the loss's denominator sg(y')^2 + f: 0.01 is nearly relative everywhere; 1 is
  /// absolute below the frame's geometric-mean light and relative above it
  double loss_floor = 0.01;
  uint64_t seed = 1;
  int threads = 2;

  /// Throws InputError naming the field for an empty training list, a crop that is not a
  /// positive multiple of 2^(levels - 1), or steps / batch / lr / threads out of range.
  void validate() const;
};

struct DenoiseHoldoutScores {
  int frames = 0;
  double loss = 0;                ///< the training loss of the network on whole frames
  double rel_rmse_input = 0;      ///< the input as it is
  double rel_rmse_atrous = 0;     ///< the à-trous filter's output
  double rel_rmse_network = 0;    ///< the network's output
};

struct DenoiseTrainResult {
  NeuralDenoiser net;
  double final_train_loss = 0;  ///< mean loss of the last 10 % of steps
  DenoiseHoldoutScores holdout;
  std::string record_json;      ///< data (file names, bytes, FNV-1a 64), settings, losses, time
};

/// Trains a network. progress(step, steps, loss) after every step (may be empty). Throws
/// InputError for a missing folder, a pair with no common file, an unreadable dump, or dumps of
/// different sizes within a pair.
DenoiseTrainResult trainNeuralDenoiser(
    const DenoiseTrainOptions& options,
    const std::function<void(int, int, double)>& progress = {});

/// The network's forward pass in LibTorch (float32), features F x H x W (H, W multiples of
/// 2^(levels - 1)) -> K x H x W logits: the reference the plain C++ pass is tested against.
ImageF torchNeuralDenoiserForward(const NeuralDenoiser& net, const ImageF& features);

}  // namespace inet
