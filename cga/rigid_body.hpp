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

  static Model build(const core::Scene& scene, const std::vector<core::BodyProperties>& props);
  // Bodies `which` (in any order) of m as a model of their own, in that order
  // (core::copy_bodies): an island integrated alone. No initial state (y0).
  static Model subset(const Model& m, std::span<const int> which);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt);
  // R / √(R R̃) (§2.3.2); true if the scene asks for it (and so the state changed).
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // max over bodies of |R R̃ − 1|: how far the stored rotor has drifted from a rotor.
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
  // the rotation by the rotor power R0 (R̃0 R1)^s (cl3.hpp log and exp), the shorter way round.
  // Not the conformal motor between the two poses (the "general rotor" §4.3.2
  // cites, interpolated along its screw): a free body turns about its centre
  // of mass, which moves on a parabola, so over a step h the straight line is
  // within g h²/8 of the true centre (1.2e-6 m at 1 ms); the screw of a step
  // that moves the centre by d while turning it by θ about a perpendicular
  // axis bows the centre's path off that line by a further ≈ d θ/8, so the
  // motor's path is never the nearer one. The rotation part is the same in both.
  static collision::Pose interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                           std::size_t b, double s);
  // The contact solver's view of a body (core/collisions.hpp): its motion in
  // the world frame, read from the state once per response. The solver's rows
  // are built once per contact (Arm) and its sweeps then only take scalar
  // products and add multivectors; store() writes the accumulated impulses back.
  struct Motion {
    Vector3 x, v;
    Bivector3 w;                     // Ω, the angular velocity bivector
    Eigen::Matrix3d inv_inertia;     // world, on bivector components: B ↦ R I⁻¹(R̃ B R) R̃; zero when static
    double inv_mass = 0;             // zero when static
    Vector3 impulse{};
    Bivector3 angular_impulse{};
  };
  // One body's part of a contact row along n at p: r ∧ n and I⁻¹(r ∧ n).
  struct Arm {
    Bivector3 r_n, turn;
  };
  static Motion motion(const Model& m, std::span<const double> y, std::size_t b);
  static Eigen::Vector3d position(const Motion& b) { return to_eigen(b.x); }
  // The same body with no velocity and no impulses: the start of a pseudo-velocity solve.
  static Motion at_rest(const Motion& b) {
    Motion p = b;
    p.v = {}, p.w = {}, p.impulse = {}, p.angular_impulse = {};
    return p;
  }
  static Arm arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // Eq. 54's term for one body: 1/M + n·(r·I⁻¹(r∧n)) = 1/M − ⟨(r∧n) I⁻¹(r∧n)⟩.
  static double inverse_effective_mass(const Motion& b, const Arm& a);
  // n·ṗ at the row's point: ṗ = v + r⌋Ω, and n⌋(r⌋Ω) = (n∧r)⌋Ω = −⟨(r∧n) Ω⟩.
  static double normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n);
  // An impulse j n at the row's point: v += j n/M, Ω += j I⁻¹(r ∧ n).
  static void push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j);
  // Friction (issue #17): the contact plane's two directions from its bivector
  // P = n I (bivector_of_axial) and left contractions, no cross product.
  // The velocity of the body's point at p: ṗ = v + r⌋Ω.
  static Eigen::Vector3d point_velocity(const Motion& b, const Eigen::Vector3d& p);
  // The part of u in the plane P = n I: (u⌋P)⌋P⁻¹, with P⁻¹ = P̃ (a unit blade).
  static Eigen::Vector3d in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u);
  // t (in P) turned a right angle within P: t⌋P (for n = e3, P = e12, e1 ↦ e2).
  static Eigen::Vector3d quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t);
  // |v| and |Ω| = √(−Ω²): how far a point at distance ρ from the centre can move.
  static double speed(const Motion& b) { return std::sqrt(scalar_product(b.v, b.v)); }
  static double angular_speed(const Motion& b) { return std::sqrt(-scalar_product(b.w, b.w)); }
  // P += Σ j n, L += Σ j r ∧ n: the impulses pushed into the motion.
  static void store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion);
  // Positional correction by pseudo-velocities (split impulse): moves body b by
  // the displacement v and turns it by the bivector angle w (R ← exp(−w/2) R) of
  // a Motion that started at rest; P and L are not touched, so no momentum is
  // injected.
  static void displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo);
};

}  // namespace gacompare::cga
