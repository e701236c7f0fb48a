// interiornet trajectory convert: a trajectory file from one dataset's format to another's
// (tum, euroc, icl, slambench, scenenet, scenenet_v1; frames and conventions in trajectory/formats.h),
// optionally as the right camera of a stereo rig.
//
// Declared for the `trajectory` subcommand (add to common.h and call it there):
//   void addTrajectoryConvertCommand(CLI::App* trajectory_cmd);
#include <cmath>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "common.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "trajectory/formats.h"

namespace inet::app {
namespace {

struct ConvertArgs {
  std::string in;
  std::string out;
  std::string from;
  std::string to;
  TrajectoryFormatOptions format;
  double baseline_m = 0.0;
  CLI::Option* fps_opt = nullptr;
  CLI::Option* baseline_opt = nullptr;
};

/// The output format: --to, else OUT's extension.
TrajectoryFormat outputFormat(const ConvertArgs& a) {
  if (!a.to.empty()) return parseTrajectoryFormat(a.to, "--to");
  if (auto f = trajectoryFormatFromExtension(a.out)) return *f;
  throw InputError(a.out, "--to",
                   "cannot tell the output format from the name (.txt tum, .csv euroc, "
                   ".freiburg icl, .log scenenet); give --to");
}

void runConvert(const ConvertArgs& a) {
  // validate every option before reading
  if (!a.from.empty()) parseTrajectoryFormat(a.from, "--from");
  const TrajectoryFormat to = outputFormat(a);
  if (*a.fps_opt && !(a.format.icl_fps > 0 && std::isfinite(a.format.icl_fps)))
    throw InputError("", "--fps", "must be > 0");
  if (*a.baseline_opt && !std::isfinite(a.baseline_m))
    throw InputError("", "--baseline", "must be a finite number of metres");

  const std::string text = readTextFile(a.in);
  const TrajectoryFormat in_fmt =
      a.from.empty() ? detectTrajectoryFormat(a.in, text) : parseTrajectoryFormat(a.from, "--from");
  const auto timeless = [](TrajectoryFormat f) {
    return f == TrajectoryFormat::Icl || f == TrajectoryFormat::SceneNetV1 ||
           f == TrajectoryFormat::Kitti;
  };
  if (*a.fps_opt && !timeless(in_fmt) && !timeless(to))
    throw InputError("", "--fps",
                     fmt::format("only used by icl, scenenet_v1 and kitti (frame numbers, pose "
                                 "lists), "
                                 "but this converts {} to {}",
                                 trajectoryFormatName(in_fmt), trajectoryFormatName(to)));
  TrajectoryFormatOptions opt = a.format;
  if (*a.fps_opt) opt.pose_list_fps = opt.kitti_fps = opt.icl_fps;
  TrajectoryReadReport report;
  Trajectory traj = parseTrajectory(text, a.in, in_fmt, opt, &report);
  warnTrajectoryRead(a.in, report);
  if (*a.baseline_opt)
    traj = offsetTrajectory(traj, Pose{Quat::Identity(), Vec3(a.baseline_m, 0, 0)});
  writeTrajectory(a.out, traj, to, opt);
  fmt::print("wrote {} ({}, {} poses over {} s) from {} ({}){}\n", a.out, trajectoryFormatName(to),
             traj.size(), nsToSecondsString(traj.poses.back().t_ns - traj.poses.front().t_ns, 3),
             a.in, trajectoryFormatName(in_fmt),
             *a.baseline_opt ? fmt::format(", right camera at {} m along x", a.baseline_m) : "");
}

}  // namespace

void addTrajectoryConvertCommand(CLI::App* trajectory_cmd) {
  auto* cmd = trajectory_cmd->add_subcommand(
      "convert",
      "Convert a camera trajectory between formats: tum (groundtruth.txt), euroc "
      "(state_groundtruth_estimate0/data.csv), icl (ICL-NUIM .gt.freiburg), slambench "
      "(SLAMBench 2 groundtruth.txt), scenenet (SceneNet RGB-D camera log), scenenet_v1 "
      "(SceneNet v1 3x4 pose blocks), kitti (KITTI odometry poses). Axes are converted "
      "to each format's convention");
  auto a = std::make_shared<ConvertArgs>();
  cmd->add_option("IN", a->in, "trajectory file to read")->required();
  cmd->add_option("OUT", a->out, "file to write (atomically)")->required();
  cmd->add_option("--from", a->from, "input format; default: detected from the content");
  cmd->add_option("--to", a->to,
                  "output format; default: from OUT's extension (.txt tum, .csv euroc, "
                  ".freiburg icl, .log scenenet)");
  a->fps_opt = cmd->add_option("--fps", a->format.icl_fps,
                               "icl, scenenet_v1 and kitti only: frame rate linking frame "
                               "numbers and time (default 30, ICL-NUIM's; scenenet_v1: 25; "
                               "kitti: 10)");
  a->baseline_opt = cmd->add_option(
      "--baseline", a->baseline_m,
      "write the right camera of a stereo rig: the pose shifted this many metres along the "
      "camera's x axis");
  cmd->callback([a] { runConvert(*a); });
}

}  // namespace inet::app
