#pragma once
// Collisions between rigid bodies in the simulation loop (issues #6, #7, #12,
// §2.4–2.5, fig. 11), written once over a backend: its rigid bodies (pose, and
// the contact solver's Motion: arm, inverse_effective_mass, normal_velocity,
// push, store, displace), its narrowphase view of a body and its
// bounding-sphere algebra. Only built when the scene lists the `collisions`
// effect; otherwise nothing here runs.
//
// One collision step from an accepted state (t0, y0), §2.5.1's double buffer,
// island by island (core/collision_step.hpp):
//   1. integrate the world to t1 = t0 + step;
//   2. broadphase (over bounding spheres grown by how far each body can move
//      in the step, core/broadphase.hpp) and narrowphase at t1: the separating-axis
//      depth, and for pairs in contact the contact manifold (method
//      "manifold", core/manifold.hpp) or the report's detector (method
//      "report", fig. 7); the grown spheres' overlaps link the bodies into
//      islands (core/islands.hpp);
//   3. an island with a pair deeper than the penetration tolerance, or a body
//      that could move more than half the smallest inradius in the step (no
//      tunnelling), is stepped alone from y0 in sub-steps, with a time of
//      impact search where a pair went too deep: t* where the deepest contact
//      is in (0, tol], re-integrating the island for every trial time:
//      bisection (§2.5.1) or Illinois regula falsi on the depth (§4.3's "more
//      advanced methods");
//   4. response at the accepted time, per island: impulses at every contact
//      (eq. 53 / 54 as each row's effective mass), solved together, then the
//      positional correction.
//
// Resting contact (the report has none; fn 29 only asks that all contacts meet
// the tolerance before any response):
//   - a contact whose approach speed is below v_rest = √(2 |g| tol) + 2 |g| h
//     (the speed a body gains falling through the tolerance, plus two steps of
//     gravity) gets restitution 0: it stops instead of bouncing ever smaller;
//   - simultaneous contacts are solved together by projected Gauss–Seidel
//     with accumulated clamping (sequential impulses: each contact's total
//     impulse λ ≥ 0, targets v_n⁺ ≥ −ε v_n⁻; a cube landing flat on four
//     corners bounces straight, one contact at a time would spin it), at most
//     kMaxSweeps sweeps (the cap hits are counted);
//   - contacts found again in the next step start from their last impulse
//     (warm starting), so a stack's load is carried from step to step instead
//     of being solved afresh through every box;
//   - a pair deeper than tol/2 after the impulses is brought to tol/4 by a
//     split impulse (pseudo-velocities that move the bodies along the contact
//     normals without touching their momenta), so a resting body never creeps down to the
//     tolerance and forces a time-of-impact search that can make no progress.
//     The lift does work against gravity of at most m g tol/4 per correction;
//     the counters say how many there were. Pairs that part after an impact
//     are never corrected: a translation changes the angular momentum about
//     the origin (x × m v), which an elastic impact must conserve.
//
// Coulomb friction (issue #17; beyond the report, whose response is
// frictionless): only for pairs with μ = √(μ_a μ_b) > 0, two tangent rows per
// contact in the same Gauss–Seidel, held in the disc |λ_t| ≤ μ λ_n and warm
// started (Friction below), and resting contacts displaced by ½ h of their
// impulses' velocity change (friction_displacement). With μ = 0 no friction
// row exists and every run is as before, bit for bit.
#include "core/bounding_volume.hpp"
#include "core/broadphase.hpp"
#include "core/collision.hpp"
#include "core/error.hpp"
#include "core/narrowphase.hpp"
#include "core/pair_memory.hpp"
#include "core/rigid_body.hpp"
#include "core/scene.hpp"
#include "core/stage.hpp"
#include "core/time_of_impact.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace gacompare::core {

// Gauss–Seidel sweeps per solve: a safety stop, counted when reached. A chain
// of n bodies converges at about cos²(π/(n+1)) per sweep, so the first solve
// of a stack of ten, before warm starting has anything to start from, needs
// ~300 sweeps to reach kVelocityTolerance; with a cap of 200 its residual
// leaves the boxes sinking and the stack falls (measured), with 500 it stands.
inline constexpr int kMaxSweeps = 1000;
// The velocity solve stops when no sweep changes a contact's velocity by more
// than this (m/s), times 1 + the fastest approach. It is tight because a
// frictionless stack turns any residual into drift: the corners of a face
// contact form a redundant set (four rows, three degrees of freedom) on which
// Gauss–Seidel converges slowly, a residual leaves a tilt, a tilted face's
// normal has a sideways part, and every step's load then pushes sideways. A
// stack of ten 0.2 m cubes over 10 s drifts sideways 9e-6 m at 1e-9,
// 2.6e-6 m at 1e-10, 6e-7 m at 1e-11 and 2.4e-7 m at 1e-12, for 0.41, 0.51,
// 0.59 and 0.78 s of run time (traditional; warm starting keeps it to
// ~35 sweeps a step).
inline constexpr double kVelocityTolerance = 1e-11;

struct CollisionCounters {
  std::uint64_t steps = 0, shortened_steps = 0, broadphase_candidates = 0, narrowphase_pairs = 0;
  std::uint64_t broadphase_tree_updates = 0, broadphase_pairs_kept = 0;  // summed over detections
  std::uint64_t impact_searches = 0, impact_iterations = 0, impact_evaluations = 0, unresolved_searches = 0;
  std::uint64_t impact_interpolations = 0, impact_interpolation_misses = 0;  // impact_motion "interpolate"
  // Bodies integrated by the searches' trials (the deep pairs' bodies, or an
  // island when the pairs' time missed the band on the island's motion).
  std::uint64_t impact_bodies_integrated = 0, impact_island_misses = 0;
  std::uint64_t contacts = 0, impulses = 0, resting_contacts = 0, sweeps = 0, corrections = 0;
  std::uint64_t warm_started = 0, sweep_cap_hits = 0, correction_cap_hits = 0, unresolved_impacts = 0;
  // Islands (core/islands.hpp, core/collision_step.hpp): the islands with a
  // candidate pair, those stepped on their own (a pair too deep or a step
  // too long for them), the bodies those held (each re-integrated from the
  // step's start) and the largest island seen.
  std::uint64_t islands = 0, local_islands = 0, local_island_bodies = 0, largest_island = 0, local_steps = 0;
  std::uint64_t island_narrowphase_pairs = 0;  // of narrowphase_pairs, those tested in islands' sub-steps
  std::uint64_t links_apart = 0;  // candidate pairs unlinked: apart by more than their reach (collision_step.hpp)
  std::uint64_t links_face_tested = 0;  // of the pairs apart, those whose link every face normal decided
  std::uint64_t narrowphase_shapes = 0, narrowphase_axes_kept = 0;  // bodies' geometry built; pairs their last axis decided
  // Friction (issue #17): the contacts given friction rows, those whose
  // friction ended on the cone (sliding) and the friction rows warm started.
  std::uint64_t friction_contacts = 0, sliding_contacts = 0, friction_warm_started = 0;
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
  std::vector<double> friction;  // each body's μ (core/scene.hpp Body::friction)
  std::vector<char> is_static;
  // A static body's box in its own frame (the mesh's bounding box, centre and
  // half sides): the broadphase's spheres are loose about a slab or a wall, so
  // a pair with a static body is kept only where the other body's sphere
  // reaches this box (Collider::reaches_static).
  std::vector<Vec3> static_mid, static_half;
  std::vector<int> everyone;  // 0 … n − 1: the world as a group (see Collider)
  SolverSpec solver;          // the scene's: an island is integrated alone with it
  double gravity = 0;       // |g|
  double resting_speed = 0;  // v_rest above
  double min_inradius = 0;
};

// Meshes, inradii and restitution (throws input_error for a non-convex body).
// The bounding spheres are filled by build_collisions (per backend).
CollisionSetup collision_setup(const Scene& scene);

// One pair in contact: the separating-axis answer and the report's contacts.
// a and b are the bodies' indices in the group detected (see Collider).
struct PairHit {
  int a = 0, b = 0;
  collision::PairContact sat;
  std::vector<collision::FeatureContact> features;
};
struct Detection {
  double max_depth = -INFINITY;  // over the pairs in contact; −∞ when none
  std::vector<PairHit> hits;
  // With margins: the pairs whose grown spheres overlap (i < j, sorted), a
  // superset of the pairs the narrowphase tested; the islands' links.
  std::vector<std::pair<int, int>> candidates;
  // With margins: the pairs found farther apart than both bodies can move in
  // the step (Collider::note_apart), in the order tested; they link nothing.
  std::vector<std::pair<int, int>> apart;
};

// The collider works on a group of bodies: the whole world (the world's model
// and state, `setup.everyone` as the group) or one island integrated on its
// own (an island's sub-model, core/collision_step.hpp). Body k of the group's
// model is world body world[k]: meshes, spheres, restitution and the
// warm-start cache are the world's, the state and the motions the group's.
template <class Bodies, class NarrowBody, class Spheres>
struct Collider {
  using Model = typename Bodies::Model;
  using BodiesType = Bodies;
  using World = std::span<const int>;
  CollisionSetup setup;
  mutable CollisionCounters counters;
  mutable Broadphase<Spheres> broadphase_;  // its trees and pairs persist between detections

  static Collider build(const Scene& scene, const Model& m, Profile& profile) {
    Collider c;
    c.setup = collision_setup(scene);
    c.broadphase_ = Broadphase<Spheres>(c.setup.settings.broadphase);
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
    const Detection d = c.detect(m, m.y0, c.setup.everyone, {}, profile);
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
  std::vector<collision::Pose> poses(const Model& m, std::span<const double> y, World world) const {
    std::vector<collision::Pose> out;
    out.reserve(world.size());
    for (std::size_t k = 0; k < world.size(); ++k) out.push_back(Bodies::pose(m, y, k));
    return out;
  }
  collision::Placed placed(const std::vector<collision::Pose>& pose, World world, int k) const {
    return {setup.meshes[world[k]].get(), pose[k]};
  }

  // Broadphase and narrowphase at one state of a group. margin (empty, or one
  // per body of the group) grows each body's sphere by how far it can move in
  // the step: the grown spheres' overlaps are the candidates (the islands'
  // links, Detection::candidates), and the narrowphase tests the candidates
  // whose own spheres overlap.
  Detection detect(const Model& m, std::span<const double> y, World world, std::span<const double> margin,
                   Profile& profile) const {
    const std::size_t n = world.size();
    Detection d;
    std::vector<std::pair<int, int>> pairs;
    std::vector<collision::Pose> pose;
    {
      ScopedStage timed(profile, Stage::broadphase);
      pose = poses(m, y, world);
      // The method, the state it keeps and the frame the spheres are held in:
      // core/broadphase.hpp. Only the world keeps its broadphase between
      // detections; another group without its candidates (detect_among) is
      // swept afresh.
      const std::vector<Vec3> centres = sphere_centres(pose, world);
      std::vector<double> radii(n);
      std::vector<char> fixed(n);
      for (std::size_t k = 0; k < n; ++k) {
        radii[k] = setup.sphere_radius[world[k]];
        fixed[k] = setup.is_static[world[k]];
      }
      BroadphaseResult found = world.data() == setup.everyone.data()
                                   ? broadphase_.find(centres, radii, fixed, margin)
                                   : Broadphase<Spheres>(BroadphaseMethod::sweep).find(centres, radii, fixed, margin);
      pairs = std::move(found.pairs);
      d.candidates = std::move(found.candidates);
      const auto away = [&](std::span<const double> grow) {
        return [&, grow](const std::pair<int, int>& p) { return misses_static(pose, world, centres, p, grow); };
      };
      std::erase_if(pairs, away({}));
      std::erase_if(d.candidates, away(margin));
      counters.broadphase_candidates += static_cast<std::uint64_t>(found.counters.candidates);
      counters.broadphase_tree_updates += static_cast<std::uint64_t>(found.counters.tree_updates);
      counters.broadphase_pairs_kept += static_cast<std::uint64_t>(found.counters.pairs_kept);
    }
    narrow(world, pose, pairs, d, profile, margin);
    return d;
  }

  // The same for a group whose candidate pairs are known (an island within
  // its step: the pairs its bodies' grown spheres link, core/collision_step.hpp):
  // of those, the pairs whose own spheres overlap (in a frame at the group's
  // mean position) and that reach a static body's box go to the narrowphase.
  Detection detect_among(const Model& m, std::span<const double> y, World world,
                         std::span<const std::pair<int, int>> candidates, Profile& profile) const {
    const std::size_t n = world.size();
    Detection d;
    std::vector<std::pair<int, int>> pairs;
    std::vector<collision::Pose> pose;
    {
      ScopedStage timed(profile, Stage::broadphase);
      pose = poses(m, y, world);
      const std::vector<Vec3> centres = sphere_centres(pose, world);
      Vec3 frame = Vec3::Zero();
      for (const Vec3& c : centres) frame += c;
      if (n > 0) frame /= static_cast<double>(n);
      std::vector<typename Spheres::Sphere> spheres;
      spheres.reserve(n);
      for (std::size_t k = 0; k < n; ++k) spheres.push_back(Spheres::sphere(centres[k] - frame, setup.sphere_radius[world[k]]));
      for (const auto& p : candidates) {
        const auto [i, j] = p;
        ++counters.broadphase_candidates;
        if (setup.is_static[world[i]] && setup.is_static[world[j]]) continue;
        if (!Spheres::overlap(spheres[static_cast<std::size_t>(i)], spheres[static_cast<std::size_t>(j)])) continue;
        if (misses_static(pose, world, centres, p, {})) continue;
        pairs.emplace_back(i, j);
      }
    }
    narrow(world, pose, pairs, d, profile);
    return d;
  }

  // Whether pair p of a group is a moving and a static body and the moving
  // one's sphere (grown by grow[o] when grow is given) misses the static
  // body's box (reaches_static).
  bool misses_static(const std::vector<collision::Pose>& pose, World world, const std::vector<Vec3>& centres,
                     const std::pair<int, int>& p, std::span<const double> grow) const {
    const auto [i, j] = p;
    const bool si = setup.is_static[world[i]];
    if (si == static_cast<bool>(setup.is_static[world[j]])) return false;
    const int s = si ? i : j, o = si ? j : i;
    const double r = setup.sphere_radius[world[o]] + (grow.empty() ? 0.0 : grow[o]);
    return !reaches_static(pose[s], world[s], centres[o], r);
  }

  // Each body's bounding-sphere centre in the world at its pose.
  std::vector<Vec3> sphere_centres(const std::vector<collision::Pose>& pose, World world) const {
    std::vector<Vec3> c(world.size());
    for (std::size_t k = 0; k < world.size(); ++k) c[k] = pose[k].apply(setup.sphere_centre[world[k]]);
    return c;
  }

  // The narrowphase of a group's pairs into d (hits and their deepest depth).
  void narrow(World world, const std::vector<collision::Pose>& pose, const std::vector<std::pair<int, int>>& pairs,
              Detection& d, Profile& profile, std::span<const double> margin = {}) const {
    ScopedStage timed(profile, Stage::narrowphase);
    const auto method = setup.settings.method == ContactMethod::report ? collision::Method::sat_then_report
                                                                       : collision::Method::sat_then_manifold;
    ++detection_;
    if (world.data() == setup.everyone.data()) hints_.next();  // the world's detection: a new round of pairs
    for (const auto& pair : pairs) {
      int i = pair.first, j = pair.second;  // plain ints: lambdas below capture them (clang 14 cannot capture a binding)
      if (setup.is_static[world[i]] && setup.is_static[world[j]]) continue;
      if (world[i] > world[j]) std::swap(i, j);  // a < b in the world: every group sees a pair the same way
      ++counters.narrowphase_pairs;
      if (world.data() != setup.everyone.data()) ++counters.island_narrowphase_pairs;
      PairHit h{i, j, {}, {}};
      if (setup.settings.reuse) {
        const int a = world[i], b = world[j];
        const Shape& sa = shape(a, [&] { return pose[i]; });
        const Shape& sb = shape(b, [&] { return pose[j]; });
        collision::SatHint& hint = hints_.at(a, b);
        h.sat = collision::narrowphase<NarrowBody>(sa, sb, method, &h.features, &hint);
        counters.narrowphase_axes_kept += hint.kept;
      } else {
        h.sat = collision::narrowphase<NarrowBody>(placed(pose, world, i), placed(pose, world, j), method, &h.features);
        counters.narrowphase_shapes += 2;
      }
      // A pair within the touching band is in contact too (it has contacts):
      // its yes/no is rounding's (core/collision.hpp), and a box resting
      // exactly on another fell for a step whenever it rounded to apart.
      if (!h.sat.intersect && h.features.empty()) {
        if (!margin.empty()) note_apart(world, pose, h, margin, d);
        continue;
      }
      d.max_depth = std::max(d.max_depth, h.sat.depth);
      d.hits.push_back(std::move(h));
    }
  }

  // A pair the world's detection found apart, kept in d.apart when it is
  // farther apart than both bodies can move in the step (the islands' links
  // leave it out: core/collision_step.hpp, unlink_far): when some face
  // normal separates it by more than that (collision::face_gap, which stops
  // at the first that does; a round pair by its exact distance).
  // Not simply by the gap the narrowphase stopped at: its first axis is the
  // pair's remembered one when geometry is reused (setup.settings.reuse), and
  // a link must not depend on that. A face axis's gap bounds the faces' best
  // from below, so where it already exceeds the reaches it decides alone.
  void note_apart(World world, const std::vector<collision::Pose>& pose, const PairHit& h,
                  std::span<const double> margin, Detection& d) const {
    const int wa = world[h.a], wb = world[h.b];
    const double reach = margin[h.a] + margin[h.b] +
                         collision::kTouchingBand * collision::pair_scale(*setup.meshes[wa], *setup.meshes[wb]);
    double gap = -h.sat.depth;
    const bool face = h.sat.feature == collision::Feature::face_a || h.sat.feature == collision::Feature::face_b;
    if (!(face && gap > reach))
      gap = on_pair(wa, wb, [&] { return pose[h.a]; }, [&] { return pose[h.b]; }, [&](const NarrowBody& va, const NarrowBody& vb) {
        if (collision::round_pair(va, vb)) return gap;  // already exact
        ++counters.links_face_tested;
        return collision::face_gap(va, vb, reach);
      });
    if (gap > reach) d.apart.emplace_back(h.a, h.b);
  }

  // f(va, vb) over world bodies wa and wb placed by pose_a() and pose_b(),
  // in the pair's own frame: with reuse, the bodies' shapes of this
  // detection; without, the pair's own, built here.
  template <class PoseA, class PoseB, class F>
  auto on_pair(int wa, int wb, PoseA&& pose_a, PoseB&& pose_b, F&& f) const {
    Shape own_a, own_b;
    if (!setup.settings.reuse) {
      own_a.place({setup.meshes[wa].get(), pose_a()}), own_b.place({setup.meshes[wb].get(), pose_b()});
      counters.narrowphase_shapes += 2;
    }
    const Shape& a = setup.settings.reuse ? shape(wa, pose_a) : own_a;
    const Shape& b = setup.settings.reuse ? shape(wb, pose_b) : own_b;
    const Vec3 o = collision::local_origin(a.position(), b.position());
    return f(NarrowBody(a, a.position() - o), NarrowBody(b, b.position() - o));
  }

  // Whether a sphere (centre c, radius r, world) reaches static body s's box
  // placed by its pose: the box point nearest c within r, padded by the
  // touching band and the rounding of the coordinates, so that no pair the
  // narrowphase would call touching is dropped. Algebra-neutral, like the
  // AABB tree: a filter on which pairs are tested, not a part of either
  // backend's geometry.
  bool reaches_static(const collision::Pose& pose, int s, const Vec3& c, double r) const {
    const Vec3 q = pose.rotation.transpose() * (c - pose.position) - setup.static_mid[s];
    const Vec3 h = setup.static_half[s];
    const Vec3 out = (q.cwiseAbs() - h).cwiseMax(0.0);
    const double pad = collision::kTouchingBand * (r + h.norm()) + 1e-14 * (c - pose.position).norm();
    return out.squaredNorm() <= (r + pad) * (r + pad);
  }

  // The deepest separating-axis depth among the given pairs of the group (the
  // time-of-impact function: continuous in time, unlike the feature test's
  // yes/no), at state y, or with each body placed by pose_of(k).
  double depth_of(const Model& m, std::span<const double> y, World world, const std::vector<std::pair<int, int>>& pairs,
                  Profile& profile) const {
    return depth_at(world, pairs, [&](int k) { return Bodies::pose(m, y, static_cast<std::size_t>(k)); }, profile);
  }
  template <class PoseOf>
  double depth_at(World world, const std::vector<std::pair<int, int>>& pairs, PoseOf&& pose_of, Profile& profile) const {
    ScopedStage timed(profile, Stage::narrowphase);
    double g = -INFINITY;
    ++detection_;
    for (const auto& pair : pairs) {  // few pairs, each body in one or two: their poses only
      const int i = pair.first, j = pair.second;
      g = std::max(g, on_pair(world[i], world[j], [&] { return pose_of(i); }, [&] { return pose_of(j); },
                              [](const NarrowBody& va, const NarrowBody& vb) {
                                return (collision::round_pair(va, vb) ? collision::round_narrowphase(va, vb)
                                                                      : collision::separating_axis(va, vb))
                                    .depth;
                              }));
    }
    return g;
  }

  // How fast body k's rim can move: |v| + ρ|ω|, ρ its bounding radius.
  double rim_speed(const Model& m, std::span<const double> y, World world, std::size_t k) const {
    if (setup.is_static[world[k]]) return 0;
    const auto mo = Bodies::motion(m, y, k);
    return Bodies::speed(mo) + setup.sphere_radius[world[k]] * Bodies::angular_speed(mo);
  }

  // How far body k of the group can move in h: a point at distance ρ from the
  // centre moves at most (|v| + ρ|ω|) h, and gravity adds ½ g h². 0 when static.
  double reach(const Model& m, std::span<const double> y, World world, std::size_t k, double h) const {
    if (setup.is_static[world[k]]) return 0;
    return rim_speed(m, y, world, k) * h + 0.5 * setup.gravity * h * h;
  }

  // How long a step of the group may be: no body moves more than half the
  // smallest inradius (of the world: a conservative bound for every island).
  double step_limit(const Model& m, std::span<const double> y, World world, double h) const {
    double most = 0;
    for (std::size_t k = 0; k < world.size(); ++k) most = std::max(most, reach(m, y, world, k, h));
    const double limit = 0.5 * setup.min_inradius;
    return most > limit ? h * limit / most : h;
  }

  // §2.5: impulses at every contact of `hits` (pairs of the group), solved
  // together, then the positional correction (see the top of this file). `dt`
  // is the time since the group's last accepted state: warm-started impulses
  // scale with it.
  void respond(const Model& m, std::span<double> y, World world, std::span<const PairHit> hits, double dt,
               Profile& profile) const {
    ScopedStage timed(profile, Stage::response);
    // The bodies in contact, read once, in slots the rows index (no lookup in
    // the solver's sweeps).
    Motions motion;
    std::vector<int> body_of;  // slot → body of the group
    std::unordered_map<int, std::size_t> slot_of;
    const auto slot = [&](int b) {
      const auto [it, fresh] = slot_of.emplace(b, motion.size());
      if (fresh) motion.push_back(Bodies::motion(m, y, static_cast<std::size_t>(b))), body_of.push_back(b);
      return it->second;
    };
    std::vector<Row> rows;
    std::vector<Friction> frictions;  // none unless a pair has μ > 0
    std::vector<char> resting_pair(hits.size(), 0);
    for (std::size_t hi = 0; hi < hits.size(); ++hi) {
      const auto& h = hits[hi];
      const int wa = world[h.a], wb = world[h.b];
      const double eps = std::min(setup.restitution[wa], setup.restitution[wb]);
      // Box2D's mixing rule, √(μ_a μ_b) (Bullet multiplies by default; its run
      // is hooked to the same √, compare/bullet_world.cpp).
      const double mu = std::sqrt(setup.friction[wa] * setup.friction[wb]);
      const std::size_t sa = slot(h.a), sb = slot(h.b);
      const Motion& ma = motion[sa];
      const Motion& mb = motion[sb];
      for (const auto& c : h.features) {
        Row r{wa, wb, sa, sb, hi, c.normal, c.point - Bodies::position(ma), c.point - Bodies::position(mb),
              Bodies::arm(ma, c.point, c.normal), Bodies::arm(mb, c.point, c.normal), 0, 0, 0, 0, c.depth};
        r.k = Bodies::inverse_effective_mass(ma, r.arm_a) + Bodies::inverse_effective_mass(mb, r.arm_b);
        if (!(r.k > 0)) continue;
        r.before = normal_velocity(r, motion);
        const bool resting = r.before < 0 && -r.before <= setup.resting_speed;
        counters.resting_contacts += resting;
        resting_pair[hi] |= resting;
        r.target = r.before < 0 ? -(resting ? 0.0 : eps) * r.before : 0.0;
        if (mu > 0) r.friction = static_cast<std::ptrdiff_t>(frictions.size()),
                    frictions.push_back(friction_row(rows.size(), r, c.point, mu, motion));
        rows.push_back(r);
      }
    }
    counters.contacts += rows.size();
    counters.friction_contacts += frictions.size();
    warm_start(rows, frictions, motion, dt);
    double scale = 0;
    for (const auto& r : rows) scale = std::max(scale, std::abs(r.target));
    for (const auto& f : frictions) scale = std::max(scale, std::hypot(f.slip[0], f.slip[1]));
    solve(rows, motion, kVelocityTolerance * (1 + scale), counters.sweep_cap_hits, frictions);
    for (const auto& f : frictions)
      counters.sliding_contacts += std::hypot(f.lambda[0], f.lambda[1]) >= f.mu * rows[f.row].lambda * (1 - 1e-9) &&
                                   rows[f.row].lambda > 0;
    for (const auto& r : rows) {
      counters.impulses += r.lambda > 0;
      // An impact whose approach the solve did not stop (to 0.1 % of its speed).
      if (r.before < -setup.resting_speed && normal_velocity(r, motion) < 1e-3 * r.before) ++counters.unresolved_impacts;
    }
    remember(hits, world, rows, frictions, dt);
    // The pairs whose depth is corrected: deeper than tol/2, and resting or
    // not parting by themselves. A pair that parts after an impact is left
    // alone: the impact conserves momenta exactly, and the depth goes with it.
    const double tol = setup.settings.penetration_tolerance;
    std::vector<char> correct(hits.size(), 0), parting(hits.size(), 1);
    for (const auto& r : rows) parting[r.hit] &= normal_velocity(r, motion) > setup.resting_speed;
    for (std::size_t hi = 0; hi < hits.size(); ++hi)
      correct[hi] = hits[hi].sat.depth > 0.5 * tol && (resting_pair[hi] || !parting[hi]);
    for (std::size_t k = 0; k < motion.size(); ++k) Bodies::store(m, y, static_cast<std::size_t>(body_of[k]), motion[k]);
    correct_positions(m, y, rows, motion, body_of, correct);
    friction_displacement(m, y, rows, frictions, motion, body_of, dt);
  }

  // Forgets warm-start impulses older than the previous collision step (a
  // pair that stopped touching; a contact is only warm started from the step
  // before). Once per collision step.
  void forget_old_contacts() const {
    std::erase_if(cache_, [&](const auto& kv) { return kv.second.step + 1 < counters.steps; });
  }

 private:
  using Motion = typename Bodies::Motion;
  using Motions = std::vector<Motion>;
  using Shape = typename NarrowBody::Shape;

  // The narrowphase's geometry of each body (issue #14): placed once per
  // detection (or per time-of-impact trial) on its first pair, then read by
  // every pair it is in; pose() is only asked for bodies some pair needs.
  mutable std::vector<Shape> shapes_;
  mutable std::vector<std::uint64_t> placed_in_;
  mutable std::uint64_t detection_ = 0;
  mutable collision::PairMemory<collision::SatHint> hints_;  // each pair's last axis
  template <class PoseOf>
  const Shape& shape(int b, PoseOf&& pose_of) const {
    if (shapes_.size() != setup.meshes.size()) shapes_.resize(setup.meshes.size()), placed_in_.assign(setup.meshes.size(), 0);
    if (placed_in_[b] != detection_) {
      shapes_[b].place({setup.meshes[b].get(), pose_of()});
      placed_in_[b] = detection_;
      ++counters.narrowphase_shapes;
    }
    return shapes_[b];
  }
  struct Row {
    int a, b;
    std::size_t sa, sb;    // the bodies' slots in the response's Motions
    std::size_t hit;       // which pair of the detection
    Vec3 n, ra, rb;        // the normal (a to b); the point from each centre
    typename Bodies::Arm arm_a, arm_b;
    double k, target, lambda, before, depth;  // 1/effective mass, target n·Δv, impulse, n·Δv before, depth
    std::ptrdiff_t friction = -1;  // its friction rows in the solve's Frictions, or −1 (μ = 0)
  };
  // Coulomb friction at one contact (issue #17): two rows along the tangents
  // t[0], t[1] of the contact plane, their accumulated impulses λ_t held in the
  // disc |λ_t| ≤ μ λ_n of the contact's accumulated normal impulse. A disc, not
  // a pyramid: the cone is isotropic, so the friction a sliding body feels does
  // not depend on how its sliding lines up with the basis (a four-sided pyramid
  // |λ_1|, |λ_2| ≤ μ λ_n lets a body sliding at 45° to t[0] feel √2 μ). t[0] is
  // the direction of the relative sliding velocity when there is one (as
  // Bullet's first friction direction), so a sliding contact's friction lies
  // along t[0] and each row's own effective mass (Gauss–Seidel uses no 2 × 2
  // block) does not turn it off the slip; at rest t[0] is any tangent.
  struct Friction {
    std::size_t row;             // its normal row
    std::array<Vec3, 2> t;       // unit tangents (backend: in_plane, quarter_turn)
    std::array<typename Bodies::Arm, 2> arm_a, arm_b;
    std::array<double, 2> k, lambda, slip;  // 1/effective mass, impulse, relative velocity before
    double mu;
    bool impact;  // its normal row approached faster than v_rest: no friction_displacement
  };
  struct Cached {
    Vec3 ra, rb;
    double rate;  // impulse per second
    Vec3 friction_rate = Vec3::Zero();  // the friction impulse per second (world), zero without friction
  };
  struct Remembered {
    std::uint64_t step = 0;  // the collision step that stored them
    std::vector<Cached> at;
  };
  // By world pair (a, b), a < b: an island and the world see a pair the same way round.
  mutable std::unordered_map<std::uint64_t, Remembered> cache_;
  static std::uint64_t key(int a, int b) {
    return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
  }

  static double normal_velocity(const Row& r, const Motions& of) {
    return Bodies::normal_velocity(of[r.sb], r.arm_b, r.n) - Bodies::normal_velocity(of[r.sa], r.arm_a, r.n);
  }
  static void push(const Row& r, Motions& of, double dl) {
    Bodies::push(of[r.sb], r.arm_b, r.n, dl);
    Bodies::push(of[r.sa], r.arm_a, r.n, -dl);
  }
  static double tangent_velocity(const Row& r, const Friction& f, int d, const Motions& of) {
    return Bodies::normal_velocity(of[r.sb], f.arm_b[d], f.t[d]) - Bodies::normal_velocity(of[r.sa], f.arm_a[d], f.t[d]);
  }
  static void push(const Row& r, const Friction& f, int d, Motions& of, double dl) {
    Bodies::push(of[r.sb], f.arm_b[d], f.t[d], dl);
    Bodies::push(of[r.sa], f.arm_a[d], f.t[d], -dl);
  }

  // The friction rows of normal row r (index `row`) at contact point p: the
  // tangents from the relative velocity's part in the contact plane (the
  // backend's in_plane and quarter_turn), or from the coordinate axis least
  // along n when the contact does not slip.
  Friction friction_row(std::size_t row, const Row& r, const Vec3& p, double mu, const Motions& of) const {
    const Vec3 slip = Bodies::point_velocity(of[r.sb], p) - Bodies::point_velocity(of[r.sa], p);
    Vec3 t = Bodies::in_plane(r.n, slip);
    if (!(t.norm() > 1e-12 * (1 + slip.norm()))) {
      Eigen::Index axis = 0;
      r.n.cwiseAbs().minCoeff(&axis);
      t = Bodies::in_plane(r.n, Vec3::Unit(axis));
    }
    t.normalize();
    Friction f{row, {t, Bodies::quarter_turn(r.n, t)}, {}, {}, {}, {0, 0}, {}, mu, r.before < -setup.resting_speed};
    for (int d = 0; d < 2; ++d) {
      f.arm_a[d] = Bodies::arm(of[r.sa], p, f.t[d]);
      f.arm_b[d] = Bodies::arm(of[r.sb], p, f.t[d]);
      f.k[d] = Bodies::inverse_effective_mass(of[r.sa], f.arm_a[d]) + Bodies::inverse_effective_mass(of[r.sb], f.arm_b[d]);
      f.slip[d] = tangent_velocity(r, f, d, of);
    }
    return f;
  }

  // One Gauss–Seidel update of a contact's friction: each row's impulse to
  // stop its slip, then the pair projected onto the disc |λ_t| ≤ μ λ_n, λ_n
  // the normal row's accumulated impulse (static friction inside the disc,
  // dynamic on its rim). Returns the largest velocity change.
  static double relax(const Row& r, Friction& f, Motions& motion) {
    std::array<double, 2> next{};
    for (int d = 0; d < 2; ++d) next[d] = f.lambda[d] - tangent_velocity(r, f, d, motion) / f.k[d];
    const double limit = f.mu * r.lambda, size = std::hypot(next[0], next[1]);
    if (size > limit) {
      const double s = size > 0 ? limit / size : 0.0;
      next[0] *= s, next[1] *= s;
    }
    double worst = 0;
    for (int d = 0; d < 2; ++d) {
      const double dl = next[d] - f.lambda[d];
      if (dl == 0) continue;
      worst = std::max(worst, std::abs(dl) * f.k[d]);
      f.lambda[d] = next[d];
      push(r, f, d, motion, dl);
    }
    return worst;
  }

  // Projected Gauss–Seidel with accumulated clamping: each row's total impulse
  // λ stays ≥ 0 while a sweep may lower it (Catto's sequential impulses; eq. 53
  // / eq. 54 are the rows' effective masses). Stops when no row changes its
  // velocity by more than `converged` in a sweep, or after kMaxSweeps (counted
  // in `cap_hits`).
  // Friction rows (if any) are relaxed after the normal rows in every sweep,
  // against the normal impulses of that sweep.
  void solve(std::vector<Row>& rows, Motions& motion, double converged, std::uint64_t& cap_hits,
             std::span<Friction> frictions = {}) const {
    if (rows.empty()) return;
    for (int sweep = 0;; ++sweep) {
      if (sweep == kMaxSweeps) {
        ++cap_hits;
        return;
      }
      ++counters.sweeps;
      double worst = 0;
      for (auto& r : rows) {
        const double next = std::max(0.0, r.lambda + (r.target - normal_velocity(r, motion)) / r.k);
        const double dl = next - r.lambda;
        if (dl == 0) continue;
        worst = std::max(worst, std::abs(dl) * r.k);
        r.lambda = next;
        push(r, motion, dl);
      }
      for (auto& f : frictions) worst = std::max(worst, relax(rows[f.row], f, motion));
      if (worst <= converged) return;
    }
  }

  // Warm starting: a contact found again (the same pair, its point within 1 %
  // of the smaller body's size of where it was relative to both centres)
  // starts from the impulse it had, scaled from that step's length to this
  // one's (a resting contact's impulse is its load times the step). A stack
  // then needs a sweep or two per step, not a fresh solve through every box.
  // A friction row starts from the remembered friction impulse's parts along
  // its tangents, held in the disc of its warm-started normal impulse.
  void warm_start(std::vector<Row>& rows, std::vector<Friction>& frictions, Motions& motion, double dt) const {
    if (cache_.empty() || !(dt > 0)) return;
    for (auto& r : rows) {
      const auto pair = cache_.find(key(r.a, r.b));
      if (pair == cache_.end()) continue;
      const double near = 1e-2 * std::min(setup.meshes[r.a]->size(), setup.meshes[r.b]->size());
      const Cached* best = nullptr;
      double closest = near;
      for (const auto& c : pair->second.at) {
        const double dist = std::max((c.ra - r.ra).norm(), (c.rb - r.rb).norm());
        if (dist < closest) closest = dist, best = &c;
      }
      if (!best) continue;
      r.lambda = best->rate * dt;
      push(r, motion, r.lambda);
      ++counters.warm_started;
      if (r.friction < 0) continue;
      Friction& f = frictions[static_cast<std::size_t>(r.friction)];
      const Vec3 j = best->friction_rate * dt;
      std::array<double, 2> l{j.dot(f.t[0]), j.dot(f.t[1])};
      const double size = std::hypot(l[0], l[1]), limit = f.mu * r.lambda;
      if (size > limit) l[0] *= limit / size, l[1] *= limit / size;
      for (int d = 0; d < 2; ++d) f.lambda[d] = l[d], push(r, f, d, motion, l[d]);
      counters.friction_warm_started += size > 0;
    }
  }
  // The impulses of this solve replace what its pairs had; other pairs (other
  // islands) keep theirs until forget_old_contacts.
  void remember(std::span<const PairHit> hits, World world, const std::vector<Row>& rows,
                const std::vector<Friction>& frictions, double dt) const {
    for (const auto& h : hits) cache_.erase(key(world[h.a], world[h.b]));
    if (!(dt > 0)) return;
    for (const auto& r : rows)
      if (r.lambda > 0) {
        auto& e = cache_[key(r.a, r.b)];
        e.step = counters.steps;
        e.at.push_back({r.ra, r.rb, r.lambda / dt});
        if (r.friction < 0) continue;
        const Friction& f = frictions[static_cast<std::size_t>(r.friction)];
        e.at.back().friction_rate = (f.lambda[0] * f.t[0] + f.lambda[1] * f.t[1]) / dt;
      }
  }

  // The impulses of a resting contact with friction stand for forces that
  // acted through the step, but the step's integration moved the bodies
  // without them: a box held on an incline slid ½ g sin θ h² down it in every
  // step, which the friction impulse then stopped (a creep of ½ g sin θ h,
  // 1.7 mm/s at h = 1 ms, 20°), and a sliding box went ½ μ g h² too far per
  // step. Each such contact's normal and friction impulse λ (one wrench, so
  // that the friction's torque about the centre is balanced by the normal's)
  // moves the bodies by ½ dt of the velocity change it made, as a constant
  // force through the step would have: pseudo-velocities as in the split
  // impulse, so no momentum changes. Impacts (approach faster than v_rest)
  // are instants, not forces, and are left alone. Only contacts with friction
  // (μ > 0): a frictionless scene is unchanged.
  void friction_displacement(const Model& m, std::span<double> y, const std::vector<Row>& rows,
                             const std::vector<Friction>& frictions, const Motions& motion,
                             const std::vector<int>& body_of, double dt) const {
    if (frictions.empty() || !(dt > 0)) return;
    Motions pseudo;
    pseudo.reserve(motion.size());
    for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
    for (const auto& f : frictions) {
      if (f.impact) continue;
      const Row& r = rows[f.row];
      push(r, pseudo, 0.5 * dt * r.lambda);
      for (int d = 0; d < 2; ++d) push(r, f, d, pseudo, 0.5 * dt * f.lambda[d]);
    }
    for (std::size_t k = 0; k < pseudo.size(); ++k) Bodies::displace(m, y, static_cast<std::size_t>(body_of[k]), pseudo[k]);
  }

  // Positional correction by split impulse (pseudo-velocities, as Bullet's
  // split impulse does): the same rows, solved together for a displacement of
  // each body instead of a velocity, with targets bringing every contact of
  // the pairs to correct to tol/4 deep (the other rows only keep their pairs
  // from getting deeper, so a correction in a stack is not passed on as
  // penetration to the next box). The bodies move; their momenta do not
  // change, so the correction injects none (the old correction translated one
  // pair's centres along its normal: a teleport that ignored the rest of a
  // stack). The rows of a face contact (three or more points) act at the
  // centres: with their arms, the four corners of a face form a redundant set
  // that Gauss–Seidel leaves with a residual tilt, and a tilted face's normal
  // pushes sideways (a stack of ten drifted 6e-4 m in 10 s that way; 6e-8 m
  // without the turn). The rows of an edge or a vertex contact keep their
  // arms: a cube pivoting on an edge sinks by turning, and lifting its centre
  // instead raised its energy by 0.24 mJ per correction (caught by check's
  // energy rule on cube_drop_edge: +1.8 mJ against 1 mJ allowed). Solved to
  // a millionth of the tolerance: at a thousandth, an edge contact's two rows
  // left a turn of ~1e-6 rad, which a cube balanced on a ridge (an unstable
  // equilibrium growing at 7.7 /s) turned into 1.3e-6 m/s within a second.
  void correct_positions(const Model& m, std::span<double> y, const std::vector<Row>& rows, const Motions& motion,
                         const std::vector<int>& body_of, const std::vector<char>& correct) const {
    const double tol = setup.settings.penetration_tolerance;
    std::vector<Row> fix;
    if (std::find(correct.begin(), correct.end(), 1) == correct.end()) return;
    std::vector<int> points(correct.size(), 0);
    for (const auto& r : rows) ++points[r.hit];
    // A face's rows act at the centres along one normal: the same row, whose
    // target is the deepest corner's (four copies with their own targets are
    // the same problem, solved slowly: the copies fight over one degree of
    // freedom, and no exact step can satisfy them all).
    std::vector<int> face_row(correct.size(), -1);
    for (const auto& r : rows) {
      const double target = correct[r.hit] ? std::max(0.0, r.depth - 0.25 * tol) : 0.0;
      if (points[r.hit] >= 3) {  // a face: at the centres, no turn
        if (face_row[r.hit] >= 0) {
          Row& q = fix[static_cast<std::size_t>(face_row[r.hit])];
          q.target = std::max(q.target, target);
          continue;
        }
        face_row[r.hit] = static_cast<int>(fix.size());
      }
      Row p = r;
      if (points[r.hit] >= 3) {
        const auto& ma = motion[r.sa];
        const auto& mb = motion[r.sb];
        p.arm_a = Bodies::arm(ma, Bodies::position(ma), r.n);
        p.arm_b = Bodies::arm(mb, Bodies::position(mb), r.n);
        p.k = Bodies::inverse_effective_mass(ma, p.arm_a) + Bodies::inverse_effective_mass(mb, p.arm_b);
      }
      p.lambda = 0;
      p.target = target;
      fix.push_back(p);
    }
    Motions pseudo;
    pseudo.reserve(motion.size());
    for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
    solve(fix, pseudo, 1e-6 * tol, counters.correction_cap_hits);  // m: a millionth of the tolerance, see above
    for (std::size_t k = 0; k < pseudo.size(); ++k) Bodies::displace(m, y, static_cast<std::size_t>(body_of[k]), pseudo[k]);
    for (std::size_t hi = 0; hi < correct.size(); ++hi) counters.corrections += correct[hi];
  }
};

}  // namespace gacompare::core
