#pragma once
// Summary statistics of a list of errors, with the definitions evo and TUM's scripts use:
// rmse = sqrt(mean(e^2)), std = population standard deviation (numpy's default, ddof = 0),
// median = middle value or the mean of the two middle values.
#include <cstddef>
#include <string>
#include <vector>

namespace inet {

struct ErrorStats {
  size_t count = 0;
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0, sse = 0;
  std::string toString() const;
};

/// Statistics of `errors` (all zero for an empty list).
ErrorStats computeErrorStats(const std::vector<double>& errors);

}  // namespace inet
