#include "core/dynamics/simulator.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace gacompare::core {

std::string first_nonfinite(std::span<const double> y, std::size_t stride, const std::vector<std::string>& names,
                            std::string_view what) {
  // Every step checks the whole state, almost always finite: x·0 is 0 for a
  // finite x and NaN for any other, so four independent running sums (no
  // branch per value, no chain through one sum) say whether to look further;
  // a block of the state each on the run's threads.
  std::vector<char> bad(blocks_of(y.size(), kGrainCopy), 0);
  for_each_block(y.size(), kGrainCopy, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::array<double, 4> sum{};
    std::size_t k = begin;
    for (; k + 4 <= end; k += 4)
      for (std::size_t i = 0; i < 4; ++i) sum[i] += y[k + i] * 0.0;
    for (; k < end; ++k) sum[0] += y[k] * 0.0;
    bad[b] = !(sum[0] + sum[1] + sum[2] + sum[3] == 0.0);
  });
  if (std::ranges::find(bad, char{1}) == bad.end()) return "";
  for (std::size_t k = 0; k < y.size(); ++k)
    if (!std::isfinite(y[k])) return std::string(what) + " '" + names[k / stride] + "'";
  return "";
}

void check_implemented(const Scene& scene) {
  if (!scene.generators.empty())
    throw std::logic_error("simulate() needs a scene whose generators are expanded (expand_generators)");
  if (!scene.bodies.empty() &&
      (scene.find_effect<AttractionBetweenParticles>() || scene.find_effect<AttractionToPoint>()))
    throw input_error(scene.file.string() +
                      ": attraction effects act on particles; bodies do not feel them yet, so a scene with bodies "
                      "cannot list them");
  if (const auto* a = scene.find_effect<AppliedForces>())
    for (const auto& f : a->forces)
      for (const auto& b : scene.bodies)
        if (b.name == f.body && b.is_static)
          throw input_error(scene.file.string() + ": applied force on static body '" + b.name + "', which cannot move");
  if (scene.find_effect<Collisions>() && scene.bodies.size() < 2)
    throw input_error(scene.file.string() + ": the collisions effect acts between rigid bodies (§2.4), and the scene has " +
                      std::to_string(scene.bodies.size()) + "; particles do not collide");
  if (const std::string why = lie_group_refusal(scene); !why.empty())
    throw input_error(scene.file.string() + ": " + why);
  if (scene.particles.empty() && scene.bodies.empty())
    throw input_error(scene.file.string() + ": the scene has nothing to simulate (no particles, no bodies)");
}

Error located(const Scene& scene, const Error& e) {
  const std::string what = e.what(), file = scene.file.string();
  if (file.empty() || what.rfind(file, 0) == 0) return e;
  std::string where = file + ": ";
  for (const std::string lead : {"body '", "bodies '"})
    if (what.rfind(lead, 0) == 0) {
      const auto end = what.find('\'', lead.size());
      const std::string name = what.substr(lead.size(), end - lead.size());
      for (std::size_t i = 0; i < scene.bodies.size(); ++i)
        if (scene.bodies[i].name == name) {
          where += "/bodies/" + std::to_string(i) + ": ";
          break;
        }
    }
  return Error(e.kind(), where + what);
}

std::shared_ptr<const Model> compiled_model(const Scene& scene) {
  try {
    return std::make_shared<const Model>(compile(scene));
  } catch (const Error& e) {
    throw located(scene, e);
  }
}

std::vector<int> particle_layout(std::size_t particles) {
  std::vector<int> v(6 * particles, -1);
  for (std::size_t i = 0; i < particles; ++i)
    for (int k = 0; k < 3; ++k) v[6 * i + k] = static_cast<int>(6 * i + 3 + k);
  return v;
}

std::vector<double> output_times(const Scene& scene) {
  std::vector<double> times;
  // k·every, not a running sum, so the sample times carry no accumulated rounding.
  const auto n = static_cast<long long>(std::floor(scene.duration / scene.output_every * (1 + 1e-12)));
  for (long long k = 0; k <= n; ++k) times.push_back(std::min(scene.duration, static_cast<double>(k) * scene.output_every));
  if (scene.duration - times.back() > 1e-12 * scene.duration) times.push_back(scene.duration);
  times.back() = std::min(times.back(), scene.duration);
  if (times.size() >= 2 && times.back() == times[times.size() - 2]) times.pop_back();
  return times;
}

}  // namespace gacompare::core
