// The event camera on rendered frames (issue 6 acceptance): the events of a real rendered
// sequence reconstruct its last log intensity within one threshold at 95 % of pixels; the event
// count over the same path does not depend on the speed (so the rate scales with it); events
// are in time order; steps follow the image speed.
#include "sensors/event_camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "event_camera_util.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "trajectory/builtin_trajectory.h"

namespace inet {
namespace {

using test::EventRun;
using test::simulate;
using test::smallCamera;

TEST(EventCamera, EventsReconstructTheLastRenderedLogIntensity) {
  const Renderer r(makeDefaultScene());
  const EventCameraOptions opt = smallCamera();
  const EventRun run = simulate(r, 1.0, opt);
  ASSERT_GT(run.events.size(), 1000u);
  EXPECT_EQ(run.stats.events, run.events.size());
  EXPECT_TRUE(std::is_sorted(run.events.begin(), run.events.end(),
                             [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; }));
  EXPECT_GE(run.events.front().t_ns, run.times.front());
  EXPECT_LE(run.events.back().t_ns, run.times.back());
  const ImageF rec =
      reconstructLogIntensity(run.events, run.first_log, opt.sim.c_pos, opt.sim.c_neg);
  size_t within = 0;
  for (size_t i = 0; i < rec.data.size(); ++i)
    within += std::abs(rec.data[i] - run.last_log.data[i]) <= opt.sim.c_pos;
  const double frac = static_cast<double>(within) / rec.data.size();
  RecordProperty("within_one_threshold", std::to_string(frac));
  // measured 0.954 with these defaults (0.930 at 4 spp: Monte Carlo error adds events, and each
  // event adds its threshold's noise to the reconstruction)
  EXPECT_GE(frac, 0.95);
  EXPECT_LE(run.stats.max_dt_s, 1.0 / opt.min_rate_hz + 1e-9);
}

TEST(EventCamera, WithoutThresholdNoiseTheReconstructionIsExact) {
  // the simulator's invariant on rendered input: |L - L_ref| < C everywhere, and L_ref is what
  // the events add up to
  const Renderer r(makeDefaultScene());
  EventCameraOptions opt = smallCamera();
  opt.sim.sigma_c = 0;
  const EventRun run = simulate(r, 1.0, opt);
  const ImageF rec =
      reconstructLogIntensity(run.events, run.first_log, opt.sim.c_pos, opt.sim.c_neg);
  for (size_t i = 0; i < rec.data.size(); ++i)
    ASSERT_LT(std::abs(rec.data[i] - run.last_log.data[i]), opt.sim.c_pos + 1e-4) << "pixel " << i;
}

TEST(EventCamera, EventCountFollowsThePathNotTheSpeed) {
  const Renderer r(makeDefaultScene());
  const EventCameraOptions opt = smallCamera();
  const EventRun fast = simulate(r, 1.0, opt), slow = simulate(r, 2.0, opt);
  const double n_fast = static_cast<double>(fast.events.size());
  const double n_slow = static_cast<double>(slow.events.size());
  RecordProperty("events_fast", std::to_string(n_fast));
  RecordProperty("events_slow", std::to_string(n_slow));
  // same path: about the same events (threshold noise and sampling differ; the slower camera
  // takes more samples per metre, and each adds a little Monte Carlo change); so the event rate
  // doubles with the speed
  EXPECT_NEAR(n_slow / n_fast, 1.0, 0.15);
  const double rate_fast = n_fast / 0.4, rate_slow = n_slow / 0.8;
  EXPECT_NEAR(rate_fast / rate_slow, 2.0, 0.3);
  // and the slower camera is sampled about half as often per second
  const double hz_fast = fast.stats.samples / 0.4, hz_slow = slow.stats.samples / 0.8;
  EXPECT_NEAR(hz_fast / hz_slow, 2.0, 0.4);
}

TEST(EventCamera, StillCameraGivesNoEvents) {
  const Renderer r(makeDefaultScene());
  Trajectory traj = builtinTrajectory(1, 25.0);
  const Pose p = traj.poses[0].T_world_camera;
  traj.poses.clear();
  for (int k = 0; k < 8; ++k) traj.poses.push_back({k * 40'000'000LL, p});
  const PoseSpline spline = PoseSpline::fit(traj);
  EventCameraOptions opt = smallCamera();
  CameraIntrinsics K;
  size_t events = 0, samples = 0;
  simulateEventCamera(r, eventIntrinsics(K, opt.width, opt.height), spline, spline.startNs(),
                      spline.endNs(), 0, opt,
                      [&](int64_t, const ImageF&, const std::vector<Event>& ev) {
                        events += ev.size();
                        ++samples;
                      });
  EXPECT_EQ(events, 0u) << "the same random numbers at every step: a still image stays still";
  EXPECT_GE(samples, 2u);
}

}  // namespace
}  // namespace inet
