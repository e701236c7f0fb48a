// Every trajectory reader (TUM, EuRoC, ICL-NUIM, SLAMBench, SceneNet, and the format detection)
// on arbitrary bytes: each parses or throws InputError; what parses has rising timestamps.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "trajectory/formats.h"

namespace {

void check(const inet::Trajectory& t) {
  for (size_t i = 1; i < t.size(); ++i)
    if (t.poses[i].t_ns <= t.poses[i - 1].t_ns) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  using inet::TrajectoryFormat;
  for (TrajectoryFormat f : {TrajectoryFormat::Tum, TrajectoryFormat::Euroc, TrajectoryFormat::Icl,
                             TrajectoryFormat::SlamBench, TrajectoryFormat::SceneNet}) {
    try {
      check(inet::parseTrajectory(text, "fuzz.txt", f));
    } catch (const inet::InputError&) {
    }
  }
  try {
    check(inet::parseTrajectory(text, "fuzz.txt", inet::detectTrajectoryFormat("fuzz.txt", text)));
  } catch (const inet::InputError&) {
  }
  return 0;
}
