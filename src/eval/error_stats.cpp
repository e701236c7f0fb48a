#include "eval/error_stats.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace inet {

ErrorStats computeErrorStats(const std::vector<double>& errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sum = 0;
  for (double e : errors) sum += e, s.sse += e * e;
  const double n = static_cast<double>(errors.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(s.sse / n);
  double var = 0;  // two-pass: no cancellation for errors far from zero
  for (double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / n);
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  s.min = sorted.front();
  s.max = sorted.back();
  const size_t h = sorted.size() / 2;
  s.median = sorted.size() % 2 ? sorted[h] : 0.5 * (sorted[h - 1] + sorted[h]);
  return s;
}

std::string ErrorStats::toString() const {
  return fmt::format(
      "ErrorStats[n={} rmse={:.6g} mean={:.6g} median={:.6g} std={:.6g} "
      "min={:.6g} max={:.6g}]",
      count, rmse, mean, median, std, min, max);
}

}  // namespace inet
