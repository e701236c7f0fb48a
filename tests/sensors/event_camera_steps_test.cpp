// The event camera's time steps on rendered frames (slow: a few hundred renders at up to 256 spp):
// how much finer steps change the events, and why.
#include "sensors/event_camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/renderer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"

namespace inet {
namespace {

struct EventRun {
  std::vector<Event> events;
  ImageF first_log, last_log;
  std::vector<int64_t> times;
  EventRunStats stats;
};

/// The built-in room's orbit, `slow` times slower, from 0.1 s to 0.5 s of the original.
EventRun simulate(const Renderer& r, double slow, const EventCameraOptions& opt) {
  Trajectory traj = builtinTrajectory(16, 25.0);
  for (auto& p : traj.poses) p.t_ns = static_cast<TimeNs>(std::llround(p.t_ns * slow));
  SplineFitOptions fit;
  fit.knot_spacing_ns = traj.poses[1].t_ns - traj.poses[0].t_ns;  // through every pose
  const PoseSpline spline = PoseSpline::fit(traj, fit);
  CameraIntrinsics K;
  K.width = 640;
  K.height = 480;
  K.fx = K.fy = 320;  // 90 degrees
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

/// The defaults (16 spp, ESIM's threshold noise 0.021) at 64 x 48; at least 10 samples per
/// second, so that the image speed sets the steps (at this size it moves slowly).
EventCameraOptions smallCamera() {
  EventCameraOptions opt;
  opt.width = 120;
  opt.height = 90;
  opt.min_rate_hz = 10;
  return opt;
}

// How the time step matters. Sampling more often gives more events, and the excess is Monte
// Carlo error: each new sample brings a little new path-tracing noise, a random walk that
// crosses thresholds more often the more samples there are. Measured at 64x48 with 8x as many
// samples (0.0625 px of image motion per step instead of 0.5): +18.5 % at 16 spp, +7.7 % at 64,
// +4.6 % at 256. Here with 4x (0.125 px): the excess must fall with the samples per pixel.
TEST(EventCamera, StepDependenceIsMonteCarloErrorAndFallsWithSamples) {
  const Renderer r(makeDefaultScene());
  EventCameraOptions opt = smallCamera();
  opt.width = 64;
  opt.height = 48;
  opt.min_rate_hz = 100;
  std::vector<double> excess;
  for (int spp : {16, 256}) {
    opt.spp = spp;
    opt.lambda_flow = 0.5;
    const EventRun coarse = simulate(r, 1.0, opt);
    opt.lambda_flow = 0.125;
    const EventRun fine = simulate(r, 1.0, opt);
    EXPECT_GT(fine.stats.samples, 3 * coarse.stats.samples / 2);  // 78 vs 41 (10 ms floor)
    excess.push_back(static_cast<double>(fine.events.size()) / coarse.events.size() - 1);
    RecordProperty("excess_spp" + std::to_string(spp), std::to_string(excess.back()));
  }
  EXPECT_LT(excess[1], excess[0] / 2);
  EXPECT_LT(excess[1], 0.06);
  EXPECT_GT(excess[1], -0.06);
}

}  // namespace
}  // namespace inet
