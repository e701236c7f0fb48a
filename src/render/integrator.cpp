#include "render/integrator.h"

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {
struct Entry {
  const char* name;
  std::unique_ptr<Integrator> (*make)();
};
// The registry: one line per integrator.
constexpr Entry kIntegrators[] = {
    {"path", &makePathTracer},
};
}  // namespace

std::vector<std::string> integratorNames() {
  std::vector<std::string> names;
  for (const auto& e : kIntegrators) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const std::string& where) {
  for (const auto& e : kIntegrators)
    if (name == e.name) return e.make();
  throw InputError(
      where, "--integrator",
      fmt::format("unknown integrator '{}' (valid: {})", name, fmt::join(integratorNames(), ", ")));
}

}  // namespace inet
