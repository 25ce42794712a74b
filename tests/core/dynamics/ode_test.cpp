// The solvers of Appendix B against closed-form solutions: y' = −y and the
// harmonic oscillator. Convergence orders are checked by halving the step, the
// adaptive methods by the global error their tolerance promises.
#include "core/dynamics/ode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gacompare::core {
namespace {

SolverSpec spec(SolverMethod m, double dt, double tol = 1e-9) { return {m, dt, tol, tol}; }

// y' = −y, y(0) = 1, integrated to t = 1: error against e^−1.
double decay_error(SolverMethod m, double dt) {
  OdeSolver s(spec(m, dt), 1);
  std::vector<double> y{1.0};
  double t = 0;
  Profile p;
  s.advance([](double, std::span<const double> yy, std::span<double> dy) { dy[0] = -yy[0]; }, t, 1.0, y, p);
  EXPECT_EQ(t, 1.0);
  return std::abs(y[0] - std::exp(-1.0));
}

TEST(Ode, EulerIsFirstOrder) {
  // Halving h halves the error of a first-order method: ratio 2 up to O(h) terms.
  const double r = decay_error(SolverMethod::euler, 1e-3) / decay_error(SolverMethod::euler, 5e-4);
  EXPECT_NEAR(r, 2.0, 0.01);
}

TEST(Ode, Rk4IsFourthOrder) {
  // Ratio 2⁴ = 16 up to O(h) terms; h = 0.02 keeps the error far above rounding.
  const double r = decay_error(SolverMethod::rk4, 0.02) / decay_error(SolverMethod::rk4, 0.01);
  EXPECT_NEAR(r, 16.0, 0.5);
}

// x'' = −x from (1, 0) over one period 2π. Each accepted step's error is at most
// abs_tol + rel_tol·|y| ≤ 2·tol (|y| ≤ 1), and the oscillator neither damps nor
// amplifies errors, so the global error stays below 2·tol·steps.
void oscillator(SolverMethod m, double tol, double& error, SolverStats& stats) {
  OdeSolver s(spec(m, 0.1, tol), 2);
  std::vector<double> y{1.0, 0.0};
  double t = 0;
  Profile p;
  const double T = 2 * std::numbers::pi;
  s.advance([](double, std::span<const double> yy, std::span<double> dy) { dy[0] = yy[1]; dy[1] = -yy[0]; }, t, T, y, p);
  error = std::hypot(y[0] - 1.0, y[1]);
  stats = s.stats();
  EXPECT_EQ(t, T);
  EXPECT_EQ(p[Stage::integrate].calls, 1u);  // one timed scope per advance()
}

TEST(Ode, CashKarpMeetsItsTolerance) {
  for (double tol : {1e-6, 1e-9, 1e-12}) {
    double err;
    SolverStats st;
    oscillator(SolverMethod::cash_karp45, tol, err, st);
    EXPECT_LT(err, 2 * tol * static_cast<double>(st.steps_accepted)) << "tol " << tol;
    EXPECT_EQ(st.derivative_evaluations, 6 * (st.steps_accepted + st.steps_rejected));
  }
}

TEST(Ode, Rk4DoublingMeetsItsTolerance) {
  for (double tol : {1e-6, 1e-9}) {
    double err;
    SolverStats st;
    oscillator(SolverMethod::rk4_doubling, tol, err, st);
    EXPECT_LT(err, 2 * tol * static_cast<double>(st.steps_accepted)) << "tol " << tol;
    EXPECT_EQ(st.derivative_evaluations, 12 * (st.steps_accepted + st.steps_rejected));
  }
}

TEST(Ode, TighterToleranceCostsMoreSteps) {
  double e1, e2;
  SolverStats s1, s2;
  oscillator(SolverMethod::cash_karp45, 1e-6, e1, s1);
  oscillator(SolverMethod::cash_karp45, 1e-11, e2, s2);
  EXPECT_GT(s2.steps_accepted, 5 * s1.steps_accepted);  // h ∝ tol^(1/5): 10^(5/5) = 10×
  EXPECT_LT(e2, e1);
}

TEST(Ode, FixedStepsSplitTheIntervalEvenly) {
  // 0.25 s with dt = 0.1 takes 3 equal steps of 1/12 s, never a sliver.
  OdeSolver s(spec(SolverMethod::rk4, 0.1), 1);
  std::vector<double> y{0.0};
  double t = 0;
  Profile p;
  s.advance([](double, std::span<const double>, std::span<double> dy) { dy[0] = 1; }, t, 0.25, y, p);
  EXPECT_EQ(s.stats().steps_accepted, 3u);
  EXPECT_DOUBLE_EQ(s.stats().min_step, 0.25 / 3);
  EXPECT_DOUBLE_EQ(y[0], 0.25);
}

TEST(Ode, NonFiniteDerivativeIsAnErrorNotAHang) {
  OdeSolver s(spec(SolverMethod::cash_karp45, 0.1), 1);
  std::vector<double> y{1.0};
  double t = 0;
  Profile p;
  auto f = [](double tt, std::span<const double>, std::span<double> dy) { dy[0] = tt > 0.5 ? NAN : 1.0; };
  try {
    s.advance(f, t, 1.0, y, p);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::run);
    EXPECT_NE(std::string(e.what()).find("step size underflow"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gacompare::core

namespace gacompare::core {
namespace {

// x'' = −x as a split state [x, v] (velocity_of = {1, −1}) from (1, 0). Returns
// the error at t_end; optionally the worst energy error over the whole run and
// over its first tenth, sampled 20 times a period.
double split_oscillator_error(SolverMethod m, double dt, double t_end, double* max_energy_error = nullptr,
                              double* early_energy_error = nullptr) {
  OdeSolver s({m, dt, 1e-9, 1e-9}, 2, {1, -1});
  std::vector<double> y{1.0, 0.0};
  double t = 0;
  Profile p;
  auto f = [](double, std::span<const double> yy, std::span<double> dy) { dy[0] = yy[1]; dy[1] = -yy[0]; };
  const double every = 2 * std::numbers::pi / 20;
  const int samples = static_cast<int>(std::ceil(t_end / every));
  double worst = 0, early = 0;
  for (int k = 1; k <= samples; ++k) {
    s.advance(f, t, std::min(t_end, k * every), y, p);
    const double e = std::abs(0.5 * (y[0] * y[0] + y[1] * y[1]) - 0.5);
    worst = std::max(worst, e);
    if (k <= samples / 10) early = std::max(early, e);
  }
  if (max_energy_error) *max_energy_error = worst;
  if (early_energy_error) *early_energy_error = early;
  return std::hypot(y[0] - std::cos(t_end), y[1] + std::sin(t_end));
}

// Measured at t = 1, not after whole periods: over a whole period symplectic
// Euler's first-order errors cancel (it is conjugate to a second-order method).
TEST(Ode, SymplecticEulerIsFirstOrder) {
  const double r = split_oscillator_error(SolverMethod::symplectic_euler, 2e-3, 1.0) /
                   split_oscillator_error(SolverMethod::symplectic_euler, 1e-3, 1.0);
  EXPECT_NEAR(r, 2.0, 0.05);
}

TEST(Ode, VelocityVerletIsSecondOrder) {
  const double r = split_oscillator_error(SolverMethod::velocity_verlet, 2e-2, 1.0) /
                   split_oscillator_error(SolverMethod::velocity_verlet, 1e-2, 1.0);
  EXPECT_NEAR(r, 4.0, 0.05);
}

// The point of a symplectic method: over 1000 periods its energy error stays
// bounded (it oscillates within the first periods' band, it does not grow), where
// RK4 loses energy step after step. "Bounded": the worst error over all 1000
// periods is within 5% of the worst over the first 100. RK4 at h = 0.2 loses
// ~h⁶/72 of the energy a step, so its worst grows ~10× from the first 100 periods.
TEST(Ode, SymplecticMethodsKeepEnergyBoundedOverLongRuns) {
  const double t_end = 1000 * 2 * std::numbers::pi;
  for (auto m : {SolverMethod::symplectic_euler, SolverMethod::velocity_verlet}) {
    double all, early;
    split_oscillator_error(m, 0.05, t_end, &all, &early);
    EXPECT_LE(all, 1.05 * early) << to_string(m);
  }
  double all, early;
  split_oscillator_error(SolverMethod::rk4, 0.2, t_end, &all, &early);
  EXPECT_GT(all, 5 * early);
}

TEST(Ode, SplitMethodsNeedAPositionVelocityLayout) {
  EXPECT_THROW(OdeSolver({SolverMethod::velocity_verlet, 0.1, 1e-9, 1e-9}, 2), Error);
}

}  // namespace
}  // namespace gacompare::core
