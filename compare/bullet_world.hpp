#pragma once
// Bullet as a whole-simulation reference: the scene's rigid bodies in
// a btDiscreteDynamicsWorld (double precision), sampled like the backends' runs,
// so that bounce heights, rest poses, momentum and time per simulated second can
// be set side by side. Bullet is not a solver of our equations: it is a
// velocity-level sequential-impulse engine with its own contact thresholds, and
// bullet_world.cpp lists every setting that makes it differ from §2.5.
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/run.hpp"

#include <string>

namespace gacompare::compare {

// Why a scene cannot run in Bullet ("" when it can): no bodies, particles (or
// generators), constraints, effects other than gravity, collisions and applied
// forces (drag, attractions), or, with collisions, a body that is not convex.
// With the scene's compiled model (convexity read from it; without one, only
// the rest is checked), or compiling one.
std::string bullet_unsupported(const core::Scene& scene, const core::Model* model);
std::string bullet_unsupported(const core::Scene& scene);

// Runs the scene in Bullet and returns a Run like the backends' (run.backend =
// "bullet"), sampled at core::output_times(scene), with fill_invariants from our
// exact mass properties. Throws input_error "FILE: bullet: <reason>" with
// bullet_unsupported()'s reason when it cannot. Does not call
// core::check_implemented: the reference runs whatever Bullet can run.
//
// Not reentrant: while it steps, Bullet's process-wide restitution-combining
// hook points at min(ε_a, ε_b) (restored on return); run one at a time.
// The bodies are the compiled model's: the same centred meshes, masses,
// principal frames and inradii as the backends'; without a model, one is compiled.
core::Run simulate_bullet(const core::Scene& scene, const core::Model& model);
core::Run simulate_bullet(const core::Scene& scene);

}  // namespace gacompare::compare
