// pga/rotation_group.hpp: the motor as a group for the Lie-group integrators
// (tests/rotation_group_cases.hpp).
#include "pga/rotation_group.hpp"
#include "../rotation_group_cases.hpp"

namespace gacompare::testing {
using Groups = ::testing::Types<pga::MotorGroup>;
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, RotationGroupCases, Groups);
}  // namespace gacompare::testing
