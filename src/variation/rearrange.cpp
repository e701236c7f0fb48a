// Physics-based rearrangement with Bullet (see rearrange.h for the model and its choices).
#include "variation/rearrange.h"

#include <btBulletDynamicsCommon.h>
#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

/// The scene-variation stream; the rearrangement's draws carry their own tag in the third word.
constexpr RngStream kRearrangeStream = RngStream::Variation;

constexpr btScalar kMargin = 0.001f;       ///< collision margin of every shape (m)
constexpr double kTolerance = 0.01;        ///< penetration / support / room tolerance (m)
constexpr double kMovedM = 5e-3;           ///< smaller translations count as "not moved"
constexpr double kMovedDeg = 0.5;          ///< smaller rotations count as "not moved"
constexpr double kFloorCoveringM = 0.02;   ///< thinner instances lying on the floor: rugs
constexpr int kMaxHullPoints = 100;        ///< larger hulls are simplified (makeHull)
constexpr int kHullDirections = 256;       ///< directions a simplified hull keeps extremes of

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

Pose poseOf(const btTransform& T) {
  const btQuaternion q = T.getRotation();
  Pose p;
  p.q = Quat(q.w(), q.x(), q.y(), q.z()).normalized();
  p.t = fromBt(T.getOrigin());
  return p;
}

/// Contact friction = the larger of the two bodies' coefficients (rearrange.h).
btScalar maxFriction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::max(a->getFriction(), b->getFriction());
}

/// World-space points of one object: mesh vertices, or 42 points on an analytic sphere (grown so
/// that their hull encloses the sphere when `enclose`, else on the sphere).
std::vector<Vec3> objectPoints(const Scene& s, const Object& o, bool enclose = true) {
  std::vector<Vec3> pts;
  if (o.mesh < 0 || o.mesh >= static_cast<int>(s.meshes.size())) return pts;
  const Mesh& m = s.meshes[o.mesh];
  const Eigen::Matrix3d L = o.T_world_object.block<3, 3>(0, 0);
  const Vec3 t = o.T_world_object.block<3, 1>(0, 3);
  if (m.isSphere()) {
    const int n = 42;  // Fibonacci sphere, radius grown so the polytope encloses the sphere
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    const double r = enclose ? m.sphere_radius / std::cos(std::numbers::pi / 9) : m.sphere_radius;
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / n, rho = std::sqrt(1 - z * z);
      const Vec3 p(rho * std::cos(golden * i), rho * std::sin(golden * i), z);
      pts.push_back(L * (r * p) + t);
    }
    return pts;
  }
  pts.reserve(m.positions.size());
  for (const Vec3f& p : m.positions) pts.push_back(L * p.cast<double>() + t);
  return pts;
}

/// A convex hull of `pts - origin`, shrunk by the margin (btConvexHullComputer moves every face
/// inwards; at most a quarter of its distance to the centre, so thin parts keep some body) so
/// that hull plus margin is the original shape: resting contacts sit at zero gap and nothing
/// pops up when it wakes. Hulls of more than kMaxHullPoints vertices are simplified.
std::unique_ptr<btConvexHullShape> makeHull(const std::vector<Vec3>& pts, const Vec3& origin) {
  std::vector<btScalar> coords;
  coords.reserve(3 * pts.size());
  for (const Vec3& p : pts)
    for (int k = 0; k < 3; ++k) coords.push_back(btScalar(p[k] - origin[k]));
  auto hull = std::make_unique<btConvexHullShape>();
  btConvexHullComputer computer;
  const int n = static_cast<int>(pts.size());
  if (computer.compute(coords.data(), 3 * sizeof(btScalar), n, kMargin, 0.25f) >= 0 &&
      computer.vertices.size() > 0) {
    for (int i = 0; i < computer.vertices.size(); ++i) hull->addPoint(computer.vertices[i], false);
  } else {
    for (int i = 0; i < n; ++i)
      hull->addPoint(btVector3(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]), false);
  }
  hull->recalcLocalAabb();
  hull->setMargin(kMargin);
  if (hull->getNumPoints() > kMaxHullPoints) {
    // The hull's extreme points along kHullDirections directions spread evenly over the sphere
    // (a Fibonacci lattice). btShapeHull samples 42 directions, too few for round parts: a bean
    // bag's polyhedron rested 1 cm above where its rounded bottom reached, so the mesh sank
    // into the floor. With 256 directions the polyhedron stays within 0.6 % of a round part's
    // radius of it (1 - cos of half the directions' spacing).
    const btVector3* v = hull->getUnscaledPoints();
    std::vector<int> chosen;
    for (int k = 0; k < kHullDirections; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / kHullDirections;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = k * 2.399963229728653;  // golden angle
      const btVector3 d(btScalar(r * std::cos(phi)), btScalar(r * std::sin(phi)), btScalar(z));
      int best = 0;
      for (int i = 1; i < hull->getNumPoints(); ++i)
        if (v[i].dot(d) > v[best].dot(d)) best = i;
      chosen.push_back(best);
    }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    auto reduced = std::make_unique<btConvexHullShape>();
    for (int i : chosen) reduced->addPoint(v[i], false);
    reduced->recalcLocalAabb();
    reduced->setMargin(kMargin);
    return reduced;
  }
  return hull;
}

/// One instance (or one instance-less object) in the physics world.
struct Body {
  int instance = 0;
  std::string name;
  std::vector<int> objects;  ///< indices into Scene::objects
  int room = -1;
  bool dynamic = false;
  bool barrier = false;  ///< a room-closing barrier
  double mass = 0.0;
  btTransform start;
  btRigidBody* rb = nullptr;
};

/// Owns Bullet's objects; tears them down in the right order.
struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;

  World() { world.setGravity(btVector3(0, 0, -9.81f)); }
  ~World() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
  btRigidBody* add(btCollisionShape* shape, const btTransform& T, double mass, double friction,
                   int index) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    states.push_back(std::make_unique<btDefaultMotionState>(T));
    btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), states.back().get(), shape,
                                                inertia);
    ci.m_friction = btScalar(friction);
    ci.m_restitution = 0;
    ci.m_linearDamping = 0.05f;
    ci.m_angularDamping = 0.3f;
    ci.m_linearSleepingThreshold = 0.05f;   // m/s
    ci.m_angularSleepingThreshold = 0.1f;   // rad/s
    bodies.push_back(std::make_unique<btRigidBody>(ci));
    btRigidBody* rb = bodies.back().get();
    rb->setUserIndex(index);
    world.addRigidBody(rb);
    return rb;
  }
};

/// Per dynamic body: lowest normal-up contact gap (support) and deepest penetration, from the
/// world's current contact manifolds.
struct ContactSummary {
  std::vector<char> supported;  ///< per body index
  double max_penetration = 0.0;
  std::vector<std::string> penetrating;
};

ContactSummary summarizeContacts(World& w, const std::vector<Body>& bodies) {
  ContactSummary cs;
  cs.supported.assign(bodies.size(), 0);
  std::map<std::pair<int, int>, double> deepest;
  btDispatcher* d = w.world.getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
    const int a = pm->getBody0()->getUserIndex(), b = pm->getBody1()->getUserIndex();
    if (a < 0 || b < 0) continue;
    for (int k = 0; k < pm->getNumContacts(); ++k) {
      const btManifoldPoint& p = pm->getContactPoint(k);
      const double dist = p.getDistance();
      if (dist > kTolerance) continue;
      const double nz = p.m_normalWorldOnB.z();  // normal on B, pointing from B towards A
      if (nz > 0.5) cs.supported[a] = 1;
      if (nz < -0.5) cs.supported[b] = 1;
      if (-dist > cs.max_penetration) cs.max_penetration = -dist;
      if (-dist > kTolerance) {
        auto key = std::minmax(a, b);
        deepest[key] = std::max(deepest[key], -dist);
      }
    }
  }
  for (const auto& [key, depth] : deepest)
    cs.penetrating.push_back(
        fmt::format("{} / {}: {:.4f} m", bodies[key.first].name, bodies[key.second].name, depth));
  return cs;
}

double angleDeg(const Quat& a, const Quat& b) {
  return Eigen::AngleAxisd(b * a.conjugate()).angle() * 180.0 / std::numbers::pi;
}

nlohmann::ordered_json poseJson(const Pose& p) {
  return {{"t", {p.t.x(), p.t.y(), p.t.z()}}, {"q", {p.q.w(), p.q.x(), p.q.y(), p.q.z()}}};
}

}  // namespace

void RearrangeOptions::validate(const std::string& where) const {
  auto fail = [&](const char* field, const std::string& problem) {
    throw InputError(where, field, problem);
  };
  // field names are the command line's (interiornet vary rearrange)
  if (!(min_share >= 0 && min_share <= 1))
    fail("--min-share", fmt::format("{} is not in [0, 1]", min_share));
  if (!(max_share >= min_share && max_share <= 1))
    fail("--max-share", fmt::format("{} is not in [--min-share {}, 1]", max_share, min_share));
  if (!(min_accel >= 0 && min_accel <= 100))
    fail("--min-accel", fmt::format("{} m/s^2 is not in [0, 100]", min_accel));
  if (!(max_accel >= min_accel && max_accel <= 100))
    fail("--max-accel",
         fmt::format("{} m/s^2 is not in [--min-accel {}, 100]", max_accel, min_accel));
  if (!(duration_s > 0 && duration_s <= 600))
    fail("--duration", fmt::format("{} s is not in (0, 600]", duration_s));
  if (!(push_s >= 0 && push_s <= duration_s))
    fail("push", fmt::format("{} s is not in [0, duration]", push_s));
  if (!(cog_drop_fraction >= 0 && cog_drop_fraction < 0.5))
    fail("cog_drop", fmt::format("{} is not in [0, 0.5)", cog_drop_fraction));
  if (!(step_s >= 1e-4 && step_s <= 0.05))
    fail("step", fmt::format("{} s is not in [1e-4, 0.05]", step_s));
}

std::string RearrangeLog::toJson() const {
  nlohmann::ordered_json j;
  j["seed"] = seed;
  j["options"] = {{"min_share", options.min_share},   {"max_share", options.max_share},
                  {"min_accel", options.min_accel},   {"max_accel", options.max_accel},
                  {"duration_s", options.duration_s}, {"push_s", options.push_s},
                  {"beat_friction", options.beat_friction},
                  {"cog_drop_fraction", options.cog_drop_fraction},
                  {"step_s", options.step_s}};
  j["movable"] = movable;
  j["selected"] = selected;
  j["share"] = share;
  j["moved"] = moved;
  j["kept_static"] = kept_static;
  j["sim_time_s"] = sim_time_s;
  j["steps"] = steps;
  // wall_ms is left out: the file is part of the output, and same seed means same bytes
  auto& arr = j["objects"] = nlohmann::ordered_json::array();
  for (const RearrangeEntry& e : entries)
    arr.push_back({{"instance", e.instance},
                   {"name", e.name},
                   {"pushed", e.pushed},
                   {"accel", {e.accel.x(), e.accel.y(), e.accel.z()}},
                   {"accel_norm", e.accel.norm()},
                   {"start", poseJson(e.start)},
                   {"end", poseJson(e.end)},
                   {"distance_m", e.distance_m},
                   {"rotation_deg", e.rotation_deg},
                   {"moved", e.moved}});
  j["checks"] = {{"max_penetration_m", max_penetration_m},
                 {"penetrating", penetrating},
                 {"unsupported", unsupported},
                 {"outside_room", outside_room},
                 {"ok", ok()}};
  return j.dump(2) + "\n";
}

Scene rearrange(const Scene& in, const RearrangeOptions& opt, RearrangeLog* log) {
  const auto t0 = std::chrono::steady_clock::now();
  opt.validate("rearrange");
  static std::once_flag friction_once;
  std::call_once(friction_once, [] { gCalculateCombinedFrictionCallback = &maxFriction; });

  // ---- group objects into instances (instance 0: each object alone), in a fixed order ----
  std::vector<Body> bodies;
  {
    std::map<int, size_t> by_instance;
    for (size_t i = 0; i < in.objects.size(); ++i) {
      const Object& o = in.objects[i];
      if (o.instance > 0) {
        auto [it, fresh] = by_instance.emplace(o.instance, bodies.size());
        if (fresh) {
          bodies.emplace_back();
          bodies.back().instance = o.instance;
          bodies.back().name = o.name;
          bodies.back().room = o.room;
        }
        bodies[it->second].objects.push_back(static_cast<int>(i));
      } else {
        bodies.emplace_back();
        bodies.back().name = o.name;
        bodies.back().room = o.room;
        bodies.back().objects.push_back(static_cast<int>(i));
      }
    }
  }

  World w;
  std::vector<std::vector<std::vector<Vec3>>> points(bodies.size());  // per body, per part
  const size_t n_objects_bodies = bodies.size();
  for (size_t bi = 0; bi < n_objects_bodies; ++bi) {
    Body& b = bodies[bi];
    Eigen::AlignedBox3d box;
    bool movable = b.instance > 0, any_points = false;
    for (int oi : b.objects) {
      const Object& o = in.objects[oi];
      points[bi].push_back(objectPoints(in, o));
      for (const Vec3& p : points[bi].back()) box.extend(p), any_points = true;
      movable = movable && o.physics && o.physics->movable && !o.moving();
    }
    if (!any_points) continue;
    // floor coverings take no part
    const double floor_z = b.room >= 0 && b.room < static_cast<int>(in.rooms.size())
                               ? in.rooms[b.room].floor_z
                               : 0.0;
    if (box.sizes().z() < kFloorCoveringM && std::fabs(box.min().z() - floor_z) < kTolerance)
      continue;
    const Object& first = in.objects[b.objects.front()];
    if (movable) {
      b.dynamic = true;
      b.mass = first.physics->mass_kg;
      Vec3 com = box.center();
      com.z() -= opt.cog_drop_fraction * box.sizes().z();
      auto compound = std::make_unique<btCompoundShape>();
      btTransform id;
      id.setIdentity();
      for (const auto& pts : points[bi]) {
        if (pts.empty()) continue;
        w.shapes.push_back(makeHull(pts, com));
        compound->addChildShape(id, w.shapes.back().get());
      }
      compound->setMargin(kMargin);
      b.start.setIdentity();
      b.start.setOrigin(bt(com));
      w.shapes.push_back(std::move(compound));
      b.rb = w.add(w.shapes.back().get(), b.start, b.mass, first.physics->friction,
                   static_cast<int>(bi));
    } else {
      // static: one compound of world-space hulls; the shell (no physics) carries friction 0
      auto compound = std::make_unique<btCompoundShape>();
      btTransform id;
      id.setIdentity();
      for (const auto& pts : points[bi]) {
        if (pts.empty()) continue;
        w.shapes.push_back(makeHull(pts, Vec3::Zero()));
        compound->addChildShape(id, w.shapes.back().get());
      }
      b.start.setIdentity();
      w.shapes.push_back(std::move(compound));
      const bool shell = first.kind == "wall" || first.kind == "floor" ||
                         first.kind == "ceiling" || !first.physics;
      b.rb = w.add(w.shapes.back().get(), b.start, 0.0,
                   shell ? 0.0 : double(first.physics->friction), static_cast<int>(bi));
    }
  }
  // ---- room barriers: thin boxes along every outline edge, floor to ceiling ----
  for (const Room& r : in.rooms) {
    for (size_t k = 0; k < r.outline.size(); ++k) {
      const Eigen::Vector2d a = r.outline[k], c = r.outline[(k + 1) % r.outline.size()];
      const double len = (c - a).norm();
      if (len < 1e-6) continue;
      const double h = r.ceiling_z - r.floor_z;
      w.shapes.push_back(std::make_unique<btBoxShape>(
          btVector3(btScalar(len / 2), 0.005f, btScalar(h / 2))));
      btTransform T;
      T.setIdentity();
      T.setOrigin(btVector3(btScalar((a.x() + c.x()) / 2), btScalar((a.y() + c.y()) / 2),
                            btScalar(r.floor_z + h / 2)));
      T.setRotation(btQuaternion(btVector3(0, 0, 1),
                                 btScalar(std::atan2(c.y() - a.y(), c.x() - a.x()))));
      Body b;
      b.name = "barrier of room " + r.id;
      b.barrier = true;
      b.start = T;
      bodies.push_back(b);
      bodies.back().rb = w.add(w.shapes.back().get(), T, 0.0, 0.0,
                               static_cast<int>(bodies.size()) - 1);
    }
  }

  // ---- movable instances nothing holds up (hung on walls) stay static ----
  RearrangeLog lg;
  lg.seed = opt.seed;
  lg.options = opt;
  w.world.performDiscreteCollisionDetection();
  {
    const ContactSummary cs = summarizeContacts(w, bodies);
    for (size_t bi = 0; bi < bodies.size(); ++bi) {
      Body& b = bodies[bi];
      if (!b.dynamic || cs.supported[bi]) continue;
      w.world.removeRigidBody(b.rb);
      b.rb->setMassProps(0, btVector3(0, 0, 0));
      b.rb->setCollisionFlags(b.rb->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      b.rb->updateInertiaTensor();
      w.world.addRigidBody(b.rb);
      b.dynamic = false;
      ++lg.kept_static;
    }
  }

  // ---- selection and pushes ----
  std::vector<int> dyn;  // body indices, instance order
  for (size_t bi = 0; bi < bodies.size(); ++bi)
    if (bodies[bi].dynamic) dyn.push_back(static_cast<int>(bi));
  std::vector<int> selected;
  if (!opt.only_instances.empty()) {
    for (int bi : dyn)
      if (std::find(opt.only_instances.begin(), opt.only_instances.end(),
                    bodies[bi].instance) != opt.only_instances.end())
        selected.push_back(bi);
  } else if (!dyn.empty()) {
    CounterRng rng(opt.seed, kRearrangeStream, 0, 0, 0);
    const int M = static_cast<int>(dyn.size());
    int lo = static_cast<int>(std::ceil(opt.min_share * M - 1e-9));
    int hi = static_cast<int>(std::floor(opt.max_share * M + 1e-9));
    int n;
    if (lo <= hi) {
      n = lo + std::min(hi - lo, static_cast<int>(rng.uniformDouble() * (hi - lo + 1)));
    } else {  // too few movable instances for the range: the count nearest to it
      n = std::clamp(static_cast<int>(std::lround(0.5 * (opt.min_share + opt.max_share) * M)),
                     std::min(1, M), M);
    }
    std::vector<int> pool = dyn;
    for (int k = 0; k < n; ++k) {
      const int j = k + std::min(M - k - 1, static_cast<int>(rng.uniformDouble() * (M - k)));
      std::swap(pool[k], pool[j]);
    }
    selected.assign(pool.begin(), pool.begin() + n);
    std::sort(selected.begin(), selected.end());
  }
  std::map<int, Vec3> accel;  // body index -> acceleration
  for (int bi : selected) {
    CounterRng rng(opt.seed, kRearrangeStream, 1, static_cast<uint32_t>(bodies[bi].instance), 0);
    const double a = rng.uniformDouble(opt.min_accel, opt.max_accel);
    const double phi = rng.uniformDouble(0.0, 2.0 * std::numbers::pi);
    accel[bi] = Vec3(a * std::cos(phi), a * std::sin(phi), 0.0);
  }
  // unpushed bodies start asleep; touching wakes them
  for (int bi : dyn)
    if (!accel.count(bi)) bodies[bi].rb->setActivationState(ISLAND_SLEEPING);

  // ---- simulate ----
  const int max_steps = static_cast<int>(std::ceil(opt.duration_s / opt.step_s - 1e-9));
  const int push_steps = static_cast<int>(std::ceil(opt.push_s / opt.step_s - 1e-9));
  const btScalar dt = btScalar(opt.step_s);
  int steps = 0;
  for (; steps < max_steps; ++steps) {
    if (steps < push_steps) {
      for (const auto& [bi, a] : accel) {
        bodies[bi].rb->activate(true);
        const double mu = opt.beat_friction ? bodies[bi].rb->getFriction() : 0.0;
        bodies[bi].rb->applyCentralForce(bt(bodies[bi].mass * (a + mu * 9.81 * a.normalized())));
      }
    } else {
      bool awake = false;
      for (int bi : dyn) awake = awake || bodies[bi].rb->isActive();
      if (!awake) break;
    }
    w.world.stepSimulation(dt, 0, dt);
  }
  lg.steps = steps;
  lg.sim_time_s = steps * opt.step_s;

  // ---- write back: moved instances get delta * T_world_object ----
  Scene out = in;
  std::vector<char> moved(bodies.size(), 0);
  std::vector<RearrangeEntry> others;
  for (int bi : dyn) {
    Body& b = bodies[bi];
    const btTransform end = b.rb->getWorldTransform();
    RearrangeEntry e;
    e.instance = b.instance;
    e.name = b.name;
    e.start = poseOf(b.start);
    e.end = poseOf(end);
    e.distance_m = (e.end.t - e.start.t).norm();
    e.rotation_deg = angleDeg(e.start.q, e.end.q);
    e.moved = e.distance_m >= kMovedM || e.rotation_deg >= kMovedDeg;
    if (accel.count(bi)) {
      e.pushed = true;
      e.accel = accel[bi];
    }
    if (e.moved) {
      moved[bi] = 1;
      ++lg.moved;
      const Mat4 delta = (e.end * e.start.inverse()).matrix();
      for (int oi : b.objects) out.objects[oi].T_world_object = delta * in.objects[oi].T_world_object;
    } else {
      b.rb->setWorldTransform(b.start);  // restore exactly for the checks
      e.end = e.start;
    }
    if (e.pushed)
      lg.entries.push_back(e);
    else if (e.moved)
      others.push_back(e);
  }
  lg.entries.insert(lg.entries.end(), others.begin(), others.end());
  lg.movable = static_cast<int>(dyn.size());
  lg.selected = static_cast<int>(selected.size());
  lg.share = dyn.empty() ? 0.0 : double(lg.selected) / lg.movable;

  // ---- checks: contacts of the final poses, support of moved bodies, rooms ----
  for (int bi : dyn) bodies[bi].rb->activate(true);
  w.world.performDiscreteCollisionDetection();
  const ContactSummary cs = summarizeContacts(w, bodies);
  lg.max_penetration_m = cs.max_penetration;
  lg.penetrating = cs.penetrating;
  for (int bi : dyn) {
    const Body& b = bodies[bi];
    if (!moved[bi]) continue;
    if (!cs.supported[bi]) lg.unsupported.push_back(b.name);
    if (b.room < 0 || b.room >= static_cast<int>(in.rooms.size())) continue;
    const Room& r = in.rooms[b.room];
    std::string outside;
    for (int oi : b.objects)
      for (const Vec3& p : objectPoints(out, out.objects[oi], false))
        // a wall-side piece rests against the room barrier, which its contact can enter by a
        // fraction of a millimetre: the outline gets the tolerance the floor and ceiling get
        if (outside.empty() && !(r.contains(p.x(), p.y(), kTolerance) &&
                                 p.z() >= r.floor_z - kTolerance &&
                                 p.z() <= r.ceiling_z + kTolerance))
          outside = fmt::format("{} ({}): ({:.3f}, {:.3f}, {:.3f}) outside room {}", b.name,
                                out.objects[oi].part, p.x(), p.y(), p.z(), r.id);
    if (!outside.empty()) lg.outside_room.push_back(outside);
  }
  lg.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (log) *log = std::move(lg);
  return out;
}

}  // namespace inet
