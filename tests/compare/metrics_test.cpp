// The measures of compare/metrics.hpp against independent computations: the
// rotation angle against Eigen's angle-axis of the relative rotation (large
// angles) and against rotations built exactly in doubles (tiny ones); the state
// differences and the energy change on hand-made samples, a blow-up among them.
#include "compare/metrics.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace gacompare::compare {
namespace {

Eigen::Vector4d wxyz(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

// Random rotations q and q' = q·r with r a turn by θ about a random axis, θ from
// 1e-3 to π − 1e-3 (log-uniform). Independent reference: Eigen's AngleAxis of
// q⁻¹q' (2 atan2(|vec|, |w|) of the product). Both sides round at ~1e-16 on unit
// quaternions and angles ≤ π, so 1e-13 leaves a margin of some hundred ulps; a
// factor-of-two slip (the angle between the 4-vectors is half the rotation's)
// would miss by θ/2 ≥ 5e-4.
TEST(RotationAngle, AgreesWithEigensAngleAxisOfTheRelativeRotation) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1), e(std::log(1e-3), std::log(M_PI - 1e-3));
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    const double theta = std::exp(e(rng));
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Quaterniond q2 = q * Eigen::Quaterniond(Eigen::AngleAxisd(theta, axis));
    const double eigen = Eigen::AngleAxisd(q.inverse() * q2).angle();
    EXPECT_NEAR(rotation_angle(wxyz(q), wxyz(q2)), eigen, 1e-13) << "theta " << theta;
    EXPECT_NEAR(rotation_angle(wxyz(q), wxyz(q2)), theta, 1e-13);
    // q and −q are one rotation; a norm drift (a sample of an unrenormalised run) is not a turn.
    EXPECT_NEAR(rotation_angle(wxyz(q), -wxyz(q2)), eigen, 1e-13);
    EXPECT_NEAR(rotation_angle(1.7 * wxyz(q), 0.6 * wxyz(q2)), eigen, 1e-13);
  }
  EXPECT_EQ(rotation_angle({1, 0, 0, 0}, {1, 0, 0, 0}), 0.0);
  EXPECT_NEAR(rotation_angle({1, 0, 0, 0}, {0, 1, 0, 0}), M_PI, 1e-15);  // a half turn, the largest there is
}

// Tiny turns built exactly: q = (½, ½, ½, ½) times r = (1, s, 0, 0) (and about y,
// z) with s = 2^-k has the components ½ ± ½s, all exact in doubles for k ≤ 52,
// so q' = q·r carries no rounding, and r/|r| turns by exactly 2 atan(s): angles
// from 1.9e-6 (k = 20) to 9.1e-13 (k = 41). Bound: the formula's own roundings
// (a difference, two norms, atan2: 4ε relative), plus, where |q'|² = 1 + s² does
// not round to 1 (k < 27), normalising q', which rounds each component by up to
// 2^-54 and so the angle (twice |q − q'|) by up to 2^-52 ≈ 2.2e-16 rad.
TEST(RotationAngle, IsAccurateToRoundingForTinyTurnsBuiltExactly) {
  const Eigen::Quaterniond q(0.5, 0.5, 0.5, 0.5);
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (int k = 20; k <= 41; ++k) {
    const double s = std::ldexp(1.0, -k);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Quaterniond r(1, 0, 0, 0);
      r.vec()[axis] = s;
      const Eigen::Quaterniond q2 = q * r;
      for (int c = 0; c < 4; ++c) ASSERT_EQ(std::abs(wxyz(q2)[c] - 0.5), 0.5 * s);  // no rounding happened
      const double exact = 2 * std::atan(s);
      const double bound = 4 * eps * exact + (q2.squaredNorm() == 1.0 ? 0.0 : eps);
      EXPECT_NEAR(rotation_angle(wxyz(q), wxyz(q2)), exact, bound) << "k " << k << " axis " << axis;
      EXPECT_NEAR(rotation_angle(wxyz(q2), wxyz(q)), exact, bound);
      // Why not 2 acos|q·q'|: below 2.1e-8 rad q·q' rounds to 1 and the angle to 0.
      if (exact < 1e-8) {
        EXPECT_EQ(2 * std::acos(std::min(1.0, std::abs(wxyz(q).dot(wxyz(q2))))), 0.0);
      }
    }
  }
}

core::Sample sample(double t) {
  core::Sample s;
  s.t = t;
  s.particles.resize(2);
  s.bodies.resize(1);
  return s;
}

TEST(StateDifference, IsTheLargestOverParticlesAndBodiesForEachMeasure) {
  core::Sample a = sample(0), b = sample(0);
  b.particles[0].position = {3e-6, 4e-6, 0};  // 5e-6 m
  b.particles[1].velocity = {0, 0, -2};
  b.bodies[0].position = {1e-6, 0, 0};
  b.bodies[0].velocity = {0, 0.5, 0};
  b.bodies[0].angular_velocity = {0, 0, 0.25};
  b.bodies[0].orientation = wxyz(Eigen::Quaterniond(Eigen::AngleAxisd(1e-10, Eigen::Vector3d::UnitY())));
  const StateErrors d = state_difference(a, b);
  EXPECT_DOUBLE_EQ(d[Measure::position], 5e-6);
  EXPECT_DOUBLE_EQ(d[Measure::velocity], 2);
  EXPECT_DOUBLE_EQ(d[Measure::angular_velocity], 0.25);
  EXPECT_NEAR(d[Measure::orientation], 1e-10, 1e-24);  // the old 2 acos|q·q'| read 0 here
  EXPECT_DOUBLE_EQ(orientation_difference(a, b), d[Measure::orientation]);
  EXPECT_DOUBLE_EQ(position_difference(b, a), 5e-6);

  // A NaN state (a diverged run) is never read as agreement: std::max(0, NaN) is 0.
  b.bodies[0].velocity.x() = NAN;
  EXPECT_TRUE(std::isnan(state_difference(a, b)[Measure::velocity]));
  EXPECT_TRUE(std::isnan(worse(NAN, 1.0)));
  EXPECT_TRUE(std::isnan(worse(1.0, NAN)));
}

core::Run energies(std::initializer_list<std::pair<double, double>> ku) {
  core::Run run;
  double t = 0;
  for (const auto& [k, u] : ku) {
    core::Sample s;
    s.t = t++;
    s.kinetic = k;
    s.potential = u;
    run.samples.push_back(s);
  }
  return run;
}

// Energy change relative to |E0|: a blow-up from −0.5 J to 1.9e6 J is a change of
// 1.9e6 + 0.5 J, 3.8e6 + 1 times |E0|; the old measure divided by the largest
// |K| or |U| seen (1.9e6 here) and read 1.000. Exact in doubles to 1e-15 relative.
TEST(EnergyDrift, IsRelativeToTheInitialEnergyAndNeverSaturates) {
  const core::Run blowup = energies({{0.25, -0.75}, {0.3, -0.8}, {1.9e6 + 1.5, -1.5}});
  EXPECT_DOUBLE_EQ(energy_scale(blowup.samples.front()), 0.5);
  EXPECT_NEAR(energy_drift(blowup), 3.8e6 + 1, 1e-15 * 3.8e6);
  EXPECT_GT(energy_drift(blowup), 1.0);

  EXPECT_EQ(energy_drift(energies({{1, 2}, {2, 1}, {3, 0}})), 0.0);           // exchanged, conserved
  EXPECT_NEAR(energy_drift(energies({{1, 2}, {0.5, 1.5}})), 1.0 / 3, 1e-15);  // dissipated: a third lost

  // E0 = 0 by the datum (K0 = 1 J, U0 = −1 J): measured against |K0| + |U0| = 2 J.
  const core::Run datum = energies({{1, -1}, {1.1, -0.9}});
  EXPECT_DOUBLE_EQ(energy_scale(datum.samples.front()), 2);
  EXPECT_NEAR(energy_drift(datum), 0.1, 1e-15);
  // Every energy 0 at t = 0 (at rest at the datum): the largest |K| + |U| seen.
  EXPECT_EQ(energy_scale(energies({{0, 0}}).samples.front()), 0.0);
  const double gain = std::ldexp(1.0, -30);  // exact: 2 − gain is a double
  EXPECT_DOUBLE_EQ(energy_drift(energies({{0, 0}, {2, -2 + gain}})), gain / (4 - gain));
  EXPECT_EQ(energy_drift(energies({{0, 0}, {0, 0}})), 0.0);

  EXPECT_TRUE(std::isnan(energy_drift(energies({{1, 0}, {NAN, 0}, {1, 0}}))));
  EXPECT_EQ(energy_drift(core::Run{}), 0.0);
}

}  // namespace
}  // namespace gacompare::compare
