#include "scene/label_map.h"

#include <cctype>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/nyu40.h"

namespace inet {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool isSeparator(char c) {
  return c == '_' || c == '-' || c == '.' || c == ' ';
}

/// Lower-cased with separators removed: "Night_Stand.2" -> "nightstand2".
std::string compact(std::string_view s) {
  std::string out;
  for (char c : s)
    if (!isSeparator(c)) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Lower-cased words between separators, digits and camelCase boundaries:
/// "Chair.003_left" -> {"chair", "left"}, "backWall" -> {"back", "wall"},
/// "TVStand" -> {"tv", "stand"}.
std::vector<std::string> tokens(std::string_view s) {
  std::vector<std::string> out;
  std::string cur;
  auto flush = [&] {
    if (!cur.empty()) out.push_back(cur);
    cur.clear();
  };
  for (size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (isSeparator(s[i]) || std::isdigit(c)) {
      flush();
      continue;
    }
    if (std::isupper(c) && i > 0) {
      const auto prev = static_cast<unsigned char>(s[i - 1]);
      const bool next_lower =
          i + 1 < s.size() && std::islower(static_cast<unsigned char>(s[i + 1]));
      if (std::islower(prev) || (std::isupper(prev) && next_lower)) flush();
    }
    cur += static_cast<char>(std::tolower(c));
  }
  flush();
  return out;
}

std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

/// The best entry for `name` following the rules in label_map.h, or nullptr.
const LabelMap::Entry* bestMatch(const std::vector<LabelMap::Entry>& entries,
                                 std::string_view name) {
  const std::string cname = compact(name);
  for (const auto& e : entries)
    if (compact(e.key) == cname) return &e;
  const std::vector<std::string> toks = tokens(name);
  const LabelMap::Entry* best = nullptr;
  size_t best_len = 0;
  for (const auto& e : entries) {
    const std::string ckey = compact(e.key);
    if (ckey.size() <= best_len) continue;  // ties keep the earlier entry
    bool hit = cname.starts_with(ckey);
    // a whole token, singular or plural ("walls", "curtains", "boxes")
    for (size_t i = 0; !hit && i < toks.size(); ++i)
      hit = toks[i] == ckey || toks[i] == ckey + "s" || toks[i] == ckey + "es";
    if (hit) {
      best = &e;
      best_len = ckey.size();
    }
  }
  return best;
}

/// The NYU40 class names (1..40) plus the common aliases nyu40FromName knows.
const std::vector<LabelMap::Entry>& builtinEntries() {
  static const std::vector<LabelMap::Entry> entries = [] {
    std::vector<LabelMap::Entry> v;
    for (int id = 1; id < kNyu40Count; ++id) v.push_back({std::string(nyu40Name(id)), id, 0});
    for (const char* alias : {"refrigerator", "fridge", "tv"})
      v.push_back({alias, *nyu40FromName(alias), 0});
    // common names of indoor datasets that are not NYU40 names (SceneNet's "painting", ...)
    const std::pair<const char*, const char*> more[] = {
        {"painting", "picture"}, {"poster", "picture"},         {"frame", "picture"},
        {"carpet", "floor_mat"}, {"rug", "floor_mat"},          {"couch", "sofa"},
        {"wardrobe", "cabinet"}, {"cupboard", "cabinet"},       {"armchair", "chair"},
        {"stool", "chair"},      {"nightstand", "night_stand"}, {"monitor", "television"},
        // SceneNet RGB-D's and 3D-FRONT's words for lights, shelves and loose furniture
        {"light", "lamp"},       {"lightbulb", "lamp"},         {"chandelier", "lamp"},
        {"lighting", "lamp"},    {"shelf", "shelves"},          {"pane", "window"},
        {"drawer", "dresser"},   {"furniture", "otherfurniture"}, {"skeleton", "wall"}};
    for (const auto& [alias, name] : more) v.push_back({alias, *nyu40FromName(name), 0});
    return v;
  }();
  return entries;
}

/// Parses the class column: an id 0..40 or an NYU40 name.
int parseClass(const std::string& value, const std::string& where, const std::string& field) {
  bool digits = !value.empty();
  for (char c : value) digits &= std::isdigit(static_cast<unsigned char>(c)) != 0;
  if (digits) {
    int id = value.size() > 3 ? 999 : std::stoi(value);
    if (id >= kNyu40Count)
      throw InputError(where, field, fmt::format("NYU40 id {} is outside 0..40", value));
    return id;
  }
  if (auto id = nyu40FromName(value)) return *id;
  throw InputError(where, field,
                   fmt::format("unknown NYU40 class '{}' (valid: an id 0..40 or one of {})", value,
                               nyu40NameList()));
}

}  // namespace

std::string nyu40NameList() {
  std::string names;
  for (int id = 0; id < kNyu40Count; ++id) {
    if (id) names += ", ";
    names += nyu40Name(id);
  }
  return names;
}

LabelMap LabelMap::load(const std::string& path) {
  return parse(readTextFile(path), path);
}

LabelMap LabelMap::parse(const std::string& text, const std::string& where) {
  LabelMap map;
  bool first_row = true;
  size_t pos = 0;
  for (int line_no = 1; pos <= text.size(); ++line_no) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line(text.substr(pos, end - pos));
    pos = end + 1;
    if (size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    line = trim(line);
    if (line.empty()) continue;
    const std::string field = fmt::format("line {}", line_no);
    size_t comma = line.find(',');
    if (comma == std::string::npos || line.find(',', comma + 1) != std::string::npos)
      throw InputError(where, field, fmt::format("expected 'name,nyu40', got '{}'", line));
    std::string key = trim(line.substr(0, comma));
    std::string value = trim(line.substr(comma + 1));
    if (first_row && lower(key) == "name") {  // optional header
      first_row = false;
      continue;
    }
    first_row = false;
    if (key.empty()) throw InputError(where, field, "empty object name");
    if (compact(key).empty())
      throw InputError(where, field, fmt::format("name '{}' has no letters or digits", key));
    int id = parseClass(value, where, field);
    key = lower(key);
    bool duplicate = false;
    for (const auto& e : map.entries_) {
      if (compact(e.key) != compact(key)) continue;
      if (e.nyu40 != id)
        throw InputError(where, field,
                         fmt::format("'{}' is already mapped to {} on line {}", key,
                                     nyu40Name(e.nyu40), e.line));
      duplicate = true;
    }
    if (!duplicate) map.entries_.push_back({key, id, line_no});
  }
  return map;
}

std::optional<int> LabelMap::lookup(std::string_view object_name) const {
  if (const Entry* e = bestMatch(entries_, object_name)) return e->nyu40;
  if (const Entry* e = bestMatch(builtinEntries(), object_name)) return e->nyu40;
  return std::nullopt;
}

std::string LabelMap::matchedKey(std::string_view object_name) const {
  if (const Entry* e = bestMatch(entries_, object_name)) return e->key;
  if (const Entry* e = bestMatch(builtinEntries(), object_name)) return e->key;
  return {};
}

}  // namespace inet
