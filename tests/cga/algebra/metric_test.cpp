// blade_sign against a brute-force reduction of basis-vector words built from
// the metric alone: concatenate the two words, bubble-sort them (each swap of
// two distinct anticommuting vectors flips the sign) and contract equal
// neighbours by their square. Shares no code with blade_sign's popcount rule.
#include "cga/algebra/dense.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gacompare::cga {
namespace {

template <class A>
std::pair<int, unsigned> reduce_word(unsigned a, unsigned b) {
  std::vector<int> w;
  for (int i = 0; i < A::dim; ++i)
    if ((a >> i) & 1u) w.push_back(i);
  for (int i = 0; i < A::dim; ++i)
    if ((b >> i) & 1u) w.push_back(i);
  int sign = 1;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t k = 0; k + 1 < w.size(); ++k) {
      if (w[k] == w[k + 1]) {
        sign *= A::metric(w[k]);
        w.erase(w.begin() + static_cast<long>(k), w.begin() + static_cast<long>(k) + 2);
        changed = true;
        break;
      }
      if (w[k] > w[k + 1]) {
        std::swap(w[k], w[k + 1]);
        sign = -sign;
        changed = true;
      }
    }
  }
  unsigned blade = 0;
  for (int i : w) blade |= 1u << i;
  return {sign, blade};
}

template <class A>
void check_table() {
  for (unsigned a = 0; a < A::blade_count; ++a)
    for (unsigned b = 0; b < A::blade_count; ++b) {
      const auto [sign, blade] = reduce_word<A>(a, b);
      ASSERT_EQ(blade, a ^ b) << a << " * " << b;
      ASSERT_EQ(sign, blade_sign<A>(a, b)) << a << " * " << b;
      // The dense Cayley table and the sparse kernel of the same pair agree too.
      Dense<A> da, db;
      da.c[a] = 1;
      db.c[b] = 1;
      ASSERT_EQ((da * db).c[a ^ b], sign);
    }
}

TEST(Metric, Cl3BladeProductsMatchBruteForce) { check_table<Cl3>(); }
TEST(Metric, Cl41BladeProductsMatchBruteForce) { check_table<Cl41>(); }
// The degenerate metric of plane-based GA: a product sharing e0 is 0 in both.
TEST(Metric, Cl301BladeProductsMatchBruteForce) { check_table<Cl301>(); }

template <unsigned A, unsigned B, class Alg>
void check_sparse_pair() {
  Multivector<Alg, BladeSet{1} << A> a{{1.0}};
  Multivector<Alg, BladeSet{1} << B> b{{1.0}};
  const auto r = a * b;
  static_assert(decltype(r)::blades == (BladeSet{1} << (A ^ B)), "one blade in, one blade out");
  EXPECT_EQ(r.c[0], reduce_word<Alg>(A, B).first) << A << " * " << B;
}

template <unsigned A, std::size_t... J>
void check_sparse_row(std::index_sequence<J...>) {
  (check_sparse_pair<A, static_cast<unsigned>(J), Cl41>(), ...);
}

template <std::size_t... I>
void check_sparse_all(std::index_sequence<I...>) {
  (check_sparse_row<static_cast<unsigned>(I)>(std::make_index_sequence<32>{}), ...);
}

TEST(Metric, Cl41SparseBladePairsMatchBruteForce) {
  // Every pair of the 32 × 32 basis blades through the compile-time kernel.
  check_sparse_all(std::make_index_sequence<32>{});
}

TEST(Metric, PseudoscalarSquaresToMinusOne) {
  EXPECT_EQ(blade_sign<Cl3>(7, 7), -1);
  EXPECT_EQ(blade_sign<Cl41>(31, 31), -1);
}

TEST(Metric, GradeSets) {
  EXPECT_EQ(grades<Cl3>({1}), BladeSet{0b00010110});
  EXPECT_EQ(grades<Cl3>({0, 2}), BladeSet{0b01101001});
  EXPECT_EQ(std::popcount(grades<Cl41>({2})), 10);
  EXPECT_EQ(std::popcount(grades<Cl41>({3})), 10);
  EXPECT_EQ(grades_in<Cl41>(grades<Cl41>({1, 3})), 0b1010u);
}

}  // namespace
}  // namespace gacompare::cga
