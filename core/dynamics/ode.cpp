#include "core/dynamics/ode.hpp"

#include "core/dynamics/lie_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gacompare::core {

bool is_adaptive(SolverMethod m) {
  return m == SolverMethod::rk4_doubling || m == SolverMethod::cash_karp45 || m == SolverMethod::rkmk45 ||
         butcher_tableau(m) != nullptr;
}

OdeSolver::OdeSolver(const SolverSpec& spec, std::size_t n, std::vector<int> velocity_of)
    : spec_(spec), h_(spec.dt), n_(n), velocity_of_(std::move(velocity_of)) {
  switch (spec.method) {
    case SolverMethod::euler:
    case SolverMethod::rk4:
    case SolverMethod::rk4_doubling:
    case SolverMethod::cash_karp45:
      break;
    case SolverMethod::bs3:
    case SolverMethod::dopri5:
    case SolverMethod::tsit5:
    case SolverMethod::vern6:
    case SolverMethod::vern7:
    case SolverMethod::vern8:
    case SolverMethod::vern9:
      tab_ = butcher_tableau(spec.method);
      control_k_ = tab_->embedded_order + 1;
      fsal_ = tab_->fsal();
      for (int i = 0; i < tab_->stages; ++i) e_.push_back(tab_->b[i] - tab_->bhat[i]);
      K_.resize(static_cast<std::size_t>(std::max(tab_->stages, tab_->dense_stages)) * n);
      weights_.resize(static_cast<std::size_t>(std::max(tab_->stages, tab_->dense_stages)));
      ys_.resize(n);
      break;
    case SolverMethod::rkmk45:
      control_k_ = 5;  // the embedded 4th-order solution's error goes as h^5
      break;
    case SolverMethod::rkmk4:
    case SolverMethod::crouch_grossman4:
      break;
    case SolverMethod::symplectic_euler:
    case SolverMethod::velocity_verlet:
      if (velocity_of_.size() != n)
        throw input_error("solver.method '" + std::string(to_string(spec.method)) +
                          "' needs a state of positions and velocities, which this backend's state is not");
      break;
  }
}

void OdeSolver::size_work() {
  if (k1_.size() == n_) return;
  for (auto* v : {&k1_, &k2_, &k3_, &k4_, &k5_, &k6_, &tmp_, &out_, &half_, &err_}) v->assign(n_, 0.0);
}

double OdeSolver::error_ratio(const std::vector<double>& y, const std::vector<double>& ynew,
                              const std::vector<double>& err) const {
  if (norm_ && spec_.error_norm == ErrorNorm::physical) return norm_(y, ynew, err);
  double worst = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double scale = spec_.abs_tol + spec_.rel_tol * std::max(std::abs(y[i]), std::abs(ynew[i]));
    const double r = std::abs(err[i]) / scale;
    if (std::isnan(r)) return r;  // a non-finite state rejects the step
    worst = std::max(worst, r);
  }
  return worst;
}

// Which component's error, against its tolerance, is the largest: the body or
// particle the step size is waiting for.
std::string OdeSolver::worst(const std::vector<double>& err) const {
  std::size_t worst = 0;
  double most = -1;
  for (std::size_t i = 0; i < err.size(); ++i) {
    const double scale = spec_.abs_tol + spec_.rel_tol * std::abs(out_[i]);
    const double r = std::isfinite(err[i]) ? std::abs(err[i]) / scale : INFINITY;
    if (r > most) most = r, worst = i;
  }
  return who_ && !err.empty() ? who_(worst) : "";
}

void OdeSolver::stop(const std::string& why, double t, double h, const std::vector<double>& err) const {
  std::ostringstream msg;
  msg << "integrate: " << why << ", at t=" << t << " (h=" << h << ")";
  if (const std::string who = is_adaptive(spec_.method) ? worst(err) : ""; !who.empty())
    msg << "; " << who << " has the largest error estimate";
  throw run_error(msg.str());
}

// The embedded pairs' step control (ode.hpp): PI after an accepted step, I after
// a rejected one. A clipped last step does not shrink the next interval's first try.
void OdeSolver::control(double ratio, double h, bool clipped) {
  const double k = control_k_;
  if (ratio <= 1.0) {
    // 0.9 E_n^(−0.7/k) E_{n−1}^(0.4/k) as one exp of logs (log E_{n−1} kept from
    // the step before): two transcendental calls a step instead of two pow's.
    static const double log_floor = std::log(1e-4);  // DOPRI5's facold floor
    const double log_ratio = ratio > 0 ? std::log(ratio) : log_floor;
    double grow = ratio == 0 ? 10.0 : 0.9 * std::exp((0.4 * log_err_prev_ - 0.7 * log_ratio) / k);
    grow = std::clamp(grow, 0.2, rejected_last_ ? 1.0 : 10.0);
    log_err_prev_ = std::max(log_ratio, log_floor);
    rejected_last_ = false;
    h_ = clipped ? std::max(h_, h * grow) : h * grow;
    return;
  }
  ++stats_.steps_rejected;
  rejected_last_ = true;
  h_ = h * (std::isfinite(ratio) ? std::max(0.2, 0.9 * std::pow(ratio, -1.0 / k)) : 0.2);
  if (!(h_ > 64 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(ti_)))) {
    std::ostringstream why;
    why << "step size underflow (error ratio " << ratio
        << "): the tolerance cannot be met or the derivative is not finite";
    stop(why.str(), ti_, h_, err_);
  }
}

// One Lie-group step into out_ (and err_), through the caller's group step.
void OdeSolver::group_step(double t, double h, const std::vector<double>& y) {
  if (!group_step_)
    throw input_error("solver.method '" + std::string(to_string(spec_.method)) +
                      "' steps rigid bodies on their rotation group, and this state has none to step");
  std::fill(err_.begin(), err_.end(), 0.0);
  group_step_(spec_.method, t, h, y, out_, err_);
  stats_.derivative_evaluations += static_cast<std::uint64_t>(lie::body_step_stages(group_method(spec_.method)));
}

// y(t) on the last accepted step [t0_, t0_ + hlast_] from its interpolant.
void OdeSolver::interpolate(double t, std::vector<double>& y) {
  const ButcherTableau& T = *tab_;
  const double theta = (t - t0_) / hlast_;
  const auto deg = static_cast<std::size_t>(T.dense_degree), s = static_cast<std::size_t>(T.dense_stages), n = y.size();
  std::vector<double>& w = weights_;
  for (std::size_t i = 0; i < s; ++i) {
    double wi = 0;  // Horner in θ, then the factor θ of every b_i(θ)
    for (std::size_t p = deg; p-- > 0;) wi = wi * theta + T.dense[i * deg + p];
    w[i] = wi * theta;
  }
  // Σ_i b_i(θ) = θ: the same differences from k_1 as the step (pair_step).
  for (std::size_t m = 0; m < n; ++m) {
    const double k1 = K_[m];
    double acc = theta * k1;
    for (std::size_t i = 1; i < s; ++i) acc += w[i] * (K_[i * n + m] - k1);
    y[m] = ys_[m] + hlast_ * acc;
  }
}

void OdeSolver::add_steps(const SolverStats& before, const SolverStats& after) {
  stats_.steps_accepted += after.steps_accepted - before.steps_accepted;
  stats_.steps_rejected += after.steps_rejected - before.steps_rejected;
  stats_.derivative_evaluations += after.derivative_evaluations - before.derivative_evaluations;
  if (after.steps_accepted > before.steps_accepted) {
    stats_.min_step = std::min(stats_.min_step, after.min_step);
    stats_.max_step = std::max(stats_.max_step, after.max_step);
  }
}

double OdeSolver::fixed_steps(double t, double t_end, const std::vector<double>& y) const {
  const double steps = std::max(1.0, std::ceil((t_end - t) / spec_.dt * (1 - 1e-12)));
  // Counted before they are taken: a count past 2^64 (dt 1e-300) would
  // convert to nothing, and the body would silently never move.
  if (static_cast<double>(stats_.steps_accepted) + steps > budget_) {
    std::ostringstream why;
    why << "the fixed step needs " << steps << " more steps to t=" << t_end << ", past the budget of " << budget_
        << " (--max-steps raises it)";
    stop(why.str(), t, spec_.dt, y);
  }
  return steps;
}

void OdeSolver::check_budget(double t) const {
  if (static_cast<double>(stats_.steps_accepted + stats_.steps_rejected) < budget_) return;
  std::ostringstream why;
  why << "the budget of " << budget_ << " steps is spent (--max-steps raises it)";
  stop(why.str(), t, h_, err_);
}

void OdeSolver::record(double h) {
  ++stats_.steps_accepted;
  stats_.min_step = std::min(stats_.min_step, h);
  stats_.max_step = std::max(stats_.max_step, h);
}

}  // namespace gacompare::core
