// The compile-time sparse products against the dense run-time oracle on seeded
// random multivectors, and the algebra's identities. Tolerance 1e-13 relative
// (testing.hpp): each component is a sum of at most 32 products of O(1) values.
#include "cga/algebra/cl41.hpp"
#include "testing.hpp"

#include <type_traits>

namespace gacompare::cga {
namespace {
using testing::random_mv;
using testing::same;

constexpr int kCases = 200;

template <class MA, class MB>
void check_products() {
  for (int k = 0; k < kCases; ++k) {
    const auto a = random_mv<MA>();
    const auto b = random_mv<MB>();
    const auto da = to_dense(a), db = to_dense(b);
    ASSERT_TRUE(same(a * b, da * db));
    ASSERT_TRUE(same(a ^ b, da ^ db));
    ASSERT_TRUE(same(a | b, da | db));
    ASSERT_TRUE(same(rc(a, b), dense_product(Product::right_contraction, da, db)));
    ASSERT_TRUE(same(inner(a, b), dense_product(Product::inner, da, db)));
    ASSERT_NEAR(scalar_product(a, b), (da * db).c[0], 1e-13 * 32);
    ASSERT_TRUE(same(~a, reverse(da)));
    ASSERT_TRUE(same(a + b, da + db));
  }
}

TEST(Multivector, Cl3SparseMatchesDense) {
  check_products<Full3, Full3>();
  check_products<Vector3, Vector3>();
  check_products<Rotor3, Vector3>();
  check_products<Rotor3, Rotor3>();
  check_products<Bivector3, Trivector3>();
}

// Cl(3,0,1): the tables drop the terms e0² = 0 removes, and agree with the
// dense oracle, which multiplies them by 0 (pga/algebra/cl301.hpp's types).
TEST(Multivector, Cl301SparseMatchesDense) {
  using Full = Multivector<Cl301, Cl301::all>;
  using Even = Multivector<Cl301, grades<Cl301>({0, 2, 4})>;
  using Vec = Multivector<Cl301, grades<Cl301>({1})>;
  using Tri = Multivector<Cl301, grades<Cl301>({3})>;
  check_products<Full, Full>();
  check_products<Even, Even>();
  check_products<Even, Tri>();
  check_products<Vec, Tri>();
  // The motor product keeps 48 of its 64 terms: 16 share e0.
  static_assert(detail::Table<Cl301, Product::geometric, Even::blades, Even::blades, ~BladeSet{0}>::n == 48);
}

TEST(Multivector, Cl41SparseMatchesDense) {
  check_products<Full5, Full5>();
  check_products<Vector5, Vector5>();
  check_products<Vector5, Quadvector5>();
  check_products<Trivector5, Bivector5>();
  check_products<Even5, Vector5>();
  check_products<Translator, Vector5>();
  check_products<Full5, Trivector5>();
}

TEST(Multivector, ResultTypesAreComputedAtCompileTime) {
  static_assert(std::is_same_v<decltype(Vector3{} * Vector3{}), Rotor3>);
  static_assert(std::is_same_v<decltype(Vector3{} ^ Vector3{}), Bivector3>);
  static_assert(std::is_same_v<decltype(Vector3{} | Vector3{}), Scalar3>);
  static_assert(std::is_same_v<decltype(Rotor3{} * Rotor3{}), Rotor3>);
  static_assert(std::is_same_v<decltype(Vector5{} ^ Vector5{} ^ Vector5{}), Trivector5>);
  static_assert(std::is_same_v<decltype(Vector5{} ^ Vector5{} ^ Vector5{} ^ Vector5{}), Quadvector5>);
  static_assert(std::is_same_v<decltype(Vector5{} | Quadvector5{}), Trivector5>);
  static_assert(std::is_same_v<decltype(!Quadvector5{}), Vector5>);
  static_assert(std::is_same_v<decltype(Trivector3{} ^ Vector3{}), Multivector<Cl3, 0>>);
  static_assert(Rotor3::size == 4 && Vector5::size == 5 && Translator::size == 7);
  SUCCEED();
}

TEST(Multivector, GeometricProductIsAssociative) {
  for (int k = 0; k < kCases; ++k) {
    const auto a = random_mv<Full5>(), b = random_mv<Full5>(), c = random_mv<Full5>();
    const auto lhs = (a * b) * c, rhs = a * (b * c);
    for (int i = 0; i < Full5::size; ++i) ASSERT_NEAR(lhs.c[i], rhs.c[i], 1e-12);
  }
}

TEST(Multivector, VectorProductIsInnerPlusOuter) {
  // ab = a·b + a∧b (eq. 1), for vectors of both algebras.
  for (int k = 0; k < kCases; ++k) {
    const auto a = random_mv<Vector5>(), b = random_mv<Vector5>();
    const auto ab = a * b;
    const auto sum = (a | b) + (a ^ b);
    for (int i = 0; i < decltype(ab)::size; ++i) ASSERT_NEAR(ab.c[i], sum.c[i], 1e-14);
    const auto u = random_mv<Vector3>(), v = random_mv<Vector3>();
    const auto uv = u * v, usum = (u | v) + (u ^ v);
    for (int i = 0; i < 4; ++i) ASSERT_NEAR(uv.c[i], usum.c[i], 1e-14);
  }
}

TEST(Multivector, ReverseInvoluteConjugate) {
  const auto a = random_mv<Full5>(), b = random_mv<Full5>();
  // (ab)~ = b̃ ã, and conjugate = reverse ∘ involute.
  const auto l = ~(a * b), r = ~b * ~a;
  for (int i = 0; i < Full5::size; ++i) EXPECT_NEAR(l.c[i], r.c[i], 1e-12);
  const auto c = conjugate(a), ri = reverse(involute(a));
  for (int i = 0; i < Full5::size; ++i) EXPECT_EQ(c.c[i], ri.c[i]);
  EXPECT_EQ(involute(Vector5{{1, 2, 3, 4, 5}}).c[2], -3.0);
}

TEST(Multivector, GradeProjection) {
  const auto a = random_mv<Full5>();
  const auto g2 = grade<2>(a);
  static_assert(std::is_same_v<std::remove_const_t<decltype(g2)>, Bivector5>);
  for (int k = 0; k < Bivector5::size; ++k) EXPECT_EQ(g2.c[k], a[Bivector5::blade_at(k)]);
}

TEST(Multivector, DualAndUndualAreInverse) {
  for (int k = 0; k < kCases; ++k) {
    const auto a = random_mv<Trivector5>();
    const auto back = undual(dual(a));
    for (int i = 0; i < Trivector5::size; ++i) ASSERT_NEAR(back.c[i], a.c[i], 1e-15);
    const auto v = random_mv<Vector3>();
    // In Cl(3,0) the dual of a vector is the bivector a I⁻¹ = −a I.
    const auto d = dual(v);
    const auto expected = -1.0 * bivector_of_axial(v);
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(d.c[i], expected.c[i], 1e-15);
  }
}

TEST(Multivector, InverseOfVersorsAndBlades) {
  for (int k = 0; k < kCases; ++k) {
    // A versor: product of random vectors (non-null with probability 1).
    const auto v = random_mv<Vector5>() * random_mv<Vector5>() * random_mv<Vector5>();
    const auto inv = inverse(v);
    ASSERT_TRUE(inv.has_value());
    const auto one = v * *inv;
    ASSERT_NEAR(one.get<0>(), 1.0, 1e-9);
    for (int i = 1; i < decltype(one)::size; ++i) ASSERT_NEAR(one.c[i], 0.0, 1e-9);
  }
  // A null vector (a conformal point) has no inverse: typed nullopt, not inf/NaN.
  EXPECT_FALSE(inverse(up(1, 2, 3)).has_value());
  EXPECT_FALSE(inverse(n_inf()).has_value());
}

TEST(Multivector, RunTimeIndexAndAccessors) {
  Vector5 v{{1, 2, 3, 4, 5}};
  EXPECT_EQ(v[e5::e2], 2);
  EXPECT_EQ(v[e5::e1 | e5::e2], 0);
  EXPECT_EQ(v.get<e5::ebar>(), 5);
  v.at<e5::e>() = 7;
  EXPECT_EQ(v.c[3], 7);
}

}  // namespace
}  // namespace gacompare::cga
