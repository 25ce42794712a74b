// tests/friction_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"

#include "../friction_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, FrictionCases, traditional::Backend);
}
