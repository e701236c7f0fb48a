#pragma once
// Procedural floor plans: an apartment's rooms as axis-aligned rectangles that tile a rectangular
// footprint, doors that connect every room (a spanning tree of the adjacency graph that prefers
// public rooms as hubs, plus the front door), windows on exterior walls, and the wall centre
// lines with their openings.
//
// Method: the room program (types and target areas) is laid out by a binary treemap: the rooms,
// sorted by area, are split into two groups of about equal area and the rectangle is cut across
// its longer side in that ratio, recursively. Cuts keep every room adjacent to its neighbours
// along whole walls, which is what doors need. Plans whose rooms come out too narrow, or whose
// adjacency graph (shared walls of at least kMinDoorWall) is not connected, are redrawn.
// Hand-written: no Debian package generates floor plans.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/rng.h"

namespace inet {

/// One room of a plan: its type and its rectangle between wall centre lines (metres).
struct PlanRoom {
  std::string type;
  Eigen::AlignedBox2d box;
};

/// A door opening on a wall centre line between rooms `a` and `b` (b = -1: the front door, to
/// the outside). The opening spans [from, to] along the wall, which is vertical (constant x)
/// when `vertical`.
struct PlanDoor {
  int a = -1, b = -1;
  bool vertical = false;
  double line = 0;  ///< x of a vertical wall, y of a horizontal one
  double from = 0, to = 0;
  double height = 2.05;
};

/// A window in an exterior wall of room `room`, [from, to] along the wall, sill to top.
struct PlanWindow {
  int room = -1;
  bool vertical = false;
  double line = 0;
  double from = 0, to = 0;
  double sill = 0.9, top = 2.2;
  Eigen::Vector2d outward;  ///< unit normal of the wall pointing out of the apartment
};

struct FloorPlan {
  std::vector<PlanRoom> rooms;
  std::vector<PlanDoor> doors;
  std::vector<PlanWindow> windows;
  Eigen::AlignedBox2d footprint;
  double wall_thickness = 0.12;
  double ceiling = 2.7;
};

/// Shortest wall two rooms must share to get a door.
constexpr double kMinDoorWall = 1.2;

/// Number of rooms of a random apartment: 1 (a studio) to 12, most often 4 to 7 (a distribution
/// shaped like the InteriorNet paper's Fig. 3 histogram of rooms per layout).
int sampleRoomCount(CounterRng& rng);

/// The room types of an apartment with `count` rooms (1..16), in order of importance: a studio
/// is one living room; then living room, kitchen, bathroom, master bedroom, ... (issue 4's 16
/// types). Deterministic in `rng`.
std::vector<std::string> roomProgram(int count, CounterRng& rng);

/// A floor plan with the rooms of `program` (rarely fewer: when 200 layouts of a big program of
/// small rooms all fail, its last, least needed room is dropped). Deterministic in `rng`.
FloorPlan makeFloorPlan(const std::vector<std::string>& program, CounterRng& rng);

/// Rooms reachable from the front door through doors (for tests): true when every room is.
bool allRoomsReachable(const FloorPlan& plan);

}  // namespace inet
