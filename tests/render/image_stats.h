#pragma once
// Checks shared by the estimator tests (light cache, sun photons): an image against a
// reference, and the same render on 1 and 2 threads.
#include <tbb/global_control.h>

#include <cmath>
#include <utility>

#include "core/image.h"

namespace inet::test {

struct AgainstReference {
  double mean_ratio = 0;  ///< image mean / reference mean
  double rel_rmse = 0;    ///< RMSE / reference mean
};

inline AgainstReference againstReference(const ImageF& img, const ImageF& ref) {
  double sum = 0, ref_sum = 0, se = 0;
  for (size_t i = 0; i < img.data.size(); ++i) {
    sum += img.data[i];
    ref_sum += ref.data[i];
    se += (img.data[i] - ref.data[i]) * (img.data[i] - ref.data[i]);
  }
  const double n = static_cast<double>(img.data.size());
  return {sum / ref_sum, std::sqrt(se / n) / (ref_sum / n)};
}

/// render() run with at most 1 and at most 2 threads.
template <class Render>
std::pair<ImageF, ImageF> onOneAndTwoThreads(Render render) {
  std::pair<ImageF, ImageF> out;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    out.first = render();
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    out.second = render();
  }
  return out;
}

}  // namespace inet::test
