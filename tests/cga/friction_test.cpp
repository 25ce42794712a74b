// tests/friction_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../friction_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, FrictionCases, cga::Backend);
}
