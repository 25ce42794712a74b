#pragma once
// The dense run-time multivector: all 2^n components, every product a loop over
// the whole Cayley table. This is the 2003 approach (a general multivector of 32
// components, Appendix A) kept for two jobs: the baseline the sparse types are
// benchmarked against, and a test oracle that shares no code path with the
// compile-time tables (only the blade-sign rule, itself tested against a
// brute-force reduction of basis-vector words).
#include "cga/algebra/multivector.hpp"

#include <array>

namespace gacompare::cga {

template <class A>
struct Dense {
  static constexpr unsigned n = A::blade_count;
  std::array<double, n> c{};  // indexed by blade bitmask

  struct Cayley {
    std::array<std::array<signed char, n>, n> sign{};
    constexpr Cayley() {
      for (unsigned a = 0; a < n; ++a)
        for (unsigned b = 0; b < n; ++b) sign[a][b] = static_cast<signed char>(blade_sign<A>(a, b));
    }
  };
  static constexpr Cayley cayley{};

  double operator[](unsigned blade) const { return c[blade]; }
  double& operator[](unsigned blade) { return c[blade]; }
};

template <class A>
Dense<A> dense_product(Product p, const Dense<A>& a, const Dense<A>& b) {
  Dense<A> r;
  for (unsigned i = 0; i < Dense<A>::n; ++i)
    for (unsigned j = 0; j < Dense<A>::n; ++j)
      if (product_keeps(p, i, j)) r.c[i ^ j] += Dense<A>::cayley.sign[i][j] * a.c[i] * b.c[j];
  return r;
}

template <class A>
Dense<A> operator*(const Dense<A>& a, const Dense<A>& b) { return dense_product(Product::geometric, a, b); }
template <class A>
Dense<A> operator^(const Dense<A>& a, const Dense<A>& b) { return dense_product(Product::outer, a, b); }
template <class A>
Dense<A> operator|(const Dense<A>& a, const Dense<A>& b) { return dense_product(Product::left_contraction, a, b); }

template <class A>
Dense<A> reverse(const Dense<A>& a) {
  Dense<A> r;
  for (unsigned i = 0; i < Dense<A>::n; ++i) r.c[i] = reverse_sign(grade_of(i)) * a.c[i];
  return r;
}
template <class A>
Dense<A> operator~(const Dense<A>& a) { return reverse(a); }

template <class A>
Dense<A> operator+(const Dense<A>& a, const Dense<A>& b) {
  Dense<A> r;
  for (unsigned i = 0; i < Dense<A>::n; ++i) r.c[i] = a.c[i] + b.c[i];
  return r;
}

// Conversions between the two representations (tests, benchmarks).
template <class A, BladeSet S>
Dense<A> to_dense(const Multivector<A, S>& m) {
  Dense<A> d;
  for (int k = 0; k < Multivector<A, S>::size; ++k) d.c[Multivector<A, S>::blade_at(k)] = m.c[k];
  return d;
}

}  // namespace gacompare::cga
