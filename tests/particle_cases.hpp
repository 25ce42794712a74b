#pragma once
// Particle cases run through a backend (core::Backend) and checked against
// closed-form solutions. Instantiated once per backend by
// tests/traditional/particle_test.cpp and tests/cga/particle_test.cpp.
#include "core/error.hpp"
#include "core/dynamics/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gacompare::testing {

inline core::Scene scene_from(const std::string& json) { return core::parse_scene(json, "inline.json"); }

template <class B>
class ParticleCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(ParticleCases);

// Linear drag (Table 2): v(t) = v∞ + (v0 − v∞) e^(−kt/m), v∞ = m g / k, and
// x(t) = x0 + v∞ t + (m/k)(v0 − v∞)(1 − e^(−kt/m)). Cash–Karp at tol 1e-10; each
// accepted step errs by at most abs_tol + rel_tol·|y| and the drag contracts
// errors, so the global error is below steps × (1e-10 + 1e-10 · 30).
TYPED_TEST_P(ParticleCases, ProjectileWithLinearDragMatchesClosedForm) {
  const auto scene = scene_from(R"({"name": "p", "duration": 2.0, "output": {"every": 0.1},
    "solver": {"method": "cash_karp45", "dt": 1e-3, "abs_tol": 1e-10, "rel_tol": 1e-10},
    "effects": [{"type": "gravity", "g": [0, 0, -9.81]}, {"type": "linear_drag", "k": 0.3}],
    "particles": [{"name": "a", "mass": 2.0, "position": [1, 2, 3], "velocity": [10, -2, 12]}]})");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value());
  ASSERT_EQ(run.samples.size(), 21u);
  const double m = 2.0, k = 0.3;
  const core::Vec3 g(0, 0, -9.81), x0(1, 2, 3), v0(10, -2, 12), vinf = m * g / k;
  const double bound = static_cast<double>(run.solver.steps_accepted) * (1e-10 + 1e-10 * 30);
  for (const auto& s : run.samples) {
    const double e = std::exp(-k * s.t / m);
    const core::Vec3 v = vinf + (v0 - vinf) * e;
    const core::Vec3 x = x0 + vinf * s.t + (m / k) * (v0 - vinf) * (1 - e);
    ASSERT_LT((s.particles[0].position - x).norm(), bound) << "t=" << s.t;
    ASSERT_LT((s.particles[0].velocity - v).norm(), bound) << "t=" << s.t;
  }
}

// Quadratic drag, falling from rest: v(t) = −v_t tanh(g t / v_t), v_t = √(m g / k),
// z(t) = z0 − (v_t² / g) ln cosh(g t / v_t). Fixed-step RK4, h = 1e-3: the global
// error is O(h⁴) ≈ 1e-12 times derivatives of order g/v_t ~ 1, far below 1e-9.
TYPED_TEST_P(ParticleCases, FallWithQuadraticDragMatchesClosedForm) {
  const auto scene = scene_from(R"({"name": "q", "duration": 3.0, "output": {"every": 0.5},
    "solver": {"method": "rk4", "dt": 1e-3},
    "effects": [{"type": "gravity", "g": [0, 0, -9.81]}, {"type": "quadratic_drag", "k": 0.2}],
    "particles": [{"name": "a", "mass": 0.5, "position": [0, 0, 50], "velocity": [0, 0, 0]}]})");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value());
  const double vt = std::sqrt(0.5 * 9.81 / 0.2);
  for (const auto& s : run.samples) {
    const double v = -vt * std::tanh(9.81 * s.t / vt);
    const double z = 50 - vt * vt / 9.81 * std::log(std::cosh(9.81 * s.t / vt));
    ASSERT_NEAR(s.particles[0].velocity.z(), v, 1e-9) << "t=" << s.t;
    ASSERT_NEAR(s.particles[0].position.z(), z, 1e-9) << "t=" << s.t;
  }
}

// Gravity alone conserves E = ½ m v² − m g·x exactly along the true path; RK4 is
// exact for the quadratic trajectory, so energy holds to rounding (1e-12 relative).
TYPED_TEST_P(ParticleCases, GravityConservesEnergyAndPinnedParticlesStay) {
  const auto scene = scene_from(R"({"name": "g", "duration": 1.0, "output": {"every": 0.25},
    "solver": {"method": "rk4", "dt": 0.01},
    "effects": [{"type": "gravity", "g": [0, 0, -9.81]}],
    "particles": [{"name": "a", "mass": 3.0, "position": [0, 0, 0], "velocity": [1, 2, 3]},
                  {"name": "pin", "mass": 1.0, "position": [5, 5, 5], "velocity": [0, 0, 0], "pinned": true}]})");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error.has_value());
  const double e0 = run.samples.front().kinetic + run.samples.front().potential;
  for (const auto& s : run.samples) {
    EXPECT_NEAR(s.kinetic + s.potential, e0, 1e-12 * std::abs(e0) + 1e-12);
    EXPECT_EQ(s.particles[1].position, core::Vec3(5, 5, 5));
  }
  EXPECT_TRUE(run.profile.ran(core::Stage::forces));
  EXPECT_TRUE(run.profile.ran(core::Stage::integrate));
  EXPECT_FALSE(run.profile.ran(core::Stage::narrowphase));  // no collisions effect, no collision stage
  EXPECT_EQ(run.solver.derivative_evaluations, 4 * run.solver.steps_accepted);
}

// A particle placed on an attracting point gets an infinite force: the run stops
// naming the particle, the stage (forces: its derivative was not finite at a
// finite state, found by replaying the failed interval) and the time, and
// keeps the samples before it.
TYPED_TEST_P(ParticleCases, NonFiniteStateStopsTheRunByName) {
  const auto scene = scene_from(R"({"name": "n", "duration": 1.0, "output": {"every": 0.5},
    "solver": {"method": "rk4", "dt": 0.01},
    "effects": [{"type": "attraction_to_point", "point": [0, 0, 0], "D": 1.0}],
    "particles": [{"name": "ok", "mass": 1.0, "position": [1, 0, 0], "velocity": [0, 1, 0]},
                  {"name": "doomed", "mass": 1.0, "position": [0, 0, 0], "velocity": [0, 0, 0]}]})");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_TRUE(run.error.has_value());
  EXPECT_NE(run.error->find("particle 'doomed'"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("stage forces"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("t=0"), std::string::npos) << *run.error;
  EXPECT_EQ(run.samples.size(), 1u);  // the t = 0 sample survives
}

// A finite derivative can still overflow the state: at 1.5e308 m/s Euler's
// x + h v passes the largest double (1.8e308) in the third half-second step,
// in the solver's combination. The stage named is integrate, and the samples
// before it survive. (A scene file cannot ask for that speed: the loader
// refuses speeds above light's, core/model/budget.hpp; the scene is set in code to
// test the simulator's own backstop.)
TYPED_TEST_P(ParticleCases, OverflowInTheSolverIsNamedIntegrate) {
  auto scene = scene_from(R"({"name": "n", "duration": 2.0, "output": {"every": 0.5},
    "solver": {"method": "euler", "dt": 0.5},
    "particles": [{"name": "fast", "mass": 1.0, "position": [0, 0, 0], "velocity": [1, 0, 0]}]})");
  scene.particles[0].velocity = {1.5e308, 0, 0};
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_TRUE(run.error.has_value());
  EXPECT_NE(run.error->find("particle 'fast'"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("stage integrate"), std::string::npos) << *run.error;
  EXPECT_EQ(run.samples.size(), 3u);  // t = 0, 0.5 and 1 (x = 1.5e308); at 1.5 s x = 2.25e308 overflows
}

// The collisions effect acts between rigid bodies; on particles alone it is refused.
TYPED_TEST_P(ParticleCases, CollisionsWithoutBodiesAreRefused) {
  const auto scene = scene_from(R"({"name": "c", "duration": 1.0, "output": {"every": 0.5},
    "solver": {"method": "rk4"},
    "particles": [{"name": "a", "mass": 1.0, "position": [1, 0, 0]}],
    "effects": [{"type": "collisions"}]})");
  try {
    core::simulate<TypeParam>(scene);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    EXPECT_NE(std::string(e.what()).find("particles do not collide"), std::string::npos) << e.what();
  }
}

// A scene must start on its constraints: the first violated one is named.
TYPED_TEST_P(ParticleCases, InitialConstraintViolationIsRefused) {
  const auto scene = scene_from(R"({"name": "c", "duration": 1.0, "output": {"every": 0.5},
    "solver": {"method": "rk4"},
    "particles": [{"name": "a", "mass": 1.0, "position": [1, 0, 0]}],
    "constraints": [{"type": "on_plane", "particle": "a", "point": [0, 0, 0], "normal": [0, 0, 1]},
                    {"type": "distance_to_point", "particle": "a", "point": [0, 0, 0], "length": 1.5}]})");
  try {
    core::simulate<TypeParam>(scene);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    EXPECT_NE(std::string(e.what()).find("constraint 1 (distance_to_point)"), std::string::npos) << e.what();
    // The violation is the first-order distance |C|/|∇C| = |½(1² − 1.5²)| / 1.
    EXPECT_NE(std::string(e.what()).find("by 0.625 m"), std::string::npos) << e.what();
  }
}

REGISTER_TYPED_TEST_SUITE_P(ParticleCases, ProjectileWithLinearDragMatchesClosedForm,
                            FallWithQuadraticDragMatchesClosedForm, GravityConservesEnergyAndPinnedParticlesStay,
                            NonFiniteStateStopsTheRunByName, OverflowInTheSolverIsNamedIntegrate, CollisionsWithoutBodiesAreRefused,
                            InitialConstraintViolationIsRefused);

}  // namespace gacompare::testing
