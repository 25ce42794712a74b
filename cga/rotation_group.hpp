#pragma once
// The rotor of Cl(3,0) as a group for the Lie-group integrators
// (core/dynamics/lie_group.hpp, concept RotationGroup). Twin of
// traditional/rotation_group.hpp and pga/rotation_group.hpp: same names, same order.
//
// x_world = R x R̃ (body to world); the body-frame rotation vector w is the
// bivector Ω = w I, and its rotor is the algebra's own exponential,
// exp(−Ω/2) = cos(θ/2) − Ω sin(θ/2)/θ (cl3.hpp exp): no matrix to re-orthogonalise.
#include "core/dynamics/lie_group.hpp"

#include "cga/algebra/cl3.hpp"

#include <Eigen/Core>

#include <cmath>
#include <string_view>

namespace gacompare::cga {

struct RotorGroup {
  using Element = Rotor3;
  using Coordinates = Eigen::Vector4d;  // 1 e12 e13 e23
  static constexpr std::string_view name = "rotor (cga)";
  static Element identity() { return {{1, 0, 0, 0}}; }
  static Element compose(const Element& a, const Element& b) { return widen<Rotor3::blades>(a * b); }
  static Element exp(const Eigen::Vector3d& w) { return cga::exp(bivector_of_axial(vector3(w)) * -0.5); }
  static Eigen::Vector3d rotate(const Element& r, const Eigen::Vector3d& v) { return to_eigen(sandwich(r, vector3(v))); }
  static Eigen::Vector3d inverse_rotate(const Element& r, const Eigen::Vector3d& v) {
    return to_eigen(sandwich(reverse(r), vector3(v)));
  }
  static Eigen::Matrix3d matrix(const Element& r) { return rotation_matrix(r); }
  static double drift(const Element& r) { return std::abs(norm2(r) - 1); }
  static Coordinates coordinates(const Element& r) { return {r.c[0], r.c[1], r.c[2], r.c[3]}; }
  static Element from_coordinates(const Coordinates& c) { return {{c[0], c[1], c[2], c[3]}}; }
  // Ṙ = −½ R Ω_body (eq. 35 with Ω = R Ω_body R̃).
  static Coordinates rate(const Element& r, const Eigen::Vector3d& w) {
    return coordinates(widen<Rotor3::blades>(r * bivector_of_axial(vector3(w))) * -0.5);
  }
};

static_assert(core::lie::RotationGroup<RotorGroup>);

}  // namespace gacompare::cga
