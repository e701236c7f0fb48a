#include "scene/layout_stats.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "core/atomic_file.h"

namespace inet {
namespace {

bool isShell(const std::string& kind) {
  static const std::set<std::string> shell = {"wall", "floor",  "ceiling", "skirting",
                                              "door", "window", "ground"};
  return shell.count(kind) > 0;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
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

std::string barChartSvg(const std::string& title, const std::string& x_label,
                        const std::vector<std::pair<std::string, double>>& bars) {
  const int bar_w = 22, gap = 6, left = 60, top = 40, height = 260, bottom = 120;
  const int width = left + static_cast<int>(bars.size()) * (bar_w + gap) + 20;
  double vmax = 0;
  for (const auto& b : bars) vmax = std::max(vmax, b.second);
  if (vmax <= 0) vmax = 1;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\" font-size=\"11\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{}\" y=\"22\" font-size=\"15\">{}</text>\n",
      width, top + height + bottom, left, escape(title));
  // axis with 4 ticks
  for (int k = 0; k <= 4; ++k) {
    const double v = vmax * k / 4;
    const int y = top + height - static_cast<int>(height * k / 4.0);
    svg += fmt::format(
        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#ddd\"/>"
        "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n",
        left, y, width - 10, y, left - 6, y + 4,
        v >= 10 ? fmt::format("{:.0f}", v) : fmt::format("{:.2g}", v));
  }
  for (size_t i = 0; i < bars.size(); ++i) {
    const int x = left + static_cast<int>(i) * (bar_w + gap) + gap;
    const int h = static_cast<int>(height * bars[i].second / vmax);
    svg += fmt::format(
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#4878a8\"><title>{}: "
        "{}</title></rect>\n"
        "<text transform=\"translate({},{}) rotate(-60)\" text-anchor=\"end\">{}</text>\n",
        x, top + height - h, bar_w, h, escape(bars[i].first), bars[i].second, x + bar_w / 2 + 4,
        top + height + 12, escape(bars[i].first));
  }
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n</svg>\n",
                     left + (width - left) / 2, top + height + bottom - 8, escape(x_label));
  return svg;
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
  auto bars = [](const auto& rows, auto label) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& [k, v] : rows) out.push_back({label(k), static_cast<double>(v)});
    return out;
  };
  writeTextAtomic(path("rooms_per_layout.svg"),
                  barChartSvg(fmt::format("Rooms per layout ({} layouts)", layouts), "rooms",
                              bars(rooms, [](int k) { return std::to_string(k); })));
  writeTextAtomic(path("objects_per_layout.svg"),
                  barChartSvg(fmt::format("Objects per layout ({} layouts)", layouts),
                              "furniture and props per layout",
                              bars(objects, [](int k) { return fmt::format("{}-{}", k, k + 9); })));
  writeTextAtomic(path("categories.svg"),
                  barChartSvg("Object category occurrences", "category",
                              bars(cats, [](const std::string& k) { return k; })));
  writeTextAtomic(
      path("room_types.svg"),
      barChartSvg("Room types", "room type", bars(types, [](const std::string& k) { return k; })));
}

}  // namespace inet
