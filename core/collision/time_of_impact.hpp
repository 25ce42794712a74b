#pragma once
// The time-of-impact searches (§2.5.1, §4.3, §4.3.1), written once
// over a depth oracle: depth(t) is the deepest separating-axis depth of the
// pairs that went too deep, at time t (the island re-integrated to t, or its
// bodies' poses interpolated to t: core/collision/collision_step.hpp). They look for a
// time in (lo, hi) where the depth is in (0, tol], starting from a bracket
// with depth(lo) ≤ tol < depth(hi):
//
//   bisection        §2.5.1, the report's: halve the bracket.
//   illinois         regula falsi with the Illinois modification (§4.3's
//                    "better search techniques"): the secant through the
//                    bracket's ends, the kept end's value halved when it is
//                    kept twice, so it converges superlinearly without
//                    stalling at one end.
//   golden_section   §4.3.1's suggestion, done as the report describes it: a
//                    line search minimising |depth − aim|, which is unimodal
//                    when the depth grows through the step. The bracket
//                    shrinks by 0.618 per evaluation (bisection: 0.5), so it
//                    needs more evaluations than bisection for a root; the
//                    report proposes it for minimising a distance
//                    (bench/time_of_impact_sweep.cpp measures what it costs here).
//   conservative_advancement  Mirtich's (1996) advancement: from lo, step
//                    forward by (aim − depth) / v, v an upper bound of how
//                    fast any pair can close (the sum of the two bodies' rim
//                    speeds), so no pair ever passes aim; converges from
//                    outside, one evaluation per step, never overshooting.
//
// Every search aims at aim, near the top of the band (see Searched::aim): the
// later the accepted time, the more a search advances, since a resting body
// sinks ½ g h² per step and needs one search per (tol − depth) it may sink.
#include "core/model/scene.hpp"

#include <cmath>
#include <cstdint>

namespace gacompare::core {

inline constexpr int kMaxImpactIterations = 60;  // time-of-impact trials per search (2⁻⁶⁰ of a step)

struct ImpactSearch {
  TimeOfImpact method = TimeOfImpact::bisection;
  double tol = 0;           // the penetration tolerance: the band is (0, tol]
  double closing_speed = 0; // conservative advancement: an upper bound of d depth / dt
};

struct Searched {
  bool found = false;
  double t = 0;         // in the band when found
  int iterations = 0;   // depth evaluations
};

// The depth to aim at inside the band: 80 % of the way from the start's depth
// (or 0) to the tolerance.
inline double impact_aim(double tol, double g_lo) { return tol - 0.2 * (tol - std::max(g_lo, 0.0)); }

// depth(double t) -> double. g_lo = depth(lo) ≤ tol, g_hi = depth(hi) > tol.
template <class Depth>
Searched search_impact(const ImpactSearch& s, Depth&& depth, double lo, double hi, double g_lo, double g_hi) {
  Searched out;
  const double aim = impact_aim(s.tol, g_lo);
  const auto in_band = [&](double g) { return g > 0 && g <= s.tol; };
  const auto probe = [&](double t) {
    ++out.iterations;
    return depth(t);
  };
  if (s.method == TimeOfImpact::golden_section) {
    constexpr double r = 0.6180339887498949;  // (√5 − 1) / 2
    double a = lo, b = hi;
    double c = b - r * (b - a), d = a + r * (b - a);
    double gc = probe(c);
    if (in_band(gc)) return {true, c, out.iterations};
    double gd = probe(d);
    if (in_band(gd)) return {true, d, out.iterations};
    while (out.iterations < kMaxImpactIterations) {
      if (std::abs(gc - aim) < std::abs(gd - aim)) {
        b = d, d = c, gd = gc;
        c = b - r * (b - a);
        gc = probe(c);
        if (in_band(gc)) return {true, c, out.iterations};
      } else {
        a = c, c = d, gc = gd;
        d = a + r * (b - a);
        gd = probe(d);
        if (in_band(gd)) return {true, d, out.iterations};
      }
    }
    return out;
  }
  if (s.method == TimeOfImpact::conservative_advancement && s.closing_speed > 0) {
    double t = lo, g = g_lo;
    while (out.iterations < kMaxImpactIterations) {
      const double next = t + (aim - g) / s.closing_speed;
      if (!(next > t) || next >= hi) break;  // no progress left in the step: bisect what remains
      const double gn = probe(next);
      if (in_band(gn)) return {true, next, out.iterations};
      if (gn > s.tol) {  // the bound was not one (it cannot be, for a true bound): bracket and bisect
        hi = next, g_hi = gn;
        break;
      }
      t = next, g = gn;
    }
    lo = t, g_lo = g;
  }
  // Bisection and Illinois (and what conservative advancement leaves).
  int side = 0;  // Illinois: which end was kept last (−1 lo, +1 hi)
  double f_lo = g_lo - aim, f_hi = g_hi - aim;
  while (out.iterations < kMaxImpactIterations) {
    double tm = 0.5 * (lo + hi);
    if (s.method == TimeOfImpact::illinois) {
      const double secant = hi - f_hi * (hi - lo) / (f_hi - f_lo);
      if (secant > lo && secant < hi) tm = secant;
    }
    const double gm = probe(tm);
    if (gm > s.tol) {
      hi = tm, f_hi = gm - aim;
      if (side == +1) f_lo *= 0.5;  // Illinois: the same end kept twice
      side = +1;
    } else if (gm > 0) {
      return {true, tm, out.iterations};
    } else {
      lo = tm, f_lo = gm - aim;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  return out;
}

}  // namespace gacompare::core
