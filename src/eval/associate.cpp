#include "eval/associate.h"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "core/error.h"

namespace inet {

std::vector<StampMatch> associateStamps(const std::vector<TimeNs>& a, const std::vector<TimeNs>& b,
                                        const AssociationOptions& opt) {
  INET_CHECK(opt.max_diff_ns >= 0);
  auto sortedOrder = [](const std::vector<TimeNs>& t) {
    std::vector<size_t> order(t.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return t[i] < t[j]; });
    return order;
  };
  const std::vector<size_t> oa = sortedOrder(a), ob = sortedOrder(b);
  // Candidates (|diff|, t_a, t_b, ia, ib): for each a, the b's whose shifted stamp lies in the
  // open window (t_a - max_diff, t_a + max_diff). The window start only moves forward.
  struct Candidate {
    TimeNs diff, ta, tb;
    size_t ia, ib;
  };
  std::vector<Candidate> cand;
  size_t first = 0;
  for (size_t ka : oa) {
    const TimeNs ta = a[ka];
    while (first < ob.size() && b[ob[first]] + opt.offset_ns <= ta - opt.max_diff_ns) ++first;
    for (size_t k = first; k < ob.size(); ++k) {
      const TimeNs tb = b[ob[k]] + opt.offset_ns;
      if (tb >= ta + opt.max_diff_ns) break;
      cand.push_back({tb > ta ? tb - ta : ta - tb, ta, b[ob[k]], ka, ob[k]});
    }
  }
  std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.diff, x.ta, x.tb, x.ia, x.ib) < std::tie(y.diff, y.ta, y.tb, y.ia, y.ib);
  });
  std::vector<char> used_a(a.size(), 0), used_b(b.size(), 0);
  std::vector<StampMatch> out;
  for (const Candidate& c : cand) {
    if (used_a[c.ia] || used_b[c.ib]) continue;
    used_a[c.ia] = used_b[c.ib] = 1;
    out.push_back({c.ia, c.ib});
  }
  std::sort(out.begin(), out.end(), [&](const StampMatch& x, const StampMatch& y) {
    return std::tie(a[x.a], b[x.b], x.a) < std::tie(a[y.a], b[y.b], y.a);
  });
  return out;
}

}  // namespace inet
