#pragma once
// The traditional backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by core::Simulation.
#include "core/simulation.hpp"
#include "traditional/particle.hpp"
#include "traditional/bounding_volume.hpp"
#include "traditional/narrowphase.hpp"
#include "traditional/rigid_body.hpp"

#include <string_view>

namespace gacompare::traditional {

// The collision algebra: the narrowphase view of a body and the bounding spheres.
struct Collide {
  using Body = traditional::Body;
  using Spheres = SphereOps;
};

struct Backend : core::Simulation<VectorOps, RigidBodies, Collide> {
  static constexpr std::string_view name = "traditional";
};

}  // namespace gacompare::traditional
