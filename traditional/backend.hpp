#pragma once
// The traditional backend as the simulator sees it (core::Backend concept).
#include "core/run.hpp"
#include "traditional/constraint.hpp"
#include "traditional/particle.hpp"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace gacompare::traditional {

struct Backend {
  static constexpr std::string_view name = "traditional";

  struct Model {
    ParticleModel particles;
    ConstraintModel constraints;
    mutable std::optional<core::ConstraintSolver> solver;  // present when the scene has constraints
    mutable std::vector<Vector> forces;                    // scratch for derivative(), sized once
  };

  static Model build(const core::Scene& scene);
  static std::size_t state_size(const Model& m) { return kParticleState * m.particles.names.size(); }
  static void initial_state(const Model& m, std::span<double> y) { initial_particle_state(m.particles, y); }
  static std::vector<int> velocity_of(const Model& m);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         core::Profile& profile);
  static bool after_step(const Model& m, std::vector<double>& y, core::Profile& profile);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  static std::string first_nonfinite(const Model& m, std::span<const double> y);
  static std::map<std::string, std::uint64_t> counters(const Model& m) { return core::constraint_counters(m.solver); }
  static std::map<std::string, double> metrics(const Model& m) { return core::constraint_metrics(m.solver); }
};

}  // namespace gacompare::traditional
