// tests/round_cases.hpp and tests/capsule_cases.hpp through the traditional backend.
#include "traditional/backend.hpp"
#include "traditional/narrowphase.hpp"

#include "../capsule_cases.hpp"  // and ../round_cases.hpp

namespace {
struct Traditional {
  using Backend = gacompare::traditional::Backend;
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::traditional::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, RoundCases, Traditional);
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, CapsuleCases, Traditional);
}
