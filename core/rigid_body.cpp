#include "core/rigid_body.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <variant>

namespace gacompare::core {

namespace {
// Mass properties per unit density: volume and the inertia tensor about the centre
// of mass divided by the density. Box: I = m/12 diag(b² + c², a² + c², a² + b²).
struct UnitDensity {
  double volume;
  Eigen::Matrix3d inertia_per_density;
};

UnitDensity unit_density(const Shape& shape, const std::string& body) {
  if (const auto* box = std::get_if<BoxShape>(&shape)) {
    const double a = box->size.x(), b = box->size.y(), c = box->size.z();
    const double v = a * b * c;
    Eigen::Matrix3d i = Eigen::Matrix3d::Zero();
    i.diagonal() << v / 12 * (b * b + c * c), v / 12 * (a * a + c * c), v / 12 * (a * a + b * b);
    return {v, i};
  }
  throw input_error("body '" + body +
                    "': mass properties of this shape come with core/mass_properties (issue #5, in progress); "
                    "only boxes can be simulated for now");
}
}  // namespace

BodyEffects body_effects(const Scene& scene) {
  BodyEffects fx;
  for (const auto& e : scene.effects) {
    if (auto* g = std::get_if<Gravity>(&e)) fx.gravity = g->g;
    if (auto* d = std::get_if<LinearDrag>(&e)) fx.linear_k = d->k, fx.linear_k_angular = d->k_angular;
    if (auto* d = std::get_if<QuadraticDrag>(&e)) fx.quadratic_k = d->k, fx.quadratic_k_angular = d->k_angular;
    if (auto* a = std::get_if<AppliedForces>(&e))
      for (const auto& f : a->forces) {
        const auto it = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const Body& b) { return b.name == f.body; });
        fx.pushes.push_back({static_cast<std::size_t>(it - scene.bodies.begin()), f.point, f.force, f.from, f.until});
      }
  }
  return fx;
}

std::vector<BodyProperties> body_properties(const Scene& scene) {
  std::vector<BodyProperties> out;
  for (const auto& body : scene.bodies) {
    const UnitDensity u = unit_density(body.shape, body.name);
    const double density = body.density ? *body.density : *body.mass / u.volume;
    out.push_back({density * u.volume, density * u.inertia_per_density});
  }
  return out;
}

}  // namespace gacompare::core
