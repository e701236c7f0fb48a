#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "scene/layout_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    inet::Scene s = inet::parseLayout(text, "/nonexistent/fuzz/layout.json");
    // whatever parses must write back and parse to the same text
    std::string once = inet::layoutToJson(s);
    std::string twice = inet::layoutToJson(inet::parseLayout(once, "/nonexistent/fuzz/again.json"));
    if (once != twice) __builtin_trap();
  } catch (const inet::InputError&) {
  }
  return 0;
}
