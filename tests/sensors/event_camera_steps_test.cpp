// The event camera's time steps on rendered frames (slow: a few hundred renders at up to 256 spp):
// how much finer steps change the events, and why.
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
