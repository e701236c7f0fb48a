#pragma once
// Shared pieces of the command line: options every subcommand understands and scene loading.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "core/stop.h"
#include "pipeline/sensor_outputs.h"
#include "pipeline/settings.h"

namespace inet::app {

/// The scene source's flags: --layout/--scene, --up, --scale, --labels, --lights,
/// --auto-lights; `without` says what the command does without --layout.
void addSceneFlags(CLI::App& cmd, SceneSource& x,
                   const std::string& without = "the built-in furnished room");
/// The camera response's flags: --exposure-ev, --tone, --sensor-noise.
void addResponseFlags(CLI::App& cmd, ResponseSettings& x);
/// --radiance-cache (with --no-radiance-cache where it is on by default) and --radiance-cell.
void addRadianceCacheFlags(CLI::App& cmd, bool& on, double& cell_m, bool on_by_default);
/// The lens's flags: --lens, --aperture, --focus, --fisheye-fov.
void addLensFlags(CLI::App& cmd, LensSettings& x);
/// The event camera's flags: --event-width, --event-height, --event-spp, --contrast, ...
void addEventFlags(CLI::App& cmd, EventSettings& x);
/// The random trajectories' flags: --v-mult, --w-mult, --clearance, --min-height,
/// --max-height, --style.
void addMotionFlags(CLI::App& cmd, MotionSettings& x);

/// Limits TBB to n threads for the life of the object (n = 0: all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int n);
  ~ThreadLimit();
  int threads() const { return threads_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int threads_;
};

/// Version string of this build.
const char* version();

void registerGenerate(CLI::App& app);
void registerRender(CLI::App& app);
void registerLayout(CLI::App& app);
void registerBench(CLI::App& app);
void registerTrajectory(CLI::App& app);
void registerEval(CLI::App& app);
void registerImu(CLI::App& app);
void registerDepthNoise(CLI::App& app);
void registerEvents(CLI::App& app);
void registerVary(CLI::App& app);
void registerDenoiser(CLI::App& app);
void registerAssets(CLI::App& app);
void registerDataset(CLI::App& app);
/// `studio` (cmd_studio.cpp): the web designer's server (src/studio/).
void registerStudio(CLI::App& app);
/// `dataset stats` (cmd_dataset_stats.cpp), added to the `dataset` command by registerDataset.
void registerDatasetStats(CLI::App& dataset_cmd);
/// `dataset shards` (cmd_dataset_shards.cpp), added to the `dataset` command by registerDataset.
void registerDatasetShards(CLI::App& dataset_cmd);

/// Replaces this process with the companion executable `tool` from this binary's folder (the
/// LibTorch tools: interiornet-train-style, interiornet-train-denoiser), as `tool subcommand
/// args...`. Throws InputError if it cannot be run.
[[noreturn]] void execCompanion(const std::string& tool, const std::string& subcommand,
                                const std::vector<std::string>& args);
void addTrajectoryConvertCommand(CLI::App* trajectory_cmd);
void addTrainStyleCommand(CLI::App* trajectory_cmd);
void addSequenceEvalCommands(CLI::App* eval_cmd);
/// `eval slam` (cmd_eval_slam.cpp).
void addSlamEvalCommand(CLI::App* eval_cmd);

}  // namespace inet::app
