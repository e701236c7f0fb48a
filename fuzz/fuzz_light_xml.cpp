// light.xml (src/scene/light_xml.h): arbitrary bytes either parse or throw InputError; what
// parses writes back as text that parses, to the same text again (analytic lights; the
// AreaLight entries need their objects in a scene and are only parsed).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "scene/light_xml.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = "/nonexistent/fuzz/light.xml";
  inet::Scene s;
  try {
    s.lights = inet::parseLightXml(text, path).lights;
  } catch (const inet::InputError&) {
    return 0;
  }
  // what we write must read back (an unescaped quote in a name once did not), to the same text
  const std::string once = inet::lightXmlText(s, path);
  inet::Scene t;
  t.lights = inet::parseLightXml(once, path).lights;
  if (inet::lightXmlText(t, path) != once) __builtin_trap();
  return 0;
}
