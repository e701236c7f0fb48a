#pragma once
// Meshes and materials of furniture catalog models (src/assets, Sweet Home 3D's .sh3f
// catalogs) as layout.json names them: {"catalog": PIECE_ID, "part": N} for a mesh and
// {"catalog": PIECE_ID, "material": NAME} for a material, so a layout stays small and portable
// (no extracted-cache paths, no inlined geometry). The scene stage cannot read catalogs itself
// (src/assets depends on it), so a program that loads such layouts installs a resolver first:
// assets/catalog_library.h installCatalogResolver(), which every `interiornet` command does.
#include <memory>
#include <string>

#include "scene/scene.h"

namespace inet {

class CatalogResolver {
 public:
  virtual ~CatalogResolver() = default;
  /// Part `part` of piece `piece`'s model, in its model frame. Throws InputError(where_file,
  /// where_field, ...) for an unknown piece or part.
  virtual Mesh mesh(const std::string& piece, int part, const std::string& where_file,
                    const std::string& where_field) = 0;
  /// The material `material` of piece `piece`'s model (texture paths resolved), the same way.
  virtual Material material(const std::string& piece, const std::string& material,
                            const std::string& where_file, const std::string& where_field) = 0;
};

/// Installs the process-wide resolver (nullptr removes it). Call before loading layouts; not
/// meant to be swapped while other threads load.
void setCatalogResolver(std::shared_ptr<CatalogResolver> resolver);
/// The installed resolver, or nullptr.
std::shared_ptr<CatalogResolver> catalogResolver();

}  // namespace inet
