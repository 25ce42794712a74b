#include "core/contact/coulomb.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace gacompare::core::contact {
namespace {

using Index = Eigen::Index;
using Triplet = Eigen::Triplet<double>;

// Smoothed max and its slope (Chen–Harker–Kanzow–Smale): (a + b + √((a−b)² + 4τ²)) / 2,
// max(a, b) at τ = 0.
struct Smooth {
  double value, da, db;
};
Smooth smooth_max(double a, double b, double tau) {
  const double d = a - b, q = std::sqrt(d * d + 4 * tau * tau);
  const double s = q > 0 ? d / q : (d > 0 ? 1.0 : -1.0);  // at a kink (τ = 0, a = b): the first branch
  return {0.5 * (a + b + q), 0.5 * (1 + s), 0.5 * (1 - s)};
}

// The disc's radius (Alart & Curnier's augmented form): μ times the mean of
// max_τ(z_k, 0) over its pair's normal rows, z_k = λ_k − ρ_k u_k, with each
// row's slope. At an answer max(z_k, 0) = λ_k, so the radius is μ λ̄_n there;
// away from one, a row that is parting (z_k < 0) already counts as unloaded,
// so Newton's model does not ask a lifting point to stick.
struct Radius {
  double r;
  std::vector<std::pair<Index, double>> slope;  // (k, ∂r/∂z_k)
};
Radius radius_of(const CoulombDisc& d, const Eigen::VectorXd& a, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                 double tau) {
  Radius out{0, {}};
  const double share = d.mu / static_cast<double>(d.pair_end - d.pair_begin);
  for (Index k = d.pair_begin; k < d.pair_end; ++k) {
    const Smooth m = smooth_max(x[k] - u[k] / a[k], 0, tau);
    out.r += share * m.value;
    out.slope.emplace_back(k, share * m.da);
  }
  return out;
}

// One disc's state at x: z = λ_t − ρ_t u_t, its radius and the smoothed
// projection P_τ(z) = z r / max_τ(|z|, r) (the projection on the disc at τ = 0).
struct DiscState {
  Eigen::Vector2d z, projected;
  Radius radius;
  double size;
  Smooth m;
};
DiscState disc_state(const CoulombDisc& d, const Eigen::VectorXd& a, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& u, double tau) {
  DiscState s;
  const Index j = d.tangent;
  s.z = Eigen::Vector2d(x[j] - u[j] / a[j], x[j + 1] - u[j + 1] / a[j + 1]);
  s.radius = radius_of(d, a, x, u, tau);
  s.size = s.z.norm();
  s.m = smooth_max(s.size, s.radius.r, tau);
  s.projected = s.m.value > 0 ? Eigen::Vector2d(s.z * (s.radius.r / s.m.value)) : Eigen::Vector2d::Zero();
  return s;
}

// Φ_τ at x (see coulomb.hpp; τ = 0: Φ itself), given u = A x + b.
void residual(const CoulombProblem& p, const Eigen::VectorXd& a, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
              double tau, Eigen::VectorXd& phi) {
  phi.resize(x.size());
  for (Index i = 0; i < p.normals; ++i) phi[i] = x[i] - smooth_max(x[i] - u[i] / a[i], 0, tau).value;
  for (const CoulombDisc& d : p.discs) {
    const DiscState s = disc_state(d, a, x, u, tau);
    phi[d.tangent] = x[d.tangent] - s.projected[0], phi[d.tangent + 1] = x[d.tangent + 1] - s.projected[1];
  }
}

// The velocity-scaled size of Φ: max |Φ_i| A_ii.
double worst(const Eigen::VectorXd& a, const Eigen::VectorXd& phi) {
  double w = 0;
  for (Index i = 0; i < phi.size(); ++i) w = std::max(w, std::abs(phi[i]) * a[i]);
  return w;
}
double merit(const Eigen::VectorXd& phi, const Eigen::VectorXd& diagonal) {
  return 0.5 * phi.cwiseProduct(diagonal).squaredNorm();
}

// Φ_τ's Jacobian at x (at τ = 0 one element of Φ's generalised Jacobian),
// shifted by εI, as triplets.
void jacobian(const CoulombProblem& p, const Eigen::VectorXd& a, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
              double tau, double shift, std::vector<Triplet>& t) {
  t.clear();
  // Row `of` of ρ A, times s, into row `row` (A symmetric: row `of` is column `of`).
  const auto a_row = [&](Index row, Index of, double s) {
    if (s == 0) return;
    const double rho = 1 / a[of];
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, of); it; ++it) t.emplace_back(row, it.row(), s * rho * it.value());
  };
  // Normal row: Φ_i = λ_i − m(z_i), ∂z_i/∂λ = e_i − ρ_i A_i, so ∂Φ_i = (1 − m') e_i + m' ρ_i A_i.
  for (Index i = 0; i < p.normals; ++i) {
    const double slope = smooth_max(x[i] - u[i] / a[i], 0, tau).da;
    t.emplace_back(i, i, 1 - slope);
    a_row(i, i, slope);
  }
  // Disc: Φ_t = λ_t − P(z, r), ∂Φ_t = E_t − P_z (E_t − ρ_t A_t) − P_r ∂r, with
  // P = z r / m, m = max_τ(|z|, r):
  //   P_z = (r/m) I − (r/m²) m_a z ẑᵀ,   P_r = z/m − (r/m²) m_b z.
  for (const CoulombDisc& d : p.discs) {
    const Index j = d.tangent;
    const DiscState s = disc_state(d, a, x, u, tau);
    const double r = s.radius.r, m = s.m.value;
    Eigen::Matrix2d Pz = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Pr = Eigen::Vector2d::Zero();
    if (m > 0) {
      const Eigen::Vector2d n = s.size > 0 ? Eigen::Vector2d(s.z / s.size) : Eigen::Vector2d::Zero();
      Pz = (r / m) * Eigen::Matrix2d::Identity() - (r / (m * m)) * s.m.da * s.z * n.transpose();
      Pr = s.z / m - (r / (m * m)) * s.m.db * s.z;
    }
    for (int e = 0; e < 2; ++e) {
      for (int c = 0; c < 2; ++c) {
        t.emplace_back(j + e, j + c, (e == c ? 1.0 : 0.0) - Pz(e, c));
        a_row(j + e, j + c, Pz(e, c));
      }
      // −P_r ∂r, ∂r = Σ_k r'_k (e_k − ρ_k A_k).
      if (Pr[e] != 0)
        for (const auto& [k, slope] : s.radius.slope) {
          t.emplace_back(j + e, k, -Pr[e] * slope);
          a_row(j + e, k, Pr[e] * slope);
        }
    }
  }
  for (Index i = 0; i < x.size(); ++i) t.emplace_back(i, i, shift);
}

}  // namespace

Eigen::SparseMatrix<double> coulomb_jacobian(const CoulombProblem& p, const Eigen::VectorXd& lambda, double tau) {
  std::vector<Triplet> t;
  jacobian(p, p.A.diagonal(), lambda, p.A * lambda + p.b, tau, 0, t);
  Eigen::SparseMatrix<double> J(lambda.size(), lambda.size());
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

Eigen::VectorXd coulomb_map(const CoulombProblem& p, const Eigen::VectorXd& lambda, double tau) {
  Eigen::VectorXd phi;
  residual(p, p.A.diagonal(), lambda, p.A * lambda + p.b, tau, phi);
  return phi;
}

double coulomb_residual(const CoulombProblem& p, const Eigen::VectorXd& lambda) {
  const Eigen::VectorXd a = p.A.diagonal();
  Eigen::VectorXd phi;
  residual(p, a, lambda, p.A * lambda + p.b, 0, phi);
  return worst(a, phi);
}

CoulombResult solve_coulomb(const CoulombProblem& p, Eigen::VectorXd& lambda, const CoulombSettings& settings) {
  const Index n = lambda.size();
  const Eigen::VectorXd a = p.A.diagonal();  // A_ii = 1/ρ_i, read once
  Eigen::VectorXd u = p.A * lambda + p.b, exact, phi;
  residual(p, a, lambda, u, 0, exact);
  CoulombResult result;
  result.residual = worst(a, exact);
  std::vector<Triplet> t;
  Eigen::SparseMatrix<double> J(n, n);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::VectorXd trial, trial_u, trial_phi;
  // Smoothing (τ) follows the exact residual down: Newton's steps on Φ_τ
  // cross the kinks of Φ (a row parting, a contact between sticking and
  // sliding) along a smooth path instead of zigzagging across them.
  double tau = exact.lpNorm<Eigen::Infinity>() + settings.smoothing * lambda.lpNorm<Eigen::Infinity>();
  residual(p, a, lambda, u, tau, phi);  // Φ_τ at the iterate, kept current below
  // The shift adapts (Levenberg–Marquardt): raised a hundredfold when no step
  // along Newton's direction lowers the merit, tenfold when the step had to
  // be cut below a quarter, and lowered tenfold after a longer one.
  double shift = settings.shift;
  // The merit is Φ_τ's, so Φ itself need not fall at every step: the best
  // iterate is kept.
  Eigen::VectorXd best = lambda;
  double best_residual = result.residual;
  while (result.residual > settings.velocity_tolerance && result.iterations < settings.max_iterations) {
    const double f = merit(phi, a);
    jacobian(p, a, lambda, u, tau, shift, t);
    J.setFromTriplets(t.begin(), t.end());
    lu.analyzePattern(J);
    lu.factorize(J);
    ++result.iterations;
    Eigen::VectorXd step;
    if (lu.info() == Eigen::Success) step = lu.solve(-phi);
    // Backtracking (Armijo on ½‖diag(A) Φ_τ‖²).
    double taken = 0;
    if (lu.info() == Eigen::Success && step.allFinite())
      for (double alpha = 1; alpha >= 1.0 / 256; alpha /= 2) {
        trial = lambda + alpha * step;
        trial_u = p.A * trial + p.b;
        residual(p, a, trial, trial_u, tau, trial_phi);
        if (merit(trial_phi, a) <= (1 - 1e-4 * alpha) * f) {
          lambda.swap(trial), u.swap(trial_u), phi.swap(trial_phi), taken = alpha;
          break;
        }
      }
    if (taken == 0) {
      if (shift >= settings.max_shift) break;  // no descent even along the damped step
      shift = std::min(settings.max_shift, shift * 100);
      continue;
    }
    // A short step means the model is poor far out (a near-singular J's step
    // is mostly its null space): shift more; a full one, less.
    if (taken >= 0.25) shift = std::max(settings.shift, shift / 10);
    else shift = std::min(settings.max_shift, shift * 10);
    residual(p, a, lambda, u, 0, exact);
    result.residual = worst(a, exact);
    if (result.residual < best_residual) best = lambda, best_residual = result.residual;
    // τ falls tenfold once Φ_τ is small against it (the smoothed problem
    // nearly solved: its answer then lies near the next one's).
    if (phi.lpNorm<Eigen::Infinity>() <= 0.1 * tau) tau *= 0.1, residual(p, a, lambda, u, tau, phi);
  }
  if (best_residual < result.residual) lambda = best, result.residual = best_residual;
  result.solved = result.residual <= settings.velocity_tolerance;
  return result;
}

}  // namespace gacompare::core::contact
