#pragma once
// The studio's random-trajectory requests: the JSON a page sends, checked field by field with
// the command line's rules and one-line messages (`interiornet trajectory generate`), and the
// poses it gets back.
//
// Request (every key optional; an unknown key is an error naming the valid ones):
//   {"type": "two-body" | "hand-held" | "look-forward",   default two-body
//    "frames": 1..max_frames (default 250), "fps": (0, 10000] (default 25), "seed": >= 0,
//    "v_mult": 0 = drawn or (0, 100], "w_mult": likewise, "clearance": 0..5 m (0.25),
//    "min_height", "max_height": 0 <= min < max <= 100 m (1, 2), "style": "none" | "learned"}
// Response:
//   {"layout": name, "type", "seed", "frames", "fps", "v_mult", "w_mult" (the ones used),
//    "style", "compute_ms",
//    "poses": [{"t_ns": int, "position": [x, y, z], "quaternion_xyzw": [x, y, z, w]}, ...]}
// Poses are T_world_camera: world Z up, metres; camera axes as OpenCV (x right, y down,
// z forward); t_ns from 0 at the first frame (shutter open).
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

#include "pipeline/settings.h"
#include "studio/studio_layout.h"
#include "trajectory/random_trajectory.h"

namespace inet::studio {

struct TrajectoryRequest {
  MotionType type = MotionType::TwoBody;
  int frames = 250;
  double fps = 25.0;
  uint64_t seed = 0;
  MotionSettings motion;
  /// The generator's options (checked when the request was parsed).
  RandomTrajectoryOptions options() const;
};

/// Parses and checks a request body (already parsed as JSON). Throws InputError("", key,
/// problem): the key as the page sends it, the problem as the command line words it.
TrajectoryRequest parseTrajectoryRequest(const nlohmann::json& body, int max_frames);

/// Generates the trajectory through `layout`'s free space and returns the response above.
/// Throws InputError when the layout has no room for a camera.
nlohmann::json runTrajectoryRequest(const StudioLayout& layout, const TrajectoryRequest& req);

}  // namespace inet::studio
