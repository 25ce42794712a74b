// cga/rotation_group.hpp: the rotor as a group for the Lie-group integrators
// (tests/rotation_group_cases.hpp).
#include "cga/rotation_group.hpp"
#include "../rotation_group_cases.hpp"

namespace gacompare::testing {
using Groups = ::testing::Types<cga::RotorGroup>;
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, RotationGroupCases, Groups);
}  // namespace gacompare::testing
