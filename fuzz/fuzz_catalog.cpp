// Sweet Home 3D catalog properties (src/assets/java_properties.h, furniture_catalog.h) and the
// SVG cut-out shapes in them (svg_path.h): arbitrary bytes either parse or throw InputError.
// Every entry the properties name is taken to exist, so the piece checks all run.
#include <cstddef>
#include <cstdint>
#include <string>

#include "assets/furniture_catalog.h"
#include "assets/java_properties.h"
#include "assets/svg_path.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  inet::JavaProperties props;
  try {
    props = inet::parseJavaProperties(text, "fuzz.properties");
  } catch (const inet::InputError&) {
    return 0;
  }
  for (const auto& [key, value] : props)
    if (key.find("CutOutShape") != std::string::npos) {
      try {
        inet::parseSvgPath(value, 1e-3, "fuzz.properties", key);
      } catch (const inet::InputError&) {
      }
    }
  try {
    inet::catalogFromProperties(props, "fuzz.sh3f", [](const std::string&) { return true; });
  } catch (const inet::InputError&) {
  }
  return 0;
}
