// tests/narrowphase_cases.hpp through traditional/narrowphase.hpp.
#include "traditional/narrowphase.hpp"
#include "traditional/segment_triangle.hpp"

#include "../narrowphase_cache_cases.hpp"
#include "../narrowphase_cases.hpp"

namespace {
struct Traditional {
  using Body = gacompare::traditional::Body;
  static auto segment_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d, const Eigen::Vector3d& e) {
    return gacompare::traditional::segment_triangle(a, b, c, d, e);
  }
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::traditional::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, NarrowphaseCases, Traditional);
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, NarrowphaseCacheCases, Traditional);
}
