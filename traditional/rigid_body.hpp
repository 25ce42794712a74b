#pragma once
// Rigid bodies with matrices, axial vectors and cross products (§2.3.1, eq. 27–34),
// or with unit quaternions (the representation §2.3.1 says most simulations use).
// Twin of cga/rigid_body.hpp: same names, same order, only the algebra differs.
//
// State per body: x (3), rotation (matrix: 9, row-major; quaternion: 4, w x y z),
// P (3), L (3, world axial vector).
//   ẋ = P/m,  Ṗ = F,  L̇ = τ = Σ (p − x) × F_p,
//   ω = I⁻¹(t) L with I⁻¹(t) = R I_body⁻¹ Rᵀ,
//   Ṙ = ω* R (eq. 33)   or   q̇ = ½ (0, ω) q.
// The report's eq. 31 writes I(t) = R I_body: that maps body to world on one side
// only. The world tensor is a similarity transform, R I_body Rᵀ (its inverse
// R I_body⁻¹ Rᵀ); the test against the free symmetric top's precession checks it.
#include "core/collision/collision.hpp"
#include "core/dynamics/rigid_body.hpp"
#include "core/run.hpp"
#include "core/model/scene.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <span>
#include <string>
#include <vector>

namespace gacompare::traditional {

struct RigidBodies {
  struct Body {
    double inv_mass;               // 0 for a static body
    Eigen::Matrix3d inv_inertia;   // body frame; zero for a static body
    Eigen::Matrix3d inertia;       // body frame
    double mass;
  };
  struct Model {
    core::Rotation rotation = core::Rotation::matrix;
    core::Renormalise renormalise = core::Renormalise::none;
    std::vector<std::string> names;
    std::vector<Body> bodies;
    std::vector<double> y0;        // the initial state, packed
    core::BodyEffects effects;
    std::size_t stride = 18;       // doubles per body
  };

  // core::RigidBodies (core/dynamics/rigid_body.hpp) declares and documents
  // every operation; only how this algebra does each is said here.
  static Model build(const core::Scene& scene, const core::Model& model);
  static Model subset(const Model& m, std::span<const int> which);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         std::span<const char> asleep = {});
  // Gram–Schmidt for a matrix, q/|q| for a quaternion.
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // ‖RᵀR − I‖ (Frobenius) or |q q* − 1|.
  static double rotation_drift(const Model& m, std::span<const double> y);
  static double error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                            std::span<const double> err, double abs, double rel);
  // A Lie-group method's step (core/dynamics/rigid_body.hpp) through traditional/rotation_group.hpp: the matrix by
  // Rodrigues' formula, or the quaternion.
  static void group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                         std::span<double> out, std::span<double> err, std::span<const char> asleep = {});

  // --- collisions (§2.4–2.5); called only when the scene lists the effect ---
  static collision::Pose pose(const Model& m, std::span<const double> y, std::size_t b);
  // The rotation by the quaternion slerp (a matrix read as its quaternion).
  static collision::Pose interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                           std::size_t b, double s);
  struct Motion {
    Eigen::Vector3d x, v, w;         // centre of mass, velocity, angular velocity (axial)
    Eigen::Matrix3d inv_inertia;     // world: R I⁻¹ Rᵀ (eq. 31 as corrected above); zero when static
    double inv_mass = 0;             // zero when static
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero(), angular_impulse = Eigen::Vector3d::Zero();
  };
  struct Arm {
    Eigen::Vector3d r_n, turn;  // r × n and I⁻¹(r × n)
  };
  static Motion motion(const Model& m, std::span<const double> y, std::size_t b);
  static Eigen::Vector3d position(const Motion& b) { return b.x; }
  static Motion at_rest(const Motion& b) {
    Motion p = b;
    p.v.setZero(), p.w.setZero(), p.impulse.setZero(), p.angular_impulse.setZero();
    return p;
  }
  static Arm arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // Eq. 53: 1/M + n·((I⁻¹(r × n)) × r) = 1/M + (r × n)·I⁻¹(r × n).
  static double inverse_effective_mass(const Motion& b, const Arm& a);
  // n·(v + ω × r), with n·(ω × r) = ω·(r × n).
  static double normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n);
  static void push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j);
  // ṗ = v + ω × r; the in-plane part n × (u × n) = u − (u·n) n; the quarter turn n × t.
  static Eigen::Vector3d point_velocity(const Motion& b, const Eigen::Vector3d& p);
  static Eigen::Vector3d in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u);
  static Eigen::Vector3d quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t);
  static double speed(const Motion& b) { return b.v.norm(); }
  static double angular_speed(const Motion& b) { return b.w.norm(); }
  static void store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion);
  static void stop(const Model& m, std::span<double> y, std::size_t b);
  // Turns by the rotation vector w of the pseudo-motion.
  static void displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo);
};

// In the header: the contact solver's sweeps call these once per row per sweep.
inline double RigidBodies::normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n) {
  return n.dot(b.v) + a.r_n.dot(b.w);
}

inline void RigidBodies::push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j) {
  if (b.inv_mass == 0) return;
  b.v += (j * b.inv_mass) * n;
  b.w += j * a.turn;
  b.impulse += j * n;
  b.angular_impulse += j * a.r_n;
}

}  // namespace gacompare::traditional
