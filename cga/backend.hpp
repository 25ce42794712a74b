#pragma once
// The cga backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by core::Simulation.
#include "core/simulation.hpp"
#include "cga/particle.hpp"
#include "cga/rigid_body.hpp"

#include <string_view>

namespace gacompare::cga {

struct Backend : core::Simulation<VectorOps, RigidBodies> {
  static constexpr std::string_view name = "cga";
};

}  // namespace gacompare::cga
