// cga/rigid_body.hpp (rotor and bivectors, eq. 35) against the analytic
// rigid-body cases.
#include "cga/backend.hpp"
#include "../rigid_cases.hpp"

namespace gacompare::testing {
struct Rotor {
  using Backend = cga::Backend;
  static constexpr const char* options = "{}";
};
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, RigidCases, Rotor);
}  // namespace gacompare::testing
