// interiornet: synthetic indoor RGB-D-inertial datasets with exact ground truth.
// main() is the only place that turns errors into exit codes (STYLE.md section 4).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "common.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "interiornet: photo-realistic indoor sequences with exact ground truth (depth, normals, "
      "NYU40 labels, instances, albedo) for SLAM and scene understanding.\n"
      "Run 'interiornet generate' for a 25-frame sequence of the built-in room, or "
      "'interiornet SUBCOMMAND --help' for details."};
  app.require_subcommand(1);
  // a repeated option takes its last value, as in most command lines (scripts append overrides)
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  // one-line errors, like every other error of the tool
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("error: ") + e.what() + " (see --help)\n";
  });
  app.set_version_flag("--version", inet::app::version());
  inet::app::registerGenerate(app);
  inet::app::registerRender(app);
  inet::app::registerLayout(app);
  inet::app::registerBench(app);
  inet::app::registerTrajectory(app);
  inet::app::registerEval(app);
  inet::app::registerImu(app);
  inet::app::registerDepthNoise(app);
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
