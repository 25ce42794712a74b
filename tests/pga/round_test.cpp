// tests/round_cases.hpp and tests/capsule_cases.hpp through the pga backend.
#include "pga/backend.hpp"
#include "pga/narrowphase.hpp"

#include "../capsule_cases.hpp"  // and ../round_cases.hpp

namespace {
struct Pga {
  using Backend = gacompare::pga::Backend;
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::pga::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, RoundCases, Pga);
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, CapsuleCases, Pga);
}
