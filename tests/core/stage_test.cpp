// The stage profiler: nested stages are timed exclusively and counted.
#include "core/stage.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace gacompare::core {
namespace {

void spin(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
  }
}

TEST(Stage, NamesRoundTrip) {
  for (int k = 0; k < kStageCount; ++k) {
    const auto s = static_cast<Stage>(k);
    EXPECT_EQ(stage_from_name(stage_name(s)), s);
  }
  EXPECT_EQ(stage_name(Stage::time_of_impact), "time_of_impact");
  EXPECT_FALSE(stage_from_name("physics").has_value());
}

TEST(Stage, NestedStagesAreExclusive) {
  Profile p;
  const auto t0 = std::chrono::steady_clock::now();
  {
    ScopedStage outer(p, Stage::integrate);
    spin(2e-3);
    for (int i = 0; i < 3; ++i) {
      ScopedStage inner(p, Stage::forces);
      spin(1e-3);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(p[Stage::integrate].calls, 1u);
  EXPECT_EQ(p[Stage::forces].calls, 3u);
  // Exclusive: the outer stage holds its own 2 ms, not the inner 3 ms; the two
  // add up to no more than the wall time around them. (Lower bounds only: a
  // loaded machine can make any spin longer, never shorter.)
  EXPECT_GE(p[Stage::forces].seconds, 3e-3);
  EXPECT_GE(p[Stage::integrate].seconds, 2e-3);
  EXPECT_LE(p.total_seconds(), wall);
  EXPECT_LT(p[Stage::integrate].seconds, wall - p[Stage::forces].seconds + 1e-9);
  EXPECT_FALSE(p.ran(Stage::narrowphase));
}

}  // namespace
}  // namespace gacompare::core
