#pragma once
// The paper's base random trajectories (section 6.1), after SceneNet RGB-D's two-body system: a
// camera body and a look-at body move under smooth random forces with drag and bounce off the
// free space's boundary.
//   two-body      both bodies wander independently (type-1)
//   hand-held     as two-body, but the look-at point stays below the camera (type-2)
//   look-forward  the view turns towards the camera's velocity through a critically damped
//                 angular spring (the paper's proportional correction of the look-at point,
//                 done on the yaw so that a bounce turns the view around instead of pulling
//                 the look-at point through the camera), and the camera's random forces are
//                 turned into its velocity's hemisphere (type-3): the camera moves where it looks
// In the first two types the look-at body moves relative to the camera (it is carried along),
// so the view's turn rate comes mostly from its own motion (w_mult) rather than from parallax.
// Camera heights stay in [min_height, max_height] (1-2 m), the up vector leans 0-5 degrees off
// gravity (a slowly varying random tilt), and per trajectory a velocity multiplier U(0.5, 5) and
// an angular multiplier U(0.5, 3) scale the motion (both can be set).
//
// The simulation runs at 1 kHz. Random forces are Ornstein-Uhlenbeck processes (correlation time
// tau), so acceleration is continuous and the positions are C2. In free flight a body with drag
// k = 1/s driven by such a force of standard deviation sigma per axis moves with an RMS speed of
// sigma * sqrt(tau / (k (1 + k tau))) per axis; sigma is set so the camera's horizontal RMS speed
// is base_speed * v_mult. Near geometry a spring pushes the bodies out along the distance
// field's gradient, and a step that would come closer than the clearance is undone and the
// velocity reflected, so every simulated camera position keeps the clearance by construction
// (FreeSpace::hasClearance: the grid where it decides, the exact triangle distance where not); output poses are also checked against
// the exact triangle distance.
#include <cstdint>
#include <string>

#include "trajectory/free_space.h"
#include "trajectory/trajectory.h"

namespace inet {

enum class MotionType { TwoBody, HandHeld, LookForward };
/// "two-body", "hand-held", "look-forward"; throws InputError(field) otherwise.
MotionType parseMotionType(const std::string& name, const std::string& field = "--type");
const char* motionTypeName(MotionType t);

struct RandomTrajectoryOptions {
  MotionType type = MotionType::TwoBody;
  uint64_t seed = 0;
  int frames = 250;
  double fps = 25.0;
  double exposure_s = 0.0;  ///< shutter open time per frame (close = open + exposure)
  double v_mult = 0.0;      ///< <= 0: drawn from U(0.5, 5.0)
  double w_mult = 0.0;      ///< <= 0: drawn from U(0.5, 3.0)
  double base_speed = 0.3;  ///< horizontal RMS camera speed at v_mult 1 (m/s)
  double base_turn_deg = 20.0;  ///< RMS turn rate of the view at w_mult 1 (deg/s)
  double min_height = 1.0, max_height = 2.0;  ///< camera height above z = 0 (m)
  double max_tilt_deg = 5.0;                  ///< up vector off gravity
  double clearance = 0.25;                    ///< camera to geometry (m)
  double dense_rate = 200.0;  ///< rate of the dense pose samples kept for sensors (Hz)
  /// Hand-held motion from the learned style model (style_model.h, builtinStyleModel()) on top
  /// of the base path, kept at the clearance; frames are then taken from the styled dense path.
  bool learned_style = false;
};

struct RandomTrajectory {
  Trajectory frames;          ///< one pose per frame, at shutter open
  Trajectory shutter_close;   ///< one pose per frame, at shutter close
  Trajectory dense;           ///< poses at dense_rate over the whole span (for splines, IMU)
  std::vector<double> tilt_deg;  ///< per frame: the base up vector's angle to gravity
  double v_mult = 1.0, w_mult = 1.0;  ///< the multipliers used
};

/// Simulates a trajectory in `space`. Deterministic in (options, space). Throws
/// InputError(source, "free space", ...) when no start position has the clearance at an allowed
/// height.
RandomTrajectory generateRandomTrajectory(const FreeSpace& space,
                                          const RandomTrajectoryOptions& opt,
                                          const std::string& source = "");

}  // namespace inet
