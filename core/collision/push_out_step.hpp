#pragma once
// The response's push-out, for a response that met a pair deeper than the
// tolerance (core/collision/collision_step.hpp decides when): every deep
// impact without an impact search (the collisions effect's time_of_impact
// "none"), and with one the pairs the search could not put in the band (a
// pair already too deep when its sub-step began, which an impulse sent into
// a body it was not linked to; a search left unresolved).
//
// Without a search an impact is taken where its step ends, millimetres deep,
// and the response's correction is one linear projection computed from the
// contacts found before it. Lifting a deep vertex turns the body, and a turn
// of a few hundredths of a radian drives its neighbouring vertices into the
// face it left, or into a body it was not touching: in the crowded box of
// CollisionStepCases a body 4.2 mm deep in a wall was left 0.4 mm deep, and
// bodies stayed deeper than the tolerance for several steps. So the island
// is detected again and pushed out again (the correction alone, no impulse:
// ContactSolver::push_out), up to kPushOutPasses times: Box2D v2's position
// iterations, which measure each separation again, in spirit.
//
// Which pairs each detection tests: a pair's depth can grow only by how far
// its bodies moved since it was measured. A point of a body moves by at most
// |Δc| + ‖ΔR‖₂ r (c its bounding sphere's centre, r the radius; travel()
// below), so each pair carries an upper bound of
// its depth: measured at its last test, raised by both bodies' motion at
// every response or correction since. Only the pairs whose bound exceeds the
// tolerance are tested. In a pile, where every body of an island of
// thousands touches another, testing every pair of the island after every
// deep response cost most of the run. What a pair's bound starts from:
//   - in contact: its depth;
//   - tested and found apart: its depth, minus the gap along the separating
//     axis the narrowphase found (Detection::gaps); the distance is at least
//     that gap;
//   - not tested (its bounding spheres apart, or the moving body's sphere
//     off the static body's box): r_a + r_b − |c_a − c_b| where below 0,
//     else 0.
// With 0 for every pair found apart, the pile of the 10,000-body box
// re-tested some 20,000 of its 29,000 pairs after each deep response, most of
// them a few millimetres apart: the response's correction moves a thousand
// of its bodies by a tenth of a millimetre or more, the tolerance.
// After the first pass, a pass's bookkeeping reads only what the pass
// changed: the pairs it tested, and the bodies its correction moved and
// their pairs. Passes over the pile's whole island each time were 2 %
// of the 10,000-body box's run's own thread, for a pass that tests a few
// hundred of its 29,000 pairs.
#include "core/collision/collisions.hpp"
#include "core/collision/subsystem.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <span>
#include <vector>

namespace gacompare::core {

// Detections and corrections after a response that left a pair too deep;
// Box2D v2 ran three position iterations. A pair still too deep after them is
// the next step's, and counted (push_out_left_deep).
inline constexpr int kPushOutPasses = 4;

// How far any point of world body w moved from pose p0 to p1, at most:
// |Δc| + ‖ΔR‖₂ r, as above (collision::rotation_change_bound: for rotations
// the Frobenius norm is √2 times the spectral one, and bounding with it had
// the 10,000-body box without a search take 35,000 bodies for escaped in a
// second, and step three islands of up to 8,000 bodies alone). A margin for
// the rounding of the poses and of the sum (far below the tolerance): a
// bound that errs, errs towards testing.
inline double travel(const CollisionSetup& setup, std::size_t w, const collision::Pose& p0, const collision::Pose& p1) {
  const Vec3& c = setup.sphere_centre[w];
  return ((p1.apply(c) - p0.apply(c)).norm() +
          setup.sphere_radius[w] * collision::rotation_change_bound(p0.rotation, p1.rotation)) *
             (1 + 1e-9) +
         1e-15;
}
// The same for body k of group `a` between two of its states: 0 for a body
// whose state is unchanged (most bodies of a large island).
template <class Bodies>
double travel(const CollisionSetup& setup, const Subsystem<Bodies>& a, std::span<const double> from,
              std::span<const double> to, std::size_t k) {
  const auto at = static_cast<long>(k * a.stride);
  if (std::equal(from.begin() + at, from.begin() + at + static_cast<long>(a.stride), to.begin() + at)) return 0.0;
  return travel(setup, static_cast<std::size_t>(a.group[k]), Bodies::pose(a.model, from, k), Bodies::pose(a.model, to, k));
}

template <class C>
class PushOutStep {
 public:
  using Bodies = typename C::BodiesType;
  using State = typename C::State;
  using Pairs = std::vector<std::pair<int, int>>;

  PushOutStep(const C& c, State& state) : c_(c), s_(state) {}

  // For the tests: called at every pass before its pairs are chosen, with
  // each pair's bound and the island's state then.
  std::function<void(int pass, const Pairs& among, const std::vector<double>& bound, const std::vector<double>& ys)>
      on_pass;

  // The island `a` (its candidate pairs `among`, sorted, in its numbering)
  // after a response at time t: `hits` its pairs in contact before the
  // response and `gaps` those the narrowphase found apart then (every other
  // pair of `among` was found apart by its bounding sphere), `before` its
  // state then, `ys` its state after, pushed out on return. `check` is
  // called on the state after every correction (it throws on a non-finite
  // one).
  void run(const Subsystem<Bodies>& a, const Pairs& among, std::span<const PairDepth> hits,
           std::span<const PairDepth> gaps, const std::vector<double>& before, std::vector<double>& ys,
           Profile& profile, const std::function<void(const std::vector<double>&)>& check) const {
    const double tol = c_.setup.settings.penetration_tolerance;
    // A pair's place in `among`, or −1. The lists looked up come in pair
    // order (a detection's hits and gaps follow its pairs), so each search
    // gallops on from the last place found (`last`, one per block of a
    // list): a step or two per pair, where a binary search over a pile's
    // 29,000 pairs missed the cache at each of its fifteen steps. Any order
    // gives the same places.
    const auto index = [&](int i, int j, std::size_t& last) -> long {
      const std::pair key(std::min(i, j), std::max(i, j));
      std::size_t lo = 0, hi = among.size();
      if (last < among.size() && !(key < among[last])) {
        lo = last;
        for (std::size_t step = 1; lo + step < among.size(); step *= 2) {
          if (key < among[lo + step]) {
            hi = lo + step;
            break;
          }
          lo += step;
        }
      }
      const auto at = std::lower_bound(among.begin() + static_cast<long>(lo), among.begin() + static_cast<long>(hi), key);
      if (at == among.end() || *at != key) return -1;
      last = static_cast<std::size_t>(at - among.begin());
      return static_cast<long>(last);
    };
    // Each pair's depth at most; NaN until measured, then the pairs left
    // unmeasured get their bounding spheres' bound (apart_by_spheres).
    std::vector<double> bound(among.size(), kUnmeasured);
    // On the run's threads, a block of the list each: a list names each
    // pair once (a detection's hits and gaps do), so no two items write
    // the same bound.
    const auto measure = [&](const auto& list) {
      for_each_block(list.size(), kGrainBody, [&](std::size_t, std::size_t begin, std::size_t end) {
        std::size_t last = 0;
        for (std::size_t q = begin; q < end; ++q)
          if (const auto k = index(list[q].a, list[q].b, last); k >= 0)
            bound[static_cast<std::size_t>(k)] = depth_bound(measured_depth(list[q]));
      });
    };
    measure(gaps), measure(hits);
    std::vector<std::size_t> everywhere(among.size());
    std::iota(everywhere.begin(), everywhere.end(), std::size_t{0});
    apart_by_spheres(a, before, among, bound, everywhere);
    const Adjacency adjacent(a.group.size(), among);
    std::vector<int> everyone(a.group.size());
    std::iota(everyone.begin(), everyone.end(), 0);
    raise(a, bound, among, adjacent, before, ys, everyone);
    Pairs pairs;
    std::vector<std::size_t> tested;  // the pass's pairs' places in among
    std::vector<int> pushed_bodies;
    // The state before each correction, of the bodies it moves only (raise
    // reads no other): copying the whole island's at every pass was a
    // quarter of a percent of the 10,000-body box's run's own thread, and
    // zeroing it once per push-out (a std::vector of its size) another
    // quarter. Left uninitialised: only the pushed bodies' entries are read.
    const std::unique_ptr<double[]> pushed_state(new double[ys.size()]);
    const std::span<const double> pushed(pushed_state.get(), ys.size());
    for (int pass = 0;; ++pass) {
      if (on_pass) on_pass(pass, among, bound, ys);
      tested.clear();
      append_picked(tested, among.size(), [&](std::size_t k) { return bound[k] > tol; }, [](std::size_t k) { return k; },
                    kGrainLight);
      if (tested.empty()) return;
      pairs.resize(tested.size());
      for_each_index(tested.size(), [&](std::size_t q) { pairs[q] = among[tested[q]], bound[tested[q]] = kUnmeasured; },
                     kGrainLight);
      Detection d = c_.detect_among(s_, a.model, ys, a.group, pairs, profile, kGrainPushOutPair);
      ++s_.counters.push_out_detections;
      measure(d.gaps), measure(d.hits);
      // Only a pair just tested can be unmeasured now.
      apart_by_spheres(a, ys, among, bound, tested);
      if (!(d.max_depth > tol)) return;
      if (pass == kPushOutPasses) return ++s_.counters.push_out_left_deep, void();
      hold_neighbours(a, among, adjacent, ys, tested, bound, d, profile);
      // The correction moves only the bodies of its contacts.
      pushed_bodies.clear();
      for (const PairHit& h : d.hits) pushed_bodies.push_back(h.a), pushed_bodies.push_back(h.b);
      std::ranges::sort(pushed_bodies);
      pushed_bodies.erase(std::unique(pushed_bodies.begin(), pushed_bodies.end()), pushed_bodies.end());
      for (const int b : pushed_bodies) {
        const auto at = static_cast<std::size_t>(b) * a.stride;
        std::copy_n(ys.begin() + static_cast<long>(at), a.stride, pushed_state.get() + at);
      }
      c_.push_out(s_, a.model, ys, a.group, d.hits, profile);
      check(ys);
      raise(a, bound, among, adjacent, pushed, ys, pushed_bodies);
    }
  }

 private:
  static constexpr double kUnmeasured = std::numeric_limits<double>::quiet_NaN();

  // A measured depth as a bound: a non-finite one (none the narrowphase
  // gives a pair it tested) bounds nothing, and counts as 0, the bound of a
  // pair known to be apart.
  static double depth_bound(double depth) { return std::isfinite(depth) ? depth : 0.0; }

  // The bounds of the pairs still unmeasured (NaN) at state y, of those at
  // the places `where` in among: the detection found them apart without a
  // narrowphase test, so r_a + r_b − |c_a − c_b| (their bounding spheres'
  // gap), or 0 where that is not below 0 (the moving body's sphere off a
  // static body's box). Each body's centre is posed once where those pairs
  // are as many as the island's bodies, else per pair.
  void apart_by_spheres(const Subsystem<Bodies>& a, const std::vector<double>& y, const Pairs& among,
                        std::vector<double>& bound, std::span<const std::size_t> where) const {
    const auto& setup = c_.setup;
    const auto centre = [&](int k) {
      return Bodies::pose(a.model, y, static_cast<std::size_t>(k)).apply(setup.sphere_centre[world(a, k)]);
    };
    const auto left =
        static_cast<std::size_t>(std::ranges::count_if(where, [&](std::size_t q) { return std::isnan(bound[q]); }));
    if (left == 0) return;
    std::vector<Vec3> all;
    if (left >= a.group.size()) {
      all.resize(a.group.size());
      for_each_index(a.group.size(), [&](std::size_t k) { all[k] = centre(static_cast<int>(k)); }, kGrainBody);
    }
    // Each place once in `where`: no two items write the same bound.
    for_each_index(where.size(), [&](std::size_t u) {
      const std::size_t q = where[u];
      if (!std::isnan(bound[q])) return;
      const auto [i, j] = among[q];
      const Vec3 ci = all.empty() ? centre(i) : all[static_cast<std::size_t>(i)];
      const Vec3 cj = all.empty() ? centre(j) : all[static_cast<std::size_t>(j)];
      // Rounding of the centres and the sum, ~1e-15 of them, errs towards testing.
      const double r = setup.sphere_radius[world(a, i)] + setup.sphere_radius[world(a, j)];
      bound[q] = std::min(0.0, r - (ci - cj).norm() + 1e-12 * (r + ci.norm() + cj.norm()));
    }, kGrainBody);
  }
  static std::size_t world(const Subsystem<Bodies>& a, int k) {
    return static_cast<std::size_t>(a.group[static_cast<std::size_t>(k)]);
  }

  // Each body's places in among (the pairs it is in), built once per push-out.
  struct Adjacency {
    std::vector<std::size_t> first, pairs;  // body k's pairs: pairs[first[k] .. first[k + 1])
    Adjacency(std::size_t bodies, const Pairs& among) : first(bodies + 1, 0), pairs(2 * among.size()) {
      for (const auto& [i, j] : among) ++first[static_cast<std::size_t>(i) + 1], ++first[static_cast<std::size_t>(j) + 1];
      for (std::size_t k = 0; k < bodies; ++k) first[k + 1] += first[k];
      std::vector<std::size_t> at(first.begin(), first.end() - 1);
      for (std::size_t q = 0; q < among.size(); ++q)
        pairs[at[static_cast<std::size_t>(among[q].first)]++] = q, pairs[at[static_cast<std::size_t>(among[q].second)]++] = q;
    }
  };

  // A pass's correction sees only the pairs it tested, those whose bound
  // passed the tolerance. A body pressed between two others was pushed out
  // of one into the other, untested because it had been within the
  // tolerance, and back at the next pass: a light cube between a heavy one
  // and the slab went 3.9, 3.4, 3.1 mm deep in turn and ended the last pass
  // 2.8 mm in. So the other pairs of each moving body of a deep pair whose
  // bound is above minus the pass's deepest depth (within what the
  // correction moves it) are tested too, and their contacts join the
  // correction, which holds them from approaching (ContactSolver::push_out).
  void hold_neighbours(const Subsystem<Bodies>& a, const Pairs& among, const Adjacency& adjacent,
                       const std::vector<double>& ys, const std::vector<std::size_t>& tested, std::vector<double>& bound,
                       Detection& d, Profile& profile) const {
    const double tol = c_.setup.settings.penetration_tolerance;
    // Flags over the island's pairs, cleared after use: a pile's island
    // holds some 29,000 pairs, a pass a few hundred.
    std::vector<char>& seen = seen_;
    seen.resize(among.size(), 0);
    for (const std::size_t q : tested) seen[q] = 1;
    std::vector<std::size_t> near;
    for (const PairHit& h : d.hits) {
      if (!(h.sat.depth > tol)) continue;
      for (const int b : {h.a, h.b}) {
        const auto k = static_cast<std::size_t>(b);
        if (c_.setup.is_static[world(a, b)]) continue;
        for (std::size_t v = adjacent.first[k]; v < adjacent.first[k + 1]; ++v) {
          const std::size_t q = adjacent.pairs[v];
          if (!seen[q] && bound[q] > -d.max_depth) seen[q] = 1, near.push_back(q);
        }
      }
    }
    for (const std::size_t q : tested) seen[q] = 0;
    for (const std::size_t q : near) seen[q] = 0;
    if (near.empty()) return;
    std::ranges::sort(near);
    Pairs pairs(near.size());
    for (std::size_t u = 0; u < near.size(); ++u) pairs[u] = among[near[u]], bound[near[u]] = kUnmeasured;
    const Detection held = c_.detect_among(s_, a.model, ys, a.group, pairs, profile, kGrainPushOutPair);
    ++s_.counters.push_out_held_detections;
    const auto measure = [&](const auto& list) {
      for (const auto& x : list) {
        const std::pair key(std::min(x.a, x.b), std::max(x.a, x.b));
        const auto at = std::lower_bound(pairs.begin(), pairs.end(), key) - pairs.begin();
        bound[near[static_cast<std::size_t>(at)]] = depth_bound(measured_depth(x));
      }
    };
    measure(held.gaps), measure(held.hits);
    apart_by_spheres(a, ys, among, bound, near);
    d.hits.insert(d.hits.end(), held.hits.begin(), held.hits.end());
  }
  mutable std::vector<char> seen_;  // hold_neighbours': the pairs a pass tests, all 0 between calls

  // Every pair's bound raised by how far its two bodies moved from `from` to
  // `to`. Only `bodies` (sorted) may have moved, so only their pairs are
  // raised: adding 0 to another pair's bound would change nothing; and
  // `from` need hold only their states.
  void raise(const Subsystem<Bodies>& a, std::vector<double>& bound, const Pairs& among, const Adjacency& adjacent,
             std::span<const double> from, const std::vector<double>& to, std::span<const int> bodies) const {
    const auto& setup = c_.setup;
    std::vector<double> moved(a.group.size(), 0.0);
    for_each_index(bodies.size(), [&](std::size_t u) {
      const auto k = static_cast<std::size_t>(bodies[u]);
      moved[k] = travel<Bodies>(setup, a, from, to, k);
    }, kGrainBody);
    // Each pair once: from the lower-numbered of its bodies that moved, so
    // no two bodies' items write the same bound.
    for_each_index(bodies.size(), [&](std::size_t u) {
      const auto k = static_cast<std::size_t>(bodies[u]);
      if (moved[k] == 0) return;
      for (std::size_t v = adjacent.first[k]; v < adjacent.first[k + 1]; ++v) {
        const std::size_t q = adjacent.pairs[v];
        const auto i = static_cast<std::size_t>(among[q].first), j = static_cast<std::size_t>(among[q].second);
        if ((i == k ? moved[j] : moved[i]) != 0 && (i == k ? j : i) < k) continue;  // done from the other body
        bound[q] += moved[i] + moved[j];
      }
    }, kGrainBody);
  }

  const C& c_;
  State& s_;
};

}  // namespace gacompare::core
