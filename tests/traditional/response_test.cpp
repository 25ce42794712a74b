// tests/response_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"

#include "../response_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, ResponseCases, traditional::Backend);
}
