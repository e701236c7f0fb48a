// Every trajectory reader (TUM, EuRoC, ICL-NUIM, SLAMBench, SceneNet, SceneNet v1, and the
// format detection) on arbitrary bytes: each parses or throws InputError; what parses has rising
// timestamps (repeated stamps dropped) and unit quaternions. `make fuzz` seeds the corpus with
// the official TUM RGB-D, TUM-VI and EuRoC ground-truth files of ../shared/data when present.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "trajectory/formats.h"

namespace {

void check(const inet::Trajectory& t) {
  for (size_t i = 1; i < t.size(); ++i)
    if (t.poses[i].t_ns <= t.poses[i - 1].t_ns) __builtin_trap();
  for (const inet::TimedPose& p : t.poses)
    if (!(std::abs(p.T_world_camera.q.norm() - 1.0) < 1e-9) || !p.T_world_camera.t.allFinite())
      __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  using inet::TrajectoryFormat;
  for (TrajectoryFormat f : {TrajectoryFormat::Tum, TrajectoryFormat::Euroc, TrajectoryFormat::Icl,
                             TrajectoryFormat::SlamBench, TrajectoryFormat::SceneNet,
                             TrajectoryFormat::SceneNetV1, TrajectoryFormat::Kitti}) {
    try {
      inet::TrajectoryReadReport report;
      check(inet::parseTrajectory(text, "fuzz.txt", f, {}, &report));
      if (report.repeated_with_other_pose > report.repeated_stamps) __builtin_trap();
    } catch (const inet::InputError&) {
    }
  }
  try {
    check(inet::parseTrajectory(text, "fuzz.txt", inet::detectTrajectoryFormat("fuzz.txt", text)));
  } catch (const inet::InputError&) {
  }
  return 0;
}
