// interiornet-train-style: the LibTorch half of `interiornet trajectory train-style`.
// Training links LibTorch (hundreds of shared libraries, ~0.3 s to load and 150 MB before any
// work), so it lives in this separate executable and `interiornet` hands over to it with exec
// (apps/cmd_trajectory.cpp); every other command starts without it.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "core/error.h"

namespace inet::app {
void addTrainStyleCommand(CLI::App* trajectory_cmd);  // cmd_train_style.cpp
}

int main(int argc, char** argv) {
  CLI::App app{"interiornet trajectory train-style"};
  app.name("interiornet trajectory");
  app.require_subcommand(1);
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("error: ") + e.what() + " (see --help)\n";
  });
  inet::app::addTrainStyleCommand(&app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const inet::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
