#pragma once
// What the collision stages share, whatever the backend: the counters every
// stage adds to, the setup built once from the scene (meshes centred on their
// centres of mass, bounding spheres, inradii, materials) and one pair in
// contact as the narrowphase hands it to the contact solver.
#include "core/collision/collision.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gacompare::core {

struct CollisionCounters {
  std::uint64_t steps = 0, shortened_steps = 0, broadphase_candidates = 0, narrowphase_pairs = 0;
  std::uint64_t broadphase_tree_updates = 0, broadphase_pairs_kept = 0;  // summed over detections
  std::uint64_t impact_searches = 0, impact_iterations = 0, impact_evaluations = 0, unresolved_searches = 0;
  std::uint64_t impact_interpolations = 0, impact_interpolation_misses = 0;  // impact_motion "interpolate"
  // Bodies integrated by the searches' trials (the deep pairs' bodies, or an
  // island when the pairs' time missed the band on the island's motion).
  std::uint64_t impact_bodies_integrated = 0, impact_island_misses = 0;
  // Pairs deeper than the tolerance at a search's end that were already so at
  // its start: left out of the search (time_of_impact_step.hpp).
  std::uint64_t impact_pairs_deep_at_start = 0;
  // Without a search (time_of_impact "none"): the detections that checked a
  // response's correction, and the islands left deeper than the tolerance
  // after every pass (push_out_step.hpp).
  std::uint64_t push_out_detections = 0, push_out_left_deep = 0;
  // The bodies a step's responses carried farther than their reach, the
  // pairs deeper than the tolerance they were found in that no island had
  // tested (collision_step.hpp, catch_escaped), and with a search the
  // islands those pairs sent to step alone again (step_again), and the
  // moving bodies those held.
  std::uint64_t escaped_bodies = 0, escaped_deep_pairs = 0, escaped_islands_stepped = 0;
  std::uint64_t escaped_island_bodies_stepped = 0;
  // Push-out detections of the pairs beside a pass's deep ones (push_out_step.hpp, hold_neighbours).
  std::uint64_t push_out_held_detections = 0;
  std::uint64_t contacts = 0, impulses = 0, resting_contacts = 0, sweeps = 0, corrections = 0;
  std::uint64_t warm_started = 0, sweep_cap_hits = 0, correction_cap_hits = 0, unresolved_impacts = 0;
  // Islands (core/collision/islands.hpp, core/collision/collision_step.hpp): the islands with a
  // candidate pair, those stepped on their own (a pair too deep or a step
  // too long for them), the bodies those held (each re-integrated from the
  // step's start) and the largest island seen.
  std::uint64_t islands = 0, local_islands = 0, local_island_bodies = 0, largest_island = 0, local_steps = 0;
  // Why each island was stepped alone (a pair deeper than the tolerance, a
  // body fast enough to pass through a thin one, or both), and the most
  // bodies one such island held: what a crowded pile's cost comes from.
  std::uint64_t local_islands_deep = 0, local_islands_fast = 0, largest_local_island = 0;
  std::uint64_t island_narrowphase_pairs = 0;  // of narrowphase_pairs, those tested in islands' sub-steps
  std::uint64_t links_apart = 0;  // candidate pairs unlinked: apart by more than their reach (collision_step.hpp)
  std::uint64_t links_face_tested = 0;  // of the pairs apart, those whose link every face normal decided
  std::uint64_t narrowphase_shapes = 0, narrowphase_axes_kept = 0;  // bodies' geometry built; pairs their last axis decided
  std::uint64_t contacts_kept = 0;  // pairs whose kept contacts were measured again, not tested (kept_contacts.hpp)
  // Friction: the contacts given friction rows, those whose
  // friction ended on the cone (sliding) and the friction rows warm started.
  std::uint64_t friction_contacts = 0, sliding_contacts = 0, friction_warm_started = 0;
  // The contact solver's work: solves (velocity and correction), the direct
  // solver's active-set changes, factorisations (and how many of them were
  // of the augmented system), changes solved through a Schur complement
  // instead, proximal steps (lcp.cpp),
  // friction-bound rounds and solves it left unsolved (the sweeps then
  // finish them), and how many
  // sweeps each solve took: sweep_histogram[k] counts solves of 2^k to
  // 2^(k+1) − 1 sweeps (the last bucket: the cap).
  std::uint64_t solves = 0, direct_pivots = 0, direct_factorisations = 0, direct_updates = 0, direct_augmented = 0, direct_held = 0, direct_proximal = 0, direct_rounds = 0, direct_unsolved = 0;
  // At rest (contact_solver.hpp): position projections skipped as idle, and
  // frictionless warm starts kept without a solve.
  std::uint64_t projections_skipped = 0, exact_starts = 0;
  // With friction: resting pairs whose friction displacement would have left
  // them apart, their moving body lowered onto its static support instead.
  std::uint64_t friction_lowerings = 0;
  // With friction, the direct solve's Coulomb problem (coulomb.hpp): warm
  // starts already exact (no solve), solves the rounds left inexact and
  // Newton's method made exact, their Newton steps, and those it could not.
  std::uint64_t coulomb_exact_starts = 0, coulomb_solves = 0, coulomb_newton_steps = 0, coulomb_unsolved = 0;
  std::uint64_t projections_refused = 0;  // the direct solver's position projections dropped (contact_solver.hpp)
  std::array<std::uint64_t, 11> sweep_histogram{};
  // The velocity residual at each velocity solve's exit (m/s: the largest
  // change of the last sweep), by decade: residual_histogram[k] counts those
  // in [1e-(k+1), 1e-k) m/s, [0] those ≥ 1e-1 and the last those < 1e-15.
  std::array<std::uint64_t, 16> residual_histogram{};
  // Sleeping (core/collision/sleep.hpp), reported only when the scene asks
  // for it: the islands put to sleep, the sleeping sets woken (by a body
  // within reach, by an applied force), the detections repeated after a
  // wake, and the sum over collision steps of the bodies asleep in them.
  bool sleeping = false;
  std::uint64_t sleep_islands = 0, sleep_woken_by_touch = 0, sleep_woken_by_force = 0, sleep_redetections = 0;
  std::uint64_t sleeping_body_steps = 0;
  void add_sweeps(int sweeps);
  void add_residual(double residual);
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
  // The farthest a point of each body is from its centre of mass (the arm of
  // its spin in the speed bounds, Collider::rim_speed): its farthest vertex,
  // exact for a round shape too (its proxy's vertices lie on it). The
  // bounding sphere's radius, used before, is that only for a sphere centred
  // on the centre of mass: a tall pyramid's apex (1.5 m from its centre of
  // mass, its sphere 1.125 m) outran its reach.
  std::vector<double> arm;
  // The most the applied forces on each body can add to its acceleration:
  // Σ|F|/m at its centre of mass and Σ|p||F|/I_min of angular acceleration
  // (p each force's point from the centre of mass, I_min the least principal
  // moment), whichever of its forces act: a bound for any step. 0 for a body
  // no force pushes. Drag only slows a body, and adds nothing.
  std::vector<double> push_linear, push_angular;
  std::vector<double> friction;  // each body's μ (core/model/scene.hpp Body::friction)
  std::vector<char> is_static;
  // A static body's box in its own frame (the mesh's bounding box, centre and
  // half sides): the broadphase's spheres are loose about a slab or a wall, so
  // a pair with a static body is kept only where the other body's sphere
  // reaches this box (Collider::reaches_static).
  std::vector<Vec3> static_mid, static_half;
  std::vector<int> all_bodies;  // 0 … n − 1: the world as a group (see Collider)
  // Each body's applied forces' windows [from, until): a force that acts
  // keeps its body awake, and one that switches on wakes it (sleep.hpp).
  std::vector<std::vector<std::pair<double, double>>> pushed;
  bool pushed_during(std::size_t b, double t0, double t1) const {
    for (const auto& [from, until] : pushed[b])
      if (from < t1 && until > t0) return true;
    return false;
  }
  SolverSpec solver;          // the scene's: an island is integrated alone with it
  double gravity = 0;       // |g|
  // Whether gravity is the only force on the bodies (no drag, no applied
  // force): then two moving bodies fall alike, and only their relative motion
  // closes them (Collider::closing).
  bool gravity_alone = true;
  double resting_speed = 0;  // v_rest above
  double min_inradius = 0;
};

// The compiled model's meshes, inradii and materials, as the collision stages
// index them (throws input_error for a non-convex body). The bounding spheres
// are filled by Collider::build (per backend).
CollisionSetup collision_setup(const Scene& scene, const Model& model);

// One pair in contact: the separating-axis answer and the report's contacts.
// a and b are the bodies' indices in the group detected (see Collider).
struct PairHit {
  int a = 0, b = 0;
  collision::PairContact sat;
  std::vector<collision::FeatureContact> features;
};

}  // namespace gacompare::core
