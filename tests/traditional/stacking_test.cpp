// tests/stacking_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"

#include "../stacking_cases.hpp"

namespace gacompare::testing {

using TraditionalStacking = StackingFamily<traditional::Backend>;
TEST_P(TraditionalStacking, ComesToRestWhereStaticsPutsIt) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, TraditionalStacking, ::testing::ValuesIn(stacking_indices()),
                         stacking_test_name);
TEST(TraditionalStackingAtRest, ARestingColumnKeepsItsWarmStartsAndSkipsMostProjections) {
  check_resting_column<traditional::Backend>();
}
TEST(TraditionalStackingAtRest, AColumnsKeptContactsGiveWhatTestingEveryPairGives) {
  check_column_kept_contacts<traditional::Backend>();
}

}  // namespace gacompare::testing
