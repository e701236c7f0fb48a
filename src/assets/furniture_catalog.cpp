#include "assets/furniture_catalog.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "assets/java_properties.h"
#include "assets/zip_archive.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

/// Reads the keys of one piece, naming "key#N" in errors.
class PieceKeys {
 public:
  PieceKeys(const JavaProperties& props, int index, const std::string& archive)
      : props_(props), index_(index), archive_(archive) {}

  std::string key(const std::string& name) const { return fmt::format("{}#{}", name, index_); }
  const std::string* find(const std::string& name) const {
    auto it = props_.find(key(name));
    return it == props_.end() ? nullptr : &it->second;
  }
  std::string text(const std::string& name, bool required) const {
    const std::string* v = find(name);
    if (!v || v->empty()) {
      if (required) throw InputError(archive_, key(name), "missing");
      return {};
    }
    return *v;
  }
  /// Numbers separated by blanks (light sources and sashes list one value per element).
  std::vector<double> numbers(const std::string& name) const {
    std::vector<double> out;
    const std::string* v = find(name);
    if (!v) return out;
    std::istringstream in(*v);
    std::string tok;
    while (in >> tok) {
      double x = 0;
      const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), x);
      if (ec != std::errc() || end != tok.data() + tok.size() || !std::isfinite(x))
        throw InputError(archive_, key(name), fmt::format("'{}' is not a number", tok));
      out.push_back(x);
    }
    return out;
  }
  std::optional<double> number(const std::string& name) const {
    const auto v = numbers(name);
    if (v.empty()) return std::nullopt;
    if (v.size() != 1) throw InputError(archive_, key(name), "expected one number");
    return v[0];
  }
  double positive(const std::string& name) const {
    const auto v = number(name);
    if (!v) throw InputError(archive_, key(name), "missing");
    if (!(*v > 0)) throw InputError(archive_, key(name), fmt::format("{} is not > 0", *v));
    return *v;
  }
  bool flag(const std::string& name, bool fallback) const {
    const std::string* v = find(name);
    if (!v) return fallback;
    if (*v == "true") return true;
    if (*v == "false") return false;
    throw InputError(archive_, key(name), fmt::format("'{}' is not true or false", *v));
  }
  [[noreturn]] void fail(const std::string& name, const std::string& problem) const {
    throw InputError(archive_, key(name), problem);
  }

 private:
  const JavaProperties& props_;
  int index_;
  const std::string& archive_;
};

Vec3f parseHexColor(const std::string& s, const PieceKeys& keys, const std::string& name) {
  std::string hex = s;
  if (!hex.empty() && hex[0] == '#') hex = hex.substr(1);
  unsigned v = 0;
  const auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
  if (ec != std::errc() || end != hex.data() + hex.size() || (hex.size() != 6 && hex.size() != 8))
    keys.fail(name, fmt::format("'{}' is not a colour #RRGGBB", s));
  return Vec3f(float((v >> 16) & 0xFF), float((v >> 8) & 0xFF), float(v & 0xFF)) / 255.f;
}

std::vector<std::string> splitTags(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string tok;
  while (std::getline(in, tok, ',')) {
    const auto b = tok.find_first_not_of(' ');
    const auto e = tok.find_last_not_of(' ');
    if (b != std::string::npos) out.push_back(tok.substr(b, e - b + 1));
  }
  return out;
}

std::vector<CatalogLightSource> readLights(const PieceKeys& keys) {
  const auto x = keys.numbers("lightSourceX"), y = keys.numbers("lightSourceY"),
             z = keys.numbers("lightSourceZ"), d = keys.numbers("lightSourceDiameter");
  if (x.size() != y.size() || x.size() != z.size())
    keys.fail("lightSourceX",
              fmt::format("{} x, {} y and {} z coordinates", x.size(), y.size(), z.size()));
  std::vector<std::string> colors;
  if (const std::string* c = keys.find("lightSourceColor")) {
    std::istringstream in(*c);
    std::string tok;
    while (in >> tok) colors.push_back(tok);
  }
  if (!colors.empty() && colors.size() != x.size())
    keys.fail("lightSourceColor", fmt::format("{} colours for {} lights", colors.size(), x.size()));
  if (!d.empty() && d.size() != x.size())
    keys.fail("lightSourceDiameter", fmt::format("{} diameters for {} lights", d.size(), x.size()));
  std::vector<CatalogLightSource> out(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    out[i].position_cm = {x[i], y[i], z[i]};
    if (!colors.empty()) out[i].color = parseHexColor(colors[i], keys, "lightSourceColor");
    if (!d.empty()) out[i].diameter_cm = d[i];
  }
  return out;
}

CatalogDoorOrWindow readDoorOrWindow(const PieceKeys& keys) {
  CatalogDoorOrWindow dw;
  dw.cut_out_shape = keys.text("doorOrWindowCutOutShape", false);
  dw.wall_thickness_cm = keys.number("doorOrWindowWallThickness").value_or(0.0);
  dw.wall_distance_cm = keys.number("doorOrWindowWallDistance").value_or(0.0);
  const auto xs = keys.numbers("doorOrWindowSashXAxis"), ys = keys.numbers("doorOrWindowSashYAxis"),
             ws = keys.numbers("doorOrWindowSashWidth"),
             a0 = keys.numbers("doorOrWindowSashStartAngle"),
             a1 = keys.numbers("doorOrWindowSashEndAngle");
  if (ys.size() != xs.size() || ws.size() != xs.size() || a0.size() != xs.size() ||
      a1.size() != xs.size())
    keys.fail("doorOrWindowSashXAxis", "the sash lists differ in length");
  // Angles are written in degrees in the catalogs (e.g. 180 and 270): kept in radians here.
  constexpr double kDeg = M_PI / 180.0;
  for (size_t i = 0; i < xs.size(); ++i)
    dw.sashes.push_back({xs[i], ys[i], ws[i], a0[i] * kDeg, a1[i] * kDeg});
  return dw;
}

Eigen::Matrix3d readRotation(const PieceKeys& keys) {
  const auto v = keys.numbers("modelRotation");
  if (v.empty()) return Eigen::Matrix3d::Identity();
  if (v.size() != 9) keys.fail("modelRotation", fmt::format("{} numbers, not 9", v.size()));
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = v[size_t(r * 3 + c)];
  // Catalogs store rotations to 8 digits: orthonormal to about 1e-6, never a mirror.
  if ((R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
      R.determinant() < 0)
    keys.fail("modelRotation", "not a rotation matrix");
  return R;
}

std::set<int> pieceIndices(const JavaProperties& props) {
  std::set<int> out;
  for (const auto& [k, v] : props) {
    if (k.rfind("id#", 0) != 0) continue;
    int n = 0;
    const auto [end, ec] = std::from_chars(k.data() + 3, k.data() + k.size(), n);
    if (ec == std::errc() && end == k.data() + k.size() && n > 0) out.insert(n);
  }
  return out;
}

}  // namespace

bool CatalogPiece::isInterior() const {
  return category != "Exterior" && category != "Vehicles";
}

FurnitureCatalog readFurnitureCatalog(const std::string& path) {
  const ZipArchive zip(path);
  const JavaProperties props =
      parseJavaProperties(zip.read("PluginFurnitureCatalog.properties", 16u << 20),
                          path + ":PluginFurnitureCatalog.properties");
  FurnitureCatalog cat = catalogFromProperties(
      props, path, [&zip](const std::string& entry) { return zip.find(entry) != nullptr; });
  cat.checksum = zip.contentChecksum();
  return cat;
}

FurnitureCatalog catalogFromProperties(const JavaProperties& props, const std::string& path,
                                       const std::function<bool(const std::string&)>& has_entry) {
  FurnitureCatalog cat;
  cat.path = path;
  auto top = [&](const char* k) {
    auto it = props.find(k);
    return it == props.end() ? std::string() : it->second;
  };
  cat.id = top("id");
  cat.name = top("name");
  cat.license = top("license");
  if (cat.name.empty()) cat.name = fs::path(path).stem().string();
  std::set<std::string> ids;
  for (int n : pieceIndices(props)) {
    const PieceKeys keys(props, n, path);
    CatalogPiece p;
    p.index = n;
    p.id = keys.text("id", true);
    if (!ids.insert(p.id).second) keys.fail("id", fmt::format("id '{}' used twice", p.id));
    p.name = keys.text("name", true);
    p.category = keys.text("category", true);
    p.tags = splitTags(keys.text("tags", false));
    p.creator = keys.text("creator", false);
    p.license = keys.text("license", false);
    if (p.license.empty()) p.license = cat.license;
    p.model = keys.text("model", true);
    if (!p.model.empty() && p.model[0] == '/') p.model = p.model.substr(1);
    if (!has_entry(p.model)) keys.fail("model", fmt::format("'{}' is not in the archive", p.model));
    p.multi_part = keys.flag("multiPartModel", false);
    p.width_cm = keys.positive("width");
    p.depth_cm = keys.positive("depth");
    p.height_cm = keys.positive("height");
    p.elevation_cm = keys.number("elevation").value_or(0.0);
    p.drop_on_top_elevation = keys.number("dropOnTopElevation").value_or(-1.0);
    p.model_rotation = readRotation(keys);
    p.movable = keys.flag("movable", true);
    p.back_face_shown = keys.flag("backFaceShown", false);
    if (keys.flag("doorOrWindow", false)) p.door_or_window = readDoorOrWindow(keys);
    p.lights = readLights(keys);
    p.staircase_cut_out_shape = keys.text("staircaseCutOutShape", false);
    cat.pieces.push_back(std::move(p));
  }
  if (cat.pieces.empty()) throw InputError(path, "id#1", "the catalog lists no furniture");
  return cat;
}

std::string catalogDir(const std::string& override_dir) {
  if (!override_dir.empty()) return override_dir;
  if (const char* env = std::getenv("INTERIORNET_CATALOG"); env && *env) return env;
  return "/usr/share/sweethome3d/furniture";
}

std::vector<FurnitureCatalog> readFurnitureCatalogs(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(dir, "",
                     "no such catalogs folder (install sweethome3d-furniture, or give "
                     "--catalog DIR)");
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".sh3f") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(dir, "", "holds no .sh3f catalog");
  std::vector<FurnitureCatalog> out;
  std::set<std::string> ids;
  for (const auto& f : files) {
    out.push_back(readFurnitureCatalog(f));
    for (const auto& p : out.back().pieces)
      if (!ids.insert(p.id).second)
        throw InputError(f, fmt::format("id#{}", p.index),
                         fmt::format("id '{}' is also in another catalog", p.id));
  }
  return out;
}

}  // namespace inet
