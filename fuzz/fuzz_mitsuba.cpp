// Mitsuba scene XML (scene/mitsuba_importer.h), parsed from memory without reading any file:
// arbitrary bytes must import or throw InputError. Whatever imports must also write as a
// layout.json, and its sensor as a camera.json that the camera reader accepts.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "render/camera.h"
#include "scene/layout_json.h"
#include "scene/mitsuba_importer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  inet::MitsubaOptions opt;
  opt.read_files = false;  // mesh files, textures and includes point at nothing
  inet::MitsubaScene m;
  try {
    m = inet::parseMitsubaScene(text, "/nonexistent/fuzz/scene.xml", opt);
  } catch (const inet::InputError&) {
    return 0;
  }
  if (m.scene.objects.empty()) __builtin_trap();
  try {
    inet::layoutToJson(m.scene);  // validated scenes write (throws only InputError)
  } catch (const inet::InputError&) {
    __builtin_trap();
  }
  if (m.sensor) {
    try {
      inet::parseCameraJson(inet::mitsubaCameraJson(*m.sensor, "fuzz"), "camera.json");
    } catch (const inet::InputError&) {
      __builtin_trap();  // a camera we made must read back
    }
  }
  return 0;
}
