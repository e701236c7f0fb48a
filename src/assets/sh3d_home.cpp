#include "assets/sh3d_home.h"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <pugixml.hpp>

#include "assets/zip_archive.h"
#include "core/error.h"

namespace inet {
namespace {

/// Reads one element's attributes, naming the element (and its id) in errors.
class Element {
 public:
  Element(pugi::xml_node node, const std::string& where) : node_(node), where_(where) {}

  [[noreturn]] void fail(const std::string& attribute, const std::string& problem) const {
    std::string field = fmt::format("Home.xml <{}", node_.name());
    if (const auto id = node_.attribute("id")) field += fmt::format(" id='{}'", id.value());
    field += ">";
    if (!attribute.empty()) field += " " + attribute;
    throw InputError(where_, field, problem);
  }
  bool has(const char* a) const { return !node_.attribute(a).empty(); }
  std::string text(const char* a, const std::string& fallback = {}) const {
    const auto at = node_.attribute(a);
    return at ? std::string(at.value()) : fallback;
  }
  std::string required(const char* a) const {
    if (!has(a)) fail(a, "missing");
    return text(a);
  }
  double number(const char* a) const {
    if (!has(a)) fail(a, "missing");
    return parse(a);
  }
  double number(const char* a, double fallback) const { return has(a) ? parse(a) : fallback; }
  std::optional<double> optionalNumber(const char* a) const {
    return has(a) ? std::optional<double>(parse(a)) : std::nullopt;
  }
  double positive(const char* a) const {
    const double v = number(a);
    if (!(v > 0)) fail(a, fmt::format("must be > 0, got {}", text(a)));
    return v;
  }
  double nonNegative(const char* a, double fallback) const {
    const double v = number(a, fallback);
    if (!(v >= 0)) fail(a, fmt::format("must be >= 0, got {}", text(a)));
    return v;
  }
  bool flag(const char* a, bool fallback) const {
    if (!has(a)) return fallback;
    const std::string v = text(a);
    if (v == "true") return true;
    if (v == "false") return false;
    fail(a, fmt::format("expected true or false, got '{}'", v));
  }
  /// AARRGGBB (Sweet Home 3D writes the alpha byte; colours are opaque).
  Sh3dColor color(const char* a) const {
    if (!has(a)) return std::nullopt;
    const std::string v = text(a);
    char* end = nullptr;
    errno = 0;
    const unsigned long argb = std::strtoul(v.c_str(), &end, 16);
    if (v.size() != 8 || *end != '\0' || errno != 0)
      fail(a, fmt::format("expected a colour AARRGGBB in hex, got '{}'", v));
    return Eigen::Vector3f(float((argb >> 16) & 0xff), float((argb >> 8) & 0xff),
                           float(argb & 0xff)) /
           255.f;
  }
  pugi::xml_node node() const { return node_; }

 private:
  double parse(const char* a) const {
    const std::string v = text(a);
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(d))
      fail(a, fmt::format("expected a number, got '{}'", v));
    return d;
  }
  pugi::xml_node node_;
  std::string where_;
};

std::optional<Sh3dTexture> textureChild(pugi::xml_node node, const char* attribute,
                                        const std::string& where) {
  for (pugi::xml_node t : node.children("texture")) {
    const std::string att = t.attribute("attribute").value();
    if (attribute != nullptr && att != attribute) continue;
    const Element e(t, where);
    Sh3dTexture tex;
    tex.image = e.required("image");
    tex.name = e.text("name");
    tex.width_cm = e.positive("width");
    tex.height_cm = e.positive("height");
    tex.angle = e.number("angle", 0.0);
    return tex;
  }
  return std::nullopt;
}

Sh3dCamera readCamera(const Element& e) {
  Sh3dCamera c;
  c.attribute = e.text("attribute");
  c.name = e.text("name");
  c.x_cm = e.number("x");
  c.y_cm = e.number("y");
  c.z_cm = e.number("z");
  c.yaw = e.number("yaw");
  c.pitch = e.number("pitch");
  c.field_of_view = e.number("fieldOfView", c.field_of_view);
  if (!(c.field_of_view > 0 && c.field_of_view < 3.14159))
    e.fail("fieldOfView", "must be in (0, pi) radians");
  c.time_ms = static_cast<int64_t>(e.number("time", 0.0));
  return c;
}

/// Where a name of a level or wall resolves, for references between elements.
int lookup(const std::map<std::string, int>& ids, const Element& e, const char* attribute) {
  if (!e.has(attribute)) return -1;
  const auto it = ids.find(e.text(attribute));
  if (it == ids.end()) e.fail(attribute, fmt::format("names no element ('{}')", e.text(attribute)));
  return it->second;
}

void readPiece(pugi::xml_node node, const std::string& group,
               const std::map<std::string, int>& levels, const std::string& where,
               std::vector<Sh3dPiece>& out) {
  const std::string tag = node.name();
  const Element e(node, where);
  if (tag == "furnitureGroup") {
    // Members carry absolute coordinates (Sweet Home 3D writes them so): the group's own
    // position, angle and size only describe their bounding box.
    const std::string name = e.text("name", "group");
    if (!e.flag("visible", true)) return;
    for (pugi::xml_node child : node.children()) readPiece(child, name, levels, where, out);
    return;
  }
  Sh3dPiece p;
  if (tag == "pieceOfFurniture")
    p.kind = Sh3dPieceKind::Furniture;
  else if (tag == "doorOrWindow")
    p.kind = Sh3dPieceKind::DoorOrWindow;
  else if (tag == "light")
    p.kind = Sh3dPieceKind::Light;
  else
    return;  // texture, material... of a group: nothing of its own
  p.group = group;
  p.id = e.text("id");
  p.name = e.text("name");
  p.catalog_id = e.text("catalogId");
  p.creator = e.text("creator");
  p.license = e.text("license");
  p.level = lookup(levels, e, "level");
  p.model = e.required("model");
  if (e.has("modelRotation")) {
    double m[9];
    const std::string v = e.text("modelRotation");
    const char* s = v.c_str();
    for (double& x : m) {
      char* end = nullptr;
      x = std::strtod(s, &end);
      if (end == s) e.fail("modelRotation", "expected 9 numbers");
      s = end;
    }
    p.model_rotation << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  }
  p.x_cm = e.number("x");
  p.y_cm = e.number("y");
  p.elevation_cm = e.number("elevation", 0.0);
  p.angle = e.number("angle", 0.0);
  p.pitch = e.number("pitch", 0.0);
  p.roll = e.number("roll", 0.0);
  p.width_cm = e.positive("width");
  p.depth_cm = e.positive("depth");
  p.height_cm = e.positive("height");
  p.mirrored = e.flag("modelMirrored", false);
  p.visible = e.flag("visible", true);
  p.movable = e.flag("movable", true);
  p.back_face_shown = e.flag("backFaceShown", false);
  p.color = e.color("color");
  p.shininess = e.optionalNumber("shininess");
  p.texture = textureChild(node, nullptr, where);
  for (pugi::xml_node m : node.children("material")) {
    const Element me(m, where);
    Sh3dMaterial mat;
    mat.name = me.required("name");
    mat.color = me.color("color");
    mat.shininess = me.optionalNumber("shininess");
    mat.texture = textureChild(m, nullptr, where);
    p.materials.push_back(mat);
  }
  if (p.kind == Sh3dPieceKind::DoorOrWindow) {
    p.wall_thickness = e.number("wallThickness", 1.0);
    p.wall_distance = e.number("wallDistance", 0.0);
    p.wall_cut_out_on_both_sides = e.flag("wallCutOutOnBothSides", false);
    p.cut_out_shape = e.text("cutOutShape");
    for (pugi::xml_node s : node.children("sash")) {
      const Element se(s, where);
      p.sashes.push_back({se.number("xAxis"), se.number("yAxis"), se.number("width"),
                          se.number("startAngle"), se.number("endAngle")});
    }
  }
  if (p.kind == Sh3dPieceKind::Light) {
    p.power = e.number("power", 0.5);
    if (!(p.power >= 0 && p.power <= 1)) e.fail("power", "must be in [0, 1]");
    for (pugi::xml_node s : node.children("lightSource")) {
      const Element se(s, where);
      Sh3dLightSource ls;
      ls.position = {se.number("x"), se.number("y"), se.number("z")};
      ls.color = se.color("color").value_or(Eigen::Vector3f::Ones());
      ls.diameter = se.nonNegative("diameter", 0.0);
      p.light_sources.push_back(ls);
    }
  }
  out.push_back(std::move(p));
}

/// The line of the first '&' that starts no entity or character reference, 0 if none.
/// pugixml keeps such an ampersand as text; XML forbids it, and a file that has one was not
/// written by Sweet Home 3D (which escapes it), so it is refused as an XML parser would.
size_t bareAmpersandLine(const std::string& xml) {
  size_t line = 1;
  for (size_t i = 0; i < xml.size(); ++i) {
    if (xml[i] == '\n') ++line;
    if (xml[i] != '&') continue;
    size_t j = i + 1;
    if (j < xml.size() && xml[j] == '#') {
      ++j;
      if (j < xml.size() && xml[j] == 'x') ++j;
      while (j < xml.size() && std::isxdigit(static_cast<unsigned char>(xml[j]))) ++j;
    } else {
      while (j < xml.size() && (std::isalnum(static_cast<unsigned char>(xml[j])) || xml[j] == '_' ||
                                xml[j] == '-' || xml[j] == '.'))
        ++j;
    }
    if (j == i + 1 || j >= xml.size() || xml[j] != ';') return line;
  }
  return 0;
}

}  // namespace

Sh3dHome parseHomeXml(const std::string& xml, const std::string& where) {
  if (const size_t line = bareAmpersandLine(xml))
    throw InputError(where, fmt::format("Home.xml line {}", line),
                     "not well-formed XML: a bare '&' (XML writes it &amp;)");
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(xml.data(), xml.size());
  if (!parsed) {
    size_t line = 1;
    for (size_t i = 0; i < size_t(parsed.offset) && i < xml.size(); ++i) line += xml[i] == '\n';
    throw InputError(where, fmt::format("Home.xml line {}", line),
                     fmt::format("not well-formed XML: {}", parsed.description()));
  }
  const pugi::xml_node root = doc.child("home");
  if (!root) throw InputError(where, "Home.xml", "no <home> element: not a Sweet Home 3D home");
  const Element h(root, where);
  Sh3dHome home;
  home.path = where;
  home.name = h.text("name");
  // Sweet Home 3D writes its version as an integer (6500 for 6.5, 7400 for 7.4); other tools
  // that imitate the format write "7.2" and attributes of their own, with different meanings.
  const std::string version = h.required("version");
  char* end = nullptr;
  const long v = std::strtol(version.c_str(), &end, 10);
  if (*end != '\0' || v < 5300 || v > 99999)
    h.fail("version", fmt::format("'{}' is not a version Sweet Home 3D 5.3 or later writes (an "
                                  "integer such as 6500): the file was written by another tool",
                                  version));
  home.version = int(v);
  if (h.has("unit"))
    h.fail("unit",
           "Sweet Home 3D never writes a unit (always centimetres): the file was "
           "written by another tool");
  home.wall_height_cm = h.has("wallHeight") ? h.positive("wallHeight") : 250.0;
  for (pugi::xml_node p : root.children("property")) {
    const std::string name = p.attribute("name").value();
    if (name == "License") home.license = p.attribute("value").value();
    if (name == "Author") home.author = p.attribute("value").value();
  }

  std::map<std::string, int> levels, walls;
  for (pugi::xml_node n : root.children("level")) {
    const Element e(n, where);
    Sh3dLevel l;
    l.id = e.required("id");
    l.name = e.text("name");
    l.elevation_cm = e.number("elevation");
    l.floor_thickness_cm = e.nonNegative("floorThickness", 12.0);
    l.height_cm = e.positive("height");
    l.elevation_index = int(e.number("elevationIndex", 0.0));
    l.visible = e.flag("visible", true) && e.flag("viewable", true);
    if (!levels.emplace(l.id, int(home.levels.size())).second) e.fail("id", "used twice");
    home.levels.push_back(l);
  }
  for (pugi::xml_node n : root.children("wall")) {
    const Element e(n, where);
    const std::string id = e.text("id", fmt::format("wall#{}", walls.size()));
    if (!walls.emplace(id, int(walls.size())).second) e.fail("id", "used twice");
  }
  auto needLevel = [&](const Element& e) {
    if (!home.levels.empty() && !e.has("level")) e.fail("level", "missing (the home has levels)");
    return lookup(levels, e, "level");
  };
  for (pugi::xml_node n : root.children("wall")) {
    const Element e(n, where);
    Sh3dWall w;
    w.id = e.text("id", fmt::format("wall#{}", home.walls.size()));
    w.level = needLevel(e);
    w.start = {e.number("xStart"), e.number("yStart")};
    w.end = {e.number("xEnd"), e.number("yEnd")};
    w.thickness_cm = e.positive("thickness");
    w.height_cm = e.optionalNumber("height");
    w.height_at_end_cm = e.optionalNumber("heightAtEnd");
    if (w.height_cm && !(*w.height_cm > 0)) e.fail("height", "must be > 0");
    if (w.height_at_end_cm && !(*w.height_at_end_cm >= 0)) e.fail("heightAtEnd", "must be >= 0");
    w.arc_extent = e.number("arcExtent", 0.0);
    w.wall_at_start = lookup(walls, e, "wallAtStart");
    w.wall_at_end = lookup(walls, e, "wallAtEnd");
    w.left_color = e.color("leftSideColor");
    w.right_color = e.color("rightSideColor");
    w.top_color = e.color("topColor");
    w.left_texture = textureChild(n, "leftSideTexture", where);
    w.right_texture = textureChild(n, "rightSideTexture", where);
    home.walls.push_back(w);
  }
  for (pugi::xml_node n : root.children("room")) {
    const Element e(n, where);
    Sh3dRoom r;
    r.id = e.text("id", fmt::format("room#{}", home.rooms.size()));
    r.name = e.text("name");
    r.level = needLevel(e);
    for (pugi::xml_node pt : n.children("point")) {
      const Element pe(pt, where);
      r.points.emplace_back(pe.number("x"), pe.number("y"));
    }
    if (r.points.size() < 3) e.fail("point", "a room needs at least 3 points");
    r.floor_visible = e.flag("floorVisible", true);
    r.ceiling_visible = e.flag("ceilingVisible", true);
    r.floor_color = e.color("floorColor");
    r.ceiling_color = e.color("ceilingColor");
    r.floor_texture = textureChild(n, "floorTexture", where);
    r.ceiling_texture = textureChild(n, "ceilingTexture", where);
    home.rooms.push_back(r);
  }
  for (pugi::xml_node n : root.children()) {
    const std::string tag = n.name();
    if (tag == "pieceOfFurniture" || tag == "doorOrWindow" || tag == "light" ||
        tag == "furnitureGroup")
      readPiece(n, "", levels, where, home.pieces);
  }
  if (!home.levels.empty())
    for (const Sh3dPiece& p : home.pieces)
      if (p.level < 0)
        throw InputError(where, fmt::format("Home.xml <piece id='{}'> level", p.id),
                         "missing (the home has levels)");
  for (pugi::xml_node n : root.children()) {
    const std::string tag = n.name();
    if (tag != "observerCamera" && tag != "camera") continue;
    const Sh3dCamera c = readCamera(Element(n, where));
    if (c.attribute == "observerCamera") home.observer = c;
    if (c.attribute == "storedCamera") home.stored_cameras.push_back(c);
  }
  if (const pugi::xml_node env = root.child("environment")) {
    const Element e(env, where);
    if (auto c = e.color("skyColor")) home.sky_color = *c;
    if (auto c = e.color("groundColor")) home.ground_color = *c;
    for (pugi::xml_node n : env.children("observerCamera"))
      home.video_path.push_back(readCamera(Element(n, where)));
  }
  if (const pugi::xml_node c = root.child("compass")) {
    const Element e(c, where);
    home.compass.north_direction = e.number("northDirection", 0.0);
    home.compass.latitude = e.number("latitude", 0.0);
    home.compass.longitude = e.number("longitude", 0.0);
    home.compass.time_zone = e.text("timeZone", "UTC");
  }
  if (home.rooms.empty() && home.pieces.empty())
    throw InputError(where, "Home.xml",
                     fmt::format("{} wall(s) and nothing else: no room and no furniture to make "
                                 "a scene of",
                                 home.walls.size()));
  return home;
}

Sh3dHome readSh3dHome(const std::string& path) {
  const ZipArchive zip(path);
  if (!zip.find("Home.xml")) {
    if (zip.find("Home"))
      throw InputError(path, "Home.xml",
                       "missing: the file predates Sweet Home 3D 5.3 (it holds only the legacy "
                       "serialized Home); open it in Sweet Home 3D 5.3 or later and save it again");
    throw InputError(path, "Home.xml", "missing: not a Sweet Home 3D home");
  }
  Sh3dHome home = parseHomeXml(zip.read("Home.xml", uint64_t(256) << 20), path);
  auto need = [&](const std::string& entry, const std::string& what) {
    if (entry.empty() || zip.find(entry)) return;
    throw InputError(path, what,
                     fmt::format("names the entry '{}', which the archive lacks", entry));
  };
  for (const Sh3dPiece& p : home.pieces) {
    need(p.model, fmt::format("Home.xml <piece id='{}'> model", p.id));
    if (p.texture) need(p.texture->image, fmt::format("Home.xml <piece id='{}'> texture", p.id));
  }
  for (const Sh3dWall& w : home.walls)
    for (const auto& t : {w.left_texture, w.right_texture})
      if (t) need(t->image, fmt::format("Home.xml <wall id='{}'> texture", w.id));
  for (const Sh3dRoom& r : home.rooms)
    for (const auto& t : {r.floor_texture, r.ceiling_texture})
      if (t) need(t->image, fmt::format("Home.xml <room id='{}'> texture", r.id));
  return home;
}

}  // namespace inet
