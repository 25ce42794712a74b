#include "core/collisions.hpp"

#include "core/mass_properties.hpp"

#include <algorithm>

namespace gacompare::core {

void CollisionCounters::add_to(std::map<std::string, std::uint64_t>& out) const {
  out["collision_steps"] = steps;
  out["collision_steps_shortened"] = shortened_steps;
  out["broadphase_candidates"] = broadphase_candidates;
  out["broadphase_tree_updates"] = broadphase_tree_updates;
  out["broadphase_pairs_kept"] = broadphase_pairs_kept;
  out["narrowphase_pairs"] = narrowphase_pairs;
  out["impact_searches"] = impact_searches;
  out["impact_iterations"] = impact_iterations;
  out["impact_state_evaluations"] = impact_evaluations;
  out["impact_searches_unresolved"] = unresolved_searches;
  out["impact_interpolated_evaluations"] = impact_interpolations;
  out["impact_interpolation_misses"] = impact_interpolation_misses;
  out["impact_bodies_integrated"] = impact_bodies_integrated;
  out["impact_island_misses"] = impact_island_misses;
  out["contacts"] = contacts;
  out["resting_contacts"] = resting_contacts;
  out["impulses"] = impulses;
  out["response_sweeps"] = sweeps;
  out["positional_corrections"] = corrections;
  out["warm_started_contacts"] = warm_started;
  out["response_sweep_cap_hits"] = sweep_cap_hits;
  out["correction_sweep_cap_hits"] = correction_cap_hits;
  out["unresolved_impacts"] = unresolved_impacts;
  out["islands"] = islands;
  out["islands_stepped_alone"] = local_islands;
  out["island_bodies_stepped_alone"] = local_island_bodies;
  out["island_steps"] = local_steps;
  out["island_narrowphase_pairs"] = island_narrowphase_pairs;
  out["links_apart"] = links_apart;
  out["links_face_tested"] = links_face_tested;
  out["largest_island"] = largest_island;
  out["narrowphase_shapes"] = narrowphase_shapes;
  out["narrowphase_axes_kept"] = narrowphase_axes_kept;
  out["friction_contacts"] = friction_contacts;
  out["sliding_contacts"] = sliding_contacts;
  out["friction_warm_started"] = friction_warm_started;
}

CollisionSetup collision_setup(const Scene& scene) {
  CollisionSetup s;
  s.settings = *scene.find_effect<Collisions>();
  s.solver = scene.solver;
  if (const auto* g = scene.find_effect<Gravity>()) s.gravity = g->g.norm();
  s.resting_speed = std::sqrt(2 * s.gravity * s.settings.penetration_tolerance) + 2 * s.gravity * s.settings.step;
  s.min_inradius = INFINITY;
  for (const auto& body : scene.bodies) {
    Mesh mesh = mesh_for(body.shape);
    const Vec3 com = mass_properties(mesh, 1.0).centre_of_mass;
    mesh = mesh.transformed(Eigen::Matrix3d::Identity(), -com);
    const Convexity c = convexity(mesh);
    if (!c.convex)
      throw input_error("body '" + body.name + "': the collisions effect needs convex bodies (§2.4.2): " + c.reason);
    const double inradius = core::inradius(mesh, Vec3::Zero());
    s.names.push_back(body.name);
    s.meshes.push_back(std::make_shared<const Mesh>(std::move(mesh)));
    s.inradius.push_back(inradius);
    s.min_inradius = std::min(s.min_inradius, inradius);
    s.restitution.push_back(body.restitution ? *body.restitution : s.settings.restitution);
    s.friction.push_back(body.friction);
    s.is_static.push_back(body.is_static);
    const Aabb box = aabb_of(std::span<const Vec3>(s.meshes.back()->vertices()));
    s.static_mid.push_back(0.5 * (box.min + box.max));
    s.static_half.push_back(0.5 * (box.max - box.min));
    s.everyone.push_back(static_cast<int>(s.everyone.size()));
  }
  return s;
}

}  // namespace gacompare::core
