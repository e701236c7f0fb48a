// interiornet: synthetic indoor RGB-D-inertial datasets with exact ground truth.
// main() is the only place that turns errors into exit codes (STYLE.md section 4).
#include "cli_main.h"
#include "common.h"

#include "assets/catalog_library.h"

int main(int argc, char** argv) {
  CLI::App app{
      "interiornet: photo-realistic indoor sequences with exact ground truth (depth, normals, "
      "NYU40 labels, instances, albedo, Kinect-like depth, optical flow, 3D boxes, IMU, events, "
      "stereo) along realistic camera trajectories, for SLAM and scene understanding; "
      "procedural apartments or imported scenes; SLAM scoring (ATE, RPE).\n"
      "Run 'interiornet generate' for a 25-frame sequence of the built-in apartment (the built-in "
      "room without Sweet Home 3D's catalogs), or "
      "'interiornet SUBCOMMAND --help' for details."};
  app.require_subcommand(1);
  // layouts may name Sweet Home 3D catalog models; nothing is read until one does
  inet::installCatalogResolver();
  inet::app::configureCli(app);
  app.set_version_flag("--version", inet::app::version());
  inet::app::registerGenerate(app);
  inet::app::registerRender(app);
  inet::app::registerLayout(app);
  inet::app::registerBench(app);
  inet::app::registerTrajectory(app);
  inet::app::registerEval(app);
  inet::app::registerImu(app);
  inet::app::registerDepthNoise(app);
  inet::app::registerEvents(app);
  inet::app::registerVary(app);
  inet::app::registerDenoiser(app);
  inet::app::registerAssets(app);
  inet::app::registerDataset(app);
  inet::app::registerStudio(app);
  return inet::app::runCli(app, argc, argv);
}
