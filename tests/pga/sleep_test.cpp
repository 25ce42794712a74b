// tests/sleep_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../sleep_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, SleepCases, pga::Backend);
}
