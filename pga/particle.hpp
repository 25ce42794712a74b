#pragma once
// Plane-based geometric algebra for particles. A free vector is held as the
// plane through the origin it is normal to (v1 e1 + v2 e2 + v3 e3): its
// products are Euclidean (e1² = e2² = e3² = 1), so a·b is the scalar product,
// and a ∧ b is the line where the two planes meet, through the origin, whose
// direction is a × b (pga/algebra/cl301.hpp line_direction). Particle
// dynamics and constraints are written once over it in
// core/dynamics/particle_system.hpp. Twin of cga/particle.hpp.
#include "pga/algebra/cl301.hpp"
#include "core/dynamics/particle_system.hpp"

#include <array>
#include <span>

namespace gacompare::pga {

using Vector = Multivector<Cl301, (BladeSet{1} << e4::e1) | (BladeSet{1} << e4::e2) | (BladeSet{1} << e4::e3)>;

inline Vector vector(double x, double y, double z) { return {{x, y, z}}; }

struct VectorOps {
  using Vector = pga::Vector;
  static Vector position(std::span<const double> y, int i) { return vector(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
  static Vector velocity(std::span<const double> y, int i) { return vector(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
  static Vector from(const core::Vec3& v) { return vector(v.x(), v.y(), v.z()); }
  static core::Vec3 to_world(const Vector& v) { return {v.c[0], v.c[1], v.c[2]}; }
  static double dot(const Vector& a, const Vector& b) { return scalar_product(a, b); }
  static Vector cross(const Vector& a, const Vector& b) {
    const Vec3 d = line_direction(cga::widen<Line::blades>(a ^ b));
    return vector(d.x(), d.y(), d.z());
  }
  static Vector unit(const Vector& a) { return a / std::sqrt(scalar_product(a, a)); }
  static std::array<double, 3> raw(const Vector& a) { return a.c; }
  static Vector vec(const std::array<double, 3>& a) { return Vector{a}; }
};

using Particles = core::ParticleSystem<VectorOps>;

}  // namespace gacompare::pga
