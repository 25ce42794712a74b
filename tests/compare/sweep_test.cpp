// The sweep's time at equal accuracy (compare/sweep.hpp cost_at_error): a
// backend's cost of reaching an error E read off its own cells, checked on
// cells made from a known power law (exact in log–log) and on the envelope
// rules (a slower, less accurate cell is ignored; nothing is extrapolated).
#include "compare/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gacompare::compare {
namespace {

// time = 1e-3 · E^(−1/4), steps = 10 · E^(−1/4): a 4th-order method's law.
EqualAccuracyPoint law(double e) { return {e, 1e-3 * std::pow(e, -0.25), 10 * std::pow(e, -0.25)}; }

TEST(Sweep, CostAtErrorInterpolatesAPowerLawExactly) {
  const std::vector<EqualAccuracyPoint> cells = {law(1e-2), law(1e-5), law(1e-8), law(1e-11)};
  for (const double e : {1e-2, 3e-4, 1e-6, 2e-9, 1e-11}) {
    const auto at = cost_at_error(cells, e);
    ASSERT_TRUE(at.has_value()) << e;
    // Linear in log error – log time reproduces a power law to rounding (1e-12 relative).
    EXPECT_NEAR(at->time, law(e).time, 1e-12 * law(e).time) << e;
    EXPECT_NEAR(at->steps, law(e).steps, 1e-12 * law(e).steps) << e;
  }
}

TEST(Sweep, CostAtErrorNeverExtrapolates) {
  const std::vector<EqualAccuracyPoint> cells = {law(1e-3), law(1e-6)};
  EXPECT_FALSE(cost_at_error(cells, 1e-2).has_value());
  EXPECT_FALSE(cost_at_error(cells, 1e-7).has_value());
  EXPECT_FALSE(cost_at_error({}, 1e-3).has_value());
}

// A cell slower than a more accurate one is not on the way to any accuracy:
// the cost of E = 1e-4 comes from the cells either side on the envelope.
TEST(Sweep, CostAtErrorReadsTheLowerEnvelope) {
  std::vector<EqualAccuracyPoint> cells = {law(1e-2), law(1e-6)};
  cells.push_back({1e-3, 10 * law(1e-6).time, 1e6});  // slow and inaccurate: ignored
  cells.push_back({0, 1e-9, 1});                      // error 0 (not measurable): ignored
  const auto at = cost_at_error(cells, 1e-4);
  ASSERT_TRUE(at.has_value());
  EXPECT_NEAR(at->time, law(1e-4).time, 1e-12 * law(1e-4).time);
}

// The diagrams' families: the Lie-group methods are one of their own.
TEST(Sweep, LieGroupMethodsAreTheirOwnFamily) {
  for (const char* m : {"rkmk4", "rkmk45", "crouch_grossman4"}) EXPECT_EQ(method_family(m), "Lie group") << m;
  EXPECT_EQ(method_family("cash_karp45"), "classical");
  EXPECT_EQ(method_family("dopri5"), "PI pairs");
  EXPECT_EQ(method_family("odeint_dopri5"), "Odeint");
}

}  // namespace
}  // namespace gacompare::compare
