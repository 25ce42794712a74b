#pragma once
// One collision step, island by island (§2.5.1 and fig. 11 of the
// report, localised). The simulation loop (core/dynamics/simulation.hpp) integrates the
// whole world from the accepted state (t0, y0) to t1 = t0 + step; then:
//
//   1. Detection at t1 with every moving body's bounding sphere grown by how
//      far the body can move in the step (Collider::reach): the grown spheres'
//      overlaps are the candidates, the narrowphase tests the pairs whose own
//      spheres overlap.
//   2. Islands: the connected components of the moving bodies under the
//      candidate pairs, less those the narrowphase found farther apart than
//      both bodies can move (unlink_far; core/collision/islands.hpp). Bodies of
//      different islands cannot meet in this step, so each island is resolved
//      on its own.
//   3. An island whose contacts are all within the penetration tolerance, and
//      whose bodies move little enough in the step, responds at t1 (its own
//      contact solve, Collider::respond).
//   4. An island with a pair deeper than the tolerance, or with a pair whose
//      bodies could close on each other by more than the thinner one's
//      inradius in the step (one could pass through the other:
//      Collider::closing and Collider::crossing), is stepped alone from y0: its bodies only,
//      as a sub-model integrated with the scene's solver, in sub-steps short
//      enough for its fastest pair, each followed by a detection among its
//      bodies, a time-of-impact search when a pair went too deep (bisection or
//      Illinois, rewinding and re-integrating the island only) and its
//      response; then its state at t1 replaces the world's.
//   5. The pairs deeper than the tolerance at t1 that no island tested: a
//      body that an island's response, correction or search carried past its
//      reach, into one it had no pair with (catch_escaped).
//   With the scene's time_of_impact "none", depth alone never sends an island
//   to step 4 and no sub-step searches: a pair deeper than the tolerance is
//   taken where its step (or sub-step) ends, and the response and the
//   push-out (core/collision/push_out_step.hpp) put it back into the band.
//   Only the fast islands are still sub-stepped, so that no body passes
//   through a thin one. With a search, a sub-step whose response still met a
//   pair too deep (one the search could not put in the band) is pushed out
//   the same way.
//
// What this changes against the report's loop, which ended every body's step
// at the first time of impact anywhere and rewound the whole world for every
// trial time: the time grid. Every island meets the world at every t1; an
// island's impacts split its own step only. A scene of one island (one body on
// a floor, two bodies meeting) takes the same impacts at the same times as
// before; after an impact at t* it continues to t1 (before: to t* + step).
// What it assumes: bodies interact only through contacts (gravity, drag and
// applied forces act on each body alone, and particles never touch bodies),
// so an island's motion is independent of every other body's within the step.
// What it cannot see within the step: an island's bodies leaving the reach
// they had at t0 (an impulse can make a body faster than it was) and meeting,
// before t1, a body they were not linked to (of another island, or of their
// own: within its step an island tests only its candidate pairs, not a fresh
// broadphase). Step 5 finds such a pair at t1: without a search it is pushed
// out there; with one, the islands it joins step alone again from y0 with it
// among their pairs, so that its impact is searched for. Growing the links
// to twice the reach, which would cover a body sent back as fast as it came,
// made islands larger and runs slower with the same impacts, so the links are
// the reach.
#include "core/collision/collisions.hpp"
#include "core/collision/islands.hpp"
#include "core/collision/push_out_step.hpp"
#include "core/collision/sleep.hpp"
#include "core/collision/subsystem.hpp"
#include "core/collision/time_of_impact_step.hpp"
#include "core/dynamics/ode.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/parallel.hpp"
#include "core/collision/time_of_impact.hpp"

#include <algorithm>
#include <functional>
#include <sstream>
#include <utility>
#include <vector>

namespace gacompare::core {

// Sub-steps of one island in one collision step: a safety stop (a body so
// fast that its step limit makes no progress), reported as a run error.
inline constexpr int kMaxIslandSteps = 1000000;
// The shortest sub-step, relative to the collision step: a body that needs a
// million sub-steps per step (5e4 m/s for a 0.1 m body at a 1 ms step) is not
// a simulation that will finish; it stops with a run error naming it. The
// bound also keeps the grown bounding spheres within what the conformal
// sphere test resolves: a sphere grown to 1e9 m beside a 1 m one carries
// ½ρ² ≈ 5e17 next to the pair's ~1 m², and cga then missed the pair.
inline constexpr double kLeastSubStep = 1e-6;

template <class C>
class CollisionStep {
 public:
  using Bodies = typename C::BodiesType;
  using Model = typename C::Model;

  using State = typename C::State;

  // The collider and model (read-only) and the run's state of the collision stages (the step context).
  CollisionStep(const C& c, const Model& m, State& state) : c_(c), m_(m), s_(state) {}

  // Resolves the collisions of the step (t0, t1]: y holds every body's state
  // at t1 from the world's integration, y0 the accepted state at t0; on
  // return y holds the step's result at t1.
  void resolve(std::span<double> y, std::span<const double> y0, double t0, double t1, Profile& profile) const {
    const auto& setup = c_.setup;
    const std::size_t n = setup.all_bodies.size();
    const double h = t1 - t0;
    c_.forget_old_contacts(s_);
    std::vector<double> margin = margins(y0, t0, h);
    Detection d = c_.detect(s_, m_, y, setup.all_bodies, margin, profile);
    unlink_far(d);
    // Sleeping sets within reach of an awake body wake, and the world is
    // detected again with them moving (core/collision/sleep.hpp).
    while (s_.sleep.any()) {
      const int woken = s_.sleep.wake_reached(setup.is_static, d.candidates);
      if (woken == 0) break;
      s_.counters.sleep_woken_by_touch += static_cast<std::uint64_t>(woken);
      ++s_.counters.sleep_redetections;
      margin = margins(y0, t0, h);
      d = c_.detect(s_, m_, y, setup.all_bodies, margin, profile);
      unlink_far(d);
    }
    std::vector<Island> islands;
    if (!d.candidates.empty()) islands = islands_of(n, setup.is_static, d.candidates);
    std::vector<double> moved(n, 0.0);
    respond_islands(islands, d, margin, moved, y, y0, t0, t1, profile);
    catch_escaped(islands, d.candidates, margin, moved, y, y0, t0, t1, profile);
    if (setup.settings.sleep.on) settle(islands, y, t1, h);
  }

  // Before the step (t0, t1) is integrated: the sleeping sets on which an
  // applied force acts within it wake, so that the force moves them.
  void wake_pushed(double t0, double t1) const {
    auto& sleep = s_.sleep;
    if (!sleep.any()) return;
    for (std::size_t k = 0; k < sleep.asleep.size(); ++k)
      if (sleep.asleep[k] && c_.setup.pushed_during(k, t0, t1))
        s_.counters.sleep_woken_by_force += sleep.wake(static_cast<int>(k));
  }

 private:
  const C& c_;
  const Model& m_;
  State& s_;

  // Whether impacts are searched for (every time_of_impact method but "none").
  bool searched() const { return c_.setup.settings.time_of_impact != TimeOfImpact::none; }

  // How far each body can move in the step (Collider::reach): 0 for a
  // sleeping body, which does not move.
  std::vector<double> margins(std::span<const double> y0, double t0, double h) const {
    const auto& setup = c_.setup;
    const std::size_t n = setup.all_bodies.size();
    std::vector<double> margin(n);
    for_each_index(n, [&](std::size_t k) {
      if (!s_.sleep.is_asleep(k)) margin[k] = c_.reach(m_, y0, setup.all_bodies, k, h);
    }, kGrainBody);
    const double farthest = 0.5 * setup.min_inradius / kLeastSubStep;  // the most a body may move in one step
    for (std::size_t k = 0; k < n; ++k)
      if (!(margin[k] <= farthest)) fail_too_fast(k, margin[k], t0, h);  // the first in body order
    return margin;
  }

  // Steps 3 and 4 above, island by island. `moved` gets how far each body of
  // an island travelled from where the world's integration left it: by its
  // response's correction, its push-out, or its steps alone (catch_escaped
  // reads it).
  void respond_islands(const std::vector<Island>& islands, Detection& d, const std::vector<double>& margin,
                       std::vector<double>& moved, std::span<double> y, std::span<const double> y0, double t0,
                       double t1, Profile& profile) const {
    const auto& setup = c_.setup;
    const std::size_t n = setup.all_bodies.size();
    const double h = t1 - t0;
    // Each hit to the island of its moving body.
    std::vector<int> island_of(n, -1);
    for (std::size_t k = 0; k < islands.size(); ++k)
      for (std::size_t i = 0; i < islands[k].moving; ++i) island_of[islands[k].bodies[i]] = static_cast<int>(k);
    std::vector<std::vector<PairHit>> hits(islands.size());
    for (auto& hit : d.hits) {
      const int mover = setup.is_static[hit.a] ? hit.b : hit.a;
      hits[island_of[mover]].push_back(std::move(hit));
    }
    // The pairs found apart, for the islands that are pushed out (a pair
    // apart beyond reach links nothing and may lie between islands or none).
    std::vector<std::vector<PairDepth>> gaps(searched() ? 0 : islands.size());
    if (!searched())
      for (const PairDepth& g : d.gaps)
        if (const int k = island_of[setup.is_static[g.a] ? g.b : g.a]; k >= 0) gaps[static_cast<std::size_t>(k)].push_back(g);
    const double tol = setup.settings.penetration_tolerance;
    // The tunnelling rule for every candidate pair (each in an island: the
    // islands are linked by them), on the run's threads.
    std::vector<char> too_fast(d.candidates.size());
    for_each_index(d.candidates.size(), [&](std::size_t q) {
      const auto ua = static_cast<std::size_t>(d.candidates[q].first), ub = static_cast<std::size_t>(d.candidates[q].second);
      const bool held = s_.sleep.is_asleep(ua) || s_.sleep.is_asleep(ub);
      too_fast[q] = c_.crossing_of(m_, y0, setup.all_bodies, ua, ub, margin[ua], margin[ub], h, held) > 1;
    }, kGrainLight);
    for (std::size_t k = 0; k < islands.size(); ++k) {
      const Island& is = islands[k];
      s_.counters.islands += 1;
      s_.counters.largest_island = std::max<std::uint64_t>(s_.counters.largest_island, is.moving);
      double deepest = -INFINITY;
      for (const auto& hit : hits[k]) deepest = std::max(deepest, hit.sat.depth);
      std::vector<std::pair<int, int>> fast_pairs;  // those the tunnelling rule refuses (Collider::crossing)
      for (const std::size_t q : is.pairs)
        if (too_fast[q]) fast_pairs.push_back(d.candidates[q]);
      const bool fast = !fast_pairs.empty();
      if ((deepest <= tol || !searched()) && !fast) {
        if (!searched() && deepest > tol) respond_and_push_out(is, d.candidates, hits[k], gaps[k], moved, y, h, t1, profile);
        else if (!hits[k].empty()) {
          // Its correction (pairs deeper than tol/2) moves bodies too.
          const std::span<const int> bodies(is.bodies.data(), is.moving);
          std::vector<collision::Pose> before(bodies.size());
          for_each_index(bodies.size(), [&](std::size_t u) { before[u] = Bodies::pose(m_, y, static_cast<std::size_t>(bodies[u])); }, kGrainBody);
          c_.respond(s_, m_, y, setup.all_bodies, hits[k], h, profile);
          for_each_index(bodies.size(), [&](std::size_t u) {
            const auto w = static_cast<std::size_t>(bodies[u]);
            moved[w] += travel(setup, w, before[u], Bodies::pose(m_, y, w));
          }, kGrainBody);
        }
        continue;
      }
      s_.counters.local_islands_deep += deepest > tol && searched();
      s_.counters.local_islands_fast += fast;
      s_.counters.largest_local_island = std::max<std::uint64_t>(s_.counters.largest_local_island, is.moving);
      step_alone(is, d.candidates, hits[k], std::move(fast_pairs), moved, y, y0, t0, t1, profile);
    }
  }

  // After the islands' responses: the pairs their corrections and searches
  // made that no island tested. A pair that was not among the
  // step's candidates had its bounding spheres farther apart at t1 than both
  // bodies' reach (margin_a + margin_b), or its narrowphase gap was
  // (unlink_far); after the responses its depth is therefore at most
  // moved_a + moved_b − margin_a − margin_b. An island's push-out tests its
  // own candidates only, and its corrections can carry a body past its reach
  // into a wall or a body it had no pair with: in the crowded box of
  // CollisionStepCases a step ended with a body 0.94 mm into a wall it had no
  // pair with, its reach 1.8 mm. Such a pair deeper than the tolerance needs
  // a body that moved more than its reach and tol/2: those bodies' pairs are
  // detected at t1, and where one is deeper than the tolerance its island of
  // touching bodies is pushed out (the correction only: the velocities are
  // the response's, and a new contact's approach is the next step's). One
  // round: a body that this push-out carries past its reach again is the
  // next step's. In the 10,000-body box without a search (1 s) some 30
  // bodies a step escape, and 47 pairs in all were found deep this way.
  // With a search the same happens: an island stepped alone takes an
  // impact's response within the step and moves on to t1 at its new
  // velocities. In CollisionStepCases' falling cube on a resting one, the
  // resting cube then ended the step 2.5–6.2 mm in the slab, and the
  // searched 1,000-body box (1 s) left pairs up to 2.6 mm deep at the end
  // of seven steps, each found only by the next.
  void catch_escaped(const std::vector<Island>& step_islands, const std::vector<std::pair<int, int>>& candidates,
                     const std::vector<double>& margin, const std::vector<double>& moved, std::span<double> y,
                     std::span<const double> y0, double t0, double t1, Profile& profile) const {
    const auto& setup = c_.setup;
    const double tol = setup.settings.penetration_tolerance;
    const std::size_t n = setup.all_bodies.size();
    std::vector<int> escaped;
    for (std::size_t k = 0; k < n; ++k)
      if (moved[k] > margin[k] + 0.5 * tol) escaped.push_back(static_cast<int>(k));
    if (escaped.empty()) return;
    s_.counters.escaped_bodies += escaped.size();
    const std::vector<std::pair<int, int>> reached = touching_spheres(escaped, moved, y, profile);
    // Every body, but not as the world: a detection of the world's own group
    // starts a new round of the pair memories, which forget every pair it
    // does not test (core/collision/pair_memory.hpp); through the world's
    // group these few pairs cost the 1,000-body box six in seven of its kept
    // axes and a tenth more instructions.
    if (every_body_.size() != n) every_body_.assign(setup.all_bodies.begin(), setup.all_bodies.end());
    Detection d = c_.detect_among(s_, m_, y, every_body_, reached, profile);
    if (!(d.max_depth > tol)) return;
    if (searched()) return step_again(step_islands, candidates, d, y, y0, t0, t1, profile);
    // The deep pairs' moving bodies, their partners, and every pair those touch.
    std::vector<int> deep;
    for (const PairHit& hit : d.hits)
      if (hit.sat.depth > tol)
        for (const int b : {hit.a, hit.b})
          if (!setup.is_static[static_cast<std::size_t>(b)]) deep.push_back(b);
    std::vector<int> ring;
    for (const auto& [i, j] : touching_spheres(unique_sorted(deep), moved, y, profile))
      for (const int b : {i, j})
        if (!setup.is_static[static_cast<std::size_t>(b)]) ring.push_back(b);
    const std::vector<std::pair<int, int>> among = touching_spheres(unique_sorted(ring), moved, y, profile);
    for (const auto& [i, j] : among)
      for (const int b : {i, j})
        if (s_.sleep.is_asleep(static_cast<std::size_t>(b))) s_.counters.sleep_woken_by_touch += s_.sleep.wake(b);
    d = c_.detect_among(s_, m_, y, every_body_, among, profile);
    s_.counters.escaped_deep_pairs += static_cast<std::uint64_t>(
        std::ranges::count_if(d.hits, [&](const PairHit& hit) { return hit.sat.depth > tol; }));
    const std::vector<Island> islands = islands_of(n, setup.is_static, among);
    std::vector<int> island_of(n, -1);
    for (std::size_t k = 0; k < islands.size(); ++k)
      for (std::size_t i = 0; i < islands[k].moving; ++i) island_of[islands[k].bodies[i]] = static_cast<int>(k);
    const auto mover = [&](int a, int b) { return setup.is_static[static_cast<std::size_t>(a)] ? b : a; };
    std::vector<std::vector<PairHit>> hits(islands.size());
    std::vector<std::vector<PairDepth>> gaps(islands.size());
    for (PairHit& hit : d.hits) hits[static_cast<std::size_t>(island_of[mover(hit.a, hit.b)])].push_back(std::move(hit));
    for (const PairDepth& g : d.gaps) gaps[static_cast<std::size_t>(island_of[mover(g.a, g.b)])].push_back(g);
    for (std::size_t k = 0; k < islands.size(); ++k) {
      if (std::ranges::none_of(hits[k], [&](const PairHit& hit) { return hit.sat.depth > tol; })) continue;
      Subsystem<Bodies> a = subsystem_of(islands[k]);
      std::vector<double> ys = a.gather(y);
      const std::vector<double> before = ys;
      const Numbering local = numbering(islands[k]);
      push_out(a, island_pairs(islands[k], among, local), pair_depths(hits[k], local), pair_depths(gaps[k], local),
               before, ys, t1, profile);
      a.scatter(ys, y);
    }
  }

  // With a search, a pair that catch_escaped found deeper than the tolerance
  // is searched for like any other: the islands of the step that hold its
  // bodies, joined by it and by the other pairs that detection found
  // touching, step alone again from y0 with those pairs among their own
  // (step 4 above), and their states at t1 replace the first answer. Pushed
  // out at t1 instead, as without a search, the pair kept the velocities
  // that drove it in, and on the stacking family's friction pyramid wall of
  // five layers a later contact solve ran its sweeps to their cap. One
  // round, as without a search: a pair this makes is the next step's.
  void step_again(const std::vector<Island>& step_islands, const std::vector<std::pair<int, int>>& candidates,
                  const Detection& caught, std::span<double> y, std::span<const double> y0, double t0, double t1,
                  Profile& profile) const {
    const auto& setup = c_.setup;
    const double tol = setup.settings.penetration_tolerance;
    const std::size_t n = setup.all_bodies.size();
    const auto moving = [&](int b) { return !setup.is_static[static_cast<std::size_t>(b)]; };
    s_.counters.escaped_deep_pairs += static_cast<std::uint64_t>(
        std::ranges::count_if(caught.hits, [&](const PairHit& hit) { return hit.sat.depth > tol; }));
    // The moving bodies of the deep pairs; of the touching pairs that reach
    // them; and of the islands of all those.
    std::vector<char> again(n, 0);
    for (const PairHit& hit : caught.hits)
      if (hit.sat.depth > tol)
        for (const int b : {hit.a, hit.b}) again[static_cast<std::size_t>(b)] = moving(b);
    std::vector<std::pair<int, int>> joining;
    for (const PairHit& hit : caught.hits)
      if (again[static_cast<std::size_t>(hit.a)] || again[static_cast<std::size_t>(hit.b)])
        joining.emplace_back(std::min(hit.a, hit.b), std::max(hit.a, hit.b));
    for (const auto& [i, j] : joining)
      for (const int b : {i, j}) again[static_cast<std::size_t>(b)] = moving(b);
    for (const Island& is : step_islands) {
      const auto first = is.bodies.begin(), last = first + static_cast<long>(is.moving);
      if (std::any_of(first, last, [&](int b) { return again[static_cast<std::size_t>(b)] != 0; }))
        std::for_each(first, last, [&](int b) { again[static_cast<std::size_t>(b)] = 1; });
    }
    // Their pairs: the step's candidates (which link no island to another)
    // and the joining ones.
    std::vector<std::pair<int, int>> links;
    for (const auto& list : {std::cref(candidates), std::cref(joining)})
      for (const auto& [i, j] : list.get())
        if (again[static_cast<std::size_t>(i)] || again[static_cast<std::size_t>(j)]) links.emplace_back(i, j);
    std::ranges::sort(links);
    links.erase(std::unique(links.begin(), links.end()), links.end());
    std::vector<double> moved(n, 0.0);  // no further round reads it
    for (const Island& is : islands_of(n, setup.is_static, links)) {
      for (std::size_t i = 0; i < is.moving; ++i)
        if (s_.sleep.is_asleep(static_cast<std::size_t>(is.bodies[i])))
          s_.counters.sleep_woken_by_touch += s_.sleep.wake(is.bodies[i]);
      ++s_.counters.escaped_islands_stepped;
      s_.counters.escaped_island_bodies_stepped += is.moving;
      std::vector<PairHit> none;
      step_alone(is, links, none, {}, moved, y, y0, t0, t1, profile, false);
    }
  }

  // The pairs (i < j, sorted) of each body of `bodies` with every other
  // body whose bounding sphere may touch its own at state y, but two static
  // ones. The others' centres are the step's detection's (before the
  // responses), each within its travel since (`moved`) of where it is, and
  // the broadphase's trees as that detection left them hold every body
  // whose sphere then came within the largest travel of this body's sphere
  // now (with the sweep, every body is scanned).
  std::vector<std::pair<int, int>> touching_spheres(const std::vector<int>& bodies, const std::vector<double>& moved,
                                                    std::span<const double> y, Profile& profile) const {
    ScopedStage timed(profile, Stage::broadphase);
    const auto& setup = c_.setup;
    const std::vector<Vec3>& centres = s_.world_centres;
    const double farthest = std::ranges::max(moved);
    std::vector<std::vector<std::pair<int, int>>> found(bodies.size());
    for_each_index(bodies.size(), [&](std::size_t u) {
      const int e = bodies[u];
      const auto ue = static_cast<std::size_t>(e);
      const Vec3 c = Bodies::pose(m_, y, ue).apply(setup.sphere_centre[ue]);
      const double re = setup.sphere_radius[ue];
      const auto test = [&](int k) {
        const auto j = static_cast<std::size_t>(k);
        if (j == ue || (setup.is_static[ue] && setup.is_static[j])) return;
        const double r = re + setup.sphere_radius[j] + moved[j];
        // Rounding of the centres, ~1e-15 of them, errs towards testing.
        if ((c - centres[j]).norm() <= r + 1e-12 * (r + c.norm() + centres[j].norm()))
          found[u].emplace_back(std::min(e, k), std::max(e, k));
      };
      std::vector<int> stack;
      const double reach = (re + farthest) * (1 + 1e-12) + 1e-12 * c.norm();
      if (!s_.broadphase.query(c, reach, stack, test))
        for (std::size_t j = 0; j < centres.size(); ++j) test(static_cast<int>(j));
    }, 1);
    std::vector<std::pair<int, int>> out;
    for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
    std::ranges::sort(out);
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  mutable std::vector<int> every_body_;  // catch_escaped's group: setup.all_bodies, at another address
  static std::vector<int> unique_sorted(std::vector<int> v) {
    std::ranges::sort(v);
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  }

  // Falling asleep (core/collision/sleep.hpp), after the step's responses:
  // each awake moving body's stillness at t1, then every island (and every
  // moving body in none) whose bodies have all been still long enough is
  // stopped and put to sleep as one set.
  void settle(const std::vector<Island>& islands, std::span<double> y, double t1, double h) const {
    const auto& setup = c_.setup;
    auto& sleep = s_.sleep;
    const Sleep& opt = setup.settings.sleep;
    const std::size_t n = setup.all_bodies.size();
    const auto awake = [&](std::size_t k) { return !setup.is_static[k] && !sleep.asleep[k]; };
    for (std::size_t k = 0; k < n; ++k) {
      if (!awake(k)) continue;
      const bool still = c_.rim_speed(m_, y, setup.all_bodies, k) <= opt.speed && !setup.pushed_during(k, t1, t1 + h);
      sleep.still_for[k] = still ? sleep.still_for[k] + h : 0.0;
    }
    // The sum of a step's h over `time` carries rounding of ~1e-13 of it.
    const auto rested = [&](int k) { return sleep.still_for[static_cast<std::size_t>(k)] >= opt.time * (1 - 1e-9); };
    const auto fall_asleep = [&](std::span<const int> bodies) {
      for (const int b : bodies) Bodies::stop(m_, y, static_cast<std::size_t>(b));
      sleep.fall_asleep(bodies);
      ++s_.counters.sleep_islands;
    };
    std::vector<char> in_island(n, 0);
    for (const Island& is : islands) {
      const std::span<const int> moving(is.bodies.data(), is.moving);
      bool all = true;
      for (const int b : moving) in_island[static_cast<std::size_t>(b)] = 1, all = all && rested(b);
      if (all) fall_asleep(moving);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const int b = static_cast<int>(k);
      if (awake(k) && !in_island[k] && rested(b)) fall_asleep(std::span<const int>(&b, 1));
    }
    s_.counters.sleeping_body_steps += sleep.sleeping;
  }

  // Links by distance, not by bounding spheres: a candidate pair the
  // narrowphase found apart at t1 by a gap g (a lower bound of the distance)
  // is at distance ≥ g − reach_a − reach_b at every time of the step, since
  // no point of either body moves farther than its reach between then and
  // t1. When that is positive (beyond the touching band, within which a pair
  // counts as touching) the pair cannot touch in the step: it links nothing
  // and is not among its island's pairs (Collider::apart_beyond_reach keeps those in
  // Detection::apart, judged by the gaps along the face normals: a bound that
  // does not depend on which axis the pair remembers). Bounding spheres are
  // loose (a tetrahedron fills a small part of its sphere), and in a dense
  // scene their grown overlaps chain islands of thousands of bodies whose
  // every impact re-detects all their pairs.
  // Both lists sorted, so one walk removes them: the candidates are, and the
  // world's pairs apart come in the order the narrowphase took them, the
  // broadphase's (sorted here only if not). The walk on the run's threads,
  // a block of candidates each, from where its first one is in `far`: on one,
  // the 10,000-body box's some 15,000 candidates a step made it 1 % of the
  // run's own thread.
  void unlink_far(Detection& d) const {
    if (d.apart.empty()) return;
    std::vector<std::pair<int, int>> far = std::move(d.apart);
    if (!std::is_sorted(far.begin(), far.end())) std::sort(far.begin(), far.end());
    s_.counters.links_apart += far.size();
    const std::vector<std::pair<int, int>>& all = d.candidates;
    const std::size_t n = all.size();
    std::vector<char> apart(n);
    for_each_block(n, kGrainLight, [&](std::size_t, std::size_t begin, std::size_t end) {
      auto next = std::lower_bound(far.begin(), far.end(), all[begin]);
      for (std::size_t k = begin; k < end; ++k) {
        while (next != far.end() && *next < all[k]) ++next;
        apart[k] = next != far.end() && *next == all[k];
      }
    });
    erase_flagged(d.candidates, apart, kGrainLight);
  }

  void fail_if_nonfinite(const Subsystem<Bodies>& a, const std::vector<double>& ys, const char* stage, double t) const {
    const std::string bad = first_nonfinite(ys, a.stride, a.model.names, "body");
    if (bad.empty()) return;
    std::ostringstream msg;
    msg << "non-finite state: " << bad << ", stage " << stage << ", at t=" << t;
    throw run_error(msg.str());
  }

  // Step 4 above: the island from (t0, y0) to t1 in sub-steps of its own.
  // `fast`: its pairs that the tunnelling rule refused over the whole step
  // (world indices), whose kept contacts at t1 are dropped before the island
  // goes back to an earlier state (Collider::forget_kept).
  // `integrated`: y holds the island's state at t1 from the world's
  // integration (else it is stepped from y0 from its first sub-step on).
  void step_alone(const Island& is, const std::vector<std::pair<int, int>>& candidates, std::vector<PairHit>& at_t1,
                  std::vector<std::pair<int, int>> fast, std::vector<double>& moved, std::span<double> y,
                  std::span<const double> y0, double t0, double t1, Profile& profile, bool integrated = true) const {
    const auto& setup = c_.setup;
    Subsystem<Bodies> a = subsystem_of(is);
    const std::vector<double> before = a.gather(y);
    ++s_.counters.local_islands;
    s_.counters.local_island_bodies += is.moving;
    std::vector<double> ys = a.gather(y0), yb;
    const Numbering local = numbering(is);
    const std::vector<std::pair<int, int>> among = island_pairs(is, candidates, local);
    const double tol = setup.settings.penetration_tolerance;
    double t = t0;
    bool at_start = integrated;  // y holds the world's integration to t1 from here
    const auto rewind = [&] { c_.forget_kept(s_, fast), fast.clear(); };
    for (int step = 0; t < t1; ++step) {
      if (step == kMaxIslandSteps) fail_stalled(a, ys, t, "the island took " + std::to_string(step) + " sub-steps");
      double h = t1 - t;
      const double limited = c_.step_limit(a.model, ys, a.group, among, h);
      if (limited < h) h = limited, ++s_.counters.shortened_steps;
      const double tb = t1 - (t + h) <= 1e-9 * h ? t1 : t + h;
      if (!(tb > t) || h < kLeastSubStep * setup.settings.step)
        fail_stalled(a, ys, t, "its step limit " + fmt(h) + " s is below " + fmt(kLeastSubStep) + " of the collision step");
      ++s_.counters.local_steps;
      yb = ys;
      Detection d;
      if (at_start && tb == t1) {
        ys = a.gather(y);
        fail_if_nonfinite(a, ys, "integrate", tb);
        d = world_hits(at_t1, among, local);
      } else {
        rewind();
        a.integrate(t, tb, ys, profile);
        fail_if_nonfinite(a, ys, "integrate", tb);
        d = c_.detect_among(s_, a.model, ys, a.group, among, profile);
      }
      at_start = false;
      double accepted = tb;
      if (d.max_depth > tol && searched()) {
        rewind();
        accepted = TimeOfImpactStep<C>(c_, s_).find(a, d, t, yb, tb, ys, profile);
        fail_if_nonfinite(a, ys, "time_of_impact", accepted);
        d = c_.detect_among(s_, a.model, ys, a.group, among, profile);
      }
      // Deep after the response's time: always without a search; with one,
      // a pair the search could not put in the band (already too deep at the
      // sub-step's start, or a search left unresolved).
      const bool push = d.max_depth > tol;
      if (push) yb = ys;  // the state before the response
      if (!d.hits.empty()) {
        c_.respond(s_, a.model, ys, a.group, d.hits, accepted - t, profile);
        fail_if_nonfinite(a, ys, "response", accepted);
      }
      if (push) {
        const auto same = [](int k) { return k; };
        push_out(a, among, pair_depths(d.hits, same), pair_depths(d.gaps, same), yb, ys, accepted, profile);
      }
      t = accepted;
    }
    record_travel(a, before, ys, moved);
    a.scatter(ys, y);
  }

  // An island's bodies as a model of their own, with the scene's solver.
  Subsystem<Bodies> subsystem_of(const Island& is) const {
    return Subsystem<Bodies>(m_, is.bodies, Bodies::state_size(m_) / c_.setup.all_bodies.size(), c_.setup.solver);
  }

  // Each pair of a hit or gap list in an island's numbering (`local` maps a
  // body's index there), with its depth: what the push-out starts from.
  template <class List, class Local>
  static std::vector<PairDepth> pair_depths(const List& list, Local&& local) {
    std::vector<PairDepth> out;
    out.reserve(list.size());
    for (const auto& x : list) out.push_back({local(x.a), local(x.b), measured_depth(x)});
    return out;
  }

  // Body w of the world in an island's own numbering (its moving bodies, then
  // its static ones, each ascending), read from a table of every world body
  // that holds the island's numbers while the Numbering lives (one island at
  // a time): a lookup per body, where two binary searches over the island's
  // bodies per pair took 0.8 s of the 10,000-body box's run on its pile.
  class Numbering {
   public:
    Numbering(std::vector<int>& table, const Island& is, std::size_t n) : table_(table), is_(is) {
      if (table_.size() != n) table_.assign(n, -1);
      for (std::size_t k = 0; k < is.bodies.size(); ++k) table_[static_cast<std::size_t>(is.bodies[k])] = static_cast<int>(k);
    }
    Numbering(const Numbering&) = delete;
    Numbering& operator=(const Numbering&) = delete;
    ~Numbering() {
      for (const int w : is_.bodies) table_[static_cast<std::size_t>(w)] = -1;
    }
    int operator()(int w) const { return table_[static_cast<std::size_t>(w)]; }

   private:
    std::vector<int>& table_;
    const Island& is_;
  };
  mutable std::vector<int> numbers_;  // Numbering's table, −1 outside the island it numbers
  Numbering numbering(const Island& is) const { return Numbering(numbers_, is, c_.setup.all_bodies.size()); }

  // The island's candidate pairs in its own numbering: within the step its
  // bodies can meet only each other and the static bodies they link to. In
  // the order a broadphase gives its pairs, so the contacts are solved in the
  // same order as if the island had been swept afresh.
  static std::vector<std::pair<int, int>> island_pairs(const Island& is, const std::vector<std::pair<int, int>>& candidates,
                                                       const Numbering& local) {
    std::vector<std::pair<int, int>> among;
    among.reserve(is.pairs.size());
    for (const std::size_t k : is.pairs) {
      const int i = local(candidates[k].first), j = local(candidates[k].second);
      among.emplace_back(std::min(i, j), std::max(i, j));
    }
    sort_pairs(among, is.bodies.size());
    return among;
  }

  // Without a search (time_of_impact "none"): an island's response at t1
  // that met a pair deeper than the tolerance, then its push-out
  // (core/collision/push_out_step.hpp) on the island alone. `hits`: the
  // island's, in the world's numbering.
  void respond_and_push_out(const Island& is, const std::vector<std::pair<int, int>>& candidates,
                            std::span<const PairHit> hits, std::span<const PairDepth> gaps,
                            std::vector<double>& moved, std::span<double> y, double h, double t1,
                            Profile& profile) const {
    Subsystem<Bodies> a = subsystem_of(is);
    const std::vector<double> before = a.gather(y);
    c_.respond(s_, m_, y, c_.setup.all_bodies, hits, h, profile);
    std::vector<double> ys = a.gather(y);
    const Numbering local = numbering(is);
    push_out(a, island_pairs(is, candidates, local), pair_depths(hits, local), pair_depths(gaps, local), before, ys,
             t1, profile);
    record_travel(a, before, ys, moved);
    a.scatter(ys, y);
  }
  // Each moving body of `a`: its travel from `from` to `to` added to `moved` (world numbering).
  void record_travel(const Subsystem<Bodies>& a, const std::vector<double>& from, const std::vector<double>& to,
                     std::vector<double>& moved) const {
    for_each_index(a.group.size(), [&](std::size_t k) {
      const auto w = static_cast<std::size_t>(a.group[k]);
      if (!c_.setup.is_static[w]) moved[w] += travel<Bodies>(c_.setup, a, from, to, k);
    }, kGrainBody);
  }
  void push_out(const Subsystem<Bodies>& a, const std::vector<std::pair<int, int>>& among,
                std::span<const PairDepth> depths, std::span<const PairDepth> gaps, const std::vector<double>& before,
                std::vector<double>& ys, double t, Profile& profile) const {
    PushOutStep<C>(c_, s_).run(a, among, depths, gaps, before, ys, profile,
                               [&](const std::vector<double>& state) { fail_if_nonfinite(a, state, "response", t); });
  }

  // The island's hits at t1 from the world's detection, in its own numbering
  // and in the order its own detection would give them (its pairs', sorted):
  // the world's state at t1 is the island's first sub-step's when that ends
  // at t1, so detecting again would find the same hits (a pair in contact
  // gets its answer from scratch, whatever axis it remembers).
  template <class Local>
  static Detection world_hits(std::vector<PairHit>& hits, const std::vector<std::pair<int, int>>& among, Local&& local) {
    std::vector<std::pair<int, int>> order;  // (position in among, hit): every hit is one of the island's pairs
    for (std::size_t k = 0; k < hits.size(); ++k) {
      const int i = local(hits[k].a), j = local(hits[k].b);
      const auto at = std::lower_bound(among.begin(), among.end(), std::pair(std::min(i, j), std::max(i, j)));
      order.emplace_back(static_cast<int>(at - among.begin()), static_cast<int>(k));
    }
    std::sort(order.begin(), order.end());
    Detection d;
    for (const auto& [at, k] : order) {
      PairHit h = std::move(hits[static_cast<std::size_t>(k)]);
      h.a = local(h.a), h.b = local(h.b);  // world order kept: a's world index below b's, as the narrowphase puts it
      d.max_depth = std::max(d.max_depth, h.sat.depth);
      d.hits.push_back(std::move(h));
    }
    return d;
  }

  [[noreturn]] void fail_too_fast(std::size_t k, double reach, double t0, double h) const {
    std::ostringstream msg;
    msg << "collisions: no progress at t=" << t0 << ": body '" << m_.names[k] << "' can move " << reach
        << " m in one collision step of " << h << " s, more than " << 1 / kLeastSubStep
        << " sub-steps of half the smallest inradius (stage time_of_impact)";
    throw run_error(msg.str());
  }
  [[noreturn]] void fail_stalled(const Subsystem<Bodies>& a, const std::vector<double>& ys, double t, const std::string& why) const {
    // Name the fastest body: it sets the step limit.
    std::size_t fastest = 0;
    double most = -1;
    for (std::size_t k = 0; k < a.group.size(); ++k) {
      if (c_.setup.is_static[a.group[k]]) continue;
      const double rim = c_.rim_speed(a.model, ys, a.group, k);
      if (rim > most) most = rim, fastest = k;
    }
    std::ostringstream msg;
    msg << "collisions: no progress at t=" << t << ": " << why << " (body '" << a.model.names[fastest]
        << "' reaches " << most << " m/s; stage time_of_impact)";
    throw run_error(msg.str());
  }
  static std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
};

}  // namespace gacompare::core
