// core/model/budget.hpp: what the loader works out a scene asks for, checked against
// what a run then does (the solver's own step count, the collision loop's
// counter) and against closed forms (a body's radii and volume), and the
// physical bounds at their edges.
#include "core/model/budget.hpp"

#include "core/error.hpp"
#include "core/model/generators.hpp"
#include "core/dynamics/simulator.hpp"
#include "traditional/backend.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace gacompare::core {
namespace {

using json = nlohmann::json;

std::string refusal(const json& scene, const Limits& limits = {}) {
  try {
    parse_compiled(scene.dump(), "b.json", limits);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    return e.what();
  }
  return "";
}

json particle_scene(double duration, double every, double dt) {
  return {{"name", "p"}, {"duration", duration}, {"output", {{"every", every}}},
          {"solver", {{"method", "rk4"}, {"dt", dt}}},
          {"particles", {{{"name", "a"}, {"mass", 1}, {"position", {0, 0, 0}}, {"velocity", {1, 0, 0}}}}}};
}

// The fixed-step count the loader refuses on is the count the solver takes:
// every output interval in equal steps of at most dt (here 10 intervals of
// ceil(0.1 / 0.03) = 4 steps).
TEST(Budget, TheFixedStepCountIsTheSolversCount) {
  const json scene = particle_scene(1, 0.1, 0.03);
  Limits limits;
  limits.max_steps = 40;
  const Scene s = parse_scene(scene.dump(), "b.json", limits);
  const core::Run run = simulate<traditional::Backend>(expand_generators(s));
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_EQ(run.solver.steps_accepted, 40u);
  limits.max_steps = 39;
  EXPECT_NE(refusal(scene, limits).find("b.json: /solver/dt: expected a step giving at most 39 steps"), std::string::npos);
}

// The solver's budget at run time is the same number: an adaptive run asked
// for more stops, exit 1, at the step that spends it.
TEST(Budget, TheRunTimeBudgetStopsAnAdaptiveRun) {
  json scene = particle_scene(1, 0.1, 0.03);
  scene["solver"] = {{"method", "cash_karp45"}, {"dt", 1e-3}, {"abs_tol", 1e-12}, {"rel_tol", 1e-12}};
  scene["effects"] = {{{"type", "quadratic_drag"}, {"k", 1}}};
  Limits limits;
  limits.max_steps = 25;
  const core::Run run = simulate<traditional::Backend>(expand_generators(parse_scene(scene.dump(), "b.json", limits)));
  ASSERT_TRUE(run.error);
  EXPECT_NE(run.error->find("integrate: the budget of 25 steps is spent"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("particle 'a' has the largest error estimate"), std::string::npos) << *run.error;
  EXPECT_EQ(run.solver.steps_accepted + run.solver.steps_rejected, 25u);
}

// Two free boxes that never meet: the collision loop takes duration / step
// steps, which is what the loader counts (no speed limits the step here:
// 0.5 m/s against half an inradius of 0.05 m is 0.1 s, above the step).
TEST(Budget, TheCollisionStepCountIsTheLoopsCount) {
  const json scene = {
      {"name", "c"}, {"duration", 0.5}, {"output", {{"every", 0.1}}}, {"solver", {{"method", "rk4"}, {"dt", 0.1}}},
      {"effects", {{{"type", "collisions"}, {"step", 0.01}}}},
      {"bodies",
       {{{"name", "a"}, {"shape", {{"box", {0.2, 0.2, 0.2}}}}, {"mass", 1}, {"position", {0, 0, 0}}, {"velocity", {0.5, 0, 0}}},
        {{"name", "b"}, {"shape", {{"box", {0.2, 0.2, 0.2}}}}, {"mass", 1}, {"position", {0, 5, 0}}}}}};
  Limits limits;
  limits.max_steps = 50;
  const core::Run run = simulate<traditional::Backend>(parse_scene(scene.dump(), "b.json", limits));
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_EQ(run.counters.at("collision_steps"), 50u);
  limits.max_steps = 49;
  EXPECT_NE(refusal(scene, limits).find("/effects/0/step: expected a collision step giving at most 49 steps"), std::string::npos);
  // 200 m/s: a step may move a body 0.05 m, so 0.25 ms steps, 2000 of them.
  json fast = scene;
  fast["bodies"][0]["velocity"] = {200, 0, 0};
  limits.max_steps = 1999;
  EXPECT_NE(refusal(fast, limits).find("/bodies/0/velocity: expected speeds the collision loop can follow"), std::string::npos);
  limits.max_steps = 2001;
  EXPECT_EQ(refusal(fast, limits), "");
}

// A body's radii and volume against closed forms: a 1 x 2 x 3 box (corner
// at sqrt(14)/2, nearest face 0.5, volume 6) and a regular tetrahedron of edge
// a (circumradius a sqrt(3/8), inradius a / (2 sqrt 6), volume a^3 / (6 sqrt 2)).
TEST(Budget, BodyScalesAreTheClosedForms) {
  Body box;
  box.shape = BoxShape{{1, 2, 3}};
  box.density = 2;
  const auto scale_of = [](const Body& body) {
    Scene s;
    s.bodies = {body};
    return body_scale(body, compile(s).bodies[0]);
  };
  const BodyScale b = scale_of(box);
  EXPECT_NEAR(b.radius, std::sqrt(14.0) / 2, 1e-15);
  EXPECT_NEAR(b.inradius, 0.5, 1e-15);
  EXPECT_NEAR(b.volume, 6, 1e-14);
  EXPECT_NEAR(b.mass, 12, 1e-13);
  Body tet;
  const double a = 0.3;
  tet.shape = TetrahedronShape{a};
  tet.mass = 1;
  const BodyScale t = scale_of(tet);
  EXPECT_NEAR(t.radius, a * std::sqrt(3.0 / 8), 1e-15);
  EXPECT_NEAR(t.inradius, a / (2 * std::sqrt(6.0)), 1e-15);
  EXPECT_NEAR(t.volume, a * a * a / (6 * std::sqrt(2.0)), 1e-16);
}

// The physical bounds at their edges: just below is a scene, just above is not.
TEST(Budget, PhysicalBoundsHoldAtTheirEdges) {
  json scene = particle_scene(1, 0.1, 0.01);
  scene["particles"][0]["velocity"] = {0.999 * kSpeedOfLight, 0, 0};
  EXPECT_EQ(refusal(scene), "");
  scene["particles"][0]["velocity"] = {1.001 * kSpeedOfLight, 0, 0};
  EXPECT_NE(refusal(scene).find("/particles/0/velocity: expected a speed below light's"), std::string::npos);
  scene = particle_scene(10, 0.1, 0.01);
  scene["effects"] = {{{"type", "gravity"}, {"g", {0, 0, -0.999 * kSpeedOfLight / 10}}}};
  EXPECT_EQ(refusal(scene), "");
  scene["effects"][0]["g"] = {0, 0, -1.001 * kSpeedOfLight / 10};
  EXPECT_NE(refusal(scene).find("/effects/0/g: expected a gravity"), std::string::npos);
  scene = particle_scene(1, 0.1, 0.01);
  scene["particles"][0]["mass"] = 0.9 * kMinMass;
  EXPECT_NE(refusal(scene).find("/particles/0/mass: expected a mass in [1e-31, 1e+53] kg"), std::string::npos);
}

}  // namespace
}  // namespace gacompare::core
