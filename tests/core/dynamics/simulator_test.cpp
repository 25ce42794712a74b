// Backend-neutral parts of the simulator: output times and state checks.
#include "core/dynamics/simulator.hpp"
#include "../../scoped_threads.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

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

// first_nonfinite looks element by element only when its running sums say
// so: every place (those the sums take four at a time and the tail after
// them, on lengths that are and are not multiples of four) and every kind of
// non-finite value is found, and the largest finite values and −0 are not.
TEST(Simulator, FirstNonFiniteFindsEveryPlaceAndKind) {
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  const auto name = [](std::size_t k) {
    std::string out = std::to_string(k);
    out.insert(0, 1, 'b');  // not "b" + ...: GCC 12 -Wrestrict, bug 105651
    return out;
  };
  for (const std::size_t n : {1u, 3u, 4u, 7u, 12u, 13u}) {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < n; ++k) names.push_back(name(k));
    std::vector<double> y(n, std::numeric_limits<double>::max());
    y[0] = -0.0, y[n - 1] = -std::numeric_limits<double>::max();
    EXPECT_EQ(first_nonfinite(y, 1, names, "body"), "") << n;
    for (std::size_t at = 0; at < n; ++at)
      for (const double v : bad) {
        std::vector<double> z = y;
        z[at] = v;
        EXPECT_EQ(first_nonfinite(z, 1, names, "body"), "body '" + name(at) + "'") << n << " " << v;
      }
  }
}

// The same on the run's threads, where each block of the state is summed on
// its own: a state of 10,000 bodies of 18 doubles (several blocks; with fine
// grains, blocks of 4 doubles) names the first non-finite body whichever
// block holds it and whichever blocks hold others after it.
TEST(Simulator, FirstNonFiniteNamesTheFirstBodyOnAnyThreadCount) {
  constexpr std::size_t kBodies = 10000, kStride = 18;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < kBodies; ++k) names.push_back("body" + std::to_string(k));
  for (const int t : {1, 2})
    for (const bool fine : {false, true}) {
      const gacompare::testing::ScopedThreads threads(t, fine);
      std::vector<double> y(kBodies * kStride, 1.0);
      EXPECT_EQ(first_nonfinite(y, kStride, names, "body"), "");
      y[9000 * kStride + 3] = std::numeric_limits<double>::infinity();
      EXPECT_EQ(first_nonfinite(y, kStride, names, "body"), "body 'body9000'");
      y[4000 * kStride + 17] = std::numeric_limits<double>::quiet_NaN();
      EXPECT_EQ(first_nonfinite(y, kStride, names, "body"), "body 'body4000'");
      y[0] = -std::numeric_limits<double>::infinity();
      EXPECT_EQ(first_nonfinite(y, kStride, names, "body"), "body 'body0'");
    }
}

}  // namespace
}  // namespace gacompare::core
