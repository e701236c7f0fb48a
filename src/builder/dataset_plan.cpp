#include "builder/dataset_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

constexpr const char* kPlanFormat = "interiornet-dataset-plan";
constexpr int kPlanVersion = 1;
/// Derived configuration seeds stay below 10^9: `generate --config lighting:N` reads 9 digits.
constexpr double kConfigSeeds = 1e9;
const char* const kMotionNames[] = {"two-body", "hand-held", "look-forward"};

/// The key of a layout's draws: its id's hash split into two 32-bit counter words.
struct LayoutKey {
  uint32_t lo, hi;
  explicit LayoutKey(const std::string& id) {
    const uint64_t h = stableHash64(id);
    lo = static_cast<uint32_t>(h);
    hi = static_cast<uint32_t>(h >> 32);
  }
};

/// Which derived seeds the spec uses: only those are drawn into the plan and written.
struct DerivedUse {
  bool lighting = false, rearranged = false, view = false;
  explicit DerivedUse(const DatasetSpec& s) {
    auto scan = [&](const std::vector<SceneConfiguration>& list) {
      for (const SceneConfiguration& c : list) {
        if (!c.derived) continue;
        lighting |= c.kind == SceneConfiguration::Kind::Lighting;
        rearranged |= c.kind == SceneConfiguration::Kind::Rearranged;
      }
    };
    if (s.sequences.per_layout > 0) scan(s.sequences.configurations);
    if (s.sparse.per_layout > 0) scan(s.sparse.configurations);
    view = s.sparse.per_layout > 0;
  }
};

/// The per-layout draws, always in the same order and number (so that a range or an unused
/// seed never shifts the others): room count, lighting seed, rearranged seed, view seed.
void drawLayout(const DatasetSpec& spec, const DerivedUse& use, PlannedLayout& L) {
  const LayoutKey key(L.id);
  CounterRng rng(spec.seed, RngStream::Layout, key.lo, key.hi, 0);
  const double u_rooms = rng.uniformDouble();
  const uint64_t lighting = static_cast<uint64_t>(rng.uniformDouble() * kConfigSeeds);
  const uint64_t rearranged = static_cast<uint64_t>(rng.uniformDouble() * kConfigSeeds);
  const uint64_t view_hi = rng.nextU32();
  const uint64_t view = (view_hi << 32) | rng.nextU32();
  if (L.kind == LayoutKind::Procedural) {
    const int lo = spec.layouts.procedural.rooms_min, hi = spec.layouts.procedural.rooms_max;
    L.rooms = std::min(hi, lo + static_cast<int>(u_rooms * (hi - lo + 1)));
  }
  L.lighting_seed = use.lighting ? lighting : 0;
  L.rearranged_seed = use.rearranged ? rearranged : 0;
  L.view_seed = use.view ? view : 0;
}

/// Sequence i's draws from its own stream: trajectory type by weight, v_mult, w_mult, seed.
PlannedSequence drawSequence(const DatasetSpec& spec, const LayoutKey& key, int i) {
  const SequencesSpec& q = spec.sequences;
  CounterRng rng(spec.seed, RngStream::Trajectory, key.lo, key.hi, static_cast<uint32_t>(i));
  PlannedSequence s;
  s.name = fmt::format("seq_{:03d}", i);
  const double weights[] = {q.trajectory.two_body, q.trajectory.hand_held,
                            q.trajectory.look_forward};
  const double x = rng.uniformDouble() * (weights[0] + weights[1] + weights[2]);
  double cum = 0;
  int type = -1;
  for (int t = 0; t < 3; ++t) {
    cum += weights[t];
    if (weights[t] > 0) {
      type = t;  // the last type with a weight, should rounding leave x above the sum
      if (x < cum) break;
    }
  }
  s.trajectory = kMotionNames[type];
  s.v_mult = rng.uniformDouble(q.v_mult_min, q.v_mult_max);
  s.w_mult = rng.uniformDouble(q.w_mult_min, q.w_mult_max);
  const uint64_t hi = rng.nextU32();
  s.seed = (hi << 32) | rng.nextU32();
  return s;
}

/// Counts the elements of the array at `path` (a chain of object keys from the root) while
/// parsing, and stops there: the room count of a layout file without building its DOM.
class ArrayCounter : public nlohmann::json_sax<json> {
 public:
  explicit ArrayCounter(std::vector<std::string> path) : path_(std::move(path)) {}
  int64_t count = 0;
  bool found = false, done = false;
  std::string error;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    value();
    stack_.push_back({false, {}});
    return true;
  }
  bool key(string_t& k) override {
    stack_.back().key = k;
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    value();
    stack_.push_back({true, {}});
    if (inTarget()) found = true;
    return true;
  }
  bool end_array() override {
    if (inTarget()) {
      done = true;
      return false;  // the rest of the file is not needed
    }
    stack_.pop_back();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    error = e.what();
    return false;
  }

 private:
  struct Level {
    bool array;
    std::string key;
  };
  bool inTarget() const {
    if (stack_.size() != path_.size() + 1 || !stack_.back().array) return false;
    for (size_t i = 0; i < path_.size(); ++i)
      if (stack_[i].array || stack_[i].key != path_[i]) return false;
    return true;
  }
  bool value() {
    if (inTarget()) ++count;
    return true;
  }
  std::vector<std::string> path_;
  std::vector<Level> stack_;
};

/// The length of the array at `path` in JSON file `file`; 0 if there is none.
int countRooms(const std::string& file, const std::vector<std::string>& path) {
  const std::string text = readTextFile(file);
  ArrayCounter counter(path);
  json::sax_parse(text, &counter);
  if (!counter.done && !counter.error.empty()) {
    std::string e = counter.error;
    const size_t bracket = e.find("] ");  // "[json.exception.parse_error.101] parse error..."
    if (e.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
      e = e.substr(bracket + 2);
    throw InputError(file, "", "not a JSON layout file: " + e);
  }
  return static_cast<int>(std::min<int64_t>(counter.count, 1'000'000));
}

/// "file:<given>/<name>" with forward slashes, "." and ".." folded.
std::string pathId(const char* prefix, const fs::path& p) {
  return prefix + p.lexically_normal().generic_string();
}

void addFileLayouts(const DatasetSpec& spec, std::vector<PlannedLayout>& out) {
  for (const SpecPath& folder : spec.layouts.folders) {
    std::error_code ec;
    if (!fs::is_directory(folder.resolved, ec))
      throw InputError(spec.file, folder.field, "no such folder: " + folder.resolved.string());
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(folder.resolved, ec))
      if (e.path().extension() == ".json" && fs::is_regular_file(e.path()))
        names.push_back(e.path().filename().string());
    if (ec)
      throw InputError(spec.file, folder.field,
                       "cannot list " + folder.resolved.string() + ": " + ec.message());
    if (names.empty())
      throw InputError(spec.file, folder.field,
                       "no *.json layout file in " + folder.resolved.string());
    std::sort(names.begin(), names.end());  // byte order: the same on every file system
    for (const std::string& name : names) {
      try {  // ids and paths are JSON strings in the plan, which must be UTF-8
        (void)json(name).dump();
      } catch (const json::type_error&) {
        throw InputError(spec.file, folder.field,
                         "the file name of " + (folder.resolved / name).string() +
                             " is not UTF-8 text; rename it");
      }
      PlannedLayout L;
      L.kind = LayoutKind::File;
      L.id = pathId("file:", fs::path(folder.given) / name);
      L.path = (folder.resolved / name).string();
      L.rooms = countRooms(L.path, {"rooms"});  // layout.json: the top-level rooms array
      out.push_back(std::move(L));
    }
  }
  for (const SpecPath& file : spec.layouts.front3d) {
    std::error_code ec;
    if (!fs::is_regular_file(file.resolved, ec))
      throw InputError(spec.file, file.field, "no such file: " + file.resolved.string());
    PlannedLayout L;
    L.kind = LayoutKind::Front3d;
    L.id = pathId("front3d:", file.given);
    L.path = file.resolved.string();
    L.rooms = countRooms(L.path, {"scene", "room"});  // 3D-FRONT: the scene's room entries
    out.push_back(std::move(L));
  }
}

Split splitFromHash(uint64_t h, const SplitShares& s) {
  const double u = static_cast<double>(h >> 11) * 0x1p-53;
  // a share of 0 gets nothing, even when the others sum to 1 - 1e-10
  const double c1 = (s.validation == 0 && s.test == 0) ? 2.0 : s.train;
  const double c2 = s.test == 0 ? 2.0 : s.train + s.validation;
  if (u < c1) return Split::Train;
  if (u < c2) return Split::Validation;
  return Split::Test;
}

int64_t unitsPerSequence(const SequencesSpec& q) {
  return (q.frames + q.unit_frames - 1) / q.unit_frames;
}

/// Digits of the frame numbers in unit ids: 4, or more for longer sequences.
int frameDigits(int frames) {
  int d = 1;
  for (int n = frames - 1; n >= 10; n /= 10) ++d;
  return std::max(4, d);
}

// ---- plan file ----

ojson layoutJson(const PlannedLayout& L, const DerivedUse& use) {
  ojson j;
  j["id"] = L.id;
  j["source"] = layoutKindName(L.kind);
  if (L.kind == LayoutKind::Procedural)
    j["seed"] = L.seed;
  else
    j["path"] = L.path;
  j["rooms"] = L.rooms;
  j["split"] = splitName(L.split);
  j["subset"] = L.subset;
  if (use.lighting) j["lighting_seed"] = L.lighting_seed;
  if (use.rearranged) j["rearranged_seed"] = L.rearranged_seed;
  if (use.view) j["view_seed"] = L.view_seed;
  ojson seqs = ojson::array();
  for (const PlannedSequence& s : L.sequences)
    seqs.push_back({{"name", s.name},
                    {"trajectory", s.trajectory},
                    {"v_mult", s.v_mult},
                    {"w_mult", s.w_mult},
                    {"seed", s.seed}});
  j["sequences"] = std::move(seqs);
  return j;
}

/// JSON indented by 2 with arrays of scalars on one line ("rooms": [1, 8]), as layout files are
/// written (scene/layout_json.h): the plan's header stays short enough to read.
void dumpPretty(const ojson& j, int indent, std::string& out) {
  const std::string pad(static_cast<size_t>(indent) + 2, ' ');
  if (j.is_object() && !j.empty()) {
    out += "{\n";
    size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      out += pad + ojson(it.key()).dump() + ": ";
      dumpPretty(it.value(), indent + 2, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += std::string(static_cast<size_t>(indent), ' ') + "}";
  } else if (j.is_array() &&
             std::any_of(j.begin(), j.end(), [](const ojson& e) { return e.is_structured(); })) {
    out += "[\n";
    for (size_t i = 0; i < j.size(); ++i) {
      out += pad;
      dumpPretty(j[i], indent + 2, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += std::string(static_cast<size_t>(indent), ' ') + "]";
  } else if (j.is_array()) {
    out += "[";
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
    out += "]";
  } else {
    out += j.dump();
  }
}

/// Typed access to a parsed plan; failures name the plan file and the field.
class PlanReader {
 public:
  explicit PlanReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(file_, field, problem);
  }
  const json& at(const json& obj, const std::string& field, const char* key) const {
    if (!obj.is_object()) fail(field, "expected an object");
    const auto it = obj.find(key);
    if (it == obj.end()) fail(field.empty() ? key : field + "." + key, "missing");
    return *it;
  }
  std::string string(const json& obj, const std::string& field, const char* key) const {
    const json& v = at(obj, field, key);
    if (!v.is_string()) fail(dot(field, key), "expected a string");
    return v.get<std::string>();
  }
  uint64_t unsignedInt(const json& obj, const std::string& field, const char* key) const {
    const json& v = at(obj, field, key);
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
      fail(dot(field, key), "expected an integer >= 0");
    return v.get<uint64_t>();
  }
  int64_t integer(const json& obj, const std::string& field, const char* key, int64_t lo,
                  int64_t hi) const {
    const json& v = at(obj, field, key);
    if (!v.is_number_integer()) fail(dot(field, key), "expected an integer");
    if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(hi))
      fail(dot(field, key), fmt::format("outside {}..{}", lo, hi));
    const int64_t x = v.get<int64_t>();
    if (x < lo || x > hi) fail(dot(field, key), fmt::format("{} is outside {}..{}", x, lo, hi));
    return x;
  }
  double number(const json& obj, const std::string& field, const char* key) const {
    const json& v = at(obj, field, key);
    if (!v.is_number()) fail(dot(field, key), "expected a number");
    return v.get<double>();
  }
  static std::string dot(const std::string& field, const char* key) {
    return field.empty() ? key : field + "." + key;
  }

 private:
  std::string file_;
};

PlannedLayout readLayout(const PlanReader& r, const json& j, const std::string& f,
                         const DerivedUse& use) {
  PlannedLayout L;
  L.id = r.string(j, f, "id");
  const std::string source = r.string(j, f, "source");
  if (source == "procedural") {
    L.kind = LayoutKind::Procedural;
    L.seed = r.unsignedInt(j, f, "seed");
  } else if (source == "file" || source == "front3d") {
    L.kind = source == "file" ? LayoutKind::File : LayoutKind::Front3d;
    L.path = r.string(j, f, "path");
  } else {
    r.fail(f + ".source", "'" + source + "' is not procedural, file or front3d");
  }
  L.rooms = static_cast<int>(r.integer(j, f, "rooms", 0, 1'000'000));
  const std::string split = r.string(j, f, "split");
  if (split == "train")
    L.split = Split::Train;
  else if (split == "validation")
    L.split = Split::Validation;
  else if (split == "test")
    L.split = Split::Test;
  else
    r.fail(f + ".split", "'" + split + "' is not train, validation or test");
  L.subset = r.string(j, f, "subset");
  if (L.subset != subsetName(L.rooms))
    r.fail(f + ".subset", "'" + L.subset + "' does not match rooms " + std::to_string(L.rooms));
  if (use.lighting) L.lighting_seed = r.unsignedInt(j, f, "lighting_seed");
  if (use.rearranged) L.rearranged_seed = r.unsignedInt(j, f, "rearranged_seed");
  if (use.view) L.view_seed = r.unsignedInt(j, f, "view_seed");
  const json& seqs = r.at(j, f, "sequences");
  if (!seqs.is_array()) r.fail(f + ".sequences", "expected an array");
  for (size_t i = 0; i < seqs.size(); ++i) {
    const std::string sf = fmt::format("{}.sequences[{}]", f, i);
    PlannedSequence s;
    s.name = r.string(seqs[i], sf, "name");
    s.trajectory = r.string(seqs[i], sf, "trajectory");
    if (std::find(std::begin(kMotionNames), std::end(kMotionNames), s.trajectory) ==
        std::end(kMotionNames))
      r.fail(sf + ".trajectory", "'" + s.trajectory + "' is not a random trajectory type");
    s.v_mult = r.number(seqs[i], sf, "v_mult");
    s.w_mult = r.number(seqs[i], sf, "w_mult");
    s.seed = r.unsignedInt(seqs[i], sf, "seed");
    L.sequences.push_back(std::move(s));
  }
  return L;
}

/// "sequences.frames (line 1)" -> "sequences.frames": lines of the spec stored in a plan are
/// lines of its one-line JSON, which would mislead.
std::string withoutLine(std::string field) {
  const size_t p = field.find(" (line ");
  if (p != std::string::npos) field.erase(p);
  return field;
}

}  // namespace

const char* layoutKindName(LayoutKind kind) {
  switch (kind) {
    case LayoutKind::Procedural:
      return "procedural";
    case LayoutKind::File:
      return "file";
    case LayoutKind::Front3d:
      return "front3d";
  }
  return "unknown";
}

const char* splitName(Split split) {
  switch (split) {
    case Split::Train:
      return "train";
    case Split::Validation:
      return "validation";
    case Split::Test:
      return "test";
  }
  return "unknown";
}

Split splitOf(const std::string& layout_id, const SplitShares& shares) {
  return splitFromHash(stableHash64(layout_id), shares);
}

std::string subsetName(int rooms) {
  return rooms > 0 ? fmt::format("rooms_{:02d}", rooms) : std::string("rooms_unknown");
}

std::string configurationName(const SceneConfiguration& c, const PlannedLayout& layout) {
  if (c.kind == SceneConfiguration::Kind::Original) return "original";
  const bool lighting = c.kind == SceneConfiguration::Kind::Lighting;
  const uint64_t seed =
      c.derived ? (lighting ? layout.lighting_seed : layout.rearranged_seed) : c.seed;
  return fmt::format("{}:{}", lighting ? "lighting" : "rearranged", seed);
}

DatasetPlan makePlan(const DatasetSpec& spec) {
  DatasetPlan plan;
  plan.spec = spec;
  const ProceduralLayoutsSpec& p = spec.layouts.procedural;
  plan.layouts.reserve(static_cast<size_t>(p.count));
  for (int64_t i = 0; i < p.count; ++i) {
    PlannedLayout L;
    L.kind = LayoutKind::Procedural;
    L.seed = p.first_seed + static_cast<uint64_t>(i);
    L.id = fmt::format("procedural:{}", L.seed);
    plan.layouts.push_back(std::move(L));
  }
  addFileLayouts(spec, plan.layouts);
  if (plan.layouts.empty())
    throw InputError(spec.file, "layouts", "no layout (procedural.count is 0 and no file)");
  if (plan.layouts.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw InputError(spec.file, "layouts", "more than 2^31 - 1 layouts");

  // ids must be unique: the same file reached through two folders, two equal 3D-FRONT paths
  std::unordered_set<std::string> ids;
  ids.reserve(plan.layouts.size());
  for (const PlannedLayout& L : plan.layouts)
    if (!ids.insert(L.id).second)
      throw InputError(spec.file, "layouts", "the layout '" + L.id + "' is listed twice");

  const DerivedUse use(spec);
  for (PlannedLayout& L : plan.layouts) {
    drawLayout(spec, use, L);
    L.split = splitOf(L.id, spec.splits);
    L.subset = subsetName(L.rooms);
    const LayoutKey key(L.id);
    L.sequences.reserve(static_cast<size_t>(spec.sequences.per_layout));
    for (int i = 0; i < spec.sequences.per_layout; ++i)
      L.sequences.push_back(drawSequence(spec, key, i));
  }
  return plan;
}

std::vector<WorkUnit> units(const DatasetPlan& plan) {
  const DatasetSpec& spec = plan.spec;
  const SequencesSpec& q = spec.sequences;
  const PlanCounts counts = planCounts(plan);
  std::vector<WorkUnit> out;
  out.reserve(static_cast<size_t>(counts.units()));
  const int digits = frameDigits(q.frames);
  for (size_t li = 0; li < plan.layouts.size(); ++li) {
    const PlannedLayout& L = plan.layouts[li];
    for (size_t si = 0; si < L.sequences.size(); ++si) {
      for (size_t ci = 0; ci < q.configurations.size(); ++ci) {
        const std::string prefix = fmt::format("seq/{}/{}/{}/", L.id, L.sequences[si].name,
                                               configurationName(q.configurations[ci], L));
        for (int begin = 0; begin < q.frames; begin += q.unit_frames) {
          WorkUnit u;
          u.kind = UnitKind::Sequence;
          u.layout = static_cast<int>(li);
          u.sequence = static_cast<int>(si);
          u.configuration = static_cast<int>(ci);
          u.frame_begin = begin;
          u.frame_end = std::min(q.frames, begin + q.unit_frames);
          u.frames = u.frame_end - u.frame_begin;
          u.id = fmt::format("{}f{:0{}d}-{:0{}d}", prefix, u.frame_begin, digits, u.frame_end - 1,
                             digits);
          out.push_back(std::move(u));
        }
      }
    }
  }
  if (spec.sparse.per_layout > 0) {
    const int n = static_cast<int>(plan.layouts.size());
    const int configs = static_cast<int>(spec.sparse.configurations.size());
    for (int first = 0; first < n; first += spec.sparse.batch) {
      WorkUnit u;
      u.kind = UnitKind::Sparse;
      u.layout = first;
      u.layout_count = std::min(spec.sparse.batch, n - first);
      u.frame_end = u.layout_count * configs;
      u.frames = u.frame_end;
      u.id = fmt::format("sparse/{}..{}", plan.layouts[first].id,
                         plan.layouts[first + u.layout_count - 1].id);
      out.push_back(std::move(u));
    }
  }
  return out;
}

PlanCounts planCounts(const DatasetPlan& plan) {
  const DatasetSpec& spec = plan.spec;
  PlanCounts c;
  c.layouts = static_cast<int64_t>(plan.layouts.size());
  const int64_t configs = static_cast<int64_t>(spec.sequences.configurations.size());
  for (const PlannedLayout& L : plan.layouts) {
    c.sequences += static_cast<int64_t>(L.sequences.size());
    ++c.split_layouts[static_cast<int>(L.split)];
  }
  c.sequence_units = c.sequences * configs * unitsPerSequence(spec.sequences);
  c.sequence_frames = c.sequences * configs * spec.sequences.frames;
  if (spec.sparse.per_layout > 0) {
    c.sparse_units = (c.layouts + spec.sparse.batch - 1) / spec.sparse.batch;
    c.sparse_views = c.layouts * static_cast<int64_t>(spec.sparse.configurations.size());
  }
  return c;
}

SplitStats splitStats(const DatasetPlan& plan) {
  const DatasetSpec& spec = plan.spec;
  const int64_t seq_frames =
      static_cast<int64_t>(spec.sequences.configurations.size()) * spec.sequences.frames;
  const int64_t views =
      spec.sparse.per_layout > 0 ? static_cast<int64_t>(spec.sparse.configurations.size()) : 0;
  SplitStats st;
  for (const PlannedLayout& L : plan.layouts) {
    const int s = static_cast<int>(L.split);
    for (SplitCount* c : {&st.splits[s], &st.subsets[L.subset][s]}) {
      ++c->layouts;
      c->sequences += static_cast<int64_t>(L.sequences.size());
      c->sequence_frames += static_cast<int64_t>(L.sequences.size()) * seq_frames;
      c->sparse_views += views;
    }
  }
  return st;
}

std::string formatSplitStats(const SplitStats& st) {
  // frames: sequence frames over every configuration plus sparse views
  auto row = [](const std::string& name, const std::array<SplitCount, 3>& c) {
    std::string out = fmt::format("{:<14}", name);
    for (const SplitCount& x : c)
      out += fmt::format(" {:>8} {:>11}", x.layouts, x.sequence_frames + x.sparse_views);
    return out + "\n";
  };
  std::string out = fmt::format("{:<14} {:<20} {:<20} {:<20}\n", "", "train", "validation", "test");
  out += fmt::format("{:<14}", "subset");
  for (int i = 0; i < 3; ++i) out += fmt::format(" {:>8} {:>11}", "layouts", "frames");
  out += "\n";
  for (const auto& [name, c] : st.subsets) out += row(name, c);
  out += row("total", st.splits);
  const int64_t total = st.splits[0].layouts + st.splits[1].layouts + st.splits[2].layouts;
  if (total > 0)
    out += fmt::format("layout shares: train {:.2f} %, validation {:.2f} %, test {:.2f} %\n",
                       100.0 * st.splits[0].layouts / total, 100.0 * st.splits[1].layouts / total,
                       100.0 * st.splits[2].layouts / total);
  return out;
}

std::string planText(const DatasetPlan& plan) {
  const PlanCounts c = planCounts(plan);
  ojson head;
  head["format"] = kPlanFormat;
  head["version"] = kPlanVersion;
  head["spec_file"] =
      plan.spec.file.empty() ? "" : fs::absolute(plan.spec.file).lexically_normal().string();
  head["spec_checksum"] = plan.spec.checksum;
  head["counts"] = {{"layouts", c.layouts},
                    {"train", c.split_layouts[0]},
                    {"validation", c.split_layouts[1]},
                    {"test", c.split_layouts[2]},
                    {"sequences", c.sequences},
                    {"units", c.units()},
                    {"sequence_units", c.sequence_units},
                    {"sparse_units", c.sparse_units},
                    {"frames", c.frames()},
                    {"sequence_frames", c.sequence_frames},
                    {"sparse_views", c.sparse_views}};
  head["spec"] = specToJson(plan.spec);
  // The header indented, then one compact line per layout: readable, and a
  // diff of two plans shows which layouts changed.
  std::string out;
  dumpPretty(head, 0, out);
  out.pop_back();  // the closing brace; the layouts follow
  while (!out.empty() && out.back() == '\n') out.pop_back();
  out += ",\n  \"layouts\": [";
  const DerivedUse use(plan.spec);
  for (size_t i = 0; i < plan.layouts.size(); ++i) {
    out += i ? ",\n    " : "\n    ";
    out += layoutJson(plan.layouts[i], use).dump();
  }
  out += plan.layouts.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

void writePlan(const DatasetPlan& plan, const fs::path& path) {
  writeTextAtomic(path, planText(plan));
}

DatasetPlan readPlan(const fs::path& path) {
  const std::string file = path.string();
  const PlanReader r(file);
  const std::string text = readTextFile(path);
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is 1-based; count lines up to it for a location a person can find
    const size_t end = std::min(text.size(), e.byte > 0 ? e.byte - 1 : 0);
    const int64_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
    const size_t line_start = text.rfind('\n', end == 0 ? 0 : end - 1);
    const size_t column = line_start == std::string::npos ? end + 1 : end - line_start;
    throw InputError(file, fmt::format("line {}, column {}", line, column),
                     "not a valid JSON plan file");
  }
  if (!root.is_object() || !root.contains("format") || root["format"] != kPlanFormat)
    r.fail("format", std::string("not a dataset plan (format \"") + kPlanFormat + "\")");
  const int64_t version = r.integer(root, "", "version", 0, 1'000'000);
  if (version != kPlanVersion)
    r.fail("version", fmt::format("plan version {} is not supported (this build reads {})", version,
                                  kPlanVersion));
  DatasetPlan plan;
  const std::string spec_file = r.string(root, "", "spec_file");
  try {
    plan.spec = parseDatasetSpecText(r.at(root, "", "spec").dump(), spec_file);
  } catch (const InputError& e) {
    const std::string f = withoutLine(e.field());
    throw InputError(file, f.empty() ? "spec" : "spec." + f, e.problem());
  }
  plan.spec.file = spec_file;
  plan.spec.checksum = r.string(root, "", "spec_checksum");

  const json& layouts = r.at(root, "", "layouts");
  if (!layouts.is_array()) r.fail("layouts", "expected an array");
  const DerivedUse use(plan.spec);
  plan.layouts.reserve(layouts.size());
  std::unordered_set<std::string> ids;
  ids.reserve(layouts.size());
  for (size_t i = 0; i < layouts.size(); ++i) {
    const std::string f = fmt::format("layouts[{}]", i);
    plan.layouts.push_back(readLayout(r, layouts[i], f, use));
    if (!ids.insert(plan.layouts.back().id).second)
      r.fail(f + ".id", "'" + plan.layouts.back().id + "' is listed twice");
    if (static_cast<int>(plan.layouts.back().sequences.size()) != plan.spec.sequences.per_layout)
      r.fail(f + ".sequences",
             fmt::format("{} sequences, the spec says {} per layout",
                         plan.layouts.back().sequences.size(), plan.spec.sequences.per_layout));
  }
  // the counts in the header are for people and tools reading it; they must agree
  const PlanCounts c = planCounts(plan);
  const json& counts = r.at(root, "", "counts");
  const std::pair<const char*, int64_t> expect[] = {
      {"layouts", c.layouts}, {"units", c.units()}, {"frames", c.frames()}};
  for (const auto& [key, value] : expect)
    if (r.integer(counts, "counts", key, 0, std::numeric_limits<int64_t>::max()) != value)
      r.fail(std::string("counts.") + key,
             fmt::format("says {}, the plan has {}", counts[key].dump(), value));
  return plan;
}

}  // namespace inet
