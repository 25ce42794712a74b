// core/dynamics/lie_group.hpp across the representations: the same method
// takes the same steps on the matrix, quaternion, rotor and motor; the
// splitting's energy error stays bounded where RKMK's drifts; the adaptive
// RKMK 5(4) against the Dzhanibekov flip's elliptic period and its tolerance;
// the torque hook against a damping whose answer is closed-form. The
// per-representation cases are tests/rotation_group_cases.hpp.
#include "core/dynamics/lie_group.hpp"
#include "cga/rotation_group.hpp"
#include "pga/rotation_group.hpp"
#include "traditional/rotation_group.hpp"
#include "../../lie_group_reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace gacompare::testing {
namespace {

using core::lie::GroupMethod;

struct Endpoint {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d momentum;
};
template <core::lie::RotationGroup G>
Endpoint run(GroupMethod m, const core::lie::FreeBody& body, double T, long n) {
  const auto y = core::lie::integrate(m, body, 0.0, T, n, top_state<G>(body));
  return {G::matrix(y.rotation), y.momentum};
}
double distance(const Endpoint& a, const Endpoint& b) {
  return (a.rotation - b.rotation).norm() + (a.momentum - b.momentum).norm();
}

// The group methods are one method in four algebras: after 1,000 steps of
// 0.01 s (with and without the torque that reads R) the four endpoints differ
// by rounding only, 1e-12, where each is ~1e-7 … 1e-3 from the exact answer.
// Flat RK4 is a different method per representation (it integrates 9, 4, 4 or
// 8 numbers, and the matrix's 9 leave the group differently): its endpoints
// differ by far more than rounding.
TEST(LieGroup, TheFourRepresentationsTakeTheSameSteps) {
  for (const bool torqued : {false, true}) {
    const auto body = asymmetric_top(torqued);
    const Reference ref = reference(body, 10.0);
    const Endpoint exact{ref.rotation, ref.momentum};
    for (const auto m : core::lie::kGroupMethods) {
      if (torqued && m == GroupMethod::splitting) continue;
      const std::vector<Endpoint> ends{run<traditional::MatrixGroup>(m, body, 10.0, 1000),
                                       run<traditional::QuaternionGroup>(m, body, 10.0, 1000),
                                       run<cga::RotorGroup>(m, body, 10.0, 1000), run<pga::MotorGroup>(m, body, 10.0, 1000)};
      double spread = 0;
      for (const auto& e : ends) spread = std::max(spread, distance(e, ends[1]));
      const double error = distance(ends[1], exact);
      std::printf("%s%s: spread between representations %.2e, error %.2e\n", core::lie::to_string(m).data(),
                  torqued ? " (torqued)" : "", spread, error);
      if (m == GroupMethod::rk4_flat) {
        EXPECT_GT(spread, 1e-10);
      } else {
        EXPECT_LT(spread, 1e-12) << core::lie::to_string(m);
      }
    }
  }
}

// The classical order conditions of the tableaus, through the eight trees of
// order ≤ 4 (Hairer, Nørsett & Wanner I, §II.2): Σb = 1, Σbc = 1/2, Σbc² = 1/3,
// Σbac = 1/6, Σbc³ = 1/4, Σbcac = 1/8, Σbac² = 1/12, Σbaac = 1/24, and that
// each cᵢ is its row's sum. Necessary for the Lie-group orders, not sufficient
// (Crouch–Grossman adds conditions of its own, which the convergence slopes
// in tests/rotation_group_cases.hpp check). Sums of a few terms near 1 round
// by a few ε (2.2e-16): the bound is 1e-15, which a coefficient off in its
// 14th digit (Crouch–Grossman 4's misprinted a54) already breaks.
template <int S>
std::vector<double> order_defects(const core::lie::detail::Tableau<S>& t, int order) {
  std::array<double, S> ac{}, ac2{}, aac{};
  for (int i = 0; i < S; ++i)
    for (int j = 0; j < i; ++j) ac[i] += t.a[i][j] * t.c[j], ac2[i] += t.a[i][j] * t.c[j] * t.c[j];
  for (int i = 0; i < S; ++i)
    for (int j = 0; j < i; ++j) aac[i] += t.a[i][j] * ac[j];
  double trees[8] = {};
  double row_sum = 0;
  for (int i = 0; i < S; ++i) {
    const double b = t.b[i], c = t.c[i];
    trees[0] += b, trees[1] += b * c, trees[2] += b * c * c, trees[3] += b * ac[i];
    trees[4] += b * c * c * c, trees[5] += b * c * ac[i], trees[6] += b * ac2[i], trees[7] += b * aac[i];
    double r = -c;
    for (int j = 0; j < i; ++j) r += t.a[i][j];
    row_sum = std::max(row_sum, std::abs(r));
  }
  const double exact[8] = {1, 1.0 / 2, 1.0 / 3, 1.0 / 6, 1.0 / 4, 1.0 / 8, 1.0 / 12, 1.0 / 24};
  std::vector<double> out{row_sum};
  for (int k = 0; k < (order >= 4 ? 8 : order == 3 ? 4 : 2); ++k) out.push_back(trees[k] - exact[k]);
  return out;
}
TEST(LieGroup, TableausMeetTheClassicalOrderConditions) {
  for (const double d : order_defects(core::lie::detail::kRk4, 4)) EXPECT_LT(std::abs(d), 1e-15);
  for (const double d : order_defects(core::lie::detail::kDormandPrince, 4)) EXPECT_LT(std::abs(d), 1e-15);
  for (const double d : order_defects(core::lie::detail::kCrouchGrossman3, 3)) EXPECT_LT(std::abs(d), 1e-15);
  for (const double d : order_defects(core::lie::detail::kCrouchGrossman4, 4)) EXPECT_LT(std::abs(d), 1e-15);
}

// The largest |E − E0| / E0 over the first and the last tenth of a run.
struct EnergyTrend {
  double first = 0, last = 0;
};
template <core::lie::RotationGroup G>
EnergyTrend energy_trend(GroupMethod m, const core::lie::FreeBody& body, double T, long n) {
  const double e0 = core::lie::energy(body, top_momentum(body));
  EnergyTrend trend;
  long k = 0;
  core::lie::integrate(m, body, 0.0, T, n, top_state<G>(body), [&](double, const core::lie::State<G>& y) {
    const double e = std::abs(core::lie::energy(body, y.momentum) / e0 - 1);
    ++k;
    if (10 * k <= n) trend.first = std::max(trend.first, e);
    if (10 * k > 9 * n) trend.last = std::max(trend.last, e);
  });
  return trend;
}

// 10⁵ steps of 0.02 s (some 300 turns): the splitting's energy error
// oscillates with no trend, its largest over the last tenth not twice that over
// the first (a symplectic method's modified energy, Hairer, Lubich & Wanner
// §IX.8). RKMK4, whose Π is classical RK4 on Euler's equations, drifts: its
// last tenth's largest error is many times the first's.
TEST(LieGroup, SplittingEnergyErrorStaysBoundedWhereRkmkDrifts) {
  const auto body = asymmetric_top(false);
  const EnergyTrend split = energy_trend<cga::RotorGroup>(GroupMethod::splitting, body, 2000.0, 100000);
  const EnergyTrend rkmk = energy_trend<cga::RotorGroup>(GroupMethod::rkmk4, body, 2000.0, 100000);
  std::printf("energy error, first and last tenth: splitting %.2e %.2e, rkmk4 %.2e %.2e\n", split.first, split.last,
              rkmk.first, rkmk.last);
  EXPECT_LE(split.last, 2 * split.first);
  EXPECT_GT(rkmk.last, 5 * rkmk.first);
}

// The Dzhanibekov flip of the rigid tests (tests/rigid_cases.hpp: spin 10
// rad/s about the intermediate axis, a 0.01 rad/s nudge), by the adaptive
// RKMK 5(4) at tolerance 1e-11: the time between upward zero crossings of Π₂
// against the period of Euler's free equations (core::lie::free_period, Landau
// & Lifshitz §37). Crossings are located to 1e-7 s by bisecting on Π₂, so a
// period is good to 2e-7 s, 5e-8 of it; the bound is 1e-7 relative (7e-10
// measured).
TEST(LieGroup, AdaptiveRkmkFlipsAtTheEllipticPeriod) {
  const core::lie::FreeBody body{{(0.16 + 0.81) / 12, (0.01 + 0.81) / 12, (0.01 + 0.16) / 12}, {}};
  const Eigen::Vector3d w(0.0, 10.0, 0.01);
  const Eigen::Vector3d pi0 = body.inertia.cwiseProduct(w);
  const double period = core::lie::free_period(body.inertia, pi0);

  using G = cga::RotorGroup;
  core::lie::StepStats stats;
  const auto advance = [&](const core::lie::State<G>& y, double t0, double t1) {
    return core::lie::rkmk45(body, t0, t1, y, 1e-3, 1e-11, 1e-11, stats);
  };
  core::lie::State<G> y{G::identity(), pi0};
  std::vector<double> flips;
  const double dt = 0.01;
  for (double t = 0; t < 3.2 * period; t += dt) {
    const auto next = advance(y, t, t + dt);
    if (y.momentum.y() < 0 && next.momentum.y() >= 0) {
      double a = t, b = t + dt;  // bisect on Π₂ from the state at t
      while (b - a > 1e-7) {
        const double mid = 0.5 * (a + b);
        (advance(y, t, mid).momentum.y() < 0 ? a : b) = mid;
      }
      flips.push_back(0.5 * (a + b));
    }
    y = next;
  }
  ASSERT_GE(flips.size(), 2u) << "period " << period;
  for (std::size_t k = 1; k < flips.size(); ++k) {
    std::printf("flip period %.9f s, elliptic %.9f s\n", flips[k] - flips[k - 1], period);
    EXPECT_NEAR((flips[k] - flips[k - 1]) / period, 1.0, 1e-7);
  }
}

// The step controller keeps the global error in proportion to the tolerance:
// over 10 s of the torqued top, the error against the reference at tolerance
// 1e-6 and 1e-9 falls by 100–10,000× (the controller aims at a local error per
// step, so the global error scales as the tolerance, give or take the step
// count), and stays under 100 × the tolerance (9.4× and 4.9× measured).
TEST(LieGroup, AdaptiveRkmkErrorFollowsItsTolerance) {
  const auto body = asymmetric_top(true);
  const Reference ref = reference(body, 10.0);
  std::vector<double> errors;
  for (const double tol : {1e-6, 1e-9}) {
    using G = traditional::QuaternionGroup;
    core::lie::StepStats stats;
    const auto y = core::lie::rkmk45(body, 0.0, 10.0, top_state<G>(body), 1e-3, tol, tol, stats);
    const double e = distance({G::matrix(y.rotation), y.momentum}, {ref.rotation, ref.momentum});
    std::printf("tolerance %.0e: error %.2e, %llu steps (%llu rejected)\n", tol, e,
                static_cast<unsigned long long>(stats.accepted), static_cast<unsigned long long>(stats.rejected));
    EXPECT_LT(e, 100 * tol);
    errors.push_back(e);
  }
  EXPECT_GT(errors[0] / errors[1], 100.0);
  EXPECT_LT(errors[0] / errors[1], 10000.0);
}

// The torque hook against a closed form: τ = −k L gives L̇ = −k L in the world,
// so L(t) = L0 e^(−kt) whatever the body does. RKMK5 with 200 steps of 0.01 s:
// the world L to 1e-10 relative (its fifth-order error, 1.3e-11 measured).
TEST(LieGroup, DampingTorqueShrinksTheWorldMomentumExponentially) {
  auto body = asymmetric_top(false);
  const double k = 0.7;
  body.torque = [k](double, const Eigen::Matrix3d&, const Eigen::Vector3d& l) { return Eigen::Vector3d(-k * l); };
  using G = pga::MotorGroup;
  const auto y0 = top_state<G>(body);
  const auto y = core::lie::integrate(GroupMethod::rkmk5, body, 0.0, 2.0, 200, y0);
  const Eigen::Vector3d expected = core::lie::world_momentum(y0) * std::exp(-k * 2.0);
  const double e = (core::lie::world_momentum(y) - expected).norm() / expected.norm();
  std::printf("damped L: relative error %.2e\n", e);
  EXPECT_LT(e, 1e-10);
}

}  // namespace
}  // namespace gacompare::testing
