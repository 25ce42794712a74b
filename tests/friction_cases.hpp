#pragma once
// Coulomb friction (issue #17, core/collisions.hpp) through a backend, on the
// bundled friction scenes (data/scenes/friction_*.json) against their analytic
// answers (core/friction_answers.hpp). Instantiated by
// tests/{traditional,cga}/friction_test.cpp.
//
// Tolerance 1e-3 relative: the bound, and the resolution the answers
// allow a discrete method at all (a stop can be timed only to the collision
// step, 1 ms of 0.4 s, unless it falls on one as the scene arranges). The
// scheme itself is exact for these constant forces: RK4 integrates gravity's
// parabola exactly, the impulses remove one step's slip exactly, and the
// friction displacement (½ h Δv at resting contacts) puts the positions on the
// same parabola; measured errors are ~1e-12 (README "Friction").
#include "core/friction_answers.hpp"
#include "core/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace gacompare::testing {

template <class Backend>
class FrictionCases : public ::testing::Test {
 protected:
  static core::Scene scene(const std::string& name) {
    return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
  }
  static void expect_answers(const std::string& name) {
    const core::Scene s = scene(name);
    const core::Run run = core::simulate<Backend>(s);
    ASSERT_FALSE(run.error) << *run.error;
    EXPECT_GT(run.counters.at("friction_contacts"), 0u);
    for (const auto& f : core::friction_figures(s, run))
      EXPECT_LE(f.error(), f.analytic == 0 ? 1e-9 : 1e-3)
          << name << ": " << f.quantity << " analytic " << f.analytic << " measured " << f.measured;
  }
};
TYPED_TEST_SUITE_P(FrictionCases);

// tan 30° > 0.3: a = g (sin θ − μ cos θ), speed and distance after 1 s.
TYPED_TEST_P(FrictionCases, BoxSlidesDownInclineWithCoulombAcceleration) {
  this->expect_answers("friction_incline_slide");
  const core::Run run = core::simulate<TypeParam>(this->scene("friction_incline_slide"));
  EXPECT_GT(run.counters.at("sliding_contacts"), 0u);
}

// tan 20° < 0.5: static friction holds the box. Displacement bound 1e-9 m over
// the run (measured ~1e-13): without the friction displacement the box crept
// ½ g sin θ h per step, 1.7e-3 m in the 1 s, and sliding freely it would go
// ½ g sin θ t² = 1.7 m. Nothing slides after the first step.
TYPED_TEST_P(FrictionCases, BoxOnShallowInclineSticksWithoutCreeping) {
  this->expect_answers("friction_incline_stick");
  const core::Run run = core::simulate<TypeParam>(this->scene("friction_incline_stick"));
  for (const auto& sample : run.samples) EXPECT_LE(sample.bodies[1].velocity.norm(), 1e-9) << "t = " << sample.t;
  EXPECT_EQ(run.counters.at("sliding_contacts"), 0u);
}

// μ g deceleration: stops after v²/(2 μ g) at v/(μ g), and stays stopped.
TYPED_TEST_P(FrictionCases, BoxSlidingOnFloorStopsAtTheCoulombDistanceAndTime) {
  this->expect_answers("friction_floor_stop");
  const core::Scene s = this->scene("friction_floor_stop");
  const core::Run run = core::simulate<TypeParam>(s);
  const auto& at_stop = run.samples[static_cast<std::size_t>(std::lround(0.4 / s.output_every))];
  ASSERT_NEAR(at_stop.t, 0.4, 1e-12);
  for (const auto& sample : run.samples) {
    if (sample.t < at_stop.t) continue;
    EXPECT_LE((sample.bodies[1].position - at_stop.bodies[1].position).norm(), 1e-9) << "t = " << sample.t;
  }
}

// Friction off costs nothing: a pair with one body at μ = 0 has √(μ · 0) = 0,
// gets no friction rows, and runs bit for bit as the frictionless scene (which
// `gacompare check` holds to its baseline from before friction existed).
TYPED_TEST_P(FrictionCases, FrictionOffIsBitIdenticalAndAddsNoRows) {
  for (const std::string name : {"cube_drop_edge", "contact_stack5"}) {
    const core::Scene plain = this->scene(name);
    core::Scene one_sided = plain;
    one_sided.bodies.back().friction = 0.8;
    const core::Run a = core::simulate<TypeParam>(plain), b = core::simulate<TypeParam>(one_sided);
    ASSERT_FALSE(a.error || b.error);
    EXPECT_EQ(a.counters.at("friction_contacts"), 0u);
    EXPECT_EQ(b.counters.at("friction_contacts"), 0u);
    EXPECT_EQ(a.counters, b.counters);
    ASSERT_EQ(a.samples.size(), b.samples.size());
    for (std::size_t k = 0; k < a.samples.size(); ++k)
      for (std::size_t i = 0; i < a.samples[k].bodies.size(); ++i) {
        const auto &p = a.samples[k].bodies[i], &q = b.samples[k].bodies[i];
        ASSERT_TRUE(p.position == q.position && p.orientation == q.orientation && p.velocity == q.velocity &&
                    p.angular_velocity == q.angular_velocity)
            << name << " body " << i << " t = " << a.samples[k].t;
      }
  }
}

// The backend's primitives for the contact plane: in_plane(n, u) is u's part
// orthogonal to n, quarter_turn(n, t) = n × t, so (t, n × t, n) is a
// right-handed orthonormal frame (traditional: cross products; cga: the
// plane's bivector n I and left contractions).
TYPED_TEST_P(FrictionCases, TangentPrimitivesSpanTheContactPlane) {
  using Bodies = typename TypeParam::Contacts::BodiesType;
  const core::Vec3 n = core::Vec3(0.3, -0.5, 0.8).normalized(), u(1.5, 2.0, -0.7);
  const core::Vec3 t = Bodies::in_plane(n, u);
  EXPECT_NEAR((t - (u - u.dot(n) * n)).norm(), 0, 1e-15);
  const core::Vec3 unit = t.normalized(), turned = Bodies::quarter_turn(n, unit);
  EXPECT_NEAR((turned - n.cross(unit)).norm(), 0, 1e-15);
  EXPECT_NEAR(turned.norm(), 1, 1e-15);
  EXPECT_NEAR(unit.cross(turned).dot(n), 1, 1e-15);
}

REGISTER_TYPED_TEST_SUITE_P(FrictionCases, BoxSlidesDownInclineWithCoulombAcceleration,
                            BoxOnShallowInclineSticksWithoutCreeping,
                            BoxSlidingOnFloorStopsAtTheCoulombDistanceAndTime, FrictionOffIsBitIdenticalAndAddsNoRows,
                            TangentPrimitivesSpanTheContactPlane);

}  // namespace gacompare::testing
