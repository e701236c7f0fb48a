#include "sensors/event_camera.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "render/renderer.h"
#include "sensors/optical_flow.h"

namespace inet {
namespace {

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

void EventCameraOptions::validate(const std::string& source) const {
  if (width < 1 || width > 65535) throw InputError(source, "--event-width", "must be in 1..65535");
  if (height < 1 || height > 65535)
    throw InputError(source, "--event-height", "must be in 1..65535");
  if (spp < 1 || spp > 1 << 16) throw InputError(source, "--event-spp", "must be in 1..65536");
  if (max_bounces < 0 || max_bounces > 1000)
    throw InputError(source, "--event-max-bounces", "must be in 0..1000");
  if (!(exposure > 0 && std::isfinite(exposure)))
    throw InputError(source, "--event-exposure", "must be > 0");
  if (!(lambda_flow > 0 && lambda_flow <= 100))
    throw InputError(source, "--adaptive-lambda", "must be in (0, 100] px");
  if (!(lambda_brightness > 0 && lambda_brightness <= 10))
    throw InputError(source, "--adaptive-lambda-brightness", "must be in (0, 10]");
  if (min_dt_ns < 1000) throw InputError(source, "--min-dt-ns", "must be >= 1000 ns (1 MHz)");
  if (!(min_rate_hz > 0 && min_rate_hz <= 1e6))
    throw InputError(source, "--min-rate-hz", "must be in (0, 1e6]");
  if (1e9 / min_rate_hz < static_cast<double>(min_dt_ns))
    throw InputError(source, "--min-rate-hz",
                     fmt::format("1 / {} Hz is shorter than --min-dt-ns {}", min_rate_hz,
                                 min_dt_ns));
  sim.validate(source);
}

CameraIntrinsics eventIntrinsics(const CameraIntrinsics& K, int width, int height) {
  // the same horizontal field of view, square pixels
  return CameraIntrinsics::centred(width, height, K.fx * width / K.width);
}

EventRunStats simulateEventCamera(const Renderer& renderer, const CameraIntrinsics& K,
                                  const PoseSpline& spline, int64_t t_begin_ns, int64_t t_end_ns,
                                  int64_t scene_t0_ns, const EventCameraOptions& opt,
                                  const EventSampleSink& sink,
                                  const std::function<void(double)>& progress) {
  opt.validate();
  INET_CHECK(K.width == opt.width && K.height == opt.height);
  INET_CHECK(t_begin_ns >= spline.startNs() && t_end_ns <= spline.endNs() && t_end_ns > t_begin_ns);
  const auto start = std::chrono::steady_clock::now();
  const LensModel lens = LensModel::pinhole(K);
  RenderOptions ro;
  ro.spp = opt.spp;
  ro.max_bounces = opt.max_bounces;
  ro.seed = opt.seed;
  ro.denoise = opt.denoise;
  ro.passes = passMask(Pass::Rgb, Pass::DepthZ);
  AdaptiveSamplingOptions flow_mode, bright_mode;
  flow_mode.mode = AdaptiveSamplingOptions::Mode::Flow;
  flow_mode.lambda = opt.lambda_flow;
  bright_mode.mode = AdaptiveSamplingOptions::Mode::Brightness;
  bright_mode.lambda = opt.lambda_brightness;
  for (auto* m : {&flow_mode, &bright_mode}) {
    m->min_dt_ns = opt.min_dt_ns;
    m->min_rate_hz = opt.min_rate_hz;
  }

  // the brightness criterion only where the flow of the camera motion does not predict the
  // change: a scene with moving objects
  const bool brightness = opt.brightness_criterion;
  EventSimulator sim(opt.width, opt.height, opt.sim);
  EventRunStats stats;
  stats.min_dt_s = 1e300;
  Frame frame;
  ImageF L_prev;
  std::vector<Event> events;
  int64_t t = t_begin_ns, t_prev = t_begin_ns;
  double render_s = 0;
  for (;;) {
    const SplineState s = spline.evaluate(t);
    Pose T_wc;
    T_wc.q = s.q_world_body;
    T_wc.t = s.p_world;
    const auto r0 = std::chrono::steady_clock::now();
    // frame index 0 every time: the same random numbers at every step (header comment)
    renderer.render(lens, CameraExposure::fixed(T_wc, t - scene_t0_ns), ro, 0, frame);
    render_s += seconds(std::chrono::steady_clock::now() - r0);
    const ImageF intensity = luminanceImage(frame.rgb, opt.exposure);
    ImageF L = logIntensityImage(intensity, opt.sim.log_eps);
    events.clear();
    stats.events += sim.addSample(t, L, events, "event camera");
    ++stats.samples;
    sink(t, intensity, events);
    if (progress) progress(static_cast<double>(t - t_begin_ns) / (t_end_ns - t_begin_ns));
    if (t >= t_end_ns) break;
    // the next step: the smaller of the flow and brightness criteria
    const double flow_speed = maxFlowSpeed(frame.depth_z, K, cameraVelocity(s));
    int64_t dt = nextSampleInterval(flow_speed, flow_mode);
    if (brightness && !L_prev.empty() && t > t_prev)
      dt = std::min(dt, nextSampleInterval(logIntensityRate(L_prev, t_prev, L, t, 0.99),
                                           bright_mode));
    L_prev = std::move(L);
    t_prev = t;
    dt = std::max<int64_t>(dt, 1);
    const int64_t next = std::min(t + dt, t_end_ns);
    stats.min_dt_s = std::min(stats.min_dt_s, (next - t) * 1e-9);
    stats.max_dt_s = std::max(stats.max_dt_s, (next - t) * 1e-9);
    t = next;
  }
  if (stats.samples < 2) stats.min_dt_s = 0;
  stats.render_s = render_s;
  stats.wall_s = seconds(std::chrono::steady_clock::now() - start);
  return stats;
}

}  // namespace inet
