// The summary's statistics (compare/stats.hpp) against answers computed by
// hand; each tolerance is stated where it is used.
#include "compare/stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gacompare::compare;

namespace {

// Times are sums and quotients of a few doubles: 1e-12 relative covers their rounding.
constexpr double kRounding = 1e-12;

}  // namespace

TEST(TimeWeightedRatio, WeighsScenesByTheirTimeNotOneVoteEach) {
  // A: 1 s against 2 s (ratio 2); B: 9 s against 9 s (ratio 1). The total is
  // 11 s against 10 s: 1.1. The median (or mean) over scenes would say 1.5.
  const std::vector<PairedRepeats> scenes = {{{2, 2}, {1, 1}}, {{9}, {9}}};
  EXPECT_NEAR(time_weighted_ratio(scenes), 1.1, kRounding);
}

TEST(TimeWeightedRatio, MeansOverRepeatsAndOnlyPairedOnes) {
  // Mean cga (2 + 4) / 2 = 3 against mean traditional (1 + 2) / 2 = 1.5: 2. The
  // third cga repeat has no partner and does not count.
  const std::vector<PairedRepeats> scenes = {{{2, 4, 100}, {1, 2}}};
  EXPECT_NEAR(time_weighted_ratio(scenes), 2.0, kRounding);
  EXPECT_TRUE(std::isnan(time_weighted_ratio(std::vector<PairedRepeats>{})));
}

TEST(BootstrapRatio, EqualRatiosGiveAPointInterval) {
  // Every repeat at ratio 2 exactly (doubling is exact in binary): every
  // resample is 2 exactly.
  const std::vector<PairedRepeats> doubled = {{{0.2, 0.6, 1.4, 0.8}, {0.1, 0.3, 0.7, 0.4}}};
  const RatioInterval b = bootstrap_ratio(doubled);
  EXPECT_EQ(b.lo, 2.0);
  EXPECT_EQ(b.hi, 2.0);
}

TEST(BootstrapRatio, TwoRepeatsEnumerated) {
  // Pairs (2 s, 2 s) and (6 s, 3 s). A resample draws two of them: both the
  // first (probability 1/4, ratio 1), one of each (1/2, ratio 8/5), both the
  // second (1/4, ratio 2). The 2.5% and 97.5% quantiles are 1 and 2; the
  // ratio of the data is 8/5. Exact: the chance that fewer than 251 of 10,000
  // resamples fall on an end is nil (binomial, mean 2,500).
  const std::vector<PairedRepeats> s = {{{2, 6}, {2, 3}}};
  const RatioInterval r = bootstrap_ratio(s);
  EXPECT_NEAR(r.ratio, 1.6, kRounding);
  EXPECT_EQ(r.lo, 1.0);
  EXPECT_EQ(r.hi, 2.0);
  EXPECT_EQ(speed_verdict(r), Speed::within_noise);  // it contains 1 (its end)
}

TEST(BootstrapRatio, ManyRepeatsMatchTheNormalInterval) {
  // 400 pairs, traditional 1 s each, cga 2 ± 0.1 s alternating: ratio 2; the
  // resampled mean has standard deviation 0.1 / √400 = 0.005, so the interval
  // is 2 ± 1.96 · 0.005 = [1.9902, 2.0098] (the expansion for n = 400 makes
  // 1.96 into 1.968). Tolerance 0.001 (a tenth of the half-width): the
  // resampled mean moves in steps of 0.0005, and 20,000 resamples place a
  // 2.5% quantile to ±0.0001 (1σ).
  PairedRepeats s;
  for (int i = 0; i < 400; ++i) {
    s.numerator.push_back(i % 2 ? 2.1 : 1.9);
    s.denominator.push_back(1.0);
  }
  const std::vector<PairedRepeats> scenes = {s};
  const RatioInterval r = bootstrap_ratio(scenes);
  EXPECT_NEAR(r.ratio, 2.0, kRounding);
  EXPECT_NEAR(r.lo, 2 - 1.96 * 0.005, 1e-3);
  EXPECT_NEAR(r.hi, 2 + 1.96 * 0.005, 1e-3);
  EXPECT_EQ(speed_verdict(r), Speed::slower);
}

TEST(BootstrapRatio, ResamplesWithinEachSceneAndKeepsPairs) {
  // Scene A's repeats all at ratio 2 and scene B's all at 1, with different
  // times per repeat: resampling within scenes, pairs kept, each resample's
  // A part is 2 × its traditional time and B's equal; the ratio varies only
  // with how much of the total A draws. A: traditional 1 or 3 s (mean 2, the
  // resample's mean 1, 2 or 3); B: 8 s always. Ratio (2a + 8)/(a + 8) for
  // a = 1, 2, 3: 10/9, 12/10, 14/11, with probabilities 1/4, 1/2, 1/4.
  const std::vector<PairedRepeats> scenes = {{{2, 6}, {1, 3}}, {{8, 8}, {8, 8}}};
  const RatioInterval r = bootstrap_ratio(scenes);
  EXPECT_NEAR(r.ratio, 12.0 / 10.0, kRounding);
  EXPECT_NEAR(r.lo, 10.0 / 9.0, kRounding);
  EXPECT_NEAR(r.hi, 14.0 / 11.0, kRounding);
}

TEST(BootstrapRatio, StudentQuantileAndExpandedTail) {
  // Reference values: Boost.Math's students_t quantile at 0.975 (6 decimals);
  // beyond the table the expansion is held to 1e-5.
  EXPECT_NEAR(student_t975(4), 2.776445, 1e-6);
  EXPECT_NEAR(student_t975(30), 2.042272, 1e-6);
  EXPECT_NEAR(student_t975(31), 2.039513, 1e-5);
  EXPECT_NEAR(student_t975(40), 2.021075, 1e-5);
  EXPECT_NEAR(student_t975(100), 1.983972, 1e-5);
  EXPECT_NEAR(student_t975(1000), 1.962339, 1e-5);
  // n = 5: Φ(−√(5/4) · 2.776445) = Φ(−3.104163) = 0.000954 (by hand: erfc).
  EXPECT_NEAR(expanded_tail(5), 0.000954, 1e-6);
  EXPECT_NEAR(expanded_tail(100000), 0.025, 1e-4);
  EXPECT_TRUE(std::isnan(expanded_tail(1)));
  // One repeat: no interval, so no verdict.
  const std::vector<PairedRepeats> one = {{{3}, {2}}};
  EXPECT_EQ(speed_verdict(bootstrap_ratio(one)), Speed::unknown);
}

TEST(BootstrapRatio, CoverageWithFiveRepeats) {
  // 400 sets of 5 paired repeats, each time exp(d + e) with e ~ N(0, 0.05) of
  // its own and d ~ N(0, 0.05) shared by the pair: the true ratio is 1. The
  // interval should hold it about 95% of the time; the expanded interval does
  // about 91% (1,000 sets, 20,000 resamples), the plain percentile interval
  // about 83%. Bounds: 3σ of a binomial over 400 sets (±4.3%) around those.
  std::mt19937_64 g(42);
  std::normal_distribution<double> noise(0, 0.05);
  int expanded = 0, plain = 0;
  const int sets = 400;
  for (int k = 0; k < sets; ++k) {
    PairedRepeats p;
    for (int i = 0; i < 5; ++i) {
      const double d = noise(g);
      p.numerator.push_back(std::exp(d + noise(g)));
      p.denominator.push_back(std::exp(d + noise(g)));
    }
    const std::vector<PairedRepeats> s = {p};
    const RatioInterval a = bootstrap_ratio(s, 4000, k + 1), b = bootstrap_ratio(s, 4000, k + 1, 0.025);
    expanded += a.lo <= 1 && 1 <= a.hi;
    plain += b.lo <= 1 && 1 <= b.hi;
  }
  EXPECT_NEAR(expanded / double(sets), 0.91, 0.043);
  EXPECT_NEAR(plain / double(sets), 0.83, 0.056);
  EXPECT_GT(expanded, plain);
}

TEST(BootstrapRatio, FixedSeedIsReproducibleAndTheSeedIsAParameter) {
  const std::vector<PairedRepeats> s = {{{1.0, 1.3, 0.9, 1.2, 1.05}, {1.0, 1.1, 1.0, 1.0, 1.02}}};
  const RatioInterval a = bootstrap_ratio(s), b = bootstrap_ratio(s);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  // Another seed gives the same interval to Monte-Carlo error (the ends are
  // resampled ratios of 5 draws: at most a few hundredths apart here).
  const RatioInterval c = bootstrap_ratio(s, kBootstrapResamples, 12345);
  EXPECT_NEAR(a.lo, c.lo, 0.02);
  EXPECT_NEAR(a.hi, c.hi, 0.02);
  EXPECT_LE(a.lo, a.ratio);
  EXPECT_GE(a.hi, a.ratio);
}

TEST(SpeedVerdict, WithinNoiseWheneverTheIntervalContainsOne) {
  EXPECT_EQ(speed_verdict({1.4, 0.98, 1.9}), Speed::within_noise);  // a large ratio that spans 1 is still noise
  EXPECT_EQ(speed_verdict({1.0, 1.0, 1.2}), Speed::within_noise);
  EXPECT_EQ(speed_verdict({1.02, 1.001, 1.05}), Speed::slower);
  EXPECT_EQ(speed_verdict({0.9, 0.85, 0.999}), Speed::faster);
  EXPECT_EQ(speed_verdict({}), Speed::unknown);
  EXPECT_EQ(to_string(Speed::within_noise, "cga"), "within noise");
  EXPECT_EQ(to_string(Speed::faster, "pga"), "pga faster");  // the numerator's word
}

TEST(BootstrapUnpairedRatio, TwoRepeatsEachEnumerated) {
  // Before (1 s, 3 s): a resample's median (of two draws: their mean) is 1, 2
  // or 3 (probabilities 1/4, 1/2, 1/4); after (2 s, 2 s) always 2. The ratio of the data is 2 / 2 = 1; the
  // resampled ratios are 2, 1 and 2/3. With 2 repeats the expanded tail is
  // 4e-73 (√2 · t(0.975, 1) = 17.97 standard deviations), so the ends are the
  // smallest and largest resample: 2/3 and 2, both drawn (the chance that
  // 20,000 resamples miss one is 0.75^20000).
  const std::vector<double> before = {1, 3}, after = {2, 2};
  const RatioInterval r = bootstrap_unpaired_ratio(before, after);
  EXPECT_NEAR(r.ratio, 1.0, kRounding);
  EXPECT_NEAR(r.lo, 2.0 / 3.0, kRounding);
  EXPECT_NEAR(r.hi, 2.0, kRounding);
}

TEST(BootstrapUnpairedRatio, ThreeRepeatsReachTheExtremes) {
  // Before (1, 2, 4) s, after (3, 5, 6) s: the ratio of the medians is 5 / 2.
  // A resample's median is 4 with probability 7/27 (two or three of three
  // draws), 1 likewise, so the most extreme ratios, 3/4 and 6/1, each come up
  // with probability (7/27)² = 6.7%, and 20,000 resamples draw them. With 3
  // repeats the expanded tail is 7e-8 (√1.5 · t(0.975, 2) = 5.3 standard
  // deviations): the ends are those extremes, exactly.
  const std::vector<double> before = {1, 2, 4}, after = {3, 5, 6};
  const RatioInterval r = bootstrap_unpaired_ratio(before, after);
  EXPECT_NEAR(r.ratio, 2.5, kRounding);
  EXPECT_NEAR(r.lo, 0.75, kRounding);
  EXPECT_NEAR(r.hi, 6.0, kRounding);
}

TEST(BootstrapUnpairedRatio, OneSlowRepeatDoesNotHideASlowdown) {
  // Nine repeats each, B 1.3 times A's, and one of A's 20 times slower than
  // the rest (what a loaded machine does): the medians see through it. A
  // resampled median of A's is one of its ordinary repeats (0.96 to 1.04 s)
  // unless 5 of 9 draws hit the slow one (probability 1.5e-3, below the
  // expanded tail of 7e-3 at n = 9), and B's is 1.3 times one of them, so the
  // interval lies within [1.3 · 0.96 / 1.04, 1.3 · 1.04 / 0.96] = [1.2, 1.41]:
  // wholly above 1. (The ratio of the means is 0.42 here: "faster".)
  std::vector<double> a, b;
  for (int i = 0; i < 9; ++i) {
    const double t = 0.96 + 0.01 * i;  // 0.96 .. 1.04 s
    a.push_back(i == 4 ? 20 * t : t);
    b.push_back(1.3 * t);
  }
  const RatioInterval r = bootstrap_unpaired_ratio(a, b);
  EXPECT_GE(r.lo, 1.3 * 0.96 / 1.04 - kRounding) << r.lo;
  EXPECT_LE(r.hi, 1.3 * 1.04 / 0.96 + kRounding) << r.hi;
  EXPECT_NEAR(r.ratio, 1.3 / 1.01, kRounding);  // medians: B's 1.3 · 1.00, A's 1.01 (its 1.00 is the slow one)
  EXPECT_EQ(speed_verdict(r), Speed::slower);  // "slower": B over A, whole interval above 1
}

TEST(BootstrapUnpairedRatio, CoverageWithFiveRepeatsEach) {
  // 400 pairs of runs of 5 repeats each, every time exp(e) with e ~ N(0, 0.05)
  // drawn on its own (no pairs: the runs did not share the machine's drift):
  // the true ratio is 1. Measured with 1,000 pairs and 4,000 resamples, the
  // interval held it 99.6% of the time (3 repeats each: 90%; 9: 99.6%): the
  // median of 5 resampled moves in coarse steps, so the interval errs wide.
  // Bound: 3σ of a binomial over 400 below 0.996 (0.0095), rounded down.
  std::mt19937_64 g(7);
  std::normal_distribution<double> noise(0, 0.05);
  int held = 0;
  const int sets = 400;
  for (int k = 0; k < sets; ++k) {
    std::vector<double> a, b;
    for (int i = 0; i < 5; ++i) {
      a.push_back(std::exp(noise(g)));
      b.push_back(std::exp(noise(g)));
    }
    const RatioInterval r = bootstrap_unpaired_ratio(a, b, 4000, k + 1);
    held += r.lo <= 1 && 1 <= r.hi;
  }
  EXPECT_GE(held / double(sets), 0.985);
}

TEST(BootstrapUnpairedRatio, OneRepeatHasNoInterval) {
  const std::vector<double> one = {2}, five = {1, 1, 1, 1, 1};
  const RatioInterval r = bootstrap_unpaired_ratio(one, five);
  EXPECT_NEAR(r.ratio, 0.5, kRounding);
  EXPECT_TRUE(std::isnan(r.lo));
  EXPECT_EQ(speed_verdict(r), Speed::unknown);
}

// The bootstrap's linear-time median is the sorted median, bit for bit: odd and
// even counts, ties, and values whose mean of the middle two rounds.
TEST(MedianInPlace, IsTheSortedMedian) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t n = 1; n <= 64; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> v(n);
      for (auto& x : v) x = trial % 4 == 0 ? std::floor(4 * u(rng)) : u(rng) * 1e-3;  // every 4th: many ties
      std::vector<double> w = v;
      EXPECT_EQ(median_in_place(w), spread(v).median) << n << " values, trial " << trial;
    }
}
