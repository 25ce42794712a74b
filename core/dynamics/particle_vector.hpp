#pragma once
// The vector algebra a backend supplies for particles (traditional/particle.hpp,
// cga/particle.hpp): particle dynamics and constraints are written once over
// it (core/dynamics/particle_system.hpp, particle_constraints.hpp).
#include "core/model/scene.hpp"

#include <array>
#include <concepts>
#include <span>

namespace gacompare::core {

// State per particle: [x (3), v (3)]. A Vector adds, subtracts and scales.
template <class Ops>
concept ParticleVectorOps = requires(std::span<const double> y, int i, const typename Ops::Vector& a,
                                     typename Ops::Vector& out, const Vec3& x, const std::array<double, 3>& raw,
                                     double k) {
  { Ops::position(y, i) } -> std::convertible_to<typename Ops::Vector>;  // particle i's x
  { Ops::velocity(y, i) } -> std::convertible_to<typename Ops::Vector>;  // and v
  { Ops::from(x) } -> std::convertible_to<typename Ops::Vector>;         // a world 3-vector in the algebra
  { Ops::to_world(a) } -> std::convertible_to<Vec3>;                     // and back
  { Ops::dot(a, a) } -> std::convertible_to<double>;
  { Ops::cross(a, a) } -> std::convertible_to<typename Ops::Vector>;     // a × b, or the dual of a ∧ b
  { Ops::unit(a) } -> std::convertible_to<typename Ops::Vector>;
  { Ops::raw(a) } -> std::convertible_to<std::array<double, 3>>;         // its three components
  { Ops::vec(raw) } -> std::convertible_to<typename Ops::Vector>;
  { a + a } -> std::convertible_to<typename Ops::Vector>;
  { a - a } -> std::convertible_to<typename Ops::Vector>;
  { k * a } -> std::convertible_to<typename Ops::Vector>;
  { out += a };
  { out -= a };
};

}  // namespace gacompare::core
