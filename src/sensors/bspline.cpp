#include "sensors/bspline.h"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "sensors/so3.h"

namespace inet {
namespace {

using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;

// lambda and the passes of the fit (header comment)
constexpr double kPenalty = 1e-6;
constexpr int kPasses = 2;
constexpr int kMaxOrder = 4;
constexpr int kMaxRotationIterations = 30;       // per pass; Gauss-Newton needs 2-5
constexpr double kRotationStepDoneRad = 1e-13;   // converged
constexpr double kRotationStepNoiseRad = 1e-10;  // below it, a step that stops shrinking is noise
constexpr double kRotationStepFailRad = 1e-9;    // still moving this much: not converging

/// Cumulative weights bc_1..bc_3 of the rotation part at u (header comment).
std::array<double, 3> cumulativeBasis(double u) {
  const double u2 = u * u, u3 = u2 * u;
  return {(5 + 3 * u - 3 * u2 + u3) / 6.0, (1 + 3 * u + 3 * u2 - 2 * u3) / 6.0, u3 / 6.0};
}

/// d[j] = Log(q[j]^T q[j+1]).
std::vector<Vec3> relativeRotations(const std::vector<Quat>& q) {
  std::vector<Vec3> d(q.size() - 1);
  for (size_t j = 0; j + 1 < q.size(); ++j) d[j] = so3::logQuat(q[j].conjugate() * q[j + 1]);
  return d;
}

/// Coefficients of the k-th forward difference, applied to x_j .. x_{j+k}.
std::vector<double> differenceCoefficients(int k) {
  std::vector<double> c{1.0};
  for (int i = 0; i < k; ++i) {
    std::vector<double> next(c.size() + 1, 0.0);
    for (size_t m = 0; m < c.size(); ++m) {
      next[m] -= c[m];
      next[m + 1] += c[m];
    }
    c = std::move(next);
  }
  return c;
}

/// The penalised least-squares system that the position solve and every Gauss-Newton step of
/// the rotation solve share (header comment): one row of B per input pose (the four basis
/// weights of its segment), one row of D per `order`-th difference of the n controls, and the
/// normal matrix B^T B + lambda D^T D, banded, factored once.
class PenalisedSystem {
 public:
  PenalisedSystem(TimeNs t_c0_ns, TimeNs dt_ns, size_t n, const Trajectory& traj, int order)
      : n_(n), order_(order), diff_(differenceCoefficients(order)) {
    const TimeNs t_start = t_c0_ns + dt_ns;
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(traj.size() * 16 + n * diff_.size() * diff_.size());
    for (const TimedPose& tp : traj.poses) {
      const size_t seg = std::min(static_cast<size_t>((tp.t_ns - t_start) / dt_ns), n - 4);
      const TimeNs seg_start = t_start + static_cast<TimeNs>(seg) * dt_ns;
      const double u = static_cast<double>(tp.t_ns - seg_start) / static_cast<double>(dt_ns);
      const double v = 1.0 - u, u2 = u * u, u3 = u2 * u;
      const std::array<double, 4> w = {v * v * v / 6.0, (3 * u3 - 6 * u2 + 4) / 6.0,
                                       (-3 * u3 + 3 * u2 + 3 * u + 1) / 6.0, u3 / 6.0};
      first_.push_back(seg);
      u_.push_back(u);
      weights_.push_back(w);
      for (size_t a = 0; a < 4; ++a)
        for (size_t b = 0; b < 4; ++b)
          entries.emplace_back(static_cast<int>(seg + a), static_cast<int>(seg + b), w[a] * w[b]);
    }
    for (size_t j = 0; j + order_ < n_; ++j)
      for (size_t a = 0; a < diff_.size(); ++a)
        for (size_t b = 0; b < diff_.size(); ++b)
          entries.emplace_back(static_cast<int>(j + a), static_cast<int>(j + b),
                               kPenalty * diff_[a] * diff_[b]);
    Eigen::SparseMatrix<double> normal(static_cast<int>(n_), static_cast<int>(n_));
    normal.setFromTriplets(entries.begin(), entries.end());
    ldlt_.compute(normal);
    // positive definite whenever the poses have `order` distinct stamps (the caller's choice):
    // only a polynomial of degree < order escapes the penalty, and it cannot vanish at them all
    INET_CHECK_MSG(ldlt_.info() == Eigen::Success,
                   fmt::format("spline normal equations not positive definite ({} controls, "
                               "{} poses, difference order {})",
                               n_, first_.size(), order_));
  }

  size_t controls() const { return n_; }
  size_t poses() const { return first_.size(); }
  int order() const { return order_; }
  size_t first(size_t k) const { return first_[k]; }
  double u(size_t k) const { return u_[k]; }

  /// B c: the spline of controls c at every input stamp.
  std::vector<Vec3> applyB(const Rows3& c) const {
    std::vector<Vec3> out(first_.size(), Vec3::Zero());
    for (size_t k = 0; k < out.size(); ++k)
      for (size_t a = 0; a < 4; ++a)
        out[k] += weights_[k][a] * c.row(static_cast<int>(first_[k] + a)).transpose();
    return out;
  }
  /// B^T r, r holding one row per input pose.
  Rows3 applyBt(const std::vector<Vec3>& r) const {
    Rows3 out = Rows3::Zero(static_cast<int>(n_), 3);
    for (size_t k = 0; k < r.size(); ++k)
      for (size_t a = 0; a < 4; ++a)
        out.row(static_cast<int>(first_[k] + a)) += weights_[k][a] * r[k].transpose();
    return out;
  }
  /// rhs -= lambda D^T e, e holding one row per difference (n - order rows).
  void subtractPenaltyGradient(const std::vector<Vec3>& e, Rows3& rhs) const {
    for (size_t j = 0; j < e.size(); ++j)
      for (size_t a = 0; a < diff_.size(); ++a)
        rhs.row(static_cast<int>(j + a)) -= kPenalty * diff_[a] * e[j].transpose();
  }
  Rows3 solve(const Rows3& rhs) const { return ldlt_.solve(rhs); }

 private:
  size_t n_;
  int order_;
  std::vector<double> diff_;
  std::vector<size_t> first_;
  std::vector<double> u_;
  std::vector<std::array<double, 4>> weights_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
      ldlt_;
};

/// The least-squares polynomial of degree order-1 of the input positions, in the scaled time
/// s = (t - t_mid) / half (well conditioned), and its exact spline controls.
class PositionPolynomial {
 public:
  PositionPolynomial(const Trajectory& traj, int terms) : terms_(terms) {
    const TimeNs t0 = traj.poses.front().t_ns, t1 = traj.poses.back().t_ns;
    t_mid_ = t0 + (t1 - t0) / 2;
    half_ns_ = std::max(0.5 * static_cast<double>(t1 - t0), 1.0);
    Eigen::MatrixXd V(traj.size(), terms), Y(traj.size(), 3);
    for (size_t k = 0; k < traj.size(); ++k) {
      const double s = scaled(traj.poses[k].t_ns);
      double sm = 1.0;
      for (int m = 0; m < terms; ++m, sm *= s) V(static_cast<int>(k), m) = sm;
      Y.row(static_cast<int>(k)) = traj.poses[k].T_world_camera.t.transpose();
    }
    coef_ = V.householderQr().solve(Y);
  }
  Vec3 at(TimeNs t) const {
    const double s = scaled(t);
    Vec3 r = Vec3::Zero();
    double sm = 1.0;
    for (int m = 0; m < terms_; ++m, sm *= s) r += sm * coef_.row(m).transpose();
    return r;
  }
  /// Control j of the polynomial on knots t_j = t_c0 + j dt: f(t_j) - dt^2 f''(t_j) / 6, which
  /// the uniform cubic B-spline maps back to f exactly for any cubic f.
  Vec3 control(TimeNs t_j, TimeNs dt_ns) const {
    const double s = scaled(t_j), r2 = std::pow(static_cast<double>(dt_ns) / half_ns_, 2);
    Vec3 f2 = Vec3::Zero();  // d^2 f / ds^2
    double sm = 1.0;
    for (int m = 2; m < terms_; ++m, sm *= s) f2 += (m * (m - 1)) * sm * coef_.row(m).transpose();
    return at(t_j) - (r2 / 6.0) * f2;
  }

 private:
  double scaled(TimeNs t) const { return static_cast<double>(t - t_mid_) / half_ns_; }
  int terms_;
  TimeNs t_mid_;
  double half_ns_;
  Eigen::MatrixXd coef_;  ///< terms x 3
};

/// Position controls: the P-spline objective and then the iterated-Tikhonov passes (header
/// comment), on what the least-squares polynomial of the input leaves. The polynomial does not
/// change the objective (the penalty does not see it), but the solves then only carry the
/// non-polynomial part: a polynomial input leaves the rounding of its samples, not of the solve.
std::vector<Vec3> fitPositions(const Trajectory& traj, const PenalisedSystem& sys, TimeNs t_c0_ns,
                               TimeNs dt_ns) {
  const PositionPolynomial poly(traj, sys.order());
  std::vector<Vec3> rest(traj.size());
  for (size_t k = 0; k < traj.size(); ++k)
    rest[k] = traj.poses[k].T_world_camera.t - poly.at(traj.poses[k].t_ns);
  Rows3 c = sys.solve(sys.applyBt(rest));
  for (int pass = 1; pass < kPasses; ++pass) {
    // min |B c' - y|^2 + lambda |D (c' - c)|^2, i.e. c' = c + N^-1 B^T (y - B c)
    std::vector<Vec3> r = sys.applyB(c);
    for (size_t k = 0; k < r.size(); ++k) r[k] = rest[k] - r[k];
    c += sys.solve(sys.applyBt(r));
  }
  std::vector<Vec3> p(sys.controls());
  for (size_t j = 0; j < p.size(); ++j)
    p[j] = poly.control(t_c0_ns + static_cast<TimeNs>(j) * dt_ns, dt_ns) +
           c.row(static_cast<int>(j)).transpose();
  return p;
}

/// Rotation at t on the geodesic through the two input poses around t (extrapolated beyond
/// the ends): exact for a constant angular velocity, the Gauss-Newton start.
Quat geodesicAt(const Trajectory& traj, TimeNs t) {
  const auto& P = traj.poses;
  const auto it = std::upper_bound(P.begin(), P.end(), t,
                                   [](TimeNs x, const TimedPose& p) { return x < p.t_ns; });
  size_t k1 = std::clamp<size_t>(static_cast<size_t>(it - P.begin()), 1, P.size() - 1);
  size_t k0 = k1 - 1;
  while (P[k1].t_ns == P[k0].t_ns && k1 + 1 < P.size()) ++k1;  // repeated stamps
  while (P[k1].t_ns == P[k0].t_ns && k0 > 0) --k0;
  const Quat a = P[k0].T_world_camera.q.normalized(), b = P[k1].T_world_camera.q.normalized();
  const double s =
      static_cast<double>(t - P[k0].t_ns) / static_cast<double>(P[k1].t_ns - P[k0].t_ns);
  return a * so3::expQuat(s * so3::logQuat(a.conjugate() * b));
}

/// The penalised differences of the rotation part: the (order-1)-th differences of d_j.
std::vector<Vec3> rotationDifferences(const std::vector<Vec3>& d, const std::vector<double>& diff,
                                      size_t rows) {
  std::vector<Vec3> e(rows, Vec3::Zero());
  for (size_t j = 0; j < rows; ++j)
    for (size_t m = 0; m < diff.size(); ++m) e[j] += diff[m] * d[j + m];
  return e;
}

/// SO(3) Jacobians (Sola et al., "A micro Lie theory for state estimation in robotics", 2018,
/// eqs. 143-146): Exp(phi + x) ~ Exp(phi) Exp(J_r(phi) x), Log(Exp(phi) Exp(x)) ~ phi +
/// J_r^-1(phi) x, Log(Exp(x) Exp(phi)) ~ phi + J_l^-1(phi) x, with J_l(phi) = J_r(-phi).
Mat3 rightJacobian(const Vec3& phi) {
  const double t2 = phi.squaredNorm(), t = std::sqrt(t2);
  const Mat3 K = so3::hat(phi);
  if (t < 1e-5) return Mat3::Identity() - 0.5 * K + (K * K) / 6.0;
  return Mat3::Identity() - ((1 - std::cos(t)) / t2) * K + ((t - std::sin(t)) / (t2 * t)) * (K * K);
}

Mat3 rightJacobianInverse(const Vec3& phi) {
  const double t2 = phi.squaredNorm(), t = std::sqrt(t2);
  const Mat3 K = so3::hat(phi);
  const double c = t < 1e-5 ? 1.0 / 12.0 : 1.0 / t2 - (1 + std::cos(t)) / (2 * t * std::sin(t));
  return Mat3::Identity() + 0.5 * K + c * (K * K);
}

/// Symmetric normal equations over n 3-vectors whose blocks (a, b) are zero for |a - b| > band:
/// the lower triangle in a sparse matrix whose pattern is built and analysed once, so that a
/// Gauss-Newton step only adds blocks into its values and refactors.
class BlockBandNormal {
 public:
  BlockBandNormal(size_t n, size_t band) : A_(static_cast<int>(3 * n), static_cast<int>(3 * n)) {
    const int dim = static_cast<int>(3 * n);
    std::vector<Eigen::Triplet<double>> pattern;
    for (int c = 0; c < dim; ++c)
      for (int r = c; r < std::min(dim, (c / 3 + static_cast<int>(band) + 1) * 3); ++r)
        pattern.emplace_back(r, c, 0.0);
    A_.setFromTriplets(pattern.begin(), pattern.end());
    A_.makeCompressed();
    ldlt_.analyzePattern(A_);
    g_ = Eigen::VectorXd::Zero(dim);
  }
  void clear() {
    std::fill(A_.valuePtr(), A_.valuePtr() + A_.nonZeros(), 0.0);
    g_.setZero();
  }
  /// block(a, b) += m for a >= b (each column's rows are contiguous from the diagonal down).
  void add(size_t a, size_t b, const Mat3& m) {
    for (int s = 0; s < 3; ++s) {
      const int col = static_cast<int>(3 * b) + s;
      double* column = A_.valuePtr() + A_.outerIndexPtr()[col] - col;
      for (int t = 0; t < 3; ++t) {
        const int row = static_cast<int>(3 * a) + t;
        if (row >= col) column[row] += m(t, s);
      }
    }
  }
  void addRhs(size_t a, const Vec3& v) { g_.segment<3>(static_cast<Eigen::Index>(3 * a)) += v; }
  Eigen::VectorXd solve() {
    ldlt_.factorize(A_);
    INET_CHECK_MSG(ldlt_.info() == Eigen::Success, "rotation normal equations not definite");
    return ldlt_.solve(g_);
  }

 private:
  Eigen::SparseMatrix<double> A_;
  Eigen::VectorXd g_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
      ldlt_;
};

/// Adds the data term of pose k to the normal equations: the residual r = Log(R(t_k)^T R_k)
/// and its exact Jacobian for right updates R_j Exp(delta_j) of the four controls of its
/// segment. With A_m = Exp(b_m d_m) and d_m perturbed by J_r^-1(d) delta_right -
/// J_l^-1(d) delta_left, R(t) moves by Exp(eps) on the right,
///   eps = (A_1 A_2 A_3)^T delta_f + sum_m (A_{m+1}..A_3)^T b_m J_r(b_m d_m) dd_m,
/// and r by -J_l^-1(r) eps. Returns |r|^2.
double addPoseTerm(const std::vector<Quat>& q, const std::vector<Vec3>& d,
                   const std::vector<Mat3>& jri, const std::vector<Mat3>& jli, size_t f, double u,
                   const Quat& measured, BlockBandNormal& nrm) {
  const std::array<double, 3> bc = cumulativeBasis(u);
  Quat A[3];
  Mat3 RA[3], C[3];
  for (size_t m = 0; m < 3; ++m) {
    A[m] = so3::expQuat(bc[m] * d[f + m]);
    RA[m] = A[m].toRotationMatrix();
    C[m] = bc[m] * rightJacobian(bc[m] * d[f + m]);
  }
  const Vec3 r = so3::logQuat((q[f] * A[0] * A[1] * A[2]).conjugate() * measured);
  const Mat3 Q1 = RA[1] * RA[2], P0 = RA[0] * Q1;
  const Mat3 T0 = Q1.transpose() * C[0], T1 = RA[2].transpose() * C[1];
  Mat3 H[4] = {P0.transpose() - T0 * jli[f], T0 * jri[f] - T1 * jli[f + 1],
               T1 * jri[f + 1] - C[2] * jli[f + 2], C[2] * jri[f + 2]};
  const Mat3 L = rightJacobianInverse(-r);  // J_l^-1(r)
  for (Mat3& h : H) h = -L * h;
  for (size_t a = 0; a < 4; ++a) {
    nrm.addRhs(f + a, -H[a].transpose() * r);
    for (size_t b = 0; b <= a; ++b) nrm.add(f + a, f + b, H[a].transpose() * H[b]);
  }
  return r.squaredNorm();
}

/// Adds the penalty rows e_j = sum_m c_m d_{j+m} - target_j (weight lambda) and their exact
/// Jacobians (d_m depends on controls m and m+1) to the normal equations.
void addRotationPenalty(const std::vector<Vec3>& d, const std::vector<Mat3>& jri,
                        const std::vector<Mat3>& jli, const std::vector<double>& c,
                        const std::vector<Vec3>& target, BlockBandNormal& nrm) {
  const size_t K = c.size();  // d_j .. d_{j+K-1}: controls j .. j+K
  std::vector<Mat3> G(K + 1);
  for (size_t j = 0; j < target.size(); ++j) {
    Vec3 e = -target[j];
    for (size_t m = 0; m < K; ++m) e += c[m] * d[j + m];
    for (size_t m = 0; m <= K; ++m) {
      G[m].setZero();
      if (m < K) G[m] -= c[m] * jli[j + m];
      if (m > 0) G[m] += c[m - 1] * jri[j + m - 1];
    }
    for (size_t a = 0; a <= K; ++a) {
      nrm.addRhs(j + a, -kPenalty * G[a].transpose() * e);
      for (size_t b = 0; b <= a; ++b) nrm.add(j + a, j + b, kPenalty * G[a].transpose() * G[b]);
    }
  }
}

/// Gauss-Newton on sum_k |Log(R(t_k)^T R_k)|^2 + lambda sum_j |e_j - target_j|^2 over right
/// updates R_j Exp(delta_j), exact Jacobians, until the updates stop. Returns the iterations;
/// `step` gets the largest update of the last one.
int rotationGaussNewton(std::vector<Quat>& q, const std::vector<Quat>& measured,
                        const PenalisedSystem& sys, const std::vector<Vec3>& target,
                        BlockBandNormal& nrm, double& step) {
  const std::vector<double> c = differenceCoefficients(sys.order() - 1);
  std::vector<Mat3> jri(q.size() - 1), jli(q.size() - 1);
  double last_step = HUGE_VAL;
  int it = 0;
  while (it < kMaxRotationIterations) {
    ++it;
    const std::vector<Vec3> d = relativeRotations(q);
    for (size_t j = 0; j < d.size(); ++j) {
      jri[j] = rightJacobianInverse(d[j]);
      jli[j] = rightJacobianInverse(-d[j]);
    }
    nrm.clear();
    for (size_t k = 0; k < measured.size(); ++k)
      addPoseTerm(q, d, jri, jli, sys.first(k), sys.u(k), measured[k], nrm);
    addRotationPenalty(d, jri, jli, c, target, nrm);
    const Eigen::VectorXd delta = nrm.solve();
    step = 0.0;
    for (size_t j = 0; j < q.size(); ++j) {
      const Vec3 dj = delta.segment<3>(static_cast<Eigen::Index>(3 * j));
      step = std::max(step, dj.norm());
      q[j] = (q[j] * so3::expQuat(dj)).normalized();
    }
    if (!(step > kRotationStepDoneRad)) break;
    // where only the penalty holds the controls (gaps, knots much denser than the poses) the
    // steps bottom out at the solve's rounding, ~1e-12 rad, and stop shrinking
    if (step < kRotationStepNoiseRad && step > 0.5 * last_step) break;
    last_step = step;
  }
  return it;
}

/// Rotation controls: the P-spline objective from geodesic starting controls, then the
/// iterated-Tikhonov passes with the previous pass's differences as the penalty's target.
std::vector<Quat> fitRotations(const Trajectory& traj, const PenalisedSystem& sys, TimeNs t_c0_ns,
                               TimeNs dt_ns, SplineFitReport& rep, const std::string& source) {
  std::vector<Quat> q(sys.controls());
  for (size_t j = 0; j < q.size(); ++j)
    q[j] = geodesicAt(traj, t_c0_ns + static_cast<TimeNs>(j) * dt_ns);
  std::vector<Quat> measured(traj.size());
  for (size_t k = 0; k < traj.size(); ++k)
    measured[k] = traj.poses[k].T_world_camera.q.normalized();
  const size_t rows = q.size() - static_cast<size_t>(sys.order());
  std::vector<Vec3> target(rows, Vec3::Zero());
  BlockBandNormal nrm(q.size(), std::max<size_t>(3, static_cast<size_t>(sys.order())));
  rep.rotation_iterations = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    if (pass > 0)
      target =
          rotationDifferences(relativeRotations(q), differenceCoefficients(sys.order() - 1), rows);
    rep.rotation_iterations +=
        rotationGaussNewton(q, measured, sys, target, nrm, rep.rotation_step_rad);
    if (!(rep.rotation_step_rad <= kRotationStepFailRad))
      throw InputError(source, "trajectory",
                       fmt::format("the rotation fit does not converge (still moving {:.1e} rad "
                                   "after {} iterations): does the camera turn by about 180 "
                                   "degrees or more between two poses or knots?",
                                   rep.rotation_step_rad, rep.rotation_iterations));
  }
  return q;
}

void measureFit(const PoseSpline& spline, const Trajectory& traj, SplineFitReport& rep) {
  double sum_p = 0, sum_a = 0;
  rep.max_position_error_m = rep.max_angle_error_rad = 0;
  rep.poses_compared = 0;
  for (const TimedPose& tp : traj.poses) {
    if (tp.t_ns > spline.endNs()) break;
    const Pose s = spline.pose(tp.t_ns);
    const double ep = (s.t - tp.T_world_camera.t).norm();
    const double ea = so3::angleBetween(s.q, tp.T_world_camera.q.normalized());
    rep.max_position_error_m = std::max(rep.max_position_error_m, ep);
    rep.max_angle_error_rad = std::max(rep.max_angle_error_rad, ea);
    sum_p += ep * ep;
    sum_a += ea * ea;
    ++rep.poses_compared;
  }
  const double n = static_cast<double>(std::max<size_t>(rep.poses_compared, 1));
  rep.rms_position_error_m = std::sqrt(sum_p / n);
  rep.rms_angle_error_rad = std::sqrt(sum_a / n);
}

}  // namespace

std::string SplineFitReport::toString() const {
  return fmt::format(
      "spline: {} knots every {:.6f} s, rotation solve {} iterations (last step {:.1e} rad); vs "
      "{} input poses: position max {:.3e} m rms {:.3e} m, angle max {:.3e} deg rms {:.3e} deg",
      knots, static_cast<double>(knot_spacing_ns) * 1e-9, rotation_iterations, rotation_step_rad,
      poses_compared, max_position_error_m, rms_position_error_m,
      max_angle_error_rad * 180.0 / M_PI, rms_angle_error_rad * 180.0 / M_PI);
}

PoseSpline::PoseSpline(TimeNs t_c0_ns, TimeNs dt_ns, std::vector<Vec3> ctrl_p,
                       std::vector<Quat> ctrl_q)
    : t_c0_ns_(t_c0_ns), dt_ns_(dt_ns), ctrl_p_(std::move(ctrl_p)), ctrl_q_(std::move(ctrl_q)) {
  INET_CHECK(dt_ns_ > 0);
  INET_CHECK(ctrl_p_.size() >= 4 && ctrl_p_.size() == ctrl_q_.size());
  for (Quat& q : ctrl_q_) q.normalize();
  delta_ = relativeRotations(ctrl_q_);
}

PoseSpline PoseSpline::interpolate(TimeNs t0_ns, TimeNs dt_ns, const std::vector<Pose>& knots,
                                   SplineFitReport* report) {
  INET_CHECK(knots.size() >= 2 && dt_ns > 0);
  Trajectory traj;
  for (size_t j = 0; j < knots.size(); ++j)
    traj.poses.push_back({t0_ns + static_cast<TimeNs>(j) * dt_ns, knots[j]});
  SplineFitOptions opt;
  opt.knot_spacing_ns = dt_ns;
  return fit(traj, opt, report);
}

PoseSpline PoseSpline::fit(const Trajectory& traj, const SplineFitOptions& opt,
                           SplineFitReport* report, const std::string& source) {
  if (traj.size() < 2) throw InputError(source, "trajectory", "a spline needs at least 2 poses");
  size_t distinct = 1;  // stamps, for the penalty's order
  for (size_t k = 1; k < traj.size(); ++k) {
    if (traj.poses[k].t_ns < traj.poses[k - 1].t_ns)
      throw InputError(source, "trajectory",
                       fmt::format("time goes back at pose {} ({} ns after {} ns)", k + 1,
                                   traj.poses[k].t_ns, traj.poses[k - 1].t_ns));
    if (traj.poses[k].t_ns != traj.poses[k - 1].t_ns) ++distinct;
  }
  const TimeNs t_first = traj.poses.front().t_ns, t_last = traj.poses.back().t_ns;
  const TimeNs span = t_last - t_first;
  TimeNs dt = opt.knot_spacing_ns;
  if (dt <= 0) dt = std::max<TimeNs>(span / static_cast<TimeNs>(traj.size() - 1), 50'000'000);
  const TimeNs whole = span / dt;
  if (whole < 1)
    throw InputError(source, "trajectory",
                     fmt::format("spans {:.6f} s, less than one knot interval ({:.6f} s)",
                                 static_cast<double>(span) * 1e-9, static_cast<double>(dt) * 1e-9));
  // fit over whole knot intervals that cover every input pose; a last, partial interval helps
  // fit the poses in it and is then dropped, so the valid range ends on a knot as before
  const TimeNs covered = whole + (span % dt != 0 ? 1 : 0);
  const TimeNs t_c0 = t_first - dt;
  const PenalisedSystem sys(t_c0, dt, static_cast<size_t>(covered) + 3, traj,
                            static_cast<int>(std::min<size_t>(distinct, kMaxOrder)));
  SplineFitReport rep;
  std::vector<Vec3> p = fitPositions(traj, sys, t_c0, dt);
  std::vector<Quat> q = fitRotations(traj, sys, t_c0, dt, rep, source);
  if (covered > whole) {
    p.pop_back();
    q.pop_back();
  }
  PoseSpline spline(t_c0, dt, std::move(p), std::move(q));
  if (report) {
    rep.knot_spacing_ns = dt;
    rep.knots = static_cast<size_t>(whole) + 1;
    rep.difference_order = sys.order();
    measureFit(spline, traj, rep);
    *report = rep;
  }
  return spline;
}

void PoseSpline::locate(TimeNs t_ns, double frac_ns, size_t& i, double& u) const {
  INET_CHECK_MSG(
      t_ns >= startNs() && t_ns <= endNs(),
      fmt::format("spline evaluated at {} ns outside [{}, {}]", t_ns, startNs(), endNs()));
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
  // relative to c_i: the weights of v and a sum to 0 and those of p to 1, so only the local
  // differences enter the sums (a 20 m control would otherwise cost ~1e-9 m/s^2 of rounding
  // at 5 ms knots, where ddB ~ 1/dt^2 = 4e4 s^-2)
  const Vec3& ref = ctrl_p_[i];
  SplineState s;
  s.p_world.setZero();
  for (int j = 0; j < 4; ++j) {
    const Vec3 c = ctrl_p_[i - 1 + j] - ref;
    s.p_world += B[j] * c;
    s.v_world += dB[j] * c;
    s.a_world += ddB[j] * c;
  }
  s.p_world += ref;
  const std::array<double, 3> bc = cumulativeBasis(u);
  const double dbc[3] = {(3 - 6 * u + 3 * u2) / (6 * dt), (3 + 6 * u - 6 * u2) / (6 * dt),
                         3 * u2 / (6 * dt)};
  Quat q = ctrl_q_[i - 1];
  Vec3 w = Vec3::Zero();
  for (size_t j = 0; j < 3; ++j) {
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
