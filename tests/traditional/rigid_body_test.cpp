// traditional/rigid_body.hpp, with the rotation as a matrix (eq. 34) and as a
// quaternion, against the analytic rigid-body cases.
#include "traditional/backend.hpp"
#include "../rigid_cases.hpp"

namespace gacompare::testing {
struct Matrix {
  using Backend = traditional::Backend;
  static constexpr const char* options = R"({"rotation": "matrix"})";
};
struct Quaternion {
  using Backend = traditional::Backend;
  static constexpr const char* options = R"({"rotation": "quaternion"})";
};
using Variants = ::testing::Types<Matrix, Quaternion>;
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, RigidCases, Variants);
}  // namespace gacompare::testing
