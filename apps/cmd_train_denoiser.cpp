// interiornet denoiser train: trains the learned denoiser (render/neural_denoise.h) with
// LibTorch and writes the weights plus a JSON record of data, settings and held-out scores.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli_main.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "render/denoise_train.h"

namespace inet::app {
namespace {

struct TrainDenoiserArgs {
  DenoiseTrainOptions opt;
  std::vector<std::string> pairs, holdout;
  std::string out, record;
  bool progress = true;
};

std::vector<DenoiseTrainPairs> parsePairs(const std::vector<std::string>& list,
                                          const char* field) {
  std::vector<DenoiseTrainPairs> out;
  for (const std::string& p : list) {
    const size_t colon = p.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == p.size())
      throw InputError(p, field, "expected INPUT_DIR:TARGET_DIR");
    out.push_back({p.substr(0, colon), p.substr(colon + 1)});
  }
  return out;
}

void runTrainDenoiser(TrainDenoiserArgs& a) {
  a.opt.train = parsePairs(a.pairs, "--pairs");
  a.opt.holdout = parsePairs(a.holdout, "--holdout");
  const std::string record = recordPath(a.out, a.record);
  ProgressBar bar(a.opt.steps, "steps", a.progress);
  DenoiseTrainResult r =
      trainNeuralDenoiser(a.opt, [&](int step, int, double) { bar.update(step); });
  bar.finish();
  saveNeuralDenoiser(r.net, a.out);
  writeTextAtomic(record, r.record_json);
  fmt::print(
      "denoiser: {} parameters, train loss {:.4f}; held out ({} frames): loss {:.4f}, relative "
      "RMSE input {:.4f}, a-trous {:.4f}, network {:.4f}\n  {}\n  {}\n",
      r.net.parameterCount(), r.final_train_loss, r.holdout.frames, r.holdout.loss,
      r.holdout.rel_rmse_input, r.holdout.rel_rmse_atrous, r.holdout.rel_rmse_network, a.out,
      record);
}

}  // namespace

void addTrainDenoiserCommand(CLI::App* denoiser_cmd) {
  auto* cmd = denoiser_cmd->add_subcommand(
      "train",
      "Train the learned denoiser (a small U-Net) with LibTorch on pairs of folders of "
      "'generate --save-denoiser-inputs' dumps: INPUT (the default pipeline) and TARGET (the "
      "same poses at many samples, no reuse); writes the weights and a JSON record of data, "
      "settings, losses and held-out scores (docs/denoise.md)");
  auto a = std::make_shared<TrainDenoiserArgs>();
  cmd->add_option("--pairs", a->pairs,
                  "training pairs INPUT_DIR:TARGET_DIR (denoise_in folders), comma-separated; "
                  "files with the same name in both are one example")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->required();
  cmd->add_option("--holdout", a->holdout, "held-out pairs, as --pairs, for the scores")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--channels", a->opt.config.channels, "channels per U-Net level")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
      ->default_str("16,24,32,32");
  cmd->add_option("--steps", a->opt.steps, "optimiser steps")->capture_default_str();
  cmd->add_option("--batch", a->opt.batch, "crops per step")->capture_default_str();
  cmd->add_option("--crop", a->opt.crop, "crop side in pixels")->capture_default_str();
  cmd->add_option("--lr", a->opt.lr, "Adam learning rate (cosine decay to lr/20)")
      ->capture_default_str();
  cmd->add_option("--loss-floor", a->opt.loss_floor,
                  "f of the loss's denominator sg(pred)^2 + f, in units of the frame's geometric-"
                  "mean light (small: relative error everywhere)")
      ->capture_default_str();
  cmd->add_option("--seed", a->opt.seed, "seed of initialisation and sampling")
      ->capture_default_str();
  cmd->add_option("--threads", a->opt.threads, "torch threads")->capture_default_str();
  cmd->add_option("--out", a->out, "weights file to write (.bin)")->required();
  cmd->add_option("--record", a->record, "record to write; default: <out stem>_record.json");
  cmd->add_flag("--no-progress{false}", a->progress, "do not draw the progress bar");
  cmd->callback([a] { runTrainDenoiser(*a); });
}

}  // namespace inet::app
