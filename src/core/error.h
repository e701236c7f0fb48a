#pragma once
// Two kinds of failure (STYLE.md section 4):
//  - InputError: bad input from a user (file, field, problem). Library code throws it; only main()
//    turns it into a one-line message and a non-zero exit.
//  - INET_CHECK: a broken invariant, i.e. a bug. Aborts with the expression.
#include <stdexcept>
#include <string>

namespace inet {

/// Bad user input. what() is "file: field: problem" (empty parts are left out).
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& problem);
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, field_, problem_;
};

/// A model file that reads but holds no surface (only lines or points): an InputError a caller
/// may tell apart by type (a Sweet Home 3D light source is drawn as lines and still lights).
class NoSurfaceError : public InputError {
 public:
  using InputError::InputError;
};

[[noreturn]] void checkFailed(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace inet

#define INET_CHECK(cond)                                             \
  do {                                                               \
    if (!(cond)) ::inet::checkFailed(#cond, __FILE__, __LINE__, {}); \
  } while (0)
#define INET_CHECK_MSG(cond, msg)                                       \
  do {                                                                  \
    if (!(cond)) ::inet::checkFailed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
