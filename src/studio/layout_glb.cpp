#include "studio/layout_glb.h"

#include <chrono>
#include <cstdlib>
#include <system_error>

#include "core/error.h"
#include "scene/gltf_export.h"

namespace inet::studio {

namespace fs = std::filesystem;

namespace {

/// A new folder only this process uses (mkdtemp: created 0700 with a unique name).
fs::path makePrivateDir() {
  std::string pattern = (fs::temp_directory_path() / "interiornet-studio-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw InputError(pattern, "", "cannot create a temporary folder for the layout's glTF");
  return pattern;
}

}  // namespace

LayoutGlb::LayoutGlb(std::shared_ptr<const StudioLayout> layout)
    : dir_(makePrivateDir()), seconds_(std::make_shared<double>(0.0)) {
  const fs::path file = dir_ / "layout.glb";
  auto seconds = seconds_;
  file_ = std::async(std::launch::async, [layout, file, seconds] {
            const auto t0 = std::chrono::steady_clock::now();
            GltfExportOptions opt;
            opt.binary = true;
            exportGltf(layout->scene, file.string(), opt);
            *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            return file;
          }).share();
}

LayoutGlb::~LayoutGlb() {
  if (file_.valid()) file_.wait();
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

fs::path LayoutGlb::path() const {
  return file_.get();
}

double LayoutGlb::exportSeconds() const {
  return file_.wait_for(std::chrono::seconds(0)) == std::future_status::ready ? *seconds_ : 0.0;
}

}  // namespace inet::studio
