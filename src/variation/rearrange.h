#pragma once
// Physics-based rearrangement of a layout (issue 7; InteriorNet, Li et al. BMVC 2018, section
// 3.3 "Simulating scene change over time"): 5-45 % of the movable objects get a random
// horizontal push of 0.5-2 m/s^2 with their centre of gravity lowered so they do not tip, the
// world is simulated for up to 10 s with Bullet, and the settled poses are written back.
//
// The physics world (rearrange.cpp):
//  - one rigid body per movable instance: a compound of one convex hull per part (the part
//    mesh's vertices in world space; analytic spheres as 42 points; shrunk by the 1 mm
//    collision margin so hull + margin is the true shape; hulls of more than 100 points
//    reduced to their extreme points along 256 even directions), mass and friction from its
//    PhysicsProps;
//  - walls, floors, ceilings, unmovable furniture and objects without PhysicsProps are static
//    convex hulls; thin floor coverings (rugs: under 2 cm tall, lying on the floor) take no part
//    (nothing stands "in" them, they never move);
//  - every room's outline is closed by thin static barriers from floor to ceiling (they lie
//    inside the walls, so only doorways and openings are affected): nothing leaves its room;
//  - a movable instance that nothing holds up at the start (hung on a wall) stays static;
//  - every dynamic body's centre of mass is its bounding box centre lowered by
//    `cog_drop_fraction` of its height (0.25: from half to a quarter of the height);
//  - the push: for `push_s` (0.5 s) the force m (a + mu g a/|a|) on the centre of mass, i.e. `a`
//    is the net acceleration of a free object while pushed (it then slides to rest at mu g;
//    a <= 2 m/s^2 and mu >= 0.08 give at most ~0.9 m). Applying the acceleration for the whole
//    10 s would slide objects tens of metres; the force m a alone (`beat_friction` = false)
//    leaves most pushes below static friction (mu g = 0.8..2.6 m/s^2 for the paper's
//    friction range), so few selected objects would move;
//  - contact friction is the larger coefficient of the two bodies (the shell carries 0, so an
//    object on the floor uses its own); this sets Bullet's global friction-combining callback;
//  - fixed step `step_s` (1/240 s), single-threaded btDiscreteDynamicsWorld with the sequential
//    impulse solver, bodies added in instance order: the same input and seed give bit-identical
//    output on any machine thread count; unpushed bodies start asleep and wake when touched;
//    the run stops early once every body sleeps (nothing can change after that).
// Afterwards instances that moved less than 5 mm and turned less than 0.5 degree keep their
// exact input pose; the rest get T_world_object = delta * T_world_object (all parts of one
// instance by the same rigid delta). The final contacts are checked: penetration deeper than
// 1 cm, a moved body without support (no contact within 1 cm whose normal points up into it),
// and a body outside its room are reported in the log.
#include <cstdint>
#include <string>
#include <vector>

#include "core/pose.h"
#include "scene/scene.h"

namespace inet {

struct RearrangeOptions {
  uint64_t seed = 0;
  double min_share = 0.05;  ///< share of movable instances pushed, drawn in [min, max]
  double max_share = 0.45;
  double min_accel = 0.5;  ///< push acceleration magnitude (m/s^2), drawn in [min, max]
  double max_accel = 2.0;
  double duration_s = 10.0;         ///< simulated time at most (s)
  double push_s = 0.5;              ///< how long the push force acts (s)
  bool beat_friction = true;  ///< push force m (a + mu g): `a` is the net acceleration; else m a
  double cog_drop_fraction = 0.25;  ///< centre of mass lowered by this share of the height
  double step_s = 1.0 / 240.0;      ///< fixed physics step (s)
  /// Instances to push instead of a random selection (tests, manual use); empty = random.
  std::vector<int> only_instances;
  /// Throws InputError(where, field, problem) on a value out of range.
  void validate(const std::string& where) const;
};

/// One pushed or otherwise moved instance.
struct RearrangeEntry {
  int instance = 0;
  std::string name;
  bool pushed = false;     ///< selected and pushed (else moved by contact or by its support)
  Vec3 accel = Vec3::Zero();  ///< applied acceleration (m/s^2, world, horizontal); 0 if not pushed
  Pose start, end;            ///< pose of the instance's body frame (centre of mass), world
  double distance_m = 0.0;    ///< |end.t - start.t|
  double rotation_deg = 0.0;  ///< angle of end.q * start.q^-1
  bool moved = false;         ///< moved >= 5 mm or turned >= 0.5 deg (its objects were updated)
};

struct RearrangeLog {
  uint64_t seed = 0;
  RearrangeOptions options;
  int movable = 0;       ///< movable instances that took part (dynamic bodies)
  int selected = 0;      ///< pushed
  double share = 0.0;    ///< selected / movable
  int moved = 0;         ///< instances whose pose changed (pushed or not)
  int kept_static = 0;   ///< movable instances without support at the start, kept static
  std::vector<RearrangeEntry> entries;  ///< every pushed instance, then every other moved one
  double sim_time_s = 0.0;  ///< simulated time (<= duration_s; less when all slept early)
  int steps = 0;
  double wall_ms = 0.0;  ///< wall-clock time of the whole call (not part of the determinism)
  // final checks
  double max_penetration_m = 0.0;  ///< deepest contact between two bodies at the end
  std::vector<std::string> penetrating;  ///< "a / b: 0.012 m" for contacts deeper than 1 cm
  std::vector<std::string> unsupported;  ///< moved instances with no support contact
  std::vector<std::string> outside_room;  ///< "name (part): (x, y, z) outside room id" (> 1 cm)
  bool ok() const { return penetrating.empty() && unsupported.empty() && outside_room.empty(); }
  /// The log as JSON (options, counts, entries with accel/start/end/distance, checks).
  std::string toJson() const;
};

/// Rearranges the movable objects of `in` (see the top of this file). Returns the settled
/// scene: moved instances get new T_world_object, nothing else changes. Objects without
/// PhysicsProps are static. `log` (optional) receives what was done. Throws InputError on bad
/// options.
Scene rearrange(const Scene& in, const RearrangeOptions& opt, RearrangeLog* log = nullptr);

}  // namespace inet
