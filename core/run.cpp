#include "core/run.hpp"

#include "core/model/sha256.hpp"

#include <bit>
#include <cstdint>

namespace gacompare::core {
namespace {

// A count, or a double's bits, as 8 bytes little-endian whatever the
// machine, so that the hash names the bits and not their layout in memory.
void put(std::string& out, std::uint64_t bits) {
  for (int k = 0; k < 8; ++k, bits >>= 8) out.push_back(static_cast<char>(bits & 0xff));
}
void put(std::string& out, double x) { put(out, std::bit_cast<std::uint64_t>(x)); }
template <class V>
void put_all(std::string& out, const V& v) {
  for (Eigen::Index k = 0; k < v.size(); ++k) put(out, v[k]);
}
// A name with its length first, so that no two lists of names run together alike.
void put(std::string& out, const std::string& name) {
  put(out, static_cast<std::uint64_t>(name.size()));
  out += name;
}

}  // namespace

std::string state_hash(const Run& run) {
  std::string bytes;
  put(bytes, static_cast<std::uint64_t>(run.samples.size()));
  for (const Sample& s : run.samples) {
    put(bytes, s.t);
    put(bytes, static_cast<std::uint64_t>(s.particles.size()));
    for (const ParticleSample& p : s.particles) put_all(bytes, p.position), put_all(bytes, p.velocity);
    put(bytes, static_cast<std::uint64_t>(s.bodies.size()));
    for (const BodySample& b : s.bodies) {
      put_all(bytes, b.position), put_all(bytes, b.orientation);
      put_all(bytes, b.velocity), put_all(bytes, b.angular_velocity);
    }
  }
  put(bytes, run.solver.steps_accepted), put(bytes, run.solver.steps_rejected);
  put(bytes, run.solver.derivative_evaluations), put(bytes, run.solver.min_step), put(bytes, run.solver.max_step);
  put(bytes, static_cast<std::uint64_t>(run.counters.size()));
  for (const auto& [name, value] : run.counters) put(bytes, name), put(bytes, value);
  put(bytes, run.error.value_or(""));
  return sha256_hex(bytes);
}

}  // namespace gacompare::core
