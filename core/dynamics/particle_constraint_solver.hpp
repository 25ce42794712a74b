#pragma once
// The backend-neutral half of constrained dynamics (§2.1.2): given the rows of the
// constraint Jacobian J that a backend computed in its own algebra, solve
// (J W Jᵀ) λ = b by conjugate gradient with a Jacobi (diagonal) preconditioner,
// W = M⁻¹. J is sparse (a row touches one or two particles), and so is J W Jᵀ:
// two rows couple only through a particle they share.
//
// The report solves eq. 24 but says nothing of how; CG on the normal matrix is
// the method of Witkin's constrained dynamics notes, which the report follows.
// The solve is warm-started from the previous λ: consecutive solves differ little.
#include "core/model/scene.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <span>
#include <vector>

namespace gacompare::core {

// One scalar constraint C(x) = 0 at the current state.
struct ConstraintRow {
  double c = 0;          // C(x)
  double jdot_qdot = 0;  // J̇ q̇: the velocity-product term of C̈
  double j_qdot = 0;     // J q̇ = Ċ
  double j_w_q = 0;      // J W Q: the applied forces' effect on C̈
  int n = 0;             // particles involved: 1 or 2
  std::array<int, 2> particle{};
  std::array<std::array<double, 3>, 2> grad{};  // ∂C/∂x of each particle
  // |∇C|: divides C into a distance (metres) for violation reports and tolerances.
  double grad_norm() const;
};

struct ConstraintStats {
  std::uint64_t solves = 0;
  std::uint64_t cg_iterations = 0;
  std::uint64_t cg_not_converged = 0;  // solves that hit cg_max_iterations
  double max_relative_residual = 0;
  std::uint64_t projections = 0;       // drift = projection: position projections made
  std::uint64_t projection_iterations = 0;
  std::uint64_t projection_not_converged = 0;
};

class ConstraintSolver {
 public:
  ConstraintSolver(const ConstraintSolverSpec& spec, std::vector<double> inv_mass);

  // λ solving (J W Jᵀ) λ = b. `warm` selects which previous solution seeds CG (the
  // dynamics and the projection solve different systems).
  const std::vector<double>& solve(std::span<const ConstraintRow> rows, std::span<const double> b, int warm = 0);

  // The right-hand side of eq. 24 for every row, with Baumgarte's terms when that
  // drift control is chosen: b = −J̇q̇ − J W Q − 2α Ċ − β² C.
  std::vector<double> dynamics_rhs(std::span<const ConstraintRow> rows) const;

  const ConstraintSolverSpec& spec() const { return spec_; }
  double inv_mass(int p) const { return inv_mass_[static_cast<std::size_t>(p)]; }
  const ConstraintStats& stats() const { return stats_; }
  ConstraintStats& stats() { return stats_; }

 private:
  ConstraintSolverSpec spec_;
  std::vector<double> inv_mass_;
  std::array<std::vector<double>, 2> lambda_;
  ConstraintStats stats_;
};

// drift = projection (after each accepted step): moves positions, then velocities,
// onto the constraints by mass-weighted least-change steps x += W Jᵀ δλ with
// (J W Jᵀ) δλ = −C (Gauss–Newton on C(x) = 0, at most 50 iterations, until every
// |C|/|∇C| is below projection_tolerance), then v += W Jᵀ μ with (J W Jᵀ) μ = −J v.
// The state holds particles of `stride` doubles: position (3) then velocity (3).
// rows(y) recomputes the backend's rows at y and returns them.
template <class RowsAt>
void project_onto_constraints(ConstraintSolver& solver, std::span<double> y, std::size_t stride, RowsAt&& rows);

// Throws input_error naming the first constraint the initial state violates by
// more than 1e-9 × max(1, largest |coordinate|): a scene must start on its constraints.
void check_initial_constraints(const Scene& scene, std::span<const ConstraintRow> rows, std::span<const int> owner,
                               std::span<const double> y0);

// The solver's statistics as run counters (empty without constraints).
std::map<std::string, std::uint64_t> constraint_counters(const std::optional<ConstraintSolver>& solver);
std::map<std::string, double> constraint_metrics(const std::optional<ConstraintSolver>& solver);

// max over rows of |C| / |∇C|: how far, to first order, the state is from
// satisfying every constraint (metres).
double max_violation(std::span<const ConstraintRow> rows);

namespace detail {
// y[p·stride + offset + a] += w_p · step_k · ∇_p C_k for every row k.
void apply_correction(const ConstraintSolver& solver, std::span<const ConstraintRow> rows,
                      const std::vector<double>& step, std::span<double> y, std::size_t stride, std::size_t offset);
}

template <class RowsAt>
void project_onto_constraints(ConstraintSolver& solver, std::span<double> y, std::size_t stride, RowsAt&& rows_at) {
  auto& st = solver.stats();
  ++st.projections;
  bool converged = false;
  for (int it = 0; it < 50; ++it) {
    const auto& rows = rows_at(std::span<const double>(y));
    if (max_violation(rows) <= solver.spec().projection_tolerance) {
      converged = true;
      break;
    }
    ++st.projection_iterations;
    std::vector<double> b(rows.size());
    for (std::size_t k = 0; k < b.size(); ++k) b[k] = -rows[k].c;
    detail::apply_correction(solver, rows, solver.solve(rows, b, 1), y, stride, 0);
  }
  if (!converged) ++st.projection_not_converged;
  const auto& rows = rows_at(std::span<const double>(y));
  std::vector<double> b(rows.size());
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = -rows[k].j_qdot;
  detail::apply_correction(solver, rows, solver.solve(rows, b, 1), y, stride, 3);
}

}  // namespace gacompare::core
