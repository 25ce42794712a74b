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

inline const core::StackCase* five_cube_column() {
  for (const core::StackCase& c : stacking_cases())
    if (c.name == "column/cubes/5") return &c;
  return nullptr;
}

// A column at rest costs no solve and rarely a projection, and still meets
// its statics: its warm starts are kept (the load carried over is already
// the answer) and its projection runs only when the column, sinking as a
// whole by ½|g|h² = 4.9e-6 m a step, leaves the band [tol/4, tol/2]: about
// one step in five (1e-4 m tolerance, 1 ms steps). Bounds well inside what
// the column does (99.8 % and 83 % in every backend), well outside
// what a solve or a projection at every step would give (0).
template <class Backend>
void check_resting_column() {
  const core::StackCase* column = five_cube_column();
  ASSERT_NE(column, nullptr);
  const core::Run run = core::simulate<Backend>(column->scene);
  const core::StackVerdict v = column->evaluate(run);
  EXPECT_TRUE(v.pass) << v.worst;
  const auto steps = static_cast<double>(run.count("collision_steps"));
  const auto solves = static_cast<double>(run.count("contact_solves"));
  ASSERT_GT(steps, 0);
  EXPECT_GT(static_cast<double>(run.count("exact_starts")), 0.8 * solves);
  const auto skipped = static_cast<double>(run.count("projections_skipped"));
  EXPECT_GT(skipped, 0.6 * steps);
  EXPECT_LT(skipped, 0.9 * steps) << "a column that sinks 4.9e-6 m a step must still be projected";
}

// The same column with its contacts kept (core/collision/kept_contacts.hpp,
// the default) and with every pair tested at every detection: nearly all its
// pairs' detections are kept ones (99.7 % measured in every backend: the
// column's pairs move only along their faces' normals once at rest, which
// changes no choice of the whole test's), none with reuse_contacts off, and
// both meet the statics and end
// within 1e-12 m of each other sideways (2e-14 to 6e-14 m measured: kept
// points sit where the tested ones do to rounding here, nothing slides).
template <class Backend>
void check_column_kept_contacts() {
  const core::StackCase* column = five_cube_column();
  ASSERT_NE(column, nullptr);
  core::Scene tested = column->scene;
  for (auto& effect : tested.effects)
    if (auto* collisions = std::get_if<core::Collisions>(&effect)) collisions->reuse_contacts = false;
  const core::Run kept = core::simulate<Backend>(column->scene), full = core::simulate<Backend>(tested);
  for (const core::Run* r : {&kept, &full}) {
    const core::StackVerdict v = column->evaluate(*r);
    EXPECT_TRUE(v.pass) << v.worst;
  }
  EXPECT_GT(static_cast<double>(kept.count("narrowphase_contacts_kept")), 0.95 * kept.count("narrowphase_pairs"));
  EXPECT_EQ(full.count("narrowphase_contacts_kept"), 0u);
  ASSERT_EQ(kept.samples.size(), full.samples.size());
  double most = 0;
  for (std::size_t b = 0; b < kept.samples.back().bodies.size(); ++b)
    most = std::max(most, (kept.samples.back().bodies[b].position - full.samples.back().bodies[b].position).head<2>().norm());
  EXPECT_LT(most, 1e-12);
}

}  // namespace gacompare::testing
