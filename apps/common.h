#pragma once
// Shared pieces of the command line: options every subcommand understands and scene loading.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/lens.h"
#include "scene/mitsuba_importer.h"
#include "scene/scene.h"
#include "trajectory/formats.h"
#include "trajectory/random_trajectory.h"

namespace inet::app {

/// How a scene argument is interpreted: a layout.json, a Mitsuba scene (.xml), or a mesh file
/// (OBJ/glTF/PLY...) imported with Assimp; empty path = the built-in default scene.
struct SceneArgs {
  std::string path;
  std::string up;  ///< "y", "z" or "auto"; "" = the format's default (auto for mesh files, y for
                   ///< Mitsuba)
  double scale = 1.0;
  std::string labels;
  std::string lights;  ///< light.xml to apply, "" = the scene's own lights
  std::string auto_lights = "auto";  ///< variation/auto_lights.h: auto, on, off
  /// Adds --layout/--scene, --up, --scale, --labels, --lights, --auto-lights to `cmd`;
  /// `without` says what the command does without --layout.
  void addTo(CLI::App& cmd, const std::string& without = "the built-in furnished room");
  /// Loads the scene, applies --lights and then the automatic lights (--auto-lights); prints
  /// the importer's warning summary and what the automatic lights did, once. Throws InputError.
  Scene load() const;
  Scene loadScene() const;  ///< without --lights and --auto-lights
  bool isDefault() const { return path.empty(); }
  /// What the command uses without --layout: the built-in room (render, bench) or, for
  /// generate, the built-in apartment where the furniture catalogs are installed.
  bool default_apartment = false;
  /// --layout builtin:room, or no --layout where the default is the room.
  bool isBuiltinRoom() const {
    return path == "builtin:room" || (path.empty() && !default_apartment);
  }
  /// --layout builtin:apartment, or no --layout where the default is the apartment.
  bool isBuiltinApartment() const {
    return path == "builtin:apartment" || (path.empty() && default_apartment);
  }
  /// Is the path a Mitsuba scene file (.xml)?
  bool isMitsuba() const;
  /// What --up, --scale and --labels ask of a Mitsuba import.
  MitsubaOptions mitsubaOptions() const;
};

/// The camera's response to light, applied to the path-traced RGB before 8-bit encoding:
/// exposure, optional sensor noise (shot + read, IMX250 defaults), tone curve. EXR output and
/// ground truth are never touched.
struct ResponseArgs {
  float exposure_ev = 0.f;
  /// Linear multiplier before exposure_ev: 1, or what `generate`'s auto exposure metered.
  float exposure_scale = 1.f;
  std::string tone = "none";
  bool sensor_noise = false;
  void addTo(CLI::App& cmd);
  /// Validates the options (InputError naming the flag).
  void validate() const;
  bool identity() const {
    return exposure_ev == 0.f && exposure_scale == 1.f && tone == "none" && !sensor_noise;
  }
  /// Linear RGB -> display-referred linear RGB in [0, 1] (then sRGB-encoded by the writers).
  ImageF apply(const ImageF& linear, uint64_t seed, uint32_t frame) const;
  std::string describe() const;
};

/// --lens, --aperture, --focus, --fisheye-fov: the lens of `render` and `generate`
/// (docs/cameras.md). A flag the chosen lens does not use is an error, not silently ignored.
struct LensArgs {
  std::string lens;  ///< registry name; empty = thin_lens if --aperture > 0, else pinhole
  double aperture_m = 0.0;
  double focus_m = 2.0;
  double fisheye_fov_deg = 180.0;
  /// Adds the four options to `cmd`.
  void addTo(CLI::App& cmd);
  /// The chosen model. InputError naming the flag: unknown --lens (listing the valid names),
  /// values out of range, or a flag the model does not use (--aperture/--focus without a thin
  /// lens, --fisheye-fov without a fisheye).
  LensType type() const;
  /// The lens. Pinhole and thin lens use K as given; a fisheye takes only K's size (square,
  /// checked by the caller) and derives f from --fisheye-fov; a panorama takes only K's size.
  LensModel make(const CameraIntrinsics& K, const std::string& where) const;

 private:
  CLI::Option* focus_opt_ = nullptr;
  CLI::Option* fov_opt_ = nullptr;
};

/// Options of the random trajectories (trajectory/random_trajectory.h) that `generate` and
/// `trajectory generate` share: --v-mult, --w-mult, --clearance, --min-height, --max-height,
/// --style.
struct MotionArgs {
  double v_mult = 0.0;  ///< 0 = drawn per trajectory
  double w_mult = 0.0;
  double clearance = 0.25;
  double min_height = 1.0, max_height = 2.0;
  std::string style = "none";  ///< none | learned
  void addTo(CLI::App& cmd);
  /// Options for a trajectory of `type` with these settings (InputError naming the flag).
  RandomTrajectoryOptions options(MotionType type, uint64_t seed, int frames, double fps) const;
};

/// The built-in procedural apartment (seed 0) that commands use when no layout is given and a
/// furnished apartment is needed (its textures are made in a temporary folder and removed).
Scene defaultApartment();

/// The apartment `generate` and `make demo` show where the Sweet Home 3D catalogs are installed
/// (--layout builtin:apartment): procedural apartment seed kBuiltinApartmentSeed, 4 rooms,
/// furnished from the catalogs, daylight; its textures live in userCacheDir("builtin").
/// Without the catalogs, an InputError saying how to install them.
Scene builtinApartment();
inline constexpr uint64_t kBuiltinApartmentSeed = 3;

/// readTrajectory, with what the reader did about the file's quirks (repeated stamps: see
/// TrajectoryReadReport) printed as one warning line.
Trajectory readTrajectoryFile(const std::string& path, std::optional<TrajectoryFormat> fmt = {},
                              const TrajectoryFormatOptions& opt = {});
/// Prints `report`'s summary as "warning: PATH: ..." when there is one.
void warnTrajectoryRead(const std::string& path, const TrajectoryReadReport& report);

/// Stopping long commands cleanly. A scheduler (Slurm, Kubernetes) sends SIGTERM some seconds
/// before it kills a job, a user Ctrl-C (SIGINT). After installStopHandlers() such a signal only
/// raises a flag; the command stops at its next safe point (between frames, between layouts),
/// where every file written so far is whole, and exits with 128 + the signal (130 for SIGINT,
/// 143 for SIGTERM), saying that a rerun of the same command resumes.
void installStopHandlers();
/// The signal that asked to stop (SIGINT, SIGTERM), or 0.
int stopSignal();
/// If a signal came: prints "stopped by SIGTERM <done>; rerun the same command to resume" and
/// throws CLI::RuntimeError(128 + signal), which main() turns into that exit status.
void stopIfSignalled(const std::string& done);

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

/// Replaces this process with the companion executable `tool` from this binary's folder (the
/// LibTorch tools: interiornet-train-style, interiornet-train-denoiser), as `tool subcommand
/// args...`. Throws InputError if it cannot be run.
[[noreturn]] void execCompanion(const std::string& tool, const std::string& subcommand,
                                const std::vector<std::string>& args);
void addTrajectoryConvertCommand(CLI::App* trajectory_cmd);
void addTrainStyleCommand(CLI::App* trajectory_cmd);
void addSequenceEvalCommands(CLI::App* eval_cmd);

}  // namespace inet::app
