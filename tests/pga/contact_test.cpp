// tests/contact_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../contact_cases.hpp"

namespace gacompare::testing {

using PgaContact = ContactFamily<pga::Backend>;
TEST_P(PgaContact, MeetsItsAnalyticOutcome) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, PgaContact, ::testing::ValuesIn(contact_cases()), case_test_name);
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, ContactBundled, pga::Backend);

}  // namespace gacompare::testing
