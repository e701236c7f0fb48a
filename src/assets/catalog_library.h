#pragma once
// The installed furniture catalogs as one library: every piece by id and by the category of
// our furniture library it stands in for, models loaded on first use and kept (thread-safe),
// and the resolver that lets layout.json name catalog meshes and materials
// (scene/catalog_ref.h).
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "assets/catalog_labels.h"
#include "assets/catalog_model.h"
#include "assets/furniture_catalog.h"

namespace inet {

class CatalogLibrary {
 public:
  /// Reads every catalog of `dir` (readFurnitureCatalogs; models are not loaded yet).
  explicit CatalogLibrary(const std::string& dir);

  const std::string& dir() const { return dir_; }
  const std::vector<FurnitureCatalog>& catalogs() const { return catalogs_; }
  /// The piece `id` and its catalog, or {nullptr, nullptr}.
  std::pair<const FurnitureCatalog*, const CatalogPiece*> find(const std::string& id) const;
  /// The label of piece `id` (labelCatalogPiece); throws InputError for an unknown id.
  const CatalogLabel& label(const std::string& id) const;
  /// Interior pieces labelled with our furniture `category` (catalog_labels.h), in catalog
  /// order (file name, then index): the same list on every machine with the same package.
  const std::vector<const CatalogPiece*>& byCategory(const std::string& category) const;
  /// The model of piece `id`, loaded once. Throws InputError(where_file, where_field) for an
  /// unknown id, and as loadCatalogModel for a broken model.
  std::shared_ptr<const CatalogModel> model(const std::string& id, const std::string& where_file,
                                            const std::string& where_field) const;

 private:
  std::string dir_;
  std::vector<FurnitureCatalog> catalogs_;
  std::map<std::string, std::pair<const FurnitureCatalog*, const CatalogPiece*>> by_id_;
  std::map<std::string, std::vector<const CatalogPiece*>> by_category_;
  std::map<std::string, CatalogLabel> labels_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const CatalogModel>> models_;
};

/// The library of the catalogs folder `dir` ("" = catalogDir()), read once per process and
/// folder. Throws InputError when the folder has no catalog.
std::shared_ptr<const CatalogLibrary> catalogLibrary(const std::string& dir = "");

/// True when catalogDir(dir) is a folder (the package, or --catalog, is there).
bool catalogsAvailable(const std::string& dir = "");

/// Installs a resolver (scene/catalog_ref.h) over catalogLibrary(dir), read on first use, so
/// layouts naming catalog models load. Cheap: nothing is read until a layout needs it.
void installCatalogResolver(const std::string& dir = "");

}  // namespace inet
