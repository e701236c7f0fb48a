// interiornet-train-style: the LibTorch half of `interiornet trajectory train-style`.
// Training links LibTorch (hundreds of shared libraries, ~0.3 s to load and 150 MB before any
// work), so it lives in this separate executable and `interiornet` hands over to it with exec
// (apps/cmd_trajectory.cpp); every other command starts without it.
#include "cli_main.h"

namespace inet::app {
void addTrainStyleCommand(CLI::App* trajectory_cmd);  // cmd_train_style.cpp
}

int main(int argc, char** argv) {
  CLI::App app{"interiornet trajectory train-style"};
  app.name("interiornet trajectory");
  app.require_subcommand(1);
  inet::app::configureCli(app);
  inet::app::addTrainStyleCommand(&app);
  return inet::app::runCli(app, argc, argv);
}
