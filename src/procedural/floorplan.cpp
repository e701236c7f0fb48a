#include "procedural/floorplan.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>

#include "core/error.h"

namespace inet {
namespace {


/// Target floor area range (m^2) of each room type.
std::pair<double, double> areaRange(const std::string& type) {
  static const std::map<std::string, std::pair<double, double>> ranges = {
      {"living_room", {18, 30}},    {"dining_room", {10, 15}},   {"kitchen", {7, 12}},
      {"master_bedroom", {13, 18}}, {"second_bedroom", {9, 13}}, {"kids_room", {9, 12}},
      {"elderly_room", {10, 13}},   {"study", {8, 12}},          {"bathroom", {4, 6.5}},
      {"master_bathroom", {5, 8}},  {"balcony", {4, 8}},         {"corridor", {5, 9}},
      {"entrance", {3.5, 6}},       {"storage", {3, 4.5}},       {"cloakroom", {3.5, 5}},
      {"laundry", {3.5, 5}}};
  auto it = ranges.find(type);
  INET_CHECK_MSG(it != ranges.end(), "no area range for room type " + type);
  return it->second;
}

/// Public rooms make good hubs: doors through them are cheap in the spanning tree.
bool isPublic(const std::string& type) {
  return type == "living_room" || type == "corridor" || type == "entrance" || type == "dining_room";
}

bool wantsWindow(const std::string& type) {
  return !(type == "corridor" || type == "storage" || type == "cloakroom" || type == "entrance");
}

struct Item {
  int index;
  double area;
};

/// Binary treemap: lays `items` (sorted by area, descending) into `box`.
void layout(std::vector<Item> items, const Eigen::AlignedBox2d& box,
            std::vector<Eigen::AlignedBox2d>& out, CounterRng& rng) {
  if (items.size() == 1) {
    out[items[0].index] = box;
    return;
  }
  const double total = std::accumulate(items.begin(), items.end(), 0.0,
                                       [](double s, const Item& i) { return s + i.area; });
  // greedy partition into two groups of about equal area, alternating from the largest, with a
  // random start so that seeds vary the arrangement
  std::vector<Item> a, b;
  double sa = 0, sb = 0;
  const bool flip = rng.uniform() < 0.5f;
  for (const Item& it : items) {
    const bool to_a = sa == sb ? !flip : sa < sb;
    (to_a ? a : b).push_back(it);
    (to_a ? sa : sb) += it.area;
  }
  if (a.empty() || b.empty()) {  // all in one group: move the smallest over
    std::vector<Item>& from = a.empty() ? b : a;
    std::vector<Item>& to = a.empty() ? a : b;
    to.push_back(from.back());
    from.pop_back();
    sa = std::accumulate(a.begin(), a.end(), 0.0,
                         [](double s, const Item& i) { return s + i.area; });
    sb = total - sa;
  }
  const Eigen::Vector2d size = box.sizes();
  const double f = sa / total;
  Eigen::AlignedBox2d ba = box, bb = box;
  // cut across the longer side unless the other cut leaves the thinner part wider
  const double thin_x = std::min(f, 1 - f) * size.x(), thin_y = std::min(f, 1 - f) * size.y();
  const bool cut_x = std::min(thin_x, size.y()) >= std::min(thin_y, size.x());
  if (cut_x) {
    const double x = box.min().x() + f * size.x();
    ba.max().x() = x;
    bb.min().x() = x;
  } else {
    const double y = box.min().y() + f * size.y();
    ba.max().y() = y;
    bb.min().y() = y;
  }
  layout(std::move(a), ba, out, rng);
  layout(std::move(b), bb, out, rng);
}

/// Overlap [lo, hi] of two rooms' shared wall, or false when they do not share one.
bool sharedWall(const Eigen::AlignedBox2d& p, const Eigen::AlignedBox2d& q, bool& vertical,
                double& line, double& lo, double& hi) {
  constexpr double eps = 1e-9;
  for (int axis = 0; axis < 2; ++axis) {
    const int other = 1 - axis;
    double at = 0;
    if (std::fabs(p.max()[axis] - q.min()[axis]) < eps) {
      at = p.max()[axis];
    } else if (std::fabs(q.max()[axis] - p.min()[axis]) < eps) {
      at = q.max()[axis];
    } else {
      continue;
    }
    lo = std::max(p.min()[other], q.min()[other]);
    hi = std::min(p.max()[other], q.max()[other]);
    if (hi - lo <= eps) continue;
    vertical = axis == 0;
    line = at;
    return true;
  }
  return false;
}

/// A door of width w on [lo, hi], near one end (doors sit near corners) with 0.15 m to spare.
void placeOpening(double lo, double hi, double w, CounterRng& rng, double& from, double& to) {
  const double slack = std::max(0.0, hi - lo - w - 0.3);
  from = lo + 0.15 + (rng.uniform() < 0.5f ? 0.0 : slack) * rng.uniformDouble(0.0, 1.0);
  to = from + w;
}

/// The parts of side `side` (0: x-min, 1: x-max, 2: y-min, 3: y-max) of room i that no other
/// room touches: exterior wall intervals.
std::vector<std::pair<double, double>> exteriorIntervals(const std::vector<PlanRoom>& rooms,
                                                         size_t i, int side) {
  const Eigen::AlignedBox2d& r = rooms[i].box;
  const bool vertical = side < 2;
  const int along = vertical ? 1 : 0;
  const double line = side == 0   ? r.min().x()
                      : side == 1 ? r.max().x()
                      : side == 2 ? r.min().y()
                                  : r.max().y();
  std::vector<std::pair<double, double>> free = {{r.min()[along], r.max()[along]}};
  for (size_t j = 0; j < rooms.size(); ++j) {
    if (j == i) continue;
    bool v;
    double l, lo, hi;
    if (!sharedWall(r, rooms[j].box, v, l, lo, hi) || v != vertical || std::fabs(l - line) > 1e-9)
      continue;
    std::vector<std::pair<double, double>> next;
    for (auto [a, b] : free) {
      if (hi <= a || lo >= b) {
        next.push_back({a, b});
        continue;
      }
      if (lo > a) next.push_back({a, lo});
      if (hi < b) next.push_back({hi, b});
    }
    free = std::move(next);
  }
  return free;
}

}  // namespace

int sampleRoomCount(CounterRng& rng) {
  // rooms per layout: 1 (studio) .. 12, mode 5 (shaped like the paper's Fig. 3 histogram)
  static const double weights[] = {4, 6, 10, 15, 18, 16, 12, 8, 5, 3, 2, 1};
  double total = 0;
  for (double w : weights) total += w;
  double u = rng.uniformDouble() * total;
  for (int k = 0; k < 12; ++k) {
    if (u < weights[k]) return k + 1;
    u -= weights[k];
  }
  return 12;
}

std::vector<std::string> roomProgram(int count, CounterRng& rng) {
  if (count < 1 || count > 16)
    throw InputError("", "--rooms", "must be in 1..16, got " + std::to_string(count));
  // in order of need; later rooms appear in bigger apartments
  std::vector<std::string> order = {"living_room", "bathroom", "kitchen", "master_bedroom"};
  std::vector<std::string> extra = {
      "second_bedroom", "corridor", "dining_room", "entrance", "kids_room",    "master_bathroom",
      "study",          "balcony",  "storage",     "laundry",  "elderly_room", "cloakroom"};
  // seeded order of the optional rooms: each keeps its rank give or take a few places, so the
  // common ones come first on average but every type turns up in mid-sized flats
  std::vector<std::pair<double, std::string>> ranked;
  for (size_t i = 0; i < extra.size(); ++i)
    ranked.push_back({static_cast<double>(i) + 12.0 * rng.uniformDouble(), extra[i]});
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < extra.size(); ++i) extra[i] = ranked[i].second;
  order.insert(order.end(), extra.begin(), extra.end());
  order.resize(static_cast<size_t>(count));
  return order;
}

FloorPlan makeFloorPlan(const std::vector<std::string>& program, CounterRng& rng) {
  INET_CHECK(!program.empty());
  FloorPlan plan;
  plan.ceiling = rng.uniformDouble(2.55, 2.9);
  for (int attempt = 0; attempt < 200; ++attempt) {
    std::vector<Item> items;
    double total = 0;
    for (size_t i = 0; i < program.size(); ++i) {
      auto [lo, hi] = areaRange(program[i]);
      double a = rng.uniformDouble(lo, hi);
      if (program.size() == 1) a = rng.uniformDouble(28, 42);  // a studio: one big room
      items.push_back({static_cast<int>(i), a});
      total += a;
    }
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& x, const Item& y) { return x.area > y.area; });
    // elongated footprints when compact ones keep failing (a small bathroom beside one big room
    // needs a long, narrow flat)
    const double aspect = rng.uniformDouble(1.0, attempt < 60 ? 1.8 : 3.5);
    const double w = std::round(std::sqrt(total * aspect) * 100) / 100;
    const double h = std::round(total / w * 100) / 100;
    plan.footprint = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(w, h));
    std::vector<Eigen::AlignedBox2d> boxes(program.size());
    layout(items, plan.footprint, boxes, rng);
    // round to centimetres so shared walls meet exactly
    for (auto& b : boxes) {
      b.min() = (b.min() * 100).array().round() / 100;
      b.max() = (b.max() * 100).array().round() / 100;
    }
    bool ok = true;
    for (size_t i = 0; i < boxes.size() && ok; ++i) {
      const std::string& type = program[i];
      const bool small = type == "storage" || type == "cloakroom" || type == "laundry";
      const double min_side = type == "corridor" ? 1.2 : small ? 1.4 : 1.6;
      const Eigen::Vector2d sz = boxes[i].sizes();
      ok = sz.minCoeff() >= min_side && sz.maxCoeff() <= 3.0 * sz.minCoeff() + 1.0;
    }
    if (!ok) continue;
    plan.rooms.clear();
    for (size_t i = 0; i < program.size(); ++i) plan.rooms.push_back({program[i], boxes[i]});

    // doors: Prim's spanning tree over walls long enough for a door, cheap through public rooms
    const size_t n = plan.rooms.size();
    struct Edge {
      double cost;
      int a, b;
      bool vertical;
      double line, lo, hi;
    };
    std::vector<Edge> edges;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) {
        Edge e{0, static_cast<int>(i), static_cast<int>(j), false, 0, 0, 0};
        if (!sharedWall(plan.rooms[i].box, plan.rooms[j].box, e.vertical, e.line, e.lo, e.hi))
          continue;
        if (e.hi - e.lo < kMinDoorWall) continue;
        const int pub = isPublic(plan.rooms[i].type) + isPublic(plan.rooms[j].type);
        const bool en_suite =
            (plan.rooms[i].type == "master_bathroom" && plan.rooms[j].type == "master_bedroom") ||
            (plan.rooms[j].type == "master_bathroom" && plan.rooms[i].type == "master_bedroom");
        e.cost = (pub == 2 ? 1.0 : pub == 1 ? 2.0 : en_suite ? 1.5 : 8.0) + rng.uniform();
        edges.push_back(e);
      }
    int root = 0;  // the living room, or the entrance when there is one
    for (size_t i = 0; i < n; ++i)
      if (plan.rooms[i].type == "entrance") root = static_cast<int>(i);
    std::vector<bool> in(n, false);
    in[root] = true;
    plan.doors.clear();
    for (size_t added = 1; added < n; ++added) {
      const Edge* best = nullptr;
      for (const Edge& e : edges)
        if (in[e.a] != in[e.b] && (!best || e.cost < best->cost)) best = &e;
      if (!best) break;
      in[best->a] = in[best->b] = true;
      PlanDoor d;
      d.a = best->a;
      d.b = best->b;
      d.vertical = best->vertical;
      d.line = best->line;
      placeOpening(best->lo, best->hi, rng.uniformDouble(0.8, 0.9), rng, d.from, d.to);
      plan.doors.push_back(d);
    }
    if (std::find(in.begin(), in.end(), false) != in.end()) continue;  // not connected: redraw

    // the front door: on an exterior wall of the root room
    bool front = false;
    for (int side = 0; side < 4 && !front; ++side)
      for (auto [lo, hi] : exteriorIntervals(plan.rooms, root, side)) {
        if (hi - lo < kMinDoorWall) continue;
        PlanDoor d;
        d.a = root;
        d.b = -1;
        d.vertical = side < 2;
        const auto& b = plan.rooms[root].box;
        d.line = side == 0   ? b.min().x()
                 : side == 1 ? b.max().x()
                 : side == 2 ? b.min().y()
                             : b.max().y();
        placeOpening(lo, hi, 0.9, rng, d.from, d.to);
        plan.doors.push_back(d);
        front = true;
        break;
      }
    if (!front) continue;

    // windows: on the exterior walls of rooms that want daylight, away from the front door
    plan.windows.clear();
    for (size_t i = 0; i < n; ++i) {
      if (!wantsWindow(plan.rooms[i].type)) continue;
      const auto& b = plan.rooms[i].box;
      for (int side = 0; side < 4; ++side) {
        for (auto [lo, hi] : exteriorIntervals(plan.rooms, i, side)) {
          if (hi - lo < 1.4) continue;
          PlanWindow w;
          w.room = static_cast<int>(i);
          w.vertical = side < 2;
          w.line = side == 0   ? b.min().x()
                   : side == 1 ? b.max().x()
                   : side == 2 ? b.min().y()
                               : b.max().y();
          w.outward = side == 0   ? Eigen::Vector2d(-1, 0)
                      : side == 1 ? Eigen::Vector2d(1, 0)
                      : side == 2 ? Eigen::Vector2d(0, -1)
                                  : Eigen::Vector2d(0, 1);
          const double width = std::min(hi - lo - 0.6, rng.uniformDouble(0.9, 1.8));
          const double centre = 0.5 * (lo + hi);
          w.from = centre - width / 2;
          w.to = centre + width / 2;
          const bool balcony = plan.rooms[i].type == "balcony";
          w.sill = balcony ? 0.3 : rng.uniformDouble(0.8, 1.0);
          w.top = std::min(plan.ceiling - 0.3, 2.2);
          // not where the front door is
          bool clash = false;
          for (const PlanDoor& d : plan.doors)
            clash = clash ||
                    (d.b == -1 && d.vertical == w.vertical && std::fabs(d.line - w.line) < 1e-9 &&
                     d.from < w.to + 0.3 && w.from < d.to + 0.3);
          if (!clash) plan.windows.push_back(w);
        }
      }
    }
    return plan;
  }
  // Some big programs of small rooms do not fit a treemap; drop the least needed room (the
  // program is in order of need) and try again. A single room always fits.
  INET_CHECK_MSG(program.size() > 1, "makeFloorPlan: no plan for a single room");
  return makeFloorPlan(std::vector<std::string>(program.begin(), program.end() - 1), rng);
}

bool allRoomsReachable(const FloorPlan& plan) {
  const size_t n = plan.rooms.size();
  std::vector<std::vector<int>> adj(n);
  int start = -1;
  for (const PlanDoor& d : plan.doors) {
    if (d.b < 0) {
      start = d.a;
      continue;
    }
    adj[d.a].push_back(d.b);
    adj[d.b].push_back(d.a);
  }
  if (start < 0) return false;
  std::vector<bool> seen(n, false);
  std::queue<int> q;
  q.push(start);
  seen[start] = true;
  size_t count = 1;
  while (!q.empty()) {
    int r = q.front();
    q.pop();
    for (int s : adj[r])
      if (!seen[s]) {
        seen[s] = true;
        ++count;
        q.push(s);
      }
  }
  return count == n;
}

}  // namespace inet
