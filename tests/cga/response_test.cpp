// tests/response_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../response_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, ResponseCases, cga::Backend);
}
