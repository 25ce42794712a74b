#pragma once
// Cl(3,0): the algebra of the mechanics (§1.2, §2.3.2): vectors, bivectors for
// angular velocity, momentum and torque, rotors for orientation.
//
// Basis bivectors are stored in canonical order e12, e13, e23. The report (eq. 3)
// uses B1 = e1e2, B2 = e2e3, B3 = e3e1 = −e13; conversions below take care of it.
// A rotor R = exp(−Bθ/2) rotates by x' = R x R̃ (§1.2.4, eq. 2 and 8). For a
// right-handed rotation by θ about the unit axis a, B = a I (the plane dual to a):
// about e3, B = e12, and R = cos(θ/2) − e12 sin(θ/2) takes e1 to cosθ e1 + sinθ e2.
// The unit quaternion (w, x, y, z) of the same rotation is R = w − x e23 + y e13 − z e12.
#include "cga/algebra/multivector.hpp"
#include "core/geometry.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace gacompare::cga {

namespace e3 {  // basis blades of Cl(3,0) as bitmasks
inline constexpr unsigned scalar = 0, e1 = 1, e2 = 2, e12 = 3, e3 = 4, e13 = 5, e23 = 6, e123 = 7;
}

using Scalar3 = Multivector<Cl3, grades<Cl3>({0})>;
using Vector3 = Multivector<Cl3, grades<Cl3>({1})>;
using Bivector3 = Multivector<Cl3, grades<Cl3>({2})>;
using Trivector3 = Multivector<Cl3, grades<Cl3>({3})>;
using Rotor3 = Multivector<Cl3, grades<Cl3>({0, 2})>;  // the even subalgebra
using Full3 = Multivector<Cl3, Cl3::all>;

constexpr Vector3 vector3(double x, double y, double z) { return {{x, y, z}}; }
inline Vector3 vector3(const Eigen::Vector3d& v) { return {{v.x(), v.y(), v.z()}}; }
inline Eigen::Vector3d to_eigen(const Vector3& v) { return {v.c[0], v.c[1], v.c[2]}; }

// Bivector from components in canonical order e12, e13, e23.
constexpr Bivector3 bivector3(double b12, double b13, double b23) { return {{b12, b13, b23}}; }
// The bivector a I dual to an axial vector a (ω as a vector ↔ Ω as a bivector):
// e1 → e23, e2 → e31 = −e13, e3 → e12. Its inverse is axial().
constexpr Bivector3 bivector_of_axial(const Vector3& a) { return {{a.c[2], -a.c[1], a.c[0]}}; }
constexpr Vector3 axial(const Bivector3& b) { return {{b.c[2], -b.c[1], b.c[0]}}; }

// exp of a bivector, closed form: B² = −|B|² ≤ 0, so exp(B) = cos|B| + B sin|B|/|B|.
// Near zero, sin|B|/|B| is taken from its series so tiny angles keep full precision.
inline Rotor3 exp(const Bivector3& b) {
  const double t2 = b.c[0] * b.c[0] + b.c[1] * b.c[1] + b.c[2] * b.c[2];
  const double t = std::sqrt(t2);
  const double sinc = t < 1e-4 ? 1.0 - t2 / 6.0 + t2 * t2 / 120.0 : std::sin(t) / t;
  return {{std::cos(t), sinc * b.c[0], sinc * b.c[1], sinc * b.c[2]}};
}

// log of a unit rotor, the inverse of exp: for R = c + B (B a bivector,
// c² + |B|² = 1), log R = B atan2(|B|, c) / |B|, the bivector whose exp is R
// with |log R| ≤ π. R^s = exp(s log R) is the rotor that turns s of the way
// (§4.3.2's interpolation of rotors; the quaternion slerp's twin). Near the
// identity atan2(t, c)/t is taken from its series; −1 (a turn by 2π, the same
// rotation as 1) gives π e12.
inline Bivector3 log(const Rotor3& r) {
  const double t2 = r.c[1] * r.c[1] + r.c[2] * r.c[2] + r.c[3] * r.c[3];
  const double t = std::sqrt(t2);
  if (t == 0) return r.c[0] < 0 ? bivector3(std::numbers::pi, 0, 0) : bivector3(0, 0, 0);
  const double k = t < 1e-8 * r.c[0] ? (1.0 - t2 / (3.0 * r.c[0] * r.c[0])) / r.c[0] : std::atan2(t, r.c[0]) / t;
  return {{k * r.c[1], k * r.c[2], k * r.c[3]}};
}

// R = exp(−Bθ/2) for the rotation by `angle` (rad) about the unit `axis`, right-handed.
inline Rotor3 rotor_from_axis_angle(const Vector3& axis, double angle) {
  return exp(bivector_of_axial(axis) * (-0.5 * angle));
}

inline Rotor3 rotor_from_quaternion(const Eigen::Quaterniond& q) {
  return {{q.w(), -q.z(), q.y(), -q.x()}};
}
inline Eigen::Quaterniond quaternion_from_rotor(const Rotor3& r) {
  return Eigen::Quaterniond(r.c[0], -r.c[3], r.c[2], -r.c[1]);
}

// The 3×3 matrix of x ↦ R x R̃ / (R R̃) (the rotor's outermorphism), built once
// per body so that many vertices cost a matrix–vector product each (§2.3.2
// "calculate once"; klein applies its rotors the same way: coefficients once,
// then applied). The homogeneous form divided by R R̃ is an exact rotation for
// any non-zero rotor, drifted or not, with one division and no square root:
// the same policy as the quaternion's (traditional/rigid_body.cpp rotation_of).
// With R = w + a e12 + b e13 + c e23, the equivalent quaternion is (w, −c, b, −a).
inline Eigen::Matrix3d rotation_matrix(const Rotor3& r) {
  return geometry::rotation_of(r.c[0], -r.c[3], r.c[2], -r.c[1]);
}

// The same rotation acting on bivector coordinates (e12, e13, e23): B ↦ R B R̃
// is the rotation of B's dual axial vector (a rotation commutes with the dual),
// so it is P M P with P the signed permutation of bivector_of_axial (P = P⁻¹).
inline Eigen::Matrix3d bivector_rotation_matrix(const Rotor3& r) {
  const Eigen::Matrix3d m = rotation_matrix(r);
  Eigen::Matrix3d s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double sign = ((i == 1) != (j == 1)) ? -1.0 : 1.0;
      s(i, j) = sign * m(2 - i, 2 - j);
    }
  return s;
}

}  // namespace gacompare::cga
