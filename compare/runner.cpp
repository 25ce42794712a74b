#include "compare/runner.hpp"

#include "cga/backend.hpp"
#include "compare/bullet_world.hpp"
#include "core/error.hpp"
#include "core/model/generators.hpp"
#include "core/dynamics/simulator.hpp"
#include "pga/backend.hpp"
#include "traditional/backend.hpp"

#include <algorithm>

namespace gacompare::compare {

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names{std::string(traditional::Backend::name), std::string(cga::Backend::name),
                                              std::string(pga::Backend::name), "bullet"};
  return names;
}

const std::vector<std::string>& known_backends() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v = backend_names();
    v.insert(v.begin() + 1, {std::string(kTraditionalRepresentations[0]), std::string(kTraditionalRepresentations[1])});
    return v;
  }();
  return names;
}

std::string_view representation_twin(const core::Scene& scene) {
  return scene.rigid_body.rotation == core::Rotation::matrix ? kTraditionalRepresentations[1]
                                                              : kTraditionalRepresentations[0];
}

core::Run run_backend(const core::Scene& scene, std::shared_ptr<const core::Model> model, std::string_view backend) {
  for (const std::string_view twin : kTraditionalRepresentations)
    if (backend == twin) {
      // The model does not depend on the representation: only the traditional
      // backend's state layout reads it.
      core::Scene as = scene;
      as.rigid_body.rotation = twin == kTraditionalRepresentations[0] ? core::Rotation::matrix : core::Rotation::quaternion;
      core::Run run = core::simulate<traditional::Backend>(as, std::move(model));
      run.backend = std::string(twin);
      return run;
    }
  if (backend == traditional::Backend::name) return core::simulate<traditional::Backend>(scene, std::move(model));
  if (backend == cga::Backend::name) return core::simulate<cga::Backend>(scene, std::move(model));
  if (backend == pga::Backend::name) return core::simulate<pga::Backend>(scene, std::move(model));
  if (backend == "bullet") return simulate_bullet(scene, *model);  // throws input_error where Bullet cannot run it
  throw input_error("unknown backend '" + std::string(backend) +
                    "' (expected traditional, traditional-matrix, traditional-quaternion, cga, pga or bullet)");
}

core::Run run_backend(const core::Scene& scene, std::string_view backend) {
  return run_backend(scene, core::compiled_model(scene), backend);
}

namespace {
// Bit for bit: every particle's position and velocity and every body's
// position, orientation, velocity and angular velocity (leaving bodies out would
// call every rigid scene "deterministic").
bool same_state(const core::Sample& a, const core::Sample& b) {
  if (a.t != b.t || a.particles.size() != b.particles.size() || a.bodies.size() != b.bodies.size()) return false;
  for (std::size_t i = 0; i < a.particles.size(); ++i)
    if (a.particles[i].position != b.particles[i].position || a.particles[i].velocity != b.particles[i].velocity)
      return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const auto &x = a.bodies[i], &y = b.bodies[i];
    if (x.position != y.position || x.orientation != y.orientation || x.velocity != y.velocity ||
        x.angular_velocity != y.angular_velocity)
      return false;
  }
  return true;
}
}  // namespace

std::vector<std::string> backends_for(const core::Scene& scene, const std::vector<std::string>& requested,
                                      Selection selection, const core::Model* model) {
  const auto unsupported = [&] { return model ? bullet_unsupported(scene, model) : bullet_unsupported(scene); };
  if (selection == Selection::exactly) {
    // Asked for by name: refuse before anything runs, not after the other backends.
    if (std::find(requested.begin(), requested.end(), "bullet") != requested.end())
      if (const std::string why = unsupported(); !why.empty())
        throw input_error(scene.file.string() + ": bullet: " + why);
    return requested;
  }
  const bool rigid = !scene.bodies.empty() && !scene.find_effect<core::Collisions>();
  const std::string twin(representation_twin(scene));
  const bool twin_named = std::find(requested.begin(), requested.end(), twin) != requested.end();
  std::vector<std::string> out;
  for (const auto& b : requested) {
    if (b != "bullet" || (scene.find_effect<core::Collisions>() && unsupported().empty())) out.push_back(b);
    if (b == traditional::Backend::name && rigid && !twin_named) out.push_back(twin);
  }
  return out;
}

SceneResult compare_scene(const core::Scene& written, const std::vector<std::string>& requested, int repeats,
                          Selection selection, const Progress& progress) {
  return compare_scene(written, nullptr, requested, repeats, selection, progress);
}

SceneResult compare_scene(const core::Scene& written, std::shared_ptr<const core::Model> model,
                          const std::vector<std::string>& requested, int repeats, Selection selection,
                          const Progress& progress) {
  const core::Scene scene = core::expand_generators(written);
  const std::vector<std::string> backends = backends_for(scene, requested, selection, model.get());
  // Generators add particles only: a model compiled from the written scene is the expanded one's.
  if (!model) model = core::compiled_model(scene);
  SceneResult result{scene, std::vector<BackendResult>(backends.size()), model};
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < backends.size(); ++k) {
      const std::size_t b = (r % 2 == 0) ? k : backends.size() - 1 - k;
      core::Run run = run_backend(scene, model, backends[b]);
      auto& br = result.backends[b];
      br.profiles.push_back(run.profile);
      br.wall_seconds.push_back(run.wall_seconds);
      if (r == 0) {
        br.run = std::move(run);
      } else if (run.samples.empty() || br.run.samples.empty() ||
                 !same_state(run.samples.back(), br.run.samples.back())) {
        br.deterministic = false;
      }
    }
    if (progress) progress(r + 1, repeats, result);
  }
  return result;
}

}  // namespace gacompare::compare
