#pragma once
// The contact problem with Coulomb's friction disc, solved exactly: the fixed
// point of the contact solver's projected Gauss–Seidel sweep
// (contact_solver.hpp), found by a semismooth Newton method instead of by
// sweeping to it.
//
//   u = A λ + b  (row velocities less their targets; A = J M⁻¹ Jᵀ, as in lcp.hpp)
//   normal row i:   Φ_i = λ_i − max(0, λ_i − ρ_i u_i)
//   disc (t0, t1):  Φ_t = λ_t − P_r(λ_t − ρ_t u_t),  P_r the projection on the
//                   disc of radius r = μ max(0, λ̄_n), λ̄_n the mean normal
//                   impulse of the disc's pair
//
// with ρ_i = 1 / A_ii, so that Φ_i A_ii is the velocity change a sweep would
// make at row i, and Φ = 0 is exactly a sweep that changes nothing. (With a
// row's own ρ, a sliding contact's friction opposes (u_t0 ρ_t0, u_t1 ρ_t1),
// not u_t: Coulomb's direction where the two tangents' effective masses are
// equal, and turned off it where they differ. The sweeps put t0 along the
// slip, so a contact sliding straight on feels it exactly.) This is Alart &
// Curnier's (1991) formulation with the sweep's own per-row ρ, and the Newton
// method over it is theirs as surveyed by Acary, Brémond & Huber (2018, "On
// solving contact problems with Coulomb friction"). Inside Newton's method
// the radius is taken from the projected normal impulses, μ mean max(0, λ_k −
// ρ_k u_k), equal to μ λ̄_n at an answer (Alart & Curnier's augmented form: a
// parting row counts as unloaded before its impulse reaches 0); the kinks of
// max and of the projection are smoothed with a parameter τ that is followed
// down to 0 (Chen–Harker–Kanzow–Smale); and each step is cut back by an
// Armijo search on ‖diag(A) Φ_τ‖² (coulomb.cpp).
//
// Why not the box of lcp.hpp alone: the direct solve holds each friction row
// in a box ±μ λ̄_n taken from the normal impulses of its previous round. In a
// landing with friction those rounds need not settle (the bounds move with
// the answer they bound), and the box's corners are √2 μ λ̄_n out: the sweeps
// after it then cycle between the discs' rims and end on their cap. Newton's
// Jacobian carries both couplings (the disc's radius through λ̄_n, the rim's
// curvature), so it converges where the fixed point on the bounds does not.
//
// Where rows are redundant (a face's four corners), J is singular; each
// Newton system is solved for J + εI (a Levenberg–Marquardt shift): on the
// consistent part this converges like ε/σ per step, and the null space's
// directions are damped, not chosen.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace gacompare::core::contact {

// One contact's friction: its two tangent rows `tangent`, `tangent + 1`, held
// in the disc of radius μ times the mean impulse of normal rows
// [pair_begin, pair_end) (its pair's points: contact_solver.hpp,
// friction_limit).
struct CoulombDisc {
  Eigen::Index tangent;
  double mu;
  Eigen::Index pair_begin, pair_end;
};

struct CoulombProblem {
  Eigen::SparseMatrix<double> A;  // symmetric, both triangles stored, A_ii > 0
  Eigen::VectorXd b;
  Eigen::Index normals = 0;       // rows [0, normals) are normal rows
  std::vector<CoulombDisc> discs;  // every other row belongs to exactly one disc
};

struct CoulombSettings {
  double velocity_tolerance = 0;  // stop when every |Φ_i| A_ii is at most this
  int max_iterations = 60;     // factorisations at most
  double shift = 1e-9;        // ε of J + εI at the start, and its least
  double max_shift = 1e3;     // its largest (coulomb.cpp)
  double smoothing = 1e-3;    // the first τ, as a share of the largest impulse (plus the first residual)
};

struct CoulombResult {
  bool solved = false;
  int iterations = 0;     // Newton steps taken (each one LU factorisation)
  double residual = 0;    // max |Φ_i| A_ii at return
};

// Solves p from the impulses in `lambda` (a good start matters: Newton's
// method converges from near an answer), leaving the best found there.
CoulombResult solve_coulomb(const CoulombProblem& p, Eigen::VectorXd& lambda, const CoulombSettings& settings);

// max |Φ_i| A_ii at λ: the largest velocity change one projected
// Gauss–Seidel sweep would make there.
double coulomb_residual(const CoulombProblem& p, const Eigen::VectorXd& lambda);

// Φ_τ at λ (τ = 0: Φ), and its Jacobian as the Newton steps use it
// (unshifted; at τ = 0 one element of Φ's generalised Jacobian): exposed so
// that tests can check it against differences.
Eigen::VectorXd coulomb_map(const CoulombProblem& p, const Eigen::VectorXd& lambda, double tau = 0);
Eigen::SparseMatrix<double> coulomb_jacobian(const CoulombProblem& p, const Eigen::VectorXd& lambda, double tau = 0);

}  // namespace gacompare::core::contact
