// tests/collision_step_cases.hpp through the pga backend.
#include "pga/backend.hpp"

#include "../collision_step_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, CollisionStepCases, pga::Backend);
}
