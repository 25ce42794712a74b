// tests/round_cases.hpp and tests/capsule_cases.hpp through the cga backend.
#include "cga/backend.hpp"
#include "cga/narrowphase.hpp"

#include "../capsule_cases.hpp"  // and ../round_cases.hpp

namespace {
struct Cga {
  using Backend = gacompare::cga::Backend;
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::cga::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, RoundCases, Cga);
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, CapsuleCases, Cga);
}
