// The CG multiplier solve against a dense factorisation of the same J W Jᵀ, built
// here from the rows independently of the solver's sparse assembly; and generator
// expansion.
#include "core/dynamics/particle_constraint_solver.hpp"
#include "core/error.hpp"
#include "core/model/generators.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>

namespace gacompare::core {
namespace {

TEST(ConstraintSolver, MatchesDenseSolveOnRandomChains) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 12;  // particles; particle 0 pinned
    std::vector<double> w(n);
    for (int i = 0; i < n; ++i) w[i] = i == 0 ? 0.0 : 1.0 / (0.5 + std::abs(u(rng)));
    std::vector<ConstraintRow> rows;
    for (int i = 0; i + 1 < n; ++i) {  // a chain, plus a few single-particle rows
      ConstraintRow r;
      r.n = 2;
      r.particle = {i, i + 1};
      for (int a = 0; a < 3; ++a) r.grad[0][a] = u(rng), r.grad[1][a] = -r.grad[0][a];
      rows.push_back(r);
    }
    for (int i = 3; i < n; i += 4) {
      ConstraintRow r;
      r.n = 1;
      r.particle = {i, i};
      for (int a = 0; a < 3; ++a) r.grad[0][a] = u(rng);
      rows.push_back(r);
    }
    const auto m = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, 3 * n);
    for (Eigen::Index k = 0; k < m; ++k)
      for (int i = 0; i < rows[k].n; ++i)
        for (int a = 0; a < 3; ++a) J(k, 3 * rows[k].particle[i] + a) += rows[k].grad[i][a];
    Eigen::VectorXd W(3 * n);
    for (int i = 0; i < n; ++i) W.segment<3>(3 * i).setConstant(w[i]);
    const Eigen::MatrixXd A = J * W.asDiagonal() * J.transpose();
    Eigen::VectorXd b(m);
    for (Eigen::Index k = 0; k < m; ++k) b[k] = u(rng);
    const Eigen::VectorXd expected = A.ldlt().solve(b);

    ConstraintSolverSpec spec;
    spec.cg_tolerance = 1e-14;
    ConstraintSolver solver(spec, w);
    const auto& lambda = solver.solve(rows, std::vector<double>(b.data(), b.data() + m));
    // CG stops at a relative residual of 1e-14; the error in λ is that times the
    // condition number of these small random systems (≲ 1e4): 1e-9 relative.
    for (Eigen::Index k = 0; k < m; ++k) ASSERT_NEAR(lambda[k], expected[k], 1e-9 * expected.norm()) << trial;
    EXPECT_EQ(solver.stats().cg_not_converged, 0u);
  }
}

TEST(ConstraintSolver, BaumgarteAddsDampingAndStiffness) {
  ConstraintSolverSpec spec;
  ConstraintRow r;
  r.c = 0.5;
  r.j_qdot = 2;
  r.jdot_qdot = 3;
  r.j_w_q = 4;
  spec.drift = Drift::off;
  EXPECT_EQ(ConstraintSolver(spec, {1}).dynamics_rhs(std::vector{r})[0], -7);  // −J̇q̇ − JWQ (eq. 24)
  spec.drift = Drift::baumgarte;
  spec.baumgarte_alpha = 2;
  spec.baumgarte_beta = 3;
  EXPECT_EQ(ConstraintSolver(spec, {1}).dynamics_rhs(std::vector{r})[0], -7 - 2 * 2 * 2 - 9 * 0.5);
}

TEST(ConstraintSolver, LockedConstraintsStopWithTheirCause) {
  // Two rows on one particle with parallel gradients and inconsistent targets:
  // J W Jᵀ is singular and b is outside its range.
  ConstraintRow a, b;
  a.n = b.n = 1;
  a.particle = b.particle = {0, 0};
  a.grad[0] = b.grad[0] = {1, 0, 0};
  ConstraintSolver solver({}, {1.0});
  try {
    solver.solve(std::vector{a, b}, std::vector<double>{1, -1});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("redundant or locked"), std::string::npos) << e.what();
  }
}

TEST(Generators, NetAndChainExpand) {
  Scene s;
  s.particles.push_back({"free", 1, Vec3(9, 9, 9), Vec3::Zero(), false});
  ParticleNet net;
  net.name = "net";
  net.rows = 2;
  net.cols = 3;
  net.spacing = 0.5;
  net.mass = 2;
  net.origin = Vec3(1, 0, 0);
  net.pinned = {{0, 2}};
  ParticleChain chain;
  chain.name = "c";
  chain.count = 3;
  chain.spacing = 0.2;
  chain.direction = Vec3(0, 0, -2);
  chain.pinned = {0};
  s.generators = {net, chain};
  s.constraints.push_back(DistanceToPoint{"net[1][1]", Vec3::Zero(), 1});
  const Scene e = expand_generators(s);
  ASSERT_EQ(e.particles.size(), 1u + 6u + 3u);
  EXPECT_TRUE(e.generators.empty());
  EXPECT_EQ(e.particles[1].name, "net[0][0]");
  EXPECT_EQ(e.particles[6].name, "net[1][2]");
  EXPECT_EQ(e.particles[6].position, Vec3(2, 0.5, 0));
  EXPECT_TRUE(e.particles[3].pinned);  // net[0][2]
  EXPECT_EQ(e.particles[9].position, Vec3(0, 0, -0.4));  // c[2]: direction normalised
  EXPECT_TRUE(e.particles[7].pinned);  // c[0]
  // 2×3 net: 2·2 horizontal + 3 vertical rods; chain: 2 links; then the scene's own.
  ASSERT_EQ(e.constraints.size(), 7u + 2u + 1u);
  EXPECT_TRUE(std::holds_alternative<DistanceToPoint>(e.constraints.back()));
  const auto& first = std::get<DistanceBetween>(e.constraints[0]);
  EXPECT_EQ(first.a, "net[0][0]");
  EXPECT_EQ(first.b, "net[0][1]");
  EXPECT_EQ(first.length, 0.5);
}

}  // namespace
}  // namespace gacompare::core
