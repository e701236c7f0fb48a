// eval/associate: TUM associate.py semantics on hand-made stamps, and against a brute-force
// transcription of its definition on random stamps.
#include "eval/associate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

namespace inet {
namespace {

constexpr TimeNs kMs = 1'000'000;

std::vector<TimeNs> ms(std::initializer_list<int> v) {
  std::vector<TimeNs> out;
  for (int x : v) out.push_back(x * kMs);
  return out;
}

TEST(Associate, MatchesWithinMaxDiffAndLeavesTheRest) {
  // 200 and 230 differ by 30 ms > 20 ms: both unmatched; 1000 has no partner at all
  const auto a = ms({0, 100, 200, 300, 1000});
  const auto b = ms({5, 98, 230, 302});
  const auto m = associateStamps(a, b, {0, 20 * kMs});
  const std::vector<StampMatch> want = {{0, 0}, {1, 1}, {3, 3}};
  EXPECT_EQ(m, want);
}

TEST(Associate, MaxDiffIsStrict) {
  const auto a = ms({0, 100});
  const auto b = ms({20, 119});  // exactly 20 ms: out; 19 ms: in
  const auto m = associateStamps(a, b, {0, 20 * kMs});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0], (StampMatch{1, 1}));
}

TEST(Associate, OffsetIsAddedToTheSecondList) {
  const auto a = ms({1000, 1100, 1200, 1300});
  const auto b = ms({950, 1050, 1150, 1250});  // b is 50 ms early
  EXPECT_TRUE(associateStamps(a, b, {0, 20 * kMs}).empty());
  const auto m = associateStamps(a, b, {50 * kMs, 1 * kMs});
  ASSERT_EQ(m.size(), 4u);
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(m[k], (StampMatch{k, k}));
  // the wrong sign pairs each a with the b two steps later (b - 50 ms = a): 1000-1050, ...
  const auto w = associateStamps(a, b, {-50 * kMs, 20 * kMs});
  const std::vector<StampMatch> want = {{0, 1}, {1, 2}, {2, 3}};
  EXPECT_EQ(w, want);
}

TEST(Associate, GreedyBySmallestDifferenceNotNearestNeighbour) {
  // 112-110 (2 ms) is taken first; 100 then loses its only partner 110 although 110 is its
  // nearest stamp, and 125 (13 ms from 112) loses too because 112 is used.
  const auto m = associateStamps(ms({100, 112}), ms({110, 125}), {0, 20 * kMs});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0], (StampMatch{1, 0}));
}

TEST(Associate, TiesGoToTheEarlierFirstStampThenEarlierSecond) {
  // 100 and 120 are both 10 ms from 110: the earlier first stamp wins
  auto m = associateStamps(ms({100, 120}), ms({110}), {0, 20 * kMs});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0], (StampMatch{0, 0}));
  // 100 is 10 ms from 90 and from 110: the earlier second stamp wins, 110 stays free for 115
  m = associateStamps(ms({100, 115}), ms({110, 90}), {0, 20 * kMs});
  const std::vector<StampMatch> want = {{0, 1}, {1, 0}};
  EXPECT_EQ(m, want);
}

TEST(Associate, ResultSortedByFirstStampWhateverTheInputOrder) {
  const auto a = ms({300, 0, 200, 100});
  const auto b = ms({101, 299, 1, 198});
  const auto m = associateStamps(a, b, {0, 20 * kMs});
  ASSERT_EQ(m.size(), 4u);
  for (size_t k = 1; k < m.size(); ++k) EXPECT_LT(a[m[k - 1].a], a[m[k].a]);
  for (const auto& p : m) EXPECT_LT(std::abs(a[p.a] - b[p.b]), 3 * kMs);
}

/// associate.py's definition written out directly: all pairs, sort, greedy.
std::vector<StampMatch> bruteForce(const std::vector<TimeNs>& a, const std::vector<TimeNs>& b,
                                   TimeNs offset, TimeNs max_diff) {
  std::vector<std::tuple<TimeNs, TimeNs, TimeNs, size_t, size_t>> all;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) {
      const TimeNs d = std::abs(a[i] - (b[j] + offset));
      if (d < max_diff) all.emplace_back(d, a[i], b[j], i, j);
    }
  std::sort(all.begin(), all.end());
  std::vector<bool> ua(a.size()), ub(b.size());
  std::vector<StampMatch> out;
  for (auto& [d, ta, tb, i, j] : all)
    if (!ua[i] && !ub[j]) ua[i] = ub[j] = true, out.push_back({i, j});
  std::sort(out.begin(), out.end(), [&](auto& x, auto& y) { return a[x.a] < a[y.a]; });
  return out;
}

TEST(Associate, AgreesWithTheDefinitionOnRandomStamps) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    std::uniform_int_distribution<TimeNs> t(0, 2000 * kMs);
    std::vector<TimeNs> a(200), b(150);
    for (auto& x : a) x = t(rng) / kMs * kMs;  // millisecond grid: plenty of exact ties
    for (auto& x : b) x = t(rng) / kMs * kMs;
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    const TimeNs offset = (trial % 5 - 2) * 3 * kMs;
    const auto got = associateStamps(a, b, {offset, 10 * kMs});
    const auto want = bruteForce(a, b, offset, 10 * kMs);
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].a, want[k].a) << "trial " << trial << " k " << k;
      EXPECT_EQ(b[got[k].b], b[want[k].b]) << "trial " << trial << " k " << k;
    }
  }
}

}  // namespace
}  // namespace inet
