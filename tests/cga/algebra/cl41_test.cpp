// The conformal model's conventions (docs/architecture.md) and versors (§1.3, §1.4),
// each against its closed-form Euclidean meaning. Tolerances: 1e-13 on O(1)
// coordinates (a handful of roundings through x² terms).
#include "cga/algebra/cl41.hpp"
#include "testing.hpp"

namespace gacompare::cga {
namespace {
using testing::uniform;

Eigen::Vector3d random_point(double r = 1) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }

TEST(Cl41, NullVectorsAndUpProjection) {
  EXPECT_EQ(scalar_product(n_inf(), n_inf()), 0);
  EXPECT_EQ(scalar_product(n_origin(), n_origin()), 0);
  EXPECT_EQ(scalar_product(n_inf(), n_origin()), 2);  // n·n̄ = 2
  for (int k = 0; k < 1000; ++k) {
    const auto x = random_point(), y = random_point();
    const auto X = up(x), Y = up(y);
    ASSERT_NEAR(scalar_product(X, X), 0, 1e-15);                          // null (fn 8)
    ASSERT_NEAR(scalar_product(X, Y), -0.5 * (x - y).squaredNorm(), 1e-14);  // X·Y = −½|x−y|²
    ASSERT_NEAR(scalar_product(X, n_inf()), -1, 1e-15);                   // X·n = −1
    ASSERT_LT((*down(X) - x).norm(), 1e-15);
    ASSERT_LT((*down(X * 3.5) - x).norm(), 1e-15);  // down normalises
  }
  EXPECT_FALSE(down(n_inf()).has_value());  // the point at infinity has no position
  EXPECT_EQ(up(0, 0, 0).c[3], -0.5);        // up(0) = −½ n̄ = −½ e + ½ ē
}

TEST(Cl41, TranslatorMovesPoints) {
  // eq. 16: T up(x) T̃ = up(x + a), and T n T̃ = n.
  for (int k = 0; k < 1000; ++k) {
    const auto x = random_point(), a = random_point(3);
    const auto T = translator(a);
    const auto moved = sandwich(T, up(x));
    const auto expected = up(x + a);
    for (int i = 0; i < 5; ++i) ASSERT_NEAR(moved.c[i], expected.c[i], 1e-13);
    const auto n = sandwich(T, widen<Vector5::blades>(n_inf()));
    for (unsigned b = 0; b < 32; ++b) ASSERT_NEAR(n[b], n_inf()[b], 1e-15);
    // T T̃ = 1 exactly in exact arithmetic; in doubles the |a|²/4-sized terms of
    // (na/2)(an/2) cancel, leaving a few ulps of their size.
    const auto tt = T * ~T;
    ASSERT_NEAR(tt.get<0>(), 1, 1e-15 * (1 + a.squaredNorm()));
  }
}

TEST(Cl41, TranslatorIsExpOfNullBivector) {
  // eq. 15: T = exp(n a / 2) = 1 + n a / 2 because n a is null.
  const Eigen::Vector3d a(0.3, -1.2, 2.5);
  const auto b = grade<2>(n_inf() * embed(vector3(a)) * 0.5);
  const auto T = exp_blade(b);
  ASSERT_TRUE(T.has_value());
  const auto expected = widen<Even5::blades>(translator(a));
  for (int i = 0; i < Even5::size; ++i) EXPECT_NEAR(T->c[i], expected.c[i], 1e-15);
}

TEST(Cl41, DilatorScalesAboutTheOrigin) {
  // §1.4.2 eq. 14: D up(x) D̃ = e^α up(e^−α x).
  for (int k = 0; k < 200; ++k) {
    const double alpha = uniform(-2, 2);
    const auto x = random_point();
    const auto D = dilator(alpha);
    const auto got = sandwich(D, up(x));
    const auto expected = up(std::exp(-alpha) * x) * std::exp(alpha);
    for (int i = 0; i < 5; ++i) ASSERT_NEAR(got.c[i], expected.c[i], 1e-12);
    const auto viaexp = exp_blade(Multivector<Cl41, BladeSet{1} << 24>{{alpha / 2}});
    ASSERT_TRUE(viaexp.has_value());
    ASSERT_NEAR(viaexp->get<0>(), D.get<0>(), 1e-15);
    ASSERT_NEAR(viaexp->get<24>(), D.get<24>(), 1e-15);
  }
}

TEST(Cl41, RotationRotorActsOnConformalPoints) {
  // eq. 12–13: a Cl(3,0) rotor leaves n and n̄ fixed, so R up(x) R̃ = up(R x R̃).
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d axis = random_point().normalized();
    const double angle = uniform(-3, 3);
    const auto r3 = rotor_from_axis_angle(vector3(axis), angle);
    const Rotor5 r = embed(r3);
    const auto x = random_point(2);
    const auto got = sandwich(r, up(x));
    const auto expected = up(to_eigen(sandwich(r3, vector3(x))));
    for (int i = 0; i < 5; ++i) ASSERT_NEAR(got.c[i], expected.c[i], 1e-13);
    const auto rot_exp = exp_blade(embed(bivector_of_axial(vector3(axis))) * (-0.5 * angle));
    ASSERT_TRUE(rot_exp.has_value());
    for (int i = 0; i < Rotor5::size; ++i) ASSERT_NEAR((*rot_exp)[Rotor5::blade_at(i)], r.c[i], 1e-15);
  }
}

TEST(Cl41, MotorComposesTranslationAndRotation) {
  // Composition (§1.4.3 last line): apply R then T, or once as M = T R.
  const auto r = embed(rotor_from_axis_angle(vector3(1, 0, 0), 0.7));
  const auto T = translator({1, 2, 3});
  const auto M = T * r;
  const auto x = up(0.5, -0.25, 2.0);
  const auto stepwise = sandwich(T, sandwich(r, x));
  const auto once = sandwich(M, x);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(once.c[i], stepwise.c[i], 1e-14);
}

TEST(Cl41, ExpRejectsNonBlades) {
  // e12 + e3e is not a blade (its square has a grade-4 part): typed failure, not NaN.
  Bivector5 b;
  b.at<e5::e1 | e5::e2>() = 1;
  b.at<e5::e3 | e5::e>() = 1;
  EXPECT_FALSE(exp_blade(b).has_value());
}

}  // namespace
}  // namespace gacompare::cga

namespace gacompare::cga {
namespace {
TEST(Cl41, OutermorphismMatchesSandwich) {
  // The 5×5 matrix of a motor applied to a point equals the sandwich (1e-13:
  // both are short sums of O(1) products, but through different roundings).
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d axis = Eigen::Vector3d(testing::uniform(), testing::uniform(), testing::uniform()).normalized();
    const auto M = translator({testing::uniform(), testing::uniform(), testing::uniform()}) *
                   embed(rotor_from_axis_angle(vector3(axis), testing::uniform(-3, 3)));
    const auto X = up(testing::uniform(), testing::uniform(), testing::uniform());
    const auto by_sandwich = sandwich(M, X);
    const Eigen::Matrix<double, 5, 1> by_matrix =
        outermorphism(M) * Eigen::Matrix<double, 5, 1>(X.c[0], X.c[1], X.c[2], X.c[3], X.c[4]);
    for (int i = 0; i < 5; ++i) ASSERT_NEAR(by_matrix[i], by_sandwich.c[i], 1e-13);
  }
}
}  // namespace
}  // namespace gacompare::cga
