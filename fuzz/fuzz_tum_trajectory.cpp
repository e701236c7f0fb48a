#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "trajectory/trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    inet::Trajectory t = inet::parseTumTrajectory(text, "fuzz.txt");
    for (size_t i = 1; i < t.size(); ++i)
      if (t.poses[i].t_ns <= t.poses[i - 1].t_ns) __builtin_trap();
  } catch (const inet::InputError&) {
  }
  return 0;
}
