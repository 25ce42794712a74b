#include "cga/backend.hpp"

#include "core/simulator.hpp"

namespace gacompare::cga {

Backend::Model Backend::build(const core::Scene& scene) {
  Model m{build_particles(scene), {}, std::nullopt, {}};
  std::vector<double> y0(kParticleState * m.particles.names.size());
  initial_particle_state(m.particles, y0);
  m.constraints = Constraints::build(scene, m.particles.names, y0);
  if (!m.constraints.constraints.empty()) m.solver.emplace(scene.constraint_solver, m.particles.inv_mass);
  m.forces.assign(m.particles.names.size(), Vector{});
  return m;
}

std::vector<int> Backend::velocity_of(const Model& m) { return core::particle_layout(m.particles.names.size()); }

void Backend::derivative(const Model& m, double, std::span<const double> y, std::span<double> dydt,
                         core::Profile& profile) {
  accumulate_forces(m.particles, y, m.forces, profile);
  if (m.solver) {
    core::ScopedStage timed(profile, core::Stage::constraints);
    Constraints::add_forces(m.constraints, m.particles.inv_mass, y, m.forces, *m.solver);
  }
  particle_derivative(m.particles, y, m.forces, dydt);
}

bool Backend::after_step(const Model& m, std::vector<double>& y, core::Profile& profile) {
  if (!m.solver || m.solver->spec().drift != core::Drift::projection) return false;
  core::ScopedStage timed(profile, core::Stage::constraints);
  Constraints::project(m.constraints, y, *m.solver);
  return true;
}

void Backend::observe(const Model& m, std::span<const double> y, core::Sample& s) {
  s.particles.resize(m.particles.names.size());
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    s.particles[i].position = to_eigen(vector3(y[6 * i], y[6 * i + 1], y[6 * i + 2]));
    s.particles[i].velocity = to_eigen(vector3(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]));
  }
  if (m.solver) {
    Constraints::fill(m.constraints, {}, y, nullptr);
    s.constraint_violation = core::max_violation(m.constraints.rows);
  }
}

std::string Backend::first_nonfinite(const Model& m, std::span<const double> y) {
  return core::first_nonfinite(y, kParticleState, m.particles.names, "particle");
}

}  // namespace gacompare::cga
