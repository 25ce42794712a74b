#pragma once
// Basis blades of a Clifford algebra Cl(p,q) as bitmasks, and the sign of their
// products: the compile-time replacement of the report's run-time "grade
// tracking" (Appendix A). A basis blade is the ordered product of the basis
// vectors whose bits are set, lowest index first: blade 0b101 is e1e3.
//
// Cl(3,0): e1 e2 e3, all squaring to +1.
// Cl(4,1): e1 e2 e3 e (+1) ē (−1), bits 0..4, so a Cl(3,0) blade has the same
// bitmask in Cl(4,1) and embedding is a copy (docs/architecture.md "Conventions").
// Cl(3,0,1): e0 (squaring to 0) e1 e2 e3, bits 0..3: the degenerate vectors
// come first, as the plane-based literature writes e0 first (pga/algebra/cl301.hpp).
#include <bit>
#include <cstdint>
#include <initializer_list>

namespace gacompare::cga {

// A set of basis blades: bit k set means blade k (itself a bitmask of basis
// vectors) is present. 2^5 = 32 blades for Cl(4,1), hence 64 bits of room.
using BladeSet = std::uint64_t;

template <int P, int Q, int R = 0>
struct Algebra {
  static constexpr int p = P;
  static constexpr int q = Q;
  static constexpr int r = R;  // vectors squaring to 0
  static constexpr int dim = P + Q + R;
  static constexpr unsigned blade_count = 1u << dim;
  static constexpr unsigned pseudoscalar = blade_count - 1;
  static constexpr BladeSet all = blade_count == 64 ? ~BladeSet{0} : (BladeSet{1} << blade_count) - 1;
  // Square of basis vector i: the first R square to 0, the next P to +1, the last Q to −1.
  static constexpr int metric(int i) { return i < R ? 0 : i < R + P ? 1 : -1; }
};

using Cl3 = Algebra<3, 0>;
using Cl41 = Algebra<4, 1>;
using Cl301 = Algebra<3, 0, 1>;

constexpr int grade_of(unsigned blade) { return std::popcount(blade); }

// Sign of the product of basis blades a and b: (−1)^(swaps to sort the vectors)
// times the squares of the vectors the two share. The product blade is a ^ b.
// 0 when they share a vector squaring to 0 (the product vanishes).
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

// Whether product p keeps the pair of blades (a, b), by grade alone: a
// degenerate metric can still make the term zero (blade_sign 0), which the
// tables test separately (multivector.hpp, term_exists).
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

// A term of product p that is not identically zero.
template <class A>
constexpr bool term_exists(Product p, unsigned a, unsigned b) {
  return product_keeps(p, a, b) && blade_sign<A>(a, b) != 0;
}

}  // namespace gacompare::cga
