#include "sensors/allan.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.h"

namespace inet {

std::vector<AllanPoint> allanDeviation(const std::vector<double>& y, double rate_hz,
                                       int per_decade, double max_fraction) {
  INET_CHECK(rate_hz > 0 && per_decade > 0 && max_fraction >= 2.0);
  const size_t n = y.size();
  const double tau0 = 1.0 / rate_hz;
  std::vector<double> theta(n + 1, 0.0);  // long double would not change the 1e-16 sums here
  for (size_t k = 0; k < n; ++k) theta[k + 1] = theta[k] + y[k] * tau0;
  std::vector<AllanPoint> out;
  const size_t m_max = static_cast<size_t>(static_cast<double>(n) / max_fraction);
  size_t last_m = 0;
  for (int e = 0;; ++e) {
    const size_t m = static_cast<size_t>(std::llround(std::pow(10.0, e / double(per_decade))));
    if (m > m_max) break;
    if (m == last_m) continue;
    last_m = m;
    const size_t count = n - 2 * m + 1;
    double sum = 0.0;
    for (size_t j = 0; j < count; ++j) {
      const double d = theta[j + 2 * m] - 2.0 * theta[j + m] + theta[j];
      sum += d * d;
    }
    const double tau = static_cast<double>(m) * tau0;
    out.push_back({tau, std::sqrt(sum / (2.0 * tau * tau * static_cast<double>(count))), count});
  }
  return out;
}

double allanAt(const std::vector<AllanPoint>& curve, double tau_s) {
  INET_CHECK(!curve.empty() && tau_s >= curve.front().tau_s && tau_s <= curve.back().tau_s);
  size_t i = 0;
  while (i + 2 < curve.size() && curve[i + 1].tau_s < tau_s) ++i;
  if (curve.size() == 1) return curve[0].adev;
  const AllanPoint& a = curve[i];
  const AllanPoint& b = curve[i + 1];
  const double s = std::log(tau_s / a.tau_s) / std::log(b.tau_s / a.tau_s);
  return std::exp((1 - s) * std::log(a.adev) + s * std::log(b.adev));
}

AllanNoiseFit fitAllanNoise(const std::vector<AllanPoint>& curve, double tau_min, double tau_max) {
  // rows: [1/tau, tau/3] / var * (N^2, K^2) = 1
  std::vector<const AllanPoint*> pts;
  for (const AllanPoint& p : curve)
    if (p.tau_s >= tau_min && p.tau_s <= tau_max && p.adev > 0) pts.push_back(&p);
  INET_CHECK(pts.size() >= 2);
  Eigen::MatrixXd A(pts.size(), 2);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(pts.size()));
  for (size_t i = 0; i < pts.size(); ++i) {
    const double var = pts[i]->adev * pts[i]->adev;
    A(static_cast<Eigen::Index>(i), 0) = 1.0 / pts[i]->tau_s / var;
    A(static_cast<Eigen::Index>(i), 1) = pts[i]->tau_s / 3.0 / var;
  }
  Eigen::Vector2d x = A.colPivHouseholderQr().solve(b);
  // a term the data cannot support: refit the other one alone
  if (x(0) < 0) x = {0.0, A.col(1).dot(b) / A.col(1).squaredNorm()};
  if (x(1) < 0) x = {A.col(0).dot(b) / A.col(0).squaredNorm(), 0.0};
  return {std::sqrt(std::max(x(0), 0.0)), std::sqrt(std::max(x(1), 0.0))};
}

double fitRandomWalkLine(const std::vector<AllanPoint>& curve, double tau_min, double tau_max) {
  double sum = 0.0;
  int n = 0;
  for (const AllanPoint& p : curve)
    if (p.tau_s >= tau_min && p.tau_s <= tau_max && p.adev > 0) {
      sum += std::log(p.adev / std::sqrt(p.tau_s / 3.0));
      ++n;
    }
  INET_CHECK(n > 0);
  return std::exp(sum / n);
}

}  // namespace inet
