// Our Cash–Karp step against Boost.Odeint's runge_kutta_cash_karp54, a peer no one
// here wrote, on a nonlinear system (Lorenz), step for step: the same tableau must
// give the same numbers up to the order of the floating-point sums (1e-14
// relative on O(10) values after steps of 1e-2).
#include "core/dynamics/ode.hpp"

#include <boost/numeric/odeint.hpp>
#include <gtest/gtest.h>

#include <array>

namespace gacompare::core {
namespace {

using State = std::array<double, 3>;

void lorenz(const State& x, State& dx, double) {
  dx[0] = 10.0 * (x[1] - x[0]);
  dx[1] = x[0] * (28.0 - x[2]) - x[1];
  dx[2] = x[0] * x[1] - 8.0 / 3.0 * x[2];
}

TEST(OdeOdeint, CashKarpStepMatchesBoostOdeintStepForStep) {
  const double h = 1e-2;
  // A tolerance no step can fail: every advance() is one Cash–Karp step of h.
  OdeSolver ours({SolverMethod::cash_karp45, h, 1e300, 0}, 3);
  boost::numeric::odeint::runge_kutta_cash_karp54<State> peer;
  std::vector<double> y{1.0, 1.0, 1.0};
  State x{1.0, 1.0, 1.0}, xerr{};
  double t = 0;
  Profile p;
  auto f = [](double tt, std::span<const double> yy, std::span<double> dy) {
    State in{yy[0], yy[1], yy[2]}, out{};
    lorenz(in, out, tt);
    for (int i = 0; i < 3; ++i) dy[i] = out[i];
  };
  for (int k = 0; k < 200; ++k) {
    const double t0 = t;
    ours.advance(f, t, t0 + h, y, p);
    peer.do_step(lorenz, x, t0, h, xerr);
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(y[i], x[i], 1e-14 * (1 + std::abs(x[i]))) << "step " << k;
    // Re-seed from the peer so differences cannot accumulate (Lorenz amplifies them).
    y.assign(x.begin(), x.end());
  }
  EXPECT_EQ(ours.stats().steps_accepted, 200u);
  EXPECT_EQ(ours.stats().derivative_evaluations, 6u * 200u);
}

}  // namespace
}  // namespace gacompare::core
