// tests/collision_step_cases.hpp through the cga backend.
#include "cga/backend.hpp"

#include "../collision_step_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, CollisionStepCases, cga::Backend);
}
