#pragma once
// ODE solvers on a flat state (Appendix B): each backend packs its own state into
// contiguous doubles and supplies f(t, y, dydt). Every advance() leaves y at the
// requested time, so samples fall on the output times.
//
//   euler         eq. 55, fixed step
//   rk4           eq. 56, fixed step
//   rk4_doubling  §B.3.1: one RK4 step of h against two of h/2; the difference
//                 /15 estimates the error of the two-half-step result, which is kept
//   cash_karp45   §B.3.2, eq. 57–58, Table 4: the 5th-order solution is kept
//                 (local extrapolation) and the embedded 4th-order one gives the error
//
// Step control of these two (§B.3.3, eq. 59, done properly): by default the caller's physical
// error norm (set_error_norm; core/model/scene.hpp ErrorNorm), else the error of component i is
// scaled by abs_tol + rel_tol·max(|y_i|, |y_new_i|); the worst ratio E sets the
// step, h_new = h · clamp(0.9 · E^(−1/(order+1)), 0.2, 5). The report's eq. 59 has
// no safety factor or limits, which lets one lucky step grow h without bound.
// Fixed-step methods split each output interval into equal steps no longer than
// dt (the recording mode of fn 39), so the last step is never a sliver.
//
// Beyond the report, embedded pairs written once as Butcher tableaus
// (core/dynamics/tableaus.hpp) and driven by one stepper, pair_step:
//   bs3 (3(2)), dopri5 and tsit5 (5(4)), vern6, vern7, vern8, vern9 (p(p−1)).
// The higher-order solution is kept; the same error norm measures b − bhat. Their
// step control is Gustafsson's PI controller (Hairer–Wanner II §IV.2, eq. 2.43c):
// after an accepted step h_new = h · clamp(0.9 · E_n^(−β1) · E_{n−1}^(β2), 0.2, 10)
// with β1 = 0.7/k, β2 = 0.4/k, k = embedded order + 1 (the power of h in the
// estimate), E_{n−1} the last accepted step's ratio (at least 1e−4, as DOPRI5's
// facold). These are Hairer–Wanner's values; with k = order of the pair they are
// also OrdinaryDiffEq.jl's defaults (7/(10p), 2/(5p)), so both peers step alike.
// A rejected step uses the I law, h · max(0.2, 0.9 · E^(−1/k)), never the memory
// (it belongs to an accepted step), and the step after a rejection may not grow.
//
// Dense output (bs3, dopri5, tsit5: interpolants that cost no extra stage;
// vern6–vern9: Verner's interpolants of the pair's order, whose 3, 6, 8 or 10
// extra stages are evaluated once in a step an output time falls in): the
// solver steps past t_end and interpolates y(t_end), keeping its own state
// ahead. The next advance() resumes from that state only when the caller hands
// back exactly the (t, y) it was given; a caller that changed y (a collision's
// impulse, a time of impact) restarts the solver from its own (t, y). A step
// is only taken past t_end once after_step is known to leave states alone: a
// projected or renormalised state would not lie on the interpolant, so with
// such an after_step (or before the first accepted step tells) these methods
// clip the last step of each interval, as the others do.
//
// Beyond the report, two split (symplectic) methods for a state of positions and
// velocities, where the derivative of position i is velocity velocity_of[i]:
//   symplectic_euler  v += h a(x, v); x += h v  (one evaluation a step)
//   velocity_verlet   x += h v + h²/2 a; v += h/2 (a + a(x', v*)), with the
//                     velocity predictor v* = v + h a for velocity-dependent
//                     forces (exact Verlet when forces depend on position only);
//                     a(x', v*) is reused as the next step's a (one evaluation).
//
// Beyond the report, the Lie-group methods (core/dynamics/lie_group.hpp), for
// a state of rigid bodies only: each body's rotation steps on its group
// (R ← R exp(θ)), so it stays a rotation without renormalising, and its
// centre and momenta with the same stages. The caller supplies the step
// (set_group_step: each backend's group_step through its RotationGroup):
//   rkmk4             Runge–Kutta–Munthe-Kaas on the classical RK4, fixed step
//   crouch_grossman4  Crouch–Grossman, order 4 in 5 stages (Jackiewicz,
//                     Marthinsen & Owren 2000), fixed step
//   rkmk45            RKMK on Dormand–Prince 5(4), the 5th-order solution
//                     kept; the difference from the 4th-order one, in the
//                     stored numbers, is measured by the same error norm and
//                     steps with the pairs' PI controller (k = 5); no dense
//                     output: the last step of each interval is clipped.
#include "core/error.hpp"
#include "core/dynamics/tableaus.hpp"
#include "core/model/scene.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <sstream>
#include <vector>

namespace gacompare::core {

struct SolverStats {
  std::uint64_t steps_accepted = 0;
  std::uint64_t steps_rejected = 0;
  std::uint64_t derivative_evaluations = 0;
  double min_step = std::numeric_limits<double>::infinity();
  double max_step = 0;
};

bool is_adaptive(SolverMethod m);

class OdeSolver {
 public:
  // velocity_of[i]: for a position component i the index of its velocity, −1 for
  // a velocity component; needed only by the split methods.
  OdeSolver(const SolverSpec& spec, std::size_t n, std::vector<int> velocity_of = {});

  // f(double t, std::span<const double> y, std::span<double> dydt).
  // after_step(std::vector<double>& y) -> bool runs after every accepted step and
  // says whether it changed y (constraint projection does).
  // Advances y from t to t_end, leaving t == t_end. Throws run_error when an
  // adaptive step shrinks below what double precision can resolve.
  template <class F, class G>
  void advance(F&& f, double& t, double t_end, std::vector<double>& y, Profile& profile, G&& after_step);
  template <class F>
  void advance(F&& f, double& t, double t_end, std::vector<double>& y, Profile& profile) {
    advance(f, t, t_end, y, profile, [](std::vector<double>&) { return false; });
  }

  const SolverStats& stats() const { return stats_; }

  // The error ratio of a step (≤ 1: accept) when the spec asks for the
  // physical norm: norm(y, y_new, err) with the tolerances applied by the
  // caller, which knows what the numbers are (core/dynamics/simulation.hpp). Without it,
  // or with error_norm "component", every component against its tolerance.
  using ErrorNormFn = std::function<double(std::span<const double>, std::span<const double>, std::span<const double>)>;
  void set_error_norm(ErrorNormFn norm) { norm_ = std::move(norm); }

  // Every loop makes progress or stops: at most `steps` steps
  // (accepted and rejected) in this solver's life, else run_error naming the
  // time and, through `who` (component index -> "body 'cube'"), what holds the
  // largest error of the last step. The scene's limits.max_steps by default.
  using DescribeFn = std::function<std::string(std::size_t)>;
  // At most 2^53: every count below it is exact in a double and converts to an integer.
  void set_step_budget(double steps) { budget_ = std::min(steps, 0x1p53); }
  void set_describe(DescribeFn who) { who_ = std::move(who); }

  // The Lie-group methods' step: (method, t, h, y, out, err) writes the state
  // after a step of h from (t, y) into out and, for rkmk45, the 5th-order
  // state less the embedded 4th-order one into err. Without it those methods
  // refuse to run.
  using GroupStepFn = std::function<void(SolverMethod, double, double, std::span<const double>, std::span<double>,
                                         std::span<double>)>;
  void set_group_step(GroupStepFn step) { group_step_ = std::move(step); }
  SolverMethod method() const { return spec_.method; }
  const SolverSpec& spec() const { return spec_; }
  // For a fixed-step method whose steps other solvers of the same spec take
  // on parts of the state (the world's bodies integrated in blocks,
  // core/dynamics/simulation.hpp): the budget check this solver's own
  // advance from t to t_end would make (it stops the run the same way), and
  // then the steps one of those solvers took, from its stats before and after.
  void check_fixed_budget(double t, double t_end, const std::vector<double>& y) const { fixed_steps(t, t_end, y); }
  void add_steps(const SolverStats& before, const SolverStats& after);

 private:
  template <class F> void eval(F& f, double t, std::span<const double> y, std::span<double> dy);
  template <class F> void rk4_step(F& f, double t, double h, const std::vector<double>& y, std::vector<double>& out);
  template <class F> void split_step(F& f, double t, double h, std::vector<double>& y);
  template <class F> double cash_karp_step(F& f, double t, double h, const std::vector<double>& y);
  template <class F> double pair_step(F& f, double t, double h, const std::vector<double>& y);
  template <class F> void pair_stage(F& f, std::size_t i, double t, double h, const std::vector<double>& y);
  template <class F> void extend(F& f);
  template <class F, class G> void advance_pair(F& f, double& t, double t_end, std::vector<double>& y, G& after_step);
  template <class G> void advance_group(double& t, double t_end, std::vector<double>& y, G& after_step);
  void group_step(double t, double h, const std::vector<double>& y);
  void interpolate(double t, std::vector<double>& y);
  void control(double ratio, double h, bool clipped);
  double error_ratio(const std::vector<double>& y, const std::vector<double>& ynew,
                     const std::vector<double>& err) const;
  void record(double h);
  // The equal steps, no longer than dt, a fixed-step method takes from t to
  // t_end, counted against the budget before they are taken.
  double fixed_steps(double t, double t_end, const std::vector<double>& y) const;
  // An adaptive method's next try: stops once the budget is spent.
  void check_budget(double t) const;
  [[noreturn]] void stop(const std::string& why, double t, double h, const std::vector<double>& y) const;
  std::string worst(const std::vector<double>& y) const;

  SolverSpec spec_;
  ErrorNormFn norm_;
  DescribeFn who_;
  GroupStepFn group_step_;
  double budget_ = 1e8;
  double h_;  // adaptive: the step to try next
  std::size_t n_;  // the state's size
  SolverStats stats_;
  std::vector<int> velocity_of_;
  bool have_acc_ = false;  // velocity_verlet: k5_ holds a(x, v) of the current state
  // The steps' work vectors, sized on the first advance (size_work): a
  // solver that only keeps the budget and counts the steps of others (an
  // island integrated in blocks, BodyBlocks) never allocates them, where a
  // pile's island would zero ten of its state's size at every step alone.
  std::vector<double> k1_, k2_, k3_, k4_, k5_, k6_, tmp_, out_, half_, err_;
  void size_work();

  // The embedded pairs: their tableau, b − bhat, the stages of the last step
  // (stage i at [i·n, (i+1)·n)), its start (ys_ at t0_, step hlast_) and the
  // solver's own state (yi_ at ti_), which is ahead of the caller's when ahead_.
  // given_ at t_given_: what the caller was handed, to tell whether it changed y.
  enum class Changes { unknown, never, yes };  // what after_step has done to states
  const ButcherTableau* tab_ = nullptr;
  double control_k_ = 0;  // the PI controller's k: the embedded order + 1 (the pairs and rkmk45)
  bool fsal_ = false;  // tab_->fsal(), once
  std::vector<double> e_, K_, weights_, ys_, yi_, given_;
  double t0_ = 0, hlast_ = 0, ti_ = 0, t_given_ = NAN;
  double log_err_prev_ = std::log(1e-4);  // the PI controller's memory: log of the last accepted step's ratio
  bool rejected_last_ = false;
  bool ahead_ = false;
  bool extended_ = false;  // K_ holds the last step's extra stages (extend)
  std::ptrdiff_t f_at_ = -1;  // the stage of K_ that holds f(ti_, yi_); −1: none
  Changes after_changes_ = Changes::unknown;
};

// Gives `solver` the Lie-group step of `model` when its method is one (else
// nothing): B::group_step(model, method, t, h, y, out, err, extra...), with B
// a simulator Backend for the world's state (core/dynamics/simulator.hpp
// solver_for) or a backend's RigidBodies for the bodies an island or a
// time-of-impact trial integrates alone (core/collision/subsystem.hpp). The
// one wiring of both, so that those bodies step on their group exactly as
// the world's do. `extra` (the world's mask of sleeping bodies) is copied
// into the step; `model` must outlive the solver.
template <class B, class... Extra>
void set_group_step_of(OdeSolver& solver, const typename B::Model& model, Extra... extra) {
  if (!is_lie_group(solver.method())) return;
  solver.set_group_step([&model, extra...](SolverMethod method, double t, double h, std::span<const double> y,
                                           std::span<double> out, std::span<double> err) {
    B::group_step(model, method, t, h, y, out, err, extra...);
  });
}

// ---------------------------------------------------------------------------------

template <class F>
void OdeSolver::eval(F& f, double t, std::span<const double> y, std::span<double> dy) {
  ++stats_.derivative_evaluations;
  f(t, y, dy);
}

template <class F>
void OdeSolver::rk4_step(F& f, double t, double h, const std::vector<double>& y, std::vector<double>& out) {
  const std::size_t n = y.size();
  eval(f, t, y, k1_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + 0.5 * h * k1_[i];
  eval(f, t + 0.5 * h, tmp_, k2_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + 0.5 * h * k2_[i];
  eval(f, t + 0.5 * h, tmp_, k3_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + h * k3_[i];
  eval(f, t + h, tmp_, k4_);
  for (std::size_t i = 0; i < n; ++i) out[i] = y[i] + h / 6.0 * (k1_[i] + 2.0 * (k2_[i] + k3_[i]) + k4_[i]);
}

// One Cash–Karp step: the 5th-order result into out_, the error estimate into err_.
template <class F>
double OdeSolver::cash_karp_step(F& f, double t, double h, const std::vector<double>& y) {
  // Table 4 of the report (Cash & Karp 1990).
  constexpr double a2 = 0.2, a3 = 0.3, a4 = 0.6, a5 = 1.0, a6 = 0.875;
  constexpr double b21 = 0.2, b31 = 3.0 / 40, b32 = 9.0 / 40, b41 = 0.3, b42 = -0.9, b43 = 1.2;
  constexpr double b51 = -11.0 / 54, b52 = 2.5, b53 = -70.0 / 27, b54 = 35.0 / 27;
  constexpr double b61 = 1631.0 / 55296, b62 = 175.0 / 512, b63 = 575.0 / 13824, b64 = 44275.0 / 110592,
                   b65 = 253.0 / 4096;
  constexpr double c1 = 37.0 / 378, c3 = 250.0 / 621, c4 = 125.0 / 594, c6 = 512.0 / 1771;
  constexpr double d1 = c1 - 2825.0 / 27648, d3 = c3 - 18575.0 / 48384, d4 = c4 - 13525.0 / 55296,
                   d5 = -277.0 / 14336, d6 = c6 - 0.25;
  const std::size_t n = y.size();
  eval(f, t, y, k1_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + h * b21 * k1_[i];
  eval(f, t + a2 * h, tmp_, k2_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + h * (b31 * k1_[i] + b32 * k2_[i]);
  eval(f, t + a3 * h, tmp_, k3_);
  for (std::size_t i = 0; i < n; ++i) tmp_[i] = y[i] + h * (b41 * k1_[i] + b42 * k2_[i] + b43 * k3_[i]);
  eval(f, t + a4 * h, tmp_, k4_);
  for (std::size_t i = 0; i < n; ++i)
    tmp_[i] = y[i] + h * (b51 * k1_[i] + b52 * k2_[i] + b53 * k3_[i] + b54 * k4_[i]);
  eval(f, t + a5 * h, tmp_, k5_);
  for (std::size_t i = 0; i < n; ++i)
    tmp_[i] = y[i] + h * (b61 * k1_[i] + b62 * k2_[i] + b63 * k3_[i] + b64 * k4_[i] + b65 * k5_[i]);
  eval(f, t + a6 * h, tmp_, k6_);
  for (std::size_t i = 0; i < n; ++i) {
    out_[i] = y[i] + h * (c1 * k1_[i] + c3 * k3_[i] + c4 * k4_[i] + c6 * k6_[i]);
    err_[i] = h * (d1 * k1_[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i]);
  }
  return error_ratio(y, out_, err_);
}

// Stage i of the pair's step from (t, y) by h into K_: f at y + h(c_i k_1 +
// Σ_{j<i} a_ij (k_j − k_1)), its argument left in tmp_ (see pair_step for why
// differences from k_1).
template <class F>
void OdeSolver::pair_stage(F& f, std::size_t i, double t, double h, const std::vector<double>& y) {
  const ButcherTableau& T = *tab_;
  const std::size_t n = y.size();
  const double* a = T.a + i * (i - 1) / 2;
  for (std::size_t m = 0; m < n; ++m) {
    const double k1 = K_[m];
    double acc = T.c[i] * k1;
    for (std::size_t j = 1; j < i; ++j) acc += a[j] * (K_[j * n + m] - k1);
    tmp_[m] = y[m] + h * acc;
  }
  eval(f, t + T.c[i] * h, tmp_, std::span<double>(K_).subspan(i * n, n));
}

// The interpolant's extra stages (Verner's pairs) for the last accepted step,
// [t0_, t0_ + hlast_] from ys_: evaluated once in a step an output time falls in.
template <class F>
void OdeSolver::extend(F& f) {
  if (extended_) return;
  for (auto i = static_cast<std::size_t>(tab_->stages); i < static_cast<std::size_t>(tab_->dense_stages); ++i)
    pair_stage(f, i, t0_, hlast_, ys_);
  extended_ = true;
}

// One step of the embedded pair: the kept solution into out_, h·Σ(b − bhat)k into
// err_; stages into K_. An FSAL pair starts from the last stage of the step before.
// Stages are y + h(c_i k_1 + Σ_j a_ij (k_j − k_1)) and the solution y + h(k_1 +
// Σ_j b_j (k_j − k_1)): the same numbers in exact arithmetic (rows sum to c_i, Σb
// = 1), but Verner's coefficients reach |a_ij| ~ 200, and their doubles miss
// c_i by 2e-14 and Σ b_i c_i = 1/2 by 7e-12 (vern6): an O(h) global error of
// 5e-11 on a Kepler orbit. With differences the rounded coefficients only
// multiply O(h) quantities.
template <class F>
double OdeSolver::pair_step(F& f, double t, double h, const std::vector<double>& y) {
  const ButcherTableau& T = *tab_;
  const std::size_t n = y.size(), s = static_cast<std::size_t>(T.stages);
  const auto stage = [&](std::size_t i) { return std::span<double>(K_).subspan(i * n, n); };
  if (f_at_ < 0) eval(f, t, y, stage(0));
  else if (f_at_ > 0) std::copy_n(K_.begin() + f_at_ * static_cast<std::ptrdiff_t>(n), n, K_.begin());
  extended_ = false;
  for (std::size_t i = 1; i < s; ++i) pair_stage(f, i, t, h, y);
  for (std::size_t m = 0; m < n; ++m) {
    const double k1 = K_[m];
    double acc = k1, err = 0;
    for (std::size_t j = 1; j < s; ++j) {
      const double d = K_[j * n + m] - k1;
      acc += T.b[j] * d;
      err += e_[j] * d;  // Σ e_j = 0
    }
    out_[m] = y[m] + h * acc;
    err_[m] = h * err;
  }
  // FSAL: the new solution is the last stage's argument, to the bit, so that the
  // stage reused next is f of exactly the state kept.
  if (fsal_) out_ = tmp_;
  return error_ratio(y, out_, err_);
}

template <class F>
void OdeSolver::split_step(F& f, double t, double h, std::vector<double>& y) {
  const std::size_t n = y.size();
  if (spec_.method == SolverMethod::symplectic_euler) {
    eval(f, t, y, k1_);
    for (std::size_t i = 0; i < n; ++i)
      if (velocity_of_[i] < 0) y[i] += h * k1_[i];
    for (std::size_t i = 0; i < n; ++i)
      if (velocity_of_[i] >= 0) y[i] += h * y[static_cast<std::size_t>(velocity_of_[i])];
    return;
  }
  std::vector<double>& acc = k5_;  // velocity components of dy/dt: the accelerations
  if (!have_acc_) eval(f, t, y, acc);
  for (std::size_t i = 0; i < n; ++i)
    if (velocity_of_[i] >= 0) {
      const auto v = static_cast<std::size_t>(velocity_of_[i]);
      y[i] += h * y[v] + 0.5 * h * h * acc[v];
    }
  for (std::size_t i = 0; i < n; ++i)
    if (velocity_of_[i] < 0) {
      tmp_[i] = y[i];
      y[i] += h * acc[i];  // the predictor v*
    }
  eval(f, t + h, y, k1_);
  for (std::size_t i = 0; i < n; ++i)
    if (velocity_of_[i] < 0) y[i] = tmp_[i] + 0.5 * h * (acc[i] + k1_[i]);
  acc.swap(k1_);
  have_acc_ = true;
}

template <class F, class G>
void OdeSolver::advance(F&& f, double& t, double t_end, std::vector<double>& y, Profile& profile, G&& after_step) {
  const double span = t_end - t;
  if (!(span > 0)) return;
  const std::size_t n = y.size();
  size_work();
  // One timed scope per advance (per output interval), not per step: two clock
  // reads a step are a measurable share of a cheap derivative's run, an
  // overhead no peer pays.
  ScopedStage timed(profile, Stage::integrate);
  if (tab_) return advance_pair(f, t, t_end, y, after_step);
  if (is_lie_group(spec_.method)) return advance_group(t, t_end, y, after_step);

  if (!is_adaptive(spec_.method)) {
    const double steps = fixed_steps(t, t_end, y);
    const double h = span / steps;
    const double t0 = t;
    for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(steps); ++k) {
      const double tk = t0 + static_cast<double>(k) * h;
      if (spec_.method == SolverMethod::euler) {
        eval(f, tk, y, k1_);
        for (std::size_t i = 0; i < n; ++i) y[i] += h * k1_[i];
      } else if (spec_.method == SolverMethod::rk4) {
        rk4_step(f, tk, h, y, out_);
        y.swap(out_);
      } else {
        split_step(f, tk, h, y);
      }
      record(h);
      if (after_step(y)) have_acc_ = false;
    }
    t = t_end;
    return;
  }

  // Both adaptive methods estimate the error of a 4th-order step: it scales as h^5.
  constexpr double order = 4.0;
  while (t < t_end) {
    check_budget(t);
    const bool last = t + h_ >= t_end;
    const double h = last ? t_end - t : h_;
    double ratio;
    if (spec_.method == SolverMethod::cash_karp45) {
      ratio = cash_karp_step(f, t, h, y);
    } else {  // rk4_doubling
      std::vector<double>& full = k6_;  // rk4_step does not use k6_
      rk4_step(f, t, h, y, full);
      rk4_step(f, t, 0.5 * h, y, half_);
      rk4_step(f, t + 0.5 * h, 0.5 * h, half_, out_);
      for (std::size_t i = 0; i < n; ++i) err_[i] = (out_[i] - full[i]) / 15.0;
      ratio = error_ratio(y, out_, err_);
    }
    if (ratio <= 1.0) {
      y.swap(out_);
      t = last ? t_end : t + h;
      record(h);
      after_step(y);
      // Grow (at most 5×) from the step just taken; a clipped last step does not
      // shrink the next interval's first try.
      const double grow = ratio == 0 ? 5.0 : std::min(5.0, 0.9 * std::pow(ratio, -1.0 / (order + 1)));
      h_ = last ? std::max(h_, h * grow) : h * grow;
    } else {
      ++stats_.steps_rejected;
      const double shrink = std::isfinite(ratio) ? std::max(0.2, 0.9 * std::pow(ratio, -1.0 / order)) : 0.2;
      h_ = h * shrink;
      if (!(h_ > 64 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t)))) {
        std::ostringstream why;
        why << "step size underflow (error ratio " << ratio
            << "): the tolerance cannot be met or the derivative is not finite";
        stop(why.str(), t, h_, err_);
      }
    }
  }
}

template <class F, class G>
void OdeSolver::advance_pair(F& f, double& t, double t_end, std::vector<double>& y, G& after_step) {
  // Resume from the solver's own state only if the caller kept what it was handed.
  if (!(t == t_given_ && y == given_)) {
    yi_ = y;
    ti_ = t;
    ahead_ = false;
    f_at_ = -1;
  }
  while (true) {
    if (ahead_ && t_end < ti_) {
      extend(f);
      interpolate(t_end, y);
      break;
    }
    if (ti_ >= t_end) {  // landed on t_end exactly
      y = yi_;
      ahead_ = false;
      break;
    }
    check_budget(ti_);
    const bool clip = tab_->dense_degree == 0 || after_changes_ != Changes::never;
    const bool last = ti_ + h_ >= t_end;
    const double h = last && clip ? t_end - ti_ : h_;
    const double ratio = pair_step(f, ti_, h, yi_);
    if (!(ratio <= 1.0)) {
      f_at_ = 0;  // the trial's first stage is still f(ti_, yi_)
      control(ratio, h, false);
      continue;
    }
    t0_ = ti_;
    hlast_ = h;
    ys_.swap(yi_);
    yi_.swap(out_);
    ti_ = last && clip ? t_end : ti_ + h;
    record(h);
    f_at_ = fsal_ ? tab_->stages - 1 : -1;
    const bool changed = after_step(yi_);
    if (changed) after_changes_ = Changes::yes, f_at_ = -1;
    else if (after_changes_ == Changes::unknown) after_changes_ = Changes::never;
    ahead_ = ti_ > t_end;
    if (ahead_ && changed) {
      // A changed state is off the interpolant: take this step again, clipped,
      // from its start (from now on every step is clipped).
      yi_.swap(ys_);
      ti_ = t0_;
      ahead_ = false;
      --stats_.steps_accepted;
      ++stats_.steps_rejected;
      continue;
    }
    control(ratio, h, last && clip);
  }
  t = t_end;
  given_ = y;
  t_given_ = t_end;
}

template <class G>
void OdeSolver::advance_group(double& t, double t_end, std::vector<double>& y, G& after_step) {
  if (spec_.method != SolverMethod::rkmk45) {
    const double steps = fixed_steps(t, t_end, y);
    const double h = (t_end - t) / steps;
    const double t0 = t;
    for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(steps); ++k) {
      group_step(t0 + static_cast<double>(k) * h, h, y);
      y.swap(out_);
      record(h);
      after_step(y);
    }
    t = t_end;
    return;
  }
  // rkmk45: the pairs' PI control (control()), every interval's last step clipped.
  while (t < t_end) {
    check_budget(t);
    const bool last = t + h_ >= t_end;
    const double h = last ? t_end - t : h_;
    ti_ = t;
    group_step(t, h, y);
    const double ratio = error_ratio(y, out_, err_);
    if (!(ratio <= 1.0)) {
      control(ratio, h, false);
      continue;
    }
    y.swap(out_);
    t = last ? t_end : t + h;
    record(h);
    after_step(y);
    control(ratio, h, last);
  }
}

}  // namespace gacompare::core
