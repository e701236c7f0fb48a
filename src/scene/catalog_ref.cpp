#include "scene/catalog_ref.h"

#include <mutex>

namespace inet {
namespace {

std::mutex& resolverMutex() {
  static std::mutex m;
  return m;
}

std::shared_ptr<CatalogResolver>& resolverSlot() {
  static std::shared_ptr<CatalogResolver> r;
  return r;
}

}  // namespace

void setCatalogResolver(std::shared_ptr<CatalogResolver> resolver) {
  std::lock_guard lock(resolverMutex());
  resolverSlot() = std::move(resolver);
}

std::shared_ptr<CatalogResolver> catalogResolver() {
  std::lock_guard lock(resolverMutex());
  return resolverSlot();
}

}  // namespace inet
