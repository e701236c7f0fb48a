#pragma once
// Tests of bad input: run something that must throw an InputError and look at it.
#include <gtest/gtest.h>

#include "core/error.h"

namespace inet::test {

/// Runs `f` and returns the InputError it throws (fails the test if none).
template <class F>
InputError expectInputError(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

}  // namespace inet::test
