// core/contact/coulomb.hpp: the Jacobian against central differences, one
// contact against its analytic answer (sticking and sliding), and seeded
// random problems of the contact kind (A = J M⁻¹ Jᵀ, corners sharing a pair's
// disc) whose answers are checked against Coulomb's conditions written out
// independently of the solver's Φ.
#include "core/contact/coulomb.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace gacompare::core::contact {
namespace {

// A problem of `pairs` pairs of `corners` contacts each (normal rows first,
// then two tangent rows per contact), over `bodies` bodies of 6 degrees of
// freedom: each contact's three rows act at one point between two random
// bodies (so a pair's rows are redundant when corners > 2), friction μ on
// the pair's mean load.
CoulombProblem random_problem(int pairs, int corners, int bodies, double mu, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> pick(0, bodies - 1);
  const int contacts = pairs * corners, n = 3 * contacts;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n, 6 * bodies);
  for (int p = 0; p < pairs; ++p) {
    const int a = pick(rng), b = (a + 1 + pick(rng) % (bodies - 1)) % bodies;
    const Eigen::Vector3d normal = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const Eigen::Vector3d t0 = normal.unitOrthogonal(), t1 = normal.cross(t0);
    for (int c = 0; c < corners; ++c) {
      const int k = p * corners + c;
      const Eigen::Vector3d arm_a(g(rng), g(rng), g(rng)), arm_b(g(rng), g(rng), g(rng));
      const Eigen::Vector3d dirs[3] = {normal, t0, t1};
      const int rows[3] = {k, contacts + 2 * k, contacts + 2 * k + 1};
      for (int d = 0; d < 3; ++d) {
        j.block<1, 3>(rows[d], 6 * b) += dirs[d].transpose();
        j.block<1, 3>(rows[d], 6 * b + 3) += arm_b.cross(dirs[d]).transpose();
        j.block<1, 3>(rows[d], 6 * a) -= dirs[d].transpose();
        j.block<1, 3>(rows[d], 6 * a + 3) -= arm_a.cross(dirs[d]).transpose();
      }
    }
  }
  Eigen::VectorXd inv_mass(6 * bodies);
  for (int c = 0; c < 6 * bodies; ++c) inv_mass[c] = std::exp(g(rng));
  CoulombProblem p;
  p.A = (j * inv_mass.asDiagonal() * j.transpose()).sparseView();
  p.b = Eigen::VectorXd::NullaryExpr(n, [&] { return g(rng); });
  p.normals = contacts;
  for (int k = 0; k < contacts; ++k) {
    const int pair = k / corners;
    p.discs.push_back({contacts + 2 * k, mu, pair * corners, (pair + 1) * corners});
  }
  return p;
}

// Coulomb's conditions at λ, each as a velocity (m/s): the worst of
//   normal rows: λ ≥ 0, u ≥ 0, and λ u = 0 (as min(λ A_ii, u));
//   friction: |λ_t| ≤ μ λ̄_n; sticking inside the disc (u_t = 0); sliding on
//   the rim, against the slip w = (u_t0 / A_t0t0, u_t1 / A_t1t1) that each
//   row's own update sees (λ_t = −r w / |w|). That is the sweeps' law
//   (coulomb.hpp): Coulomb's, against u_t itself, where the two tangents'
//   effective masses are equal.
double coulomb_violation(const CoulombProblem& p, const Eigen::VectorXd& x) {
  const Eigen::VectorXd u = p.A * x + p.b;
  double worst = 0;
  for (Eigen::Index i = 0; i < p.normals; ++i) {
    const double a = p.A.coeff(i, i);
    worst = std::max({worst, -x[i] * a, -u[i], std::min(std::abs(x[i]) * a, std::abs(u[i]))});
  }
  for (const CoulombDisc& d : p.discs) {
    double sum = 0;
    for (Eigen::Index k = d.pair_begin; k < d.pair_end; ++k) sum += x[k];
    const double r = d.mu * std::max(0.0, sum) / static_cast<double>(d.pair_end - d.pair_begin);
    const double a0 = p.A.coeff(d.tangent, d.tangent), a1 = p.A.coeff(d.tangent + 1, d.tangent + 1);
    const Eigen::Vector2d l(x[d.tangent], x[d.tangent + 1]), v(u[d.tangent], u[d.tangent + 1]);
    const Eigen::Vector2d w(v[0] / a0, v[1] / a1);
    const double a = std::max(a0, a1);
    worst = std::max(worst, (l.norm() - r) * a);  // inside the disc
    // Either sticking (no slip) or on the rim against the slip.
    const double stick = v.norm();
    const double slide = w.norm() > 0 ? (l + r * w.normalized()).norm() * a : INFINITY;
    worst = std::max(worst, std::min(stick, slide));
  }
  return worst;
}

// Φ_τ's Jacobian against central differences (h = 1e-7). Φ_τ is smooth for
// τ > 0 (curvatures ~1/τ = 1e3 here), so the differences are good to
// ~h² × 1e6 + rounding / h ≈ 1e-8; 1e-6 leaves room. At τ = 0 the same holds
// at random points, which lie off the kinks.
TEST(Coulomb, JacobianMatchesCentralDifferences) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  for (const double tau : {1e-3, 0.0})
    for (int trial = 0; trial < 20; ++trial) {
      const CoulombProblem p = random_problem(2, 2, 3, 0.5, rng);
      const Eigen::Index n = p.b.size();
      Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(n, [&] { return g(rng); });
      x.head(p.normals) = x.head(p.normals).cwiseAbs();
      const Eigen::MatrixXd J(coulomb_jacobian(p, x, tau));
      Eigen::MatrixXd F(n, n);
      const double h = 1e-7;
      for (Eigen::Index c = 0; c < n; ++c) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
        e[c] = h;
        F.col(c) = (coulomb_map(p, x + e, tau) - coulomb_map(p, x - e, tau)) / (2 * h);
      }
      EXPECT_LT((J - F).cwiseAbs().maxCoeff(), 1e-6) << "τ = " << tau << ", trial " << trial;
    }
}

// A 2 kg particle arriving at a static plane (n = z) with velocity v; the
// impulse stops its approach (target 0). Analytic answer: λ_n = −m v_z;
// sticking, λ_t = −m v_t, if |v_t| ≤ μ |v_z|; else sliding on, with
// λ_t = −μ λ_n v̂_t.
TEST(Coulomb, OneContactSticksOrSlidesAsCoulombSays) {
  const double m = 2, mu = 0.4;
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0.1, -0.2, -1.0), Eigen::Vector3d(0.6, 0.8, -1.0)}) {
    CoulombProblem p;
    p.A = (Eigen::MatrixXd::Identity(3, 3) / m).sparseView();
    p.b = Eigen::Vector3d(v.z(), v.x(), v.y());
    p.normals = 1;
    p.discs.push_back({1, mu, 0, 1});
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    CoulombSettings how;
    how.velocity_tolerance = 1e-13;
    const CoulombResult r = solve_coulomb(p, x, how);
    ASSERT_TRUE(r.solved) << r.residual;
    const double ln = -m * v.z();
    const Eigen::Vector2d vt(v.x(), v.y());
    const Eigen::Vector2d lt = vt.norm() <= mu * -v.z() ? Eigen::Vector2d(-m * vt) : Eigen::Vector2d(-mu * ln * vt.normalized());
    // 1e-12 of the impulses (~2 N s): rounding of a few Newton steps.
    EXPECT_NEAR(x[0], ln, 1e-12);
    EXPECT_NEAR(x[1], lt[0], 1e-12);
    EXPECT_NEAR(x[2], lt[1], 1e-12);
  }
}

// Seeded random problems (pairs of two and four corners, μ = 0.5), solved
// from zero impulses: each meets 1e-10 of Φ, and Coulomb's conditions
// written out above hold to the same order (a few times 1e-10: they
// measure sticking and sliding in velocity, Φ in impulse × A_ii).
TEST(Coulomb, RandomProblemsMeetCoulombsConditions) {
  std::mt19937_64 rng(11);
  int solved = 0, total = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int corners = trial % 2 ? 4 : 2;
    const CoulombProblem p = random_problem(3, corners, 4, 0.5, rng);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
    CoulombSettings how;
    how.velocity_tolerance = 1e-10;
    const CoulombResult r = solve_coulomb(p, x, how);
    ++total;
    if (!r.solved) continue;
    ++solved;
    EXPECT_LE(coulomb_residual(p, x), 1e-10);
    EXPECT_LE(coulomb_violation(p, x), 1e-9) << "trial " << trial;
  }
  EXPECT_EQ(solved, total);
}

}  // namespace
}  // namespace gacompare::core::contact
