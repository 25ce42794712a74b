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
#include "core/collision/collision.hpp"
#include "core/dynamics/rigid_body.hpp"
#include "core/run.hpp"
#include "core/model/scene.hpp"

#include "cga/algebra/cl3.hpp"

#include <Eigen/Core>

#include <cmath>
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

  // core::RigidBodies (core/dynamics/rigid_body.hpp) declares and documents
  // every operation; only how this algebra does each is said here.
  static Model build(const core::Scene& scene, const core::Model& model);
  static Model subset(const Model& m, std::span<const int> which);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         std::span<const char> asleep = {});
  // R / √(R R̃) (§2.3.2).
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // |R R̃ − 1|.
  static double rotation_drift(const Model& m, std::span<const double> y);
  static double error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                            std::span<const double> err, double abs, double rel);
  // A Lie-group method's step (core/dynamics/rigid_body.hpp) through cga/rotation_group.hpp: the rotor, exp of
  // a bivector.
  static void group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                         std::span<double> out, std::span<double> err, std::span<const char> asleep = {});

  // --- collisions (§2.4–2.5); called only when the scene lists the effect ---
  static collision::Pose pose(const Model& m, std::span<const double> y, std::size_t b);
  // The rotation by the rotor power R0 (R̃0 R1)^s (cl3.hpp log and exp). Not
  // the conformal motor between the two poses (the "general rotor" §4.3.2
  // cites, interpolated along its screw): a free body turns about its centre
  // of mass, which moves on a parabola, within g h²/8 of the straight line
  // over a step h; the screw bows the centre's path off that line by a
  // further ≈ d θ/8, so the motor's path is never the nearer one.
  static collision::Pose interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                           std::size_t b, double s);
  struct Motion {
    Vector3 x, v;
    Bivector3 w;                     // Ω, the angular velocity bivector
    Eigen::Matrix3d inv_inertia;     // world, on bivector components: B ↦ R I⁻¹(R̃ B R) R̃; zero when static
    double inv_mass = 0;             // zero when static
    Vector3 impulse{};
    Bivector3 angular_impulse{};
  };
  struct Arm {
    Bivector3 r_n, turn;  // r ∧ n and I⁻¹(r ∧ n)
  };
  static Motion motion(const Model& m, std::span<const double> y, std::size_t b);
  static Eigen::Vector3d position(const Motion& b) { return to_eigen(b.x); }
  static Motion at_rest(const Motion& b) {
    Motion p = b;
    p.v = {}, p.w = {}, p.impulse = {}, p.angular_impulse = {};
    return p;
  }
  static Arm arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // Eq. 54: 1/M + n·(r·I⁻¹(r∧n)) = 1/M − ⟨(r∧n) I⁻¹(r∧n)⟩.
  static double inverse_effective_mass(const Motion& b, const Arm& a);
  // ṗ = v + r⌋Ω, and n⌋(r⌋Ω) = (n∧r)⌋Ω = −⟨(r∧n) Ω⟩.
  static double normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n);
  // v += j n/M, Ω += j I⁻¹(r ∧ n).
  static void push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j);
  // ṗ = v + r⌋Ω; with the contact plane's bivector P = n I (a unit blade,
  // P⁻¹ = P̃): the in-plane part (u⌋P)⌋P⁻¹ and the quarter turn t⌋P (for
  // n = e3, P = e12, e1 ↦ e2), no cross product.
  static Eigen::Vector3d point_velocity(const Motion& b, const Eigen::Vector3d& p);
  static Eigen::Vector3d in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u);
  static Eigen::Vector3d quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t);
  // |v| and |Ω| = √(−Ω²).
  static double speed(const Motion& b) { return std::sqrt(scalar_product(b.v, b.v)); }
  static double angular_speed(const Motion& b) { return std::sqrt(-scalar_product(b.w, b.w)); }
  static void store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion);
  static void stop(const Model& m, std::span<double> y, std::size_t b);
  // Turns by the bivector angle w of the pseudo-motion: R ← exp(−w/2) R.
  static void displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo);
};

// In the header: the contact solver's sweeps call these once per row per sweep.
inline double RigidBodies::normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n) {
  return scalar_product(vector3(n), b.v) - scalar_product(a.r_n, b.w);
}

inline void RigidBodies::push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j) {
  if (b.inv_mass == 0) return;
  const Vector3 dj = j * vector3(n);
  b.v += b.inv_mass * dj;
  b.w += j * a.turn;
  b.impulse += dj;
  b.angular_impulse += j * a.r_n;
}

}  // namespace gacompare::cga
