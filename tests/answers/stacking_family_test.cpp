// answers/stacking_family.hpp: the verdict that holds a stacking run to its
// statics. Runs written by hand, not simulated: a column exactly at rest
// passes, and each way a stack goes wrong (sideways drift, motion once
// landed, sinking, floating, coming off its support, a capped solve, no
// samples at all) fails, naming the body, the time and the check. A verdict
// that passed a wrong run would hide wrong physics behind a green check.
#include "answers/stacking_family.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace gacompare::core {
namespace {

const StackCase& column_of_five() {
  static const std::vector<StackCase> family = stacking_family(ContactSolverMethod::direct);
  const auto it = std::find_if(family.begin(), family.end(), [](const StackCase& c) { return c.name == "column/cubes/5"; });
  if (it == family.end()) throw std::runtime_error("column/cubes/5 is not in the family");
  return *it;
}

// Every body at its rest, still, sampled every half second for 10 s.
Run at_rest(const StackCase& c) {
  Run run;
  for (int k = 0; k <= 20; ++k) {
    Sample s;
    s.t = 0.5 * k;
    for (std::size_t b = 0; b < c.scene.bodies.size(); ++b) {
      BodySample body;
      body.position = c.scene.bodies[b].is_static ? c.scene.bodies[b].position : c.rest[b];
      s.bodies.push_back(body);
    }
    run.samples.push_back(s);
  }
  return run;
}

// The run at rest with one body of one sample changed.
Run changed(const StackCase& c, double t, const std::string& name, const std::function<void(BodySample&)>& change) {
  Run run = at_rest(c);
  for (auto& s : run.samples) {
    if (s.t != t) continue;
    for (std::size_t b = 0; b < c.scene.bodies.size(); ++b)
      if (c.scene.bodies[b].name == name) change(s.bodies[b]);
  }
  return run;
}

void expect_fails(const StackVerdict& v, const std::string& words) {
  EXPECT_FALSE(v.pass);
  EXPECT_GT(v.ratio, 1);
  EXPECT_NE(v.worst.find(words), std::string::npos) << v.worst;
  EXPECT_FALSE(v.first_failure.empty());
}

TEST(StackVerdict, AColumnAtRestPasses) {
  const StackCase& c = column_of_five();
  const StackVerdict v = c.evaluate(at_rest(c));
  EXPECT_TRUE(v.pass) << v.worst;
  EXPECT_LE(v.ratio, 1e-3);  // rounding's allowance only
  EXPECT_TRUE(v.first_failure.empty());
}

TEST(StackVerdict, EveryWayAColumnGoesWrongFails) {
  const StackCase& c = column_of_five();
  // Sideways by twice the drift allowed, at any time (a landing too).
  expect_fails(c.evaluate(changed(c, 0.5, "b3", [](BodySample& b) { b.position.x() += 2 * kStackDrift; })),
               "b3 at t = 0.50 s drifted sideways");
  // Moving once landed: ten times the rim speed allowed, by spinning alone
  // (a 0.2 m cube's rim is 0.1 √3 m from its centre).
  const double rim = 0.1 * std::sqrt(3.0);
  expect_fails(c.evaluate(changed(c, 5, "b2", [&](BodySample& b) { b.angular_velocity.z() = 10 * kStackSpeed / rim; })),
               "b2 at t = 5.00 s moves");
  // Two tolerances deeper than its contacts below allow.
  const double tol = 1e-4;
  expect_fails(c.evaluate(changed(c, 6, "b4", [&](BodySample& b) { b.position.z() -= 6 * tol; })),
               "b4 at t = 6.00 s sank below its rest");
  expect_fails(c.evaluate(changed(c, 7, "b5", [&](BodySample& b) { b.position.z() += 2 * tol; })),
               "b5 at t = 7.00 s floats above its rest");
  // Far below: off its support, not into it.
  expect_fails(c.evaluate(changed(c, 10, "b5", [](BodySample& b) { b.position = {3, 0, -150}; })),
               "b5 at t = 10.00 s fell off its support");
}

TEST(StackVerdict, BeforeTheLandingsEndMotionIsAllowed) {
  // A body still moving at 0.5 s (a landing) is no failure; the same at 1 s is.
  const StackCase& c = column_of_five();
  const auto moving = [](BodySample& b) { b.velocity.z() = -0.01; };
  EXPECT_TRUE(c.evaluate(changed(c, 0.5, "b2", moving)).pass);
  expect_fails(c.evaluate(changed(c, kStackSettle, "b2", moving)), "b2 at t = 1.00 s moves");
}

TEST(StackVerdict, NoSamplesACappedSolveOrAnErrorFails) {
  const StackCase& c = column_of_five();
  expect_fails(c.evaluate(core::Run{}), "no samples");
  core::Run capped = at_rest(c);
  capped.counters["response_sweep_cap_hits"] = 1;
  expect_fails(c.evaluate(capped), "response_sweep_cap_hits 1");
  core::Run stopped = at_rest(c);
  stopped.error = "a NaN in flight";
  expect_fails(c.evaluate(stopped), "the run stopped: a NaN in flight");
}

}  // namespace
}  // namespace gacompare::core
