#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "core/rng.h"

namespace inet {
namespace {

TEST(CounterRng, SameKeySameNumbers) {
  CounterRng a(42, RngStream::PathTracer, 3, 1000, 7), b(42, RngStream::PathTracer, 3, 1000, 7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.nextU32(), b.nextU32());
}

TEST(CounterRng, EveryKeyPartMatters) {
  auto first = [](uint64_t seed, RngStream s, uint32_t a, uint32_t b, uint32_t c) {
    CounterRng r(seed, s, a, b, c);
    return std::vector<uint32_t>{r.nextU32(), r.nextU32(), r.nextU32(), r.nextU32(), r.nextU32()};
  };
  auto base = first(1, RngStream::PathTracer, 2, 3, 4);
  EXPECT_NE(base, first(2, RngStream::PathTracer, 2, 3, 4));
  EXPECT_NE(base, first(1ull << 40, RngStream::PathTracer, 2, 3, 4));  // high seed bits count
  EXPECT_NE(base, first(1, RngStream::Sensor, 2, 3, 4));
  EXPECT_NE(base, first(1, RngStream::PathTracer, 9, 3, 4));
  EXPECT_NE(base, first(1, RngStream::PathTracer, 2, 9, 4));
  EXPECT_NE(base, first(1, RngStream::PathTracer, 2, 3, 9));
}

TEST(CounterRng, UniformIsInUnitIntervalWithRightMoments) {
  CounterRng r(7, RngStream::PathTracer, 0, 0, 0);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  int bins[10] = {};
  for (int i = 0; i < n; ++i) {
    float u = r.uniform();
    ASSERT_GE(u, 0.f);
    ASSERT_LT(u, 1.f);
    sum += u;
    sum2 += u * u;
    ++bins[static_cast<int>(u * 10)];
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 0.002) << "variance";
  // chi-square with 9 dof: 99.9% quantile 27.9
  double chi2 = 0;
  for (int b : bins) chi2 += (b - n / 10.0) * (b - n / 10.0) / (n / 10.0);
  EXPECT_LT(chi2, 27.9);
}

TEST(CounterRng, DoublesUse53Bits) {
  CounterRng r(1, RngStream::Trajectory, 0, 0, 0);
  std::set<double> seen;
  for (int i = 0; i < 1000; ++i) {
    double u = r.uniformDouble();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    seen.insert(u);
  }
  EXPECT_EQ(seen.size(), 1000u);
}

}  // namespace
}  // namespace inet
