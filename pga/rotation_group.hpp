#pragma once
// The motor of Cl(3,0,1) as a group for the Lie-group integrators
// (core/dynamics/lie_group.hpp, concept RotationGroup). Twin of
// traditional/rotation_group.hpp and cga/rotation_group.hpp: same names, same order.
//
// The rotational motion only: the motor keeps a zero translation (the body's
// centre is its origin), and the rotation vector w is the line through the
// origin along w, exp(−½ line) (cl301.hpp exp). Its products run over all 8
// components, the ideal half zero: the cost of carrying the motor for a turn.
#include "core/dynamics/lie_group.hpp"

#include "pga/algebra/cl301.hpp"

#include <Eigen/Core>

#include <cmath>
#include <string_view>

namespace gacompare::pga {

struct MotorGroup {
  using Element = Motor;
  using Coordinates = Eigen::Matrix<double, 8, 1>;
  static constexpr std::string_view name = "motor (pga)";
  static Element identity() { return {{1, 0, 0, 0, 0, 0, 0, 0}}; }
  static Element compose(const Element& a, const Element& b) { return pga::compose(a, b); }
  static Element exp(const Eigen::Vector3d& w) { return pga::exp(line(w, Vec3::Zero()) * -0.5); }
  static Eigen::Vector3d rotate(const Element& m, const Eigen::Vector3d& v) { return apply_direction(m, v); }
  static Eigen::Vector3d inverse_rotate(const Element& m, const Eigen::Vector3d& v) {
    return apply_direction(reverse(m), v);
  }
  static Eigen::Matrix3d matrix(const Element& m) { return rotation_matrix(m); }
  // |R R̃ − 1| of the rotation part (the backend's rotation_drift).
  static double drift(const Element& m) { return std::abs(study(m).first - 1); }
  static Coordinates coordinates(const Element& m) { return Eigen::Map<const Coordinates>(m.c.data()); }
  static Element from_coordinates(const Coordinates& c) {
    Element m;
    for (int i = 0; i < 8; ++i) m.c[static_cast<std::size_t>(i)] = c[i];
    return m;
  }
  // Ṁ = −½ M V_body, V_body the rate line through the origin along ω.
  static Coordinates rate(const Element& m, const Eigen::Vector3d& w) {
    return coordinates(cga::widen<Motor::blades>(m * line(w, Vec3::Zero())) * -0.5);
  }
};

static_assert(core::lie::RotationGroup<MotorGroup>);

}  // namespace gacompare::pga
