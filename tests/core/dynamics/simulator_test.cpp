// Backend-neutral parts of the simulator: output times and state checks.
#include "core/dynamics/simulator.hpp"

#include <gtest/gtest.h>

namespace gacompare::core {
namespace {

Scene timed(double duration, double every) {
  Scene s;
  s.duration = duration;
  s.output_every = every;
  return s;
}

TEST(Simulator, OutputTimesIncludeBothEnds) {
  const auto t = output_times(timed(1.0, 0.25));
  EXPECT_EQ(t, (std::vector<double>{0, 0.25, 0.5, 0.75, 1.0}));
  // 0.1 is not exact in binary: 10·0.1 must still give one sample at 1.0, not two.
  const auto u = output_times(timed(1.0, 0.1));
  EXPECT_EQ(u.size(), 11u);
  EXPECT_EQ(u.back(), 1.0);
  // A duration that is not a multiple of the interval still ends on the duration.
  const auto v = output_times(timed(1.0, 0.3));
  EXPECT_EQ(v.size(), 5u);
  EXPECT_DOUBLE_EQ(v[3], 0.9);
  EXPECT_EQ(v.back(), 1.0);
}

TEST(Simulator, FirstNonFiniteNamesTheOwner) {
  const std::vector<std::string> names{"a", "b"};
  std::vector<double> y(12, 1.0);
  EXPECT_EQ(first_nonfinite(y, 6, names, "particle"), "");
  y[7] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(first_nonfinite(y, 6, names, "particle"), "particle 'b'");
}

}  // namespace
}  // namespace gacompare::core
