#pragma once
// Basis blades of a Clifford algebra Cl(p,q) as bitmasks, and the sign of their
// products: the compile-time replacement of the report's run-time "grade
// tracking" (Appendix A). A basis blade is the ordered product of the basis
// vectors whose bits are set, lowest index first: blade 0b101 is e1e3.
//
// Cl(3,0): e1 e2 e3, all squaring to +1.
// Cl(4,1): e1 e2 e3 e (+1) ē (−1), bits 0..4, so a Cl(3,0) blade has the same
// bitmask in Cl(4,1) and embedding is a copy (docs/architecture.md "Conventions").
#include <bit>
#include <cstdint>
#include <initializer_list>

namespace gacompare::cga {

// A set of basis blades: bit k set means blade k (itself a bitmask of basis
// vectors) is present. 2^5 = 32 blades for Cl(4,1), hence 64 bits of room.
using BladeSet = std::uint64_t;

template <int P, int Q>
struct Algebra {
  static constexpr int p = P;
  static constexpr int q = Q;
  static constexpr int dim = P + Q;
  static constexpr unsigned blade_count = 1u << dim;
  static constexpr unsigned pseudoscalar = blade_count - 1;
  static constexpr BladeSet all = blade_count == 64 ? ~BladeSet{0} : (BladeSet{1} << blade_count) - 1;
  // Square of basis vector i: the first P square to +1, the last Q to −1.
  static constexpr int metric(int i) { return i < P ? 1 : -1; }
};

using Cl3 = Algebra<3, 0>;
using Cl41 = Algebra<4, 1>;

constexpr int grade_of(unsigned blade) { return std::popcount(blade); }

// Sign of the product of basis blades a and b: (−1)^(swaps to sort the vectors)
// times the squares of the vectors the two share. The product blade is a ^ b.
template <class A>
constexpr int blade_sign(unsigned a, unsigned b) {
  int swaps = 0;
  for (unsigned t = a >> 1; t != 0; t >>= 1) swaps += std::popcount(t & b);
  int sign = (swaps & 1) ? -1 : 1;
  const unsigned common = a & b;
  for (int i = 0; i < A::dim; ++i)
    if ((common >> i) & 1u) sign *= A::metric(i);
  return sign;
}

// The set of all blades of the listed grades.
template <class A>
constexpr BladeSet grades(std::initializer_list<int> gs) {
  BladeSet s = 0;
  for (unsigned b = 0; b < A::blade_count; ++b)
    for (int g : gs)
      if (grade_of(b) == g) s |= BladeSet{1} << b;
  return s;
}

// Grades present in a blade set, as a bitmask over grades.
template <class A>
constexpr unsigned grades_in(BladeSet s) {
  unsigned g = 0;
  for (unsigned b = 0; b < A::blade_count; ++b)
    if ((s >> b) & 1u) g |= 1u << grade_of(b);
  return g;
}

// Sign that reverse (~), grade involution and Clifford conjugation put on a
// blade of grade k.
constexpr int reverse_sign(int k) { return ((k * (k - 1) / 2) & 1) ? -1 : 1; }
constexpr int involute_sign(int k) { return (k & 1) ? -1 : 1; }
constexpr int conjugate_sign(int k) { return reverse_sign(k) * involute_sign(k); }

// The products, each a filter on basis-blade pairs of the geometric product.
//  geometric         ab
//  outer             a∧b: blades share no vector
//  left_contraction  a⌋b (Dorst): a's vectors all in b; grade(b) − grade(a)
//  right_contraction a⌊b: b's vectors all in a; grade(a) − grade(b)
//  inner             the symmetric "fat dot" a·b of grade |grade(a) − grade(b)|:
//                    the report's "·" (§1.2.2, eq. 1); equals ⌋ when grade(a) ≤ grade(b)
//  scalar            ⟨ab⟩₀
enum class Product { geometric, outer, left_contraction, right_contraction, inner, scalar };

constexpr bool product_keeps(Product p, unsigned a, unsigned b) {
  switch (p) {
    case Product::geometric: return true;
    case Product::outer: return (a & b) == 0;
    case Product::left_contraction: return (a & ~b) == 0;
    case Product::right_contraction: return (b & ~a) == 0;
    case Product::inner: return (a & ~b) == 0 || (b & ~a) == 0;
    case Product::scalar: return a == b;
  }
  return false;
}

}  // namespace gacompare::cga
