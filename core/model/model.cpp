#include "core/model/model.hpp"

#include "core/error.hpp"
#include "core/model/budget.hpp"
#include "core/model/mass_properties.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <variant>

namespace gacompare::core {

namespace {

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

// Exact polyhedral mass properties at unit density (core/model/mass_properties.hpp),
// scaled to the body's mass or density; the inertia is about the centre of
// mass, whatever coordinates a hull or OBJ mesh was given in. The mesh is
// then moved so that this centre is the origin.
BodyModel body_model(const Body& body, const Collisions* collisions) {
  BodyModel b;
  auto [shape_mesh, unit] = [&] {
    try {
      Mesh mesh = mesh_for(body.shape);
      const MassProperties props = mass_properties(mesh, 1.0);
      return std::pair{std::move(mesh), props};
    } catch (const Error& e) {
      throw Error(e.kind(), "body '" + body.name + "': " + e.what());
    }
  }();
  const double density = body.density ? *body.density : *body.mass / unit.volume;
  b.volume = unit.volume;
  b.mass = density * unit.volume;
  b.inertia = density * unit.inertia;
  b.moments = b.inertia.diagonal();
  const double off = std::max({std::abs(b.inertia(0, 1)), std::abs(b.inertia(0, 2)), std::abs(b.inertia(1, 2))});
  if (off > 1e-12 * b.inertia.diagonal().cwiseAbs().maxCoeff()) {
    const PrincipalAxes pa = principal_axes(b.inertia);
    b.principal = pa.axes;
    b.moments = pa.moments;
  }
  Mesh mesh = shape_mesh.transformed(Eigen::Matrix3d::Identity(), -unit.centre_of_mass);
  b.inradius = inradius(mesh, Vec3::Zero());
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& v : mesh.vertices()) {
    b.radius = std::max(b.radius, v.norm());
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  b.box_mid = 0.5 * (lo + hi);
  b.box_half = 0.5 * (hi - lo);
  if (collisions) {
    const Convexity c = convexity(mesh);
    b.convex = c.convex;
    b.not_convex = c.reason;
    b.restitution = body.restitution ? *body.restitution : collisions->restitution;
  }
  b.friction = body.friction;
  b.is_static = body.is_static;
  b.mesh = std::make_shared<const Mesh>(std::move(mesh));
  return b;
}

// Bodies of one shape share one Mesh. A scene of many like bodies (the
// scale boxes: three shapes over 10,000 bodies) then reads three meshes, hot
// in the cache, where it read one per body from all over the heap: placing a
// body's shape for the narrowphase spent most of its time waiting on them.
// Shared only when bit for bit the same (Mesh::identical), so no answer
// changes.
class MeshPool {
 public:
  std::shared_ptr<const Mesh> shared(std::shared_ptr<const Mesh> mesh) {
    const auto& v = mesh->vertices();
    const std::size_t key =
        std::hash<std::string_view>{}({reinterpret_cast<const char*>(v.data()), v.size() * sizeof(Vec3)});
    auto& same_key = pool_[key];
    for (const auto& m : same_key)
      if (m->identical(*mesh)) return m;
    same_key.push_back(mesh);
    return mesh;
  }

 private:
  std::unordered_map<std::size_t, std::vector<std::shared_ptr<const Mesh>>> pool_;
};

}  // namespace

Model compile(const Scene& scene) {
  Model m;
  Profile once;
  {
    ScopedStage timed(once, Stage::mass_properties);
    const auto* collisions = scene.find_effect<Collisions>();
    m.effects = body_effects(scene);
    if (const auto* g = scene.find_effect<Gravity>()) m.gravity = g->g.norm();
    if (collisions)
      m.resting_speed = std::sqrt(2 * m.gravity * collisions->penetration_tolerance) + 2 * m.gravity * collisions->step;
    m.min_inradius = INFINITY;
    m.bodies.reserve(scene.bodies.size());
    MeshPool meshes;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      try {
        m.bodies.push_back(body_model(scene.bodies[i], collisions));
      } catch (const Error& e) {
        // A shape that cannot be meshed (a box too thin for its faces to have
        // area) is refused at its JSON path when the scene came from a file.
        if (scene.file.empty() || e.kind() != ErrorKind::input) throw;
        const std::string what = e.what(), prefix = "body '" + scene.bodies[i].name + "': ";
        refuse_at(scene.file, "/bodies/" + std::to_string(i) + "/shape",
                  what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
      }
      m.bodies.back().mesh = meshes.shared(std::move(m.bodies.back().mesh));
      m.min_inradius = std::min(m.min_inradius, m.bodies.back().inradius);
    }
  }
  m.seconds = once[Stage::mass_properties].seconds;
  return m;
}

void require_volumes(const Scene& scene, const Model& model) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    if (!(model.bodies[i].volume > 0))
      throw input_error("body '" + scene.bodies[i].name + "': its shape encloses no volume");
}

namespace {
// The refusals that need the model, in the loader's order: convexity, then
// magnitudes no physics means, then the steps (whose numbers the bounds keep finite).
Compiled checked(Scene scene) {
  auto model = std::make_shared<const Model>(compile(scene));
  std::optional<Refusal> refused = not_convex(scene, *model);
  if (!refused) refused = physically_absurd(scene, *model);
  if (!refused) refused = over_step_budget(scene, *model);
  if (refused) refuse_at(scene.file, refused->path, refused->what);
  return {std::move(scene), std::move(model)};
}
}  // namespace

Compiled parse_compiled(const std::string& text, const std::filesystem::path& file, const Limits& limits) {
  return checked(parse_scene(text, file, limits));
}

Compiled load_compiled(const std::filesystem::path& file, const Limits& limits) {
  return checked(load_scene(file, limits));
}

}  // namespace gacompare::core
