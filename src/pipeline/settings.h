#pragma once
// What a sequence is made from, as plain data: the scene source and how it is loaded, the
// camera's lens and response, the random trajectories' motion. The command line (apps/) adds
// its flags around these (SceneArgs, LensArgs, ...); the dataset builder fills them from a
// dataset spec. Errors name the command-line flag of the field, as a user sees it there.
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/lens.h"
#include "scene/mitsuba_importer.h"
#include "scene/scene.h"
#include "trajectory/formats.h"
#include "trajectory/random_trajectory.h"

namespace inet {

/// How a scene argument is interpreted: a layout.json, a 3D-FRONT house (.json), a Sweet Home
/// 3D home (.sh3d), a Mitsuba scene (.xml), or a mesh file (OBJ/glTF/PLY...) imported with
/// Assimp; builtin:room, builtin:apartment, procedural:<seed>, or empty = the built-in default
/// scene.
struct SceneSource {
  std::string path;
  std::string up;  ///< "y", "z" or "auto"; "" = the format's default (auto for mesh files, y for
                   ///< Mitsuba)
  double scale = 1.0;
  std::string labels;
  std::string lights;                ///< light.xml to apply, "" = the scene's own lights
  std::string auto_lights = "auto";  ///< variation/auto_lights.h: auto, on, off
  /// What is used without a path: the built-in room (render, bench) or, for generate, the
  /// built-in apartment where the furniture catalogs are installed.
  bool default_apartment = false;
  /// A path "procedural:<seed>" is the procedural apartment of that seed, with this many rooms
  /// (0 = drawn by the generator) and this furniture (catalog, parametric, mixed; "" = catalog
  /// where the catalogs are installed); its textures are kept in userCacheDir("procedural").
  int rooms = 0;
  std::string furniture;

  /// Loads the scene, applies `lights` and then the automatic lights (auto_lights); prints the
  /// importer's warning summary and what the automatic lights did, once. Throws InputError.
  Scene load() const;
  Scene loadScene() const;  ///< without `lights` and the automatic lights
  bool isDefault() const { return path.empty(); }
  /// builtin:room, or no path where the default is the room.
  bool isBuiltinRoom() const {
    return path == "builtin:room" || (path.empty() && !default_apartment);
  }
  /// builtin:apartment, or no path where the default is the apartment.
  bool isBuiltinApartment() const {
    return path == "builtin:apartment" || (path.empty() && default_apartment);
  }
  /// Is the path "procedural:<seed>"?
  bool isProcedural() const { return path.rfind("procedural:", 0) == 0; }
  /// Is the path a Mitsuba scene file (.xml)?
  bool isMitsuba() const;
  /// What `up`, `scale` and `labels` ask of a Mitsuba import.
  MitsubaOptions mitsubaOptions() const;
};

/// The built-in procedural apartment (seed 0) that commands use when no layout is given and a
/// furnished apartment is needed (its textures are made in a temporary folder and removed).
Scene defaultApartment();

/// The apartment `generate` and `make demo` show where the Sweet Home 3D catalogs are installed
/// (builtin:apartment): procedural apartment seed kBuiltinApartmentSeed, 4 rooms, furnished from
/// the catalogs, daylight; its textures live in userCacheDir("builtin"). Without the catalogs,
/// an InputError saying how to install them.
Scene builtinApartment();
inline constexpr uint64_t kBuiltinApartmentSeed = 3;

/// readTrajectory, with what the reader did about the file's quirks (repeated stamps: see
/// TrajectoryReadReport) printed as one warning line.
Trajectory readTrajectoryFile(const std::string& path, std::optional<TrajectoryFormat> fmt = {},
                              const TrajectoryFormatOptions& opt = {});
/// Prints `report`'s summary as "warning: PATH: ..." when there is one.
void warnTrajectoryRead(const std::string& path, const TrajectoryReadReport& report);

/// The camera's response to light, applied to the path-traced RGB before 8-bit encoding:
/// exposure, optional sensor noise (shot + read, IMX250 defaults), tone curve. EXR output and
/// ground truth are never touched.
struct ResponseSettings {
  float exposure_ev = 0.f;
  /// Linear multiplier before exposure_ev: 1, or what `generate`'s auto exposure metered.
  float exposure_scale = 1.f;
  std::string tone = "none";
  bool sensor_noise = false;
  /// Validates the options (InputError naming the flag).
  void validate() const;
  bool identity() const {
    return exposure_ev == 0.f && exposure_scale == 1.f && tone == "none" && !sensor_noise;
  }
  /// Linear RGB -> display-referred linear RGB in [0, 1] (then sRGB-encoded by the writers).
  ImageF apply(const ImageF& linear, uint64_t seed, uint32_t frame) const;
  std::string describe() const;
};

/// The lens of `render` and `generate` (docs/cameras.md). A setting the chosen lens does not use
/// is an error, not silently ignored.
struct LensSettings {
  std::string lens;  ///< registry name; empty = thin_lens if aperture_m > 0, else pinhole
  double aperture_m = 0.0;
  double focus_m = 2.0;
  bool focus_set = false;  ///< focus_m was given (only a thin lens uses it)
  double fisheye_fov_deg = 180.0;
  bool fisheye_fov_set = false;  ///< fisheye_fov_deg was given (only a fisheye uses it)
  /// Brown-Conrady coefficients k1, k2, p1, p2[, k3] in OpenCV's order (pinhole and thin lens);
  /// empty = none
  std::vector<double> distortion;
  /// The chosen model. InputError naming the flag: unknown --lens (listing the valid names),
  /// values out of range, or a setting the model does not use (--aperture/--focus without a
  /// thin lens, --fisheye-fov without a fisheye, --distortion on a fisheye or panorama).
  LensType type() const;
  /// The lens. Pinhole and thin lens use K as given; a fisheye takes only K's size (square,
  /// checked by the caller) and derives f from fisheye_fov_deg; a panorama takes only K's size.
  /// InputError on --distortion that folds over inside the image (it cannot be rendered).
  LensModel make(const CameraIntrinsics& K, const std::string& where) const;
  /// InputError on --distortion when a fifth coefficient (k3) meets the ASL layout among the
  /// output `formats`: Kalibr's radial-tangential sensor.yaml holds k1 k2 p1 p2 only.
  void checkFormats(const std::vector<std::string>& formats) const;
};

/// Options of the random trajectories (trajectory/random_trajectory.h) that `generate`,
/// `trajectory generate` and the dataset builder share.
struct MotionSettings {
  double v_mult = 0.0;  ///< 0 = drawn per trajectory
  double w_mult = 0.0;
  double clearance = 0.25;
  double min_height = 1.0, max_height = 2.0;
  std::string style = "none";  ///< none | learned
  /// Options for a trajectory of `type` with these settings (InputError naming the flag).
  RandomTrajectoryOptions options(MotionType type, uint64_t seed, int frames, double fps) const;
};

}  // namespace inet
