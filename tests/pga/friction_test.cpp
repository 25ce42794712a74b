// tests/friction_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../friction_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, FrictionCases, pga::Backend);
}
