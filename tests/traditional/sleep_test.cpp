// tests/sleep_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"

#include "../sleep_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, SleepCases, traditional::Backend);
}
