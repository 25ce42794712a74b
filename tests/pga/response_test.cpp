// tests/response_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../response_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, ResponseCases, pga::Backend);
}
