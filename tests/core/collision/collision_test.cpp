// How far a body's rotation can move its points (core/collision/collision.hpp
// rotation_change_bound), against the spectral norm computed by an SVD:
// never below it, for rotations within rounding of it, for matrices off a
// rotation (a drifting integrated matrix, a scaled or reflected one) still
// above it. Seeded random cases.
#include "core/collision/collision.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace gacompare::collision {
namespace {

double spectral(const Mat3& m) { return Eigen::JacobiSVD<Mat3>(m).singularValues()(0); }

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// A rotation turned by angle θ about a random axis.
Mat3 turned(const Mat3& r, double theta, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::AngleAxisd(theta, Vec3(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix() * r;
}

// Two rotations: the spectral norm, 2 sin(θ/2), to rounding; the Frobenius
// norm (the bound before) is √2 times it.
TEST(RotationChangeBound, IsTheSpectralNormForRotations) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-3.1, 3.1);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 r0 = random_rotation(rng);
    const double theta = k % 2 ? angle(rng) : std::ldexp(angle(rng), -(k % 40));  // down to 1e-12 rad
    const Mat3 r1 = turned(r0, theta, rng);
    const double exact = 2 * std::abs(std::sin(theta / 2)), bound = rotation_change_bound(r0, r1);
    ASSERT_GE(bound, spectral(r1 - r0) * (1 - 1e-12)) << k;
    // Within the rounding allowance (1 + 1/√2)·(d0 + d1 + 1e-15), d ~ 1e-16 here.
    ASSERT_NEAR(bound, exact, 1e-14 + 1e-12 * exact) << k;
    ASSERT_LT(bound, (r1 - r0).norm() / 1.4 + 1e-14) << k;
  }
}

// Matrices off a rotation by up to 1e-3 (an integrated matrix drifts): the
// bound stays above the true spectral norm, however small the turn.
TEST(RotationChangeBound, StaysABoundOffARotation) {
  std::mt19937_64 rng(12);
  std::normal_distribution<double> g;
  for (int k = 0; k < 4000; ++k) {
    const Mat3 r0 = random_rotation(rng);
    const Mat3 r1 = turned(r0, std::ldexp(1.0, -(k % 50)), rng);
    const double off = std::ldexp(1.0, -10 - k % 40);
    const Mat3 m0 = r0 + off * Mat3::NullaryExpr([&] { return g(rng); });
    const Mat3 m1 = r1 + off * Mat3::NullaryExpr([&] { return g(rng); });
    ASSERT_GE(rotation_change_bound(m0, m1), spectral(m1 - m0)) << k;
    ASSERT_LE(rotation_change_bound(m0, m1), (m1 - m0).norm()) << k;
  }
}

// Far from a rotation (a quaternion left unnormalised, a reflection): the
// Frobenius norm, always a bound.
TEST(RotationChangeBound, FallsBackToTheFrobeniusNormFarFromARotation) {
  std::mt19937_64 rng(13);
  const Mat3 r0 = random_rotation(rng), r1 = turned(r0, 0.3, rng);
  EXPECT_EQ(rotation_change_bound(2 * r0, 2 * r1), (2 * r1 - 2 * r0).norm());
  const Mat3 flip = Vec3(1, 1, -1).asDiagonal();
  EXPECT_EQ(rotation_change_bound(r0 * flip, r1 * flip), (r1 * flip - r0 * flip).norm());
  EXPECT_GE(rotation_change_bound(2 * r0, 2 * r1), spectral(2 * r1 - 2 * r0));
}

}  // namespace
}  // namespace gacompare::collision
