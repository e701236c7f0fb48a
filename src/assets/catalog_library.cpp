#include "assets/catalog_library.h"

#include <fmt/format.h>

#include <filesystem>

#include "core/error.h"
#include "scene/catalog_ref.h"

namespace inet {

CatalogLibrary::CatalogLibrary(const std::string& dir)
    : dir_(dir), catalogs_(readFurnitureCatalogs(dir)) {
  for (const auto& c : catalogs_)
    for (const auto& p : c.pieces) {
      by_id_[p.id] = {&c, &p};
      const CatalogLabel& l = labels_[p.id] = labelCatalogPiece(p);
      if (p.isInterior() && !l.category.empty()) by_category_[l.category].push_back(&p);
    }
}

std::pair<const FurnitureCatalog*, const CatalogPiece*> CatalogLibrary::find(
    const std::string& id) const {
  auto it = by_id_.find(id);
  return it == by_id_.end() ? std::pair<const FurnitureCatalog*, const CatalogPiece*>{}
                            : it->second;
}

const CatalogLabel& CatalogLibrary::label(const std::string& id) const {
  auto it = labels_.find(id);
  if (it == labels_.end()) throw InputError(dir_, "", fmt::format("no catalog piece '{}'", id));
  return it->second;
}

const std::vector<const CatalogPiece*>& CatalogLibrary::byCategory(
    const std::string& category) const {
  static const std::vector<const CatalogPiece*> none;
  auto it = by_category_.find(category);
  return it == by_category_.end() ? none : it->second;
}

std::shared_ptr<const CatalogModel> CatalogLibrary::model(const std::string& id,
                                                          const std::string& where_file,
                                                          const std::string& where_field) const {
  {
    std::lock_guard lock(mutex_);
    auto it = models_.find(id);
    if (it != models_.end()) return it->second;
  }
  const auto [catalog, piece] = find(id);
  if (!piece)
    throw InputError(where_file, where_field, fmt::format("no catalog piece '{}' in {}", id, dir_));
  auto m = std::make_shared<const CatalogModel>(loadCatalogModel(*catalog, *piece));
  std::lock_guard lock(mutex_);
  return models_.emplace(id, std::move(m)).first->second;  // a racing load of the same wins
}

std::shared_ptr<const CatalogLibrary> catalogLibrary(const std::string& dir) {
  static std::mutex m;
  static std::map<std::string, std::shared_ptr<const CatalogLibrary>> libraries;
  const std::string d = catalogDir(dir);
  std::lock_guard lock(m);
  auto it = libraries.find(d);
  if (it != libraries.end()) return it->second;
  auto lib = std::make_shared<const CatalogLibrary>(d);
  return libraries.emplace(d, std::move(lib)).first->second;
}

bool catalogsAvailable(const std::string& dir) {
  std::error_code ec;
  return std::filesystem::is_directory(catalogDir(dir), ec);
}

namespace {

class LibraryResolver : public CatalogResolver {
 public:
  explicit LibraryResolver(std::string dir) : dir_(std::move(dir)) {}

  Mesh mesh(const std::string& piece, int part, const std::string& where_file,
            const std::string& where_field) override {
    const auto m = catalogLibrary(dir_)->model(piece, where_file, where_field);
    if (part < 0 || part >= static_cast<int>(m->parts.meshes.size()))
      throw InputError(
          where_file, where_field,
          fmt::format("'{}' has {} parts, not {}", piece, m->parts.meshes.size(), part + 1));
    return m->parts.meshes[size_t(part)];
  }

  Material material(const std::string& piece, const std::string& material,
                    const std::string& where_file, const std::string& where_field) override {
    const auto m = catalogLibrary(dir_)->model(piece, where_file, where_field);
    for (const Material& mat : m->parts.materials)
      if (mat.catalog_material == material) return mat;
    throw InputError(where_file, where_field,
                     fmt::format("'{}' has no material '{}'", piece, material));
  }

 private:
  std::string dir_;
};

}  // namespace

void installCatalogResolver(const std::string& dir) {
  setCatalogResolver(std::make_shared<LibraryResolver>(dir));
}

}  // namespace inet
