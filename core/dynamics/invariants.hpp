#pragma once
// Energy and momenta of a sample, computed from the backend-neutral sample with
// one piece of code for every backend, so both are measured by the same yardstick.
#include "core/model/model.hpp"
#include "core/run.hpp"

namespace gacompare::core {

// Fills kinetic, potential, linear_momentum and angular_momentum of `s` from its
// particles and bodies (the bodies' masses and inertias from `model`). A body adds ½ m v² + ½ ω·L,
// P = m v, and x × P + L with L = R I_body Rᵀ ω (R from the sampled orientation).
// Potential energy comes from the conservative effects the scene lists:
// gravity −m g·x (particles and bodies), attraction to a point
// −D m / √(r² + ε²), attraction between particles −C m_i m_j / √(r² + ε²).
// Drag has none; ideal constraints do no work.
void fill_invariants(const Scene& scene, const Model& model, Sample& s);

}  // namespace gacompare::core
