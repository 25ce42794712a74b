#pragma once
// What the collision stages share, whatever the backend: the counters every
// stage adds to, the setup built once from the scene (meshes centred on their
// centres of mass, bounding spheres, inradii, materials) and one pair in
// contact as the narrowphase hands it to the contact solver.
#include "core/collision.hpp"
#include "core/mesh.hpp"
#include "core/scene.hpp"

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

}  // namespace gacompare::core
