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
// The response (resting contact, friction, the positional correction):
// core/contact/contact_solver.hpp.
#include "core/bounding_volume.hpp"
#include "core/broadphase.hpp"
#include "core/collision.hpp"
#include "core/collision_setup.hpp"
#include "core/contact/contact_solver.hpp"
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
    contact_.respond(setup, counters, m, y, world, hits, dt, profile);
  }

  // Once per collision step: see ContactSolver::forget_old_contacts.
  void forget_old_contacts() const { contact_.forget_old_contacts(counters.steps); }

 private:
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
  mutable ContactSolver<Bodies> contact_;  // the response stage, with its warm-start cache
};

}  // namespace gacompare::core
