#include "compare/runner.hpp"

#include "cga/backend.hpp"
#include "core/error.hpp"
#include "core/generators.hpp"
#include "core/simulator.hpp"
#include "traditional/backend.hpp"

#include <algorithm>

namespace gacompare::compare {

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names{std::string(traditional::Backend::name), std::string(cga::Backend::name)};
  return names;
}

core::Run run_backend(const core::Scene& scene, std::string_view backend) {
  if (backend == traditional::Backend::name) return core::simulate<traditional::Backend>(scene);
  if (backend == cga::Backend::name) return core::simulate<cga::Backend>(scene);
  throw input_error("unknown backend '" + std::string(backend) + "' (expected traditional or cga)");
}

namespace {
bool same_state(const core::Sample& a, const core::Sample& b) {
  if (a.t != b.t || a.particles.size() != b.particles.size()) return false;
  for (std::size_t i = 0; i < a.particles.size(); ++i)
    if (a.particles[i].position != b.particles[i].position || a.particles[i].velocity != b.particles[i].velocity)
      return false;
  return true;
}
}  // namespace

SceneResult compare_scene(const core::Scene& written, const std::vector<std::string>& backends, int repeats) {
  const core::Scene scene = core::expand_generators(written);
  SceneResult result{scene, std::vector<BackendResult>(backends.size())};
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < backends.size(); ++k) {
      const std::size_t b = (r % 2 == 0) ? k : backends.size() - 1 - k;
      core::Run run = run_backend(scene, backends[b]);
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
  }
  return result;
}

}  // namespace gacompare::compare
