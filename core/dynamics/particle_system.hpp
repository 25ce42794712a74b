#pragma once
// Particle dynamics (§2.1.1, Table 2) with constraints (§2.1.2), written once over
// a backend's vector algebra. For particles every quantity is a vector and a
// Cl(3,0) vector is a 3-vector, so the report (§2.2) expects no difference between
// the approaches; the formulas are therefore shared, and each backend supplies only
// its algebra as an `Ops` policy (traditional/particle.hpp: Eigen; cga/particle.hpp:
// Cl(3,0) multivectors). The harness measures what the algebra costs.
//
// State per particle: [x, v], 6 doubles, contiguous. dx/dt = v, dv/dt = F/m;
// pinned particles have infinite mass (inverse mass 0) and never move.
//
// Ops, beyond what core/dynamics/particle_constraints.hpp needs:
//      static Vec3 to_world(const Vector&) — back to the backend-neutral sample.
#include "core/dynamics/particle_constraints.hpp"
#include "core/run.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/stage.hpp"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace gacompare::core {

template <ParticleVectorOps Ops>
struct ParticleSystem {
  using V = typename Ops::Vector;
  using Constraints = ParticleConstraints<Ops>;

  // The effects a scene lists, in this algebra (built once: an unlisted effect has
  // no object here and no branch in the derivative).
  struct Gravity { V g; };
  struct LinearDrag { double k; };
  struct QuadraticDrag { double k; };
  struct AttractionBetweenParticles { double C, eps2; };  // eps2: softening length squared
  struct AttractionToPoint { V point; double D, eps2; };
  using Effect = std::variant<Gravity, LinearDrag, QuadraticDrag, AttractionBetweenParticles, AttractionToPoint>;

  struct Model {
    std::vector<std::string> names;
    std::vector<double> mass, inv_mass;  // inv_mass 0 for pinned particles
    std::vector<V> x0, v0;
    std::vector<Effect> effects;
    typename Constraints::Model constraints;
    mutable std::optional<ConstraintSolver> solver;  // present when the scene has constraints
    mutable std::vector<V> forces;                   // scratch for derivative(), sized once
  };

  static Model build(const Scene& scene) {
    Model m;
    for (const auto& p : scene.particles) {
      m.names.push_back(p.name);
      m.mass.push_back(p.mass);
      m.inv_mass.push_back(p.pinned ? 0.0 : 1.0 / p.mass);
      m.x0.push_back(Ops::from(p.position));
      m.v0.push_back(Ops::from(p.pinned ? Vec3::Zero().eval() : p.velocity));
    }
    for (const auto& e : scene.effects)  // collisions and applied forces act on bodies only
      if (!std::holds_alternative<Collisions>(e) && !std::holds_alternative<AppliedForces>(e))
        m.effects.push_back(convert(e));
    std::vector<double> y0(state_size(m));
    initial_state(m, y0);
    m.constraints = Constraints::build(scene, m.names, y0);
    if (!m.constraints.constraints.empty()) m.solver.emplace(scene.constraint_solver, m.inv_mass);
    m.forces.assign(m.names.size(), Ops::from(Vec3::Zero()));
    return m;
  }

  static std::size_t state_size(const Model& m) { return 6 * m.names.size(); }
  static std::vector<int> velocity_of(const Model& m) { return particle_layout(m.names.size()); }

  static void initial_state(const Model& m, std::span<double> y) {
    for (std::size_t i = 0; i < m.names.size(); ++i) {
      const auto x = Ops::raw(m.x0[i]), v = Ops::raw(m.v0[i]);
      for (int k = 0; k < 3; ++k) {
        y[6 * i + k] = x[k];
        y[6 * i + 3 + k] = v[k];
      }
    }
  }

  static void derivative(const Model& m, double, std::span<const double> y, std::span<double> dydt, Profile& profile) {
    {
      ScopedStage timed(profile, Stage::forces);
      for (auto& f : m.forces) f = Ops::from(Vec3::Zero());
      for (const auto& e : m.effects) std::visit([&](const auto& effect) { add_force(effect, m, y, m.forces); }, e);
    }
    if (m.solver) {
      ScopedStage timed(profile, Stage::constraints);
      Constraints::add_forces(m.constraints, m.inv_mass, y, m.forces, *m.solver);
    }
    for (std::size_t i = 0; i < m.forces.size(); ++i) {
      const auto a = Ops::raw(m.inv_mass[i] * m.forces[i]);
      for (int k = 0; k < 3; ++k) {
        dydt[6 * i + k] = m.inv_mass[i] == 0 ? 0.0 : y[6 * i + 3 + k];
        dydt[6 * i + 3 + k] = a[k];
      }
    }
  }

  static bool after_step(const Model& m, std::vector<double>& y, Profile& profile) {
    if (!m.solver || m.solver->spec().drift != Drift::projection) return false;
    ScopedStage timed(profile, Stage::constraints);
    Constraints::project(m.constraints, y, *m.solver);
    return true;
  }

  static void observe(const Model& m, std::span<const double> y, Sample& s) {
    s.particles.resize(m.names.size());
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      s.particles[i].position = Ops::to_world(Ops::position(y, static_cast<int>(i)));
      s.particles[i].velocity = Ops::to_world(Ops::velocity(y, static_cast<int>(i)));
    }
    if (m.solver) {
      Constraints::fill(m.constraints, {}, y, nullptr);
      s.constraint_violation = max_violation(m.constraints.rows);
    }
  }

  static std::string first_nonfinite(const Model& m, std::span<const double> y) {
    return core::first_nonfinite(y, 6, m.names, "particle");
  }
  static std::map<std::string, std::uint64_t> counters(const Model& m) { return constraint_counters(m.solver); }
  static std::map<std::string, double> metrics(const Model& m) { return constraint_metrics(m.solver); }

  // F += the effect's force on every particle (Table 2).
  static void add_force(const Gravity& e, const Model& m, std::span<const double>, std::vector<V>& f) {
    for (std::size_t i = 0; i < f.size(); ++i) f[i] += m.mass[i] * e.g;
  }
  static void add_force(const LinearDrag& e, const Model&, std::span<const double> y, std::vector<V>& f) {
    for (std::size_t i = 0; i < f.size(); ++i) f[i] -= e.k * Ops::velocity(y, static_cast<int>(i));
  }
  static void add_force(const QuadraticDrag& e, const Model&, std::span<const double> y, std::vector<V>& f) {
    for (std::size_t i = 0; i < f.size(); ++i) {
      const V v = Ops::velocity(y, static_cast<int>(i));
      f[i] -= (e.k * std::sqrt(Ops::dot(v, v))) * v;
    }
  }
  // C m_i m_j / r² along the line between them, softened (Plummer) to
  // C m_i m_j r / (r² + ε²)^(3/2). With ε = 0, two particles that meet give a
  // non-finite state that the run reports by name.
  static void add_force(const AttractionBetweenParticles& e, const Model& m, std::span<const double> y,
                        std::vector<V>& f) {
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = i + 1; j < f.size(); ++j) {
        const V r = Ops::position(y, static_cast<int>(j)) - Ops::position(y, static_cast<int>(i));
        const double r2 = Ops::dot(r, r) + e.eps2;
        const V fij = (e.C * m.mass[i] * m.mass[j] / (r2 * std::sqrt(r2))) * r;
        f[i] += fij;
        f[j] -= fij;
      }
  }
  static void add_force(const AttractionToPoint& e, const Model& m, std::span<const double> y, std::vector<V>& f) {
    for (std::size_t i = 0; i < f.size(); ++i) {
      const V r = e.point - Ops::position(y, static_cast<int>(i));
      const double r2 = Ops::dot(r, r) + e.eps2;
      f[i] += (e.D * m.mass[i] / (r2 * std::sqrt(r2))) * r;
    }
  }

 private:
  static Effect convert(const core::Effect& e) {
    if (auto* g = std::get_if<core::Gravity>(&e)) return Gravity{Ops::from(g->g)};
    if (auto* d = std::get_if<core::LinearDrag>(&e)) return LinearDrag{d->k};
    if (auto* d = std::get_if<core::QuadraticDrag>(&e)) return QuadraticDrag{d->k};
    if (auto* a = std::get_if<core::AttractionBetweenParticles>(&e))
      return AttractionBetweenParticles{a->C, a->softening * a->softening};
    const auto& p = std::get<core::AttractionToPoint>(e);
    return AttractionToPoint{Ops::from(p.point), p.D, p.softening * p.softening};
  }
};

}  // namespace gacompare::core
