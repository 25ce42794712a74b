#pragma once
// Switches for the long physics tests, read from the environment.
#include <cstdlib>
#include <string>

namespace gacompare::testing {

// False when GACOMPARE_QUICK_TESTS=1: the sanitizer run leaves out the 10 s
// stacks and columns (they run unsanitized in the same CI).
inline bool long_tests() {
  const char* v = std::getenv("GACOMPARE_QUICK_TESTS");
  return !(v && std::string(v) == "1");
}

// True when GACOMPARE_SLOW_TESTS=1 (and not GACOMPARE_QUICK_TESTS=1): the
// cases that take minutes per backend (the largest pyramids) run too; the
// plain test run, which CI runs, leaves them out and the stacking table's
// results page runs them.
inline bool slow_tests() {
  const char* v = std::getenv("GACOMPARE_SLOW_TESTS");
  return long_tests() && v && std::string(v) == "1";
}

// True when GACOMPARE_OPEN_CASES=1: the cases a solver does not meet yet run
// too (and fail until it does); without it they are skipped with their reason.
inline bool open_cases() {
  const char* v = std::getenv("GACOMPARE_OPEN_CASES");
  return v && std::string(v) == "1";
}

}  // namespace gacompare::testing
