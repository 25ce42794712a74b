// cga/rigid_body.hpp (rotor and bivectors, eq. 35) against the analytic
// rigid-body cases.
#include "cga/backend.hpp"
#include "cga/rotation_group.hpp"
#include "../lie_bodies_cases.hpp"
#include "../rigid_cases.hpp"

namespace gacompare::testing {
struct Rotor {
  using Backend = cga::Backend;
  using Group = cga::RotorGroup;  // the Lie-group methods' step (tests/lie_bodies_cases.hpp)
  static constexpr const char* options = "{}";
};
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, RigidCases, Rotor);
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, LieBodiesCases, Rotor);
}  // namespace gacompare::testing
