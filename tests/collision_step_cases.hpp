#pragma once
// core/collision_step.hpp through a backend: islands are resolved on their own
// (issue #14). Instantiated by tests/{traditional,cga}/collision_step_test.cpp.
//   - Two drops far apart give, body for body and bit for bit, what each gives
//     alone, and cost exactly the sum of what each costs alone: a time of
//     impact in one island neither rewinds nor shortens the other.
//   - A body spinning too fast for the step limit is shortened only while it
//     has something to hit: alone in the air it takes whole steps.
//   - A body too fast for any step stops the run with one line naming it.
#include "core/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace gacompare::testing {

template <class Backend>
class CollisionStepCases : public ::testing::Test {
 protected:
  static core::Scene drop() {
    return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / "cube_drop_corner.json");
  }
  // The drop moved by dx, its bodies renamed with a suffix.
  static std::vector<core::Body> moved(const core::Scene& s, double dx, const std::string& suffix) {
    std::vector<core::Body> out = s.bodies;
    for (auto& b : out) b.position.x() += dx, b.name += suffix;
    return out;
  }
};
TYPED_TEST_SUITE_P(CollisionStepCases);

TYPED_TEST_P(CollisionStepCases, FarApartIslandsGiveWhatEachGivesAlone) {
  const core::Scene base = this->drop();
  core::Scene a = base, b = base, both = base;
  a.bodies = this->moved(base, 0, "_a");
  b.bodies = this->moved(base, 10, "_b");
  b.bodies[1].angular_velocity = {0, 3, 1};  // so the two islands' impacts fall at other times
  both.bodies = a.bodies;
  both.bodies.insert(both.bodies.end(), b.bodies.begin(), b.bodies.end());
  const core::Run ra = core::simulate<TypeParam>(a), rb = core::simulate<TypeParam>(b),
                  rboth = core::simulate<TypeParam>(both);
  ASSERT_FALSE(ra.error || rb.error || rboth.error);
  ASSERT_EQ(rboth.samples.size(), ra.samples.size());
  ASSERT_GT(ra.counters.at("impact_searches"), 0u);
  ASSERT_GT(rb.counters.at("impact_searches"), 0u);
  // Exactly equal: the islands are integrated and solved alone, the
  // narrowphase works in each pair's own frame, and fixed-step RK4 treats
  // every body's components on their own.
  for (std::size_t k = 0; k < ra.samples.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& alone_a = ra.samples[k].bodies[i];
      const auto& alone_b = rb.samples[k].bodies[i];
      const auto& in_a = rboth.samples[k].bodies[i];
      const auto& in_b = rboth.samples[k].bodies[2 + i];
      EXPECT_EQ(in_a.position, alone_a.position) << "t=" << ra.samples[k].t;
      EXPECT_EQ(in_a.orientation, alone_a.orientation) << "t=" << ra.samples[k].t;
      EXPECT_EQ(in_a.velocity, alone_a.velocity) << "t=" << ra.samples[k].t;
      EXPECT_EQ(in_b.position, alone_b.position) << "t=" << rb.samples[k].t;
      EXPECT_EQ(in_b.angular_velocity, alone_b.angular_velocity) << "t=" << rb.samples[k].t;
    }
  // The searches of one island re-integrate its own bodies only.
  for (const char* counter : {"impact_searches", "impact_state_evaluations", "island_bodies_stepped_alone",
                              "island_steps", "contacts", "impulses"})
    EXPECT_EQ(rboth.counters.at(counter), ra.counters.at(counter) + rb.counters.at(counter)) << counter;
  EXPECT_EQ(rboth.counters.at("collision_steps"), ra.counters.at("collision_steps"));
  EXPECT_EQ(rboth.counters.at("largest_island"), 1u);
}

// A cube spinning at 2000 rad/s: its corners travel 0.35 m in a 1 ms step, 7
// times half its inradius, so near the slab its steps are cut into sub-steps
// (and it must not pass through); 10 m above the slab it has nothing to hit
// and takes whole steps, where the report's loop (and this project's before
// issue #14) shortened every step of every body.
TYPED_TEST_P(CollisionStepCases, StepLimitOnlyWhereThereIsSomethingToHit) {
  core::Scene s = this->drop();
  s.duration = 0.2;
  s.output_every = 0.01;
  s.bodies[1].orientation = {1, 0, 0, 0};
  s.bodies[1].angular_velocity = {0, 0, 2000};
  s.bodies[1].position = {0, 0, 10};
  const core::Run high = core::simulate<TypeParam>(s);
  ASSERT_FALSE(high.error) << *high.error;
  EXPECT_EQ(high.counters.at("collision_steps_shortened"), 0u);
  EXPECT_EQ(high.counters.at("collision_steps"), 200u);
  EXPECT_EQ(high.counters.at("island_steps"), 0u);

  s.bodies[1].position = {0, 0, 0.11};  // 1 cm above the slab, spinning about the vertical
  const core::Run low = core::simulate<TypeParam>(s);
  ASSERT_FALSE(low.error) << *low.error;
  EXPECT_GT(low.counters.at("collision_steps_shortened"), 100u);
  for (const auto& sample : low.samples)
    EXPECT_GT(sample.bodies[1].position.z(), 0.1 - 1e-3) << "through the slab at t=" << sample.t;
}

// 1e12 m/s towards the slab: a sub-step short enough would be 1e-11 of the
// collision step. The run stops at once with a run error naming the body and
// the stage; the samples before it are kept.
TYPED_TEST_P(CollisionStepCases, BodyTooFastForAnyStepStopsTheRunNamingIt) {
  core::Scene s = this->drop();
  s.bodies[1].position = {0, 0, 0.3};
  s.bodies[1].velocity = {0, 0, -1e12};
  const core::Run run = core::simulate<TypeParam>(s);
  ASSERT_TRUE(run.error);
  EXPECT_NE(run.error->find("no progress"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("'cube'"), std::string::npos) << *run.error;
  EXPECT_NE(run.error->find("time_of_impact"), std::string::npos) << *run.error;
  EXPECT_EQ(run.samples.size(), 1u);  // t = 0
}

REGISTER_TYPED_TEST_SUITE_P(CollisionStepCases, FarApartIslandsGiveWhatEachGivesAlone,
                            StepLimitOnlyWhereThereIsSomethingToHit, BodyTooFastForAnyStepStopsTheRunNamingIt);

}  // namespace gacompare::testing
