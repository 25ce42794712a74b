// The particle validation problems through the pga backend.
#include "pga/backend.hpp"

#include "../dynamics_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, DynamicsCases, pga::Backend);
}
