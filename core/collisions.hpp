#pragma once
// Collisions between rigid bodies in the simulation loop (issues #6 and #7,
// §2.4–2.5, fig. 11), written once over a backend: its rigid bodies (pose,
// velocity_at, inverse_effective_mass, apply_impulse, translate), its
// narrowphase view of a body and its bounding-sphere algebra. Only built when
// the scene lists the `collisions` effect; otherwise nothing here runs.
//
// One collision step from an accepted state (t0, y0), §2.5.1's double buffer:
//   1. integrate to t1 = t0 + h (h ≤ the effect's `step`, shorter where a body
//      could move more than half the smallest inradius: no tunnelling);
//   2. broadphase (sort and sweep over bounding spheres) and narrowphase (the
//      report's detector; separating-axis depth) at t1;
//   3. deeper than the penetration tolerance: time of impact. y0 is still
//      there; search t* in (t0, t1) where the deepest contact is in (0, tol],
//      re-integrating from y0 for every trial time: bisection (§2.5.1) or
//      Illinois regula falsi on the depth (§4.3's "more advanced methods");
//   4. response at the accepted time: impulses at every feature contact
//      (eq. 53 / 54 per contact, solved together), then positional correction.
//
// The resting-contact rule (the report has none; fn 29 only asks that all
// contacts meet the tolerance before any response):
//   - a contact whose approach speed is below v_rest = √(2 |g| tol) + 2 |g| h
//     (the speed a body gains falling through the tolerance, plus two steps of
//     gravity) gets restitution 0: it stops instead of bouncing ever smaller;
//   - simultaneous contacts are solved together by projected Gauss–Seidel on
//     the impulses λ_i ≥ 0 with targets v_n⁺ ≥ −ε v_n⁻ (a cube landing flat on
//     four corners bounces straight; one contact at a time would spin it),
//     at most kMaxSweeps sweeps;
//   - a pair deeper than tol/2 after the impulses is pushed apart along its
//     separating-axis normal to tol/4 (by inverse mass), so a resting body
//     never creeps down to the tolerance and forces a time-of-impact search
//     that can make no progress. The push does work against gravity of at most
//     m g tol/4 per correction; the counters say how many there were. Pairs
//     that part after an impact are never pushed: a translation changes the
//     angular momentum about the origin (x × m v), which an elastic impact
//     must conserve.
#include "core/bounding_volume.hpp"
#include "core/broadphase.hpp"
#include "core/collision.hpp"
#include "core/error.hpp"
#include "core/narrowphase.hpp"
#include "core/rigid_body.hpp"
#include "core/scene.hpp"
#include "core/stage.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace gacompare::core {

inline constexpr int kMaxSweeps = 50;         // Gauss–Seidel sweeps per response
inline constexpr int kMaxImpactIterations = 60;  // time-of-impact trials per search (2⁻⁶⁰ of a step)

struct CollisionCounters {
  std::uint64_t steps = 0, shortened_steps = 0, broadphase_candidates = 0, narrowphase_pairs = 0;
  std::uint64_t impact_searches = 0, impact_iterations = 0, impact_evaluations = 0, unresolved_searches = 0;
  std::uint64_t contacts = 0, impulses = 0, resting_contacts = 0, sweeps = 0, corrections = 0;
  void add_to(std::map<std::string, std::uint64_t>& out) const;
};

// The backend-neutral part, built once: each body's mesh with its centre of mass
// at the origin, its bounding sphere in body coordinates, inradius, restitution.
struct CollisionSetup {
  Collisions settings;
  std::vector<std::string> names;
  std::vector<std::shared_ptr<const Mesh>> meshes;
  std::vector<Vec3> sphere_centre;  // body frame
  std::vector<double> sphere_radius, inradius, restitution;
  std::vector<bool> is_static;
  double gravity = 0;       // |g|
  double resting_speed = 0;  // v_rest above
  double min_inradius = 0;
};

// Meshes, inradii and restitution (throws input_error for a non-convex body).
// The bounding spheres are filled by build_collisions (per backend).
CollisionSetup collision_setup(const Scene& scene);

// One pair in contact: the separating-axis answer and the report's contacts.
struct PairHit {
  int a = 0, b = 0;
  collision::PairContact sat;
  std::vector<collision::FeatureContact> features;
};
struct Detection {
  double max_depth = -INFINITY;  // over the pairs in contact; −∞ when none
  std::vector<PairHit> hits;
};

template <class Bodies, class NarrowBody, class Spheres>
struct Collider {
  using Model = typename Bodies::Model;
  CollisionSetup setup;
  mutable CollisionCounters counters;

  static Collider build(const Scene& scene, const Model& m, Profile& profile) {
    Collider c{collision_setup(scene), {}};
    {
      ScopedStage timed(profile, Stage::bounding_volumes);
      std::mt19937_64 rng(1);  // Welzl's shuffle: fixed, so runs repeat exactly
      for (const auto& mesh : c.setup.meshes) {
        const auto s = welzl_sphere<Spheres>(std::span<const Vec3>(mesh->vertices()), rng).sphere;
        c.setup.sphere_centre.push_back(Spheres::centre(s));
        c.setup.sphere_radius.push_back(Spheres::radius(s));
      }
    }
    // fn 28: bodies must not start in collision.
    const Detection d = c.detect(m, m.y0, profile);
    for (const auto& h : d.hits)
      if (h.sat.depth > c.setup.settings.penetration_tolerance)
        throw input_error("bodies '" + c.setup.names[h.a] + "' and '" + c.setup.names[h.b] + "' overlap at t = 0 by " +
                          std::to_string(h.sat.depth) + " m, more than the penetration tolerance (" +
                          std::to_string(c.setup.settings.penetration_tolerance) +
                          " m): a scene must start without collisions (§2.4.3 fn 28)");
    c.counters = {};
    return c;
  }

  // Every body's pose at state y, once per detection (a rotor or quaternion
  // becomes a matrix here, not once per pair it takes part in).
  std::vector<collision::Pose> poses(const Model& m, std::span<const double> y) const {
    std::vector<collision::Pose> out;
    out.reserve(setup.meshes.size());
    for (std::size_t b = 0; b < setup.meshes.size(); ++b) out.push_back(Bodies::pose(m, y, b));
    return out;
  }
  collision::Placed placed(const std::vector<collision::Pose>& pose, std::size_t b) const {
    return {setup.meshes[b].get(), pose[b]};
  }

  // Broadphase and narrowphase at one state.
  Detection detect(const Model& m, std::span<const double> y, Profile& profile) const {
    const std::size_t n = setup.meshes.size();
    BroadphaseResult pairs;
    std::vector<collision::Pose> pose;
    {
      ScopedStage timed(profile, Stage::broadphase);
      pose = poses(m, y);
      std::vector<typename Spheres::Sphere> spheres;
      spheres.reserve(n);
      for (std::size_t b = 0; b < n; ++b)
        spheres.push_back(Spheres::sphere(pose[b].apply(setup.sphere_centre[b]), setup.sphere_radius[b]));
      pairs = sort_and_sweep<Spheres>(std::span<const typename Spheres::Sphere>(spheres));
      counters.broadphase_candidates += static_cast<std::uint64_t>(pairs.counters.candidates);
    }
    ScopedStage timed(profile, Stage::narrowphase);
    Detection d;
    for (const auto& [i, j] : pairs.pairs) {
      if (setup.is_static[i] && setup.is_static[j]) continue;
      ++counters.narrowphase_pairs;
      PairHit h{i, j, {}, {}};
      h.sat = collision::narrowphase<NarrowBody>(placed(pose, i), placed(pose, j), collision::Method::sat_then_report,
                                                 &h.features);
      if (!h.sat.intersect) continue;
      d.max_depth = std::max(d.max_depth, h.sat.depth);
      d.hits.push_back(std::move(h));
    }
    return d;
  }

  // The deepest separating-axis depth among the given pairs (the time-of-impact
  // function: continuous in time, unlike the feature test's yes/no).
  double depth_of(const Model& m, std::span<const double> y, const std::vector<std::pair<int, int>>& pairs,
                  Profile& profile) const {
    ScopedStage timed(profile, Stage::narrowphase);
    double g = -INFINITY;
    for (const auto& [i, j] : pairs)
    {  // few pairs, each body in one or two: their poses only
      const collision::Placed a{setup.meshes[i].get(), Bodies::pose(m, y, i)};
      const collision::Placed b{setup.meshes[j].get(), Bodies::pose(m, y, j)};
      const Vec3 o = collision::local_origin(a, b);
      g = std::max(g, collision::separating_axis(NarrowBody(a, o), NarrowBody(b, o)).depth);
    }
    return g;
  }

  // How long a step may be: no body moves more than half the smallest inradius.
  double step_limit(const Model& m, std::span<const double> y, double h) const {
    double reach = 0;
    for (std::size_t b = 0; b < setup.meshes.size(); ++b) {
      if (setup.is_static[b]) continue;
      const collision::Pose p = Bodies::pose(m, y, b);
      const Vec3 v = Bodies::velocity_at(m, y, b, p.position);
      double spin = 0;  // ≥ ρ|ω|: the rim speeds along three axes
      for (int k = 0; k < 3; ++k)
        spin += (Bodies::velocity_at(m, y, b, p.position + setup.sphere_radius[b] * p.rotation.col(k)) - v).norm();
      reach = std::max(reach, (v.norm() + spin) * h + 0.5 * setup.gravity * h * h);
    }
    const double limit = 0.5 * setup.min_inradius;
    return reach > limit ? h * limit / reach : h;
  }

  // §2.5: impulses at every feature contact, solved together; then the
  // positional correction (see the top of this file).
  void respond(const Model& m, std::span<double> y, const Detection& d, Profile& profile) const {
    ScopedStage timed(profile, Stage::response);
    struct Row {
      int a, b;
      Vec3 p, n;
      double k, target, lambda;
    };
    std::vector<Row> rows;
    std::vector<char> resting_pair(d.hits.size(), 0);
    for (std::size_t hi = 0; hi < d.hits.size(); ++hi) {
      const auto& h = d.hits[hi];
      const double eps = std::min(setup.restitution[h.a], setup.restitution[h.b]);
      for (const auto& c : h.features) {
        const double k = Bodies::inverse_effective_mass(m, y, h.a, c.point, c.normal) +
                         Bodies::inverse_effective_mass(m, y, h.b, c.point, c.normal);
        if (!(k > 0)) continue;
        const double vn = c.normal.dot(Bodies::velocity_at(m, y, h.b, c.point) - Bodies::velocity_at(m, y, h.a, c.point));
        const bool resting = vn < 0 && -vn <= setup.resting_speed;
        counters.resting_contacts += resting;
        resting_pair[hi] |= resting;
        rows.push_back({h.a, h.b, c.point, c.normal, k, vn < 0 ? -(resting ? 0.0 : eps) * vn : 0.0, 0.0});
      }
    }
    counters.contacts += rows.size();
    double scale = 0;
    for (const auto& r : rows) scale = std::max(scale, std::abs(r.target));
    for (int sweep = 0; sweep < kMaxSweeps && !rows.empty(); ++sweep) {
      ++counters.sweeps;
      double worst = 0;
      for (auto& r : rows) {
        const double vn = r.n.dot(Bodies::velocity_at(m, y, r.b, r.p) - Bodies::velocity_at(m, y, r.a, r.p));
        const double next = std::max(0.0, r.lambda + (r.target - vn) / r.k);
        const double dl = next - r.lambda;
        if (dl == 0) continue;
        worst = std::max(worst, std::abs(dl) * r.k);
        r.lambda = next;
        Bodies::apply_impulse(m, y, r.b, r.p, dl * r.n);
        Bodies::apply_impulse(m, y, r.a, r.p, -dl * r.n);
        ++counters.impulses;
      }
      if (worst <= 1e-6 * (1 + scale)) break;  // m/s: a millionth of the fastest approach (or of 1 m/s)
    }
    const double tol = setup.settings.penetration_tolerance;
    for (std::size_t hi = 0; hi < d.hits.size(); ++hi) {
      const auto& h = d.hits[hi];
      if (!(h.sat.depth > 0.5 * tol)) continue;
      const double parting = h.sat.normal.dot(Bodies::velocity_at(m, y, h.b, h.sat.contact) -
                                              Bodies::velocity_at(m, y, h.a, h.sat.contact));
      if (!resting_pair[hi] && parting > setup.resting_speed) continue;  // an impact: the bodies part by themselves
      const double wa = setup.is_static[h.a] ? 0.0 : 1.0, wb = setup.is_static[h.b] ? 0.0 : 1.0;
      // The bodies' inverse masses along the normal, at their centres (no turning).
      const double ia = wa * Bodies::inverse_effective_mass(m, y, h.a, Bodies::pose(m, y, h.a).position, h.sat.normal);
      const double ib = wb * Bodies::inverse_effective_mass(m, y, h.b, Bodies::pose(m, y, h.b).position, h.sat.normal);
      if (!(ia + ib > 0)) continue;
      const double push = h.sat.depth - 0.25 * tol;
      Bodies::translate(m, y, h.a, (-push * ia / (ia + ib)) * h.sat.normal);
      Bodies::translate(m, y, h.b, (push * ib / (ia + ib)) * h.sat.normal);
      ++counters.corrections;
    }
  }
};

}  // namespace gacompare::core
