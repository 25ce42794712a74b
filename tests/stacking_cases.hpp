#pragma once
// The stacking family (answers/stacking_family.hpp) through a backend: one test
// per generated case, each run for its 10 simulated seconds with the contact
// solver the family is built for and held to its statics answer at every
// sample. Instantiated by tests/{traditional,cga,pga}/stacking_test.cpp under the
// `stacking` label; the long cases (ten moving bodies or more: columns,
// pyramids, dominoes) are left out by GACOMPARE_QUICK_TESTS=1, the slow ones
// (minutes per backend: the largest pyramids) run only with
// GACOMPARE_SLOW_TESTS=1, and the open ones
// (StackCase::open) are skipped with their reason unless GACOMPARE_OPEN_CASES=1.
#include "core/dynamics/simulator.hpp"
#include "answers/stacking_family.hpp"

#include "long_tests.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

namespace gacompare::testing {

// The family as the default contact solver builds it (the one a scene gets).
inline const std::vector<core::StackCase>& stacking_cases() {
  static const std::vector<core::StackCase> family = core::stacking_family(core::Collisions{}.contact_solver);
  return family;
}
inline std::vector<std::size_t> stacking_indices() {
  std::vector<std::size_t> out(stacking_cases().size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = k;
  return out;
}
inline std::string stacking_test_name(const ::testing::TestParamInfo<std::size_t>& info) {
  std::string out = stacking_cases()[info.param].name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return out;
}

template <class Backend>
class StackingFamily : public ::testing::TestWithParam<std::size_t> {
 protected:
  void check_case() {
    const core::StackCase& c = stacking_cases()[GetParam()];
    if (c.long_running && !long_tests()) GTEST_SKIP() << c.name << " is long: left out by GACOMPARE_QUICK_TESTS=1";
    if (c.slow && !slow_tests())
      GTEST_SKIP() << c.name << " takes minutes per backend: GACOMPARE_SLOW_TESTS=1 runs it (the stacking table always does)";
    if (!c.open.empty() && !open_cases())
      GTEST_SKIP() << c.name << " is open: " << c.open << " (GACOMPARE_OPEN_CASES=1 runs it)";
    const core::Run run = core::simulate<Backend>(c.scene);
    const core::StackVerdict v = c.evaluate(run);
    EXPECT_TRUE(v.pass) << c.name << ": worst " << v.worst << " (" << v.ratio << " x its bound)\n  first failure: "
                        << v.first_failure << "\n  expected: " << c.scene.description;
  }
};

}  // namespace gacompare::testing
