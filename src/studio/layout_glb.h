#pragma once
// The layout as one binary glTF (GET /api/layout.glb), for the page's 3D view: our own glTF
// export (scene/gltf_export.h) written once to a private temporary folder and served from there.
// The export starts in the background when the server is made, so that it is usually ready by
// the time the page asks; a request that comes earlier waits for it. The folder is removed with
// the object. The same layout gives the same bytes.
#include <filesystem>
#include <future>
#include <memory>
#include <string>

#include "studio/studio_layout.h"

namespace inet::studio {

class LayoutGlb {
 public:
  /// Starts the export of `layout`'s scene.
  explicit LayoutGlb(std::shared_ptr<const StudioLayout> layout);
  ~LayoutGlb();  ///< waits for the export, removes the folder
  LayoutGlb(const LayoutGlb&) = delete;
  LayoutGlb& operator=(const LayoutGlb&) = delete;

  /// The .glb file, once written. Rethrows what the export threw (an InputError, e.g. a
  /// texture that cannot be read).
  std::filesystem::path path() const;
  /// The private temporary folder (mkdtemp, 0700) the file is written to; removed with this.
  const std::filesystem::path& folder() const { return dir_; }
  /// How long the export took (s), 0 until it is done.
  double exportSeconds() const;

 private:
  std::filesystem::path dir_;
  std::shared_future<std::filesystem::path> file_;
  std::shared_ptr<double> seconds_;
};

}  // namespace inet::studio
