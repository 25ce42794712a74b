// tests/collision_step_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"

#include "../collision_step_cases.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, CollisionStepCases, traditional::Backend);
}
