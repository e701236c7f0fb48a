#pragma once
// Object name -> NYU40 class, for importers whose files carry semantics only in object names
// (SceneNet's "wall.034", an OBJ's "chair_01", a glTF node "Chair.003").
//
// CSV format (docs/layout.md has the full description):
//   # comment lines and trailing "# ..." comments are ignored, as are blank lines
//   name,nyu40            <- optional header line
//   painting,picture      <- the NYU40 class as a name (any spelling nyu40FromName accepts) ...
//   nightstand,32         <- ... or as an id 0..40
//
// Matching of an object name, first hit wins:
//   1. map entries: exact name (case-insensitive);
//   2. map entries: the longest key that is a prefix of the name or equals one whole token of it
//      (tokens split on '_', '-', '.', ' ', digits and camelCase boundaries, so "backWall" has
//      the token "wall"; '_', '-', '.' and ' ' are ignored when
//      testing prefixes, so the key "night_stand" matches "nightstand_left");
//   3. the same two steps against the 41 NYU40 class names themselves and a few common
//      aliases (fridge, tv, painting, rug, carpet, couch, wardrobe, armchair, nightstand, ...),
//      so "bed_2" -> bed and "room_walls" -> wall even with an empty map.
// A token also matches a key in its plural form ("walls", "boxes").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace inet {

/// "void, wall, floor, ..., otherprop": the 41 canonical NYU40 names, for error messages.
std::string nyu40NameList();

class LabelMap {
 public:
  /// One CSV row: lower-cased key and its NYU40 id (0..40).
  struct Entry {
    std::string key;
    int nyu40 = 0;
    int line = 0;  ///< line in the CSV (1-based), 0 for built-in names
  };

  /// An empty map: only the NYU40 class names match.
  LabelMap() = default;

  /// Reads a CSV `path`. A malformed line, an unknown class or a key mapped twice to different
  /// classes throws InputError(path, "line N", problem).
  static LabelMap load(const std::string& path);

  /// Parses CSV text; `where` names the source in error messages.
  static LabelMap parse(const std::string& text, const std::string& where);

  /// NYU40 id for an object name, or nullopt when neither the map nor the NYU40 names match.
  std::optional<int> lookup(std::string_view object_name) const;

  /// The key that decided lookup(object_name) ("" when nothing matched); for reports.
  std::string matchedKey(std::string_view object_name) const;

  const std::vector<Entry>& entries() const { return entries_; }
  size_t size() const { return entries_.size(); }

 private:
  std::vector<Entry> entries_;
};

}  // namespace inet
