#pragma once
// Constraints on particles (§2.1.2) in the traditional algebra: the rows are
// written once in core/particle_constraints.hpp; this is the algebra they run on,
// Eigen 3-vectors with dot and cross products. Twin of cga/constraint.hpp.
#include "core/particle_constraints.hpp"
#include "traditional/particle.hpp"

#include <Eigen/Geometry>

namespace gacompare::traditional {

struct VectorOps {
  using Vector = traditional::Vector;
  static Vector position(std::span<const double> y, int i) { return Vector(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
  static Vector velocity(std::span<const double> y, int i) { return Vector(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
  static Vector from(const core::Vec3& v) { return v; }
  static double dot(const Vector& a, const Vector& b) { return a.dot(b); }
  static Vector cross(const Vector& a, const Vector& b) { return a.cross(b); }
  static Vector unit(const Vector& a) { return a.normalized(); }
  static std::array<double, 3> raw(const Vector& a) { return {a[0], a[1], a[2]}; }
  static Vector vec(const std::array<double, 3>& a) { return Vector(a[0], a[1], a[2]); }
};

using Constraints = core::ParticleConstraints<VectorOps>;
using ConstraintModel = Constraints::Model;

}  // namespace gacompare::traditional
