#include "scene/light_xml.h"

#include <pugixml.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

const char* typeName(const Light& l) {
  switch (l.type) {
    case LightType::Point:
      return "PointLight";
    case LightType::Spot:
      return "SpotLight";
    case LightType::Sun:
      return "SunLight";
    case LightType::Sky:
      return "SkyLight";
  }
  return "PointLight";
}

/// Shortest text that reads back to the same double.
std::string num(double v) {
  for (int precision = 6; precision <= 17; ++precision) {
    std::string s = fmt::format("{:.{}g}", v, precision);
    if (std::stod(s) == v) return s;
  }
  return fmt::format("{:.17g}", v);
}

/// A name as an XML attribute value: & < > " and control characters escaped (pugixml reads
/// them back), so a lamp called `Lamp "A" & co` makes a readable file.
std::string attr(const std::string& v) {
  std::string out;
  for (char c : v) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:  // a tab or line break would come back as a space (attribute normalisation)
        if (static_cast<unsigned char>(c) < 0x20)
          out += fmt::format("&#{};", static_cast<int>(c));
        else
          out += c;
    }
  }
  return out;
}

template <class V>
std::string vec(const V& v) {
  std::string s;
  for (int i = 0; i < v.size(); ++i) {
    if (i) s += ' ';
    s += num(static_cast<double>(v[i]));
  }
  return s;
}

class Attrs {
 public:
  Attrs(const pugi::xml_node& node, std::string file, std::string field)
      : node_(node), file_(std::move(file)), field_(std::move(field)) {}
  bool has(const char* name) const { return node_.attribute(name); }
  std::string text(const char* name) const {
    pugi::xml_attribute a = node_.attribute(name);
    if (!a) fail(name, "missing attribute");
    return a.value();
  }
  double number(const char* name) const {
    const std::string t = text(name);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !std::isfinite(v))
      fail(name, "expected a finite number, got '" + t + "'");
    return v;
  }
  /// `n` finite numbers separated by spaces; `what` says which, for the error.
  std::vector<double> numbers(const char* name, size_t n, const char* what) const {
    std::istringstream in(text(name));
    std::vector<double> v(n);
    std::string extra;
    for (double& x : v)
      if (!(in >> x) || !std::isfinite(x)) fail(name, what);
    if (in >> extra) fail(name, what);
    return v;
  }
  Vec3 vec3(const char* name) const {
    const std::vector<double> v = numbers(name, 3, "expected three finite numbers 'x y z'");
    return Vec3(v[0], v[1], v[2]);
  }
  /// A value kept as a float (energies, colours, angles): beyond float's range it would be
  /// written back as inf, which no reader takes.
  float single(const char* name, double v) const {
    if (!(std::abs(v) <= std::numeric_limits<float>::max()))
      fail(name, fmt::format("{} is beyond a 32-bit float's range", v));
    return static_cast<float>(v);
  }
  float single(const char* name) const { return single(name, number(name)); }
  Vec3f single3(const char* name, const Vec3& v) const {
    return Vec3f(single(name, v.x()), single(name, v.y()), single(name, v.z()));
  }
  bool flag(const char* name, bool fallback) const {
    if (!has(name)) return fallback;
    const std::string t = text(name);
    if (t != "true" && t != "false") fail(name, "expected true or false, got '" + t + "'");
    return t == "true";
  }
  [[noreturn]] void fail(const char* name, const std::string& problem) const {
    throw InputError(file_, field_ + "." + name, problem);
  }

 private:
  pugi::xml_node node_;
  std::string file_, field_;
};

/// The optional brightness="b" of a light: a factor on its energy or radiance (the paper's
/// light.xml keeps energy and brightness apart), >= 0, default 1. Read into the energy, so a
/// written file states the product and brightness 1.
double brightnessOf(const Attrs& a) {
  if (!a.has("brightness")) return 1.0;
  const double b = a.number("brightness");
  if (b < 0) a.fail("brightness", "must be >= 0");
  return b;
}

}  // namespace

LightSetup lightSetupOf(const Scene& scene) {
  LightSetup setup;
  setup.lights = scene.lights;
  std::map<std::pair<std::string, std::string>, bool> seen;
  for (const Object& o : scene.objects) {
    const Material& m = scene.materials[o.material];
    if (!m.isEmissive() || seen[{o.name, o.part}]) continue;
    seen[{o.name, o.part}] = true;
    setup.areas.push_back({o.name, o.part, m.emission, true});
  }
  return setup;
}

std::string lightXmlText(const Scene& scene, const std::string& path) {
  const LightSetup setup = lightSetupOf(scene);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format("<lights layout=\"{}\" version=\"1\">\n", attr(scene.name));
  for (const Light& l : setup.lights) {
    out += fmt::format("  <light name=\"{}\" type=\"{}\"", attr(l.name), typeName(l));
    if (!l.object.empty()) out += fmt::format(" object=\"{}\"", attr(l.object));
    out += fmt::format(" on=\"{}\" energy=\"{}\"", l.on ? "true" : "false", num(l.intensity));
    if (l.type == LightType::Sky) {
      out += fmt::format(" model=\"{}\"", skyModelName(l.sky_model));
      if (l.sky_model == SkyModel::Preetham)
        out += fmt::format(" sun_direction=\"{}\" turbidity=\"{}\"", vec(l.direction),
                           num(l.turbidity));
      if (l.sky_model == SkyModel::EnvMap) {
        // the image relative to this file's folder (as `layout import` and `vary` write
        // layout.json's), the rotation as 9 numbers, row by row
        const fs::path image = l.envmap.path.empty() ? l.envmap.file : l.envmap.path;
        const fs::path rel =
            fs::proximate(fs::absolute(image), fs::absolute(path).parent_path());
        Eigen::Matrix<double, 9, 1> rows;
        for (int i = 0; i < 3; ++i) rows.segment<3>(3 * i) = l.envmap_rotation.row(i).transpose();
        out += fmt::format(" file=\"{}\" rotation=\"{}\"", attr(rel.generic_string()), vec(rows));
      }
    } else {
      out += fmt::format(" color=\"{}\" temperature_k=\"{}\"", vec(l.color), num(l.temperature_k));
    }
    if (l.type == LightType::Point || l.type == LightType::Spot)
      out += fmt::format(" position=\"{}\" max_distance=\"{}\"{}", vec(l.position),
                         num(l.max_distance),
                         l.radius > 0.f ? fmt::format(" radius=\"{}\"", num(l.radius)) : "");
    if (l.type == LightType::Spot || l.type == LightType::Sun)
      out += fmt::format(" direction=\"{}\"", vec(l.direction));
    if (l.type == LightType::Spot)
      out +=
          fmt::format(" cone_deg=\"{}\" falloff_deg=\"{}\"", num(l.cone_deg), num(l.falloff_deg));
    if (l.type == LightType::Sun)
      out += fmt::format(" angular_diameter_deg=\"{}\"", num(l.angular_diameter_deg));
    out += "/>\n";
  }
  for (const AreaLightEntry& a : setup.areas)
    out += fmt::format("  <light type=\"AreaLight\" object=\"{}\"{} on=\"{}\" radiance=\"{}\"/>\n",
                       attr(a.object), a.part.empty() ? "" : " part=\"" + attr(a.part) + "\"",
                       a.on ? "true" : "false", vec(a.radiance));
  out += "</lights>\n";
  return out;
}

void saveLightXml(const Scene& scene, const std::string& path) {
  writeTextAtomic(path, lightXmlText(scene, path));
}

LightSetup loadLightXml(const std::string& path) { return parseLightXml(readTextFile(path), path); }

LightSetup parseLightXml(const std::string& text, const std::string& path) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_buffer(text.data(), text.size());
  if (!ok)
    throw InputError(path, fmt::format("offset {}", ok.offset),
                     fmt::format("malformed XML: {}", ok.description()));
  const pugi::xml_node root = doc.child("lights");
  if (!root) throw InputError(path, "lights", "missing the <lights> root element");
  LightSetup setup;
  int i = 0;
  for (pugi::xml_node n : root.children()) {
    const std::string field = fmt::format("light[{}]", i++);
    if (n.type() != pugi::node_element) continue;
    if (std::string(n.name()) != "light")
      throw InputError(path, field, fmt::format("unknown element <{}>", n.name()));
    const Attrs a(n, path, field);
    const std::string type = a.text("type");
    if (type == "AreaLight") {
      AreaLightEntry e;
      e.object = a.text("object");
      if (a.has("part")) e.part = a.text("part");
      e.on = a.flag("on", true);
      const Vec3 r = a.vec3("radiance");
      if (r.minCoeff() < 0) a.fail("radiance", "must be >= 0");
      e.radiance = a.single3("radiance", r * brightnessOf(a));
      setup.areas.push_back(e);
      continue;
    }
    Light l;
    l.name = a.text("name");
    if (type == "PointLight") {
      l.type = LightType::Point;
    } else if (type == "SpotLight") {
      l.type = LightType::Spot;
    } else if (type == "SunLight") {
      l.type = LightType::Sun;
    } else if (type == "SkyLight") {
      l.type = LightType::Sky;
    } else {
      a.fail("type", "unknown light type '" + type +
                         "' (valid: PointLight, SpotLight, SunLight, SkyLight, AreaLight)");
    }
    if (a.has("object")) l.object = a.text("object");
    l.on = a.flag("on", true);
    l.intensity = a.single("energy", a.number("energy") * brightnessOf(a));
    if (l.type == LightType::Sky) {
      const std::string model = a.has("model") ? a.text("model") : "uniform";
      if (model == "preetham") {
        l.sky_model = SkyModel::Preetham;
        l.direction = a.vec3("sun_direction");
        l.turbidity = a.single("turbidity");
      } else if (model == "envmap") {
        l.sky_model = SkyModel::EnvMap;
        l.envmap.file = a.text("file");
        l.envmap.path = fs::path(l.envmap.file).is_absolute()
                            ? l.envmap.file
                            : (fs::path(path).parent_path() / l.envmap.file).string();
        std::error_code ec;
        if (!fs::is_regular_file(l.envmap.path, ec))
          a.fail("file", "no such image '" + l.envmap.path + "'");
        if (a.has("rotation")) {
          const std::vector<double> m =
              a.numbers("rotation", 9, "expected 9 finite numbers (a 3x3 rotation, row by row)");
          for (int i = 0; i < 3; ++i)
            l.envmap_rotation.row(i) = Vec3(m[3 * i], m[3 * i + 1], m[3 * i + 2]).transpose();
        }
      } else if (model != "uniform") {
        a.fail("model", "unknown sky model '" + model + "' (valid: uniform, preetham, envmap)");
      }
    } else {
      if (a.has("color")) l.color = a.single3("color", a.vec3("color"));
      if (a.has("temperature_k")) l.temperature_k = a.single("temperature_k");
    }
    if (l.type == LightType::Point || l.type == LightType::Spot) {
      l.position = a.vec3("position");
      if (a.has("max_distance")) l.max_distance = a.single("max_distance");
      if (a.has("radius")) l.radius = a.single("radius");
    }
    if (l.type == LightType::Spot || l.type == LightType::Sun) l.direction = a.vec3("direction");
    if (l.type == LightType::Spot) {
      l.cone_deg = a.single("cone_deg");
      l.falloff_deg = a.single("falloff_deg");
    }
    if (l.type == LightType::Sun && a.has("angular_diameter_deg"))
      l.angular_diameter_deg = a.single("angular_diameter_deg");
    setup.lights.push_back(l);
  }
  return setup;
}

void applyLightSetup(Scene& scene, const LightSetup& setup, const std::string& where) {
  scene.lights = setup.lights;
  std::vector<bool> emissive_before(scene.objects.size());
  for (size_t i = 0; i < scene.objects.size(); ++i)
    emissive_before[i] = scene.materials[scene.objects[i].material].isEmissive();
  for (size_t k = 0; k < setup.areas.size(); ++k) {
    const AreaLightEntry& e = setup.areas[k];
    // which parts: the named one; else those already emissive (a lamp's lens, not its
    // housing: the light.xml files before parts were written said only the object); else all
    bool any_emissive = false;
    for (size_t i = 0; i < scene.objects.size(); ++i)
      any_emissive = any_emissive || (scene.objects[i].name == e.object && emissive_before[i]);
    bool found = false;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      Object& o = scene.objects[i];
      if (o.name != e.object || (!e.part.empty() && o.part != e.part)) continue;
      found = true;
      if (e.part.empty() && any_emissive && !emissive_before[i]) continue;
      Material m = scene.materials[o.material];
      const Vec3f emission = e.on ? e.radiance : Vec3f::Zero();
      if (m.emission == emission) continue;
      m.id = fmt::format("{}@{}", m.id, o.name);  // this object's own copy
      m.emission = emission;
      int index = scene.findMaterial(m.id);
      if (index < 0) {
        scene.materials.push_back(m);
        index = static_cast<int>(scene.materials.size()) - 1;
      }
      scene.materials[index].emission = emission;
      o.material = index;
    }
    if (!found)
      throw InputError(where, fmt::format("AreaLight[{}].object", k),
                       e.part.empty()
                           ? fmt::format("no object is named '{}'", e.object)
                           : fmt::format("no object '{}' has a part '{}'", e.object, e.part));
  }
  scene.validate(where);
}

}  // namespace inet
