#include "core/dynamics/particle_constraint_solver.hpp"

#include "core/error.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <cmath>
#include <cstdio>

namespace gacompare::core {

double ConstraintRow::grad_norm() const {
  double s = 0;
  for (int k = 0; k < n; ++k)
    for (double g : grad[k]) s += g * g;
  return std::sqrt(s);
}

double max_violation(std::span<const ConstraintRow> rows) {
  double worst = 0;
  for (const auto& r : rows) {
    const double g = r.grad_norm();
    worst = std::max(worst, g > 0 ? std::abs(r.c) / g : std::abs(r.c));
  }
  return worst;
}

std::map<std::string, std::uint64_t> constraint_counters(const std::optional<ConstraintSolver>& solver) {
  if (!solver) return {};
  const auto& s = solver->stats();
  return {{"constraint_solves", s.solves},
          {"cg_iterations", s.cg_iterations},
          {"cg_not_converged", s.cg_not_converged},
          {"projections", s.projections},
          {"projection_iterations", s.projection_iterations},
          {"projection_not_converged", s.projection_not_converged}};
}

std::map<std::string, double> constraint_metrics(const std::optional<ConstraintSolver>& solver) {
  if (!solver) return {};
  return {{"max_cg_relative_residual", solver->stats().max_relative_residual}};
}

void detail::apply_correction(const ConstraintSolver& solver, std::span<const ConstraintRow> rows,
                              const std::vector<double>& step, std::span<double> y, std::size_t stride,
                              std::size_t offset) {
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (int i = 0; i < rows[k].n; ++i) {
      const int p = rows[k].particle[i];
      const double s = solver.inv_mass(p) * step[k];
      for (std::size_t a = 0; a < 3; ++a) y[static_cast<std::size_t>(p) * stride + offset + a] += s * rows[k].grad[i][a];
    }
}

void check_initial_constraints(const Scene& scene, std::span<const ConstraintRow> rows, std::span<const int> owner,
                               std::span<const double> y0) {
  double scale = 1;
  for (double x : y0) scale = std::max(scale, std::abs(x));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double g = rows[k].grad_norm();
    const double violation = g > 0 ? std::abs(rows[k].c) / g : std::abs(rows[k].c);
    if (!(violation <= 1e-9 * scale)) {
      const int i = owner[k];
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g", violation);
      throw input_error(scene.file.string() + ": constraint " + std::to_string(i) + " (" +
                        std::string(constraint_name(scene.constraints[static_cast<std::size_t>(i)])) +
                        "): the initial state violates it by " + buf +
                        " m; particles must start on their constraints (generated constraints come first)");
    }
  }
}

ConstraintSolver::ConstraintSolver(const ConstraintSolverSpec& spec, std::vector<double> inv_mass)
    : spec_(spec), inv_mass_(std::move(inv_mass)) {}

std::vector<double> ConstraintSolver::dynamics_rhs(std::span<const ConstraintRow> rows) const {
  std::vector<double> b(rows.size());
  const bool baumgarte = spec_.drift == Drift::baumgarte;
  const double a2 = 2 * spec_.baumgarte_alpha, b2 = spec_.baumgarte_beta * spec_.baumgarte_beta;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    b[k] = -rows[k].jdot_qdot - rows[k].j_w_q;
    if (baumgarte) b[k] -= a2 * rows[k].j_qdot + b2 * rows[k].c;
  }
  return b;
}

const std::vector<double>& ConstraintSolver::solve(std::span<const ConstraintRow> rows, std::span<const double> b,
                                                   int warm) {
  const auto m = static_cast<Eigen::Index>(rows.size());
  bool inputs_finite = true;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    inputs_finite = inputs_finite && std::isfinite(b[k]);
    for (const auto& g : rows[k].grad) inputs_finite = inputs_finite && std::isfinite(g[0] + g[1] + g[2]);
  }
  // Rows that touch each particle, to find the pairs of rows that couple.
  std::vector<std::vector<int>> touching(inv_mass_.size());
  for (int k = 0; k < static_cast<int>(rows.size()); ++k)
    for (int i = 0; i < rows[k].n; ++i) touching[static_cast<std::size_t>(rows[k].particle[i])].push_back(k);

  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t p = 0; p < touching.size(); ++p) {
    const double w = inv_mass_[p];
    if (w == 0) continue;  // a pinned particle does not move: no coupling through it
    for (int k : touching[p])
      for (int l : touching[p]) {
        auto grad_of = [&](int row) -> const std::array<double, 3>& {
          return rows[row].particle[0] == static_cast<int>(p) ? rows[row].grad[0] : rows[row].grad[1];
        };
        const auto& gk = grad_of(k);
        const auto& gl = grad_of(l);
        entries.emplace_back(k, l, w * (gk[0] * gl[0] + gk[1] * gl[1] + gk[2] * gl[2]));
      }
  }
  // A row whose particles are all pinned has an empty row in J W Jᵀ; a unit
  // diagonal keeps the system regular and gives that row λ = b (its force acts
  // on nothing that moves).
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  for (Eigen::Index k = 0; k < m; ++k)
    if (a.coeff(k, k) == 0) a.coeffRef(k, k) = 1;

  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::DiagonalPreconditioner<double>> cg;
  cg.setTolerance(spec_.cg_tolerance);
  cg.setMaxIterations(spec_.cg_max_iterations);
  cg.compute(a);
  const Eigen::Map<const Eigen::VectorXd> rhs(b.data(), m);
  auto& lambda = lambda_[static_cast<std::size_t>(warm)];
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(m);
  if (static_cast<Eigen::Index>(lambda.size()) == m) guess = Eigen::Map<const Eigen::VectorXd>(lambda.data(), m);
  const Eigen::VectorXd x = cg.solveWithGuess(rhs, guess);
  ++stats_.solves;
  stats_.cg_iterations += static_cast<std::uint64_t>(cg.iterations());
  if (cg.info() != Eigen::Success) ++stats_.cg_not_converged;
  // A solve that stops short of cg_tolerance is counted (cg_not_converged) and
  // used: near-singular moments of a net cost accuracy, not the run. One that
  // stays above 1e-3 relative means J W Jᵀ is singular with a right-hand side
  // outside its range: redundant or locked constraints (a taut chain of rods
  // between two pinned particles cannot move sideways at all). Stop with that
  // said, rather than integrate the garbage λ into NaNs.
  if (!inputs_finite)
    throw run_error("constraints: the multiplier solve was given non-finite values: the state has diverged "
                    "(a step too large for this scene, or an explicit Euler step on constraints)");
  if (!(cg.error() <= 1e-3) || !x.allFinite()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "constraints: the multiplier solve did not converge (relative residual %.3g after %ld CG iterations)",
                  cg.error(), static_cast<long>(cg.iterations()));
    throw run_error(std::string(buf) +
                    ": the constraints are redundant or locked (e.g. a taut chain of rods between two pinned "
                    "particles), or a step too large has carried the state far off them");
  }
  stats_.max_relative_residual = std::max(stats_.max_relative_residual, cg.error());
  lambda.assign(x.data(), x.data() + m);
  return lambda;
}

}  // namespace gacompare::core
