// core/run.hpp's state hash: equal for equal answers, different for any
// change a determinism check must see (one bit of one double, a counter, the
// stop), and blind to what differs from run to run (timings).
#include "core/run.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gacompare::core {
namespace {

core::Run answer() {
  core::Run r;
  r.backend = "traditional";
  for (int k = 0; k < 3; ++k) {
    Sample s;
    s.t = 0.1 * k;
    s.bodies.resize(2);
    s.bodies[1].position = Vec3(0.25, -1.0 / 3, 2 + k);
    s.bodies[1].orientation = Eigen::Vector4d(std::sqrt(0.5), 0, std::sqrt(0.5), 0);
    s.particles.resize(1);
    s.particles[0].velocity = Vec3(1e-300, 0, -9.81 * s.t);
    r.samples.push_back(s);
  }
  r.counters = {{"responses", 12}, {"time_of_impact_searches", 3}};
  return r;
}

TEST(StateHash, IsTheSameForTheSameAnswerWhateverItsTimings) {
  const core::Run a = answer();
  core::Run b = answer();
  b.wall_seconds = 123;
  { ScopedStage timed(b.profile, Stage::response); }
  b.metrics["largest_cg_residual"] = 1e-9;
  EXPECT_EQ(state_hash(a), state_hash(b));
  EXPECT_EQ(state_hash(a).size(), 64u);
}

TEST(StateHash, SeesOneBitOfOneDouble) {
  const core::Run a = answer();
  core::Run b = answer();
  double& x = b.samples[2].bodies[1].position.y();
  x = std::nextafter(x, 1.0);
  EXPECT_NE(state_hash(a), state_hash(b));
  core::Run c = answer();
  c.samples[0].particles[0].velocity.x() = 0;  // 1e-300 → 0
  EXPECT_NE(state_hash(a), state_hash(c));
  core::Run d = answer();
  d.samples[1].bodies[0].position.x() = -0.0;  // +0.0 → −0.0: equal as numbers, not as bits
  EXPECT_NE(state_hash(a), state_hash(d));
}

TEST(StateHash, SeesCountersTheSolversStepsTheStopAndTheShapeOfTheSamples) {
  const std::string base = state_hash(answer());
  core::Run counter = answer();
  counter.counters["responses"] = 13;
  core::Run added = answer();
  added.counters["sleep_islands"] = 0;
  core::Run stopped = answer();
  stopped.error = "non-finite state";
  core::Run steps = answer();
  steps.solver.steps_accepted = 1;
  core::Run fewer = answer();
  fewer.samples.pop_back();
  core::Run moved = answer();  // a body moved from one sample into the next keeps every number, not the grouping
  moved.samples[1].bodies.pop_back();
  moved.samples[2].bodies.insert(moved.samples[2].bodies.begin(), answer().samples[1].bodies[1]);
  for (const core::Run* r : {&counter, &added, &stopped, &steps, &fewer, &moved}) EXPECT_NE(base, state_hash(*r));
}

}  // namespace
}  // namespace gacompare::core
