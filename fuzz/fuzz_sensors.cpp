// The sensor readers on arbitrary bytes: event text (RPG events.txt and its E2VID variant) and
// the IMU noise yaml (Kalibr / EuRoC imu0/sensor.yaml). Each parses or throws InputError; parsed
// events have pixel coordinates in the stated sensor size (when given).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "sensors/event_io.h"
#include "sensors/imu_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const inet::EventFile f = inet::parseEventsTxt(text, "fuzz.txt", 0);
    for (const inet::Event& e : f.events) {
      if (e.p > 1) __builtin_trap();
      if (f.width > 0 && (e.x >= f.width || e.y >= f.height)) __builtin_trap();
    }
  } catch (const inet::InputError&) {
  }
  try {
    inet::parseImuNoiseYaml(text, "fuzz.yaml");
  } catch (const inet::InputError&) {
  }
  return 0;
}
