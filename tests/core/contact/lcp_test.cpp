// core/contact/lcp.hpp: the bounded LCP against brute force (every split of
// the rows into free / lower / upper, each solved exactly), on seeded random
// problems of the contact kind (A = J M⁻¹ Jᵀ, singular when rows are
// redundant), and on a column of bodies whose answer is statics.
#include "core/contact/lcp.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <random>

namespace gacompare::core::contact {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::SparseMatrix<double> sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }

// A = J M⁻¹ Jᵀ for m rows over k bodies of 6 degrees of freedom each, every
// row touching one or two random bodies: positive semi-definite, singular
// when m > 6k or rows repeat.
Eigen::MatrixXd delassus(int rows, int bodies, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> pick(0, bodies - 1);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(rows, 6 * bodies);
  for (int r = 0; r < rows; ++r)
    for (int side = 0; side < 2; ++side) {
      const int b = pick(rng);
      for (int c = 0; c < 6; ++c) j(r, 6 * b + c) += g(rng);
    }
  Eigen::VectorXd inv_mass(6 * bodies);
  for (int c = 0; c < 6 * bodies; ++c) inv_mass[c] = std::exp(g(rng));  // mass ratios of e^±3
  return j * inv_mass.asDiagonal() * j.transpose();
}

// The exact answer by enumeration: for every assignment of rows to free /
// lower / upper, solve the free rows (least squares, SVD) and keep an
// assignment that meets every condition. Only for a handful of rows.
bool brute_force(const Blcp& p, Eigen::VectorXd& out, double tol) {
  const auto n = static_cast<int>(p.b.size());
  const Eigen::MatrixXd a(p.A);
  int total = 1;
  for (int i = 0; i < n; ++i) total *= 3;
  for (int code = 0; code < total; ++code) {
    std::vector<int> s(static_cast<std::size_t>(n));
    bool ok = true;
    for (int i = 0, c = code; i < n; ++i, c /= 3) {
      s[static_cast<std::size_t>(i)] = c % 3;
      if ((c % 3 == 1 && !std::isfinite(p.lo[i])) || (c % 3 == 2 && !std::isfinite(p.hi[i]))) ok = false;
    }
    if (!ok) continue;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<int> f;
    for (int i = 0; i < n; ++i) {
      if (s[static_cast<std::size_t>(i)] == 1) x[i] = p.lo[i];
      if (s[static_cast<std::size_t>(i)] == 2) x[i] = p.hi[i];
      if (s[static_cast<std::size_t>(i)] == 0) f.push_back(i);
    }
    if (!f.empty()) {
      Eigen::MatrixXd aff(f.size(), f.size());
      Eigen::VectorXd r(f.size());
      const Eigen::VectorXd known = a * x + p.b;
      for (std::size_t u = 0; u < f.size(); ++u) {
        r[static_cast<Eigen::Index>(u)] = -known[f[u]];
        for (std::size_t v = 0; v < f.size(); ++v) aff(static_cast<Eigen::Index>(u), static_cast<Eigen::Index>(v)) = a(f[u], f[v]);
      }
      const Eigen::VectorXd xf = aff.completeOrthogonalDecomposition().solve(r);
      for (std::size_t u = 0; u < f.size(); ++u) x[f[u]] = xf[static_cast<Eigen::Index>(u)];
    }
    if (blcp_residual(p, x) <= tol) {
      out = x;
      return true;
    }
  }
  return false;
}

// Seeded random problems of up to 7 rows (some redundant: 7 rows on one
// body's 6 freedoms), normal rows and friction-like boxes mixed: the solver's
// answer meets the conditions to 1e-9 of the problem's scale (rounding in a
// regularised, refined factorisation of a matrix with e^±6 in its entries),
// and gives every row the velocity the brute-force answer gives it (w is
// unique for a positive semi-definite problem even where λ is not).
TEST(Blcp, MatchesBruteForceOnRandomContactProblems) {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> u(-1, 1);
  int solved = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 6, bodies = 1 + trial % 3;
    Blcp p;
    const Eigen::MatrixXd a = delassus(n, bodies, rng);
    p.A = sparse(a);
    p.b.resize(n), p.lo.resize(n), p.hi.resize(n);
    for (int i = 0; i < n; ++i) {
      p.b[i] = u(rng);
      const int kind = (trial + i) % 3;  // normal, box, bilateral
      p.lo[i] = kind == 0 ? 0.0 : kind == 1 ? -0.3 : -kInf;
      p.hi[i] = kind == 0 ? kInf : kind == 1 ? 0.3 : kInf;
    }
    const double scale = 1 + a.cwiseAbs().maxCoeff();
    Eigen::VectorXd exact;
    if (!brute_force(p, exact, 1e-9 * scale)) continue;  // bilateral rows inconsistent: no solution exists
    ++solved;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(n);
    const BlcpResult r = solve_blcp(p, lambda, {});
    ASSERT_TRUE(r.solved) << "trial " << trial;
    EXPECT_LE(blcp_residual(p, lambda), 1e-9 * scale) << "trial " << trial;
    const Eigen::VectorXd w = a * lambda + p.b, w_exact = a * exact + p.b;
    EXPECT_LE((w - w_exact).cwiseAbs().maxCoeff(), 1e-8 * scale) << "trial " << trial;
  }
  EXPECT_GT(solved, 200);  // most random problems have a solution: the test ran on them
}

// A column of n unit masses on the ground, one row between neighbours (a
// chain: the problem on which Gauss–Seidel needs ~n² sweeps). Each body moves
// down at g h before the solve; the answer is statics: row k carries
// (n − k) g h, and every body stops.
TEST(Blcp, ColumnGetsItsStaticsInOneFactorisation) {
  for (const int n : {2, 10, 40}) {
    const double gh = 9.81e-3;
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n, n);  // row k between body k−1 (or the ground) and body k
    for (int k = 0; k < n; ++k) {
      j(k, k) = 1;
      if (k > 0) j(k, k - 1) = -1;
    }
    Blcp p;
    p.A = sparse(j * j.transpose());
    p.b = j * Eigen::VectorXd::Constant(n, -gh);
    p.lo = Eigen::VectorXd::Zero(n);
    p.hi = Eigen::VectorXd::Constant(n, kInf);
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(n);
    const BlcpResult r = solve_blcp(p, lambda, {});
    ASSERT_TRUE(r.solved);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(lambda[k], (n - k) * gh, 1e-14 * n) << "n " << n << " row " << k;
    // Warm started with its own answer it needs no pivot.
    const BlcpResult again = solve_blcp(p, lambda, {});
    EXPECT_EQ(again.pivots, 0);
    EXPECT_EQ(again.factorisations, 1);
  }
}

// A column whose bodies all part at once (each moving up at g h, warm
// started with its resting loads): every row leaves its load for its bound
// in one projected step, where a step to the first bound each time took one
// factorisation per row. The answer is no impulse anywhere, every row
// parting.
TEST(Blcp, RowsThatAllPartLeaveTogether) {
  const int n = 40;
  const double gh = 9.81e-3;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    j(k, k) = 1;
    if (k > 0) j(k, k - 1) = -1;
  }
  Blcp p;
  p.A = sparse(j * j.transpose());
  Eigen::VectorXd up(n);
  for (int k = 0; k < n; ++k) up[k] = (k + 1) * gh;  // faster the higher: every row opens
  p.b = j * up;
  p.lo = Eigen::VectorXd::Zero(n);
  p.hi = Eigen::VectorXd::Constant(n, kInf);
  Eigen::VectorXd lambda(n);
  for (int k = 0; k < n; ++k) lambda[k] = (n - k) * gh;
  const BlcpResult r = solve_blcp(p, lambda, {});
  ASSERT_TRUE(r.solved);
  EXPECT_LE(r.factorisations, 2);
  EXPECT_EQ(lambda.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(blcp_residual(p, lambda), 0.0);
}

// Four corners of a face on the ground: four rows, three freedoms (lift and
// two tilts). The load is shared (not uniquely), every corner stops, and the
// body neither turns nor tilts: w vanishes to rounding.
TEST(Blcp, RedundantFaceRowsStopEveryCorner) {
  const double half = 0.1, gh = 9.81e-3;
  const double inv_i = 1 / (2 * half * half / 3);  // unit cube of side 0.2 about a face axis
  Eigen::MatrixXd j(4, 3);  // (lift, tilt x, tilt y) per corner
  int k = 0;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) j.row(k++) << 1, sy * half, -sx * half;
  const Eigen::Vector3d m_inv(1, inv_i, inv_i);
  Blcp p;
  p.A = sparse(j * m_inv.asDiagonal() * j.transpose());
  p.b = j * Eigen::Vector3d(-gh, 0, 0);
  p.lo = Eigen::VectorXd::Zero(4);
  p.hi = Eigen::VectorXd::Constant(4, kInf);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
  ASSERT_TRUE(solve_blcp(p, lambda, {}).solved);
  EXPECT_NEAR(lambda.sum(), gh, 1e-16);
  const Eigen::VectorXd w = Eigen::MatrixXd(p.A) * lambda + p.b;
  EXPECT_LE(w.cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_GE(lambda.minCoeff(), 0.0);
}

// Two rows along the same line (a redundant pair, A = [1 1; 1 1]) must carry
// one unit of impulse between them: every split λ1 + λ2 = 1 is exact. With
// weights (1, w) the regularised problem picks the least Σ w_i λ_i², the split
// λ_i ∝ 1 / w_i (Lagrange), so the heavy row carries 1/(1 + w): how the
// contact solver keeps friction out of a stack's answer wherever the normal
// rows can carry it. The split is the regularisation's, kept exactly by the
// refinement (it lies in A's null space); the velocity is exact.
TEST(Blcp, WeightsChooseTheLeastWeightedAnswer) {
  Blcp p;
  p.A = sparse((Eigen::MatrixXd(2, 2) << 1, 1, 1, 1).finished());
  p.b = Eigen::Vector2d(-1, -1);
  p.lo = Eigen::VectorXd::Constant(2, -kInf);
  p.hi = Eigen::VectorXd::Constant(2, kInf);
  for (const double w : {1.0, 1e4}) {
    p.weight = Eigen::Vector2d(1, w);
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(2);
    ASSERT_TRUE(solve_blcp(p, lambda, {}).solved);
    EXPECT_NEAR(lambda.sum(), 1.0, 1e-12) << "w = " << w;
    // 1e-6 relative: the split comes from factorising A + δW, whose
    // condition number is about 2/δ = 2e10, so rounding (1e-16) can move it
    // by ~1e-6 of itself; measured 8e-8 at w = 1e4.
    EXPECT_NEAR(lambda[1], 1 / (1 + w), 1e-6 / (1 + w)) << "w = " << w;
  }
}

// A row whose warm start lies within rounding of its bound (what the last
// step's answer leaves at a redundant corner) starts on it: one
// factorisation, no pivot, and the exact answer. Started free, it would be
// driven negative by the first solve and blocked, at a second factorisation.
TEST(Blcp, AWarmStartWithinRoundingOfABoundStartsOnIt) {
  Blcp p;
  p.A = sparse(Eigen::MatrixXd::Identity(2, 2));
  p.b = Eigen::Vector2d(-1, 1);  // row 0 carries 1; row 1 parts (w = 1 at λ = 0)
  p.lo = Eigen::VectorXd::Zero(2);
  p.hi = Eigen::VectorXd::Constant(2, kInf);
  Eigen::VectorXd lambda = Eigen::Vector2d(1, 1e-18);
  const BlcpResult r = solve_blcp(p, lambda, {});
  ASSERT_TRUE(r.solved);
  EXPECT_EQ(r.factorisations, 1);
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(lambda[0], 1.0);
  EXPECT_EQ(lambda[1], 0.0);
  // A row well above its bound (1e-9 of the largest impulse) still starts free.
  lambda = Eigen::Vector2d(1, 1e-9);
  const BlcpResult free_start = solve_blcp(p, lambda, {});
  EXPECT_EQ(free_start.factorisations, 2);  // blocked at its bound
  EXPECT_EQ(lambda[1], 0.0);
}

// A row alone is solved in closed form (−b/a held within its bounds, lcp.cpp's
// one_row). Seeded random rows of every kind (normal, box, bilateral, fixed)
// from warm starts at zero, inside, on a bound and just off one: the answer
// meets the conditions to rounding (1e-13 of the scale, where the general
// method's refined answer is held to its tolerance), equals the brute-force
// answer where the start does not decide it, and agrees with the general
// method on the same row beside an uncoupled second one (A = diag(a, 1)),
// which the closed form does not take: the same λ to 1e-12 of its size.
// A row that starts on a bound stays there while w points away from it within
// the tolerance, as in the general method.
TEST(Blcp, OneRowInClosedFormMatchesTheGeneralMethod) {
  std::mt19937_64 rng(20261207);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 400; ++trial) {
    const double a = std::exp(2 * g(rng)), b = u(rng);
    const int kind = trial % 4;  // normal, box, bilateral, fixed
    Blcp one;
    one.A = sparse(Eigen::MatrixXd::Constant(1, 1, a));
    one.b = Eigen::VectorXd::Constant(1, b);
    one.lo = Eigen::VectorXd::Constant(1, kind == 0 ? 0.0 : kind == 1 ? -0.3 : kind == 2 ? -kInf : 0.2);
    one.hi = Eigen::VectorXd::Constant(1, kind == 0 ? kInf : kind == 1 ? 0.3 : kind == 2 ? kInf : 0.2);
    const int start = (trial / 4) % 4;  // zero, inside, on the lower bound, just above it
    const double lo = one.lo[0];
    const double warm = start == 0 ? 0.0 : start == 1 ? 0.1 : start == 2 ? (std::isfinite(lo) ? lo : 0.0)
                                                                           : (std::isfinite(lo) ? lo + 1e-6 : 0.0);
    Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, warm);
    const BlcpResult r = solve_blcp(one, lambda, {});
    ASSERT_TRUE(r.solved) << "trial " << trial;
    const double scale = 1 + a;
    EXPECT_LE(blcp_residual(one, lambda), 1e-13 * scale) << "trial " << trial;
    Eigen::VectorXd exact;
    ASSERT_TRUE(brute_force(one, exact, 1e-13 * scale)) << "trial " << trial;
    EXPECT_NEAR(lambda[0], exact[0], 1e-12 * (1 + std::abs(exact[0]))) << "trial " << trial;

    Blcp two;
    Eigen::MatrixXd a2 = Eigen::MatrixXd::Identity(2, 2);
    a2(0, 0) = a;
    two.A = sparse(a2);
    two.b = Eigen::Vector2d(b, -1);
    two.lo = Eigen::Vector2d(one.lo[0], 0);
    two.hi = Eigen::Vector2d(one.hi[0], kInf);
    Eigen::VectorXd both = Eigen::Vector2d(warm, 0);
    ASSERT_TRUE(solve_blcp(two, both, {}).solved) << "trial " << trial;
    EXPECT_NEAR(lambda[0], both[0], 1e-12 * (1 + std::abs(both[0]))) << "trial " << trial;
  }
  // On its bound, w pointing inwards by less than the tolerance: it stays,
  // with no factorisation; by more, it is released and solved.
  Blcp p;
  p.A = sparse(Eigen::MatrixXd::Constant(1, 1, 2.0));
  p.lo = Eigen::VectorXd::Zero(1);
  p.hi = Eigen::VectorXd::Constant(1, kInf);
  BlcpSettings how;
  how.velocity_tolerance = 1e-6;
  p.b = Eigen::VectorXd::Constant(1, -0.5e-6);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(1);
  BlcpResult r = solve_blcp(p, lambda, how);
  EXPECT_EQ(lambda[0], 0.0);
  EXPECT_EQ(r.factorisations, 0);
  EXPECT_EQ(r.pivots, 0);
  p.b[0] = -4.0;
  lambda[0] = 0;
  r = solve_blcp(p, lambda, how);
  EXPECT_EQ(lambda[0], 2.0);
  EXPECT_EQ(r.factorisations, 1);
  EXPECT_EQ(r.pivots, 1);  // the release
  // Started free, its answer past the upper bound: blocked there.
  p.hi[0] = 1.0;
  lambda[0] = 0.5;
  r = solve_blcp(p, lambda, how);
  EXPECT_EQ(lambda[0], 1.0);
  EXPECT_EQ(r.factorisations, 1);
  EXPECT_EQ(r.pivots, 1);  // the block
}

// The contact solver weights its friction rows 1e4 (contact_solver.hpp), so
// their regularisation δ_i is 1e-6 of the largest diagonal, and an answer of
// the regularised problem is off by about δ_i λ_i in their velocities. Where
// a weighted row's exact answer lies just past its bound, the regularised
// one stops just short of it, free; the refinement then leaves the bound and
// is dropped, and only the proximal steps take the bias out. Seeded random
// problems built so (the rows' unconstrained answer has one weighted box row
// 1e-9 past its bound), solved to the contact solver's tolerance (1e-11 of
// the scale): every answer meets it with the steps (the slowest, on a matrix
// of condition 5e6, takes ~26), and most miss it without (max_proximal = 0:
// 194 of 200 measured), so the test checks what the steps add.
TEST(Blcp, ProximalStepsRemoveTheWeightsBias) {
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> u(0, 1);
  int met = 0, met_without = 0, problems = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 4, bodies = 1;  // at most 6 rows on 6 freedoms: A is regular
    Blcp p;
    const Eigen::MatrixXd a = delassus(n, bodies, rng);
    p.A = sparse(a);
    p.lo.resize(n), p.hi.resize(n), p.weight.resize(n);
    Eigen::VectorXd target(n);
    for (int i = 0; i < n; ++i) {
      const bool box = i % 2 == 1;  // normal rows and friction-like boxes, the boxes weighted
      p.lo[i] = box ? -0.2 : 0.0;
      p.hi[i] = box ? 0.2 : kInf;
      p.weight[i] = box ? 1e4 : 1.0;
      target[i] = box ? 0.1 * (2 * u(rng) - 1) : 0.5 + u(rng);
    }
    target[1] = 0.2 * (1 + 1e-9);
    p.b = -a * target;
    const double scale = 1 + a.cwiseAbs().maxCoeff();
    Eigen::VectorXd exact;
    if (!brute_force(p, exact, 1e-9 * scale)) continue;
    ++problems;
    BlcpSettings how, without;
    how.velocity_tolerance = without.velocity_tolerance = 1e-11 * scale;
    without.max_proximal = 0;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(n), plain = Eigen::VectorXd::Zero(n);
    ASSERT_TRUE(solve_blcp(p, lambda, how).solved) << "trial " << trial;
    solve_blcp(p, plain, without);
    met += blcp_residual(p, lambda) <= how.velocity_tolerance;
    met_without += blcp_residual(p, plain) <= how.velocity_tolerance;
  }
  EXPECT_GT(problems, 150);
  EXPECT_EQ(met, problems);
  EXPECT_LT(met_without, problems / 2);
}

// A problem larger than the dense limit goes through the sparse factorisation
// and gives the same answer as the dense one.
TEST(Blcp, SparseAndDenseAgree) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 120;
  Blcp p;
  const Eigen::MatrixXd a = delassus(n, 40, rng);
  p.A = sparse(a);
  p.b.resize(n);
  for (int i = 0; i < n; ++i) p.b[i] = u(rng);
  p.lo = Eigen::VectorXd::Zero(n);
  p.hi = Eigen::VectorXd::Constant(n, kInf);
  Eigen::VectorXd dense = Eigen::VectorXd::Zero(n), sparse_answer = Eigen::VectorXd::Zero(n);
  BlcpSettings all_dense, all_sparse;
  all_dense.dense_up_to = n, all_sparse.dense_up_to = 0;
  const BlcpResult rd = solve_blcp(p, dense, all_dense), rs = solve_blcp(p, sparse_answer, all_sparse);
  ASSERT_TRUE(rd.solved);
  ASSERT_TRUE(rs.solved);
  const double scale = 1 + a.cwiseAbs().maxCoeff();
  EXPECT_LE(blcp_residual(p, sparse_answer), 1e-9 * scale);
  EXPECT_LE(((a * dense) - (a * sparse_answer)).cwiseAbs().maxCoeff(), 1e-8 * scale);
}

// The active-set changes solved through a Schur complement (lcp.cpp's
// UpdatedSystem) against a fresh factorisation at every change: on seeded
// random sparse problems of 200 rows (over 60 bodies, and over 30, where A is
// singular: more rows than freedoms), normal and box rows mixed, started cold
// so that many rows change, both answers meet the conditions and give every
// row the same velocity to 1e-8 of the problem's scale (the tolerance of
// MatchesBruteForceOnRandomContactProblems: w is unique even where λ is not),
// the updates are taken, and they save factorisations. With a budget of 3
// changes the updated system is factorised again when it is spent, and the
// answer is the same too.
TEST(Blcp, UpdatesAgreeWithFreshFactorisations) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 200;
  int updates = 0, fresh_factorisations = 0, updated_factorisations = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Blcp p;
    const Eigen::MatrixXd a = delassus(n, trial % 2 ? 30 : 60, rng);
    p.A = sparse(a);
    p.b.resize(n), p.lo.resize(n), p.hi.resize(n);
    for (int i = 0; i < n; ++i) {
      p.b[i] = u(rng);
      const bool box = (trial + i) % 3 == 1;
      p.lo[i] = box ? -0.3 : 0.0;
      p.hi[i] = box ? 0.3 : kInf;
    }
    const double scale = 1 + a.cwiseAbs().maxCoeff();
    BlcpSettings fresh, updated, small_budget;
    fresh.dense_up_to = updated.dense_up_to = small_budget.dense_up_to = 0;
    fresh.most_updates = 0, small_budget.most_updates = 3;
    Eigen::VectorXd x_fresh = Eigen::VectorXd::Zero(n), x_updated = x_fresh, x_small = x_fresh;
    const BlcpResult rf = solve_blcp(p, x_fresh, fresh), ru = solve_blcp(p, x_updated, updated),
                     rs = solve_blcp(p, x_small, small_budget);
    ASSERT_TRUE(rf.solved) << "trial " << trial;
    ASSERT_TRUE(ru.solved) << "trial " << trial;
    ASSERT_TRUE(rs.solved) << "trial " << trial;
    EXPECT_EQ(rf.updates, 0);
    for (const Eigen::VectorXd* x : {&x_updated, &x_small}) {
      EXPECT_LE(blcp_residual(p, *x), 1e-9 * scale) << "trial " << trial;
      EXPECT_LE(((a * *x) - (a * x_fresh)).cwiseAbs().maxCoeff(), 1e-8 * scale) << "trial " << trial;
    }
    EXPECT_GT(rs.factorisations, 1) << "trial " << trial;  // the budget ran out and it factorised again
    updates += ru.updates, fresh_factorisations += rf.factorisations, updated_factorisations += ru.factorisations;
  }
  EXPECT_GT(updates, 12 * 5);  // the problems changed their active sets: the updates ran
  EXPECT_LT(updated_factorisations, fresh_factorisations / 4);
}

// psd_factor against the matrices it factorises: seeded random G0 G0ᵀ of
// rank 1 to 6 on up to 30 rows (the rows at one body), and a face's four
// coplanar corners on one cube (rank 3: lift and two tilts). It finds the
// rank and G Gᵀ matches to 1e-13 of the largest entry (pivoted Cholesky's
// rounding on a semi-definite matrix, Higham 1990: a few ulps times the
// rows).
TEST(PsdFactor, RecoversLowRankMatrices) {
  std::mt19937_64 rng(6);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 60; ++trial) {
    const int k = 1 + trial % 30, rank = std::min(k, 1 + trial % 6);
    Eigen::MatrixXd g0(k, rank);
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < rank; ++j) g0(i, j) = g(rng);
    const Eigen::MatrixXd a = g0 * g0.transpose();
    const Eigen::MatrixXd f = psd_factor(a, 6);
    EXPECT_EQ(f.cols(), rank) << "trial " << trial;
    EXPECT_LE((f * f.transpose() - a).cwiseAbs().maxCoeff(), 1e-13 * a.cwiseAbs().maxCoeff()) << "trial " << trial;
  }
  const double half = 0.1, inv_i = 1 / (2 * half * half / 3);
  Eigen::MatrixXd j(4, 3);
  int k = 0;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) j.row(k++) << 1, sy * half, -sx * half;
  const Eigen::MatrixXd face = j * Eigen::Vector3d(1, inv_i, inv_i).asDiagonal() * j.transpose();
  const Eigen::MatrixXd f = psd_factor(face, 6);
  EXPECT_EQ(f.cols(), 3);
  EXPECT_LE((f * f.transpose() - face).cwiseAbs().maxCoeff(), 1e-13 * face.cwiseAbs().maxCoeff());
}

// A square pyramid of L layers of unit cubes of side 0.2 (each on four
// below, four coplanar corner rows per face contact: redundant rows), as G =
// J M^-½ with A = G Gᵀ: the contact solver's factor by body.
Eigen::SparseMatrix<double, Eigen::RowMajor> pyramid_factor(int layers) {
  const double side = 0.2, pitch = 0.22, inv_i = 1 / (side * side / 6);
  std::vector<Eigen::Vector3d> centre;
  std::vector<std::vector<int>> at(static_cast<std::size_t>(layers));
  for (int l = 0; l < layers; ++l) {
    const int r = layers - l;
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < r; ++j) {
        at[static_cast<std::size_t>(l)].push_back(static_cast<int>(centre.size()));
        centre.emplace_back((i - (r - 1) / 2.0) * pitch, (j - (r - 1) / 2.0) * pitch, side / 2 + l * side);
      }
  }
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  const auto add_row = [&](int below, int above, const Eigen::Vector3d& p) {
    const Eigen::Vector3d n(0, 0, 1);
    for (const int b : {below, above}) {
      if (b < 0) continue;
      const double sign = b == above ? 1 : -1;
      const Eigen::Vector3d turn = (p - centre[static_cast<std::size_t>(b)]).cross(n) * std::sqrt(inv_i);
      for (int c = 0; c < 3; ++c) t.emplace_back(row, 6 * b + c, sign * n[c]), t.emplace_back(row, 6 * b + 3 + c, sign * turn[c]);
    }
    ++row;
  };
  for (int l = 0; l < layers; ++l) {
    const int r = layers - l;
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < r; ++j) {
        const int a = at[static_cast<std::size_t>(l)][static_cast<std::size_t>(i * r + j)];
        const Eigen::Vector3d& c = centre[static_cast<std::size_t>(a)];
        const double z = c.z() - side / 2;
        std::vector<int> below{-1};
        if (l > 0) below = {};
        for (int di = 0; l > 0 && di < 2; ++di)
          for (int dj = 0; dj < 2; ++dj) below.push_back(at[static_cast<std::size_t>(l - 1)][static_cast<std::size_t>((i + di) * (r + 1) + j + dj)]);
        for (const int b : below) {
          const Eigen::Vector3d cb = b < 0 ? c : centre[static_cast<std::size_t>(b)];
          const double x0 = std::max(c.x(), cb.x()) - side / 2, x1 = std::min(c.x(), cb.x()) + side / 2;
          const double y0 = std::max(c.y(), cb.y()) - side / 2, y1 = std::min(c.y(), cb.y()) + side / 2;
          for (const double x : {x0, x1})
            for (const double y : {y0, y1}) add_row(b, a, Eigen::Vector3d(x, y, z));
        }
      }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> g(row, 6 * static_cast<int>(centre.size()));
  g.setFromTriplets(t.begin(), t.end());
  return g;
}

// The augmented factorisation [I Gᵀ; G −δ] (lcp.cpp's FreeSystem, given G)
// against A's own, on a 6-layer square pyramid (91 cubes, 1,024 rows, a
// quarter of each face's corners redundant) with seeded random velocities:
// every cube pressed down or lifted, so rows part and close and the active
// set changes. Both answers meet the conditions to 1e-9 of the problem's
// scale and give every row the same velocity to 1e-8 of it (the tolerances
// of MatchesBruteForceOnRandomContactProblems), and the augmented
// factorisations are the ones taken.
// Both factorisations on a 6-layer pyramid's redundant rows (1,024 rows):
// random body velocities, mostly down, so rows part and close; b's entries
// multiplied by 1 + 1e-15 g (g standard normal, seeded) where `perturb` is
// not 0. Returns the held rows, summed over the trials.
int agree_on_pyramid(std::uint64_t perturb) {
  std::mt19937_64 rng(20261205), noise(perturb);
  std::normal_distribution<double> g;
  Blcp p;
  p.G = pyramid_factor(6);
  p.A = Eigen::SparseMatrix<double>(p.G) * Eigen::SparseMatrix<double>(p.G).transpose();
  const auto n = p.A.rows();
  EXPECT_EQ(n, 1024);
  int held = 0;
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::VectorXd v(p.G.cols());  // each body's velocity (scaled by M^½), mostly down
    for (Eigen::Index c = 0; c < v.size(); ++c) v[c] = g(rng) * (c % 6 == 2 ? 1.0 : 0.1) - (c % 6 == 2 ? 0.5 : 0.0);
    p.b = Eigen::SparseMatrix<double>(p.G) * v;
    if (perturb != 0)
      for (Eigen::Index i = 0; i < n; ++i) p.b[i] *= 1 + 1e-15 * g(noise);
    p.lo = Eigen::VectorXd::Zero(n);
    p.hi = Eigen::VectorXd::Constant(n, kInf);
    const double scale = 1 + p.A.coeffs().cwiseAbs().maxCoeff();
    BlcpSettings augmented, row_space;
    augmented.augmented_from = 0;
    augmented.augment_by_entries = false;
    row_space.augmented_from = static_cast<int>(n) + 1;
    Eigen::VectorXd x_aug = Eigen::VectorXd::Zero(n), x_row = x_aug;
    const BlcpResult ra = solve_blcp(p, x_aug, augmented), rr = solve_blcp(p, x_row, row_space);
    const std::string at = "perturbation " + std::to_string(perturb) + ", trial " + std::to_string(trial);
    EXPECT_TRUE(ra.solved) << at << ": " << ra.pivots << " pivots";
    EXPECT_TRUE(rr.solved) << at << ": " << rr.pivots << " pivots";
    EXPECT_EQ(ra.augmented, ra.factorisations) << at;
    EXPECT_EQ(rr.augmented, 0) << at;
    EXPECT_GT(ra.pivots, 0) << at;
    EXPECT_LE(blcp_residual(p, x_aug), 1e-9 * scale) << at;
    EXPECT_LE(blcp_residual(p, x_row), 1e-9 * scale) << at;
    EXPECT_LE((p.A * x_aug - p.A * x_row).cwiseAbs().maxCoeff(), 1e-8 * scale) << at;
    held += ra.held + rr.held;
  }
  return held;
}

TEST(Blcp, AugmentedAndRowSpaceFactorisationsAgree) { agree_on_pyramid(0); }

// The active set's path is sensitive to the last digits of each solve: the
// free systems are singular to δ (a face's four corners), so b perturbed by
// 1e-15 of itself gives other pivots. Without the guard against cycling,
// 7 of these 24 solves (6 augmented, 1 row-space) ran to the 256-pivot
// limit, repeating a few active sets at one objective value (rows released
// at w ≈ −4e-11, driven below their bounds by the next solve, blocked at a
// step of 0); with it every solve ends, and the two forms agree.
TEST(Blcp, DegenerateCyclesEnd) {
  int held = 0;
  for (const std::uint64_t perturb : {1, 2, 3}) held += agree_on_pyramid(perturb);
  EXPECT_GT(held, 0);  // the family does cycle: the guard was needed
}

// A pile's factor by body: each of `bodies` bodies touches the next at two
// points (a chain, about four rows a body), seeded random G entries, six
// columns a body.
Eigen::SparseMatrix<double, Eigen::RowMajor> chain_factor(int bodies, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  for (int b = 0; b + 1 < bodies; ++b)
    for (int point = 0; point < 2; ++point, ++row)
      for (const int body : {b, b + 1})
        for (int c = 0; c < 6; ++c) t.emplace_back(row, 6 * body + c, g(rng));
  Eigen::SparseMatrix<double, Eigen::RowMajor> f(row, 6 * bodies);
  f.setFromTriplets(t.begin(), t.end());
  return f;
}

// Which free systems are augmented (lcp.cpp, FreeSystem): only those whose
// augmented matrix holds fewer entries than A_FF. Every row starts free, so
// the first factorisation is of all of them. The pyramid's cubes carry some
// twenty rows each (A_FF ~ 20² entries a cube, the augmented ~ 6 · 20): its
// system is augmented. The chain's bodies carry four (A_FF ~ 16 a body, the
// augmented ~ 6 · 4 + 6): A's own factor. (Once the pyramid's rows part, a
// free system of half of them has half the rows a cube, and A_FF the fewer
// entries.) Forced either way, the chain's answers agree to the tolerances
// of AugmentedAndRowSpaceFactorisationsAgree.
TEST(Blcp, TheAugmentedFormIsTakenWhereItHoldsFewerEntries) {
  std::mt19937_64 rng(20261208);
  std::normal_distribution<double> g;
  // Each body's velocity (scaled by M^½): the stack's pressed down, as in
  // agree_on_pyramid, so that its rows stay free.
  const auto problem = [&](Eigen::SparseMatrix<double, Eigen::RowMajor> factor, double down) {
    Blcp p;
    p.G = std::move(factor);
    p.A = Eigen::SparseMatrix<double>(p.G) * Eigen::SparseMatrix<double>(p.G).transpose();
    const auto n = p.A.rows();
    Eigen::VectorXd v(p.G.cols());
    for (Eigen::Index c = 0; c < v.size(); ++c) v[c] = c % 6 == 2 ? g(rng) - down : 0.1 * g(rng);
    p.b = Eigen::SparseMatrix<double>(p.G) * v;
    p.lo = Eigen::VectorXd::Zero(n);
    p.hi = Eigen::VectorXd::Constant(n, kInf);
    return p;
  };
  BlcpSettings chosen;
  chosen.augmented_from = 0;
  {
    const Blcp p = problem(pyramid_factor(6), 0.5);
    Eigen::VectorXd x = Eigen::VectorXd::Ones(p.A.rows());
    const BlcpResult r = solve_blcp(p, x, chosen);
    EXPECT_TRUE(r.solved);
    EXPECT_GT(r.augmented, 0) << r.factorisations << " factorisations, " << r.pivots << " pivots, " << r.updates << " updates";
  }
  const Blcp p = problem(chain_factor(400, rng), 0.0);
  ASSERT_EQ(p.A.rows(), 798);
  BlcpSettings forced = chosen;
  forced.augment_by_entries = false;
  Eigen::VectorXd x_own = Eigen::VectorXd::Ones(p.A.rows()), x_aug = x_own;
  const BlcpResult own = solve_blcp(p, x_own, chosen), aug = solve_blcp(p, x_aug, forced);
  EXPECT_TRUE(own.solved);
  EXPECT_TRUE(aug.solved);
  EXPECT_GT(own.factorisations, 0);
  EXPECT_EQ(own.augmented, 0);
  EXPECT_GT(aug.augmented, 0);
  const double scale = 1 + p.A.coeffs().cwiseAbs().maxCoeff();
  EXPECT_LE(blcp_residual(p, x_own), 1e-9 * scale);
  EXPECT_LE(blcp_residual(p, x_aug), 1e-9 * scale);
  EXPECT_LE((p.A * x_own - p.A * x_aug).cwiseAbs().maxCoeff(), 1e-8 * scale);
}

}  // namespace
}  // namespace gacompare::core::contact
