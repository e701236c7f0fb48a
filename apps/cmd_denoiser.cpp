// interiornet denoiser ...: the learned denoiser (render/neural_denoise.h, docs/denoise.md).
// `denoiser train` runs in interiornet-train-denoiser (LibTorch), next to this binary, so that
// interiornet itself never loads LibTorch.
#include "common.h"

namespace inet::app {

void registerDenoiser(CLI::App& app) {
  auto* denoiser = app.add_subcommand(
      "denoiser", "The learned denoiser: train it on pairs of our own renders (docs/denoise.md)");
  denoiser->require_subcommand(1);
  // every argument after the subcommand, --help included, goes to the companion unparsed
  auto* train = denoiser->add_subcommand(
      "train",
      "Train the learned denoiser with LibTorch on folders of 'generate --save-denoiser-inputs' "
      "dumps (runs interiornet-train-denoiser; 'interiornet denoiser train --help' lists its "
      "options)");
  train->prefix_command();
  train->set_help_flag();
  train->callback([train] {
    execCompanion("interiornet-train-denoiser", "train", train->remaining());
  });
}

}  // namespace inet::app
