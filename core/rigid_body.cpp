#include "core/rigid_body.hpp"

#include "core/error.hpp"
#include "core/mass_properties.hpp"
#include "core/mesh.hpp"

#include <algorithm>
#include <variant>

namespace gacompare::core {

BodyEffects body_effects(const Scene& scene) {
  BodyEffects fx;
  for (const auto& e : scene.effects) {
    if (auto* g = std::get_if<Gravity>(&e)) fx.has_gravity = true, fx.gravity = g->g;
    if (auto* d = std::get_if<LinearDrag>(&e))
      fx.has_linear_drag = true, fx.linear_k = d->k, fx.linear_k_angular = d->k_angular;
    if (auto* d = std::get_if<QuadraticDrag>(&e))
      fx.has_quadratic_drag = true, fx.quadratic_k = d->k, fx.quadratic_k_angular = d->k_angular;
    if (auto* a = std::get_if<AppliedForces>(&e))
      for (const auto& f : a->forces) {
        const auto it = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const Body& b) { return b.name == f.body; });
        fx.pushes.push_back({static_cast<std::size_t>(it - scene.bodies.begin()), f.point, f.force, f.from, f.until});
      }
  }
  return fx;
}

// Exact polyhedral mass properties of each body's mesh (core/mass_properties.hpp),
// at unit density and then scaled to the body's mass or density. The inertia is
// about the centre of mass, whatever coordinates a hull or OBJ mesh was given in:
// the body's `position` is where that centre of mass is.
std::vector<BodyProperties> body_properties(const Scene& scene) {
  std::vector<BodyProperties> out;
  for (const auto& body : scene.bodies) {
    MassProperties unit;
    try {
      unit = mass_properties(mesh_for(body.shape), 1.0);
    } catch (const Error& e) {
      throw Error(e.kind(), "body '" + body.name + "': " + e.what());
    }
    if (!(unit.volume > 0)) throw input_error("body '" + body.name + "': its shape encloses no volume");
    const double density = body.density ? *body.density : *body.mass / unit.volume;
    out.push_back({density * unit.volume, density * unit.inertia});
  }
  return out;
}

}  // namespace gacompare::core
