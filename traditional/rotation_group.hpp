#pragma once
// The rotation matrix and the unit quaternion as groups for the Lie-group
// integrators (core/dynamics/lie_group.hpp, concept RotationGroup). Twin of
// cga/rotation_group.hpp and pga/rotation_group.hpp: same names, same order.
#include "core/dynamics/lie_group.hpp"
#include "core/geometry.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <utility>

namespace gacompare::traditional {

// sin(t)/t and (1 − cos t)/t² = ½ (sin(t/2)/(t/2))², by their series near 0
// (the second written with the half angle has no cancellation anywhere).
inline std::pair<double, double> rodrigues_coefficients(double t) {
  const double t2 = t * t;
  const auto sinc = [](double u) { return u < 1e-4 ? 1.0 - u * u / 6.0 : std::sin(u) / u; };
  const double half = sinc(0.5 * t);
  return {t < 1e-4 ? 1.0 - t2 / 6.0 : std::sin(t) / t, 0.5 * half * half};
}

inline Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

// R (body to world) as a 3×3 matrix; exp by Rodrigues' formula,
// exp(ŵ) = I + (sin θ/θ) ŵ + ((1 − cos θ)/θ²) ŵ², θ = |w|.
struct MatrixGroup {
  using Element = Eigen::Matrix3d;
  using Coordinates = Eigen::Matrix<double, 9, 1>;
  static constexpr std::string_view name = "matrix (traditional)";
  static Element identity() { return Element::Identity(); }
  static Element compose(const Element& a, const Element& b) { return a * b; }
  static Element exp(const Eigen::Vector3d& w) {
    const auto [a, b] = rodrigues_coefficients(w.norm());
    const Eigen::Matrix3d k = hat(w);
    return Element::Identity() + a * k + b * (k * k);
  }
  static Eigen::Vector3d rotate(const Element& r, const Eigen::Vector3d& v) { return r * v; }
  static Eigen::Vector3d inverse_rotate(const Element& r, const Eigen::Vector3d& v) { return r.transpose() * v; }
  static Eigen::Matrix3d matrix(const Element& r) { return r; }
  static double drift(const Element& r) { return (r.transpose() * r - Eigen::Matrix3d::Identity()).norm(); }
  static Coordinates coordinates(const Element& r) { return Eigen::Map<const Coordinates>(r.data()); }
  static Element from_coordinates(const Coordinates& c) { return Eigen::Map<const Element>(c.data()); }
  static Coordinates rate(const Element& r, const Eigen::Vector3d& w) { return coordinates(r * hat(w)); }
};

// A unit quaternion q (x_world = q x q*); exp(w) = (cos(θ/2), sin(θ/2) w/θ).
struct QuaternionGroup {
  using Element = Eigen::Quaterniond;
  using Coordinates = Eigen::Vector4d;  // w x y z
  static constexpr std::string_view name = "quaternion (traditional)";
  static Element identity() { return Element::Identity(); }
  static Element compose(const Element& a, const Element& b) { return a * b; }
  static Element exp(const Eigen::Vector3d& w) {
    const double half = 0.5 * w.norm();
    const double s = half < 1e-4 ? 0.5 * (1.0 - half * half / 6.0) : 0.5 * std::sin(half) / half;
    return {std::cos(half), s * w.x(), s * w.y(), s * w.z()};
  }
  // v + 2w (u × v) + 2u × (u × v): the unit quaternion's rotation, as stored.
  static Eigen::Vector3d rotate(const Element& q, const Eigen::Vector3d& v) { return q._transformVector(v); }
  static Eigen::Vector3d inverse_rotate(const Element& q, const Eigen::Vector3d& v) {
    return q.conjugate()._transformVector(v);
  }
  static Eigen::Matrix3d matrix(const Element& q) { return geometry::rotation_of(q.w(), q.x(), q.y(), q.z()); }
  static double drift(const Element& q) { return std::abs(q.squaredNorm() - 1); }
  static Coordinates coordinates(const Element& q) { return {q.w(), q.x(), q.y(), q.z()}; }
  static Element from_coordinates(const Coordinates& c) { return {c[0], c[1], c[2], c[3]}; }
  // q̇ = ½ q (0, ω), ω in the body frame.
  static Coordinates rate(const Element& q, const Eigen::Vector3d& w) {
    return 0.5 * coordinates(q * Element(0, w.x(), w.y(), w.z()));
  }
};

static_assert(core::lie::RotationGroup<MatrixGroup> && core::lie::RotationGroup<QuaternionGroup>);

}  // namespace gacompare::traditional
