#pragma once
// Detection between rigid bodies (§2.4, fig. 11), written once over a
// backend: its rigid bodies (core::RigidBodies), its narrowphase view of a
// body and its bounding-sphere algebra (CollisionAlgebra below). The Collider
// is read-only, built once per run from the compiled model; what the stages
// carry from one step to the next is the run's CollisionState, passed to each
// stage. Only built when the scene lists the `collisions` effect.
//
// One collision step (core/collision/collision_step.hpp): the world integrated
// to t1, then here the broadphase (bounding spheres grown by how far each body
// can move in the step, core/collision/broadphase.hpp) and the narrowphase
// (the separating-axis depth, then the contact manifold, core/collision/manifold.hpp,
// or the report's fig. 7 detector); then islands (core/collision/islands.hpp),
// time of impact (core/collision/time_of_impact_step.hpp) and the response
// (core/contact/contact_solver.hpp).
#include "core/collision/bounding_volume.hpp"
#include "core/collision/broadphase.hpp"
#include "core/collision/collision.hpp"
#include "core/collision/collision_setup.hpp"
#include "core/contact/contact_solver.hpp"
#include "core/error.hpp"
#include "core/collision/kept_contacts.hpp"
#include "core/collision/narrowphase.hpp"
#include "core/collision/pair_memory.hpp"
#include "core/collision/sleep.hpp"
#include "core/dynamics/rigid_body.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"
#include "core/collision/time_of_impact.hpp"

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

// A pair of a group (its numbering) and its depth where last measured.
struct PairDepth {
  int a, b;
  double depth;
};
// A pair's measured depth, whether a hit's or one found apart.
inline double measured_depth(const PairDepth& p) { return p.depth; }
inline double measured_depth(const PairHit& h) { return h.sat.depth; }

struct Detection {
  double max_depth = -INFINITY;  // over the pairs in contact; −∞ when none
  std::vector<PairHit> hits;
  // The pairs the narrowphase tested and found apart, with their depth: minus
  // the gap along a separating axis, so at least minus their distance (the
  // push-out's bounds start from it, core/collision/push_out_step.hpp).
  std::vector<PairDepth> gaps;
  // With margins: the pairs whose grown spheres overlap (i < j, sorted), a
  // superset of the pairs the narrowphase tested; the islands' links.
  std::vector<std::pair<int, int>> candidates;
  // With margins: the pairs found farther apart than both bodies can move in
  // the step (Collider::apart_beyond_reach), in the order tested; they link nothing.
  std::vector<std::pair<int, int>> apart;
};

// What a pair remembers between detections (collision::PairMemory): the axis
// that decided it last (core/collision/separating_axis.hpp) and the state of
// its kept contacts (core/collision/kept_contacts.hpp), 20 bytes read by one
// lookup. The kept manifolds lie in a table of their own, read only by the
// pairs whose state needs them.
struct PairRecord {
  collision::SatHint axis;
  collision::KeptState kept;
  bool operator==(const PairRecord&) const = default;
};

// One pair's work in a narrowphase detection (Collider::narrow,
// core/collision/narrowphase_step.hpp): its slot, written by whichever thread
// tests it.
struct NarrowSlot {
  PairHit h;
  collision::SatHint hint;
  collision::FaceChoice choice;
  PairRecord* record = nullptr;                   // the pair's record, if it has one
  PairRecord remembered{};                        // and what it held
  collision::KeptState held{};                    // its kept-contacts state, written back to the record
  collision::KeptContacts* kept_entry = nullptr;  // its kept manifold, where it is read or kept
  bool apart = false, kept = false;
  bool hold = false;  // its kept contacts wait (KeptState::wait): not kept after its test
  std::uint64_t face_tested = 0, shapes = 0;
};

// What a backend supplies the collision stages beyond its rigid bodies: the
// narrowphase view of a body (a BodyView over its narrowphase algebra) and
// its bounding-sphere algebra.
template <class C>
concept CollisionAlgebra = collision::NarrowphaseBody<typename C::Body> && SphereTreeOps<typename C::Spheres>;

// What the collision stages carry from one step to the next: the step
// context every stage reads and writes (the Collider itself is read-only).
// A run owns one, started from the state the Collider's build left (its
// broadphase tree and pair memory after the overlap check at t = 0).
template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
struct CollisionState {
  CollisionCounters counters;
  Broadphase<Spheres> broadphase;  // its trees and pairs persist between detections
  // The narrowphase's geometry of each body: placed once per detection (or
  // per time-of-impact trial) on its first pair, then read by every pair it
  // is in; pose() is only asked for bodies some pair needs.
  std::vector<typename NarrowBody::Shape> shapes;
  std::vector<std::uint64_t> placed_in;  // the detection each shape was placed in
  std::uint64_t detection = 0;
  collision::PairMemory<PairRecord> pairs;  // each pair's last axis and kept-contacts state
  collision::PairMemory<collision::KeptContacts> kept;  // pairs in contact: their kept manifolds
  ContactSolver<Bodies> contact;  // the response stage, with its warm-start cache
  SleepState sleep;               // empty unless the scene asks for sleeping
  // The narrowphase's slots, kept between detections: a 10,000-body world's
  // tens of thousands of slots (a third of a kilobyte each) written to fresh
  // memory at every detection were a tenth of the serial part of its run.
  std::vector<NarrowSlot> slots;
  std::vector<std::pair<int, int>> tests;  // a detection's pairs to test, in slot order
  // detect_among's poses and sphere centres of a group, kept between calls:
  // only the entries of the bodies its candidates name are current.
  std::vector<collision::Pose> among_pose;
  std::vector<Vec3> among_centres;
  // The world's bounding-sphere centres at its last detection (the step's,
  // before its responses): where collision_step.hpp's catch_escaped looks
  // for the pairs a correction made.
  std::vector<Vec3> world_centres;
};

// The collider works on a group of bodies: the whole world (the world's model
// and state, `setup.all_bodies` as the group) or one island integrated on its
// own (an island's sub-model, core/collision/collision_step.hpp). Body k of the group's
// model is world body group[k]: meshes, spheres, restitution and the
// warm-start cache are the world's, the state and the motions the group's.
// Read-only: the stages' drivers below (broadphase_step.hpp,
// narrowphase_step.hpp) take the run's CollisionState.
template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
  requires collision::NarrowphaseBody<NarrowBody>
struct Collider {
  using Model = typename Bodies::Model;
  using BodiesType = Bodies;
  // The world index of each body of a group (the group's body k is world body group[k]).
  using BodyIndices = std::span<const int>;
  using State = CollisionState<Bodies, NarrowBody, Spheres>;
  CollisionSetup setup;

  // The collider, and in `state` the stages' state a run starts from.
  static Collider build(const Scene& scene, const core::Model& compiled, const Model& m, State& state,
                        Profile& profile) {
    Collider c;
    c.setup = collision_setup(scene, compiled);
    state.broadphase = Broadphase<Spheres>(c.setup.settings.broadphase);
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
    const Detection d = c.detect(state, m, m.y0, c.setup.all_bodies, {}, profile);
    for (const auto& h : d.hits)
      if (h.sat.depth > c.setup.settings.penetration_tolerance)
        throw input_error("bodies '" + c.setup.names[h.a] + "' and '" + c.setup.names[h.b] + "' overlap at t = 0 by " +
                          std::to_string(h.sat.depth) + " m, more than the penetration tolerance (" +
                          std::to_string(c.setup.settings.penetration_tolerance) +
                          " m): a scene must start without collisions (§2.4.3 fn 28)");
    state.counters = {};
    state.counters.sleeping = c.setup.settings.sleep.on;
    if (c.setup.settings.sleep.on) state.sleep = SleepState(c.setup.all_bodies.size());
    return c;
  }

  // --- the broadphase stage (core/collision/broadphase_step.hpp) ---

  // Every body's pose at state y, once per detection (a rotor or quaternion
  // becomes a matrix here, not once per pair it takes part in).
  std::vector<collision::Pose> poses(const Model& m, std::span<const double> y, BodyIndices group) const;
  collision::Placed placed(const std::vector<collision::Pose>& pose, BodyIndices group, int k) const;

  // Broadphase and narrowphase at one state of a group. margin (empty, or one
  // per body of the group) grows each body's sphere by how far it can move in
  // the step: the grown spheres' overlaps are the candidates (the islands'
  // links, Detection::candidates), and the narrowphase tests the candidates
  // whose own spheres overlap.
  Detection detect(State& state, const Model& m, std::span<const double> y, BodyIndices group, std::span<const double> margin,
                   Profile& profile) const;

  // The same for a group whose candidate pairs are known (an island within
  // its step: the pairs its bodies' grown spheres link, core/collision/collision_step.hpp):
  // of those, the pairs whose own spheres overlap (in a frame at the mean
  // centre of the bodies the candidates name) and that reach a static body's box go to the narrowphase,
  // its pairs split across the run's threads in chunks of `grain`.
  Detection detect_among(State& state, const Model& m, std::span<const double> y, BodyIndices group,
                         std::span<const std::pair<int, int>> candidates, Profile& profile,
                         std::size_t grain = kGrainPair) const;

  // Whether pair p of a group is a moving and a static body and the moving
  // one's sphere (grown by grow[o] when grow is given) misses the static
  // body's box (reaches_static).
  bool misses_static(const std::vector<collision::Pose>& pose, BodyIndices group, const std::vector<Vec3>& centres,
                     const std::pair<int, int>& p, std::span<const double> grow) const;

  // Whether a sphere (centre c, radius r, world) reaches static body s's box
  // placed by its pose: the box point nearest c within r, padded by the
  // touching band and the rounding of the coordinates, so that no pair the
  // narrowphase would call touching is dropped. Algebra-neutral, like the
  // AABB tree: a filter on which pairs are tested, not a part of either
  // backend's geometry.
  bool reaches_static(const collision::Pose& pose, int s, const Vec3& c, double r) const;

  // Each body's bounding-sphere centre in the world at its pose.
  std::vector<Vec3> sphere_centres(const std::vector<collision::Pose>& pose, BodyIndices group) const;

  // --- the narrowphase stage (core/collision/narrowphase_step.hpp) ---

  // The narrowphase of a group's pairs into d (hits and their deepest
  // depth), split across the run's threads in chunks of `grain`.
  void narrow(State& state, BodyIndices group, const std::vector<collision::Pose>& pose, const std::vector<std::pair<int, int>>& pairs,
              Detection& d, Profile& profile, std::span<const double> margin = {}, std::size_t grain = kGrainPair) const;

  // Whether a pair the world's detection found apart is farther apart than
  // both bodies can move in the step (then d.apart keeps it, and the
  // islands' links leave it out: core/collision/collision_step.hpp,
  // unlink_far): when some face normal separates it by more than that
  // (collision::face_gap, which stops at the first that does; a round pair
  // by its exact distance). Not simply by the gap the narrowphase stopped
  // at: its first axis is the pair's remembered one when geometry is reused
  // (setup.settings.reuse), and a link must not depend on that. A face axis's
  // gap bounds the faces' best from below, so where it already exceeds the
  // reaches it decides alone. Reads the shapes narrow() placed; counts its
  // face tests and the shapes it built (without reuse) in the last two
  // arguments, not in the state: it runs on the pool's threads.
  bool apart_beyond_reach(const State& state, BodyIndices group, const std::vector<collision::Pose>& pose,
                          const PairHit& h, std::span<const double> margin, std::uint64_t& face_tested,
                          std::uint64_t& shapes) const;

  // f(va, vb) over world bodies wa and wb placed by pose_a() and pose_b(),
  // in the pair's own frame: with reuse, the bodies' shapes of this
  // detection; without, the pair's own, built here.
  template <class PoseA, class PoseB, class F>
  auto on_pair(State& state, int wa, int wb, PoseA&& pose_a, PoseB&& pose_b, F&& f) const;

  // The deepest separating-axis depth among the given pairs of the group (the
  // time-of-impact function: continuous in time, unlike the feature test's
  // yes/no), at state y, or with each body placed by pose_of(k).
  double depth_of(State& state, const Model& m, std::span<const double> y, BodyIndices group, const std::vector<std::pair<int, int>>& pairs,
                  Profile& profile) const;
  template <class PoseOf>
  double depth_at(State& state, BodyIndices group, const std::vector<std::pair<int, int>>& pairs, PoseOf&& pose_of, Profile& profile) const;

  // --- how far bodies can move in a step (the islands' links, sub-steps) ---

  // How fast body k's rim can move: |v| + ρ|ω|, ρ its arm (setup.arm: no
  // point of it is farther from its centre of mass).
  double rim_speed(const Model& m, std::span<const double> y, BodyIndices group, std::size_t k) const {
    if (setup.is_static[group[k]]) return 0;
    const auto mo = Bodies::motion(m, y, k);
    return Bodies::speed(mo) + setup.arm[group[k]] * Bodies::angular_speed(mo);
  }

  // The most any point of body w (world index) can be accelerated: gravity,
  // and the applied forces' push on its centre and turn about it at its arm.
  double acceleration(int w) const {
    const auto u = static_cast<std::size_t>(w);
    return setup.gravity + setup.push_linear[u] + setup.arm[u] * setup.push_angular[u];
  }

  // How far body k of the group can move in h: a point at distance ρ from the
  // centre of mass moves at most (|v| + ρ|ω|) h, and what accelerates it
  // (gravity, applied forces) adds ½ a h². 0 when static.
  double reach(const Model& m, std::span<const double> y, BodyIndices group, std::size_t k, double h) const {
    if (setup.is_static[group[k]]) return 0;
    return rim_speed(m, y, group, k) * h + 0.5 * acceleration(group[k]) * h * h;
  }

  // How far bodies k and l of a group (awake, at state y) can close on each
  // other in h, given how far each can move (reach_k, reach_l): at most the
  // sum of the two. Two moving bodies under gravity alone fall alike (a
  // uniform field moves both the same way), so only their relative motion
  // closes them: a point of k and one of l part or close at most at
  // |v_k − v_l| + ρ_k|ω_k| + ρ_l|ω_l|, with the same reading of ω as the
  // reach (its size at the step's start). Two bodies thrown down a box
  // side by side at 20 m/s then close at the speed they have against each
  // other, not at 40 m/s: on the 10,000-body box such pairs, landing on the
  // pile together, sent the whole pile (up to 8,225 bodies) to be sub-stepped
  // at 50 of the 1,000 steps (docs/collision-response.md). Drag and applied
  // forces act on each body alone and part their velocities, so with either
  // in the scene, or a static body in the pair, it is the sum of the reaches.
  double closing(const Model& m, std::span<const double> y, BodyIndices group, std::size_t k, std::size_t l,
                 double reach_k, double reach_l, double h) const {
    const double apart = reach_k + reach_l;
    if (!setup.gravity_alone || setup.is_static[group[k]] || setup.is_static[group[l]]) return apart;
    const auto mk = Bodies::motion(m, y, k), ml = Bodies::motion(m, y, l);
    const Vec3 dv = Bodies::point_velocity(mk, Bodies::position(mk)) - Bodies::point_velocity(ml, Bodies::position(ml));
    const double spin = setup.arm[group[k]] * Bodies::angular_speed(mk) + setup.arm[group[l]] * Bodies::angular_speed(ml);
    return std::min(apart, (dv.norm() + spin) * h);
  }

  // The tunnelling rule, pair by pair: bodies a and b (world indices) that
  // close on each other by at most `closing` in a step (Collider::closing)
  // cannot pass through each other while that is within the thinner one's
  // inradius, nor go past half its thickness (which would turn the
  // separating axis's normal around). Returns how many times too long the
  // step is for the pair (≤ 1: short enough). It was a bound on each body
  // alone, half the smallest inradius in the world: the same guarantee for a
  // pair of the thinnest bodies, but on the 10,000-body box it sent the whole
  // pile (8,212 bodies) to be sub-stepped at a quarter of the collision steps
  // for a fast body anywhere in it, a seventh of the run's time (44.9 against
  // 38.6 s on one thread, docs/collision-response.md).
  double crossing(int a, int b, double closing) const {
    return closing / std::min(setup.inradius[static_cast<std::size_t>(a)], setup.inradius[static_cast<std::size_t>(b)]);
  }

  // The tunnelling rule for bodies k and l of a group whose reaches in h are
  // given: the ratio of their reaches' sum, and where that breaks the rule,
  // of their closing (which can only lower it). `held`: one of them is
  // asleep, and stays put while the other falls, so the sum stands.
  double crossing_of(const Model& m, std::span<const double> y, BodyIndices group, std::size_t k, std::size_t l,
                     double reach_k, double reach_l, double h, bool held = false) const {
    const double ratio = crossing(group[k], group[l], reach_k + reach_l);
    if (ratio <= 1 || held) return ratio;
    return crossing(group[k], group[l], closing(m, y, group, k, l, reach_k, reach_l, h));
  }

  // How long a step of the group may be: the tunnelling rule for every pair
  // (in the group's numbering) it may test. A closing is at most linear in h
  // (speeds × h + ½ a h²), so h shortened by the worst ratio meets it.
  double step_limit(const Model& m, std::span<const double> y, BodyIndices group,
                    const std::vector<std::pair<int, int>>& pairs, double h) const {
    std::vector<double> r(group.size());
    for (std::size_t k = 0; k < group.size(); ++k) r[k] = reach(m, y, group, k, h);
    double worst = 0;
    for (const auto& [a, b] : pairs) {
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      worst = std::max(worst, crossing_of(m, y, group, ua, ub, r[ua], r[ub], h));
    }
    return worst > 1 ? h / worst : h;
  }

  // §2.5: impulses at every contact of `hits` (pairs of the group), solved
  // together, then the positional correction (see the top of this file). `dt`
  // is the time since the group's last accepted state: warm-started impulses
  // scale with it.
  void respond(State& state, const Model& m, std::span<double> y, BodyIndices group, std::span<const PairHit> hits, double dt,
               Profile& profile) const {
    state.contact.respond(setup, state.counters, m, y, group, hits, dt, profile);
  }

  // The positional correction alone (ContactSolver::push_out).
  void push_out(State& state, const Model& m, std::span<double> y, BodyIndices group, std::span<const PairHit> hits,
                Profile& profile) const {
    state.contact.push_out(setup, state.counters, m, y, group, hits, profile);
  }

  // Once per collision step: see ContactSolver::forget_old_contacts.
  void forget_old_contacts(State& state) const { state.contact.forget_old_contacts(state.counters.steps); }

  // The kept contacts (core/collision/kept_contacts.hpp) of the given pairs
  // (world indices) dropped, before their island is rewound to an earlier
  // state. The world's detection at a step's end keeps each touching pair's
  // answer there, and a kept answer is carried only across motions that
  // cannot change it from its own pose; but a pair's motion along its normal
  // can change which face of a thin body is the nearer way out. A 2 cm cube
  // that reached a 2 cm plate's far half by the step's end had its answer on
  // the plate's far face; refreshed at the island's first sub-step, that
  // answer pushed the cube out through the plate at 40 m/s
  // (CollisionStepCases.FastBodiesNeverPassThroughThinPlates). To reach the
  // far half from the near side within the band, a pair must close by more
  // than the sum of its inradii, so only the pairs the tunnelling rule
  // refused over the step (crossing) can have such an answer; they are the
  // ones dropped, and the island's other pairs keep theirs, as in any other
  // step. (Dropping every pair deeper than the tolerance changed the
  // landings of the friction pyramids, and pga's 3-layer one then hit the
  // sweeps' cap.)
  void forget_kept(State& state, const std::vector<std::pair<int, int>>& pairs) const {
    if (!setup.settings.reuse_contacts) return;
    for (const auto& [a, b] : pairs)
      if (PairRecord* r = state.pairs.find(std::min(a, b), std::max(a, b))) r->kept.valid = false;
  }

 private:
  using Shape = typename NarrowBody::Shape;

  template <class PoseOf>
  const Shape& shape(State& state, int b, PoseOf&& pose_of) const;
  // f(va, vb) over two placed shapes in the pair's own frame (its origin
  // between them: collision::local_origin).
  template <class F>
  static auto in_pair_frame(const Shape& a, const Shape& b, F&& f);
  // The same over shapes of the pair's own, placed here (without reuse);
  // counts them in `shapes`.
  template <class F>
  static auto on_own_shapes(const collision::Placed& a, const collision::Placed& b, std::uint64_t& shapes, F&& f);
};

}  // namespace gacompare::core

// The stages' drivers, members of the Collider.
#include "core/collision/broadphase_step.hpp"
#include "core/collision/narrowphase_step.hpp"
