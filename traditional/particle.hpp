#pragma once
// Particle dynamics with 3-vectors (§2.1.1, Table 2), the traditional twin of
// cga/particle.hpp: same names, same order, only the algebra differs.
// State per particle: [x, v], 6 doubles, contiguous. dx/dt = v, dv/dt = F/m.
#include "core/scene.hpp"
#include "core/stage.hpp"

#include <Eigen/Core>

#include <span>
#include <string>
#include <variant>
#include <vector>

namespace gacompare::traditional {

using Vector = Eigen::Vector3d;

// The effects a scene lists, in this backend's types (built once, DESIGN.md).
struct Gravity { Vector g; };
struct LinearDrag { double k; };
struct QuadraticDrag { double k; };
struct AttractionBetweenParticles { double C; double eps2; };       // eps2: softening length squared
struct AttractionToPoint { Vector point; double D; double eps2; };
using ParticleEffect = std::variant<Gravity, LinearDrag, QuadraticDrag, AttractionBetweenParticles, AttractionToPoint>;

struct ParticleModel {
  std::vector<std::string> names;
  std::vector<double> mass, inv_mass;  // inv_mass 0 for pinned particles
  std::vector<Vector> x0, v0;
  std::vector<ParticleEffect> effects;
};

inline constexpr std::size_t kParticleState = 6;

ParticleModel build_particles(const core::Scene& scene);
void initial_particle_state(const ParticleModel& m, std::span<double> y);

// F += the effect's force on every particle.
void add_force(const Gravity& e, const ParticleModel& m, std::span<const double> y, std::vector<Vector>& f);
void add_force(const LinearDrag& e, const ParticleModel& m, std::span<const double> y, std::vector<Vector>& f);
void add_force(const QuadraticDrag& e, const ParticleModel& m, std::span<const double> y, std::vector<Vector>& f);
void add_force(const AttractionBetweenParticles& e, const ParticleModel& m, std::span<const double> y,
               std::vector<Vector>& f);
void add_force(const AttractionToPoint& e, const ParticleModel& m, std::span<const double> y, std::vector<Vector>& f);

// forces = the sum of every listed effect's force (stage `forces`).
void accumulate_forces(const ParticleModel& m, std::span<const double> y, std::vector<Vector>& forces,
                       core::Profile& profile);
// dy/dt from the total forces: dx/dt = v, dv/dt = F/m; zero for pinned particles.
void particle_derivative(const ParticleModel& m, std::span<const double> y, const std::vector<Vector>& forces,
                         std::span<double> dydt);

}  // namespace gacompare::traditional
