// interiornet events: the event camera alone, along a camera trajectory file through a scene;
// the same events0/ folder `generate --passes events` writes (pipeline/sensor_outputs.h).
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "common.h"
#include "core/error.h"
#include "render/renderer.h"
#include "pipeline/sensor_outputs.h"
#include "dataset/sequence_writer.h"
#include "trajectory/formats.h"

namespace inet::app {
namespace {

struct EventsCliArgs {
  SceneSource scene;
  std::string trajectory, out;
  EventSettings events;
  double hfov_deg = 90.0;
  double knot_spacing_s = 0.0;
  uint64_t seed = 0;
  bool progress = true;
};

void runEvents(const EventsCliArgs& a) {
  installStopHandlers();
  if (!(a.hfov_deg > 1 && a.hfov_deg < 179))
    throw InputError("", "--hfov", "must be in (1, 179) degrees");
  if (!(a.knot_spacing_s >= 0.0) || a.knot_spacing_s > 10.0)
    throw InputError("", "--knot-spacing", "must be in [0, 10] s (0 = automatic)");
  const EventCameraOptions opt = a.events.options(a.seed);
  // everything is read and checked before the first file is written
  const Trajectory traj = readTrajectoryFile(a.trajectory);
  SplineFitOptions fit;
  fit.knot_spacing_ns = static_cast<TimeNs>(a.knot_spacing_s * 1e9 + 0.5);
  const PoseSpline spline = PoseSpline::fit(traj, fit, nullptr, a.trajectory);
  const Scene scene = a.scene.load();
  checkOutputFolder(a.out);
  // the event camera's field of view through a cam0 of its own size
  const CameraIntrinsics K = CameraIntrinsics::centred(
      opt.width, opt.height, opt.width / 2.0 / std::tan(a.hfov_deg * M_PI / 360.0));
  if (!EventsFolder::complete(a.out)) {  // a finished folder is not redone
    Renderer renderer(scene);
    const CameraIntrinsics K_events = eventIntrinsics(K, opt.width, opt.height);
    EventsFolder folder(a.out, traj.poses.front().t_ns, K_events);
    simulateEvents(folder, renderer, scene, K_events, spline, spline.startNs(), spline.endNs(),
                   traj.poses.front().t_ns, opt, a.progress, a.out);
  }
  fmt::print("wrote {}/events0/ ({:.3f} s of events)\n", a.out,
             static_cast<double>(spline.endNs() - spline.startNs()) * 1e-9);
}

}  // namespace

void registerEvents(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "events",
      "Simulate an event camera (ESIM model: log-intensity contrast thresholds, interpolated "
      "timestamps) along a camera trajectory file through a scene: path-traced intensity at an "
      "adaptive rate along the trajectory's B-spline; writes OUT/events0/{events.txt (t x y p), "
      "events.h5 (DSEC), frames/, sensor.yaml}. A finished folder is not redone");
  auto a = std::make_shared<EventsCliArgs>();
  addSceneFlags(*cmd, a->scene);
  cmd->add_option("--trajectory", a->trajectory,
                  "camera trajectory file (tum, euroc, icl, ...; T_world_camera, OpenCV axes)")
      ->required();
  addEventFlags(*cmd, a->events);
  cmd->add_option("--hfov", a->hfov_deg, "horizontal field of view in degrees (default 90)");
  cmd->add_option("--knot-spacing", a->knot_spacing_s,
                  "spline knot spacing in s; default 0 = the input's mean spacing but at least "
                  "0.05 s (as interiornet imu)");
  cmd->add_option("--seed", a->seed, "seed of rendering and threshold noise (default 0)");
  cmd->add_option("--out", a->out, "output folder (events0/ is written inside)")->required();
  cmd->add_flag("--no-progress{false}", a->progress, "do not draw the progress bar");
  cmd->callback([a] { runEvents(*a); });
}

}  // namespace inet::app
