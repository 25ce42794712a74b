#pragma once
// The cga backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by core::Simulation.
#include "core/simulation.hpp"
#include "cga/particle.hpp"
#include "cga/bounding_volume.hpp"
#include "cga/narrowphase.hpp"
#include "cga/rigid_body.hpp"

#include <string_view>

namespace gacompare::cga {

// The collision algebra: the narrowphase view of a body and the bounding spheres.
struct Collide {
  using Body = cga::Body;
  using Spheres = SphereOps;
};

struct Backend : core::Simulation<VectorOps, RigidBodies, Collide> {
  static constexpr std::string_view name = "cga";
};

}  // namespace gacompare::cga
