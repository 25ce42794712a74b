// tests/stacking_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../stacking_cases.hpp"

namespace gacompare::testing {

using PgaStacking = StackingFamily<pga::Backend>;
TEST_P(PgaStacking, ComesToRestWhereStaticsPutsIt) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, PgaStacking, ::testing::ValuesIn(stacking_indices()),
                         stacking_test_name);
TEST(PgaStackingAtRest, ARestingColumnKeepsItsWarmStartsAndSkipsMostProjections) {
  check_resting_column<pga::Backend>();
}
TEST(PgaStackingAtRest, AColumnsKeptContactsGiveWhatTestingEveryPairGives) {
  check_column_kept_contacts<pga::Backend>();
}

}  // namespace gacompare::testing
