// tests/narrowphase_cases.hpp through cga/narrowphase.hpp.
#include "cga/narrowphase.hpp"
#include "cga/geometry/meet.hpp"
#include "cga/segment_triangle.hpp"

#include "../narrowphase_cache_cases.hpp"
#include "../narrowphase_cases.hpp"

namespace {
struct Cga {
  using Body = gacompare::cga::Body;
  static auto segment_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d, const Eigen::Vector3d& e) {
    return gacompare::cga::segment_triangle(a, b, c, d, e);
  }
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::cga::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, NarrowphaseCases, Cga);
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, NarrowphaseCacheCases, Cga);
}

// The manifold's line–plane crossing in cga (Body::cut, the meet written out
// from the two inner products the clipper already has) against the generic
// meet of cga/geometry/meet.hpp, π⌋(X0 ∧ X1 ∧ n), on seeded random segments
// and planes: the same point within 1e-12 (both are a handful of operations
// on coordinates of size ~1; segments nearly parallel to the plane, where
// either divides by a small weight, are skipped).
TEST(CgaManifold, CutIsTheMeetOfTheLineAndThePlane) {
  using gacompare::cga::Body;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  int compared = 0;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d x0(u(rng), u(rng), u(rng)), x1(u(rng), u(rng), u(rng)), n(u(rng), u(rng), u(rng));
    const Body::Plane pi = Body::plane_through(gacompare::cga::up(Eigen::Vector3d(u(rng), u(rng), u(rng))), n);
    const Body::Point p0 = gacompare::cga::up(x0), p1 = gacompare::cga::up(x1);
    const double d0 = Body::distance(pi, p0), d1 = Body::distance(pi, p1);
    if (!(d0 * d1 < 0) || std::abs(d0 - d1) < 1e-3 * n.norm() * (x1 - x0).norm()) continue;
    const auto line = gacompare::cga::line_through(x0, x1);
    ASSERT_TRUE(line);
    const auto meet = gacompare::cga::meet_line_plane(*line, pi);
    ASSERT_EQ(meet.kind, gacompare::geometry::Kind::point);
    EXPECT_NEAR((Body::position(Body::cut(p0, d0, p1, d1)) - meet.point).norm(), 0, 1e-12);
    ++compared;
  }
  EXPECT_GT(compared, 300);
}
