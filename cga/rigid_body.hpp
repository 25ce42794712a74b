#pragma once
// Rigid bodies with rotors and bivectors in Cl(3,0) (§2.3.2, eq. 35–37). Twin of
// traditional/rigid_body.hpp: same names, same order, only the algebra differs.
//
// State per body: x (3), rotor R (4: 1, e12, e13, e23), P (3), L (3, world
// bivector: e12, e13, e23).
//   ẋ = P/m,  Ṗ = F,  L̇ = τ = Σ (p − x) ∧ F_p,
//   L_body = R̃ L R,  Ω_body = I⁻¹(L_body),  Ω = R Ω_body R̃   (§2.3.2),
//   Ṙ = −½ Ω R   (eq. 35).
// The inertia acts on bivectors: Ω_body = I⁻¹ L_body in the bivector basis, the
// body tensor conjugated by the axial↔bivector map (that is what eq. 37 writes
// out). Rotating L into the body and Ω back costs two sandwiches on 3-component
// bivectors, where the matrix backend forms R I⁻¹ Rᵀ. With R = exp(−Bθ/2) and
// x' = R x R̃, a body spinning at ω about axis a has Ω = a I (= bivector_of_axial(ω a)).
#include "core/collision.hpp"
#include "core/rigid_body.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"

#include "cga/algebra/cl3.hpp"

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

namespace gacompare::cga {

struct RigidBodies {
  struct Body {
    double inv_mass;               // 0 for a static body
    Eigen::Matrix3d inv_inertia;   // body frame, acting on bivector components; zero for a static body
    Eigen::Matrix3d inertia;       // body frame, acting on bivector components
    double mass;
  };
  struct Model {
    core::Renormalise renormalise = core::Renormalise::none;
    std::vector<std::string> names;
    std::vector<Body> bodies;
    std::vector<double> y0;        // the initial state, packed
    core::BodyEffects effects;
    static constexpr std::size_t stride = 13;  // doubles per body
  };

  static Model build(const core::Scene& scene, const std::vector<core::BodyProperties>& props);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt);
  // R / √(R R̃) (§2.3.2); true if the scene asks for it (and so the state changed).
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // max over bodies of |R R̃ − 1|: how far the stored rotor has drifted from a rotor.
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

}  // namespace gacompare::cga
