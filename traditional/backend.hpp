#pragma once
// The traditional backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by core::Simulation.
#include "core/simulation.hpp"
#include "traditional/particle.hpp"
#include "traditional/rigid_body.hpp"

#include <string_view>

namespace gacompare::traditional {

struct Backend : core::Simulation<VectorOps, RigidBodies> {
  static constexpr std::string_view name = "traditional";
};

}  // namespace gacompare::traditional
