#pragma once
// Medians with their spread: how every timing in a report is quoted. And the
// statistics of the summary's verdict: a time-weighted ratio of two backends'
// times (cga/traditional, pga/traditional, pga/cga) over scenes with a
// bootstrap interval over paired repeats.
#include <algorithm>
#include <string>
#include <string_view>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace gacompare::compare {

struct Spread {
  double median = 0, min = 0, max = 0;
};

inline Spread spread(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {med, v.front(), v.back()};
}

// spread(v).median, the same number, in linear time (v is reordered): the
// bootstrap takes 20,000 medians a line.
inline double median_in_place(std::vector<double>& v) {
  if (v.empty()) return 0;
  const std::size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2), v.end());
  if (n % 2) return v[n / 2];
  const double below = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2));
  return 0.5 * (below + v[n / 2]);
}

// One scene's (or one stage's) times of two backends, seconds per repeat: the
// numerator's (cga in cga/traditional) and the denominator's; repeat i of each
// ran back to back, so they form a pair. Only the first
// min(numerator.size(), denominator.size()) repeats count.
struct PairedRepeats {
  std::vector<double> numerator, denominator;
  std::size_t pairs() const { return std::min(numerator.size(), denominator.size()); }
};

// Σ over scenes of the mean numerator time / Σ of the mean denominator time:
// the ratio of the total time, i.e. each scene's ratio weighted by its
// denominator time (Σ w_s r_s with w_s = t_s / Σ t). A 33 µs scene weighs as
// little as it costs next to a 15 s one; a median over scenes would weigh them
// alike. NaN when there is no denominator time.
inline double time_weighted_ratio(std::span<const PairedRepeats> scenes) {
  double num = 0, den = 0;
  for (const auto& s : scenes) {
    const std::size_t n = s.pairs();
    if (n == 0) continue;
    double c = 0, t = 0;
    for (std::size_t i = 0; i < n; ++i) c += s.numerator[i], t += s.denominator[i];
    num += c / static_cast<double>(n);
    den += t / static_cast<double>(n);
  }
  return den > 0 ? num / den : NAN;
}

// Student's t 97.5% quantile for ν degrees of freedom: tabulated to ν = 30
// (Boost.Math's quantile, to 6 decimals), beyond by the Cornish–Fisher
// expansion (Abramowitz & Stegun 26.7.5), within 1e-5 there.
inline double student_t975(int nu) {
  static constexpr double table[] = {12.706205, 4.302653, 3.182446, 2.776445, 2.570582, 2.446912, 2.364624, 2.306004,
                                     2.262157,  2.228139, 2.200985, 2.178813, 2.160369, 2.144787, 2.131450, 2.119905,
                                     2.109816,  2.100922, 2.093024, 2.085963, 2.079614, 2.073873, 2.068658, 2.063899,
                                     2.059539,  2.055529, 2.051831, 2.048407, 2.045230, 2.042272};
  if (nu < 1) return NAN;
  if (nu <= 30) return table[nu - 1];
  const double z = 1.959963984540054, v = nu, z2 = z * z;
  const double g1 = (z2 + 1) * z / 4, g2 = ((5 * z2 + 16) * z2 + 3) * z / 96,
               g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384,
               g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
  return z + (g1 + (g2 + (g3 + g4 / v) / v) / v) / v;
}

// The tail probability of Hesterberg's expanded percentile interval for n
// repeats: α' with Φ⁻¹(α') = −√(n/(n−1)) t(0.975, n−1) (T. Hesterberg, "What
// teachers should know about the bootstrap", The American Statistician 69(4),
// 2015). The plain percentile interval (α' = 0.025) takes the repeats seen for
// all there are and is too narrow with few. Simulated (1,000 sets of paired
// repeats, 5% lognormal noise each and 5% drift the pair shares, true ratio 1;
// tests/compare/stats_test.cpp repeats it with 400 sets of 5), the expanded
// interval held the true ratio 87%, 91%, 94% and 94% of the time with 4, 5, 6
// and 9 repeats, the plain one 79%, 83%, 87% and 89%; with 3, neither passes
// 74%: no resample goes beyond the most extreme repeat. n = 5 gives
// α' = 0.00095; n → ∞ gives 0.025. NaN for n < 2: one repeat shows no noise.
inline double expanded_tail(int n) {
  if (n < 2) return NAN;
  const double z = std::sqrt(n / (n - 1.0)) * student_t975(n - 1);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// 20,000 resamples: with 5 repeats the interval's ends are the 19th smallest
// and largest resample (α' = 0.00095 above), and 38 other seeds gave the same
// ends on 20 simulated sets (so few distinct ratios lie that far out); with 9
// or 20 repeats the ends moved by 1% of the interval's half-width (standard
// deviation over the seeds). It costs milliseconds. The seed is fixed so the
// same results always give the same interval.
inline constexpr int kBootstrapResamples = 20000;
inline constexpr std::uint64_t kBootstrapSeed = 1;

struct RatioInterval {
  double ratio = NAN;        // time_weighted_ratio of the data
  double lo = NAN, hi = NAN; // 95% expanded percentile bootstrap interval
};

// The interval's ends from the resampled ratios: the k-th smallest and largest,
// k = ⌊tail · B⌋ (none when there are no resamples).
inline void percentile_ends(std::vector<double>& resampled, double tail, RatioInterval& out) {
  if (resampled.empty()) return;
  std::sort(resampled.begin(), resampled.end());
  const std::size_t k = static_cast<std::size_t>(tail * static_cast<double>(resampled.size()));
  out.lo = resampled[k];
  out.hi = resampled[resampled.size() - 1 - k];
}

// The 95% bootstrap interval of time_weighted_ratio: each resample draws,
// within every scene independently, as many repeats as it has, with
// replacement, keeping each numerator repeat with its denominator partner (so the
// drift both shared cancels), and recomputes the ratio; the interval's ends are
// the k-th smallest and largest resample, k = ⌊α' B⌋ with α' =
// expanded_tail(n), n the fewest repeats of any scene. Indices are mt19937_64
// output mod n (its sequence is fixed by the standard, unlike
// std::uniform_int_distribution's; the bias, n/2⁶⁴, is nil). No interval (NaN
// ends) when a scene has fewer than 2 repeats. `tail` replaces α' when given
// (0.025: the plain percentile interval).
inline RatioInterval bootstrap_ratio(std::span<const PairedRepeats> scenes, int resamples = kBootstrapResamples,
                                     std::uint64_t seed = kBootstrapSeed, double tail = NAN) {
  RatioInterval out;
  out.ratio = time_weighted_ratio(scenes);
  std::size_t fewest = 0;
  for (const auto& s : scenes)
    if (s.pairs() > 0) fewest = fewest ? std::min(fewest, s.pairs()) : s.pairs();
  if (fewest < 2) return out;
  if (std::isnan(tail)) tail = expanded_tail(static_cast<int>(fewest));
  if (std::isnan(out.ratio) || std::isnan(tail) || resamples < 1) return out;
  std::mt19937_64 rng(seed);
  std::vector<double> r;
  r.reserve(static_cast<std::size_t>(resamples));
  for (int b = 0; b < resamples; ++b) {
    double num = 0, den = 0;
    for (const auto& s : scenes) {
      const std::size_t n = s.pairs();
      if (n == 0) continue;
      double c = 0, t = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = static_cast<std::size_t>(rng() % n);
        c += s.numerator[i], t += s.denominator[i];
      }
      num += c / static_cast<double>(n);
      den += t / static_cast<double>(n);
    }
    if (den > 0) r.push_back(num / den);
  }
  percentile_ends(r, tail, out);
  return out;
}

// The 95% interval of median(after) / median(before) for two sets of repeats
// that did not run side by side (two runs, two commits, a run and its stored
// baseline: `gacompare diff`, `check --max-time-ratio`). Nothing pairs repeat i
// of one with repeat i of the other, so bootstrap_ratio's pairing would pair
// noise with noise; instead each resample draws each set on its own, as many
// repeats as it has, with replacement (the two-sample bootstrap: Efron &
// Tibshirani, An Introduction to the Bootstrap, 1993, ch. 8), and the ratio of
// the resampled medians is recomputed. Medians, not the means the summary
// uses between backends: runs compared this way were made at different times,
// often on a loaded machine, where one repeat 20 times slower than the rest is
// common (seen here at load 6), and a mean follows it. The interval is the
// expanded percentile one (expanded_tail) with n the smaller set's size.
// Simulated (tests/compare/stats_test.cpp; 1,000 pairs of sets, 5% lognormal
// noise, true ratio 1, 4,000 resamples): it held the ratio 90%, 99.6% and 99.6%
// of the time with 3, 5 and 9 repeats each; with one repeat of 9 made 20
// times slower its interval stayed as narrow (mean log width 0.17 against 0.15)
// where the ratio of means' widened twentyfold (2.3 against 0.11), and it
// still found a true 1.3 every time (the means' never). With 5 repeats one such outlier widens either interval
// past use: run 9 or more on a loaded machine. Drift between the two runs
// (another load, another machine) is not noise this interval can see: it
// reads as a real difference, which it is for the runs compared. NaN ends with
// fewer than 2 repeats in either set.
inline RatioInterval bootstrap_unpaired_ratio(std::span<const double> before, std::span<const double> after,
                                              int resamples = kBootstrapResamples, std::uint64_t seed = kBootstrapSeed) {
  RatioInterval out;
  const auto median = [](std::span<const double> v) {
    return v.empty() ? NAN : spread(std::vector<double>(v.begin(), v.end())).median;
  };
  const double den = median(before);
  out.ratio = den > 0 ? median(after) / den : NAN;
  const std::size_t fewest = std::min(before.size(), after.size());
  if (fewest < 2 || std::isnan(out.ratio) || resamples < 1) return out;
  const double tail = expanded_tail(static_cast<int>(fewest));
  std::mt19937_64 rng(seed);
  std::vector<double> draw;
  const auto resampled_median = [&](std::span<const double> v) {
    draw.clear();
    for (std::size_t k = 0; k < v.size(); ++k) draw.push_back(v[static_cast<std::size_t>(rng() % v.size())]);
    return median_in_place(draw);
  };
  std::vector<double> r;
  r.reserve(static_cast<std::size_t>(resamples));
  for (int b = 0; b < resamples; ++b) {
    const double d = resampled_median(before);
    const double n = resampled_median(after);
    if (d > 0) r.push_back(n / d);
  }
  percentile_ends(r, tail, out);
  return out;
}

// The word for an interval: it must not flip with noise, so a ratio is "within
// noise" whenever its interval contains 1 (ends included), whatever the ratio.
// faster and slower are the numerator's.
enum class Speed { within_noise, faster, slower, unknown };
inline Speed speed_verdict(const RatioInterval& r) {
  if (std::isnan(r.lo) || std::isnan(r.hi)) return Speed::unknown;
  if (r.hi < 1) return Speed::faster;
  if (r.lo > 1) return Speed::slower;
  return Speed::within_noise;
}
// "within noise", "cga faster" (numerator "cga"), "cga slower" or "no verdict".
inline std::string to_string(Speed s, std::string_view numerator) {
  switch (s) {
    case Speed::within_noise: return "within noise";
    case Speed::faster: return std::string(numerator) + " faster";
    case Speed::slower: return std::string(numerator) + " slower";
    case Speed::unknown: break;
  }
  return "no verdict";
}

}  // namespace gacompare::compare
