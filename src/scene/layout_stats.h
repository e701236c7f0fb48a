#pragma once
// Statistics over a set of layouts, like the InteriorNet paper's Fig. 3: object-category
// occurrences, rooms per layout, objects per layout and the room-type distribution. Written as
// CSV tables and as PNG bar charts (core/plot.h; any image viewer shows them).
#include <map>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

struct LayoutStats {
  size_t layouts = 0;
  std::map<int, size_t> rooms_per_layout;    ///< rooms -> layouts
  std::map<int, size_t> objects_per_layout;  ///< furniture instances (bucketed by 10) -> layouts
  std::map<std::string, size_t> categories;  ///< furniture kind -> instances
  std::map<std::string, size_t> room_types;  ///< room type -> rooms

  /// Adds one layout. Furniture instances are the distinct instance ids whose kind is not part
  /// of the building shell (wall, floor, ceiling, skirting, door, window, ground).
  void add(const Scene& scene);
  /// Writes rooms_per_layout.csv/.png, objects_per_layout.csv/.png, categories.csv/.png and
  /// room_types.csv/.png into `dir` (atomically).
  void write(const std::string& dir) const;
};

}  // namespace inet
