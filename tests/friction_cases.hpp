#pragma once
// Coulomb friction (core/collision/collisions.hpp) through a backend, on the
// bundled friction scenes (data/scenes/friction_*.json) against their analytic
// answers (answers/friction_answers.hpp). Instantiated by
// tests/{traditional,cga}/friction_test.cpp.
//
// Tolerance 1e-3 relative: the bound, and the resolution the answers
// allow a discrete method at all (a stop can be timed only to the collision
// step, 1 ms of 0.4 s, unless it falls on one as the scene arranges). The
// scheme itself is exact for these constant forces: RK4 integrates gravity's
// parabola exactly, the impulses remove one step's slip exactly, and the
// friction displacement (½ h Δv at resting contacts) puts the positions on the
// same parabola; measured errors are ~1e-12 (docs/results/contacts.md).
#include "answers/friction_answers.hpp"
#include "core/dynamics/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>
#include <algorithm>

namespace gacompare::testing {

template <class Backend>
class FrictionCases : public ::testing::Test {
 protected:
  static core::Scene scene(const std::string& name) {
    return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
  }
  // A figure's error (relative, or absolute where the answer is 0) within `bound`.
  static void expect_within(const core::FrictionFigure& f, double bound) {
    EXPECT_LE(f.error(), bound) << f.quantity << ": analytic " << f.analytic << " measured " << f.measured;
  }
  // The scene run through the backend, its figures by `figures_of`, each within its bound.
  template <class Figures>
  static core::Run expect_figures(const std::string& name, Figures figures_of, const std::vector<double>& bounds) {
    const core::Scene s = scene(name);
    core::Run run = core::simulate<Backend>(s);
    if (run.error) ADD_FAILURE() << *run.error;
    const auto figures = figures_of(s, run);
    EXPECT_EQ(figures.size(), bounds.size());
    for (std::size_t k = 0; k < std::min(figures.size(), bounds.size()); ++k) expect_within(figures[k], bounds[k]);
    return run;
  }
  static void expect_answers(const std::string& name) {
    const core::Scene s = scene(name);
    const core::Run run = core::simulate<Backend>(s);
    ASSERT_FALSE(run.error) << *run.error;
    EXPECT_GT(run.counters.at("friction_contacts"), 0u);
    for (const auto& f : core::friction_figures(s, run)) expect_within(f, f.analytic == 0 ? 1e-9 : 1e-3);
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

// A cube let go at rest 3e-6 m above the floor, with friction: it falls onto
// the floor within the first collision step and must then rest on it, its
// bottom face at the floor's top, never above it (and below it by no more
// than the penetration tolerance). Every height up to ½|g|h² (4.9e-6 m at
// h = 1 ms) above the floor was a fixed point of the friction displacement,
// which put the cube back where each step began: it hovered 3e-6 m up for the
// whole run. Above by at most 1e-12 m: the lowering puts the deepest corner at
// the floor's top to the rounding of the heights (~1e-16 m), with room for
// the next steps' ½|g|h² falls and lifts, which cancel to rounding.
TYPED_TEST_P(FrictionCases, CubeLetGoJustAboveTheFloorRestsOnItInsteadOfHovering) {
  core::Scene s = this->scene("friction_floor_stop");
  s.bodies.back().velocity = core::Vec3::Zero();
  s.bodies.back().position.z() = 0.1 + 3e-6;
  s.duration = 0.2;
  const core::Run run = core::simulate<TypeParam>(s);
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_GT(run.counters.at("friction_lowerings"), 0u);
  const std::size_t box = s.bodies.size() - 1;
  int checked = 0;
  for (const auto& sample : run.samples) {
    if (sample.t < 0.002) continue;  // let go above the floor; on it after the first step
    const double z = sample.bodies[box].position.z();
    EXPECT_LE(z, 0.1 + 1e-12) << "t = " << sample.t;
    EXPECT_GE(z, 0.1 - 1e-4) << "t = " << sample.t;
    ++checked;
  }
  EXPECT_GT(checked, 90);
}

// A solid sphere sent along the floor without spin slides, then rolls: speed
// v0 − μ g t while it slides, ω r = v at t* = 2 v0/(7 μ g), 5/7 v0 after. To
// 1e-3 relative (the bound; measured 1.4e-5: in each step the ball
// sinks ½ g h² = 4.9e-6 m into the floor before its impulse, and the contact
// point is midway through that overlap, so it rolls on a radius 2.45e-6 m
// short: v/(ω r) = 1 − 2.45e-5, and 5/7 becomes 1/(1 + 2/5 (r/r')²)).
TYPED_TEST_P(FrictionCases, SphereSentAlongFloorSlidesThenRollsAtFiveSevenths) {
  this->expect_answers("sphere_slide_to_roll");
  const core::Run run = core::simulate<TypeParam>(this->scene("sphere_slide_to_roll"));
  EXPECT_GT(run.counters.at("sliding_contacts"), 0u);
}

// A top spinning on its apex on a floor precesses as Lagrange's heavy top
// about a fixed point (answers/friction_answers.hpp, top_figures): the rate and
// the tilt to 1e-3 relative (the bound; measured 1.3e-5 and 3.6e-4).
// The apex is held by friction impulses once per collision step, so between
// them it slides under the free motion: the drift is first order in the step
// (measured 8.6e-6 m at 1e-4 s, 1.5e-4 m at 1e-3 s over the 0.5 s); bound
// 1e-4 m, a thousandth of the top's 0.1 m height.
TYPED_TEST_P(FrictionCases, TopOnFloorPrecessesAtTheHeavyTopRate) {
  const core::Run run = this->expect_figures("top_on_floor", core::top_figures, {1e-3, 1e-3, 1e-4});
  EXPECT_GT(run.counters.at("friction_contacts"), 0u);
}

// Nine cubes, four spheres in the pockets between them and a plate on the
// spheres settle where the stacked-rest rule puts them (answers/friction_answers.hpp,
// pile_figures): every height to 1e-3 relative (the bound; measured
// 1.4e-4 — the contacts overlap by up to the 1e-4 m penetration tolerance,
// and the spheres' impacts push the cubes 8e-6 m apart, which lowers the
// spheres); the horizontal drift below 1e-3 of the 0.1 m gap between cubes;
// and at the end everything at rest (1e-9 m/s, rad/s: a resting contact's
// impulse cancels the step's gravity exactly).
TYPED_TEST_P(FrictionCases, MixedPileOfSpheresAndBoxesSettlesAtItsStackedHeights) {
  this->expect_figures("mixed_pile", core::pile_figures, {1e-3, 1e-3, 1e-4, 1e-9, 1e-9});
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
                            CubeLetGoJustAboveTheFloorRestsOnItInsteadOfHovering,
                            SphereSentAlongFloorSlidesThenRollsAtFiveSevenths, TopOnFloorPrecessesAtTheHeavyTopRate,
                            MixedPileOfSpheresAndBoxesSettlesAtItsStackedHeights, TangentPrimitivesSpanTheContactPlane);

}  // namespace gacompare::testing
