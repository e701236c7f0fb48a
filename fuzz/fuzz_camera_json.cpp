#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "render/camera.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    inet::CameraFile c = inet::parseCameraJson(text, "fuzz.json");
    if (!(c.intrinsics.fx > 0) || c.intrinsics.width < 1) __builtin_trap();
  } catch (const inet::InputError&) {
  }
  return 0;
}
