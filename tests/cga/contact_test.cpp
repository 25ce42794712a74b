// tests/contact_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../contact_cases.hpp"

namespace gacompare::testing {

using CgaContact = ContactFamily<cga::Backend>;
TEST_P(CgaContact, MeetsItsAnalyticOutcome) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, CgaContact, ::testing::ValuesIn(contact_cases()), case_test_name);

INSTANTIATE_TYPED_TEST_SUITE_P(Cga, ContactBundled, cga::Backend);

}  // namespace gacompare::testing
