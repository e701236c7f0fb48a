#pragma once
// Uniform cubic B-spline of a rigid motion T_world_body(t): the continuous trajectory that the
// IMU (and later every other sensor) samples, so all streams come from one curve (SENSORS.md 1).
//
// Representation: split R3 x SO(3) (Basalt's se3_spline.h / Lovegrove et al. BMVC 2013
// "Spline Fusion" for the rotation part). Control points c_0..c_{n-1} sit at times
// t_j = t_c0 + j*dt; segment i covers [t_i, t_i + dt) with u = (t - t_i)/dt and uses
// c_{i-1}..c_{i+2}; the valid range is [t_1, t_{n-2}].
//
//   position   p(t) = sum_j B_j(u) c_{i-1+j},   B = [(1-u)^3, 3u^3-6u^2+4, -3u^3+3u^2+3u+1, u^3]/6
//              v = sum dB_j c, a = sum ddB_j c with dB = d/dt B (1/dt factor), ddB (1/dt^2):
//              dB  = [-3(1-u)^2, 9u^2-12u, -9u^2+6u+3, 3u^2] / (6 dt)
//              ddB = [6(1-u), 18u-12, -18u+6, 6u] / (6 dt^2)
//   rotation   R(t) = R_{i-1} * A_1 A_2 A_3,  A_j = Exp(bc_j(u) d_j),
//              d_j = Log(R_{i+j-2}^T R_{i+j-1})
//              cumulative basis bc_1 = (5+3u-3u^2+u^3)/6, bc_2 = (1+3u+3u^2-2u^3)/6, bc_3 = u^3/6
//   body rate  each A_j turns about the fixed axis d_j, so A_j^T dA_j/dt = [dbc_j/dt d_j]x and
//              w_body = A_3^T A_2^T (dbc_1 d_1) + A_3^T (dbc_2 d_2) + dbc_3 d_3, i.e. the
//              recursion w <- A_j^T w + dbc_j d_j (j = 1..3, w = 0 at the start). No SO(3)
//              Jacobian appears: that is the point of the cumulative form.
//              dbc_1 = (3-6u+3u^2)/(6dt), dbc_2 = (3+6u-6u^2)/(6dt), dbc_3 = 3u^2/(6dt).
//
// Why not a B-spline of the rotation vector (InteriorNet's paper, SENSORS.md's faithful mode)?
// phi(t) is singular at |phi| = pi, and for our cameras that is not a corner case: an OpenCV
// camera (z forward, y down) that looks level along world -Y has R_world_camera with columns
// (-1,0,0), (0,0,-1), (0,-1,0): trace -1, a rotation by exactly pi. Every look-forward
// trajectory that turns round in yaw passes through it (or within 0.1 rad of it, where
// SENSORS.md would have to reject or unwrap). The cumulative SO(3) spline has no singularity,
// its body rate needs no J_r(phi), and its relative rotations d_j stay small (a few degrees
// between knots). The position part is the same in both.
//
// Fitting (interpolation, not approximation): the input poses are resampled at uniform knots
// (linear position, slerp; exact when the input is already uniform at that spacing), then the
// control points are solved so that the spline passes THROUGH every knot pose:
//   position   (c_{j-1} + 4 c_j + c_{j+1}) / 6 = k_j, a tridiagonal system (Thomas algorithm);
//   rotation   R(t_j) = c_{j-1} Exp(5/6 d) Exp(1/6 d') = k_j, solved by Newton-like iterations:
//              the residuals Log(R(t_j)^T k_j) are mapped through the same (1,4,1)/6 system
//              (the exact Jacobian when neighbouring controls are close) and applied on the
//              right, until the largest residual is below 1e-12 rad (3-6 iterations in practice).
// Ends are "natural": c_{-1} is the reflection of c_1 about c_0 (2c_0 - c_1, and
// c_0 c_1^T c_0 for rotations), which gives zero acceleration at the ends and makes the end knots
// exact too. The valid range is the whole knot range [first knot, last knot].
// Between knots the spline differs from the input poses by the resampling error; fitReport()
// measures it (the tests state the figures for the generated and the TUM trajectories).
#include <string>
#include <vector>

#include "core/pose.h"
#include "trajectory/trajectory.h"

namespace inet {

/// Everything the IMU needs at one time: pose, linear velocity and acceleration in the world,
/// angular velocity in the body frame.
struct SplineState {
  Quat q_world_body = Quat::Identity();
  Vec3 p_world = Vec3::Zero();    ///< m
  Vec3 v_world = Vec3::Zero();    ///< m/s
  Vec3 a_world = Vec3::Zero();    ///< m/s^2 (kinematic, gravity not included)
  Vec3 w_body = Vec3::Zero();     ///< rad/s, in the body frame
};

/// How well a fitted spline reproduces the poses it was fitted to (within its time range).
struct SplineFitReport {
  TimeNs knot_spacing_ns = 0;
  size_t knots = 0;
  int rotation_iterations = 0;       ///< Newton-like iterations of the rotation solve
  double knot_residual_rad = 0.0;    ///< largest rotation residual at the knots after the solve
  double max_position_error_m = 0.0, rms_position_error_m = 0.0;  ///< vs every input pose
  double max_angle_error_rad = 0.0, rms_angle_error_rad = 0.0;
  size_t poses_compared = 0;
  std::string toString() const;
};

struct SplineFitOptions {
  /// Knot spacing; 0 = the input's mean spacing, but at least 50 ms (OpenVINS' rule: denser
  /// knots follow the pose noise of motion-capture files and turn it into large accelerations).
  TimeNs knot_spacing_ns = 0;
};

class PoseSpline {
 public:
  /// Control points at t_c0_ns + j*dt_ns; needs n >= 4 and dt_ns > 0 (INET_CHECK).
  PoseSpline(TimeNs t_c0_ns, TimeNs dt_ns, std::vector<Vec3> ctrl_p, std::vector<Quat> ctrl_q);

  /// The spline through `knots` (poses T_world_body at t0_ns + j*dt_ns, at least 2), natural
  /// ends (see the header comment). `report` (optional) gets the iteration count and residual.
  static PoseSpline interpolate(TimeNs t0_ns, TimeNs dt_ns, const std::vector<Pose>& knots,
                                SplineFitReport* report = nullptr);
  /// Resamples `traj` (poses T_world_body, at least 2) at uniform knots from its first time and
  /// interpolates them; the input after the last whole knot interval is not covered. `report`
  /// gets the errors against every input pose in range. Throws InputError(source, "trajectory")
  /// for fewer than 2 poses or a span shorter than one knot interval.
  static PoseSpline fit(const Trajectory& traj, const SplineFitOptions& opt = {},
                        SplineFitReport* report = nullptr, const std::string& source = "");

  TimeNs startNs() const { return t_c0_ns_ + dt_ns_; }
  TimeNs endNs() const { return t_c0_ns_ + static_cast<TimeNs>(numControls() - 2) * dt_ns_; }
  TimeNs knotSpacingNs() const { return dt_ns_; }
  size_t numControls() const { return ctrl_p_.size(); }

  /// Pose, velocities and acceleration at t (INET_CHECK: t in [startNs, endNs]). `frac_ns` adds
  /// a sub-nanosecond offset in [0, 1) for finite differences finer than 1 ns.
  SplineState evaluate(TimeNs t_ns, double frac_ns = 0.0) const;
  Pose pose(TimeNs t_ns) const;

 private:
  /// Segment index i (1-based as in the header comment) and u for time t.
  void locate(TimeNs t_ns, double frac_ns, size_t& i, double& u) const;

  TimeNs t_c0_ns_, dt_ns_;
  std::vector<Vec3> ctrl_p_;
  std::vector<Quat> ctrl_q_;
  std::vector<Vec3> delta_;  ///< delta_[j] = Log(R_j^T R_{j+1})
};

}  // namespace inet
