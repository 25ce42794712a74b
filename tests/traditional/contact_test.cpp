// tests/contact_cases.hpp through the traditional backend: every case with
// rotation matrices, and again with quaternions (the two representations turn
// the same impulses into different rounding).
#include "traditional/backend.hpp"

#include "../contact_cases.hpp"

namespace gacompare::testing {

using TraditionalContact = ContactFamily<traditional::Backend>;
TEST_P(TraditionalContact, MeetsItsAnalyticOutcome) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, TraditionalContact, ::testing::ValuesIn(contact_cases()), case_test_name);

using TraditionalQuaternionContact = ContactFamily<traditional::Backend, core::Rotation::quaternion>;
TEST_P(TraditionalQuaternionContact, MeetsItsAnalyticOutcome) { check_case(); }
INSTANTIATE_TEST_SUITE_P(Family, TraditionalQuaternionContact, ::testing::ValuesIn(contact_cases()), case_test_name);

INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, ContactBundled, traditional::Backend);

}  // namespace gacompare::testing
