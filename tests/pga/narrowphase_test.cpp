// tests/narrowphase_cases.hpp through pga/narrowphase.hpp, and the pga forms
// it chose against the generic products they are written out from.
#include "pga/narrowphase.hpp"
#include "pga/segment_triangle.hpp"

#include "../narrowphase_cache_cases.hpp"
#include "../narrowphase_cases.hpp"

namespace {
struct Pga {
  using Body = gacompare::pga::Body;
  static auto segment_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d, const Eigen::Vector3d& e) {
    return gacompare::pga::segment_triangle(a, b, c, d, e);
  }
  static auto narrowphase(const gacompare::collision::Placed& a, const gacompare::collision::Placed& b,
                          gacompare::collision::Method m, std::vector<gacompare::collision::FeatureContact>* out) {
    return gacompare::pga::narrowphase(a, b, m, out);
  }
};
}  // namespace

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, NarrowphaseCases, Pga);
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, NarrowphaseCacheCases, Pga);
}

namespace gacompare::pga {
namespace {

// The manifold's crossing (Body::cut, the combination d0 X1 − d1 X0) against
// the meet of the plane with the join, π ∧ (X0 ∨ X1), formed by the generic
// products, on seeded random segments: the same point within 1e-12 (a few
// operations on size-1 coordinates; near-parallel segments skipped, where
// either divides by a small weight).
TEST(PgaManifold, CutIsTheMeetOfThePlaneAndTheJoin) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  int compared = 0;
  for (int k = 0; k < 1000; ++k) {
    const Vec3 x0(u(rng), u(rng), u(rng)), x1(u(rng), u(rng), u(rng)), n(u(rng), u(rng), u(rng));
    const Plane pi = Body::plane_through(point(Vec3(u(rng), u(rng), u(rng))), n);
    const Point p0 = point(x0), p1 = point(x1);
    const double d0 = Body::distance(pi, p0), d1 = Body::distance(pi, p1);
    if (!(d0 * d1 < 0) || std::abs(d0 - d1) < 1e-3 * n.norm() * (x1 - x0).norm()) continue;
    const Point meet = pi ^ join(p0, p1);
    EXPECT_NEAR((Body::position(Body::cut(p0, d0, p1, d1)) - euclid(meet)).norm(), 0, 1e-12);
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

// The face test π ∧ X is n·x − d, and the edge axis the cross product, on
// seeded random inputs (rounding of a few size-1 products: 1e-14).
TEST(PgaNarrowphase, FaceTestAndEdgeAxisAreTheEuclideanOnes) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k) {
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized(), x(u(rng), u(rng), u(rng)), a(u(rng), u(rng), u(rng));
    const double d = u(rng);
    EXPECT_NEAR(NarrowAlgebra::distance(plane(n, d), point(x)), n.dot(x) - d, 1e-14);
    EXPECT_NEAR((NarrowAlgebra::edge_axis(n, a) - n.cross(a)).norm(), 0, 1e-14);
    EXPECT_NEAR(NarrowAlgebra::distance2(point(x), point(a)), (x - a).squaredNorm(), 1e-14);
  }
}

}  // namespace
}  // namespace gacompare::pga
