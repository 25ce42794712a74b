#pragma once
// Constraints on particles (§2.1.2) in geometric algebra: the rows are written
// once in core/particle_constraints.hpp; this is the algebra they run on, Cl(3,0)
// vectors with the scalar product, and a × b as the vector dual to the plane a ∧ b.
// Twin of traditional/constraint.hpp.
#include "cga/particle.hpp"
#include "core/particle_constraints.hpp"

namespace gacompare::cga {

struct VectorOps {
  using Vector = cga::Vector;
  static Vector position(std::span<const double> y, int i) { return vector3(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
  static Vector velocity(std::span<const double> y, int i) { return vector3(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
  static Vector from(const core::Vec3& v) { return vector3(v); }
  static double dot(const Vector& a, const Vector& b) { return scalar_product(a, b); }
  static Vector cross(const Vector& a, const Vector& b) { return axial(a ^ b); }
  static Vector unit(const Vector& a) { return a / norm(a); }
  static std::array<double, 3> raw(const Vector& a) { return a.c; }
  static Vector vec(const std::array<double, 3>& a) { return Vector{a}; }
};

using Constraints = core::ParticleConstraints<VectorOps>;
using ConstraintModel = Constraints::Model;

}  // namespace gacompare::cga
