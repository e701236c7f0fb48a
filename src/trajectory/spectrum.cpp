#include "trajectory/spectrum.h"

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace inet {
namespace {

/// Catmull-Rom on a non-uniform grid: Hermite cubic between y1 (at t1) and y2 (at t2) with
/// tangents from central differences over the neighbours (one-sided at the ends).
template <class V>
V hermite(const V& y0, const V& y1, const V& y2, const V& y3, double t0, double t1, double t2,
          double t3, double t) {
  const double h = t2 - t1, u = (t - t1) / h;
  const V m1 = (y2 - y0) / (t2 - t0), m2 = (y3 - y1) / (t3 - t1);
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * y1 + (u3 - 2 * u2 + u) * h * m1 + (-2 * u3 + 3 * u2) * y2 +
         (u3 - u2) * h * m2;
}

}  // namespace

Trajectory resampleUniform(const Trajectory& traj, double rate_hz) {
  INET_CHECK(rate_hz > 0);
  const size_t n = traj.size();
  if (n < 2) return traj;
  // sign-consistent quaternions, so that component-wise interpolation takes the short way
  std::vector<Eigen::Vector4d> q(n);
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i) {
    q[i] = traj.poses[i].T_world_camera.q.coeffs();
    if (i > 0 && q[i].dot(q[i - 1]) < 0) q[i] = -q[i];
    t[i] = 1e-9 * static_cast<double>(traj.poses[i].t_ns - traj.poses[0].t_ns);
  }
  const TimeNs t0 = traj.poses.front().t_ns, span = traj.poses.back().t_ns - t0;
  const double period_ns = 1e9 / rate_hz;
  Trajectory out;
  size_t i = 0;
  for (int64_t k = 0;; ++k) {
    const TimeNs dt_ns = std::llround(static_cast<double>(k) * period_ns);
    if (dt_ns > span) break;
    const double tk = 1e-9 * static_cast<double>(dt_ns);
    while (i + 2 < n && t[i + 1] <= tk) ++i;
    const size_t a = i == 0 ? 0 : i - 1, d = std::min(i + 2, n - 1);
    // at the ends the tangent is one-sided: neighbour index == own index
    const double ta = a == i ? t[i] : t[a], td = d == i + 1 ? t[i + 1] : t[d];
    const Pose& P0 = traj.poses[a].T_world_camera;
    const Pose& P1 = traj.poses[i].T_world_camera;
    const Pose& P2 = traj.poses[i + 1].T_world_camera;
    const Pose& P3 = traj.poses[d].T_world_camera;
    Vec3 p = hermite<Vec3>(P0.t, P1.t, P2.t, P3.t, ta, t[i], t[i + 1], td, tk);
    Eigen::Vector4d qc =
        hermite<Eigen::Vector4d>(q[a], q[i], q[i + 1], q[d], ta, t[i], t[i + 1], td, tk);
    Quat qq;
    qq.coeffs() = qc.normalized();
    out.poses.push_back({t0 + dt_ns, Pose{qq, p}});
  }
  return out;
}

MotionSeries motionSeries(const Trajectory& uniform, double rate_hz) {
  MotionSeries m;
  m.rate_hz = rate_hz;
  const double dt = 1.0 / rate_hz;
  for (size_t k = 1; k + 1 < uniform.size(); ++k) {
    const Pose& a = uniform.poses[k - 1].T_world_camera;
    const Pose& b = uniform.poses[k].T_world_camera;
    const Pose& c = uniform.poses[k + 1].T_world_camera;
    m.v_world.push_back((c.t - a.t) / (2 * dt));
    m.a_world.push_back((c.t - 2 * b.t + a.t) / (dt * dt));
    Eigen::AngleAxisd aa(c.q * a.q.conjugate());
    m.w_world.push_back(aa.axis() * aa.angle() / (2 * dt));
  }
  return m;
}

WelchPsd::WelchPsd(double rate_hz, int segment)
    : rate_hz_(rate_hz), segment_(segment), window_(segment), acc_(segment / 2 + 1, 0.0) {
  INET_CHECK(segment >= 8 && rate_hz > 0);
  for (int i = 0; i < segment; ++i) {
    window_[i] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / segment);  // periodic Hann
    window_power_ += window_[i] * window_[i];
  }
}

void WelchPsd::addSegment(const double* x, size_t stride, std::vector<double>& acc) const {
  double mean = 0;
  for (int i = 0; i < segment_; ++i) mean += x[i * stride];
  mean /= segment_;
  // direct DFT: segments are short (a few hundred samples) and the bins few
  for (int f = 0; f <= segment_ / 2; ++f) {
    double re = 0, im = 0;
    const double w = -2 * std::numbers::pi * f / segment_;
    for (int i = 0; i < segment_; ++i) {
      const double v = (x[i * stride] - mean) * window_[i];
      re += v * std::cos(w * i);
      im += v * std::sin(w * i);
    }
    double p = (re * re + im * im) / (rate_hz_ * window_power_);
    if (f != 0 && !(segment_ % 2 == 0 && f == segment_ / 2)) p *= 2;  // one-sided
    acc[f] += p;
  }
}

void WelchPsd::add(const std::vector<double>& x) {
  const size_t n = x.size(), hop = segment_ / 2;
  for (size_t s = 0; s + segment_ <= n; s += hop) {
    addSegment(x.data() + s, 1, acc_);
    ++count_;
  }
}

void WelchPsd::add(const std::vector<Vec3>& x) {
  const size_t n = x.size(), hop = segment_ / 2;
  for (size_t s = 0; s + segment_ <= n; s += hop) {
    for (int axis = 0; axis < 3; ++axis) addSegment(x[s].data() + axis, 3, acc_);
    ++count_;
  }
}

Spectrum WelchPsd::result() const {
  INET_CHECK_MSG(count_ > 0, "WelchPsd: no series as long as one segment");
  Spectrum s;
  for (size_t f = 0; f < acc_.size(); ++f) {
    s.freq_hz.push_back(f * rate_hz_ / segment_);
    s.psd.push_back(acc_[f] / count_);
  }
  return s;
}

double logSpectralDistanceDb(const Spectrum& p, const Spectrum& q, double f_lo, double f_hi) {
  INET_CHECK(p.freq_hz.size() == q.freq_hz.size());
  double sum = 0;
  int n = 0;
  for (size_t i = 0; i < p.freq_hz.size(); ++i) {
    if (p.freq_hz[i] < f_lo || p.freq_hz[i] > f_hi) continue;
    INET_CHECK(std::abs(p.freq_hz[i] - q.freq_hz[i]) < 1e-9);
    const double d = 10 * std::log10(std::max(p.psd[i], 1e-300) / std::max(q.psd[i], 1e-300));
    sum += d * d;
    ++n;
  }
  INET_CHECK_MSG(n > 0, "logSpectralDistanceDb: no bin in the band");
  return std::sqrt(sum / n);
}

}  // namespace inet
