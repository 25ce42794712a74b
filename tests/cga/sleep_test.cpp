// tests/sleep_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../sleep_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, SleepCases, cga::Backend);
}
