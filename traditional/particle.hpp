#pragma once
// The traditional algebra for particles: Eigen 3-vectors with dot and cross
// products. Particle dynamics and constraints are written once over it in
// core/dynamics/particle_system.hpp. Twin of cga/particle.hpp.
#include "core/dynamics/particle_system.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <span>

namespace gacompare::traditional {

using Vector = Eigen::Vector3d;

struct VectorOps {
  using Vector = traditional::Vector;
  static Vector position(std::span<const double> y, int i) { return Vector(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
  static Vector velocity(std::span<const double> y, int i) { return Vector(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
  static Vector from(const core::Vec3& v) { return v; }
  static core::Vec3 to_world(const Vector& v) { return v; }
  static double dot(const Vector& a, const Vector& b) { return a.dot(b); }
  static Vector cross(const Vector& a, const Vector& b) { return a.cross(b); }
  static Vector unit(const Vector& a) { return a.normalized(); }
  static std::array<double, 3> raw(const Vector& a) { return {a[0], a[1], a[2]}; }
  static Vector vec(const std::array<double, 3>& a) { return Vector(a[0], a[1], a[2]); }
};

using Particles = core::ParticleSystem<VectorOps>;

}  // namespace gacompare::traditional
