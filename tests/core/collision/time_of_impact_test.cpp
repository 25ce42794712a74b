// core/collision/time_of_impact.hpp: the four searches on depth functions whose root is
// known, against the band (0, tol] they must land in and the number of depth
// evaluations their convergence rates predict.
#include "core/collision/time_of_impact.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gacompare::core {
namespace {

constexpr double kTol = 1e-4;

struct Counted {
  int calls = 0;
  double worst = -INFINITY;  // the deepest probe: conservative advancement never passes its aim
};

template <class F>
Searched run(TimeOfImpact m, F&& g, Counted& c, double closing = 0) {
  const ImpactSearch s{m, kTol, closing};
  auto probe = [&](double t) {
    ++c.calls;
    const double d = g(t);
    c.worst = std::max(c.worst, d);
    return d;
  };
  return search_impact(s, probe, 0.0, 1.0, g(0.0), g(1.0));
}

// Contact at t = 0.37 of the step, closing at 0.05 m per step: bracket depths
// −0.0185 and 0.0315. Every method lands in the band, with as many calls as
// the search reports.
TEST(TimeOfImpact, EveryMethodLandsInTheBand) {
  const auto g = [](double t) { return 0.05 * (t - 0.37); };
  for (const auto m : {TimeOfImpact::bisection, TimeOfImpact::illinois, TimeOfImpact::golden_section,
                       TimeOfImpact::conservative_advancement}) {
    Counted c;
    const Searched r = run(m, g, c, 0.05);
    ASSERT_TRUE(r.found) << static_cast<int>(m);
    EXPECT_GT(g(r.t), 0);
    EXPECT_LE(g(r.t), kTol);
    EXPECT_EQ(r.iterations, c.calls);
  }
}

// What each method's convergence predicts on that line. Bisection: the band
// is tol / 0.05 = 2e-3 of the step wide, so log2(1 / 2e-3) ≈ 9 halvings at
// most. Golden section shrinks by 0.618 per call: at most log(2e-3)/log(0.618)
// ≈ 13 calls. Illinois on a straight line: its first secant is the root's
// aim (one call). Conservative advancement with the exact closing speed: one
// step to the aim.
TEST(TimeOfImpact, EvaluationsFollowEachMethodsConvergence) {
  const auto g = [](double t) { return 0.05 * (t - 0.37); };
  Counted bis, ill, gold, ca;
  EXPECT_LE(run(TimeOfImpact::bisection, g, bis).iterations, 9);
  EXPECT_EQ(run(TimeOfImpact::illinois, g, ill).iterations, 1);
  EXPECT_LE(run(TimeOfImpact::golden_section, g, gold).iterations, 14);
  EXPECT_EQ(run(TimeOfImpact::conservative_advancement, g, ca, 0.05).iterations, 1);
}

// A curved approach (decelerating: depth grows as a square root) with the
// closing bound its fastest rate, g'(0) = 0.02 / (2 √0.01) = 0.1 per step, 7
// times the rate at contact (t = 0.5): conservative advancement takes more
// steps but never probes a depth above its aim, and still lands in the band.
TEST(TimeOfImpact, ConservativeAdvancementNeverOvershoots) {
  const auto g = [](double t) { return 0.02 * (std::sqrt(t + 0.01) - std::sqrt(0.51)); };
  Counted c;
  const Searched r = run(TimeOfImpact::conservative_advancement, g, c, 0.1);
  ASSERT_TRUE(r.found);
  EXPECT_GT(g(r.t), 0);
  EXPECT_LE(c.worst, impact_aim(kTol, g(0.0)) + 1e-18);
  EXPECT_GT(r.iterations, 3);
}

// A depth that jumps across the band (a face arriving edge-on within one
// trial's rounding): no time is in (0, tol], every method gives up after
// kMaxImpactIterations calls, and says so.
TEST(TimeOfImpact, NoTimeInTheBandIsReportedNotFound) {
  const auto g = [](double t) { return t < 0.5 ? -1.0 : 1.0; };
  for (const auto m : {TimeOfImpact::bisection, TimeOfImpact::illinois, TimeOfImpact::golden_section,
                       TimeOfImpact::conservative_advancement}) {
    Counted c;
    const Searched r = run(m, g, c, 1.0);
    EXPECT_FALSE(r.found) << static_cast<int>(m);
    EXPECT_LE(r.iterations, kMaxImpactIterations);
  }
}

}  // namespace
}  // namespace gacompare::core
