// interiornet-train-denoiser: the LibTorch half of `interiornet denoiser train` (see
// train_style_main.cpp for why training is a separate executable).
#include "cli_main.h"

namespace inet::app {
void addTrainDenoiserCommand(CLI::App* denoiser_cmd);  // cmd_train_denoiser.cpp
}

int main(int argc, char** argv) {
  CLI::App app{"interiornet denoiser train"};
  app.name("interiornet denoiser");
  app.require_subcommand(1);
  inet::app::configureCli(app);
  inet::app::addTrainDenoiserCommand(&app);
  return inet::app::runCli(app, argc, argv);
}
