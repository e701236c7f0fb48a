#include "scene/layout_stats.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/plot.h"

namespace inet {
namespace {

bool isShell(const std::string& kind) {
  static const std::set<std::string> shell = {"wall", "floor",  "ceiling", "skirting",
                                              "door", "window", "ground"};
  return shell.count(kind) > 0;
}

template <class K>
void writeTable(const std::string& path, const std::string& header,
                const std::vector<std::pair<K, size_t>>& rows) {
  std::string out = header + "\n";
  for (const auto& [k, v] : rows) out += fmt::format("{},{}\n", k, v);
  writeTextAtomic(path, out);
}

}  // namespace

void LayoutStats::add(const Scene& scene) {
  ++layouts;
  ++rooms_per_layout[static_cast<int>(scene.rooms.size())];
  for (const Room& r : scene.rooms) ++room_types[r.type];
  std::map<int, std::string> instances;  // instance id -> kind
  for (const Object& o : scene.objects) {
    const std::string kind = o.kind.empty() ? std::string("unknown") : o.kind;
    if (isShell(kind)) continue;
    instances.emplace(o.instance, kind);
  }
  for (const auto& [id, kind] : instances) ++categories[kind];
  ++objects_per_layout[static_cast<int>(instances.size()) / 10 * 10];
}

void LayoutStats::write(const std::string& dir) const {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
  std::vector<std::pair<int, size_t>> rooms(rooms_per_layout.begin(), rooms_per_layout.end());
  writeTable(path("rooms_per_layout.csv"), "rooms,layouts", rooms);
  std::vector<std::pair<int, size_t>> objects(objects_per_layout.begin(), objects_per_layout.end());
  writeTable(path("objects_per_layout.csv"), "objects_from,layouts", objects);
  std::vector<std::pair<std::string, size_t>> cats(categories.begin(), categories.end());
  std::stable_sort(cats.begin(), cats.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  writeTable(path("categories.csv"), "category,instances", cats);
  std::vector<std::pair<std::string, size_t>> types(room_types.begin(), room_types.end());
  std::stable_sort(types.begin(), types.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  writeTable(path("room_types.csv"), "room_type,rooms", types);
  // PNG bar charts (core/plot.h), viewable in any image viewer or browser
  auto chart = [&](const char* name, const std::string& title, const std::string& axis,
                   const auto& rows, auto label, bool horizontal) {
    std::vector<Bar> bars;
    for (const auto& [k, v] : rows) bars.push_back({label(k), static_cast<double>(v), {}});
    PlotSpec spec;
    spec.title = title;
    spec.horizontal = horizontal;
    (horizontal ? spec.y_label : spec.x_label) = axis;
    (horizontal ? spec.x_label : spec.y_label) = "count";
    spec.width = 900;
    spec.height = horizontal ? std::max(400, 60 + 22 * static_cast<int>(bars.size())) : 500;
    writeBarChartPng(path(name), spec, bars);
  };
  chart("rooms_per_layout.png", fmt::format("Rooms per layout ({} layouts)", layouts), "rooms",
        rooms, [](int k) { return std::to_string(k); }, false);
  chart("objects_per_layout.png", fmt::format("Objects per layout ({} layouts)", layouts),
        "furniture and props per layout", objects,
        [](int k) { return fmt::format("{}-{}", k, k + 9); }, false);
  chart("categories.png", "Object category occurrences", "category", cats,
        [](const std::string& k) { return k; }, true);
  chart("room_types.png", "Room types", "room type", types,
        [](const std::string& k) { return k; }, true);
}

}  // namespace inet
