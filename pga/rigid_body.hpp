#pragma once
// Rigid bodies in plane-based GA: the motor state, the momentum line and
// forces as lines (after Dorst & De Keninck, "May the Forque Be with You" and
// "Physical Geometry by Plane-Based Geometric Algebra"). Twin of
// traditional/rigid_body.hpp and cga/rigid_body.hpp: same names, same order.
//
// State per body (14 numbers): the motor M (8: body to world, M = T(x) R) and
// the momentum line Π (6) in the frame at the centre of mass with the world's
// axes: its direction is the linear momentum P, its moment the angular
// momentum L about the centre.
//   Π̇ = Σ F_k: forces are lines, F = X ∨ D (the join of the point of
//        application and the force's direction, moment r × f), and their sum
//        is the wrench: gravity acts on a line through the centre;
//   V = A⁻¹[Π]: the rate line (direction ω, moment v) from the inertia map,
//        which swaps a line's parts: ω = I⁻¹ L (world), v = P/m;
//   Ṁ = −½ V_w M, V_w = T V T̃ the rate about the world origin (moment
//        v + x × ω); computed as −½ M V_b with the body frame's rate R̃ V R.
// The report (§2.3.2) integrates a rotor and a position separately; the motor
// holds both, so one product moves the body. Why the centre's frame and not
// the world origin's for Π: the angular momentum about the origin, L + x × P,
// would lose ε|x||P| to cancellation when L is read back.
//
// Rows of the contact solver are lines too: an impulse j along n at p is the
// line J = (p − x) ∨ n (direction n, moment r × n); a body's response is
// A⁻¹[J]; the Delassus term and the normal velocity are joins of two lines,
// J ∨ A⁻¹[J] = 1/m + (r × n)·I⁻¹(r × n) and V ∨ J = v·n + ω·(r × n) (eq. 53).
#include "core/collision/collision.hpp"
#include "core/dynamics/rigid_body.hpp"
#include "core/model/scene.hpp"
#include "core/run.hpp"

#include "pga/algebra/cl301.hpp"

#include <Eigen/Core>

#include <cmath>
#include <span>
#include <string>
#include <vector>

namespace gacompare::pga {

struct RigidBodies {
  struct Body {
    double inv_mass;               // 0 for a static body
    Eigen::Matrix3d inv_inertia;   // body frame; zero for a static body
    Eigen::Matrix3d inertia;       // body frame
    double mass;
  };
  struct Model {
    core::Renormalise renormalise = core::Renormalise::none;
    std::vector<std::string> names;
    std::vector<Body> bodies;
    std::vector<double> y0;        // the initial state, packed
    core::BodyEffects effects;
    static constexpr std::size_t stride = 14;  // doubles per body
  };

  // core::RigidBodies (core/dynamics/rigid_body.hpp) declares and documents
  // every operation; only how this algebra does each is said here.
  static Model build(const core::Scene& scene, const core::Model& model);
  static Model subset(const Model& m, std::span<const int> which);
  static std::size_t state_size(const Model& m) { return m.stride * m.bodies.size(); }
  static void initial_state(const Model& m, std::span<double> y);
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         std::span<const char> asleep = {});
  // M / √(M M̃), the dual-number square root (cl301.hpp normalised): the rotor's
  // norm and the Study condition both.
  static bool renormalise(const Model& m, std::span<double> y);
  static void observe(const Model& m, std::span<const double> y, core::Sample& s);
  // |R R̃ − 1| of the motor's rotation part.
  static double rotation_drift(const Model& m, std::span<const double> y);
  static double error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                            std::span<const double> err, double abs, double rel);
  // A Lie-group method's step (core/dynamics/rigid_body.hpp) through pga/rotation_group.hpp: the motor turned
  // on the right (its translation kept) and then moved to the new centre.
  static void group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                         std::span<double> out, std::span<double> err, std::span<const char> asleep = {});

  // --- collisions (§2.4–2.5); called only when the scene lists the effect ---
  static collision::Pose pose(const Model& m, std::span<const double> y, std::size_t b);
  // The screw between the two poses: M0 (M̃0 M1)^s, the motor power through
  // log and exp (cl301.hpp). The centre moves on a helix about the screw's
  // axis, not on the straight line the other two backends interpolate: over
  // a step h that turns by θ, the two paths part by at most ≈ d θ/8 (d the
  // centre's distance from the axis); the search's bound on the motion
  // (core/collision/time_of_impact.hpp) holds for either.
  static collision::Pose interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                           std::size_t b, double s);
  struct Motion {
    Vec3 x;
    Line rate{};                     // V: direction ω, moment v (at the centre)
    Eigen::Matrix3d inv_inertia;     // world; zero when static
    double inv_mass = 0;             // zero when static
    Line impulse{};                  // Σ j J
  };
  struct Arm {
    Line row, turn;  // J = r ∨ n and A⁻¹[J]
  };
  static Motion motion(const Model& m, std::span<const double> y, std::size_t b);
  static Eigen::Vector3d position(const Motion& b) { return b.x; }
  static Motion at_rest(const Motion& b) {
    Motion p = b;
    p.rate = {}, p.impulse = {};
    return p;
  }
  static Arm arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
  // J ∨ A⁻¹[J].
  static double inverse_effective_mass(const Motion& b, const Arm& a);
  // V ∨ J.
  static double normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n);
  // V += j A⁻¹[J], the impulse line += j J.
  static void push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j);
  // The velocity of the point X carried by the rate V is the commutator
  // X × V = ½(X V − V X), an ideal point (a direction). A quarter turn of t
  // about n is the same commutator with the unit rate about the line through
  // the origin along n; the in-plane part of u is the projection (D·π)π of its
  // direction onto the plane through the origin with normal n.
  static Eigen::Vector3d point_velocity(const Motion& b, const Eigen::Vector3d& p);
  static Eigen::Vector3d in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u);
  static Eigen::Vector3d quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t);
  static double speed(const Motion& b) { return line_moment(b.rate).norm(); }
  static double angular_speed(const Motion& b) { return line_direction(b.rate).norm(); }
  static void store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion);
  static void stop(const Model& m, std::span<double> y, std::size_t b);
  // The pseudo-motion's rate as a displacement: M ← T(v) exp(−½ Ω_x) M, a turn
  // by |ω| about the line through the centre along ω, then the shift v.
  static void displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo);
};

// In the header: the contact solver's sweeps call these once per row per sweep.
inline double RigidBodies::normal_velocity(const Motion& b, const Arm& a, const Eigen::Vector3d& n) {
  (void)n;
  return join(b.rate, a.row).c[0];
}

inline void RigidBodies::push(Motion& b, const Arm& a, const Eigen::Vector3d& n, double j) {
  (void)n;
  if (b.inv_mass == 0) return;
  b.rate += j * a.turn;
  b.impulse += j * a.row;
}

// X × V, the velocity of the point X (any weight; an ideal point turns only)
// under the rate V: the commutator product, an ideal point.
inline Vec3 velocity_of(const Line& rate, const Point& x) {
  const auto c = product<Product::geometric, Point::blades>(x, rate) - product<Product::geometric, Point::blades>(rate, x);
  return coordinates(cga::widen<Point::blades>(0.5 * c));
}

}  // namespace gacompare::pga
