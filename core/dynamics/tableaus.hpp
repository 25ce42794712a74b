#pragma once
// Explicit embedded Runge–Kutta pairs as Butcher tableaus: data only, driven by
// one generic stepper (OdeSolver::pair_step, core/dynamics/ode.hpp). Each pair is
// cited above its numbers in tableaus.cpp; tests/core/dynamics/tableaus_test.cpp
// checks every one against the rooted-tree order conditions.
#include "core/model/scene.hpp"

#include <cstddef>

namespace gacompare::core {

struct ButcherTableau {
  int order = 0;           // of b: the solution kept (local extrapolation)
  int embedded_order = 0;  // of bhat: (b − bhat)·h·k estimates its error, O(h^(embedded_order+1))
  int stages = 0;
  const double* c = nullptr;     // [dense_stages]
  const double* a = nullptr;     // strict lower triangle by rows: a(i, j) = a[i(i−1)/2 + j], j < i < dense_stages
  const double* b = nullptr;     // [stages]
  const double* bhat = nullptr;  // [stages]
  // A continuous extension: y(t + θh) = y + h Σ_i b_i(θ) k_i over the first
  // dense_stages stages, with b_i(θ) = Σ_{p=1..dense_degree} dense[i·dense_degree
  // + p−1] θ^p, of order dense_order; dense_degree 0: none, the solver clips its
  // last step instead. dense_stages = stages: free (bs3, dopri5, tsit5); more:
  // the extra stages' nodes and rows follow the step's in c and a, and are
  // evaluated only in a step that is interpolated (Verner's pairs).
  int dense_degree = 0;
  int dense_order = 0;
  const double* dense = nullptr;
  int dense_stages = 0;

  double at(int i, int j) const { return a[static_cast<std::size_t>(i * (i - 1) / 2 + j)]; }
  // First same as last: the last stage is evaluated at the new solution (c = 1,
  // its row of a equals b), so it is the next step's first stage.
  bool fsal() const;
};

// The pair a method integrates with; nullptr for the methods that are not one
// (euler, rk4, rk4_doubling, cash_karp45 and the split methods keep their own steps).
const ButcherTableau* butcher_tableau(SolverMethod m);

}  // namespace gacompare::core
