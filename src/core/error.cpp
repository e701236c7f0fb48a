#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace inet {
namespace {
std::string joinMessage(const std::string& file, const std::string& field,
                        const std::string& problem) {
  std::string msg;
  if (!file.empty()) msg += file + ": ";
  if (!field.empty()) msg += field + ": ";
  msg += problem;
  return msg;
}
}  // namespace

InputError::InputError(const std::string& file, const std::string& field,
                       const std::string& problem)
    : std::runtime_error(joinMessage(file, field, problem)),
      file_(file),
      field_(field),
      problem_(problem) {}

void checkFailed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "internal error: CHECK(%s) failed at %s:%d %s\n", expr, file, line,
               msg.c_str());
  std::abort();
}

}  // namespace inet
