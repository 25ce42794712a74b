#pragma once
// Constraints on particles (§2.1.2) with 3-vectors: each constraint gives rows of
// C, ∇C, J̇q̇ in this backend's algebra; core::ConstraintSolver finds λ and the
// forces Jᵀλ are applied here. Twin of cga/constraint.hpp.
#include "core/constraint_solver.hpp"
#include "traditional/particle.hpp"

#include <span>
#include <variant>
#include <vector>

namespace gacompare::traditional {

struct PointDistance { int p; Vector point; double length; };   // C = ½(|x − o|² − L²)        (eq. 25)
struct PairDistance { int a, b; double length; };               // C = ½(|xa − xb|² − L²)      (eq. 26)
struct PlaneConstraint { int p; Vector point, normal; };        // C = n·(x − o)
struct LineConstraint { int p; Vector point, u1, u2; };         // C_i = u_i·(x − o), u_i ⊥ line
struct CircleConstraint { int p; Vector center, normal; double radius; };  // plane row + sphere row
struct HelixConstraint { int p; Vector center, u, v, axis; double radius, k; };  // k = pitch / 2π
using ParticleConstraint = std::variant<PointDistance, PairDistance, PlaneConstraint, LineConstraint,
                                        CircleConstraint, HelixConstraint>;

struct ConstraintModel {
  std::vector<ParticleConstraint> constraints;
  std::vector<int> owner;  // per row: the constraint (scene order) it belongs to
  mutable std::vector<core::ConstraintRow> rows;  // scratch, refilled on every evaluation
};

// Resolves names to particle indices and builds each constraint's frame. Throws
// input_error when the initial state does not satisfy a constraint.
ConstraintModel build_constraints(const core::Scene& scene, const ParticleModel& particles);

// Fills m.rows at state y, with `forces` the applied forces (for J W Q).
void constraint_rows(const ConstraintModel& m, const ParticleModel& particles, std::span<const double> y,
                     const std::vector<Vector>& forces);

// forces += Jᵀλ with λ from eq. 24 (and Baumgarte's terms when chosen).
void add_constraint_forces(const ConstraintModel& m, const ParticleModel& particles, std::span<const double> y,
                           std::vector<Vector>& forces, core::ConstraintSolver& solver);

// drift = projection: moves positions, then velocities, onto the constraints by
// mass-weighted least-change steps x += W Jᵀ δλ (Gauss–Newton on C(x) = 0, then
// J v = 0), until every violation is below the tolerance.
void project_constraints(const ConstraintModel& m, const ParticleModel& particles, std::span<double> y,
                         core::ConstraintSolver& solver);

}  // namespace gacompare::traditional
