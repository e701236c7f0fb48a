#include "scene/mitsuba_xml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace inet::mitsuba {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Includes nest at most this deep (a file including itself would otherwise never end).
constexpr int kMaxIncludeDepth = 8;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

/// A finite number, the whole of `text` (surrounding blanks allowed).
std::optional<double> parseNumber(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Numbers separated by commas and/or blanks ("1, 2, 3" or "1 2 3").
std::optional<std::vector<double>> parseNumbers(const std::string& text) {
  std::vector<double> out;
  std::string token;
  auto flush = [&]() {
    if (token.empty()) return true;
    auto v = parseNumber(token);
    token.clear();
    if (!v) return false;
    out.push_back(*v);
    return true;
  };
  for (char c : text) {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      if (!flush()) return std::nullopt;
    } else {
      token += c;
    }
  }
  if (!flush()) return std::nullopt;
  return out;
}

/// "#rrggbb" as a linear colour (hex colours are display, i.e. sRGB-encoded, values).
std::optional<Vec3f> parseHex(const std::string& text) {
  const std::string t = trim(text);
  if (t.size() != 7 || t[0] != '#') return std::nullopt;
  Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const std::string byte = t.substr(1 + 2 * c, 2);
    if (!std::isxdigit(static_cast<unsigned char>(byte[0])) ||
        !std::isxdigit(static_cast<unsigned char>(byte[1])))
      return std::nullopt;
    out[c] = static_cast<float>(srgbEotf(std::strtol(byte.c_str(), nullptr, 16) / 255.0));
  }
  return out;
}

/// Linear sRGB of a reflectance or emission spectrum given as (wavelength nm, value) pairs,
/// piecewise linear between them and constant beyond: CIE 1931 XYZ, then the sRGB matrix, then
/// divided by the RGB of a flat spectrum so that a constant value v gives (v, v, v).
Vec3f spectrumToRgb(std::vector<std::pair<double, double>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  auto at = [&](double nm) {
    if (nm <= pairs.front().first) return pairs.front().second;
    if (nm >= pairs.back().first) return pairs.back().second;
    auto hi = std::lower_bound(pairs.begin(), pairs.end(), std::make_pair(nm, -1e300));
    auto lo = hi - 1;
    const double t = (nm - lo->first) / std::max(hi->first - lo->first, 1e-12);
    return lo->second + t * (hi->second - lo->second);
  };
  Eigen::Matrix3d m;  // IEC 61966-2-1: XYZ (D65) -> linear sRGB
  m << 3.2404542, -1.5371385, -0.4985314, -0.9692660, 1.8760108, 0.0415560, 0.0556434,
      -0.2040259, 1.0572252;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), flat = Eigen::Vector3d::Zero();
  for (int nm = 360; nm <= 830; ++nm) {
    const Eigen::Vector3d cmf = cieXyzMatching(nm);
    xyz += at(nm) * cmf;
    flat += cmf;
  }
  return ((m * xyz).array() / (m * flat).array()).cast<float>();
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> items;
  std::string cur;
  for (char c : text + ",") {
    if (c != ',') {
      cur += c;
      continue;
    }
    if (!trim(cur).empty()) items.push_back(trim(cur));
    cur.clear();
  }
  return items;
}

Mat4 translation(const Vec3& t) {
  Mat4 m = Mat4::Identity();
  m.block<3, 1>(0, 3) = t;
  return m;
}

}  // namespace

std::string snakeCase(const std::string& name) {
  std::string out;
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    const bool after_lower =
        i > 0 && (std::islower(static_cast<unsigned char>(name[i - 1])) ||
                  std::isdigit(static_cast<unsigned char>(name[i - 1])));
    if (std::isupper(c) && after_lower) out += '_';
    out += static_cast<char>(std::tolower(c));
  }
  return out;
}

void Notes::add(const std::string& what, const std::string& subject) {
  auto it = std::find_if(items_.begin(), items_.end(),
                         [&](const auto& item) { return item.first == what; });
  if (it == items_.end()) {
    items_.emplace_back(what, std::vector<std::string>{});
    it = items_.end() - 1;
  }
  if (!subject.empty() &&
      std::find(it->second.begin(), it->second.end(), subject) == it->second.end())
    it->second.push_back(subject);
}

std::vector<std::string> Notes::lines() const {
  std::vector<std::string> out;
  for (const auto& [what, subjects] : items_) {
    if (subjects.empty()) {
      out.push_back(what);
      continue;
    }
    const size_t shown = std::min<size_t>(subjects.size(), 6);
    std::string names;
    for (size_t i = 0; i < shown; ++i) names += (i ? ", " : "") + subjects[i];
    if (subjects.size() > shown) names += fmt::format(", ... ({} more)", subjects.size() - shown);
    out.push_back(fmt::format("{} ({}: {})", what, subjects.size(), names));
  }
  return out;
}

// --- Document ------------------------------------------------------------------------------

struct Document::Source {
  std::string path;
  std::string text;
  std::vector<size_t> line_starts;
  pugi::xml_document doc;
  int line(ptrdiff_t offset) const {
    if (offset < 0) return 0;
    return static_cast<int>(std::upper_bound(line_starts.begin(), line_starts.end(),
                                             static_cast<size_t>(offset)) -
                            line_starts.begin());
  }
};

Document::Document(const std::string& text, const std::string& path,
                   const std::map<std::string, std::string>& parameters, bool read_includes,
                   Notes& notes) {
  const Source& main = load(text, path);
  const pugi::xml_node root = main.doc.document_element();
  const std::string version = root.attribute("version").value();
  major_ = std::atoi(version.c_str());
  // the file's <default> values first, then the caller's (which win), as Mitsuba's -D
  for (pugi::xml_node d : root.children("default")) {
    const std::string name = d.attribute("name").value();
    if (name.empty() || !d.attribute("value"))
      fail(d, "a <default> needs a name and a value attribute");
    parameters_[name] = d.attribute("value").value();
  }
  for (const auto& [name, value] : parameters) parameters_[name] = value;
  expand(main, 0, read_includes, notes);
  indexIds();
}

Document::~Document() = default;

const Document::Source& Document::load(const std::string& text, const std::string& path) {
  auto src = std::make_unique<Source>();
  src->path = path;
  src->text = text;
  src->line_starts.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') src->line_starts.push_back(i + 1);
  const pugi::xml_parse_result ok = src->doc.load_buffer(src->text.data(), src->text.size());
  if (!ok)
    throw InputError(path, fmt::format("line {}", src->line(ok.offset)),
                     fmt::format("malformed XML: {}", ok.description()));
  const pugi::xml_node root = src->doc.document_element();
  if (std::string(root.name()) != "scene")
    throw InputError(path, fmt::format("line {}", src->line(root.offset_debug())),
                     fmt::format("the root element is <{}>, expected <scene>", root.name()));
  sources_.push_back(std::move(src));
  const Source& s = *sources_.back();
  if (!root.attribute("version"))
    fail(root, "missing the version attribute (Mitsuba requires one, e.g. version=\"3.0.0\")");
  const std::string version = root.attribute("version").value();
  const std::string major = version.substr(0, version.find('.'));
  const bool digits = !major.empty() && major.size() < 4 &&
                      std::all_of(version.begin(), version.end(), [](char c) {
                        return std::isdigit(static_cast<unsigned char>(c)) || c == '.';
                      });
  const int m = digits ? std::atoi(major.c_str()) : -1;
  if (m != 0 && m != 2 && m != 3)
    fail(root, fmt::format("unsupported Mitsuba version '{}' (this importer reads 0.4-0.6, 2.x "
                           "and 3.x scene files)",
                           version));
  return s;
}

void Document::expand(const Source& src, int depth, bool read_includes, Notes& notes) {
  for (pugi::xml_node child : src.doc.document_element().children()) {
    if (child.type() != pugi::node_element) continue;
    substitute(child, src);
    const std::string tag = child.name();
    if (tag == "default") continue;  // read up front
    if (tag != "include") {
      top_level_.push_back(child);
      continue;
    }
    const std::string file = child.attribute("filename").value();
    if (file.empty()) fail(child, "an <include> needs a filename attribute");
    if (!read_includes) {
      notes.add("<include> not read (files are not read in this mode)", file);
      continue;
    }
    if (depth + 1 > kMaxIncludeDepth)
      fail(child, fmt::format("includes nest deeper than {} files (does a file include itself?)",
                              kMaxIncludeDepth));
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file)
                                                       : fs::path(folderOf(child)) / file;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) fail(child, fmt::format("'{}': file not found", path.string()));
    const Source& sub = load(readTextFile(path.string()), path.string());
    for (pugi::xml_node d : sub.doc.document_element().children("default"))
      parameters_.emplace(d.attribute("name").value(), d.attribute("value").value());
    expand(sub, depth + 1, read_includes, notes);
  }
}

void Document::substitute(pugi::xml_node node, const Source& src) const {
  for (pugi::xml_attribute a : node.attributes()) {
    const std::string value = a.value();
    if (value.find('$') == std::string::npos) continue;
    std::string out;
    for (size_t i = 0; i < value.size(); ++i) {
      size_t j = i + 1;
      while (value[i] == '$' && j < value.size() &&
             (std::isalnum(static_cast<unsigned char>(value[j])) || value[j] == '_'))
        ++j;
      if (value[i] != '$' || j == i + 1) {
        out += value[i];
        continue;
      }
      const std::string name = value.substr(i + 1, j - i - 1);
      auto it = parameters_.find(name);
      if (it == parameters_.end())
        fail(node, fmt::format("undefined parameter '${}' in {}=\"{}\" (declare it with "
                               "<default name=\"{}\" value=\"...\"/>)",
                               name, a.name(), value, name));
      out += it->second;
      i = j - 1;
    }
    a.set_value(out.c_str());
  }
  for (pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element) substitute(child, src);
}

void Document::indexIds() {
  std::vector<pugi::xml_node> stack(top_level_.rbegin(), top_level_.rend());
  while (!stack.empty()) {
    const pugi::xml_node n = stack.back();
    stack.pop_back();
    const std::string id = n.attribute("id").value();
    if (!id.empty() && std::string(n.name()) != "ref") {
      auto [it, inserted] = ids_.emplace(id, n);
      if (!inserted)
        fail(n, fmt::format("duplicate id '{}' (already used at {})", id, where(it->second)));
    }
    for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
      if (c.type() == pugi::node_element) stack.push_back(c);
  }
}

pugi::xml_node Document::byId(const std::string& id) const {
  auto it = ids_.find(id);
  return it == ids_.end() ? pugi::xml_node() : it->second;
}

const Document::Source* Document::sourceOf(pugi::xml_node node) const {
  const pugi::xml_node root = node.root();
  for (const auto& s : sources_)
    if (s->doc == root) return s.get();
  return nullptr;
}

const std::string& Document::fileOf(pugi::xml_node node) const {
  const Source* s = sourceOf(node);
  return s ? s->path : sources_.front()->path;
}

std::string Document::folderOf(pugi::xml_node node) const {
  return fs::path(fileOf(node)).parent_path().string();
}

std::string Document::where(pugi::xml_node node) const {
  std::string attrs;
  for (const char* key : {"type", "name", "id"})
    if (node.attribute(key)) attrs += fmt::format(" {}=\"{}\"", key, node.attribute(key).value());
  const Source* s = sourceOf(node);
  const int line = s ? s->line(node.offset_debug()) : 0;
  const std::string tag = fmt::format("<{}{}>", node.name(), attrs);
  return line > 0 ? fmt::format("line {} {}", line, tag) : tag;
}

void Document::fail(pugi::xml_node node, const std::string& problem) const {
  throw InputError(fileOf(node), where(node), problem);
}

void Document::markUsed(pugi::xml_node node) const {
  const void* p = node.internal_object();
  auto it = std::lower_bound(used_.begin(), used_.end(), p);
  if (it == used_.end() || *it != p) used_.insert(it, p);
}

bool Document::used(pugi::xml_node node) const {
  return std::binary_search(used_.begin(), used_.end(),
                            static_cast<const void*>(node.internal_object()));
}

// --- Plugin --------------------------------------------------------------------------------

pugi::xml_node Plugin::find(const std::string& name, bool mark) const {
  pugi::xml_node found;
  for (pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element || !c.attribute("name")) continue;
    if (snakeCase(c.attribute("name").value()) != name) continue;
    if (found)
      doc_->fail(c, fmt::format("property '{}' is given twice (also at {})", name,
                                doc_->where(found)));
    found = c;
  }
  if (found && mark) doc_->markUsed(found);
  return found;
}

pugi::xml_node Plugin::resolve(pugi::xml_node ref) const {
  const std::string id = ref.attribute("id").value();
  if (id.empty()) doc_->fail(ref, "a <ref> needs an id attribute");
  const pugi::xml_node target = doc_->byId(id);
  if (!target) doc_->fail(ref, fmt::format("no element has id '{}'", id));
  return target;
}

namespace {

std::string valueOf(const Document& doc, pugi::xml_node n) {
  if (!n.attribute("value")) doc.fail(n, "missing the value attribute");
  return n.attribute("value").value();
}

double numberAttr(const Document& doc, pugi::xml_node n, const char* attr) {
  auto v = parseNumber(n.attribute(attr).value());
  if (!v)
    doc.fail(n, fmt::format("{}=\"{}\": expected a finite number", attr, n.attribute(attr).value()));
  return *v;
}

/// x/y/z attributes (each defaulting to `fallback`) or value="x y z".
Vec3 xyz(const Document& doc, pugi::xml_node n, double fallback, bool uniform_value = false) {
  if (n.attribute("value")) {
    auto v = parseNumbers(n.attribute("value").value());
    if (v && v->size() == 1 && uniform_value) return Vec3::Constant((*v)[0]);
    if (!v || v->size() != 3)
      doc.fail(n, fmt::format("value=\"{}\": expected three numbers 'x, y, z'",
                              n.attribute("value").value()));
    return {(*v)[0], (*v)[1], (*v)[2]};
  }
  Vec3 out = Vec3::Constant(fallback);
  const char* keys[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (n.attribute(keys[k])) out[k] = numberAttr(doc, n, keys[k]);
  return out;
}

Vec3 vec3Attr(const Document& doc, pugi::xml_node n, const char* attr) {
  auto v = parseNumbers(n.attribute(attr).value());
  if (!v || v->size() != 3)
    doc.fail(n, fmt::format("{}=\"{}\": expected three numbers 'x, y, z'", attr,
                            n.attribute(attr).value()));
  return {(*v)[0], (*v)[1], (*v)[2]};
}

/// Mitsuba's Transform::lookAt: columns (up x dir, dir x left, dir, origin): the camera looks
/// along its +z with +y up.
Mat4 lookAt(const Document& doc, pugi::xml_node n) {
  const Vec3 origin = vec3Attr(doc, n, "origin"), target = vec3Attr(doc, n, "target");
  const Vec3 d = target - origin;
  if (!(d.norm() > 1e-12)) doc.fail(n, "origin and target are the same point");
  const Vec3 dir = d.normalized();
  Vec3 up = n.attribute("up") ? vec3Attr(doc, n, "up") : Vec3::UnitY();
  if (!n.attribute("up") && std::abs(dir.y()) > 0.999) up = Vec3::UnitZ();
  const Vec3 left = up.cross(dir);
  if (!(left.norm() > 1e-9)) doc.fail(n, "up is parallel to the viewing direction (or zero)");
  Mat4 m = Mat4::Identity();
  m.block<3, 1>(0, 0) = left.normalized();
  m.block<3, 1>(0, 1) = dir.cross(left.normalized());
  m.block<3, 1>(0, 2) = dir;
  m.block<3, 1>(0, 3) = origin;
  return m;
}

Mat4 transformOp(const Document& doc, pugi::xml_node n) {
  const std::string tag = n.name();
  if (tag == "translate") return translation(xyz(doc, n, 0.0));
  if (tag == "scale") {
    Mat4 m = Mat4::Identity();
    m.block<3, 3>(0, 0) = xyz(doc, n, 1.0, true).asDiagonal();
    return m;
  }
  if (tag == "rotate") {
    const Vec3 axis = xyz(doc, n, 0.0);
    if (!(axis.norm() > 1e-12)) doc.fail(n, "the rotation axis is zero");
    if (!n.attribute("angle")) doc.fail(n, "missing the angle attribute (degrees)");
    const double angle = numberAttr(doc, n, "angle") * kPi / 180.0;
    Mat4 m = Mat4::Identity();
    m.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
    return m;
  }
  if (tag == "matrix") {
    auto v = parseNumbers(valueOf(doc, n));
    if (!v || (v->size() != 16 && v->size() != 9))
      doc.fail(n, "value: expected 16 numbers (4x4, row by row) or 9 (3x3)");
    Mat4 m = Mat4::Identity();
    const int k = v->size() == 16 ? 4 : 3;
    for (int r = 0; r < k; ++r)
      for (int c = 0; c < k; ++c) m(r, c) = (*v)[r * k + c];
    return m;
  }
  if (tag == "lookat" || tag == "lookAt") return lookAt(doc, n);
  doc.fail(n, "unknown transform operation (valid: translate, rotate, scale, matrix, lookat)");
}

}  // namespace

double Plugin::number(const std::string& name, double fallback) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return fallback;
  const std::string tag = n.name();
  if (tag != "float" && tag != "integer")
    doc_->fail(n, fmt::format("'{}' must be a <float>, got <{}>", name, tag));
  return numberAttr(*doc_, n, "value");
}

int Plugin::integer(const std::string& name, int fallback) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return fallback;
  const double v = numberAttr(*doc_, n, "value");
  if (std::string(n.name()) != "integer" || v != std::floor(v) || std::abs(v) > 1e9)
    doc_->fail(n, fmt::format("'{}' must be an <integer>", name));
  return static_cast<int>(v);
}

bool Plugin::boolean(const std::string& name, bool fallback) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return fallback;
  const std::string v = lower(trim(valueOf(*doc_, n)));
  if (std::string(n.name()) != "boolean" || (v != "true" && v != "false"))
    doc_->fail(n, fmt::format("'{}' must be a <boolean> with value true or false", name));
  return v == "true";
}

std::string Plugin::string(const std::string& name, const std::string& fallback) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return fallback;
  if (std::string(n.name()) != "string")
    doc_->fail(n, fmt::format("'{}' must be a <string>, got <{}>", name, n.name()));
  return valueOf(*doc_, n);
}

Vec3 Plugin::vector(const std::string& name, const Vec3& fallback) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return fallback;
  const std::string tag = n.name();
  if (tag != "vector" && tag != "point")
    doc_->fail(n, fmt::format("'{}' must be a <vector> or <point>, got <{}>", name, tag));
  return xyz(*doc_, n, 0.0);
}

Mat4 Plugin::transform(const std::string& name) const {
  const pugi::xml_node n = find(name, true);
  if (!n) return Mat4::Identity();
  if (std::string(n.name()) != "transform")
    doc_->fail(n, fmt::format("'{}' must be a <transform>, got <{}>", name, n.name()));
  Mat4 m = Mat4::Identity();
  for (pugi::xml_node op : n.children())
    if (op.type() == pugi::node_element) m = transformOp(*doc_, op) * m;
  if (!m.allFinite()) doc_->fail(n, "the transform is not finite");
  return m;
}

Slot Plugin::slot(const std::string& name, const Vec3f& fallback, Notes& notes) const {
  Slot s;
  s.value = fallback;
  pugi::xml_node n = find(name, true);
  if (!n) return s;
  s.given = true;
  const std::string tag = n.name();
  if (tag == "texture" || tag == "ref") {
    const pugi::xml_node target = tag == "ref" ? resolve(n) : n;
    if (std::string(target.name()) != "texture")
      doc_->fail(n, fmt::format("'{}' refers to a <{}>, expected a <texture>", name,
                                target.name()));
    s.texture = std::make_shared<Plugin>(*doc_, target);
    return s;
  }
  if (tag == "float") {
    s.value = Vec3f::Constant(static_cast<float>(numberAttr(*doc_, n, "value")));
  } else if (tag == "rgb" || tag == "srgb") {
    const std::string text = valueOf(*doc_, n);
    if (auto hex = parseHex(text)) {
      s.value = *hex;
      return s;
    }
    auto v = parseNumbers(text);
    if (!v || (v->size() != 1 && v->size() != 3))
      doc_->fail(n, fmt::format("value=\"{}\": expected 'r, g, b' or one number", text));
    const Vec3 c = v->size() == 1 ? Vec3::Constant((*v)[0]) : Vec3((*v)[0], (*v)[1], (*v)[2]);
    s.value = tag == "srgb" ? Vec3(srgbEotf(c.x()), srgbEotf(c.y()), srgbEotf(c.z()))
                                  .cast<float>()
                            : c.cast<float>();
  } else if (tag == "spectrum") {
    if (!n.attribute("value")) {
      notes.add("spectrum without a value (file or plugin) not read: the default is used", where());
      return s;
    }
    const std::string text = valueOf(*doc_, n);
    if (auto v = parseNumber(text)) {
      s.value = Vec3f::Constant(static_cast<float>(*v));
      return s;
    }
    std::vector<std::pair<double, double>> pairs;
    for (const std::string& item : splitCommas(text)) {
      const size_t colon = item.find(':');
      const auto numbers = colon == std::string::npos
                               ? std::nullopt
                               : parseNumbers(item.substr(0, colon) + " " + item.substr(colon + 1));
      if (!numbers || numbers->size() != 2)
        doc_->fail(n, fmt::format("value=\"{}\": expected one number or 'nm:value' pairs", text));
      pairs.emplace_back((*numbers)[0], (*numbers)[1]);
    }
    if (pairs.empty()) doc_->fail(n, "value: empty spectrum");
    s.value = spectrumToRgb(pairs);
  } else if (tag == "blackbody") {
    std::string t = trim(n.attribute("temperature").value());
    if (!t.empty() && (t.back() == 'K' || t.back() == 'k')) t.pop_back();
    auto kelvin = parseNumber(t);
    if (!kelvin || *kelvin < 1000 || *kelvin > 40000)
      doc_->fail(n, "temperature: expected 1000..40000 (kelvin)");
    const double scale = n.attribute("scale") ? numberAttr(*doc_, n, "scale") : 1.0;
    s.value = blackbodyRgb(*kelvin) * static_cast<float>(scale);
  } else {
    doc_->fail(n, fmt::format("'{}' must be a colour (<rgb>, <srgb>, <spectrum>, <float>, "
                              "<blackbody>) or a <texture>, got <{}>",
                              name, tag));
  }
  if (!s.value.allFinite()) doc_->fail(n, "the colour is not finite");
  return s;
}

std::vector<Plugin> Plugin::children(const std::string& tag) const {
  std::vector<Plugin> out;
  for (pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element) continue;
    if (c.name() == tag) {
      doc_->markUsed(c);
      out.emplace_back(*doc_, c);
    } else if (std::string(c.name()) == "ref") {
      const pugi::xml_node target = resolve(c);
      if (target.name() != tag) continue;
      doc_->markUsed(c);
      out.emplace_back(*doc_, target);
    }
  }
  return out;
}

std::vector<std::string> Plugin::unused() const {
  std::vector<std::string> out;
  for (pugi::xml_node c : node_.children())
    if (c.type() == pugi::node_element && c.attribute("name") && !doc_->used(c))
      out.push_back(snakeCase(c.attribute("name").value()));
  return out;
}

namespace {

/// Mitsuba's table of named indices of refraction (its documentation of the dielectric plugin).
const std::vector<std::pair<const char*, double>>& iorTable() {
  static const std::vector<std::pair<const char*, double>> table = {
      {"vacuum", 1.0},        {"helium", 1.00004},        {"hydrogen", 1.00013},
      {"air", 1.00028},       {"carbon dioxide", 1.00045}, {"water", 1.3330},
      {"acetone", 1.36},      {"ethanol", 1.361},          {"carbon tetrachloride", 1.461},
      {"glycerol", 1.4729},   {"benzene", 1.501},          {"silicone oil", 1.52045},
      {"bromine", 1.661},     {"water ice", 1.31},         {"fused quartz", 1.458},
      {"pyrex", 1.470},       {"acrylic glass", 1.49},     {"polypropylene", 1.49},
      {"bk7", 1.5046},        {"sodium chloride", 1.544},  {"amber", 1.55},
      {"pet", 1.5750},        {"diamond", 2.419}};
  return table;
}

}  // namespace

std::optional<double> namedIor(const std::string& name) {
  const std::string key = lower(trim(name));
  for (const auto& [n, v] : iorTable())
    if (key == n) return v;
  return std::nullopt;
}

std::string namedIorList() {
  std::string out;
  for (const auto& [n, v] : iorTable()) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

}  // namespace inet::mitsuba
