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
// Fitting (PoseSpline::fit): least squares against every input pose at its own stamp (no
// resampling), with a penalty on differences of the controls, a P-spline (Eilers & Marx,
// "Flexible smoothing with B-splines and penalties", Statistical Science 11(2), 1996):
//   position   min_c  sum_k |p(t_k) - p_k|^2 + lambda sum_j |D4 c_j|^2,
//              D4 c_j = c_{j+4} - 4 c_{j+3} + 6 c_{j+2} - 4 c_{j+1} + c_j
//   rotation   min_R  sum_k |Log(R(t_k)^T R_k)|^2 + lambda sum_j |D3 d_j|^2, d_j = Log(R_j^T R_j+1)
// lambda = 1e-6 (per input pose). Why:
// - Exact motions. The controls of a cubic f(t) are c_j = f(t_j) - dt^2 f''(t_j) / 6, a cubic
//   sequence in j, so D4 c = 0 and both terms vanish: a position polynomial of degree <= 3
//   (constant acceleration in particular) comes out exact from any stamps at any knot spacing.
//   Rotation controls R_j = R_0 Exp(w t_j) give equal d_j = w dt, D3 d = 0, and since the
//   cumulative weights sum to 1 + u, R(t) = R_0 Exp(w t): a constant angular velocity is exact.
//   The fit this replaced (issue 13) resampled at the knots linearly (not exact for a parabola)
//   and interpolated with natural ends (a = 0 at both ends, ringing inwards): the accelerometer
//   of a 25 Hz file of p = t^2/2 read 0 .. 1.24 m/s^2 instead of 1.
// - The penalty decides what the poses leave open: the ends, knots denser than the input, gaps.
//   There the curve continues as smoothly as D4 allows. D4 rather than Eilers & Marx's usual
//   D2/D3: D3 keeps quadratics exact too, but bends the ends towards a parabola, an O(dt)
//   acceleration error there (0.09 m/s^2 on a 2 rad/s, 0.5 m sinusoid from 25 Hz with knots at
//   the samples), D4 an O(dt^2) one (0.004). Fewer than 4 distinct stamps lower the order to
//   their number (2 stamps: D2, linear motion and constant rate exact).
// - Knots at the input stamps (generate's 200 Hz samples) must reproduce the samples. One pass
//   misses them by ~lambda |D4^T D4 c|: 6e-9 m and 2e-8 rad on generated hand-held paths (their
//   bounces and learned jitter are rough at 5 ms). A smaller lambda would cost precision where
//   the penalty alone holds the curve (the normal matrix's condition grows as 1/lambda). So a
//   second pass of iterated Tikhonov (Hanke & Groetsch, JOTA 98(1), 1998) follows:
//   min |B c - y|^2 + lambda |D4 (c - c_1)|^2 around the first solution c_1 (for rotations the
//   penalty's target is the first pass's D3 d), which leaves ~lambda^2 of the miss and keeps
//   whatever is exact exact: 5e-12 m and 4e-11 rad on the same paths.
// Solving. Position: B (one row per input pose: its four basis weights) and the banded normal
// matrix B^T B + lambda D4^T D4, factored once (Eigen's SimplicialLDLT in natural order: no
// fill outside the band), the second pass a back-substitution more. It is solved after taking
// out the least-squares cubic of the input and adding back that cubic's exact controls, so a
// polynomial input leaves only the rounding of its samples. Rotation: Gauss-Newton over right
// updates R_j Exp(delta_j) with exact Jacobians (SO(3) J_r, J_l^-1 through the cumulative
// product), from controls on the geodesics between the input poses (exact for a constant
// rate); block-banded 3n x 3n normal equations refactored per step. 3-9 steps for both passes
// in the tests; it converges with up to 3 rad between knots and reports an InputError where it
// cannot (about pi between knots: the rotation is aliased). 100 s of 200 Hz poses take 0.09 s
// (50 ms knots) and 0.21 s (5 ms knots) on one core (bench/imu_bench, BM_SplineFit).
// Range: knots from the first stamp every dt; the poses after the last whole knot interval
// still take part in the fit, but the valid range ends at that knot.
#include <string>
#include <vector>

#include "core/pose.h"
#include "trajectory/trajectory.h"

namespace inet {

/// Everything the IMU needs at one time: pose, linear velocity and acceleration in the world,
/// angular velocity in the body frame.
struct SplineState {
  Quat q_world_body = Quat::Identity();
  Vec3 p_world = Vec3::Zero();  ///< m
  Vec3 v_world = Vec3::Zero();  ///< m/s
  Vec3 a_world = Vec3::Zero();  ///< m/s^2 (kinematic, gravity not included)
  Vec3 w_body = Vec3::Zero();   ///< rad/s, in the body frame
};

/// How well a fitted spline reproduces the poses it was fitted to (within its time range).
struct SplineFitReport {
  TimeNs knot_spacing_ns = 0;
  size_t knots = 0;
  int rotation_iterations = 0;     ///< Gauss-Newton iterations of the rotation solve
  double rotation_step_rad = 0.0;  ///< largest control update of the last iteration
  int difference_order = 0;        ///< of the position penalty: 4 (fewer stamps: their number)
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

  /// fit() of `knots` (poses T_world_body at t0_ns + j*dt_ns, at least 2) with knots at their
  /// stamps: the spline through them (to ~1e-11 m; header comment), valid over
  /// [t0_ns, t0_ns + (n-1) dt_ns].
  static PoseSpline interpolate(TimeNs t0_ns, TimeNs dt_ns, const std::vector<Pose>& knots,
                                SplineFitReport* report = nullptr);
  /// The penalised least-squares spline of `traj` (poses T_world_body, at least 2, stamps not
  /// decreasing; header comment), knots every opt.knot_spacing_ns from its first stamp, valid up
  /// to the last knot within the input. `report` gets the solve's figures and the errors
  /// against every input pose in range. Throws InputError(source, "trajectory") for fewer than 2
  /// poses, a stamp before the previous one, a span shorter than one knot interval, or a
  /// rotation solve that does not converge (a turn of about 180 degrees between poses).
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
