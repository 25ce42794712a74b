#pragma once
// core/collision/sleep.hpp through a backend: sleeping islands against the
// same scenes run awake. Instantiated by tests/{traditional,cga,pga}/sleep_test.cpp.
//   - A settled column of cubes falls asleep, meets its statics answer at
//     every sample, ends where the awake column rests, and costs fewer force
//     terms and narrowphase pairs.
//   - A cube let go above the sleeping column wakes it; all six come to rest
//     where the awake run's do, and sleep again.
//   - An applied force switching on wakes the body it pushes.
// Every comparison with the awake run is held to the stacking family's rest
// bound (core::kStackDrift = 1e-4 m): what we demand of rest at all is what
// sleeping may cost.
#include "answers/stacking_family.hpp"
#include "core/dynamics/simulator.hpp"

#include <gtest/gtest.h>

#include <string>

namespace gacompare::testing {

inline core::StackCase sleep_stack(const std::string& name, double duration) {
  for (core::StackCase& c : core::stacking_family(core::Collisions{}.contact_solver))
    if (c.name == name) {
      c.scene.duration = duration;
      return c;
    }
  ADD_FAILURE() << "no stacking case " << name;
  return {};
}

inline core::Scene with_sleep(core::Scene s) {
  for (auto& e : s.effects)
    if (auto* c = std::get_if<core::Collisions>(&e)) c->sleep.on = true;
  return s;
}

// Body by body, the final positions of two runs of one scene.
inline double largest_offset(const core::Run& a, const core::Run& b) {
  double worst = 0;
  const auto& ea = a.samples.back().bodies;
  const auto& eb = b.samples.back().bodies;
  for (std::size_t k = 0; k < ea.size() && k < eb.size(); ++k)
    worst = std::max(worst, (ea[k].position - eb[k].position).norm());
  return worst;
}

template <class Backend>
class SleepCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(SleepCases);

TYPED_TEST_P(SleepCases, ASettledColumnSleepsWhereTheAwakeColumnRests) {
  const core::StackCase c = sleep_stack("column/cubes/5", 3.0);
  const core::Run awake = core::simulate<TypeParam>(c.scene);
  const core::Run asleep = core::simulate<TypeParam>(with_sleep(c.scene));
  ASSERT_FALSE(awake.error || asleep.error);
  EXPECT_EQ(awake.counters.count("sleep_islands"), 0u) << "sleep counters only where the scene asks for sleeping";
  const core::StackVerdict v = c.evaluate(asleep);
  EXPECT_TRUE(v.pass) << v.first_failure;
  // The five cubes sleep as one island, once, and stay asleep: the drops
  // settle within the first second (kStackSettle), so at least 1.5 s asleep.
  EXPECT_EQ(asleep.count("sleep_islands"), 1u);
  EXPECT_EQ(asleep.count("sleep_woken_by_touch") + asleep.count("sleep_woken_by_force"), 0u);
  EXPECT_GE(asleep.count("sleeping_body_steps"), 5u * 1500u);
  for (const auto& b : asleep.samples.back().bodies) EXPECT_EQ(b.velocity.norm() + b.angular_velocity.norm(), 0.0);
  EXPECT_LE(largest_offset(asleep, awake), core::kStackDrift);
  // What it saves: no gravity term and no narrowphase pair for a sleeping body.
  EXPECT_LT(asleep.count("effect_gravity_terms"), awake.count("effect_gravity_terms") / 2);
  EXPECT_LT(asleep.count("narrowphase_pairs"), awake.count("narrowphase_pairs") / 2);
}

TYPED_TEST_P(SleepCases, ACubeLetGoAboveTheSleepingColumnWakesIt) {
  core::StackCase c = sleep_stack("column/cubes/5", 4.0);
  // A sixth cube held 5 cm above the column's top by a force that balances
  // its weight until t = 1.8 s (by when the column has slept), then let go.
  core::Body top = c.scene.bodies.back();
  top.name = "held";
  top.position.z() += 0.25;
  c.scene.bodies.push_back(top);
  const double weight = 9.81 * top.mass.value();
  c.scene.effects.push_back(core::AppliedForces{{core::AppliedForce{"held", {0, 0, 0}, {0, 0, weight}, 0.0, 1.8}}});
  const core::Run awake = core::simulate<TypeParam>(c.scene);
  const core::Run asleep = core::simulate<TypeParam>(with_sleep(c.scene));
  ASSERT_FALSE(awake.error || asleep.error);
  EXPECT_GE(asleep.count("sleep_woken_by_touch"), 1u);
  EXPECT_GE(asleep.count("sleep_redetections"), 1u);
  // Asleep before the drop (the column), and again after it (all six).
  EXPECT_GE(asleep.count("sleep_islands"), 2u);
  EXPECT_EQ(asleep.samples.back().bodies.back().velocity.norm(), 0.0);
  EXPECT_LE(largest_offset(asleep, awake), core::kStackDrift);
}

TYPED_TEST_P(SleepCases, AnAppliedForceWakesTheBodyItPushes) {
  core::StackCase c = sleep_stack("column/cubes/2", 3.0);
  const core::Body& top = c.scene.bodies.back();
  // 1.5 weights for 0.1 s from t = 1.5 s: the top cube lifts about 4 cm and
  // lands back on the lower one.
  c.scene.effects.push_back(
      core::AppliedForces{{core::AppliedForce{top.name, {0, 0, 0}, {0, 0, 1.5 * 9.81 * top.mass.value()}, 1.5, 1.6}}});
  const core::Run awake = core::simulate<TypeParam>(c.scene);
  const core::Run asleep = core::simulate<TypeParam>(with_sleep(c.scene));
  ASSERT_FALSE(awake.error || asleep.error);
  EXPECT_EQ(asleep.count("sleep_woken_by_force"), 1u);
  EXPECT_GE(asleep.count("sleep_islands"), 2u);
  EXPECT_LE(largest_offset(asleep, awake), core::kStackDrift);
  // The lift happened in the sleeping run too: the top cube was above its rest at some sample.
  double highest = -INFINITY;
  for (const auto& s : asleep.samples) highest = std::max(highest, s.bodies.back().position.z() - c.rest.back().z());
  EXPECT_GT(highest, 0.01);
}

REGISTER_TYPED_TEST_SUITE_P(SleepCases, ASettledColumnSleepsWhereTheAwakeColumnRests,
                            ACubeLetGoAboveTheSleepingColumnWakesIt, AnAppliedForceWakesTheBodyItPushes);

}  // namespace gacompare::testing
