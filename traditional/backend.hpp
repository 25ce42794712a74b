#pragma once
// The traditional backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by core::Simulation.
#include "core/dynamics/simulation.hpp"
#include "core/dynamics/simulator.hpp"
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

// Every seam, checked here: a missing operation is a compile error naming the
// concept and the expression that failed.
static_assert(core::ParticleVectorOps<VectorOps>);
static_assert(core::RigidBodies<RigidBodies>);
static_assert(collision::NarrowphaseAlgebra<NarrowAlgebra>);
static_assert(core::SphereTreeOps<SphereOps>);
static_assert(core::CollisionAlgebra<Collide>);

struct Backend : core::Simulation<VectorOps, RigidBodies, Collide> {
  static constexpr std::string_view name = "traditional";
};
static_assert(core::Backend<Backend>);

}  // namespace gacompare::traditional

// The simulator over this backend is compiled once, in backend.cpp: every test,
// bench and tool that runs a scene links it instead of instantiating it again.
namespace gacompare::core {
extern template Run simulate<traditional::Backend>(const Scene&, std::shared_ptr<const Model>);
extern template Run simulate<traditional::Backend>(const Scene&);
}  // namespace gacompare::core
