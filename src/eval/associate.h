#pragma once
// Association of two timestamped trajectories, as TUM RGB-D's associate.py does it: every pair
// (a, b) with |t_a - (t_b + offset)| < max_diff is a candidate; candidates are taken greedily by
// smallest difference (ties: earlier t_a, then earlier t_b), each stamp used at most once; the
// result is sorted by t_a. Unlike associate.py this looks only at the candidates inside the
// window (two sorted sweeps), so it is O((n + m) log(n + m) + candidates), not O(n m).
#include <cstddef>
#include <vector>

#include "core/pose.h"

namespace inet {

/// A matched pair: index into the first stamp list, index into the second.
struct StampMatch {
  size_t a = 0, b = 0;
  bool operator==(const StampMatch&) const = default;
};

/// How two stamp lists are matched. offset_ns is added to the second list's stamps (TUM's
/// --offset); a pair matches only if the difference is strictly below max_diff_ns (TUM's
/// --max_difference, default 0.02 s).
struct AssociationOptions {
  TimeNs offset_ns = 0;
  TimeNs max_diff_ns = 20'000'000;
};

/// Matches stamps `a` to stamps `b` (either list in any order; duplicate stamps allowed).
/// Returns pairs sorted by t_a (then t_b).
std::vector<StampMatch> associateStamps(const std::vector<TimeNs>& a, const std::vector<TimeNs>& b,
                                        const AssociationOptions& opt);

}  // namespace inet
