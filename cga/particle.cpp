#include "cga/particle.hpp"

#include "core/error.hpp"

#include <cmath>

namespace gacompare::cga {

namespace {
Vector position(std::span<const double> y, std::size_t i) { return vector3(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
Vector velocity(std::span<const double> y, std::size_t i) { return vector3(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }

ParticleEffect convert(const core::Effect& e) {
  if (auto* g = std::get_if<core::Gravity>(&e)) return Gravity{vector3(g->g)};
  if (auto* d = std::get_if<core::LinearDrag>(&e)) return LinearDrag{d->k};
  if (auto* d = std::get_if<core::QuadraticDrag>(&e)) return QuadraticDrag{d->k};
  if (auto* a = std::get_if<core::AttractionBetweenParticles>(&e))
    return AttractionBetweenParticles{a->C, a->softening * a->softening};
  const auto& p = std::get<core::AttractionToPoint>(e);
  return AttractionToPoint{vector3(p.point), p.D, p.softening * p.softening};
}
}  // namespace

ParticleModel build_particles(const core::Scene& scene) {
  ParticleModel m;
  for (const auto& p : scene.particles) {
    m.names.push_back(p.name);
    m.mass.push_back(p.mass);
    m.inv_mass.push_back(p.pinned ? 0.0 : 1.0 / p.mass);
    m.x0.push_back(vector3(p.position));
    m.v0.push_back(p.pinned ? Vector{} : vector3(p.velocity));
  }
  for (const auto& e : scene.effects)
    if (!std::holds_alternative<core::Collisions>(e)) m.effects.push_back(convert(e));
  return m;
}

void initial_particle_state(const ParticleModel& m, std::span<double> y) {
  for (std::size_t i = 0; i < m.names.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      y[6 * i + k] = m.x0[i].c[k];
      y[6 * i + 3 + k] = m.v0[i].c[k];
    }
}

void add_force(const Gravity& e, const ParticleModel& m, std::span<const double>, std::vector<Vector>& f) {
  for (std::size_t i = 0; i < f.size(); ++i) f[i] += m.mass[i] * e.g;
}

void add_force(const LinearDrag& e, const ParticleModel&, std::span<const double> y, std::vector<Vector>& f) {
  for (std::size_t i = 0; i < f.size(); ++i) f[i] -= e.k * velocity(y, i);
}

void add_force(const QuadraticDrag& e, const ParticleModel&, std::span<const double> y, std::vector<Vector>& f) {
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Vector v = velocity(y, i);
    f[i] -= e.k * norm(v) * v;
  }
}

// Table 2: C m_i m_j / r² along the line between them, softened (Plummer) to
// C m_i m_j r / (r² + ε²)^(3/2). With ε = 0, two particles that meet give a
// non-finite state that the run reports by name.
void add_force(const AttractionBetweenParticles& e, const ParticleModel& m, std::span<const double> y,
               std::vector<Vector>& f) {
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = i + 1; j < f.size(); ++j) {
      const Vector r = position(y, j) - position(y, i);
      const double r2 = norm2(r) + e.eps2;
      const Vector fij = (e.C * m.mass[i] * m.mass[j] / (r2 * std::sqrt(r2))) * r;
      f[i] += fij;
      f[j] -= fij;
    }
}

void add_force(const AttractionToPoint& e, const ParticleModel& m, std::span<const double> y, std::vector<Vector>& f) {
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Vector r = e.point - position(y, i);
    const double r2 = norm2(r) + e.eps2;
    f[i] += (e.D * m.mass[i] / (r2 * std::sqrt(r2))) * r;
  }
}

void accumulate_forces(const ParticleModel& m, std::span<const double> y, std::vector<Vector>& forces,
                       core::Profile& profile) {
  core::ScopedStage timed(profile, core::Stage::forces);
  for (auto& f : forces) f = Vector{};
  for (const auto& e : m.effects) std::visit([&](const auto& effect) { add_force(effect, m, y, forces); }, e);
}

void particle_derivative(const ParticleModel& m, std::span<const double> y, const std::vector<Vector>& forces,
                         std::span<double> dydt) {
  for (std::size_t i = 0; i < forces.size(); ++i) {
    const Vector a = m.inv_mass[i] * forces[i];
    for (int k = 0; k < 3; ++k) {
      dydt[6 * i + k] = m.inv_mass[i] == 0 ? 0.0 : y[6 * i + 3 + k];
      dydt[6 * i + 3 + k] = a.c[k];
    }
  }
}

}  // namespace gacompare::cga
