// interiornet layout show: what a layout or mesh scene contains, as the renderer will see it.
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "common.h"
#include "scene/nyu40.h"

namespace inet::app {
namespace {

void showScene(const Scene& s) {
  auto [lo, hi] = s.bounds();
  std::map<int, int> per_class;
  std::map<int, int> instances;
  int emitters = 0;
  for (const auto& o : s.objects) {
    instances[o.instance] = o.nyu40;
    if (s.materials[o.material].isEmissive()) ++emitters;
  }
  for (const auto& [inst, label] : instances) ++per_class[label];
  fmt::print("layout     {}\n", s.name);
  fmt::print("meshes     {} ({} triangles placed in the world)\n", s.meshes.size(),
             s.triangleCount());
  fmt::print("materials  {}\n", s.materials.size());
  fmt::print("objects    {} parts in {} instances, {} emissive, {} analytic lights\n",
             s.objects.size(), instances.size(), emitters, s.lights.size());
  fmt::print("bounds     x [{:.3f}, {:.3f}]  y [{:.3f}, {:.3f}]  z [{:.3f}, {:.3f}] m\n", lo.x(),
             hi.x(), lo.y(), hi.y(), lo.z(), hi.z());
  fmt::print("instances per NYU40 class:\n");
  for (const auto& [label, count] : per_class)
    fmt::print("  {:>2} {:<16} {}\n", label, nyu40Name(label), count);
}

}  // namespace

void registerLayout(CLI::App& app) {
  auto* layout = app.add_subcommand(
      "layout", "Inspect layouts (generate, import and stats come with the layout stage)");
  layout->require_subcommand(1);
  auto* show = layout->add_subcommand(
      "show", "Print a summary of a layout.json or mesh scene: objects, classes, bounds");
  auto args = std::make_shared<SceneArgs>();
  args->addTo(*show);
  show->callback([args] { showScene(args->load()); });
}

}  // namespace inet::app
