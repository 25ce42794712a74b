#include "compare/metrics.hpp"


#include <algorithm>
#include <cmath>

namespace gacompare::compare {

double rotation_angle(const Eigen::Vector4d& q, const Eigen::Vector4d& q2) {
  const Eigen::Vector4d a = q.normalized();
  Eigen::Vector4d b = q2.normalized();
  if (a.dot(b) < 0) b = -b;
  return 4 * std::atan2((a - b).norm(), (a + b).norm());
}

std::string_view measure_name(Measure m) {
  switch (m) {
    case Measure::position: return "position";
    case Measure::orientation: return "orientation";
    case Measure::velocity: return "velocity";
    case Measure::angular_velocity: return "angular_velocity";
  }
  return "";
}

std::string_view measure_unit(Measure m) {
  switch (m) {
    case Measure::position: return "m";
    case Measure::orientation: return "rad";
    case Measure::velocity: return "m/s";
    case Measure::angular_velocity: return "rad/s";
  }
  return "";
}

std::string_view measure_words(Measure m) { return m == Measure::angular_velocity ? "angular velocity" : measure_name(m); }

std::optional<Measure> measure_from_string(std::string_view name) {
  for (const Measure m : kMeasures)
    if (measure_name(m) == name) return m;
  return std::nullopt;
}

std::vector<double> body_radii(const core::Model& model) {
  std::vector<double> out;
  for (const auto& b : model.bodies) out.push_back(b.radius);
  return out;
}

bool body_only(Measure m) { return m == Measure::orientation || m == Measure::angular_velocity; }

double worse(double worst, double x) {
  if (std::isnan(worst) || std::isnan(x)) return NAN;
  return std::max(worst, x);
}

void StateErrors::take(const StateErrors& o) {
  for (const Measure m : kMeasures) (*this)[m] = worse((*this)[m], o[m]);
}

StateErrors particle_difference(const core::ParticleSample& a, const core::ParticleSample& b) {
  StateErrors e;
  e[Measure::position] = (a.position - b.position).norm();
  e[Measure::velocity] = (a.velocity - b.velocity).norm();
  return e;
}

StateErrors body_difference(const core::BodySample& a, const core::BodySample& b) {
  StateErrors e;
  e[Measure::position] = (a.position - b.position).norm();
  e[Measure::orientation] = rotation_angle(a.orientation, b.orientation);
  e[Measure::velocity] = (a.velocity - b.velocity).norm();
  e[Measure::angular_velocity] = (a.angular_velocity - b.angular_velocity).norm();
  return e;
}

StateErrors state_difference(const core::Sample& a, const core::Sample& b) {
  StateErrors e;
  for (std::size_t i = 0; i < std::min(a.particles.size(), b.particles.size()); ++i)
    e.take(particle_difference(a.particles[i], b.particles[i]));
  for (std::size_t i = 0; i < std::min(a.bodies.size(), b.bodies.size()); ++i)
    e.take(body_difference(a.bodies[i], b.bodies[i]));
  return e;
}

double position_difference(const core::Sample& a, const core::Sample& b) {
  return state_difference(a, b)[Measure::position];
}

double orientation_difference(const core::Sample& a, const core::Sample& b) {
  return state_difference(a, b)[Measure::orientation];
}

StateErrors max_state_divergence(const SceneResult& r) {
  StateErrors worst;
  for (std::size_t b = 1; b < r.backends.size(); ++b) {
    if (r.backends[b].run.backend == "bullet") continue;
    const auto& a = r.backends[0].run.samples;
    const auto& c = r.backends[b].run.samples;
    for (std::size_t k = 0; k < std::min(a.size(), c.size()); ++k) worst.take(state_difference(a[k], c[k]));
  }
  return worst;
}

double max_divergence(const SceneResult& r) { return max_state_divergence(r)[Measure::position]; }
double max_orientation_divergence(const SceneResult& r) { return max_state_divergence(r)[Measure::orientation]; }

double energy_scale(const core::Sample& first) {
  const double e0 = first.kinetic + first.potential;
  const double parts = std::abs(first.kinetic) + std::abs(first.potential);
  return std::abs(e0) >= 1e-6 * parts ? std::abs(e0) : parts;
}

double energy_drift(const core::Run& run) {
  if (run.samples.empty()) return 0;
  const double e0 = run.samples.front().kinetic + run.samples.front().potential;
  double worst = 0, seen = 0;
  for (const auto& s : run.samples) {
    worst = worse(worst, std::abs(s.kinetic + s.potential - e0));
    seen = std::max(seen, std::abs(s.kinetic) + std::abs(s.potential));
  }
  // Every energy 0 at t = 0 (a scene whose datum is where it starts, at rest):
  // no scale at t = 0, so the largest |K| + |U| seen; only here can the value
  // not exceed 1.
  const double scale = energy_scale(run.samples.front()) > 0 ? energy_scale(run.samples.front()) : seen;
  return scale > 0 ? worst / scale : worst;
}

}  // namespace gacompare::compare
