// The particle validation problems through the cga backend.
#include "cga/backend.hpp"
#include "../dynamics_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, DynamicsCases, cga::Backend);
}
