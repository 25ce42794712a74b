// Cl(3,0) rotors against Eigen's quaternions and matrices on seeded random
// rotations. Tolerance 1e-14: rotating a unit vector costs a few roundings.
#include "cga/algebra/cl3.hpp"
#include "testing.hpp"

#include <Eigen/Geometry>
#include <numbers>

namespace gacompare::cga {
namespace {
using testing::uniform;

Eigen::Quaterniond random_quaternion() {
  Eigen::Vector4d q(uniform(), uniform(), uniform(), uniform());
  q.normalize();
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

TEST(Cl3, RotorTimesReverseIsOne) {
  for (int k = 0; k < 1000; ++k) {
    const auto r = rotor_from_quaternion(random_quaternion());
    const auto one = r * ~r;
    ASSERT_NEAR(one.get<0>(), 1.0, 1e-15);
    for (int i = 1; i < 4; ++i) ASSERT_NEAR(one.c[i], 0.0, 1e-15);
  }
}

TEST(Cl3, RotorSandwichMatchesQuaternionAndMatrix) {
  for (int k = 0; k < 1000; ++k) {
    const auto q = random_quaternion();
    const Eigen::Vector3d x(uniform(), uniform(), uniform());
    const auto r = rotor_from_quaternion(q);
    const Eigen::Vector3d expected = q * x;
    const Eigen::Vector3d by_rotor = to_eigen(sandwich(r, vector3(x)));
    const Eigen::Vector3d by_matrix = rotation_matrix(r) * x;
    ASSERT_LT((by_rotor - expected).norm(), 1e-14);
    ASSERT_LT((by_matrix - expected).norm(), 1e-14);
    ASSERT_LT((rotation_matrix(r) - q.toRotationMatrix()).norm(), 1e-14);
  }
}

// A drifted rotor (|R| from 0.5 to 2) still gives an exact rotation: the
// homogeneous matrix over R R̃ equals the sandwich of R/|R|, and its bivector
// twin equals the sandwich of each basis bivector (one pose policy for
// quaternion and rotor; the response's S without three sandwiches).
TEST(Cl3, RotationMatricesOfADriftedRotorMatchTheSandwich) {
  for (int k = 0; k < 1000; ++k) {
    const auto unit = rotor_from_quaternion(random_quaternion());
    const auto r = unit * uniform(0.5, 2.0);
    const Eigen::Matrix3d m = rotation_matrix(r), s = bivector_rotation_matrix(r);
    for (int j = 0; j < 3; ++j) {
      Vector3 e{};
      e.c[static_cast<std::size_t>(j)] = 1;
      const Eigen::Vector3d by_sandwich = to_eigen(sandwich(unit, e));
      ASSERT_LT((m.col(j) - by_sandwich).norm(), 1e-14);
      Bivector3 b{};
      b.c[static_cast<std::size_t>(j)] = 1;
      const Bivector3 turned = sandwich(unit, b);
      ASSERT_LT((s.col(j) - Eigen::Vector3d(turned.c[0], turned.c[1], turned.c[2])).norm(), 1e-14);
    }
    ASSERT_LT((m * m.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
  }
}

TEST(Cl3, RotorProductComposesLikeQuaternions) {
  for (int k = 0; k < 1000; ++k) {
    const auto q1 = random_quaternion(), q2 = random_quaternion();
    const auto r = rotor_from_quaternion(q1) * rotor_from_quaternion(q2);
    const auto q = quaternion_from_rotor(r);
    ASSERT_LT((q.coeffs() - (q1 * q2).coeffs()).norm(), 1e-15);
  }
}

TEST(Cl3, AxisAngleRotatesRightHanded) {
  // §1.2.4: R = exp(−Bθ/2) with B = e12 turns e1 towards e2 about e3.
  const auto r = rotor_from_axis_angle(vector3(0, 0, 1), std::numbers::pi / 2);
  const auto y = sandwich(r, vector3(1, 0, 0));
  // cos(π/2) rounds to 6e-17 and c² − s² to one ulp of 1: allow 2 ulps.
  EXPECT_NEAR(y.c[0], 0, 4.5e-16);
  EXPECT_NEAR(y.c[1], 1, 4.5e-16);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d axis = Eigen::Vector3d(uniform(), uniform(), uniform()).normalized();
    const double angle = uniform(-4, 4);
    const auto q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
    const auto r2 = rotor_from_axis_angle(vector3(axis), angle);
    const auto expected = rotor_from_quaternion(q);
    for (int i = 0; i < 4; ++i) ASSERT_NEAR(r2.c[i], expected.c[i], 1e-15);
  }
}

TEST(Cl3, ExpOfTinyBivectorKeepsPrecision) {
  const auto r = exp(bivector3(1e-9, 0, 0));
  EXPECT_DOUBLE_EQ(r.c[1], 1e-9);
  EXPECT_DOUBLE_EQ(r.c[0], 1.0);
}

TEST(Cl3, OuterProductIsDualOfCrossProduct) {
  // a ∧ b = (a × b) I: the bivector the report uses for ω, L, τ (§1.2.1, §2.3.2).
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d a(uniform(), uniform(), uniform()), b(uniform(), uniform(), uniform());
    const auto w = vector3(a) ^ vector3(b);
    const auto expected = bivector_of_axial(vector3(a.cross(b)));
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(w.c[i], expected.c[i], 1e-15);
    const auto back = to_eigen(axial(w));
    ASSERT_LT((back - a.cross(b)).norm(), 1e-15);
  }
}

// log is exp's inverse: exp(log R) = R on random unit rotors (the shorter of
// R, −R), log(exp B) = B for |B| < π, and R^s = exp(s log R) turns by s of the
// angle, checked against Eigen's slerp from the identity (the quaternion twin
// of the time of impact's interpolation). Tolerance 1e-14: a few roundings of
// numbers ≤ 1 (atan2 and sin/cos are correctly rounded to an ulp or two).
TEST(Cl3, LogInvertsExpAndPowersMatchSlerp) {
  for (int k = 0; k < 1000; ++k) {
    auto r = rotor_from_quaternion(random_quaternion());
    if (r.c[0] < 0) r = r * -1.0;
    const auto back = exp(log(r));
    for (int i = 0; i < 4; ++i) ASSERT_NEAR(back.c[i], r.c[i], 1e-14);
    const auto b = bivector3(uniform(), uniform(), uniform()) * 0.9;  // |B| ≤ 0.9 √3 < π
    const auto lb = log(exp(b));
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(lb.c[i], b.c[i], 1e-14);
    const double s = 0.5 * (uniform() + 1);
    const Eigen::Quaterniond q = Eigen::Quaterniond::Identity().slerp(s, quaternion_from_rotor(r));
    ASSERT_LT((rotation_matrix(exp(log(r) * s)) - q.toRotationMatrix()).norm(), 1e-14);
  }
}

TEST(Cl3, LogNearTheIdentityAndOfMinusOne) {
  const auto small = log(exp(bivector3(0, 3e-10, 0)));
  EXPECT_DOUBLE_EQ(small.c[1], 3e-10);
  const Rotor3 minus_one{{-1, 0, 0, 0}};
  const auto turn = exp(log(minus_one));  // a turn by 2π: −1 again
  EXPECT_NEAR(turn.c[0], -1.0, 1e-15);
}

}  // namespace
}  // namespace gacompare::cga
