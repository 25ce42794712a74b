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

  // --- collisions (§2.4–2.5); called only when the scene lists the effect ---
  // The pose the narrowphase places the mesh with (centre of mass, rotation).
  static collision::Pose pose(const Model& m, std::span<const double> y, std::size_t b);
  // Velocity of the world point p carried by body b (eq. 47).
  static Eigen::Vector3d velocity_at(const Model& m, std::span<const double> y, std::size_t b, const Eigen::Vector3d& p);
  // Body b's term of the impulse denominator for an impulse along n at p, so
  // that n·Δṗ = j · inverse_effective_mass (eq. 53 / eq. 54 per backend).
  static double inverse_effective_mass(const Model& m, std::span<const double> y, std::size_t b,
                                       const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // An impulse J applied at world point p (eq. 48–49): P += J, L += r × J / r ∧ J.
  static void apply_impulse(const Model& m, std::span<double> y, std::size_t b, const Eigen::Vector3d& p,
                            const Eigen::Vector3d& impulse);
  // Moves body b's centre of mass by d (positional correction of resting contact).
  static void translate(const Model& m, std::span<double> y, std::size_t b, const Eigen::Vector3d& d);
};

}  // namespace gacompare::traditional
