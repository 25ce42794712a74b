#pragma once
// The pga backend as the simulator sees it (core::Backend concept): its
// vector algebra for particles and its rigid bodies, composed by
// core::Simulation. Plane-based geometric algebra, Cl(3,0,1): points, lines
// and planes, motors for the rigid motions (pga/algebra/cl301.hpp).
#include "core/dynamics/simulation.hpp"
#include "core/dynamics/simulator.hpp"
#include "pga/particle.hpp"
#include "pga/bounding_volume.hpp"
#include "pga/narrowphase.hpp"
#include "pga/rigid_body.hpp"

#include <string_view>

namespace gacompare::pga {

// The collision algebra: the narrowphase view of a body and the bounding spheres.
struct Collide {
  using Body = pga::Body;
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
  static constexpr std::string_view name = "pga";
};
static_assert(core::Backend<Backend>);

}  // namespace gacompare::pga

// The simulator over this backend is compiled once, in backend.cpp: every test,
// bench and tool that runs a scene links it instead of instantiating it again.
namespace gacompare::core {
extern template Run simulate<pga::Backend>(const Scene&, std::shared_ptr<const Model>);
extern template Run simulate<pga::Backend>(const Scene&);
}  // namespace gacompare::core
