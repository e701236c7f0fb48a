// interiornet trajectory generate | convert | show: camera paths without rendering.
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "common.h"
#include "core/error.h"
#include "core/plot.h"
#include "trajectory/formats.h"
#include "trajectory/free_space.h"
#include "trajectory/random_trajectory.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct TrajectoryGenerateArgs {
  SceneSource scene;
  MotionSettings motion;
  std::string type = "two-body";
  int frames = 250;
  double fps = 25.0;
  uint64_t seed = 0;
  std::string format;
  std::string out;
  std::string dense;
  std::string plot;
  TrajectoryFormatOptions format_options;
};

/// The layout's scene for a trajectory: the given layout, or the built-in apartment.
Scene trajectoryScene(const SceneSource& args) {
  return args.isDefault() ? defaultApartment() : args.loadScene();
}

TrajectoryFormat formatFor(const std::string& format, const std::string& path,
                           const std::string& flag) {
  if (!format.empty()) return parseTrajectoryFormat(format, "--format");
  if (auto f = trajectoryFormatFromExtension(path)) return *f;
  throw InputError(path, flag,
                   "cannot tell the format from the name (.txt tum, .csv euroc, .freiburg icl, "
                   ".log scenenet); give --format");
}

/// Top-down view (room outlines, obstacles at camera height, the path with view directions),
/// height over time and speed over time, side by side.
void plotTrajectory(const fs::path& png, const Trajectory& traj, const Scene* scene,
                    const FreeSpace* space, const std::string& title) {
  std::vector<Series> top;
  if (space != nullptr) {
    // obstacles at 1.5 m: grid cells a surface passes through (the exact distance, so the plot
    // shows the geometry itself, not the grid's conservative band round it nor the faces of an
    // open scene's grid)
    Series wall{"obstacles at 1.5 m", {}, {}, Rgb{150, 150, 150}, Series::Style::Points};
    wall.point_radius_px = 0.8;
    const double z = 1.5, v = space->voxel();
    for (double y = space->origin().y(); y < space->origin().y() + v * space->ny(); y += v)
      for (double x = space->origin().x(); x < space->origin().x() + v * space->nx(); x += v)
        if (space->exactDistance({x, y, z}) < 0.5 * v) wall.x.push_back(x), wall.y.push_back(y);
    top.push_back(std::move(wall));
  }
  if (scene != nullptr)
    for (size_t r = 0; r < scene->rooms.size(); ++r) {
      Series room{r == 0 ? "rooms" : "", {}, {}, Rgb{60, 60, 60}, Series::Style::Line};
      room.line_width_px = 1.0;
      for (size_t i = 0; i <= scene->rooms[r].outline.size(); ++i) {
        const auto& p = scene->rooms[r].outline[i % scene->rooms[r].outline.size()];
        room.x.push_back(p.x());
        room.y.push_back(p.y());
      }
      top.push_back(std::move(room));
    }
  Series path{"camera", {}, {}, paletteColour(0), Series::Style::Line};
  Series view{"view (1 s)", {}, {}, paletteColour(3), Series::Style::Line};
  Series start{"start", {}, {}, paletteColour(2), Series::Style::Points};
  start.point_radius_px = 5;
  std::vector<double> t, height, speed;
  const double t0 = traj.poses.front().t_ns * 1e-9;
  TimeNs next_view = traj.poses.front().t_ns;
  for (size_t k = 0; k < traj.size(); ++k) {
    const Pose& T = traj.poses[k].T_world_camera;
    path.x.push_back(T.t.x());
    path.y.push_back(T.t.y());
    if (traj.poses[k].t_ns >= next_view) {  // a short line along the view every second
      Vec3 f = T.rotation().col(2);
      Vec3 tip = T.t + 0.4 * Vec3(f.x(), f.y(), 0);
      view.x.insert(view.x.end(), {T.t.x(), tip.x(), std::nan("")});
      view.y.insert(view.y.end(), {T.t.y(), tip.y(), std::nan("")});
      next_view += 1'000'000'000;
    }
    t.push_back(traj.poses[k].t_ns * 1e-9 - t0);
    height.push_back(T.t.z());
    speed.push_back(traj.velocityWorld(k).norm());
  }
  start.x = {path.x.front()};
  start.y = {path.y.front()};
  top.push_back(std::move(path));
  top.push_back(std::move(view));
  top.push_back(std::move(start));

  auto panel = [](std::string panel_title, std::string x, std::string y, int width) {
    LinePlot p;
    p.spec.title = std::move(panel_title);
    p.spec.x_label = std::move(x);
    p.spec.y_label = std::move(y);
    p.spec.width = width;
    p.spec.height = 700;
    return p;
  };
  LinePlot plan = panel(title, "x (m)", "y (m)", 900);
  plan.spec.equal_aspect = true;
  plan.series = std::move(top);
  LinePlot h = panel("height", "time (s)", "z (m)", 450);
  h.spec.legend = false;
  h.series.push_back(Series{"", t, height, {}, Series::Style::Line});
  LinePlot v = panel("speed", "time (s)", "m/s", 450);
  v.spec.legend = false;
  v.series.push_back(Series{"", t, speed, {}, Series::Style::Line});
  writeLinePlotRowPng(png, {plan, h, v});
}

void runGenerate(const TrajectoryGenerateArgs& a) {
  const MotionType type = parseMotionType(a.type, "--type");
  if (a.frames < 1 || a.frames > 10'000'000) throw InputError("", "--frames", "must be >= 1");
  if (!(a.fps > 0 && a.fps <= 10000)) throw InputError("", "--fps", "must be in (0, 10000]");
  const TrajectoryFormat fmt = formatFor(a.format, a.out, "--out");
  RandomTrajectoryOptions opt = a.motion.options(type, a.seed, a.frames, a.fps);
  const Scene scene = trajectoryScene(a.scene);
  const std::string source = a.scene.isDefault() ? "built-in apartment" : a.scene.path;
  FreeSpace space(scene, {}, source);
  RandomTrajectory traj = generateRandomTrajectory(space, opt, source);
  writeTrajectory(a.out, traj.frames, fmt, a.format_options);
  if (!a.dense.empty())
    writeTrajectory(a.dense, traj.dense, formatFor(a.format, a.dense, "--dense"),
                    a.format_options);
  if (!a.plot.empty())
    plotTrajectory(a.plot, traj.frames, &scene, &space,
                   fmt::format("{}{} trajectory, v_mult {:.2f}, w_mult {:.2f}, seed {}",
                               motionTypeName(type), opt.learned_style ? " styled" : "",
                               traj.v_mult, traj.w_mult, a.seed));
  std::printf("wrote %zu poses (%s, v_mult %.2f, w_mult %.2f) to %s\n", traj.frames.size(),
              motionTypeName(type), traj.v_mult, traj.w_mult, a.out.c_str());
}

}  // namespace

void registerTrajectory(CLI::App& app) {
  auto* trajectory =
      app.add_subcommand("trajectory", "Generate, convert and show camera trajectories");
  trajectory->require_subcommand(1);

  auto* gen = trajectory->add_subcommand(
      "generate",
      "A random camera trajectory through a layout's free space (the paper's base types: "
      "two-body, hand-held, look-forward), heights 1-2 m, up vector within 5 degrees of "
      "gravity, never closer than --clearance to any geometry. World Z up, floor at z = 0, "
      "camera axes as OpenCV");
  auto a = std::make_shared<TrajectoryGenerateArgs>();
  addSceneFlags(*gen, a->scene);
  addMotionFlags(*gen, a->motion);
  gen->add_option("--type", a->type, "two-body, hand-held or look-forward (default two-body)");
  gen->add_option("--frames", a->frames, "number of poses (default 250)");
  gen->add_option("--fps", a->fps, "pose rate (default 25)");
  gen->add_option("--seed", a->seed, "random seed; same seed, same trajectory (default 0)");
  gen->add_option("--format", a->format,
                  "tum, euroc, icl, slambench or scenenet (default: from --out's extension)");
  gen->add_option("--icl-fps", a->format_options.icl_fps,
                  "frame rate that ICL-NUIM frame numbers count at (default 30)");
  gen->add_option("--out", a->out, "trajectory file to write")->required();
  gen->add_option("--dense", a->dense,
                  "also write the 200 Hz samples the sensors (IMU) use, to this file");
  gen->add_option("--plot", a->plot, "also draw the path (top-down, height, speed) as a PNG");
  gen->callback([a] { runGenerate(*a); });

  addTrajectoryConvertCommand(trajectory);

  // train-style runs in interiornet-train-style (LibTorch), next to this binary: every argument
  // after the subcommand, --help included, goes to it unparsed
  auto* train = trajectory->add_subcommand(
      "train-style",
      "Train the learned hand-held style model with LibTorch (runs interiornet-train-style; "
      "'interiornet trajectory train-style --help' lists its options)");
  train->prefix_command();
  train->set_help_flag();
  train->callback(
      [train] { execCompanion("interiornet-train-style", "train-style", train->remaining()); });

  auto* show = trajectory->add_subcommand(
      "show", "Draw a trajectory file (top-down over the layout, height and speed) as a PNG");
  auto s = std::make_shared<std::pair<std::string, std::string>>();
  auto scene = std::make_shared<SceneSource>();
  show->add_option("TRAJECTORY", s->first, "trajectory file (tum, euroc, icl, slambench, scenenet, scenenet_v1, kitti)")
      ->required();
  addSceneFlags(*show, *scene, "no scene drawn, only the path");
  show->add_option("--out", s->second, "PNG to write")->required();
  show->callback([s, scene] {
    Trajectory traj = readTrajectoryFile(s->first);
    if (scene->isDefault()) {
      plotTrajectory(s->second, traj, nullptr, nullptr, fs::path(s->first).filename().string());
    } else {
      Scene sc = scene->loadScene();
      FreeSpace space(sc, {}, scene->path);
      plotTrajectory(s->second, traj, &sc, &space, fs::path(s->first).filename().string());
    }
    std::printf("wrote %s\n", s->second.c_str());
  });
}

}  // namespace inet::app
