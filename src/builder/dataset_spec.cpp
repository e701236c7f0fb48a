#include "builder/dataset_spec.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/format_writer.h"
#include "render/passes.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using Keys = std::vector<std::string>;

std::string join(const Keys& keys) {
  std::string out;
  for (size_t i = 0; i < keys.size(); ++i) out += (i ? ", " : "") + keys[i];
  return out;
}

/// A value of the spec with where it is: its dotted key path and its line (1-based; 0 when
/// unknown, e.g. for a JSON spec stored inside a plan, which is one line).
struct Value {
  YAML::Node node;
  std::string path;
  int line = 0;
};

/// The line of `node`, or `fallback` when it has none (an empty value "key:" is a null node
/// whose mark is that of the next token, so its key's line is the better answer).
int lineOf(const YAML::Node& node, int fallback) {
  if (node.IsNull() || node.Mark().line < 0) return fallback;
  return node.Mark().line + 1;
}

/// Whether a scalar was written as text: quoted or tagged !!str. A quoted "12" is a string;
/// taking it as a number would hide a type error in a JSON spec.
bool quoted(const YAML::Node& n) {
  return n.Tag() != "?" && n.Tag() != "tag:yaml.org,2002:int" &&
         n.Tag() != "tag:yaml.org,2002:float" && n.Tag() != "tag:yaml.org,2002:bool";
}

/// "a list", "a map", "nothing", "text 'abc'": what a node is, for messages.
std::string describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Scalar: {
      std::string s = n.Scalar();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return (quoted(n) ? "the text \"" : "'") + s + (quoted(n) ? "\"" : "'");
    }
    default:
      return "nothing";
  }
}

/// Typed access to the parsed YAML; every failure names the file, the key path and the line.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  static std::string located(const std::string& path, int line) {
    return line > 0 ? fmt::format("{} (line {})", path, line) : path;
  }
  [[noreturn]] void fail(const Value& v, const std::string& problem) const {
    throw InputError(file_, located(v.path, v.line), problem);
  }

  /// The entries of map `v`, checked: a map, scalar keys, no duplicates, only `keys`.
  std::map<std::string, Value> map(const Value& v, const Keys& keys) const {
    if (!v.node.IsMap())
      fail(v, "expected a map (keys: " + join(keys) + "), got " + describe(v.node));
    std::map<std::string, Value> out;
    for (auto it = v.node.begin(); it != v.node.end(); ++it) {
      const int key_line = lineOf(it->first, v.line);
      if (!it->first.IsScalar())
        fail({it->first, v.path, key_line}, "keys must be plain names, got " + describe(it->first));
      const std::string key = it->first.Scalar();
      const std::string path = v.path.empty() ? key : v.path + "." + key;
      if (std::find(keys.begin(), keys.end(), key) == keys.end())
        fail({it->first, path, key_line}, "unknown key '" + key + "' (valid: " + join(keys) + ")");
      if (out.count(key)) fail({it->first, path, key_line}, "the key is given twice");
      out.emplace(key, Value{it->second, path, lineOf(it->second, key_line)});
    }
    return out;
  }

  /// The elements of list `v` (field "path[i]").
  std::vector<Value> list(const Value& v) const {
    if (!v.node.IsSequence()) fail(v, "expected a list, got " + describe(v.node));
    std::vector<Value> out;
    for (size_t i = 0; i < v.node.size(); ++i)
      out.push_back({v.node[i], fmt::format("{}[{}]", v.path, i), lineOf(v.node[i], v.line)});
    return out;
  }

  int64_t integer(const Value& v, int64_t lo, int64_t hi) const {
    const std::string& s = plainScalar(v, "an integer");
    int64_t x = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && (x < lo || x > hi)))
      fail(v, fmt::format("{} is outside {}..{}", s, lo, hi));
    if (ec != std::errc() || end != s.data() + s.size())
      fail(v, "expected an integer, got " + describe(v.node));
    return x;
  }

  uint64_t unsignedInteger(const Value& v) const {
    const std::string& s = plainScalar(v, "an integer 0..2^64-1");
    uint64_t x = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (ec == std::errc::result_out_of_range) fail(v, s + " is outside 0..2^64-1");
    if (ec != std::errc() || end != s.data() + s.size())
      fail(v, "expected an integer 0..2^64-1, got " + describe(v.node));
    return x;
  }

  /// A finite number in [lo, hi] (or (lo, hi] with `lo_open`).
  double number(const Value& v, double lo, double hi, bool lo_open = false) const {
    const std::string& s = plainScalar(v, "a number");
    double x = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(x))
      fail(v, "expected a number, got " + describe(v.node));
    if (x > hi || x < lo || (lo_open && x == lo))
      fail(v, fmt::format("{} is outside {}{}, {}]", s, lo_open ? "(" : "[", lo, hi));
    return x;
  }

  bool boolean(const Value& v) const {
    const std::string& s = plainScalar(v, "true or false");
    if (s == "true") return true;
    if (s == "false") return false;
    fail(v, "expected true or false, got " + describe(v.node));
  }

  std::string string(const Value& v) const {
    if (!v.node.IsScalar()) fail(v, "expected a string, got " + describe(v.node));
    return v.node.Scalar();
  }

  /// One of `valid`.
  std::string choice(const Value& v, const Keys& valid) const {
    const std::string s = string(v);
    if (std::find(valid.begin(), valid.end(), s) == valid.end())
      fail(v, "'" + s + "' is not one of " + join(valid));
    return s;
  }

  /// A two-element list [lo, hi] of numbers in [min, max] (or (min, max]) with lo <= hi.
  std::pair<double, double> numberRange(const Value& v, double min, double max,
                                        bool min_open) const {
    const std::vector<Value> items = pair(v);
    const double lo = number(items[0], min, max, min_open);
    const double hi = number(items[1], min, max, min_open);
    if (lo > hi) fail(v, fmt::format("the minimum {} is above the maximum {}", lo, hi));
    return {lo, hi};
  }
  std::pair<int, int> integerRange(const Value& v, int min, int max) const {
    const std::vector<Value> items = pair(v);
    const int lo = static_cast<int>(integer(items[0], min, max));
    const int hi = static_cast<int>(integer(items[1], min, max));
    if (lo > hi) fail(v, fmt::format("the minimum {} is above the maximum {}", lo, hi));
    return {lo, hi};
  }

 private:
  const std::string& plainScalar(const Value& v, const char* what) const {
    if (!v.node.IsScalar() || quoted(v.node))
      fail(v, std::string("expected ") + what + ", got " + describe(v.node));
    return v.node.Scalar();
  }
  std::vector<Value> pair(const Value& v) const {
    std::vector<Value> items = list(v);
    if (items.size() != 2)
      fail(v, fmt::format("expected a list [min, max] of two numbers, got {} items", items.size()));
    return items;
  }

  std::string file_;
};

/// Calls f(value) when `key` is present.
template <class F>
void with(const std::map<std::string, Value>& m, const char* key, F f) {
  const auto it = m.find(key);
  if (it != m.end()) f(it->second);
}

/// A plain folder-safe name: letters, digits, '.', '_', '-', not starting with '.' or '-'.
bool folderSafe(const std::string& s) {
  if (s.empty() || s.size() > 100 || s[0] == '.' || s[0] == '-') return false;
  for (unsigned char c : s)
    if (!std::isalnum(c) && c != '.' && c != '_' && c != '-') return false;
  return true;
}

std::vector<SceneConfiguration> parseConfigurations(const Reader& r, const Value& v) {
  std::vector<SceneConfiguration> out;
  for (const Value& item : r.list(v)) {
    SceneConfiguration c =
        parseSceneConfiguration(r.string(item), r.file(), Reader::located(item.path, item.line));
    for (const SceneConfiguration& o : out)
      if (o.text() == c.text()) r.fail(item, "'" + c.text() + "' is listed twice");
    out.push_back(c);
  }
  if (out.empty()) r.fail(v, "no configuration given (e.g. [original])");
  return out;
}

std::vector<SpecPath> parsePaths(const Reader& r, const Value& v, const fs::path& base) {
  std::vector<SpecPath> out;
  for (const Value& item : r.list(v)) {
    SpecPath p;
    p.given = r.string(item);
    if (p.given.empty()) r.fail(item, "empty path");
    fs::path path(p.given);
    if (path.is_relative()) path = base / path;
    p.resolved = fs::absolute(path).lexically_normal();
    p.field = Reader::located(item.path, item.line);
    for (const SpecPath& o : out)
      if (o.resolved == p.resolved) r.fail(item, "'" + p.given + "' is listed twice");
    out.push_back(std::move(p));
  }
  return out;
}

LayoutsSpec parseLayouts(const Reader& r, const Value& v, const fs::path& base) {
  LayoutsSpec out;
  const auto m = r.map(v, {"procedural", "folders", "front3d"});
  with(m, "procedural", [&](const Value& p) {
    ProceduralLayoutsSpec& s = out.procedural;
    const auto pm = r.map(p, {"count", "first_seed", "rooms", "furniture"});
    with(pm, "count", [&](const Value& x) { s.count = r.integer(x, 0, 100'000'000); });
    with(pm, "first_seed", [&](const Value& x) { s.first_seed = r.unsignedInteger(x); });
    with(pm, "rooms",
         [&](const Value& x) { std::tie(s.rooms_min, s.rooms_max) = r.integerRange(x, 1, 16); });
    with(pm, "furniture", [&](const Value& x) {
      s.furniture = r.choice(x, {"catalog", "parametric", "mixed"});
    });
    if (s.count > 0 &&
        s.first_seed > std::numeric_limits<uint64_t>::max() - static_cast<uint64_t>(s.count - 1))
      r.fail(pm.count("first_seed") ? pm.at("first_seed") : p,
             "first_seed + count - 1 does not fit in 64 bits");
  });
  with(m, "folders", [&](const Value& x) { out.folders = parsePaths(r, x, base); });
  with(m, "front3d", [&](const Value& x) { out.front3d = parsePaths(r, x, base); });
  if (out.procedural.count == 0 && out.folders.empty() && out.front3d.empty())
    r.fail(v, "no layout: give procedural.count > 0, folders or front3d");
  return out;
}

SplitShares parseSplits(const Reader& r, const Value& v) {
  SplitShares s;
  const auto m = r.map(v, {"train", "validation", "test"});
  with(m, "train", [&](const Value& x) { s.train = r.number(x, 0, 1); });
  with(m, "validation", [&](const Value& x) { s.validation = r.number(x, 0, 1); });
  with(m, "test", [&](const Value& x) { s.test = r.number(x, 0, 1); });
  const double sum = s.train + s.validation + s.test;
  if (std::abs(sum - 1.0) > 1e-9)
    r.fail(v, fmt::format("the shares must sum to 1, got {:.10g} (train {} + validation {} + "
                          "test {})",
                          sum, s.train, s.validation, s.test));
  return s;
}

SequencesSpec parseSequences(const Reader& r, const Value& v) {
  SequencesSpec s;
  const auto m = r.map(v, {"per_layout", "frames", "fps", "unit_frames", "trajectory", "v_mult",
                           "w_mult", "configurations"});
  with(m, "per_layout", [&](const Value& x) { s.per_layout = r.integer(x, 0, 100'000); });
  with(m, "frames", [&](const Value& x) { s.frames = r.integer(x, 1, 10'000'000); });
  with(m, "fps", [&](const Value& x) { s.fps = r.number(x, 0, 10'000, true); });
  with(m, "unit_frames", [&](const Value& x) { s.unit_frames = r.integer(x, 1, 10'000'000); });
  with(m, "trajectory", [&](const Value& t) {
    const auto tm = r.map(t, {"two-body", "hand-held", "look-forward"});
    with(tm, "two-body", [&](const Value& x) { s.trajectory.two_body = r.number(x, 0, 1e6); });
    with(tm, "hand-held", [&](const Value& x) { s.trajectory.hand_held = r.number(x, 0, 1e6); });
    with(tm, "look-forward",
         [&](const Value& x) { s.trajectory.look_forward = r.number(x, 0, 1e6); });
    if (s.trajectory.two_body + s.trajectory.hand_held + s.trajectory.look_forward <= 0)
      r.fail(t, "every weight is 0: give at least one trajectory type a weight > 0");
  });
  // (0, 100]: what `generate --v-mult/--w-mult` accept
  with(m, "v_mult", [&](const Value& x) {
    std::tie(s.v_mult_min, s.v_mult_max) = r.numberRange(x, 0, 100, true);
  });
  with(m, "w_mult", [&](const Value& x) {
    std::tie(s.w_mult_min, s.w_mult_max) = r.numberRange(x, 0, 100, true);
  });
  with(m, "configurations", [&](const Value& x) { s.configurations = parseConfigurations(r, x); });
  return s;
}

SparseSpec parseSparse(const Reader& r, const Value& v) {
  SparseSpec s;
  const auto m = r.map(v, {"per_layout", "configurations", "batch"});
  with(m, "per_layout", [&](const Value& x) { s.per_layout = r.integer(x, 0, 1); });
  with(m, "configurations", [&](const Value& x) { s.configurations = parseConfigurations(r, x); });
  with(m, "batch", [&](const Value& x) { s.batch = r.integer(x, 1, 1'000'000); });
  return s;
}

CameraSpec parseCamera(const Reader& r, const Value& v) {
  CameraSpec c;
  const auto m = r.map(v, {"width", "height", "fx", "fy", "lens", "stereo"});
  with(m, "lens", [&](const Value& x) {
    // a thin lens needs an aperture and a focus distance, which version 1 does not hold
    if (r.string(x) == "thin_lens")
      r.fail(x,
             "thin_lens is not in version 1 of the spec (no aperture or focus keys); "
             "valid: pinhole, fisheye, panorama");
    c.lens = r.choice(x, {"pinhole", "fisheye", "panorama"});  // render/lens.h's names
  });
  const bool w_set = m.count("width"), h_set = m.count("height");
  with(m, "width", [&](const Value& x) { c.width = r.integer(x, 1, 32768); });
  with(m, "height", [&](const Value& x) { c.height = r.integer(x, 1, 32768); });
  with(m, "fx", [&](const Value& x) { c.fx = r.number(x, 0, 1e6, true); });
  with(m, "fy", [&](const Value& x) { c.fy = r.number(x, 0, 1e6, true); });
  with(m, "stereo", [&](const Value& x) { c.stereo = r.number(x, 0, 10); });
  if (c.lens == "fisheye" || c.lens == "panorama") {
    // as `generate`: the focal length follows from the size; the size from the aspect ratio
    for (const char* k : {"fx", "fy"})
      with(m, k, [&](const Value& x) {
        r.fail(x, "a " + c.lens + "'s focal length follows from its size: leave out fx, fy");
      });
    c.fx = c.fy = 0;
    const int aspect = c.lens == "fisheye" ? 1 : 2;
    if (!w_set && !h_set) {
      c.width = c.lens == "fisheye" ? 600 : 5000;
      c.height = c.width / aspect;
    } else if (!h_set) {
      if (c.width % aspect) r.fail(m.at("width"), "a panorama's width must be even");
      c.height = c.width / aspect;
    } else if (!w_set) {
      c.width = c.height * aspect;
    } else if (c.width != c.height * aspect) {
      r.fail(m.at("height"),
             fmt::format("a {} is {} wide as it is high: height {} for width {}", c.lens,
                         aspect == 1 ? "as" : "twice as", c.width / aspect, c.width));
    }
  }
  return c;
}

RenderSpec parseRender(const Reader& r, const Value& v) {
  RenderSpec s;
  const auto m = r.map(v, {"spp", "denoise", "max_bounces"});
  with(m, "spp", [&](const Value& x) { s.spp = r.integer(x, 1, 1 << 20); });
  with(m, "denoise", [&](const Value& x) { s.denoise = r.boolean(x); });
  with(m, "max_bounces", [&](const Value& x) { s.max_bounces = r.integer(x, 0, 1000); });
  return s;
}

/// `generate --passes` names, one per item: the frame passes (render/frame.h) and the sequence
/// sensors; checks the lens rules `generate` applies to explicit names.
std::vector<std::string> parsePasses(const Reader& r, const Value& v, const CameraSpec& cam) {
  Keys valid = {"default", "all", "imu", "events", "boxes"};
  for (const PassInfo& p : kPassTable) valid.push_back(p.name);
  std::vector<std::string> out;
  for (const Value& item : r.list(v)) {
    const std::string name = r.choice(item, valid);
    if (std::find(out.begin(), out.end(), name) != out.end())
      r.fail(item, "'" + name + "' is listed twice");
    if (name == "events" && cam.lens != "pinhole")
      r.fail(item, "events need a pinhole camera (camera.lens)");
    if (name == "depth_noisy" && cam.lens != "pinhole")
      r.fail(item, "depth_noisy needs a pinhole camera (camera.lens)");
    out.push_back(name);
  }
  if (out.empty()) r.fail(v, "no pass given (e.g. [default])");
  return out;
}

StorageSpec parseStorage(const Reader& r, const Value& v) {
  StorageSpec s;
  const auto m = r.map(v, {"exr_compression", "png_level", "flow", "rgb_exr"});
  // only OpenEXR's lossless codecs: pxr24, b44 and dwa would change float ground truth
  with(m, "exr_compression", [&](const Value& x) {
    s.exr_compression = r.choice(x, {"none", "rle", "zips", "zip", "piz"});
  });
  with(m, "png_level", [&](const Value& x) { s.png_level = r.integer(x, 0, 9); });
  with(m, "flow", [&](const Value& x) {
    s.flow = r.string(x);
    StorageOptions o;  // the sequence writer's own reading of the list, so both agree
    try {
      parseFlowFiles(s.flow, o, "", "");
    } catch (const InputError&) {
      r.fail(x, "'" + s.flow + "' is not a list of flow files (flo, kitti, exr joined by '+', "
                "or both = flo+kitti)");
    }
  });
  with(m, "rgb_exr", [&](const Value& x) { s.rgb_exr = r.choice(x, {"none", "float", "half"}); });
  return s;
}

/// `shards`: pass keys are checked for form only here; which exist depends on the passes,
/// formats and storage, and `dataset shards` checks them against the manifest.
ShardsSpec parseShards(const Reader& r, const Value& v) {
  ShardsSpec s;
  const auto m = r.map(v, {"enabled", "max_mb", "passes"});
  with(m, "enabled", [&](const Value& x) { s.enabled = r.boolean(x); });
  with(m, "max_mb", [&](const Value& x) { s.max_mb = r.number(x, 0.001, 1e7); });
  with(m, "passes", [&](const Value& x) {
    s.passes.clear();
    for (const Value& item : r.list(x)) {
      const std::string p = r.string(item);
      const bool plain = !p.empty() && p[0] != '.' && std::all_of(p.begin(), p.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
      if (!plain)
        r.fail(item, "'" + p +
                         "' is not a pass key of the manifest (e.g. cam0, depth0.exr, "
                         "label0_nyu) or all");
      if (std::find(s.passes.begin(), s.passes.end(), p) != s.passes.end())
        r.fail(item, "'" + p + "' is listed twice");
      s.passes.push_back(p);
    }
    if (s.passes.empty()) r.fail(x, "no pass key given (e.g. [all] or [cam0, depth0])");
    if (s.passes.size() > 1 && std::count(s.passes.begin(), s.passes.end(), "all"))
      r.fail(x, "'all' stands alone: it already holds every pass key");
  });
  return s;
}

DatasetSpec parseRoot(const Reader& r, const YAML::Node& root, const fs::path& base) {
  const Value top{root, "", root.IsNull() ? 0 : lineOf(root, 1)};
  if (!root.IsMap())
    r.fail(top, root.IsNull() ? std::string("the spec is empty (it needs at least version, "
                                            "name and layouts)")
                              : "expected a map of keys at the top, got " + describe(root));
  // the version first: a future version may have other keys, and saying so is the better error
  const Keys keys = {"version", "name",   "seed",   "layouts", "splits",  "sequences", "sparse",
                     "camera",  "render", "passes", "imu",     "formats", "storage",   "shards"};
  for (auto it = root.begin(); it != root.end(); ++it) {
    if (!it->first.IsScalar() || it->first.Scalar() != "version") continue;
    const Value v{it->second, "version", lineOf(it->second, lineOf(it->first, 0))};
    const int64_t version =
        r.integer(v, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    if (version != kDatasetSpecVersion)
      r.fail(v, fmt::format("version {} is not supported (this build reads version {})", version,
                            kDatasetSpecVersion));
  }
  const auto m = r.map(top, keys);
  DatasetSpec s;
  if (!m.count("version"))
    throw InputError(r.file(), "version",
                     fmt::format("missing: the spec must say which version "
                                 "it is written in (version: {})",
                                 kDatasetSpecVersion));
  if (!m.count("name"))
    throw InputError(r.file(), "name", "missing: the dataset needs a name (a folder name)");
  if (!m.count("layouts"))
    throw InputError(r.file(), "layouts",
                     "missing: say which layouts (procedural, folders, front3d)");
  with(m, "name", [&](const Value& x) {
    s.name = r.string(x);
    if (!folderSafe(s.name))
      r.fail(x, "'" + s.name +
                    "' is not a plain folder name (1-100 letters, digits, '.', '_', "
                    "'-', not starting with '.' or '-')");
  });
  with(m, "seed", [&](const Value& x) { s.seed = r.unsignedInteger(x); });
  s.layouts = parseLayouts(r, m.at("layouts"), base);
  with(m, "splits", [&](const Value& x) { s.splits = parseSplits(r, x); });
  with(m, "sequences", [&](const Value& x) { s.sequences = parseSequences(r, x); });
  with(m, "sparse", [&](const Value& x) { s.sparse = parseSparse(r, x); });
  with(m, "camera", [&](const Value& x) { s.camera = parseCamera(r, x); });
  with(m, "render", [&](const Value& x) { s.render = parseRender(r, x); });
  with(m, "passes", [&](const Value& x) { s.passes = parsePasses(r, x, s.camera); });
  with(m, "imu", [&](const Value& x) { s.imu = r.number(x, 0, 100'000); });
  with(m, "formats", [&](const Value& x) {
    s.formats.clear();
    for (const Value& item : r.list(x)) {
      const std::string f = r.choice(item, {"asl", "tum"});
      if (std::find(s.formats.begin(), s.formats.end(), f) != s.formats.end())
        r.fail(item, "'" + f + "' is listed twice");
      s.formats.push_back(f);
    }
    if (s.formats.empty()) r.fail(x, "no format given (asl, tum)");
  });
  with(m, "storage", [&](const Value& x) { s.storage = parseStorage(r, x); });
  with(m, "shards", [&](const Value& x) { s.shards = parseShards(r, x); });
  // what the sequence writer would refuse in every unit of the build, said once here: TUM
  // folders pair colour with depth images
  auto has = [&](const char* pass) {
    for (const std::string& p : s.passes)
      if (p == pass || p == "default" || p == "all") return true;
    return false;
  };
  if (std::find(s.formats.begin(), s.formats.end(), "tum") != s.formats.end() &&
      (!has("rgb") || !has("depth")))
    r.fail(m.count("formats") ? m.at("formats") : m.at("passes"),
           "format 'tum' (a default) needs the rgb and depth passes: add them, or say "
           "formats: [asl]");
  return s;
}

nlohmann::ordered_json configurationsJson(const std::vector<SceneConfiguration>& list) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const SceneConfiguration& c : list) out.push_back(c.text());
  return out;
}

nlohmann::ordered_json pathsJson(const std::vector<SpecPath>& list) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const SpecPath& p : list) out.push_back(p.given);
  return out;
}

}  // namespace

std::string SceneConfiguration::text() const {
  if (kind == Kind::Original) return "original";
  const char* name = kind == Kind::Lighting ? "lighting" : "rearranged";
  return derived ? std::string(name) : fmt::format("{}:{}", name, seed);
}

SceneConfiguration parseSceneConfiguration(const std::string& text, const std::string& file,
                                           const std::string& field) {
  SceneConfiguration c;
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  if (kind == "original" && colon == std::string::npos) return c;
  if (kind != "lighting" && kind != "rearranged")
    throw InputError(file, field, "'" + text + "' is not original, lighting[:N] or rearranged[:N]");
  c.kind = kind == "lighting" ? SceneConfiguration::Kind::Lighting
                              : SceneConfiguration::Kind::Rearranged;
  if (colon == std::string::npos) {
    c.derived = true;
    return c;
  }
  const std::string n = text.substr(colon + 1);
  // at most 9 digits, as `generate --config`, so a configuration reads the same in both
  if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos || n.size() > 9)
    throw InputError(file, field, "'" + text + "': the number after ':' is a seed 0..999999999");
  c.seed = std::stoull(n);
  return c;
}

bool DatasetSpec::operator==(const DatasetSpec& o) const {
  return version == o.version && name == o.name && seed == o.seed && layouts == o.layouts &&
         splits == o.splits && sequences == o.sequences && sparse == o.sparse &&
         camera == o.camera && render == o.render && passes == o.passes && imu == o.imu &&
         formats == o.formats && storage == o.storage && shards == o.shards;
}

uint64_t stableHash64(std::string_view bytes) {
  // Written out here rather than taken from a library (or std::hash): split membership and every
  // draw of a plan are keyed by it, so it must give the same bits forever, on every platform.
  uint64_t h = 0xcbf29ce484222325ull;                            // FNV-1a 64-bit offset basis
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;  // FNV prime
  // splitmix64's finaliser (Steele, Lea, Flood 2014): a bijective avalanche of all 64 bits
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

std::string specChecksum(const std::string& text) {
  return fmt::format("{:016x}", stableHash64(text));
}

DatasetSpec parseDatasetSpecText(const std::string& text, const std::string& name) {
  const Reader r(name);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, fmt::format("line {}, column {}", e.mark.line + 1, e.mark.column + 1),
                     "not valid YAML or JSON: " + e.msg);
  }
  DatasetSpec s = parseRoot(r, root, fs::path(name).parent_path());
  s.file = name;
  s.checksum = specChecksum(text);
  return s;
}

DatasetSpec parseDatasetSpec(const fs::path& file) {
  return parseDatasetSpecText(readTextFile(file), file.string());
}

nlohmann::ordered_json specToJson(const DatasetSpec& s) {
  using J = nlohmann::ordered_json;
  const ProceduralLayoutsSpec& p = s.layouts.procedural;
  const SequencesSpec& q = s.sequences;
  J j;
  j["version"] = s.version;
  j["name"] = s.name;
  j["seed"] = s.seed;
  j["layouts"] = {{"procedural",
                   {{"count", p.count},
                    {"first_seed", p.first_seed},
                    {"rooms", {p.rooms_min, p.rooms_max}},
                    {"furniture", p.furniture}}},
                  {"folders", pathsJson(s.layouts.folders)},
                  {"front3d", pathsJson(s.layouts.front3d)}};
  j["splits"] = {
      {"train", s.splits.train}, {"validation", s.splits.validation}, {"test", s.splits.test}};
  j["sequences"] = {{"per_layout", q.per_layout},
                    {"frames", q.frames},
                    {"fps", q.fps},
                    {"unit_frames", q.unit_frames},
                    {"trajectory",
                     {{"two-body", q.trajectory.two_body},
                      {"hand-held", q.trajectory.hand_held},
                      {"look-forward", q.trajectory.look_forward}}},
                    {"v_mult", {q.v_mult_min, q.v_mult_max}},
                    {"w_mult", {q.w_mult_min, q.w_mult_max}},
                    {"configurations", configurationsJson(q.configurations)}};
  j["sparse"] = {{"per_layout", s.sparse.per_layout},
                 {"configurations", configurationsJson(s.sparse.configurations)},
                 {"batch", s.sparse.batch}};
  J camera = {{"width", s.camera.width}, {"height", s.camera.height}};
  if (s.camera.lens == "pinhole") {  // fisheye and panorama refuse fx, fy
    camera["fx"] = s.camera.fx;
    camera["fy"] = s.camera.fy;
  }
  camera["lens"] = s.camera.lens;
  camera["stereo"] = s.camera.stereo;
  j["camera"] = camera;
  j["render"] = {
      {"spp", s.render.spp}, {"denoise", s.render.denoise}, {"max_bounces", s.render.max_bounces}};
  j["passes"] = s.passes;
  j["imu"] = s.imu;
  j["formats"] = s.formats;
  j["storage"] = {{"exr_compression", s.storage.exr_compression},
                  {"png_level", s.storage.png_level},
                  {"flow", s.storage.flow},
                  {"rgb_exr", s.storage.rgb_exr}};
  j["shards"] = {
      {"enabled", s.shards.enabled}, {"max_mb", s.shards.max_mb}, {"passes", s.shards.passes}};
  return j;
}

}  // namespace inet
