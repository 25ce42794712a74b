#include "core/collision/collisions.hpp"


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
  out["impact_pairs_deep_at_start"] = impact_pairs_deep_at_start;
  if (push_out_detections || escaped_bodies) {
    out["push_out_detections"] = push_out_detections;
    out["push_out_left_deep"] = push_out_left_deep;
    out["push_out_held_detections"] = push_out_held_detections;
    out["escaped_bodies"] = escaped_bodies;
    out["escaped_deep_pairs"] = escaped_deep_pairs;
    out["escaped_islands_stepped"] = escaped_islands_stepped;
    out["escaped_island_bodies_stepped"] = escaped_island_bodies_stepped;
  }
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
  out["islands_stepped_alone_deep"] = local_islands_deep;
  out["islands_stepped_alone_fast"] = local_islands_fast;
  out["largest_island_stepped_alone"] = largest_local_island;
  out["island_steps"] = local_steps;
  out["island_narrowphase_pairs"] = island_narrowphase_pairs;
  out["links_apart"] = links_apart;
  out["links_face_tested"] = links_face_tested;
  out["largest_island"] = largest_island;
  out["narrowphase_shapes"] = narrowphase_shapes;
  out["narrowphase_axes_kept"] = narrowphase_axes_kept;
  out["narrowphase_contacts_kept"] = contacts_kept;
  out["friction_contacts"] = friction_contacts;
  out["sliding_contacts"] = sliding_contacts;
  out["friction_warm_started"] = friction_warm_started;
  out["contact_solves"] = solves;
  out["direct_pivots"] = direct_pivots;
  out["direct_factorisations"] = direct_factorisations;
  out["direct_updates"] = direct_updates;
  out["direct_augmented_factorisations"] = direct_augmented;
  out["direct_rows_held"] = direct_held;
  out["direct_proximal_steps"] = direct_proximal;
  out["direct_friction_rounds"] = direct_rounds;
  out["direct_unsolved"] = direct_unsolved;
  out["exact_starts"] = exact_starts;
  out["friction_lowerings"] = friction_lowerings;
  out["projections_skipped"] = projections_skipped;
  out["coulomb_exact_starts"] = coulomb_exact_starts;
  out["coulomb_solves"] = coulomb_solves;
  out["coulomb_newton_steps"] = coulomb_newton_steps;
  out["coulomb_unsolved"] = coulomb_unsolved;
  out["projections_refused"] = projections_refused;
  if (sleeping) {
    out["sleep_islands"] = sleep_islands;
    out["sleep_woken_by_touch"] = sleep_woken_by_touch;
    out["sleep_woken_by_force"] = sleep_woken_by_force;
    out["sleep_redetections"] = sleep_redetections;
    out["sleeping_body_steps"] = sleeping_body_steps;
  }
  for (std::size_t k = 0; k < sweep_histogram.size(); ++k) {
    if (!sweep_histogram[k]) continue;
    const std::uint64_t lo = std::uint64_t{1} << k, hi = (lo << 1) - 1;
    std::string key = "sweeps_per_solve_";
    key += std::to_string(lo);
    if (hi > lo) key += '_', key += std::to_string(hi);
    out[key] = sweep_histogram[k];
  }
  for (std::size_t k = 0; k < residual_histogram.size(); ++k) {
    if (!residual_histogram[k]) continue;
    const bool last = k + 1 == residual_histogram.size();
    std::string key = last ? "velocity_residual_below_1e-" : "velocity_residual_from_1e-";
    key += std::to_string(last ? k : k + 1);
    out[key] = residual_histogram[k];
  }
}

void CollisionCounters::add_sweeps(int sweeps) {
  std::size_t k = 0;
  while (k + 1 < sweep_histogram.size() && (2 << k) <= sweeps) ++k;
  ++sweep_histogram[k];
}

void CollisionCounters::add_residual(double residual) {
  // Bucket k holds [1e-(k+1), 1e-k): k = floor(-log10 r), the last bucket everything smaller.
  std::size_t k = 0;
  double edge = 1e-1;
  while (k + 1 < residual_histogram.size() && residual < edge) ++k, edge *= 0.1;
  ++residual_histogram[k];
}

CollisionSetup collision_setup(const Scene& scene, const Model& model) {
  CollisionSetup s;
  s.settings = *scene.find_effect<Collisions>();
  s.solver = scene.solver;
  s.gravity = model.gravity;
  const BodyEffects& fx = model.effects;
  s.gravity_alone = !fx.has_linear_drag && !fx.has_quadratic_drag && fx.pushes.empty();
  s.resting_speed = model.resting_speed;
  s.min_inradius = model.min_inradius;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyModel& b = model.bodies[i];
    if (!b.convex)
      throw input_error("body '" + scene.bodies[i].name + "': the collisions effect needs convex bodies (§2.4.2): " +
                        b.not_convex);
    s.names.push_back(scene.bodies[i].name);
    s.meshes.push_back(b.mesh);
    s.inradius.push_back(b.inradius);
    s.arm.push_back(b.radius);
    s.restitution.push_back(b.restitution);
    s.friction.push_back(b.friction);
    s.is_static.push_back(b.is_static);
    s.static_mid.push_back(b.box_mid);
    s.static_half.push_back(b.box_half);
    s.all_bodies.push_back(static_cast<int>(s.all_bodies.size()));
  }
  s.pushed.resize(scene.bodies.size());
  s.push_linear.assign(scene.bodies.size(), 0.0);
  s.push_angular.assign(scene.bodies.size(), 0.0);
  for (const auto& push : fx.pushes) {
    const BodyModel& b = model.bodies[push.body];
    s.pushed[push.body].emplace_back(push.from, push.until);
    s.push_linear[push.body] += push.force.norm() / b.mass;
    s.push_angular[push.body] += push.point.norm() * push.force.norm() / b.moments.minCoeff();
  }
  return s;
}

}  // namespace gacompare::core
