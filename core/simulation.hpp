#pragma once
// A backend's whole state: particles (written once over the backend's vector
// algebra, core/particle_system.hpp) followed by rigid bodies (in the backend's own
// algebra: traditional/rigid_body.hpp, cga/rigid_body.hpp). This composes the two
// into what the simulator needs (core::Backend); each backend is this template
// with its algebra and its name.
#include "core/particle_system.hpp"
#include "core/rigid_body.hpp"

namespace gacompare::core {

template <class ParticleOps, class Bodies>
struct Simulation {
  using Particles = ParticleSystem<ParticleOps>;
  struct Model {
    typename Particles::Model particles;
    typename Bodies::Model bodies;
    std::vector<BodyProperties> props;
    std::size_t offset = 0;  // where the bodies' state starts
  };

  static Model build(const Scene& scene) {
    Model m{Particles::build(scene), {}, body_properties(scene), 0};
    m.bodies = Bodies::build(scene, m.props);
    m.offset = Particles::state_size(m.particles);
    return m;
  }
  static std::size_t state_size(const Model& m) { return m.offset + Bodies::state_size(m.bodies); }
  static void initial_state(const Model& m, std::span<double> y) {
    Particles::initial_state(m.particles, y.first(m.offset));
    Bodies::initial_state(m.bodies, y.subspan(m.offset));
  }
  // The split (symplectic) solvers need positions and velocities: particles only.
  static std::vector<int> velocity_of(const Model& m) {
    return m.bodies.bodies.empty() ? Particles::velocity_of(m.particles) : std::vector<int>{};
  }
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         Profile& profile) {
    if (m.offset > 0) Particles::derivative(m.particles, t, y.first(m.offset), dydt.first(m.offset), profile);
    if (!m.bodies.bodies.empty()) {
      ScopedStage timed(profile, Stage::forces);
      Bodies::derivative(m.bodies, t, y.subspan(m.offset), dydt.subspan(m.offset));
    }
  }
  static bool after_step(const Model& m, std::vector<double>& y, Profile& profile) {
    const bool projected = Particles::after_step(m.particles, y, profile);
    const bool renormalised = Bodies::renormalise(m.bodies, std::span<double>(y).subspan(m.offset));
    return projected || renormalised;
  }
  static void observe(const Model& m, std::span<const double> y, Sample& s) {
    Particles::observe(m.particles, y.first(m.offset), s);
    Bodies::observe(m.bodies, y.subspan(m.offset), s);
  }
  static std::string first_nonfinite(const Model& m, std::span<const double> y) {
    std::string bad = Particles::first_nonfinite(m.particles, y.first(m.offset));
    if (bad.empty() && !m.bodies.bodies.empty())
      bad = core::first_nonfinite(y.subspan(m.offset), Bodies::state_size(m.bodies) / m.bodies.bodies.size(),
                                  m.bodies.names, "body");
    return bad;
  }
  static std::map<std::string, std::uint64_t> counters(const Model& m) { return Particles::counters(m.particles); }
  static std::map<std::string, double> metrics(const Model& m) { return Particles::metrics(m.particles); }
};

}  // namespace gacompare::core
