// traditional/rotation_group.hpp: the matrix (Rodrigues) and the quaternion as
// groups for the Lie-group integrators (tests/rotation_group_cases.hpp).
#include "traditional/rotation_group.hpp"
#include "../rotation_group_cases.hpp"

namespace gacompare::testing {
using Groups = ::testing::Types<traditional::MatrixGroup, traditional::QuaternionGroup>;
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, RotationGroupCases, Groups);
}  // namespace gacompare::testing
