#include "core/model/generators.hpp"

#include <algorithm>
#include <string>

namespace gacompare::core {

namespace {
std::string net_name(const std::string& n, int r, int c) {
  return n + "[" + std::to_string(r) + "][" + std::to_string(c) + "]";
}
std::string chain_name(const std::string& n, int i) { return n + "[" + std::to_string(i) + "]"; }

void expand(const ParticleNet& net, std::vector<Particle>& particles, std::vector<Constraint>& constraints) {
  for (int r = 0; r < net.rows; ++r)
    for (int c = 0; c < net.cols; ++c) {
      const bool pinned = std::find(net.pinned.begin(), net.pinned.end(), std::pair{r, c}) != net.pinned.end();
      particles.push_back({net_name(net.name, r, c), net.mass,
                           net.origin + Vec3(c * net.spacing, r * net.spacing, 0), Vec3::Zero(), pinned});
      if (c + 1 < net.cols) constraints.push_back(DistanceBetween{net_name(net.name, r, c), net_name(net.name, r, c + 1), net.spacing});
      if (r + 1 < net.rows) constraints.push_back(DistanceBetween{net_name(net.name, r, c), net_name(net.name, r + 1, c), net.spacing});
    }
}

void expand(const ParticleChain& chain, std::vector<Particle>& particles, std::vector<Constraint>& constraints) {
  const Vec3 step = chain.spacing * chain.direction.normalized();
  for (int i = 0; i < chain.count; ++i) {
    const bool pinned = std::find(chain.pinned.begin(), chain.pinned.end(), i) != chain.pinned.end();
    particles.push_back({chain_name(chain.name, i), chain.mass, chain.origin + i * step, Vec3::Zero(), pinned});
    if (i > 0) constraints.push_back(DistanceBetween{chain_name(chain.name, i - 1), chain_name(chain.name, i), chain.spacing});
  }
}
}  // namespace

Scene expand_generators(const Scene& scene) {
  Scene out = scene;
  out.generators.clear();
  std::vector<Constraint> generated;
  for (const auto& g : scene.generators) std::visit([&](const auto& gen) { expand(gen, out.particles, generated); }, g);
  out.constraints.insert(out.constraints.begin(), generated.begin(), generated.end());
  return out;
}

}  // namespace gacompare::core
