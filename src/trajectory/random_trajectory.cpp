#include "trajectory/random_trajectory.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "core/error.h"
#include "core/rng.h"
#include "trajectory/style_model.h"

namespace inet {

namespace {

constexpr double kSimDt = 1e-3;     // simulation step (s)
constexpr double kDrag = 1.0;       // k: velocity decays as exp(-k t) without forces (1/s)
constexpr double kWarmup = 3.0;     // seconds simulated before the first frame
constexpr double kMaxSettle = 20.0;  // more seconds at most, for a first view that is not a wall
constexpr double kMargin = 0.005;   // extra clearance so interpolated samples keep the real one
constexpr double kWallBand = 0.25;  // distance beyond the clearance where walls start to push
constexpr double kMaxYawRate = 2.0;  // look-forward: yaw rate limit at w_mult 1 (rad/s)
constexpr double kLeanOmega = 2.0;  // natural frequency of the up vector's lean (rad/s)
constexpr double kCarry = 1.0;      // share of the camera's velocity the look-at body takes on

/// A 3-D Ornstein-Uhlenbeck process with correlation time tau and stationary standard
/// deviation sigma per axis, stepped exactly (not Euler), so its statistics do not depend on dt,
/// then low-passed (first order, time constant kForceSmoothing) into `value`. An OU process is
/// continuous but has a white-noise derivative; a force like that gives a body a jerk of white
/// noise, i.e. broadband acceleration up to the simulation rate. Smoothed, the base motion is
/// smooth (acceleration falls as 1/f^2 above ~0.5 Hz), as the paper's base trajectories are
/// meant to be: realistic hand-held jitter is the style model's job.
constexpr double kForceSmoothing = 0.3;  // s
constexpr double kGuideSmoothing = 0.1;  // s: low-pass of the look-forward turn and brake
constexpr double kWallPush = 8.0;     // m/s^2: wall push at the clearance (0 at the band edge)

struct OuProcess {
  Vec3 ou = Vec3::Zero();
  Vec3 value = Vec3::Zero();
  Vec3 sigma = Vec3::Zero();
  double tau = 1.0;
  void start(CounterRng& rng) {
    for (int c = 0; c < 3; ++c) ou[c] = sigma[c] * rng.normal();
    value = ou;
  }
  void step(CounterRng& rng, double dt) {
    const double a = std::exp(-dt / tau), b = std::sqrt(1.0 - a * a);
    for (int c = 0; c < 3; ++c) ou[c] = a * ou[c] + b * sigma[c] * rng.normal();
    value += (ou - value) * (dt / kForceSmoothing);
  }
};

/// RMS speed per axis of a body with drag k driven by a smoothed OU force of unit sigma: the
/// variance at the output of three first-order low-passes with poles a = 1/tau, b =
/// 1/kForceSmoothing, c = k driven by white noise of intensity 2 a, from
///   integral dw / ((w^2+a^2)(w^2+b^2)(w^2+c^2)) = pi (a+b+c) / (abc (a+b)(b+c)(c+a)).
double ouSpeedFactor(double tau, double k = kDrag) {
  const double a = 1.0 / tau, b = 1.0 / kForceSmoothing, c = k;
  return std::sqrt(b * (a + b + c) / (c * (a + b) * (b + c) * (c + a)));
}

struct State {
  Vec3 cam, target, up;
};

State lerp(const State& a, const State& b, double f) {
  return {a.cam + f * (b.cam - a.cam), a.target + f * (b.target - a.target),
          (a.up + f * (b.up - a.up)).normalized()};
}

}  // namespace

MotionType parseMotionType(const std::string& name, const std::string& field) {
  if (name == "two-body") return MotionType::TwoBody;
  if (name == "hand-held") return MotionType::HandHeld;
  if (name == "look-forward") return MotionType::LookForward;
  throw InputError("", field,
                   fmt::format("unknown trajectory type '{}' (two-body, hand-held, look-forward)",
                               name));
}

const char* motionTypeName(MotionType t) {
  switch (t) {
    case MotionType::TwoBody: return "two-body";
    case MotionType::HandHeld: return "hand-held";
    case MotionType::LookForward: return "look-forward";
  }
  return "?";
}

namespace {

/// Why no start was found, with what was tried and what to change.
std::string noStartMessage(const FreeSpace& space, const RandomTrajectoryOptions& opt,
                           double clear) {
  std::string floors;
  for (double z : space.floorLevels())  // (no "-0.00")
    floors += fmt::format("{}{:.2f}", floors.empty() ? "" : ", ", std::abs(z) < 0.005 ? 0.0 : z);
  const std::string what = fmt::format(
      "no place {:.2f} m from all geometry at {:.1f}-{:.1f} m above a floor for a camera "
      "(tried a {:.3f} m voxel grid: {:.1f} m^3 of free space indoors, {:.1f} m^3 of it {:.2f} m "
      "from the geometry; {})",
      opt.clearance, opt.min_height, opt.max_height, space.voxel(), space.indoorVolume(),
      space.freeVolume(clear), clear,
      floors.empty() ? std::string("no floor found") : "floors at z = " + floors + " m");
  if (space.floorLevels().empty())
    return what + ": no floor was found (a level surface of at least 2 m^2 with free space "
                  "above it); is the up axis right (--up y for Y-up files)?";
  if (space.freeVolume(clear) < 0.1)
    return what + ": the scene is too tight or not enclosed; try a smaller --clearance";
  return what + ": try other --min-height/--max-height for this scene";
}

}  // namespace

RandomTrajectory generateRandomTrajectory(const FreeSpace& space,
                                          const RandomTrajectoryOptions& opt,
                                          const std::string& source) {
  INET_CHECK(opt.frames >= 1 && opt.fps > 0 && opt.exposure_s >= 0 && opt.dense_rate > 0);
  INET_CHECK(opt.min_height < opt.max_height && opt.clearance >= 0);
  CounterRng rng(opt.seed, RngStream::Trajectory, static_cast<uint32_t>(opt.type), 0, 0);
  RandomTrajectory out;
  out.v_mult = opt.v_mult > 0 ? opt.v_mult : rng.uniformDouble(0.5, 5.0);
  out.w_mult = opt.w_mult > 0 ? opt.w_mult : rng.uniformDouble(0.5, 3.0);
  const double clear = opt.clearance + kMargin;
  const bool forward = opt.type == MotionType::LookForward;

  // ---- start: a random free voxel at a comfortable height above its floor ----
  std::vector<FreeSpace::FreeVoxel> starts =
      space.freeCentres(clear + 0.2, opt.min_height + 0.2, opt.max_height - 0.2);
  if (starts.empty()) starts = space.freeCentres(clear, opt.min_height, opt.max_height);
  if (starts.empty())
    throw InputError(source, "free space", noStartMessage(space, opt, clear));
  // an open scene: start where geometry surrounds the camera (the room, not the eaves outside
  // its walls or the gap where a wall is missing): the candidates that see geometry in at
  // least 10 of 16 horizontal directions (or in the most, if none does); of those, the
  // roomiest below (a cupboard's inside sees geometry all round too, but close)
  if (space.isOpen()) {
    std::vector<int> seen(starts.size(), 0);
    for (size_t i = 0; i < starts.size(); ++i)
      for (int h = 0; h < 16; ++h) {
        const double a = 2 * M_PI * h / 16;
        seen[i] += space.seesGeometry(starts[i].centre, Vec3(std::cos(a), std::sin(a), 0), 15.0);
      }
    const int need = std::min(10, *std::max_element(seen.begin(), seen.end()));
    std::vector<FreeSpace::FreeVoxel> enclosed;
    for (size_t i = 0; i < starts.size(); ++i)
      if (seen[i] >= need) enclosed.push_back(starts[i]);
    starts = std::move(enclosed);
  }
  // start in open space: among the quarter of the candidates farthest from any geometry (the
  // middles of the larger rooms), so a trajectory does not open in a closet facing a wall; the
  // rest keep their grid order, so the draw below is deterministic
  const size_t keep = std::max<size_t>(1, starts.size() / 4);
  std::vector<size_t> order(starts.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::nth_element(order.begin(), order.begin() + (keep - 1), order.end(), [&](size_t a, size_t b) {
    return starts[a].clearance != starts[b].clearance ? starts[a].clearance > starts[b].clearance
                                                      : a < b;
  });
  order.resize(keep);
  std::sort(order.begin(), order.end());
  State s;
  const FreeSpace::FreeVoxel& start =
      starts[order[std::min(keep - 1, static_cast<size_t>(rng.uniformDouble() * keep))]];
  s.cam = start.centre;
  // heights are kept above the start's floor: its storey (z = 0 in procedural layouts)
  const double floor_z = start.floor_z;
  // In a low space of an imported scene (a 2 m Cornell box) the heights shrink with the room
  // (below 2.6 m of headroom) and the look-at point stays 0.3 m under the ceiling, so the view
  // takes in the floor and what stands on it rather than the ceiling lamp. Procedural rooms
  // are 2.5 m or higher and keep the plain limits.
  double scale = 1.0, look_top = floor_z + 2.5;
  if (space.floorsFromGeometry())
    if (const double c = space.ceilingAbove(start.centre); std::isfinite(c)) {
      scale = std::clamp((c - floor_z) / 2.6, 0.5, 1.0);
      look_top = std::min(look_top, c - 0.3);
    }
  const double h_lo = floor_z + opt.min_height * scale, h_hi = floor_z + opt.max_height * scale;
  s.up = Vec3::UnitZ();
  const double look_dist = 1.5;
  // How open the view along horizontal heading `a` is from `p`: the mean free line of sight
  // (up to 5 m, as a share of it) over five directions across a 60-degree field of view. One
  // central ray is not enough: through a doorway it may see 5 m while the view beside it is a
  // wall half a metre away. An open scene's rays into the void past a missing wall count -0.1.
  auto openness = [&](const Vec3& p, double a) {
    double sum = 0.0;
    for (const double off_deg : {-30.0, -15.0, 0.0, 15.0, 30.0}) {
      const double b = a + off_deg * M_PI / 180.0;
      const Vec3 dir(std::cos(b), std::sin(b), 0);
      double r = 0.0;
      while (r < 5.0 && space.lowerBound(p + (r + 0.1) * dir) > 0.0) r += 0.1;
      sum += space.isOpen() && !space.seesGeometry(p, dir, 15.0) ? -0.1 : r / 5.0;
    }
    return sum / 5.0;
  };
  // first view: of 16 headings, the most open one (ties broken by a random rotation of the fan)
  const double fan = 2 * M_PI * rng.uniformDouble();
  double best_range = -1.0, best_heading = fan;
  for (int h = 0; h < 16; ++h) {
    const double a = fan + 2 * M_PI * h / 16;
    const double range = openness(s.cam, a);
    if (range > best_range) best_range = range, best_heading = a;
  }
  s.target = s.cam + Vec3(look_dist * std::cos(best_heading), look_dist * std::sin(best_heading), -0.3);

  // ---- forces ----
  // look-forward: the heading is the velocity's direction, which forgets itself at the drag rate
  // and the force's correlation time; both scale with w_mult so the view turns with it
  const double cam_tau = forward ? 2.0 / out.w_mult : 1.0;
  const double cam_drag = forward ? 0.5 * kDrag * out.w_mult : kDrag;
  const double cam_sigma =
      opt.base_speed * out.v_mult / std::sqrt(2.0) / ouSpeedFactor(cam_tau, cam_drag);
  OuProcess cam_force;
  cam_force.tau = cam_tau;
  cam_force.sigma = Vec3(cam_sigma, cam_sigma, 0.25 * cam_sigma);
  const double turn = opt.base_turn_deg * M_PI / 180.0 * out.w_mult;
  const double target_sigma = turn * look_dist / std::sqrt(2.0) / ouSpeedFactor(1.0);
  OuProcess target_force;
  target_force.tau = 1.0;
  target_force.sigma = Vec3(target_sigma, target_sigma, 0.5 * target_sigma);
  // the up vector's lean (x, y, radians) follows an OU process through a critically damped
  // spring (2 rad/s), so it is smooth (C1): an OU process itself has a white-noise derivative,
  // which would put ~1 rad/s of jitter into the angular velocity
  OuProcess tilt;
  tilt.tau = 2.0;
  tilt.sigma = Vec3::Constant(opt.max_tilt_deg * M_PI / 180.0 / 2.5);
  tilt.sigma.z() = 0;
  cam_force.start(rng);
  target_force.start(rng);
  tilt.start(rng);
  const double max_tilt = opt.max_tilt_deg * M_PI / 180.0;
  Vec3 lean(tilt.value.x(), tilt.value.y(), 0), lean_rate = Vec3::Zero();
  if (lean.norm() > max_tilt) lean *= max_tilt / lean.norm();
  const double kp = std::pow(4.0 * out.w_mult, 2), kd = 2.0 * std::sqrt(kp);  // look-forward yaw

  Vec3 v_cam = Vec3::Zero(), v_target = Vec3::Zero();
  double steer = 0.0, brake = 0.0;  // look-forward: smoothed turn (+ left) and brake strengths
  double yaw = std::atan2(s.target.y() - s.cam.y(), s.target.x() - s.cam.x()), yaw_rate = 0.0;
  Vec3 heading(std::cos(yaw), std::sin(yaw), 0);
  double pitch = -0.15;
  // one step of the coupled system; keeps the camera free and within the height limits
  auto step = [&]() {
    cam_force.step(rng, kSimDt);
    target_force.step(rng, kSimDt);
    tilt.step(rng, kSimDt);

    // camera
    Vec3 f = cam_force.value;
    Vec3 vh(v_cam.x(), v_cam.y(), 0);
    if (vh.norm() > 0.05) heading = vh.normalized();
    if (forward && f.dot(heading) < 0) f -= 2.0 * f.dot(heading) * heading;
    // guidance: walls push and heights are kept. Both forces are continuous in the position
    // (the field's gradient is a central difference over a whole voxel), so the base motion
    // stays smooth without a low-pass in time (a 0.1 s one here once pumped a camera bouncing
    // between the walls of a narrow room into growing oscillations: a delayed spring)
    Vec3 guide = Vec3::Zero();
    const double d = space.lowerBound(s.cam);
    if (d < clear + kWallBand) {
      Vec3 g = space.gradient(s.cam);
      if (g.norm() > 1e-9) {
        g.normalize();
        guide += kWallPush * (clear + kWallBand - d) / kWallBand * g;
        // and a brake on the speed towards the wall, just what stops it before the clearance
        // (v^2 / 2 gap, with a margin), so a fast camera does not reach it and bounce: a bounce
        // is an impulse of acceleration, the opposite of a smooth base path
        const double towards = std::max(0.0, -v_cam.dot(g));
        const double gap = std::max(d - clear, 0.02);
        guide += 1.1 * towards * towards / (2.0 * gap) * g;
      }
    }
    // look-forward: a walker steers round what is ahead instead of bouncing off it: look ahead
    // along the heading and turn towards the freer side, braking as the obstacle nears. The
    // turn and the brake act along the current velocity (perpendicular to it, and against it),
    // so they never add energy; only their strengths go through the low-pass.
    double steer_target = 0.0, brake_target = 0.0;
    const Vec3 left(-heading.y(), heading.x(), 0);
    if (forward && vh.norm() > 0.05) {
      const double speed = vh.norm(), look = 0.4 + 1.0 * speed;
      const double ahead = space.lowerBound(s.cam + look * heading);
      const double want = clear + 0.3;
      if (ahead < want) {
        const double c = std::cos(M_PI / 3), sn = std::sin(M_PI / 3);
        const double dl = space.lowerBound(s.cam + look * (c * heading + sn * left));
        const double dr = space.lowerBound(s.cam + look * (c * heading - sn * left));
        const double urgency = std::clamp((want - ahead) / want, 0.0, 1.0);
        steer_target = dl >= dr ? urgency : -urgency;
        brake_target = urgency;
      }
    }
    steer += (steer_target - steer) * (kSimDt / kGuideSmoothing);
    brake += (brake_target - brake) * (kSimDt / kGuideSmoothing);
    const double mid = 0.5 * (h_lo + h_hi);
    guide.z() += -1.0 * (s.cam.z() - mid);  // weak pull to mid-height, so heights vary but stay
    const double margin = 0.15;             // and a firm one near the height limits
    if (s.cam.z() < h_lo + margin) guide.z() += 30.0 * (h_lo + margin - s.cam.z());
    if (s.cam.z() > h_hi - margin) guide.z() -= 30.0 * (s.cam.z() - (h_hi - margin));
    const Vec3 a = f - cam_drag * v_cam + guide +
                   steer * (vh.squaredNorm() / 0.4) * left - brake * 1.0 * vh;
    v_cam += a * kSimDt;
    Vec3 next = s.cam + v_cam * kSimDt;
    if (next.z() < h_lo || next.z() > h_hi) {
      v_cam.z() = -0.5 * v_cam.z();
      next.z() = std::clamp(next.z(), h_lo, h_hi);
    }
    if (!space.hasClearance(next, clear)) {
      Vec3 n = space.gradient(s.cam);
      if (n.norm() > 1e-9) {
        n.normalize();
        if (v_cam.dot(n) < 0) v_cam -= 1.5 * v_cam.dot(n) * n;  // restitution 0.5
      } else {
        v_cam = -v_cam;
      }
      next = s.cam + v_cam * kSimDt;
      next.z() = std::clamp(next.z(), h_lo, h_hi);
      if (!space.hasClearance(next, clear)) {  // still blocked: stay and lose the speed
        next = s.cam;
        v_cam *= 0.5;
      }
    }
    s.cam = next;

    // look-at body
    if (forward) {
      // the view's yaw follows the heading through a critically damped angular spring, so a
      // bounce turns the view around smoothly instead of pulling the look-at point through
      // the camera; a little random force keeps it from being rigid
      const double want = std::atan2(heading.y(), heading.x());
      const double err = std::remainder(want - yaw, 2.0 * M_PI);
      yaw_rate += (kp * err - kd * yaw_rate + 0.5 * target_force.value.x()) * kSimDt;
      // a person turns at most ~2 rad/s at w_mult 1 (a bounce off a wall would otherwise
      // swing the view around at over 9 rad/s)
      yaw_rate = std::clamp(yaw_rate, -kMaxYawRate * out.w_mult, kMaxYawRate * out.w_mult);
      yaw += yaw_rate * kSimDt;
      pitch += (-2.0 * (pitch + 0.15) + 0.3 * target_force.value.z()) * kSimDt;
      pitch = std::clamp(pitch, -0.6, 0.3);
      s.target = s.cam + look_dist * Vec3(std::cos(yaw) * std::cos(pitch),
                                          std::sin(yaw) * std::cos(pitch), std::sin(pitch));
    } else {
      Vec3 at = target_force.value - kDrag * v_target;
      Vec3 rel = s.target - s.cam;
      Vec3 rel_h(rel.x(), rel.y(), 0);
      const double dist_h = rel_h.norm();
      // keep the look-at point 0.8-2.5 m away horizontally, so the view never points straight
      // up or down, and 0.3-2.5 m above the floor
      if (dist_h < 0.8 && dist_h > 1e-9) at += 6.0 * (0.8 - dist_h) * rel_h / dist_h;
      if (dist_h > 2.5) at -= 6.0 * (dist_h - 2.5) * rel_h / dist_h;
      // hand-held: a firm spring keeps the look-at point 0.3 m below the camera or lower, so
      // the hard limit below is a last resort (a clamp stops the view's vertical turns dead)
      const bool below = opt.type == MotionType::HandHeld;
      const double z_hi = below ? s.cam.z() - 0.3 : look_top;
      if (s.target.z() > z_hi) at.z() -= (below ? 30.0 : 6.0) * (s.target.z() - z_hi);
      if (s.target.z() < floor_z + 0.3) at.z() += 6.0 * (floor_z + 0.3 - s.target.z());
      // an open scene: a view that would stare past a missing wall into the void is turned
      // back towards the middle of the scene
      // and, weakly, every view of an open scene is drawn to its middle, where its content is
      // (a Cornell box seen from inside: the boxes, not a wall at arm's length)
      if (space.isOpen()) {
        // towards the middle, and to 0.4 m under the camera (a view some 15 degrees down, as
        // a hand-held camera looks at a room: a bare wall seen level fills the whole view, as
        // in SceneNet's kitchen2, whose view stared at one for 1.5 s with 0.2 m)
        Vec3 back = space.indoorCentre() - s.target;
        back.z() = s.cam.z() - 0.4 - s.target.z();
        at += (space.seesGeometry(s.cam, s.target - s.cam, 15.0) ? 1.0 : 6.0) * back;
      }
      v_target += at * kSimDt;
      // the look-at body is carried along with the camera in part (kCarry), so the view's turn
      // rate comes mostly from its own motion (w_mult) rather than from the camera's (v_mult)
      // (the look-at point may pass into geometry: it only aims the camera, and stopping it at
      // walls would turn the view with the camera's speed)
      s.target += (v_target + kCarry * v_cam) * kSimDt;
      if (opt.type == MotionType::HandHeld && s.target.z() > s.cam.z() - 0.05) {
        s.target.z() = s.cam.z() - 0.05;  // hard limit: the look-at point stays below the camera
        v_target.z() = std::min(0.0, v_target.z());
      }
    }
    lean_rate += (kLeanOmega * kLeanOmega * (Vec3(tilt.value.x(), tilt.value.y(), 0) - lean) -
                  2.0 * kLeanOmega * lean_rate) *
                 kSimDt;
    lean += lean_rate * kSimDt;
    if (lean.norm() > max_tilt) {  // rarely reached (sigma is max / 2.5): stop at the limit
      lean *= max_tilt / lean.norm();
      lean_rate -= lean_rate.dot(lean.normalized()) * lean.normalized();
    }
    s.up = Vec3(std::tan(lean.x()), std::tan(lean.y()), 1.0).normalized();
  };

  for (int i = 0; i < static_cast<int>(kWarmup / kSimDt); ++i) step();
  // and on, 0.1 s at a time for up to kMaxSettle, until the view is not a wall at arm's length
  // (a mean free line of sight of 1.5 m or more, openness above): the warm-up forgets the open
  // first view, and a sequence that opens on a blank wall is no good to look at nor to
  // initialise a SLAM system on
  // (not hand-held, whose view is down at the floor and tables by design)
  const int settle = opt.type == MotionType::HandHeld ? 0 : static_cast<int>(kMaxSettle / 0.1);
  for (int k = 0; k < settle; ++k) {
    const Vec3 view = s.target - s.cam;
    if (openness(s.cam, std::atan2(view.y(), view.x())) >= 0.3) break;
    for (int i = 0; i < static_cast<int>(0.1 / kSimDt); ++i) step();
  }

  // ---- record: sim states at every step over the span the samples need ----
  const TimeNs last_ns = static_cast<TimeNs>(std::llround((opt.frames - 1) * 1e9 / opt.fps)) +
                         static_cast<TimeNs>(std::llround(opt.exposure_s * 1e9));
  const size_t steps = static_cast<size_t>(std::ceil(last_ns * 1e-9 / kSimDt)) + 2;
  std::vector<State> states;
  states.reserve(steps);
  states.push_back(s);
  while (states.size() < steps) {
    step();
    states.push_back(s);
  }
  auto stateAt = [&](TimeNs t_ns) {
    double x = t_ns * 1e-9 / kSimDt;
    size_t i = std::min(states.size() - 2, static_cast<size_t>(x));
    return lerp(states[i], states[i + 1], x - static_cast<double>(i));
  };
  auto poseAt = [&](TimeNs t_ns) {
    State st = stateAt(t_ns);
    return TimedPose{t_ns, Pose::lookAt(st.cam, st.target, st.up)};
  };
  for (int k = 0; k < opt.frames; ++k) {
    const TimeNs t = static_cast<TimeNs>(std::llround(k * 1e9 / opt.fps));
    out.frames.poses.push_back(poseAt(t));
    out.shutter_close.poses.push_back(
        poseAt(t + static_cast<TimeNs>(std::llround(opt.exposure_s * 1e9))));
    out.tilt_deg.push_back(std::acos(std::clamp(stateAt(t).up.z(), -1.0, 1.0)) * 180.0 / M_PI);
  }
  for (int64_t i = 0;; ++i) {
    const TimeNs t = static_cast<TimeNs>(std::llround(i * 1e9 / opt.dense_rate));
    if (t > last_ns) break;
    out.dense.poses.push_back(poseAt(t));
  }
  if (opt.learned_style) {
    out.dense = applyStyle(out.dense, builtinStyleModel(), opt.seed, [&](const Vec3& p) {
      return p.z() >= h_lo && p.z() <= h_hi && space.hasClearance(p, clear);
    });
    for (auto* poses : {&out.frames, &out.shutter_close})
      for (TimedPose& p : poses->poses) p.T_world_camera = out.dense.poseAt(p.t_ns);
  }
  return out;
}

}  // namespace inet
