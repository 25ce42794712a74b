// The particle validation problems through the traditional backend.
#include "traditional/backend.hpp"
#include "../dynamics_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, DynamicsCases, traditional::Backend);
}
