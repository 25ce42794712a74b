#pragma once
// The rigid-body interface every backend supplies (§2.3), declared and
// documented once here as concepts; traditional/rigid_body.hpp and
// cga/rigid_body.hpp implement it in their algebra and say only how. Also the
// backend-neutral part both share (copy_bodies).
#include "core/collision/collision.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/run.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <concepts>
#include <utility>
#include <span>
#include <string>
#include <vector>

namespace gacompare::core {

// The state and its derivative: what the integrator and the sampler need.
// State per body, packed by the backend: position, rotation (matrix,
// quaternion or rotor), linear momentum P, angular momentum L (axial vector or
// bivector).
template <class B>
concept RigidBodyDynamics = requires(const Scene& scene, const Model& compiled, const typename B::Model& m,
                                     std::span<const int> which, std::span<const double> y, std::span<double> out,
                                     double t, Sample& sample) {
  { m.names } -> std::convertible_to<const std::vector<std::string>&>;
  { m.bodies.size() } -> std::convertible_to<std::size_t>;
  // The bodies of the compiled model in the backend's representation, their
  // initial state packed in m.y0.
  { B::build(scene, compiled) } -> std::same_as<typename B::Model>;
  // Bodies `which` (in any order) as a model of their own, in that order
  // (copy_bodies below): an island integrated alone. No initial state.
  { B::subset(m, which) } -> std::same_as<typename B::Model>;
  { B::state_size(m) } -> std::same_as<std::size_t>;
  { B::initial_state(m, out) };
  // ẋ = P/m, Ṗ = F, L̇ = τ = Σ (p − x) × F_p (or ∧), and the rotation's rate;
  // zero, and not computed, for the bodies flagged in a mask of sleeping ones
  // (core/collision/sleep.hpp).
  { B::derivative(m, t, y, out) };
  { B::derivative(m, t, y, out, std::span<const char>{}) };
  // Restores the rotation to a rotation (Gram–Schmidt, or dividing by the
  // norm) where the scene asks for it; true when the state changed.
  { B::renormalise(m, out) } -> std::same_as<bool>;
  // Fills sample.bodies in world terms, and sample.rotation_drift.
  { B::observe(m, y, sample) };
  // How far the stored rotations have drifted from rotations, at most:
  // ‖RᵀR − I‖ (Frobenius), |q q* − 1| or |R R̃ − 1|.
  { B::rotation_drift(m, y) } -> std::same_as<double>;
  // The physical error norm of an adaptive step (core/model/scene.hpp
  // ErrorNorm): per body, |δx|, |δv|, the rotation angle of R⁻¹ δR and |δω|,
  // each over abs + rel·|value| (the angle over abs + rel: a rotation has no
  // size of its own); the worst ratio, NaN when the step is not finite.
  { B::error_ratio(m, y, y, y, t, t) } -> std::same_as<double>;
  // A Lie-group method's step (solver.method rkmk4, rkmk45,
  // crouch_grossman4): each moving body through core::lie::body_step on the
  // backend's own rotation (its RotationGroup), L = R Π read and written at
  // the step's ends; out the state after h, err (rkmk45) the 5th-order state
  // less the embedded 4th-order one, in the stored numbers, for error_ratio;
  // like the derivative, the bodies flagged in a mask of sleeping ones do
  // not move (copied, their err zero).
  { B::group_step(m, SolverMethod{}, t, t, y, out, out) };
  { B::group_step(m, SolverMethod{}, t, t, y, out, out, std::span<const char>{}) };
};

// What the collision stages read of a body at a state: its pose (centre of
// mass and rotation, for the narrowphase), the pose s ∈ [0, 1] of the way
// between two states (the time-of-impact search's interpolated motion,
// §4.3.2: the centre along the line, the rotation the shorter way round), and
// its Motion's speeds, |v| and |ω|: how far a point at distance ρ from the
// centre can move.
template <class B>
concept PosedBodies = requires(const typename B::Model& m, std::span<const double> y, std::size_t b, double s,
                               const typename B::Motion& motion) {
  { B::pose(m, y, b) } -> std::same_as<collision::Pose>;
  { B::interpolated_pose(m, y, y, b, s) } -> std::same_as<collision::Pose>;
  { B::motion(m, y, b) } -> std::same_as<typename B::Motion>;
  { B::speed(motion) } -> std::convertible_to<double>;
  { B::angular_speed(motion) } -> std::convertible_to<double>;
};

// The contact solver's view of a body (core/contact/contact_solver.hpp): its
// Motion in the world frame, read from the state once per response; a row's
// Arm built once per contact, so that the solver's sweeps only take scalar
// products and add; store() writes the accumulated impulses back.
template <class B>
concept ContactBodies = requires(const typename B::Model& m, std::span<double> y, std::size_t b,
                                 typename B::Motion& motion, const typename B::Arm& arm, const Eigen::Vector3d& v,
                                 double j) {
  { B::position(std::as_const(motion)) } -> std::convertible_to<Eigen::Vector3d>;
  // The same body with no velocity and no impulses: the start of a pseudo-velocity solve.
  { B::at_rest(std::as_const(motion)) } -> std::same_as<typename B::Motion>;
  // One body's part of a row along n at p: r × n and I⁻¹(r × n), or r ∧ n and I⁻¹(r ∧ n).
  { B::arm(std::as_const(motion), v, v) } -> std::same_as<typename B::Arm>;
  // Eq. 53's (or eq. 54's) term for one body: 1/M + (r × n)·I⁻¹(r × n).
  { B::inverse_effective_mass(std::as_const(motion), arm) } -> std::same_as<double>;
  // n·ṗ at the row's point (eq. 47: ṗ = v + ω × r).
  { B::normal_velocity(std::as_const(motion), arm, v) } -> std::same_as<double>;
  // An impulse j n at the row's point (eq. 48–49): v += j n/M, ω += j I⁻¹(r × n).
  { B::push(motion, arm, v, j) };
  // Friction: the velocity of the body's point at p; the part of u in the
  // plane with unit normal n; t (in that plane) turned a right angle about n.
  { B::point_velocity(std::as_const(motion), v) } -> std::convertible_to<Eigen::Vector3d>;
  { B::in_plane(v, v) } -> std::convertible_to<Eigen::Vector3d>;
  { B::quarter_turn(v, v) } -> std::convertible_to<Eigen::Vector3d>;
  // P += Σ j n, L += Σ j r × n: the impulses pushed into the motion.
  { B::store(m, y, b, std::as_const(motion)) };
  // P = 0 and L = 0: a body put to sleep (core/collision/sleep.hpp).
  { B::stop(m, y, b) };
  // Positional correction by pseudo-velocities (split impulse): moves body b
  // by the displacement and turns it by the rotation of a Motion that started
  // at rest; P and L are not touched, so no momentum is injected.
  { B::displace(m, y, b, std::as_const(motion)) };
};

// Everything a backend's rigid bodies supply.
template <class B>
concept RigidBodies = RigidBodyDynamics<B> && PosedBodies<B> && ContactBodies<B>;


// Bodies `which` (scene indices, any order) of model `from` into `to`, whose
// settings the backend has already copied: the bodies' entries and names, the
// effects, and the applied forces on those bodies re-indexed (body k of `to` is
// body which[k] of `from`). The model of an island integrated on its own
// (core/collision/collision_step.hpp); both backends' `subset` call it, so the two
// sub-models hold the same bodies in the same order.
template <class Model>
void copy_bodies(const Model& from, std::span<const int> which, Model& to) {
  // On the run's threads: a pile's island copies thousands of bodies at
  // every response.
  to.names.resize(which.size());
  to.bodies.resize(which.size());
  for_each_index(which.size(), [&](std::size_t k) {
    to.names[k] = from.names[static_cast<std::size_t>(which[k])];
    to.bodies[k] = from.bodies[static_cast<std::size_t>(which[k])];
  }, kGrainBody);
  to.effects = from.effects;
  to.effects.pushes.clear();
  for (auto push : from.effects.pushes) {
    // A linear search: `which` need not be ascending (an island lists its
    // moving bodies, then its static ones), and a binary search over it
    // dropped the pushes of moving bodies numbered above a static one.
    const auto it = std::find(which.begin(), which.end(), static_cast<int>(push.body));
    if (it == which.end()) continue;
    push.body = static_cast<std::size_t>(it - which.begin());
    to.effects.pushes.push_back(push);
  }
}

}  // namespace gacompare::core
