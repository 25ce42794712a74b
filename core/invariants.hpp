#pragma once
// Energy and momenta of a sample, computed from the backend-neutral sample with
// one piece of code for every backend, so both are measured by the same yardstick.
#include "core/run.hpp"

namespace gacompare::core {

// Fills kinetic, potential, linear_momentum and angular_momentum of `s` from its
// particles (rigid bodies join with issue #5). Potential energy comes from the
// conservative effects the scene lists: gravity −m g·x, attraction to a point
// −D m / √(r² + ε²), attraction between particles −C m_i m_j / √(r² + ε²).
// Drag has none; ideal constraints do no work.
void fill_invariants(const Scene& scene, Sample& s);

}  // namespace gacompare::core
