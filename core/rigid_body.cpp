#include "core/rigid_body.hpp"

#include "core/error.hpp"

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
