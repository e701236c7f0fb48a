#include "pipeline/sensor_outputs.h"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "core/stop.h"
#include "render/renderer.h"
#include "sensors/optical_flow.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

}  // namespace

SequencePasses parseSequencePasses(const std::string& list, LensType lens, bool rolling_shutter) {
  const bool pinhole = lens == LensType::Pinhole;
  const bool events_ok = lens == LensType::Pinhole || lens == LensType::ThinLens;
  SequencePasses out;
  std::vector<std::string> frame_names;
  bool everything = false, standard = false;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    if (item == "all") {
      everything = true;
    } else if (item == "default") {
      standard = true;
    } else if (item == "imu") {
      out.imu = out.imu_by_name = true;
    } else if (item == "boxes") {
      out.boxes = true;
    } else if (item == "events") {
      if (!events_ok)
        throw InputError("", "--passes",
                         "events need a pinhole or thin lens (the event camera is a pinhole "
                         "with cam0's field of view)");
      out.events = true;
    } else {
      frame_names.push_back(item);
    }
  }
  if (everything || standard) {
    out.frame = kAllPasses;
    if (!pinhole) out.frame &= ~kPinholeOnlyPasses;
    if (rolling_shutter) out.frame &= ~kGlobalShutterOnlyPasses;
    out.imu = out.boxes = true;
    out.events |= everything && events_ok;
  }
  if (!frame_names.empty()) {
    std::string joined;
    for (const auto& n : frame_names) joined += (joined.empty() ? "" : ",") + n;
    try {
      out.frame |= parsePassList(joined, "");
    } catch (const InputError& e) {
      throw InputError("", "--passes",
                       e.problem() + "; also: imu, events, boxes, default (all but events)");
    }
    if ((out.frame & kPinholeOnlyPasses) && !pinhole)
      throw InputError("", "--passes",
                       "depth_noisy needs --lens pinhole (the Kinect model is a pinhole "
                       "projector and camera)");
    if ((out.frame & kGlobalShutterOnlyPasses) && rolling_shutter)
      throw InputError("", "--passes",
                       "flow with a rolling shutter (--readout-ms) is not supported: the rows of "
                       "a frame see different poses");
  }
  if (out.frame == 0)
    throw InputError("", "--passes",
                     "select at least one frame pass (rgb, depth, ...): imu, events and boxes "
                     "go with frames (for them alone: interiornet imu, interiornet events)");
  return out;
}

EventCameraOptions EventSettings::options(uint64_t seed) const {
  EventCameraOptions o = opt;
  // --contrast sets both thresholds; the simulator checks them under its own names, which are
  // the flags --contrast-pos and --contrast-neg (as all its fields are flags here)
  if (!(contrast >= kMinContrastThreshold && contrast <= 10))
    throw InputError("", "--contrast", fmt::format("must be in [{}, 10]", kMinContrastThreshold));
  o.sim.c_pos = std::isnan(contrast_pos) ? contrast : contrast_pos;
  o.sim.c_neg = std::isnan(contrast_neg) ? contrast : contrast_neg;
  if (!(refractory_ms >= 0 && refractory_ms <= 1000))
    throw InputError("", "--refractory-ms", "must be in 0..1000");
  o.sim.refractory_ns = static_cast<int64_t>(std::llround(refractory_ms * 1e6));
  o.seed = seed;
  o.sim.seed = seed;
  o.lambda_brightness = std::min(o.lambda_brightness, std::min(o.sim.c_pos, o.sim.c_neg) / 2);
  o.validate();
  return o;
}

PassMask renderPassesFor(PassMask passes, LensType lens, bool boxes) {
  PassMask r = (passes & kRenderPasses) |
               neededForDerived(passes, groundTruthDepthKind(lens) == DepthKind::ZDepth);
  if (boxes) r |= bit(Pass::Instance);
  return r;
}

namespace {

/// Flow between `frame` (at `self`) and a ground-truth render at `other`: forward when `other` is
/// the next frame, backward when it is the previous one.
FlowField flowTowards(const Renderer& renderer, const Scene& scene, const LensModel& lens,
                      const NeighbourFrame& self, const NeighbourFrame& other, bool forward,
                      const Frame& frame) {
  FlowOptions fo;
  fo.depth_kind = groundTruthDepthKind(lens.type);
  const bool z = fo.depth_kind == DepthKind::ZDepth;
  RenderOptions ro;  // ground truth only (no rgb): one ray per pixel, objects at that time
  ro.passes = bit(z ? Pass::DepthZ : Pass::DepthRay) | bit(Pass::Instance);
  Frame there;
  renderer.render(lens, CameraExposure::fixed(other.T_world_camera, other.scene_time_ns), ro, 0,
                  there);
  const FlowFrameView here_view{z ? frame.depth_z : frame.depth_ray, frame.instance,
                                self.T_world_camera};
  const FlowFrameView there_view{z ? there.depth_z : there.depth_ray, there.instance,
                                 other.T_world_camera};
  if (forward)
    return forwardFlow(here_view, there_view, lens,
                       objectMotionBetween(scene, self.scene_time_ns * 1e-9,
                                           other.scene_time_ns * 1e-9, scene.name),
                       fo);
  // backwardFlow takes the previous -> this motion table
  return backwardFlow(
      there_view, here_view, lens,
      objectMotionBetween(scene, other.scene_time_ns * 1e-9, self.scene_time_ns * 1e-9, scene.name),
      fo);
}

}  // namespace

void deriveFramePasses(const Renderer& renderer, const Scene& scene, const LensModel& lens,
                       PassMask passes, const KinectNoiseOptions& noise, uint64_t seed,
                       uint32_t noise_frame, const NeighbourFrame& self,
                       const NeighbourFrame* previous, const NeighbourFrame* next, Frame& frame) {
  if (has(passes, Pass::DepthNoisy)) {
    frame.depth_noisy =
        kinectNoisyDepth(frame.depth_z, frame.normal, lens.K, noise, seed, noise_frame);
    frame.passes |= bit(Pass::DepthNoisy);
  }
  if (has(passes, Pass::Flow) && next != nullptr) {
    frame.flow = flowTowards(renderer, scene, lens, self, *next, true, frame);
    frame.passes |= bit(Pass::Flow);
  }
  if (has(passes, Pass::FlowBackward) && previous != nullptr) {
    frame.flow_bwd = flowTowards(renderer, scene, lens, self, *previous, false, frame);
    frame.passes |= bit(Pass::FlowBackward);
  }
}

void simulateEvents(EventsFolder& out, const Renderer& renderer, const Scene& scene,
                    const CameraIntrinsics& K_events, const PoseSpline& spline, TimeNs t_begin_ns,
                    TimeNs t_end_ns, TimeNs scene_t0_ns, const EventCameraOptions& opt,
                    bool progress, const std::string& where) {
  EventCameraOptions o = opt;
  for (const Object& obj : scene.objects) o.brightness_criterion |= obj.moving();
  ProgressBar bar(1000, "permille of event time", progress);
  const EventRunStats stats = simulateEventCamera(
      renderer, K_events, spline, t_begin_ns, t_end_ns, scene_t0_ns, o,
      [&](int64_t t, const ImageF& intensity, const std::vector<Event>& events) {
        out.add(t, intensity, events);
      },
      [&](double f) {
        bar.update(static_cast<int64_t>(f * 1000));
        // events0/ is complete only once finished: a rerun simulates it again
        stopIfSignalled("during the event camera of " + where);
      });
  bar.finish();
  out.finish(opt.sim, stats.samples, stats.events);
  const double sim_s = (t_end_ns - t_begin_ns) * 1e-9;
  std::fprintf(stderr,
               "events: %zu events from %zu samples over %.3f s of simulation (%.0f events/s "
               "simulated) in %.1f s wall (%.1f s rendering); steps %.2f..%.2f ms\n",
               stats.events, stats.samples, sim_s, stats.events / std::max(sim_s, 1e-9),
               stats.wall_s, stats.render_s, stats.min_dt_s * 1e3, stats.max_dt_s * 1e3);
}

}  // namespace inet
