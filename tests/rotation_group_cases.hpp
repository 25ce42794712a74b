#pragma once
// The Lie-group integrators (core/dynamics/lie_group.hpp) through one rotation
// representation: the group operations against Eigen's angle–axis rotation,
// each method's convergence order against an independent reference, the
// normalisation that stays at rounding without renormalising, and the
// splitting's invariants. Instantiated per representation by
// tests/{traditional,cga,pga}/rotation_group_test.cpp; `G` is the group.
#include "core/dynamics/lie_group.hpp"
#include "lie_group_reference.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace gacompare::testing {

template <class G>
class RotationGroupCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(RotationGroupCases);

// exp against Eigen's angle–axis matrix, from 1e-9 rad (the series branch) to
// 3 rad; compose, rotate and inverse_rotate against the matrices. Entries are
// O(1): 1e-14 is a few roundings.
TYPED_TEST_P(RotationGroupCases, GroupOperationsMatchTheRotationMatrices) {
  using G = TypeParam;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized(), v(0.7, -1.1, 2.3);
  for (const double angle : {1e-9, 1e-5, 0.3, 1.7, 3.0}) {
    const auto r = G::exp(angle * axis);
    const Eigen::Matrix3d m = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    EXPECT_LT((G::matrix(r) - m).norm(), 1e-14) << angle;
    EXPECT_LT((G::rotate(r, v) - m * v).norm(), 1e-14) << angle;
    EXPECT_LT((G::inverse_rotate(r, v) - m.transpose() * v).norm(), 1e-14) << angle;
    const auto s = G::exp(Eigen::Vector3d(-0.4, 0.2, 1.2));
    EXPECT_LT((G::matrix(G::compose(r, s)) - m * G::matrix(s)).norm(), 1e-14) << angle;
    EXPECT_LT(G::drift(r), 1e-15) << angle;
  }
}

// rate(R, ω) is d/dε of R exp(ε ω) in the stored numbers: a central difference
// with ε = 1e-5, whose truncation (ε² ≈ 1e-10) and rounding (1e-16/ε ≈ 1e-11)
// stay below 1e-9.
TYPED_TEST_P(RotationGroupCases, RateIsTheDerivativeOfTheBodyFrameTurn) {
  using G = TypeParam;
  const auto r = G::exp(Eigen::Vector3d(0.9, -0.3, 0.4));
  const Eigen::Vector3d w(1.3, 0.2, -2.1);
  const double eps = 1e-5;
  const typename G::Coordinates fd =
      (G::coordinates(G::compose(r, G::exp(eps * w))) - G::coordinates(G::compose(r, G::exp(-eps * w)))) / (2 * eps);
  EXPECT_LT((fd - G::rate(r, w)).norm(), 1e-9);
}

// Each method's order from its global error at T = 1 s (about half a turn)
// with n, 2n and 4n steps, torque-free and with the torque that reads R and L:
// the slope of the finer halving, log2(e(2n)/e(4n)), within ±0.3 of the order.
// The finest error stays above 1e-10 (100× the reference's). (At T = 2 s the
// fifth-order endpoint error passes near a cancellation between its parts, and
// plain Dormand–Prince on Π alone gives slopes 4.6–4.9 there.)
TYPED_TEST_P(RotationGroupCases, EachMethodConvergesAtItsOrder) {
  using G = TypeParam;
  const double T = 1.0;
  for (const bool torqued : {false, true}) {
    const auto body = asymmetric_top(torqued);
    const Reference ref = reference(body, T);
    for (const auto m : core::lie::kGroupMethods) {
      if (torqued && m == core::lie::GroupMethod::splitting) continue;  // torque-free only
      const long n = m == core::lie::GroupMethod::splitting ? 100 : 20;
      const double e1 = global_error<G>(m, body, T, n, ref), e2 = global_error<G>(m, body, T, 2 * n, ref),
                   e4 = global_error<G>(m, body, T, 4 * n, ref);
      const double slope = std::log2(e2 / e4);
      std::printf("%s %s%s: errors %.2e %.2e %.2e, slopes %.2f %.2f\n", G::name.data(),
                  core::lie::to_string(m).data(), torqued ? " (torqued)" : "", e1, e2, e4, std::log2(e1 / e2), slope);
      EXPECT_GT(e4, 1e-10) << core::lie::to_string(m);
      EXPECT_GT(e1, e2) << core::lie::to_string(m);
      EXPECT_NEAR(slope, core::lie::order(m), 0.3) << core::lie::to_string(m) << (torqued ? " torqued" : "");
    }
  }
}

// 10⁵ steps of 0.01 s (about 60 turns) without renormalising: the group
// methods keep the stored rotation a rotation to rounding. The bound is 1e-13
// per 10⁵ compositions, growing as their square root (independent roundings
// add in quadrature): 1e-13 for RKMK's one composition a step, 1.7e-13 for
// Crouch–Grossman 3's three, 2.2e-13 for Crouch–Grossman 4's and the
// splitting's five, which the matrix needs (1.4e-13 to 1.6e-13 measured with
// those three) and the motor with the splitting (1.2e-13); the rest measure
// 1e-15 to 9e-14.
// Flat RK4 leaves the group by O(h⁵) a step, which the same bound catches.
TYPED_TEST_P(RotationGroupCases, GroupMethodsStayOnTheGroupWithoutRenormalising) {
  using G = TypeParam;
  const auto body = asymmetric_top(false);
  for (const auto m : core::lie::kGroupMethods) {
    const auto y = core::lie::integrate(m, body, 0.0, 1000.0, 100000, top_state<G>(body));
    std::printf("%s %s: drift after 1e5 steps %.2e\n", G::name.data(), core::lie::to_string(m).data(),
                G::drift(y.rotation));
    if (m == core::lie::GroupMethod::rk4_flat)
      EXPECT_GT(G::drift(y.rotation), 1e-12);
    else
      EXPECT_LE(G::drift(y.rotation), 1e-13 * std::sqrt(core::lie::compositions_per_step(m)))
          << core::lie::to_string(m);
  }
}

// The splitting's every sub-flow is a rotation of Π and the opposite turn of R,
// so |Π| is kept to rounding, 1e-13 relative after 10⁵ steps of 0.01 s, and
// so is the world L = R Π, to 1e-13 per 10⁵ roundings as above: each of the 5
// sub-flows a step rounds both the turn of R and that of Π, √10 · 1e-13
// (1.6e-13 measured with the quaternion, 2.4e-13 with the motor).
TYPED_TEST_P(RotationGroupCases, SplittingKeepsTheAngularMomentumToRounding) {
  using G = TypeParam;
  const auto body = asymmetric_top(false);
  const auto y0 = top_state<G>(body);
  const Eigen::Vector3d l0 = core::lie::world_momentum(y0);
  const auto y = core::lie::integrate(core::lie::GroupMethod::splitting, body, 0.0, 1000.0, 100000, y0);
  EXPECT_LE(std::abs(y.momentum.norm() / y0.momentum.norm() - 1), 1e-13);
  EXPECT_LE((core::lie::world_momentum(y) - l0).norm() / l0.norm(), 1e-13 * std::sqrt(10.0));
}

REGISTER_TYPED_TEST_SUITE_P(RotationGroupCases, GroupOperationsMatchTheRotationMatrices,
                            RateIsTheDerivativeOfTheBodyFrameTurn, EachMethodConvergesAtItsOrder,
                            GroupMethodsStayOnTheGroupWithoutRenormalising, SplittingKeepsTheAngularMomentumToRounding);

}  // namespace gacompare::testing
