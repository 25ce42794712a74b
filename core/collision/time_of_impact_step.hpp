#pragma once
// The time_of_impact stage's driver: on one island whose sub-step ended with
// pairs deeper than the penetration tolerance, the time at which they are in
// the band, found by the searches of core/collision/time_of_impact.hpp over
// the pairs' bodies (collision_step.hpp decides when).
#include "core/collision/collisions.hpp"
#include "core/collision/subsystem.hpp"
#include "core/collision/time_of_impact.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <vector>

namespace gacompare::core {

template <class C>
class TimeOfImpactStep {
 public:
  using Bodies = typename C::BodiesType;
  using State = typename C::State;

  TimeOfImpactStep(const C& c, State& state) : c_(c), s_(state) {}

  // §2.5.1's search, on one island: a time t* in (t, tb) where the deepest
  // contact of the pairs of `d` deeper than tol at tb is in (0, tol]
  // (core/collision/time_of_impact.hpp). The trial poses come from re-integrating the
  // pairs' bodies from (t, yb) for every trial time (impact_motion
  // "integrate", §2.5.1), or from interpolating them between yb and ys in the
  // backend's algebra (§4.3.2's "alternative to recalculating the entire
  // system motion many times"); then the island is integrated once, to the
  // time found, and the search goes on over the island's own motion from the
  // bracket found if that time is not in the band. ys holds the state at tb
  // and, on return, the state at the accepted time, which it returns.
  //
  // Only the pairs' bodies for the trials (the report re-integrates the whole
  // system): within a
  // sub-step no impulse acts and every body's forces are its own, so those
  // bodies move alone as they move in the island — bit for bit with a
  // fixed-step solver, whose steps do not depend on the other bodies. An
  // adaptive solver chooses its steps for them alone, so its time may miss the
  // band on the island's motion; that is what the check after the search
  // catches. A trial then costs the few bodies of the deep pairs, not the
  // island's hundreds.
  double find(Subsystem<Bodies>& a, const Detection& d, double t, const std::vector<double>& yb, double tb,
                std::vector<double>& ys, Profile& profile) const {
    const auto& setup = c_.setup;
    ScopedStage timed(profile, Stage::time_of_impact);
    Profile inner;  // the search's integration and narrowphase count as time of impact
    ++s_.counters.impact_searches;
    // The pairs that went too deep, in the island's numbering. Not every hit:
    // a resting contact already in the band (0, tol] would put the deepest
    // depth in the band at any trial time, and the search would stop short of
    // the impact (halving the sub-step instead of finding it).
    // Nor a pair already deeper than the tolerance at t (an impulse sent a
    // body into one it was not linked to, or a correction pushed it into a
    // third): no earlier time puts it in the band; the response at the time
    // found resolves it (at tb when no other pair went deep). The report's
    // search (§2.5.1) has one pair. Among many, such a pair once made the
    // whole search give up, and a pile's other impacts were taken at tb,
    // millimetres deep (CollisionStepCases.CrowdedBox...).
    const double tol = setup.settings.penetration_tolerance;
    std::vector<std::pair<int, int>> pairs;
    double g_hi = -INFINITY;  // the deepest of the searched pairs at tb
    for (const auto& hit : d.hits) {
      if (hit.sat.depth <= tol) continue;
      const std::vector<std::pair<int, int>> one{{hit.a, hit.b}};
      if (c_.depth_of(s_, a.model, yb, a.group, one, inner) > tol) {
        ++s_.counters.impact_pairs_deep_at_start;
        continue;
      }
      pairs.emplace_back(hit.a, hit.b);
      g_hi = std::max(g_hi, hit.sat.depth);
    }
    if (pairs.empty()) {
      ++s_.counters.unresolved_searches;
      return tb;  // ys already holds the state at tb
    }
    // The pairs' bodies (ascending island indices), as a model of their own.
    std::vector<int> deep_bodies;
    for (const auto& pair : pairs) deep_bodies.push_back(pair.first), deep_bodies.push_back(pair.second);
    std::sort(deep_bodies.begin(), deep_bodies.end());
    deep_bodies.erase(std::unique(deep_bodies.begin(), deep_bodies.end()), deep_bodies.end());
    const auto at = [&](int i) { return static_cast<int>(std::lower_bound(deep_bodies.begin(), deep_bodies.end(), i) - deep_bodies.begin()); };
    std::vector<std::pair<int, int>> deep_pairs;
    for (const auto& pair : pairs) deep_pairs.emplace_back(at(pair.first), at(pair.second));
    std::vector<int> deep_group(deep_bodies.size());
    for (std::size_t k = 0; k < deep_bodies.size(); ++k) deep_group[k] = a.group[static_cast<std::size_t>(deep_bodies[k])];
    Subsystem<Bodies> p(a.model, deep_bodies, a.stride, setup.solver);
    const std::vector<double> pb = p.gather(yb);
    const ImpactSearch how{setup.settings.time_of_impact, tol,
                           closing_speed(a, pairs, yb, ys, tb - t)};
    // Counters: a trial is one depth evaluation of the search; an island
    // integration (impact_state_evaluations) the costly kind.
    std::vector<double> pm;
    const auto alone = [&](double tm) {
      pm = pb;
      p.integrate(t, tm, pm, inner);
      ++s_.counters.impact_iterations;
      s_.counters.impact_bodies_integrated += deep_bodies.size();
      return c_.depth_of(s_, p.model, pm, deep_group, deep_pairs, inner);
    };
    std::vector<double> ym;
    const auto island = [&](double tm) {
      ym = yb;
      a.integrate(t, tm, ym, inner);
      ++s_.counters.impact_evaluations;
      s_.counters.impact_bodies_integrated += a.group.size();
      return c_.depth_of(s_, a.model, ym, a.group, pairs, inner);
    };
    const auto island_trial = [&](double tm) {
      ++s_.counters.impact_iterations;
      return island(tm);
    };
    const double g_lo = c_.depth_of(s_, p.model, pb, deep_group, deep_pairs, inner);  // ≤ tol: see above
    Searched r;
    if (setup.settings.impact_motion == ImpactMotion::integrate) {
      r = search_impact(how, alone, t, tb, g_lo, g_hi);
    } else {
      const auto interpolated = [&](double tm) {
        ++s_.counters.impact_interpolations;
        ++s_.counters.impact_iterations;
        const double s = (tm - t) / (tb - t);
        return c_.depth_at(s_, a.group, pairs, [&](int k) {
          return Bodies::interpolated_pose(a.model, yb, ys, static_cast<std::size_t>(k), s);
        }, inner);
      };
      r = search_impact(how, interpolated, t, tb, g_lo, g_hi);
      if (r.found) {
        const double g = alone(r.t);  // the true motion there
        if (!(g > 0 && g <= how.tol)) {
          ++s_.counters.impact_interpolation_misses;
          r = search_again(how, alone, t, tb, g_lo, g_hi, r.t, g);
        }
      } else {
        r = search_impact(how, alone, t, tb, g_lo, g_hi);
      }
    }
    // The island once, to the time found; the search again over the
    // island's own motion if there the pairs are not in the band.
    if (r.found && r.t - t > 1e-6 * (tb - t)) {
      const double g = island(r.t);
      if (!(g > 0 && g <= how.tol)) {
        ++s_.counters.impact_island_misses;
        r = search_again(how, island_trial, t, tb, g_lo, g_hi, r.t, g);
      }
    }
    // No time in the band, or one so close to t that the search would make
    // no progress (Zeno): take the whole sub-step; response and correction
    // resolve the depth. Progress is then always at least one sub-step.
    if (r.found && r.t - t <= 1e-6 * (tb - t)) r.found = false;
    if (!r.found) {
      ++s_.counters.unresolved_searches;
      return tb;  // ys already holds the state at tb
    }
    ys.swap(ym);
    return r.t;
  }

 private:
  // A time tm found on one motion whose depth g on another is not in the band:
  // the search over the other motion, from the bracket (lo, hi) that tm
  // narrows (tm becomes hi if the pairs are too deep there, else lo).
  template <class Depth>
  static Searched search_again(const ImpactSearch& how, Depth&& depth, double lo, double hi, double g_lo, double g_hi,
                               double tm, double g) {
    (g > how.tol ? hi : lo) = tm;
    (g > how.tol ? g_hi : g_lo) = g;
    return search_impact(how, depth, lo, hi, g_lo, g_hi);
  }

  // Conservative advancement's bound of how fast the pairs' depth can grow:
  // the largest sum of the two bodies' rim speeds, each the larger at the
  // interval's two ends plus what its acceleration (Collider::acceleration)
  // adds over it.
  double closing_speed(const Subsystem<Bodies>& a, const std::vector<std::pair<int, int>>& pairs, const std::vector<double>& yb,
                       const std::vector<double>& ys, double h) const {
    if (c_.setup.settings.time_of_impact != TimeOfImpact::conservative_advancement) return 0;
    const auto rim = [&](int k) {
      const auto b = static_cast<std::size_t>(k);
      if (c_.setup.is_static[a.group[b]]) return 0.0;
      return std::max(c_.rim_speed(a.model, yb, a.group, b), c_.rim_speed(a.model, ys, a.group, b)) +
             c_.acceleration(a.group[b]) * h;
    };
    double most = 0;
    for (const auto& [i, j] : pairs) most = std::max(most, rim(i) + rim(j));
    return most;
  }

  const C& c_;
  State& s_;
};

}  // namespace gacompare::core
