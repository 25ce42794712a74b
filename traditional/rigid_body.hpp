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
#include "core/collision.hpp"
#include "core/rigid_body.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"

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

  static Model build(const core::Scene& scene, const std::vector<core::BodyProperties>& props);
  // Bodies `which` (in any order) of m as a model of their own, in that order
  // (core::copy_bodies): an island integrated alone. No initial state (y0).
  static Model subset(const Model& m, std::span<const int> which);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt);
  // Re-orthonormalises matrices (Gram–Schmidt) or normalises quaternions; true if
  // the scene asks for it (and so the state changed).
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // max over bodies of ‖RᵀR − I‖ (Frobenius) or |q q* − 1|: how far the stored
  // rotation has drifted from a rotation.
  static double rotation_drift(const Model& m, std::span<const double> y);
  // The physical error norm of an adaptive step (issue #13; core/scene.hpp
  // ErrorNorm): per body, |δx|, |δv|, the rotation angle of R⁻¹ δR and |δω|,
  // each over abs + rel·|value| (the angle over abs + rel: a rotation has no
  // size of its own); the worst ratio, NaN when the step is not finite.
  static double error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                            std::span<const double> err, double abs, double rel);

  // --- collisions (§2.4–2.5); called only when the scene lists the effect ---
  // The pose the narrowphase places the mesh with (centre of mass, rotation).
  static collision::Pose pose(const Model& m, std::span<const double> y, std::size_t b);
  // The pose s ∈ [0, 1] of the way from state y0 to y1 (the time-of-impact
  // search's interpolated motion, §4.3.2): the centre of mass along the line,
  // the rotation by the quaternion slerp (a matrix read as its quaternion), the shorter way round.
  static collision::Pose interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                           std::size_t b, double s);
  // The contact solver's view of a body (core/collisions.hpp): its motion in
  // the world frame, read from the state once per response. The solver's rows
  // are built once per contact (Arm) and its sweeps then only take dot
  // products and add vectors; store() writes the accumulated impulses back.
  struct Motion {
    Eigen::Vector3d x, v, w;         // centre of mass, velocity, angular velocity (axial)
    Eigen::Matrix3d inv_inertia;     // world: R I⁻¹ Rᵀ (eq. 31 as corrected above); zero when static
    double inv_mass = 0;             // zero when static
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero(), angular_impulse = Eigen::Vector3d::Zero();
  };
  // One body's part of a contact row along n at p: r × n and I⁻¹(r × n).
  struct Arm {
    Eigen::Vector3d r_n, turn;
  };
  static Motion motion(const Model& m, std::span<const double> y, std::size_t b);
  static Eigen::Vector3d position(const Motion& b) { return b.x; }
  // The same body with no velocity and no impulses: the start of a pseudo-velocity solve.
  static Motion at_rest(const Motion& b) {
    Motion p = b;
    p.v.setZero(), p.w.setZero(), p.impulse.setZero(), p.angular_impulse.setZero();
    return p;
  }
  static Arm arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // Eq. 53's term for one body: 1/M + n·((I⁻¹(r × n)) × r) = 1/M + (r × n)·I⁻¹(r × n).
  static double inverse_effective_mass(const Motion& b, const Arm& a);
  // n·ṗ at the row's point (eq. 47: ṗ = v + ω × r, and n·(ω × r) = ω·(r × n)).
  static double normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n);
  // An impulse j n at the row's point (eq. 48–49): v += j n/M, ω += j I⁻¹(r × n).
  static void push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j);
  // Friction (issue #17): the contact plane's two directions from cross products.
  // The velocity of the body's point at p: ṗ = v + ω × r (eq. 47).
  static Eigen::Vector3d point_velocity(const Motion& b, const Eigen::Vector3d& p);
  // The part of u in the plane with unit normal n: n × (u × n) = u − (u·n) n.
  static Eigen::Vector3d in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u);
  // t (in that plane) turned a right angle about n: n × t.
  static Eigen::Vector3d quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t);
  // |v| and |ω|: how far a point at distance ρ from the centre can move.
  static double speed(const Motion& b) { return b.v.norm(); }
  static double angular_speed(const Motion& b) { return b.w.norm(); }
  // P += Σ j n, L += Σ j r × n: the impulses pushed into the motion.
  static void store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion);
  // Positional correction by pseudo-velocities (split impulse): moves body b by
  // the displacement v and turns it by the rotation vector w of a Motion that
  // started at rest; P and L are not touched, so no momentum is injected.
  static void displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo);
};

}  // namespace gacompare::traditional
