#pragma once
// Shared helpers for the algebra tests: seeded random multivectors and a
// component-wise comparison against the dense oracle.
#include "cga/algebra/dense.hpp"

#include <gtest/gtest.h>

#include <random>

namespace gacompare::cga::testing {

inline std::mt19937_64& rng() {
  static std::mt19937_64 g(20031);  // fixed seed: failures replay
  return g;
}
inline double uniform(double lo = -1, double hi = 1) {
  return std::uniform_real_distribution<double>(lo, hi)(rng());
}

template <class M>
M random_mv() {
  M m;
  for (double& x : m.c) x = uniform();
  return m;
}

// |a − b| per component ≤ tol · (1 + scale): products of O(1) random inputs with
// up to 32 terms per component round to a few ulps of their magnitude.
template <class A, BladeSet S>
::testing::AssertionResult same(const Multivector<A, S>& sparse, const Dense<A>& dense, double tol = 1e-13) {
  for (unsigned b = 0; b < A::blade_count; ++b) {
    const double x = sparse[b], y = dense.c[b];
    if (!(std::abs(x - y) <= tol * (1 + std::abs(y)))) {
      if (!Multivector<A, S>::has(b) && std::abs(y) <= tol) continue;
      return ::testing::AssertionFailure() << "blade " << b << ": sparse " << x << " vs dense " << y;
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace gacompare::cga::testing
