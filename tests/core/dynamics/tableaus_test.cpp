// Every Butcher tableau of core/dynamics/tableaus.hpp against the theory it
// claims, with nothing taken from the tableau's source: the row sums c_i = Σ_j a_ij,
// the rooted-tree order conditions Φ(t) = 1/γ(t) (Hairer–Nørsett–Wanner I §II.2,
// Theorem 2.13) for b through the pair's order and for bhat through the embedded
// order, a failed condition one order up (the order is exact, so the error
// estimate has the power of h the step control assumes), FSAL where claimed, and
// the interpolants' own conditions Σ b_i(θ) Φ_i(t) = θ^ρ(t)/γ(t) (HNW I §II.6),
// over their extra stages where they have them (Verner's pairs).
#include "core/dynamics/tableaus.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace gacompare::core {
namespace {

constexpr SolverMethod kPairs[] = {SolverMethod::bs3,   SolverMethod::dopri5, SolverMethod::tsit5, SolverMethod::vern6,
                                   SolverMethod::vern7, SolverMethod::vern8,  SolverMethod::vern9};

// The rooted trees through order `max` (1, 1, 2, 4, 9, 20, 48, 115, 286 of them),
// each a multiset of earlier trees as its children, with its stage vector
// g(t)_i = Π_children (A g(child))_i, the same with |A| (the size of what
// rounding acts on), ρ(t) and the density γ(t) = ρ Π γ(child).
struct Tree {
  int order;
  double gamma;
  std::vector<double> g, g_abs;
};

// Over the first `stages` stages: the step's, or with the interpolant's extra ones.
std::vector<Tree> trees(const ButcherTableau& T, int max, int stages) {
  const auto s = static_cast<std::size_t>(stages);
  std::vector<Tree> all;
  const auto Ag = [&](const std::vector<double>& g, bool abs) {
    std::vector<double> out(s, 0.0);
    for (int i = 1; i < stages; ++i)
      for (int j = 0; j < i; ++j) out[static_cast<std::size_t>(i)] += (abs ? std::abs(T.at(i, j)) : T.at(i, j)) * g[static_cast<std::size_t>(j)];
    return out;
  };
  // Children as non-decreasing indices into `all` whose orders sum to n − 1.
  std::vector<std::size_t> children;
  const auto extend = [&](auto&& self, int n, int left, std::size_t from, std::size_t known) -> void {
    if (left == 0) {
      Tree t{n, static_cast<double>(n), std::vector<double>(s, 1.0), std::vector<double>(s, 1.0)};
      for (std::size_t k : children) {
        const auto a = Ag(all[k].g, false), b = Ag(all[k].g_abs, true);
        for (std::size_t i = 0; i < s; ++i) t.g[i] *= a[i], t.g_abs[i] *= b[i];
        t.gamma *= all[k].gamma;
      }
      all.push_back(std::move(t));
      return;
    }
    for (std::size_t k = from; k < known; ++k)
      if (all[k].order <= left) {
        children.push_back(k);
        self(self, n, left - all[k].order, k, known);
        children.pop_back();
      }
  };
  for (int n = 1; n <= max; ++n) extend(extend, n, n - 1, 0, all.size());
  return all;
}

// The worst |Φ(t) − 1/γ(t)| / (rounding scale) over trees of order ≤ p, where
// the rounding scale is Σ|w_i| g_abs_i: the coefficients are doubles, each half
// an ulp off its exact value, so Φ can be off by ~ε of that sum and no less.
double worst_condition(const std::vector<Tree>& all, const double* w, int s, int p) {
  double worst = 0;
  for (const Tree& t : all) {
    if (t.order > p) continue;
    double phi = 0, scale = 0;
    for (int i = 0; i < s; ++i) {
      phi += w[i] * t.g[static_cast<std::size_t>(i)];
      scale += std::abs(w[i]) * t.g_abs[static_cast<std::size_t>(i)];
    }
    worst = std::max(worst, std::abs(phi - 1.0 / t.gamma) / std::max(scale, 1.0 / t.gamma));
  }
  return worst;
}

// Trees of order p + 1 only: the largest |Φ − 1/γ|.
double largest_defect(const std::vector<Tree>& all, const double* w, int s, int p) {
  double most = 0;
  for (const Tree& t : all) {
    if (t.order != p + 1) continue;
    double phi = 0;
    for (int i = 0; i < s; ++i) phi += w[i] * t.g[static_cast<std::size_t>(i)];
    most = std::max(most, std::abs(phi - 1.0 / t.gamma));
  }
  return most;
}

constexpr double eps = std::numeric_limits<double>::epsilon();

TEST(Tableaus, RowSumsAreTheNodes) {
  for (SolverMethod m : kPairs) {
    const ButcherTableau& T = *butcher_tableau(m);
    EXPECT_EQ(T.c[0], 0.0) << to_string(m);
    // The interpolant's extra stages too (dense_stages ≥ stages).
    EXPECT_GE(T.dense_stages, T.stages) << to_string(m);
    for (int i = 1; i < T.dense_stages; ++i) {
      double sum = 0, size = 0;
      for (int j = 0; j < i; ++j) sum += T.at(i, j), size += std::abs(T.at(i, j));
      // 1e-15 of the row's size: Verner's rows reach |a_ij| ~ 200 summing to c ~ 1,
      // and each entry is rounded to half an ulp, so a flat 1e-15 is below what
      // the exact values rounded to double can give (the worst here is 8e-17 of it).
      EXPECT_LE(std::abs(sum - T.c[i]), 1e-15 * std::max(1.0, size)) << to_string(m) << " row " << i;
    }
  }
}

TEST(Tableaus, OrderConditionsHoldThroughTheStatedOrders) {
  for (SolverMethod m : kPairs) {
    const ButcherTableau& T = *butcher_tableau(m);
    const auto all = trees(T, T.order + 1, T.stages);
    // 64 ε of the rounding scale: the exact coefficients satisfy the conditions
    // exactly, their doubles up to a few ε of Σ|b_i| g_abs_i; a wrong digit in any
    // coefficient is off by ≥ 1e-10 of it.
    EXPECT_LE(worst_condition(all, T.b, T.stages, T.order), 64 * eps) << to_string(m) << " b";
    EXPECT_LE(worst_condition(all, T.bhat, T.stages, T.embedded_order), 64 * eps) << to_string(m) << " bhat";
    // …and not one order further: some condition is off by far more than rounding
    // (the smallest such defect among these pairs is 4e-7, vern8's b).
    EXPECT_GT(largest_defect(all, T.b, T.stages, T.order), 1e-8) << to_string(m) << " b";
    EXPECT_GT(largest_defect(all, T.bhat, T.stages, T.embedded_order), 1e-8) << to_string(m) << " bhat";
  }
}

TEST(Tableaus, TheTreesAreCountedRight) {
  // A check on the generator itself: 1, 1, 2, 4, 9, 20, 48, 115, 286 trees of
  // orders 1..9 (OEIS A000081), 486 in all.
  const auto all = trees(*butcher_tableau(SolverMethod::vern9), 9, 16);
  std::vector<int> per(10, 0);
  for (const Tree& t : all) ++per[static_cast<std::size_t>(t.order)];
  EXPECT_EQ(per, (std::vector<int>{0, 1, 1, 2, 4, 9, 20, 48, 115, 286}));
}

TEST(Tableaus, FirstSameAsLastWhereClaimed) {
  for (SolverMethod m : {SolverMethod::bs3, SolverMethod::dopri5, SolverMethod::tsit5, SolverMethod::vern6})
    EXPECT_TRUE(butcher_tableau(m)->fsal()) << to_string(m);
  for (SolverMethod m : {SolverMethod::vern7, SolverMethod::vern8, SolverMethod::vern9})
    EXPECT_FALSE(butcher_tableau(m)->fsal()) << to_string(m);
  for (SolverMethod m : {SolverMethod::euler, SolverMethod::rk4, SolverMethod::cash_karp45, SolverMethod::velocity_verlet})
    EXPECT_EQ(butcher_tableau(m), nullptr) << to_string(m);
}

TEST(Tableaus, InterpolantsMeetTheirConditionsAndTheStepsEnds) {
  for (SolverMethod m : kPairs) {
    const ButcherTableau& T = *butcher_tableau(m);
    if (T.dense_degree == 0) continue;
    // Over every stage the interpolant uses (Verner's extra ones too).
    const auto all = trees(T, T.dense_order + 1, T.dense_stages);
    const auto s = static_cast<std::size_t>(T.dense_stages), deg = static_cast<std::size_t>(T.dense_degree);
    for (double theta : {0.0, 0.3, 0.7, 1.0}) {
      // b_i(θ), and the size of what rounding acts on in it, Σ_p |r_ip| θ^p: the
      // polynomials cancel (Verner's coefficients reach 1e5 for weights of order
      // 1), so their own rounding, not |b_i(θ)|, sets the scale.
      std::vector<double> w(s, 0.0), w_abs(s, 0.0);
      for (std::size_t i = 0; i < s; ++i)
        for (std::size_t p = 0; p < deg; ++p) {
          const double term = T.dense[i * deg + p] * std::pow(theta, static_cast<double>(p + 1));
          w[i] += term, w_abs[i] += std::abs(term);
        }
      for (const Tree& t : all) {
        if (t.order > T.dense_order) continue;
        double phi = 0, scale = 1.0 / t.gamma;
        for (std::size_t i = 0; i < s; ++i) phi += w[i] * t.g[i], scale += w_abs[i] * t.g_abs[i];
        // The same rounding scale as above, times 8 for the powers of θ.
        EXPECT_LE(std::abs(phi - std::pow(theta, t.order) / t.gamma), 512 * eps * scale)
            << to_string(m) << " θ " << theta << " tree of order " << t.order;
      }
      // θ = 1 is the step's end: b_i(1) = b_i (the interpolant is continuous).
      // An extra stage has no weight there.
      if (theta == 1.0) {
        for (std::size_t i = 0; i < s; ++i) {
          const double b = i < static_cast<std::size_t>(T.stages) ? T.b[i] : 0.0;
          EXPECT_NEAR(w[i], b, 64 * eps * (1 + w_abs[i])) << to_string(m) << " stage " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace gacompare::core
