#pragma once
// One collision step, island by island (issue #14; §2.5.1 and fig. 11 of the
// report, localised). The simulation loop (core/simulation.hpp) integrates the
// whole world from the accepted state (t0, y0) to t1 = t0 + step; then:
//
//   1. Detection at t1 with every moving body's bounding sphere grown by how
//      far the body can move in the step (Collider::reach): the grown spheres'
//      overlaps are the candidates, the narrowphase tests the pairs whose own
//      spheres overlap.
//   2. Islands: the connected components of the moving bodies under the
//      candidate pairs, less those the narrowphase found farther apart than
//      both bodies can move (unlink_far; core/islands.hpp). Bodies of
//      different islands cannot meet in this step, so each island is resolved
//      on its own.
//   3. An island whose contacts are all within the penetration tolerance, and
//      whose bodies move little enough in the step, responds at t1 (its own
//      contact solve, Collider::respond).
//   4. An island with a pair deeper than the tolerance, or with a body that
//      could move more than half the smallest inradius in the step (it could
//      pass through a thin body), is stepped alone from y0: its bodies only,
//      as a sub-model integrated with the scene's solver, in sub-steps short
//      enough for its fastest body, each followed by a detection among its
//      bodies, a time-of-impact search when a pair went too deep (bisection or
//      Illinois, rewinding and re-integrating the island only) and its
//      response; then its state at t1 replaces the world's.
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
// What it cannot see: an island's bodies leaving the reach they had at t0 (an
// impulse can make a body faster than it was) and meeting, before t1, a body
// they were not linked to (of another island, or of their own: within its
// step an island tests only its candidate pairs, not a fresh broadphase);
// that pair is found at t1, deeper than the tolerance, and the next step
// resolves it like any pair already too deep at its start. Growing the links
// to twice the reach, which would cover a body sent back as fast as it came,
// made the 1000-body box's islands 20 % larger and its run 23 % slower with
// the same impacts, searches and samples, so the links are the reach.
#include "core/collisions.hpp"
#include "core/islands.hpp"
#include "core/ode.hpp"
#include "core/simulator.hpp"
#include "core/time_of_impact.hpp"

#include <algorithm>
#include <sstream>
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

  CollisionStep(const C& c, const Model& m) : c_(c), m_(m) {}

  // Resolves the collisions of the step (t0, t1]: y holds every body's state
  // at t1 from the world's integration, y0 the accepted state at t0; on
  // return y holds the step's result at t1.
  void resolve(std::span<double> y, std::span<const double> y0, double t0, double t1, Profile& profile) const {
    const auto& setup = c_.setup;
    const std::size_t n = setup.everyone.size();
    const double h = t1 - t0;
    c_.forget_old_contacts();
    std::vector<double> margin(n);
    const double farthest = 0.5 * setup.min_inradius / kLeastSubStep;  // the most a body may move in one step
    for (std::size_t k = 0; k < n; ++k) {
      margin[k] = c_.reach(m_, y0, setup.everyone, k, h);
      if (!(margin[k] <= farthest)) fail_too_fast(k, margin[k], t0, h);
    }
    Detection d = c_.detect(m_, y, setup.everyone, margin, profile);
    unlink_far(d);
    if (d.candidates.empty()) return;
    const std::vector<Island> islands = islands_of(n, setup.is_static, d.candidates);
    // Each hit to the island of its moving body.
    std::vector<int> island_of(n, -1);
    for (std::size_t k = 0; k < islands.size(); ++k)
      for (std::size_t i = 0; i < islands[k].moving; ++i) island_of[islands[k].bodies[i]] = static_cast<int>(k);
    std::vector<std::vector<PairHit>> hits(islands.size());
    for (auto& hit : d.hits) {
      const int mover = setup.is_static[hit.a] ? hit.b : hit.a;
      hits[island_of[mover]].push_back(std::move(hit));
    }
    const double tol = setup.settings.penetration_tolerance;
    for (std::size_t k = 0; k < islands.size(); ++k) {
      const Island& is = islands[k];
      c_.counters.islands += 1;
      c_.counters.largest_island = std::max<std::uint64_t>(c_.counters.largest_island, is.moving);
      double deepest = -INFINITY;
      for (const auto& hit : hits[k]) deepest = std::max(deepest, hit.sat.depth);
      double most = 0;  // the island's longest reach in the step
      for (std::size_t i = 0; i < is.moving; ++i) most = std::max(most, margin[is.bodies[i]]);
      if (deepest <= tol && most <= 0.5 * setup.min_inradius) {
        if (!hits[k].empty()) c_.respond(m_, y, setup.everyone, hits[k], h, profile);
        continue;
      }
      step_alone(is, d.candidates, hits[k], y, y0, t0, t1, profile);
    }
  }

 private:
  const C& c_;
  const Model& m_;

  // Links by distance, not by bounding spheres: a candidate pair the
  // narrowphase found apart at t1 by a gap g (a lower bound of the distance)
  // is at distance ≥ g − reach_a − reach_b at every time of the step, since
  // no point of either body moves farther than its reach between then and
  // t1. When that is positive (beyond the touching band, within which a pair
  // counts as touching) the pair cannot touch in the step: it links nothing
  // and is not among its island's pairs (Collider::note_apart keeps those in
  // Detection::apart, judged by the gaps along the face normals: a bound that
  // does not depend on which axis the pair remembers). Bounding spheres are
  // loose (a tetrahedron fills 12 % of its sphere), and in the dense part of
  // the 10,000-body box their grown overlaps, ~10 per body, chained islands
  // of thousands of bodies whose every impact re-detected all their pairs:
  // 93 % of all narrowphase pairs.
  void unlink_far(Detection& d) const {
    if (d.apart.empty()) return;
    std::vector<std::pair<int, int>> far = std::move(d.apart);
    std::sort(far.begin(), far.end());
    c_.counters.links_apart += far.size();
    std::erase_if(d.candidates, [&](const std::pair<int, int>& p) { return std::binary_search(far.begin(), far.end(), p); });
  }

  // An island's bodies as a model of their own, their state copied out of the
  // world's and back, and the scene's solver for them alone.
  struct Alone {
    Model model;
    std::span<const int> world;
    std::size_t stride;
    OdeSolver solver;
    Alone(const Model& m, std::span<const int> bodies, std::size_t stride_, const SolverSpec& spec)
        : model(Bodies::subset(m, bodies)), world(bodies), stride(stride_), solver(spec, bodies.size() * stride_) {
      solver.set_error_norm([this, spec](std::span<const double> a, std::span<const double> b, std::span<const double> e) {
        return Bodies::error_ratio(model, a, b, e, spec.abs_tol, spec.rel_tol);
      });
    }
    Alone(const Alone&) = delete;
    Alone& operator=(const Alone&) = delete;
    std::vector<double> gather(std::span<const double> y) const {
      std::vector<double> out(world.size() * stride);
      for (std::size_t k = 0; k < world.size(); ++k)
        std::copy_n(y.begin() + static_cast<long>(world[k] * stride), stride, out.begin() + static_cast<long>(k * stride));
      return out;
    }
    void scatter(const std::vector<double>& ys, std::span<double> y) const {
      for (std::size_t k = 0; k < world.size(); ++k)
        std::copy_n(ys.begin() + static_cast<long>(k * stride), stride, y.begin() + static_cast<long>(world[k] * stride));
    }
    // Integrates ys from t to t_end (the island's forces are timed as `forces`
    // in `profile`, like the world's).
    void integrate(double t, double t_end, std::vector<double>& ys, Profile& profile) {
      auto f = [&](double tt, std::span<const double> yy, std::span<double> dy) {
        ScopedStage timed(profile, Stage::forces);
        Bodies::derivative(model, tt, yy, dy);
      };
      auto after = [&](std::vector<double>& yy) { return Bodies::renormalise(model, yy); };
      solver.advance(f, t, t_end, ys, profile, after);
    }
  };

  void fail_if_nonfinite(const Alone& a, const std::vector<double>& ys, const char* stage, double t) const {
    const std::string bad = first_nonfinite(ys, a.stride, a.model.names, "body");
    if (bad.empty()) return;
    std::ostringstream msg;
    msg << "non-finite state: " << bad << ", stage " << stage << ", at t=" << t;
    throw run_error(msg.str());
  }

  // Step 4 above: the island from (t0, y0) to t1 in sub-steps of its own.
  void step_alone(const Island& is, const std::vector<std::pair<int, int>>& candidates, std::vector<PairHit>& at_t1,
                  std::span<double> y, std::span<const double> y0, double t0, double t1, Profile& profile) const {
    const auto& setup = c_.setup;
    const std::size_t stride = Bodies::state_size(m_) / setup.everyone.size();
    Alone a(m_, is.bodies, stride, setup.solver);
    ++c_.counters.local_islands;
    c_.counters.local_island_bodies += is.moving;
    std::vector<double> ys = a.gather(y0), yb;
    // The island's candidate pairs in its own numbering: within the step its
    // bodies can meet only each other and the static bodies they link to.
    std::vector<std::pair<int, int>> among;
    among.reserve(is.pairs.size());
    const auto local = [&](int w) {
      const auto movers = is.bodies.begin() + static_cast<long>(is.moving);
      const auto at = std::lower_bound(is.bodies.begin(), movers, w);
      return static_cast<int>((at != movers && *at == w ? at : std::lower_bound(movers, is.bodies.end(), w)) -
                              is.bodies.begin());
    };
    for (const std::size_t k : is.pairs) {
      const int i = local(candidates[k].first), j = local(candidates[k].second);
      among.emplace_back(std::min(i, j), std::max(i, j));
    }
    // In the order a broadphase gives its pairs, so the contacts are solved
    // in the same order as if the island had been swept afresh.
    std::sort(among.begin(), among.end());
    const double tol = setup.settings.penetration_tolerance;
    double t = t0;
    bool at_start = true;  // the world's integration already reached t1 from here
    for (int step = 0; t < t1; ++step) {
      if (step == kMaxIslandSteps) fail_stalled(a, ys, t, "the island took " + std::to_string(step) + " sub-steps");
      double h = t1 - t;
      const double limited = c_.step_limit(a.model, ys, a.world, h);
      if (limited < h) h = limited, ++c_.counters.shortened_steps;
      const double tb = t1 - (t + h) <= 1e-9 * h ? t1 : t + h;
      if (!(tb > t) || h < kLeastSubStep * setup.settings.step)
        fail_stalled(a, ys, t, "its step limit " + fmt(h) + " s is below " + fmt(kLeastSubStep) + " of the collision step");
      ++c_.counters.local_steps;
      yb = ys;
      Detection d;
      if (at_start && tb == t1) {
        ys = a.gather(y);
        fail_if_nonfinite(a, ys, "integrate", tb);
        d = world_hits(at_t1, among, local);
      } else {
        a.integrate(t, tb, ys, profile);
        fail_if_nonfinite(a, ys, "integrate", tb);
        d = c_.detect_among(a.model, ys, a.world, among, profile);
      }
      at_start = false;
      double accepted = tb;
      if (d.max_depth > tol) {
        accepted = impact(a, d, t, yb, tb, ys, profile);
        fail_if_nonfinite(a, ys, "time_of_impact", accepted);
        d = c_.detect_among(a.model, ys, a.world, among, profile);
      }
      if (!d.hits.empty()) {
        c_.respond(a.model, ys, a.world, d.hits, accepted - t, profile);
        fail_if_nonfinite(a, ys, "response", accepted);
      }
      t = accepted;
    }
    a.scatter(ys, y);
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
  [[noreturn]] void fail_stalled(const Alone& a, const std::vector<double>& ys, double t, const std::string& why) const {
    // Name the fastest body: it sets the step limit.
    std::size_t fastest = 0;
    double most = -1;
    for (std::size_t k = 0; k < a.world.size(); ++k) {
      if (c_.setup.is_static[a.world[k]]) continue;
      const auto mo = Bodies::motion(a.model, ys, k);
      const double rim = Bodies::speed(mo) + c_.setup.sphere_radius[a.world[k]] * Bodies::angular_speed(mo);
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

  // §2.5.1's search, on one island: a time t* in (t, tb) where the deepest
  // contact of the pairs of `d` deeper than tol at tb is in (0, tol]
  // (core/time_of_impact.hpp). The trial poses come from re-integrating the
  // pairs' bodies from (t, yb) for every trial time (impact_motion
  // "integrate", §2.5.1), or from interpolating them between yb and ys in the
  // backend's algebra (§4.3.2's "alternative to recalculating the entire
  // system motion many times"); then the island is integrated once, to the
  // time found, and the search goes on over the island's own motion from the
  // bracket found if that time is not in the band. ys holds the state at tb
  // and, on return, the state at the accepted time, which it returns.
  //
  // Only the pairs' bodies for the trials (issue #14; the report re-integrates
  // the whole system, and so did this search over its island): within a
  // sub-step no impulse acts and every body's forces are its own, so those
  // bodies move alone as they move in the island — bit for bit with a
  // fixed-step solver, whose steps do not depend on the other bodies. An
  // adaptive solver chooses its steps for them alone, so its time may miss the
  // band on the island's motion; that is what the check after the search
  // catches. A trial then costs the few bodies of the deep pairs, not the
  // island's hundreds.
  double impact(Alone& a, const Detection& d, double t, const std::vector<double>& yb, double tb,
                std::vector<double>& ys, Profile& profile) const {
    const auto& setup = c_.setup;
    ScopedStage timed(profile, Stage::time_of_impact);
    Profile inner;  // the search's integration and narrowphase count as time of impact
    ++c_.counters.impact_searches;
    // The pairs that went too deep, in the island's numbering. Not every hit:
    // a resting contact already in the band (0, tol] would put the deepest
    // depth in the band at any trial time, and the search would stop short of
    // the impact (halving the sub-step instead of finding it).
    std::vector<std::pair<int, int>> pairs;
    for (const auto& hit : d.hits)
      if (hit.sat.depth > setup.settings.penetration_tolerance) pairs.emplace_back(hit.a, hit.b);
    // The pairs' bodies (ascending island indices), as a model of their own.
    std::vector<int> few;
    for (const auto& pair : pairs) few.push_back(pair.first), few.push_back(pair.second);
    std::sort(few.begin(), few.end());
    few.erase(std::unique(few.begin(), few.end()), few.end());
    const auto at = [&](int i) { return static_cast<int>(std::lower_bound(few.begin(), few.end(), i) - few.begin()); };
    std::vector<std::pair<int, int>> few_pairs;
    for (const auto& pair : pairs) few_pairs.emplace_back(at(pair.first), at(pair.second));
    std::vector<int> few_world(few.size());
    for (std::size_t k = 0; k < few.size(); ++k) few_world[k] = a.world[static_cast<std::size_t>(few[k])];
    Alone p(a.model, few, a.stride, setup.solver);
    const std::vector<double> pb = p.gather(yb);
    const ImpactSearch how{setup.settings.time_of_impact, setup.settings.penetration_tolerance,
                           closing_speed(a, pairs, yb, ys, tb - t)};
    // Counters: a trial is one depth evaluation of the search; an island
    // integration (impact_state_evaluations) the costly kind.
    std::vector<double> pm;
    const auto alone = [&](double tm) {
      pm = pb;
      p.integrate(t, tm, pm, inner);
      ++c_.counters.impact_iterations;
      c_.counters.impact_bodies_integrated += few.size();
      return c_.depth_of(p.model, pm, few_world, few_pairs, inner);
    };
    std::vector<double> ym;
    const auto island = [&](double tm) {
      ym = yb;
      a.integrate(t, tm, ym, inner);
      ++c_.counters.impact_evaluations;
      c_.counters.impact_bodies_integrated += a.world.size();
      return c_.depth_of(a.model, ym, a.world, pairs, inner);
    };
    const auto island_trial = [&](double tm) {
      ++c_.counters.impact_iterations;
      return island(tm);
    };
    const double g_lo = c_.depth_of(p.model, pb, few_world, few_pairs, inner);
    // Already deeper than the tolerance at t (a correction pushed one body
    // into a third): no earlier time can be in the band; don't search.
    Searched r;
    if (g_lo <= how.tol) {
      if (setup.settings.impact_motion == ImpactMotion::integrate) {
        r = search_impact(how, alone, t, tb, g_lo, d.max_depth);
      } else {
        const auto interpolated = [&](double tm) {
          ++c_.counters.impact_interpolations;
          ++c_.counters.impact_iterations;
          const double s = (tm - t) / (tb - t);
          return c_.depth_at(a.world, pairs, [&](int k) {
            return Bodies::interpolated_pose(a.model, yb, ys, static_cast<std::size_t>(k), s);
          }, inner);
        };
        r = search_impact(how, interpolated, t, tb, g_lo, d.max_depth);
        if (r.found) {
          const double g = alone(r.t);  // the true motion there
          if (!(g > 0 && g <= how.tol)) {
            ++c_.counters.impact_interpolation_misses;
            r = search_again(how, alone, t, tb, g_lo, d.max_depth, r.t, g);
          }
        } else {
          r = search_impact(how, alone, t, tb, g_lo, d.max_depth);
        }
      }
      // The island once, to the time found; the search again over the
      // island's own motion if there the pairs are not in the band.
      if (r.found && r.t - t > 1e-6 * (tb - t)) {
        const double g = island(r.t);
        if (!(g > 0 && g <= how.tol)) {
          ++c_.counters.impact_island_misses;
          r = search_again(how, island_trial, t, tb, g_lo, d.max_depth, r.t, g);
        }
      }
    }
    // No time in the band, or one so close to t that the search would make
    // no progress (Zeno): take the whole sub-step; response and correction
    // resolve the depth. Progress is then always at least one sub-step.
    if (r.found && r.t - t <= 1e-6 * (tb - t)) r.found = false;
    if (!r.found) {
      ++c_.counters.unresolved_searches;
      return tb;  // ys already holds the state at tb
    }
    ys.swap(ym);
    return r.t;
  }

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
  // interval's two ends plus what gravity adds over it.
  double closing_speed(const Alone& a, const std::vector<std::pair<int, int>>& pairs, const std::vector<double>& yb,
                       const std::vector<double>& ys, double h) const {
    if (c_.setup.settings.time_of_impact != TimeOfImpact::conservative_advancement) return 0;
    const auto rim = [&](int k) {
      const auto b = static_cast<std::size_t>(k);
      if (c_.setup.is_static[a.world[b]]) return 0.0;
      return std::max(c_.rim_speed(a.model, yb, a.world, b), c_.rim_speed(a.model, ys, a.world, b)) +
             c_.setup.gravity * h;
    };
    double most = 0;
    for (const auto& [i, j] : pairs) most = std::max(most, rim(i) + rim(j));
    return most;
  }
};

}  // namespace gacompare::core
