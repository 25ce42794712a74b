#pragma once
// A direct solver for the contact problem of one island: the bounded linear
// complementarity problem (BLCP)
//
//   w = A λ + b,  lo ≤ λ ≤ hi,  and for every row i
//   w_i = 0 where lo_i < λ_i < hi_i,  w_i ≥ 0 where λ_i = lo_i,  w_i ≤ 0 where λ_i = hi_i,
//
// with A = J M⁻¹ Jᵀ symmetric positive semi-definite (the rows' Delassus
// matrix: the velocity change of row i per unit impulse on row j). A normal
// row has lo = 0, hi = ∞ (it pushes, never pulls); a friction row ±μλ_n; a
// bilateral row ±∞. Projected Gauss–Seidel converges on this at a rate that
// falls with the stack's height and the mass ratio (a column of n bodies at
// about cos²(π/(n+1)) per sweep); this solver finds the active set instead and
// then solves for it exactly.
//
// Method: a primal active-set method for the equivalent convex quadratic
// programme, minimise ½ λᵀAλ + bᵀλ over lo ≤ λ ≤ hi (its optimality
// conditions are the BLCP's; Nocedal & Wright, ch. 16.5). Each iteration
// solves the free rows' linear system with the other rows held on their
// bounds and steps towards that answer as far as the bounds allow; a row that
// a step blocks joins its bound, and at a free minimiser every row that its
// bound holds against the gradient is released. In exact arithmetic the
// objective falls at every release, so the method cannot cycle; in floating
// point a degenerate set can, and a guard holds the rows that cycle on their
// bounds (lcp.cpp). A warm start's active set is usually already right: one
// factorisation is the common case. Where many rows meet
// their bounds at once (a stack landing), the free minimiser projected onto
// the bounds is taken instead of the step to the first bound when it lowers
// the objective more, so they join their bounds in one iteration (lcp.cpp).
// The changes after a factorisation are solved through a Schur complement
// bordering it while they are few, not by factorising again (lcp.cpp).
// (Block principal pivoting, tried first, cycled on the degenerate sets of a
// face's corners.)
//
// A is singular whenever rows are redundant (the four corners of a face have
// three degrees of freedom between them): then the answer's λ is not unique
// and the free rows' system is singular. So the active set is found for
// A + δW, δ a 1e-10 of A's largest diagonal and W the rows' weights (1 unless
// the problem says otherwise): positive definite, a unique
// answer, every free system invertible. Its free rows' impulses are then refined against
// A itself (the regularisation's δλ taken out of their velocities): on the
// consistent part the refinement converges like δ/σ per step (σ the smallest
// non-zero eigenvalue), and what it leaves in A_FF's null space changes no
// velocity (null A = null Jᵀ).
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace gacompare::core::contact {

struct Blcp {
  Eigen::SparseMatrix<double> A;  // symmetric, both triangles stored
  Eigen::VectorXd b, lo, hi;
  // Each row's share of the regularisation, δ_i = weight_i δ (empty: 1 for
  // every row). Where λ is not unique, the answer found is the one of least
  // Σ weight_i λ_i² among the exact answers: a heavier weight keeps a row out
  // of the answer wherever the others can carry it.
  Eigen::VectorXd weight;
  // Optional: A's factor by body, A = G Gᵀ, a row per row of A and at most
  // six columns per body (G = J M^-½ in some basis of each body's motions).
  // Given, a free system of at least augmented_from rows is factorised as
  // the augmented system [I Gᵀ; G −δ] (lcp.cpp) where that holds fewer
  // entries than A_FF: where rows share bodies many at a time (a stack).
  Eigen::SparseMatrix<double, Eigen::RowMajor> G;
};

struct BlcpSettings {
  int max_pivots = 256;         // active-set changes before giving up
  double velocity_tolerance = 0;  // w's sign conditions hold to this (m/s or m)
  int dense_up_to = 48;         // rows at most for a dense factorisation
  int max_proximal = 64;        // proximal steps at most, once the active set is found (lcp.cpp)
  int most_updates = 64;        // active-set changes solved through a Schur complement before factorising again (lcp.cpp; 0: none)
  // Free rows at least for the augmented factorisation, where G is given
  // (lcp.cpp): about where the two cost the same on the square pyramids
  // (5 layers, ~580 rows: 0.28 s per simulated second either way; 7 layers,
  // ~1,650 rows: 0.88 s factorising A, 0.56 s the augmented system).
  int augmented_from = 500;
  // Of those, only the ones whose augmented matrix holds fewer entries than
  // A_FF (a stack's, not a pile's: lcp.cpp, FreeSystem); false: all of them
  // (the tests compare the two forms on the same systems).
  bool augment_by_entries = true;
};

struct BlcpResult {
  bool solved = false;
  int pivots = 0;          // active-set changes made
  int factorisations = 0;
  int updates = 0;         // active-set changes solved through the Schur complement instead (lcp.cpp)
  int augmented = 0;       // factorisations of the augmented system [I Gᵀ; G −δ] among them
  int proximal = 0;        // proximal steps taken to remove the regularisation's bias
  int held = 0;            // rows the guard against cycling kept on their bounds, at each release (lcp.cpp)
  double residual = 0;     // the worst violation of the conditions above (w's units)
};

// Solves p for λ; lambda holds the warm start on entry (its rows strictly
// inside their bounds start free) and the solution on return (the best found,
// with result.solved false, after max_pivots).
BlcpResult solve_blcp(const Blcp& p, Eigen::VectorXd& lambda, const BlcpSettings& settings);

// G with G Gᵀ = a for a symmetric positive semi-definite a, at most
// `most_columns` columns: pivoted Cholesky (LAPACK's dpstrf; Higham,
// "Analysis of the Cholesky decomposition of a semi-definite matrix", 1990),
// each column from the largest diagonal of what is left, stopping where that
// is at most 1e-14 of a's largest diagonal (rounding) or at the column
// limit. What it leaves out is at most that diagonal, entry by entry.
Eigen::MatrixXd psd_factor(const Eigen::MatrixXd& a, int most_columns);

// The principal block of A on `rows` (A compressed, each column's rows in
// order): place[i] is row i's position in the block, or −1 outside it, and
// increases with i over the rows, so the block's columns come out sorted.
Eigen::SparseMatrix<double> principal_block(const Eigen::SparseMatrix<double>& a, const std::vector<Eigen::Index>& rows,
                                            const std::vector<Eigen::Index>& place);

// The worst violation of the BLCP conditions by λ (in w's units, with a bound
// violation measured as its velocity effect |A_ii| |excess|).
double blcp_residual(const Blcp& p, const Eigen::VectorXd& lambda);

}  // namespace gacompare::core::contact
