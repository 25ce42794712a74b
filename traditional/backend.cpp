#include "traditional/backend.hpp"

#include "core/simulator.hpp"

namespace gacompare::traditional {

Backend::Model Backend::build(const core::Scene& scene) {
  Model m{build_particles(scene), {}};
  m.forces.assign(m.particles.names.size(), Vector::Zero());
  return m;
}

void Backend::observe(const Model& m, std::span<const double> y, core::Sample& s) {
  s.particles.resize(m.particles.names.size());
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    s.particles[i].position = Vector(y[6 * i], y[6 * i + 1], y[6 * i + 2]);
    s.particles[i].velocity = Vector(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]);
  }
}

std::string Backend::first_nonfinite(const Model& m, std::span<const double> y) {
  return core::first_nonfinite(y, kParticleState, m.particles.names, "particle");
}

}  // namespace gacompare::traditional
