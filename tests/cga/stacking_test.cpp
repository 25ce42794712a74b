// tests/stacking_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../stacking_cases.hpp"

namespace gacompare::testing {

using CgaStacking = StackingFamily<cga::Backend>;
TEST_P(CgaStacking, ComesToRestWhereStaticsPutsIt) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, CgaStacking, ::testing::ValuesIn(stacking_indices()),
                         stacking_test_name);
TEST(CgaStackingAtRest, ARestingColumnKeepsItsWarmStartsAndSkipsMostProjections) {
  check_resting_column<cga::Backend>();
}
TEST(CgaStackingAtRest, AColumnsKeptContactsGiveWhatTestingEveryPairGives) {
  check_column_kept_contacts<cga::Backend>();
}

}  // namespace gacompare::testing
