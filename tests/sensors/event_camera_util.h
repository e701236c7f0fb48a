#pragma once
// Shared by the event camera tests: the built-in room's orbit through the event camera.
#include <cmath>
#include <vector>

#include "render/renderer.h"
#include "sensors/event_camera.h"
#include "trajectory/builtin_trajectory.h"

namespace inet::test {

struct EventRun {
  std::vector<Event> events;
  ImageF first_log, last_log;
  std::vector<int64_t> times;
  EventRunStats stats;
};

/// The built-in room's orbit, `slow` times slower, from 0.1 s to 0.5 s of the original.
inline EventRun simulate(const Renderer& r, double slow, const EventCameraOptions& opt) {
  Trajectory traj = builtinTrajectory(16, 25.0);
  for (auto& p : traj.poses) p.t_ns = static_cast<TimeNs>(std::llround(p.t_ns * slow));
  SplineFitOptions fit;
  fit.knot_spacing_ns = traj.poses[1].t_ns - traj.poses[0].t_ns;  // through every pose
  const PoseSpline spline = PoseSpline::fit(traj, fit);
  const CameraIntrinsics K = CameraIntrinsics::centred(640, 480, 320);  // 90 degrees
  const CameraIntrinsics Ke = eventIntrinsics(K, opt.width, opt.height);
  EventRun run;
  const auto t0 = static_cast<int64_t>(0.1e9 * slow), t1 = static_cast<int64_t>(0.5e9 * slow);
  run.stats = simulateEventCamera(
      r, Ke, spline, t0, t1, 0, opt,
      [&](int64_t t, const ImageF& intensity, const std::vector<Event>& ev) {
        const ImageF L = logIntensityImage(intensity, opt.sim.log_eps);
        if (run.times.empty()) run.first_log = L;
        run.last_log = L;
        run.times.push_back(t);
        run.events.insert(run.events.end(), ev.begin(), ev.end());
      });
  return run;
}

/// The defaults (16 spp, ESIM's threshold noise 0.021) at 120 x 90; at least 10 samples per
/// second, so that the image speed sets the steps (at this size it moves slowly).
inline EventCameraOptions smallCamera() {
  EventCameraOptions opt;
  opt.width = 120;
  opt.height = 90;
  opt.min_rate_hz = 10;
  return opt;
}

}  // namespace inet::test
