#pragma once
// The traditional backend as the simulator sees it (core::Backend concept).
#include "core/run.hpp"
#include "traditional/particle.hpp"

#include <span>
#include <string>
#include <string_view>

namespace gacompare::traditional {

struct Backend {
  static constexpr std::string_view name = "traditional";

  struct Model {
    ParticleModel particles;
    mutable std::vector<Vector> forces;  // scratch for derivative(), sized once
  };

  static Model build(const core::Scene& scene);
  static std::size_t state_size(const Model& m) { return kParticleState * m.particles.names.size(); }
  static void initial_state(const Model& m, std::span<double> y) { initial_particle_state(m.particles, y); }
  static void derivative(const Model& m, double, std::span<const double> y, std::span<double> dydt,
                         core::Profile& profile) {
    particle_derivative(m.particles, y, dydt, m.forces, profile);
  }
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  static std::string first_nonfinite(const Model& m, std::span<const double> y);
};

}  // namespace gacompare::traditional
