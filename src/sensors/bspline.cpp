#include "sensors/bspline.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "sensors/so3.h"

namespace inet {
namespace {

/// Solves (x_{j-1} + 4 x_j + x_{j+1}) / 6 = rhs_j for j = 0..n-1 with x_{-1} = x_n = 0
/// (Thomas algorithm; the matrix is strictly diagonally dominant, so no pivoting).
std::vector<Vec3> solveTridiagonal141(const std::vector<Vec3>& rhs) {
  const size_t n = rhs.size();
  std::vector<Vec3> x(n);
  if (n == 0) return x;
  std::vector<double> c(n);  // modified super-diagonal
  const double a = 1.0 / 6.0, b = 4.0 / 6.0;
  c[0] = a / b;
  x[0] = rhs[0] / b;
  for (size_t j = 1; j < n; ++j) {
    const double m = b - a * c[j - 1];
    c[j] = a / m;
    x[j] = (rhs[j] - a * x[j - 1]) / m;
  }
  for (size_t j = n - 1; j-- > 0;) x[j] -= c[j] * x[j + 1];
  return x;
}

/// Rotation at knot j (u = 0 of the segment whose controls are q[j-1..j+2]), from the
/// cumulative form: R = q[j-1] Exp(5/6 d_{j-1}) Exp(1/6 d_j).
Quat rotationAtKnot(const std::vector<Quat>& q, size_t j) {
  const Vec3 d0 = so3::logQuat(q[j - 1].conjugate() * q[j]);
  const Vec3 d1 = so3::logQuat(q[j].conjugate() * q[j + 1]);
  return q[j - 1] * so3::expQuat(d0 * (5.0 / 6.0)) * so3::expQuat(d1 * (1.0 / 6.0));
}

/// Natural-end virtual controls: reflection of the neighbour about the end control.
void reflectEnds(std::vector<Quat>& q) {
  const size_t n = q.size();
  q[0] = (q[1] * q[2].conjugate() * q[1]).normalized();
  q[n - 1] = (q[n - 2] * q[n - 3].conjugate() * q[n - 2]).normalized();
}

}  // namespace

std::string SplineFitReport::toString() const {
  return fmt::format(
      "spline: {} knots every {:.6f} s, rotation solve {} iterations (residual {:.2e} rad); vs "
      "{} input poses: position max {:.3e} m rms {:.3e} m, angle max {:.3e} deg rms {:.3e} deg",
      knots, static_cast<double>(knot_spacing_ns) * 1e-9, rotation_iterations, knot_residual_rad,
      poses_compared, max_position_error_m, rms_position_error_m,
      max_angle_error_rad * 180.0 / M_PI, rms_angle_error_rad * 180.0 / M_PI);
}

PoseSpline::PoseSpline(TimeNs t_c0_ns, TimeNs dt_ns, std::vector<Vec3> ctrl_p,
                       std::vector<Quat> ctrl_q)
    : t_c0_ns_(t_c0_ns), dt_ns_(dt_ns), ctrl_p_(std::move(ctrl_p)), ctrl_q_(std::move(ctrl_q)) {
  INET_CHECK(dt_ns_ > 0);
  INET_CHECK(ctrl_p_.size() >= 4 && ctrl_p_.size() == ctrl_q_.size());
  delta_.resize(ctrl_q_.size() - 1);
  for (size_t j = 0; j + 1 < ctrl_q_.size(); ++j) {
    ctrl_q_[j + 1].normalize();
    delta_[j] = so3::logQuat(ctrl_q_[j].normalized().conjugate() * ctrl_q_[j + 1]);
  }
  ctrl_q_[0].normalize();
}

PoseSpline PoseSpline::interpolate(TimeNs t0_ns, TimeNs dt_ns, const std::vector<Pose>& knots,
                                   SplineFitReport* report) {
  const size_t m = knots.size();
  INET_CHECK(m >= 2 && dt_ns > 0);
  // controls 1..m carry knots 0..m-1; controls 0 and m+1 are the natural-end reflections
  std::vector<Vec3> p(m + 2);
  p[1] = knots[0].t;
  p[m] = knots[m - 1].t;
  if (m > 2) {
    std::vector<Vec3> rhs(m - 2);
    for (size_t j = 0; j < m - 2; ++j) rhs[j] = knots[j + 1].t;
    rhs.front() -= p[1] / 6.0;
    rhs.back() -= p[m] / 6.0;
    const std::vector<Vec3> x = solveTridiagonal141(rhs);
    for (size_t j = 0; j < m - 2; ++j) p[j + 2] = x[j];
  }
  p[0] = 2.0 * p[1] - p[2];
  p[m + 1] = 2.0 * p[m] - p[m - 1];

  std::vector<Quat> q(m + 2);
  for (size_t j = 0; j < m; ++j) {
    q[j + 1] = knots[j].q.normalized();
    // same hemisphere as the previous control so that products stay well conditioned
    if (j > 0 && q[j + 1].dot(q[j]) < 0) q[j + 1].coeffs() = -q[j + 1].coeffs();
  }
  reflectEnds(q);
  int iterations = 0;
  double residual = 0.0;
  std::vector<Vec3> r(m > 2 ? m - 2 : 0);
  for (; iterations < 50; ++iterations) {
    residual = 0.0;
    for (size_t j = 0; j < r.size(); ++j) {
      r[j] = so3::logQuat(rotationAtKnot(q, j + 2).conjugate() * knots[j + 1].q.normalized());
      residual = std::max(residual, r[j].norm());
    }
    if (residual < 1e-12) break;
    const std::vector<Vec3> dx = solveTridiagonal141(r);
    for (size_t j = 0; j < r.size(); ++j) q[j + 2] = (q[j + 2] * so3::expQuat(dx[j])).normalized();
    reflectEnds(q);
  }
  if (report) {
    report->knot_spacing_ns = dt_ns;
    report->knots = m;
    report->rotation_iterations = iterations;
    report->knot_residual_rad = residual;
  }
  return PoseSpline(t0_ns - dt_ns, dt_ns, std::move(p), std::move(q));
}

PoseSpline PoseSpline::fit(const Trajectory& traj, const SplineFitOptions& opt,
                           SplineFitReport* report, const std::string& source) {
  if (traj.size() < 2)
    throw InputError(source, "trajectory", "a spline needs at least 2 poses");
  const TimeNs t_first = traj.poses.front().t_ns, t_last = traj.poses.back().t_ns;
  TimeNs dt = opt.knot_spacing_ns;
  if (dt <= 0)
    dt = std::max<TimeNs>((t_last - t_first) / static_cast<TimeNs>(traj.size() - 1), 50'000'000);
  const TimeNs intervals = (t_last - t_first) / dt;
  if (intervals < 1)
    throw InputError(source, "trajectory",
                     fmt::format("spans {:.6f} s, less than one knot interval ({:.6f} s)",
                                 static_cast<double>(t_last - t_first) * 1e-9,
                                 static_cast<double>(dt) * 1e-9));
  // resample at the knots: linear position, slerp rotation between the bracketing poses
  std::vector<Pose> knots(static_cast<size_t>(intervals) + 1);
  size_t k = 0;
  for (size_t j = 0; j < knots.size(); ++j) {
    const TimeNs t = t_first + static_cast<TimeNs>(j) * dt;
    while (k + 2 < traj.size() && traj.poses[k + 1].t_ns <= t) ++k;
    const TimedPose& a = traj.poses[k];
    const TimedPose& b = traj.poses[k + 1];
    const double s = static_cast<double>(t - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
    knots[j].t = (1.0 - s) * a.T_world_camera.t + s * b.T_world_camera.t;
    knots[j].q = a.T_world_camera.q.normalized().slerp(s, b.T_world_camera.q.normalized());
  }
  PoseSpline spline = interpolate(t_first, dt, knots, report);
  if (report) {
    double sum_p = 0, sum_a = 0;
    report->max_position_error_m = report->max_angle_error_rad = 0;
    report->poses_compared = 0;
    for (const TimedPose& tp : traj.poses) {
      if (tp.t_ns > spline.endNs()) break;
      const Pose s = spline.pose(tp.t_ns);
      const double ep = (s.t - tp.T_world_camera.t).norm();
      const double ea = so3::angleBetween(s.q, tp.T_world_camera.q.normalized());
      report->max_position_error_m = std::max(report->max_position_error_m, ep);
      report->max_angle_error_rad = std::max(report->max_angle_error_rad, ea);
      sum_p += ep * ep;
      sum_a += ea * ea;
      ++report->poses_compared;
    }
    const double n = static_cast<double>(std::max<size_t>(report->poses_compared, 1));
    report->rms_position_error_m = std::sqrt(sum_p / n);
    report->rms_angle_error_rad = std::sqrt(sum_a / n);
  }
  return spline;
}

void PoseSpline::locate(TimeNs t_ns, double frac_ns, size_t& i, double& u) const {
  INET_CHECK_MSG(t_ns >= startNs() && t_ns <= endNs(),
                 fmt::format("spline evaluated at {} ns outside [{}, {}]", t_ns, startNs(),
                             endNs()));
  const TimeNs rel = t_ns - startNs();
  i = std::min<size_t>(static_cast<size_t>(rel / dt_ns_), numControls() - 4) + 1;
  const TimeNs seg_start = t_c0_ns_ + static_cast<TimeNs>(i) * dt_ns_;
  u = (static_cast<double>(t_ns - seg_start) + frac_ns) / static_cast<double>(dt_ns_);
}

SplineState PoseSpline::evaluate(TimeNs t_ns, double frac_ns) const {
  size_t i;
  double u;
  locate(t_ns, frac_ns, i, u);
  const double dt = static_cast<double>(dt_ns_) * 1e-9;
  const double u2 = u * u, u3 = u2 * u, v = 1.0 - u;
  const double B[4] = {v * v * v / 6.0, (3 * u3 - 6 * u2 + 4) / 6.0,
                       (-3 * u3 + 3 * u2 + 3 * u + 1) / 6.0, u3 / 6.0};
  const double dB[4] = {-3 * v * v / (6 * dt), (9 * u2 - 12 * u) / (6 * dt),
                        (-9 * u2 + 6 * u + 3) / (6 * dt), 3 * u2 / (6 * dt)};
  const double ddB[4] = {6 * v / (6 * dt * dt), (18 * u - 12) / (6 * dt * dt),
                         (-18 * u + 6) / (6 * dt * dt), 6 * u / (6 * dt * dt)};
  SplineState s;
  s.p_world.setZero();
  for (int j = 0; j < 4; ++j) {
    const Vec3& c = ctrl_p_[i - 1 + j];
    s.p_world += B[j] * c;
    s.v_world += dB[j] * c;
    s.a_world += ddB[j] * c;
  }
  const double bc[3] = {(5 + 3 * u - 3 * u2 + u3) / 6.0, (1 + 3 * u + 3 * u2 - 2 * u3) / 6.0,
                        u3 / 6.0};
  const double dbc[3] = {(3 - 6 * u + 3 * u2) / (6 * dt), (3 + 6 * u - 6 * u2) / (6 * dt),
                         3 * u2 / (6 * dt)};
  Quat q = ctrl_q_[i - 1];
  Vec3 w = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    const Vec3& d = delta_[i - 1 + j];
    const Quat A = so3::expQuat(bc[j] * d);
    q = q * A;
    w = A.conjugate() * w + dbc[j] * d;
  }
  s.q_world_body = q.normalized();
  s.w_body = w;
  return s;
}

Pose PoseSpline::pose(TimeNs t_ns) const {
  const SplineState s = evaluate(t_ns);
  return {s.q_world_body, s.p_world};
}

}  // namespace inet
