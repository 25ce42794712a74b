#pragma once
// The particle validation problems, run from the bundled scenes
// (data/scenes) through a backend and checked against analytic answers.
// Instantiated per backend by tests/{traditional,cga}/dynamics_test.cpp.
#include "core/model/generators.hpp"
#include "core/dynamics/simulator.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gacompare::testing {

inline core::Scene bundled(const std::string& name) {
  return core::expand_generators(core::load_scene(std::string(GACOMPARE_DATA_DIR) + "/scenes/" + name + ".json"));
}

// Times at which coordinate `axis` of particle `p` crosses `level` upwards, each
// found on the cubic Hermite interpolant of the samples (positions and
// velocities at both ends), so the crossing error is O(Δt⁴), not O(Δt²).
inline std::vector<double> upward_crossings(const core::Run& run, std::size_t p, int axis, double level) {
  std::vector<double> times;
  for (std::size_t k = 1; k < run.samples.size(); ++k) {
    const auto& a = run.samples[k - 1];
    const auto& b = run.samples[k];
    const double h = b.t - a.t;
    const double x0 = a.particles[p].position[axis] - level, x1 = b.particles[p].position[axis] - level;
    if (!(x0 < 0 && x1 >= 0)) continue;
    const double v0 = a.particles[p].velocity[axis] * h, v1 = b.particles[p].velocity[axis] * h;
    auto hermite = [&](double s) {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * v0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * v1;
    };
    double lo = 0, hi = 1;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (hermite(mid) < 0 ? lo : hi) = mid;
    }
    times.push_back(a.t + 0.5 * (lo + hi) * h);
  }
  return times;
}

template <class B>
class DynamicsCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(DynamicsCases);

// Large amplitude: T = 4 √(L/g) K(sin(θ0/2)) (complete elliptic integral of the
// first kind). Cash–Karp at 1e-10 over 10 s and crossings interpolated to
// O(Δt⁴) ≈ 1e-8 s: the measured periods agree to 1e-7 relative.
TYPED_TEST_P(DynamicsCases, LargeAmplitudePendulumMatchesEllipticIntegral) {
  const auto scene = bundled("pendulum");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  const double L = 1.0, g = 9.81, theta0 = 2.5;
  const double period = 4 * std::sqrt(L / g) * std::comp_ellint_1(std::sin(theta0 / 2));
  const auto t = upward_crossings(run, 0, 0, 0.0);  // x crosses 0 moving +x: once a period
  ASSERT_GE(t.size(), 3u);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NEAR((t[k] - t[k - 1]) / period, 1.0, 1e-7);
  for (const auto& s : run.samples) EXPECT_LT(s.constraint_violation, 1e-8);
  EXPECT_EQ(run.counters.at("cg_not_converged"), 0u);
}

// Small amplitude, θ0 = 0.01: T = 2π √(L/g) (1 + θ0²/16 + …), so the small-angle
// formula is right to 6.3e-6; the test allows 1e-5.
TYPED_TEST_P(DynamicsCases, SmallAnglePendulumMatchesHarmonicPeriod) {
  auto scene = bundled("pendulum");
  const double theta0 = 0.01;
  scene.particles[0].position = core::Vec3(std::sin(theta0), 0, -std::cos(theta0));
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  const double period = 2 * std::numbers::pi * std::sqrt(1.0 / 9.81);
  const auto t = upward_crossings(run, 0, 0, 0.0);
  ASSERT_GE(t.size(), 4u);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NEAR((t[k] - t[k - 1]) / period, 1.0, 1e-5);
}

// Kepler, e = 0.6: period 2π √(a³/(C M)) and energy −C m1 m2 / (2a). The run covers
// three periods; the planet returns to periapsis (x at its largest) once a
// period. Cash–Karp at 1e-11 relative: ~1e-9 in positions, so periods agree to
// 1e-7 and the energy, an exact invariant, to 1e-8 relative.
TYPED_TEST_P(DynamicsCases, EccentricKeplerOrbitHasAnalyticPeriodAndEnergy) {
  const auto scene = bundled("kepler");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  const double m1 = 1, m2 = 0.5, a = 1, C = 1;
  const double period = 2 * std::numbers::pi * std::sqrt(a * a * a / (C * (m1 + m2)));
  const double energy = -C * m1 * m2 / (2 * a);
  for (const auto& s : run.samples) EXPECT_NEAR((s.kinetic + s.potential) / energy, 1.0, 1e-8);
  // The planet crosses y = 0 upwards at periapsis, once a period.
  const auto t = upward_crossings(run, 1, 1, 0.0);
  ASSERT_GE(t.size(), 2u);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NEAR((t[k] - t[k - 1]) / period, 1.0, 1e-7);
  const auto& last = run.samples.back();  // three periods later, back at the start
  EXPECT_LT((last.particles[1].position - run.samples.front().particles[1].position).norm(), 1e-6);
  EXPECT_LT(last.linear_momentum.norm(), 1e-12);
}

// The hanging net (fig. 4) comes to rest on its constraints: projection holds
// every |C|/|∇C| under its 1e-10 m tolerance after each step, CG converges on
// every solve, and drag leaves no kinetic energy to speak of after 20 s.
TYPED_TEST_P(DynamicsCases, HangingNetComesToRestOnItsConstraints) {
  const auto scene = bundled("hanging_net");
  ASSERT_EQ(scene.particles.size(), 64u);
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  for (const auto& s : run.samples) EXPECT_LE(s.constraint_violation, 1e-10);
  EXPECT_LT(run.samples.back().kinetic, 1e-9);
  EXPECT_LT(run.samples.back().potential, -1.0);  // it fell: the net hangs below its pins
  EXPECT_EQ(run.counters.at("cg_not_converged"), 0u);
  EXPECT_EQ(run.counters.at("projection_not_converged"), 0u);
  EXPECT_LE(run.metrics.at("max_cg_relative_residual"), scene.constraint_solver.cg_tolerance);
}

// A bead on a frictionless helix: the constraint does no work, so energy holds
// to the O(h²) error of velocity Verlet (h = 1e-3: ~1e-5 relative to the energy
// exchanged), and it stays on the helix.
TYPED_TEST_P(DynamicsCases, BeadOnHelixKeepsItsEnergyAndPath) {
  const auto scene = bundled("bead_on_helix");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  const double e0 = run.samples.front().kinetic + run.samples.front().potential;
  double exchanged = 0;
  for (const auto& s : run.samples) exchanged = std::max(exchanged, s.kinetic);
  ASSERT_GT(exchanged, 0.1);
  for (const auto& s : run.samples) {
    EXPECT_NEAR(s.kinetic + s.potential, e0, 1e-4 * exchanged);
    EXPECT_LE(s.constraint_violation, 1e-10);
    const core::Vec3& x = s.particles[0].position;
    EXPECT_NEAR(std::hypot(x.x(), x.y()), 0.5, 1e-9);
  }
}

// Beads on a plane, a line and a circle, thrown and falling: ideal constraints
// do no work, so with Cash–Karp at 1e-11 energy holds to 1e-8 relative, and
// Baumgarte (α = β = 10) keeps each bead within 1e-8 m of its path.
TYPED_TEST_P(DynamicsCases, BeadsOnPlaneLineAndCircleStayOnThem) {
  const auto scene = core::parse_scene(R"({"name": "beads", "duration": 3.0, "output": {"every": 0.05},
    "solver": {"method": "cash_karp45", "dt": 1e-3, "abs_tol": 1e-11, "rel_tol": 1e-11},
    "constraint_solver": {"drift": "baumgarte", "baumgarte_alpha": 10, "baumgarte_beta": 10},
    "effects": [{"type": "gravity", "g": [0, 0, -9.81]}],
    "particles": [
      {"name": "p", "mass": 1.0, "position": [0, 0, 1], "velocity": [1, 1, -1]},
      {"name": "l", "mass": 2.0, "position": [0, 0, 0], "velocity": [0.5, 0, 0.5]},
      {"name": "c", "mass": 0.5, "position": [0, 1, 0], "velocity": [-0.5, 0, 0.5]}],
    "constraints": [
      {"type": "on_plane", "particle": "p", "point": [0, 0, 1], "normal": [0, 1, 1]},
      {"type": "on_line", "particle": "l", "point": [0, 0, 0], "direction": [1, 0, 1]},
      {"type": "on_circle", "particle": "c", "center": [0, 0, 0], "normal": [1, 0, 1], "radius": 1.0}]})",
                                       "beads.json");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value()) << *run.error;
  const double e0 = run.samples.front().kinetic + run.samples.front().potential;
  for (const auto& s : run.samples) {
    EXPECT_NEAR(s.kinetic + s.potential, e0, 1e-8 * std::max(1.0, std::abs(e0)));
    const core::Vec3 &p = s.particles[0].position, &l = s.particles[1].position, &c = s.particles[2].position;
    EXPECT_NEAR((p - core::Vec3(0, 0, 1)).dot(core::Vec3(0, 1, 1).normalized()), 0, 1e-8);
    EXPECT_NEAR(l.cross(core::Vec3(1, 0, 1).normalized()).norm(), 0, 1e-8);
    EXPECT_NEAR(c.dot(core::Vec3(1, 0, 1).normalized()), 0, 1e-8);
    EXPECT_NEAR(c.norm(), 1.0, 1e-8);
  }
}

REGISTER_TYPED_TEST_SUITE_P(DynamicsCases, BeadsOnPlaneLineAndCircleStayOnThem, LargeAmplitudePendulumMatchesEllipticIntegral,
                            SmallAnglePendulumMatchesHarmonicPeriod, EccentricKeplerOrbitHasAnalyticPeriodAndEnergy,
                            HangingNetComesToRestOnItsConstraints, BeadOnHelixKeepsItsEnergyAndPath);

}  // namespace gacompare::testing
