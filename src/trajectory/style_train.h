#pragma once
// Training of the style model (trajectory/style_model.h) with LibTorch. Only this header and
// style_train.cpp see torch (library inet_style_train); everything else uses the plain C++
// inference of style_model.h.
//
// Data: every listed file of `data_dir` is read with loadMotionSegments (gaps and mocap glitches
// cut, pieces >= 5 s resampled at config.rate_hz), turned into residual features
// (styleResiduals) and normalised with scales measured on the training files only. Training
// draws windows of `window` samples at random positions (Philox, keyed by seed and epoch),
// each turned by a random yaw, `windows_per_epoch` per epoch in batches of `batch`, with
// Gaussian noise (input_noise) added to the inputs but not to the targets; the loss is
// the Gaussian negative log-likelihood per sample and channel,
//   NLL = 0.5 (log_var + (x[t + 1] - mean)^2 / exp(log_var) + log 2 pi),
// averaged over every prediction of the window. Adam, learning rate lr with cosine decay to
// lr / 20, gradients clipped to norm 1. Weights start from StyleModel::random(config, seed) and
// torch is seeded with `seed` and limited to `threads` threads, so a run is repeatable.
// Losses are reported on the training and held-out files over fixed non-overlapping windows
// without rotation.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "trajectory/style_model.h"

namespace inet {

struct StyleTrainOptions {
  std::string data_dir;
  /// File names in data_dir (hand-held sequences only).
  std::vector<std::string> train = {"tum_vi_room1_mocap.csv", "tum_vi_room3_mocap.csv",
                                    "tum_vi_room4_mocap.csv", "tum_vi_room6_mocap.csv",
                                    "tum_rgbd_fr1_xyz_groundtruth.txt",
                                    "tum_rgbd_fr2_desk_groundtruth.txt"};
  std::vector<std::string> holdout = {"tum_vi_room2_mocap.csv", "tum_vi_room5_mocap.csv",
                                      "tum_rgbd_fr3_long_office_household_groundtruth.txt"};
  StyleModelConfig config;
  int epochs = 40;
  int windows_per_epoch = 256;
  int window = 384;
  int batch = 16;
  double lr = 2e-3;
  /// Standard deviation of Gaussian noise added to the inputs (not the targets), normalised
  /// units: teaches the model to recover from its own sampling noise (exposure bias).
  double input_noise = 0.05;
  uint64_t seed = 1;
  int threads = 1;
};

struct StyleTrainResult {
  StyleModel model;
  double train_nll = 0, holdout_nll = 0;
  std::string record_json;  ///< data files (bytes, FNV-1a 64 hash), split, settings, losses
};

/// Trains a model. `progress(epoch, epochs, train_loss)` is called after every epoch (may be
/// empty). Throws InputError for a missing or unreadable file, an empty list, or a file in
/// both lists.
StyleTrainResult trainStyleModel(
    const StyleTrainOptions& options,
    const std::function<void(int, int, double)>& progress = {});

/// LibTorch's forward pass of `model` over a normalised input x (6 x T), in double or float
/// precision: the reference the plain C++ inference is tested against.
Eigen::MatrixXd torchStyleForward(const StyleModel& model, const Eigen::MatrixXd& x,
                                  bool double_precision);

}  // namespace inet
