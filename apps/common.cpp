#include "common.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "scene/assimp_importer.h"
#include "scene/default_scene.h"
#include "scene/layout_json.h"

namespace inet::app {

void SceneArgs::addTo(CLI::App& cmd) {
  cmd.add_option("--layout,--scene", path,
                 "layout.json, or a mesh scene (.obj .gltf .glb .ply ...) imported with Assimp; "
                 "default: the built-in furnished room");
  cmd.add_option("--up", up, "up axis of an imported mesh scene (y or z; default z)")
      ->check(CLI::IsMember({"y", "z"}));
  cmd.add_option("--scale", scale, "metres per unit of an imported mesh scene (default 1)");
  cmd.add_option("--labels", labels,
                 "CSV 'name,nyu40' mapping object names of an imported scene to NYU40");
}

Scene SceneArgs::load() const {
  if (path.empty()) return makeDefaultScene();
  std::filesystem::path p(path);
  if (p.extension() == ".json") return loadLayout(path);
  if (!(scale > 0)) throw InputError(path, "--scale", "must be > 0");
  ImportOptions opt;
  opt.scale = scale;
  opt.up = up[0];
  opt.label_map = labels;
  ImportReport report;
  Scene s = importMeshScene(path, opt, &report);
  std::string warn = report.summary(opt.default_category);
  if (!warn.empty()) std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warn.c_str());
  return s;
}

struct ThreadLimit::Impl {
  std::unique_ptr<tbb::global_control> control;
};

ThreadLimit::ThreadLimit(int n) : impl_(std::make_unique<Impl>()) {
  if (n < 0) throw InputError("", "--threads", "must be >= 0 (0 = all cores)");
  if (n > 0)
    impl_->control =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, n);
  threads_ = n > 0 ? n : tbb::info::default_concurrency();
}

ThreadLimit::~ThreadLimit() = default;

const char* version() {
  return INET_VERSION;
}

}  // namespace inet::app
