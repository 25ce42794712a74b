#include "core/dynamics/ode.hpp"

#include <cmath>
#include <sstream>

namespace gacompare::core {

bool is_adaptive(SolverMethod m) {
  return m == SolverMethod::rk4_doubling || m == SolverMethod::cash_karp45;
}

OdeSolver::OdeSolver(const SolverSpec& spec, std::size_t n, std::vector<int> velocity_of)
    : spec_(spec), h_(spec.dt), velocity_of_(std::move(velocity_of)),
      k1_(n), k2_(n), k3_(n), k4_(n), k5_(n), k6_(n), tmp_(n), out_(n), half_(n), err_(n) {
  switch (spec.method) {
    case SolverMethod::euler:
    case SolverMethod::rk4:
    case SolverMethod::rk4_doubling:
    case SolverMethod::cash_karp45:
      break;
    case SolverMethod::symplectic_euler:
    case SolverMethod::velocity_verlet:
      if (velocity_of_.size() != n)
        throw input_error("solver.method '" + std::string(to_string(spec.method)) +
                          "' needs a state of positions and velocities, which this backend's state is not");
      break;
  }
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

void OdeSolver::record(double h) {
  ++stats_.steps_accepted;
  stats_.min_step = std::min(stats_.min_step, h);
  stats_.max_step = std::max(stats_.max_step, h);
}

}  // namespace gacompare::core
