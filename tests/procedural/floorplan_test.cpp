// Floor plans: rooms tile the footprint without overlap, every room is reachable from the front
// door, doors and windows sit on walls of their rooms, and plans are deterministic per seed.
#include "procedural/floorplan.h"

#include <gtest/gtest.h>

#include <map>

#include "core/error.h"

namespace inet {
namespace {

CounterRng rngFor(uint32_t seed) {
  return CounterRng(seed, RngStream::Layout, 0, 0, 0);
}

TEST(FloorPlan, ThousandPlansTileConnectAndOpen) {
  std::map<int, int> counts;
  for (uint32_t seed = 0; seed < 1000; ++seed) {
    SCOPED_TRACE(seed);
    CounterRng rng = rngFor(seed);
    const int k = sampleRoomCount(rng);
    ++counts[k];
    FloorPlan plan = makeFloorPlan(roomProgram(k, rng), rng);
    ASSERT_EQ(plan.rooms.size(), static_cast<size_t>(k)) << "all 1,000 fit without dropping";
    double area = 0;
    for (size_t i = 0; i < plan.rooms.size(); ++i) {
      const auto& b = plan.rooms[i].box;
      area += b.volume();
      EXPECT_TRUE(plan.footprint.contains(b));
      EXPECT_GE(b.sizes().minCoeff(), 1.2 - 1e-9);
      for (size_t j = i + 1; j < plan.rooms.size(); ++j) {
        const auto overlap = b.intersection(plan.rooms[j].box);  // empty: min > max
        EXPECT_TRUE(overlap.isEmpty() || overlap.volume() < 1e-9) << i << " overlaps " << j;
      }
    }
    EXPECT_NEAR(area, plan.footprint.volume(), 0.05 * k) << "rooms tile the footprint";
    EXPECT_TRUE(allRoomsReachable(plan));
    int front = 0;
    for (const PlanDoor& d : plan.doors) {
      front += d.b < 0;
      EXPECT_NEAR(d.to - d.from, 0.85, 0.051);
      // the opening lies on a wall of room a
      const auto& b = plan.rooms[d.a].box;
      const int along = d.vertical ? 1 : 0;
      EXPECT_GE(d.from, b.min()[along] - 1e-9);
      EXPECT_LE(d.to, b.max()[along] + 1e-9);
      const double lo = d.vertical ? b.min().x() : b.min().y();
      const double hi = d.vertical ? b.max().x() : b.max().y();
      EXPECT_TRUE(std::fabs(d.line - lo) < 1e-9 || std::fabs(d.line - hi) < 1e-9);
    }
    EXPECT_EQ(front, 1) << "one front door";
    EXPECT_EQ(plan.doors.size(), plan.rooms.size()) << "a spanning tree plus the front door";
    for (const PlanWindow& w : plan.windows) {
      EXPECT_GT(w.to - w.from, 0.5);
      EXPECT_LT(w.sill, w.top);
    }
  }
  // every count from a studio to 10+ rooms occurs, most often 4..7
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[10] + counts[11] + counts[12], 0);
  int mid = 0;
  for (int k = 4; k <= 7; ++k) mid += counts[k];
  EXPECT_GT(mid, 500);
}

TEST(FloorPlan, EverySixteenRoomProgramGetsAPlan) {
  for (uint32_t seed = 0; seed < 40; ++seed) {
    CounterRng rng = rngFor(seed);
    FloorPlan plan = makeFloorPlan(roomProgram(16, rng), rng);
    EXPECT_GE(plan.rooms.size(), 12u) << "at most the few least needed rooms dropped";
    EXPECT_TRUE(allRoomsReachable(plan));
  }
}

TEST(FloorPlan, DeterministicPerSeed) {
  CounterRng a = rngFor(42), b = rngFor(42);
  FloorPlan p = makeFloorPlan(roomProgram(6, a), a), q = makeFloorPlan(roomProgram(6, b), b);
  ASSERT_EQ(p.rooms.size(), q.rooms.size());
  for (size_t i = 0; i < p.rooms.size(); ++i) {
    EXPECT_EQ(p.rooms[i].type, q.rooms[i].type);
    EXPECT_EQ(p.rooms[i].box.min(), q.rooms[i].box.min());
    EXPECT_EQ(p.rooms[i].box.max(), q.rooms[i].box.max());
  }
  EXPECT_EQ(p.doors.size(), q.doors.size());
}

TEST(FloorPlan, ProgramHasTheRoomTypesAndRejectsBadCounts) {
  CounterRng rng = rngFor(1);
  EXPECT_EQ(roomProgram(1, rng), std::vector<std::string>{"living_room"});
  auto all = roomProgram(16, rng);
  std::sort(all.begin(), all.end());
  EXPECT_EQ(std::unique(all.begin(), all.end()), all.end()) << "16 distinct types";
  EXPECT_THROW(roomProgram(0, rng), InputError);
  EXPECT_THROW(roomProgram(17, rng), InputError);
}

}  // namespace
}  // namespace inet
