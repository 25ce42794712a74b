#pragma once
// The geometric algebra for particles: Cl(3,0) vectors, the scalar product, and
// a × b as the vector dual to the plane a ∧ b. Particle dynamics and constraints
// are written once over it in core/dynamics/particle_system.hpp. Twin of traditional/particle.hpp.
#include "cga/algebra/cl3.hpp"
#include "core/dynamics/particle_system.hpp"

#include <array>
#include <span>

namespace gacompare::cga {

using Vector = Vector3;

struct VectorOps {
  using Vector = cga::Vector;
  static Vector position(std::span<const double> y, int i) { return vector3(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
  static Vector velocity(std::span<const double> y, int i) { return vector3(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
  static Vector from(const core::Vec3& v) { return vector3(v); }
  static core::Vec3 to_world(const Vector& v) { return to_eigen(v); }
  static double dot(const Vector& a, const Vector& b) { return scalar_product(a, b); }
  static Vector cross(const Vector& a, const Vector& b) { return axial(a ^ b); }
  static Vector unit(const Vector& a) { return a / norm(a); }
  static std::array<double, 3> raw(const Vector& a) { return a.c; }
  static Vector vec(const std::array<double, 3>& a) { return Vector{a}; }
};

using Particles = core::ParticleSystem<VectorOps>;

}  // namespace gacompare::cga
