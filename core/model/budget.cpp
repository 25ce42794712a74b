#include "core/model/budget.hpp"

#include "core/dynamics/ode.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace gacompare::core {

namespace {

// A number as given (shortest round trip: 1e-300, 4096, 2.5) and a number
// worked out (three digits: 9.6e+03).
std::string fmt(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : "?";
}
std::string approx(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 3);
  return ec == std::errc() ? std::string(buffer, end) : "?";
}

std::string body_path(std::size_t i, const char* key) { return "/bodies/" + std::to_string(i) + "/" + key; }

template <class T>
std::size_t effect_index(const Scene& s) {
  for (std::size_t k = 0; k < s.effects.size(); ++k)
    if (std::holds_alternative<T>(s.effects[k])) return k;
  return s.effects.size();
}

std::size_t particle_count(const Scene& s) {
  std::size_t n = s.particles.size();
  for (const auto& g : s.generators) {
    if (const auto* net = std::get_if<ParticleNet>(&g)) n += static_cast<std::size_t>(net->rows) * net->cols;
    if (const auto* chain = std::get_if<ParticleChain>(&g)) n += static_cast<std::size_t>(chain->count);
  }
  return n;
}

// How fast body i may go during the run, at most: its speed at t = 0 (and the
// speed of its rim), what gravity gives it falling to the lowest static body
// (energy: v² = 2 |g| h; all the way through the duration when nothing static
// is below it), and the impulse of the forces applied to it.
// The lowest point of any static body along gravity (its height against
// gravity's direction), +inf without gravity or static bodies: once per
// scene, not per body (a per-body search made 100,000 bodies take minutes).
double floor_of(const Scene& s, const std::vector<BodyScale>& scale) {
  double floor = INFINITY;
  const auto* g = s.find_effect<Gravity>();
  if (!g || !(g->g.stableNorm() > 0)) return floor;
  const Vec3 down = g->g.normalized();
  for (std::size_t k = 0; k < s.bodies.size(); ++k)
    if (s.bodies[k].is_static) floor = std::min(floor, -down.dot(s.bodies[k].position) - scale[k].radius);
  return floor;
}

double top_speed(const Scene& s, const std::vector<BodyScale>& scale, std::size_t i, double floor) {
  const Body& b = s.bodies[i];
  double v = b.velocity.stableNorm() + b.angular_velocity.stableNorm() * scale[i].radius;
  if (const auto* g = s.find_effect<Gravity>(); g && g->g.stableNorm() > 0) {
    const Vec3 down = g->g.normalized();
    const double height = -down.dot(b.position) - floor;
    const double free_fall = g->g.stableNorm() * s.duration;
    v += std::isfinite(floor) ? std::min(free_fall, std::sqrt(2 * g->g.stableNorm() * std::max(0.0, height))) : free_fall;
  }
  if (const auto* a = s.find_effect<AppliedForces>())
    for (const auto& f : a->forces)
      if (f.body == b.name)
        v += f.force.stableNorm() / scale[i].mass * std::max(0.0, std::min(f.until, s.duration) - f.from);
  return v;
}

std::optional<Refusal> mass_out_of_range(const std::string& path, double mass) {
  if (mass >= kMinMass && mass <= kMaxMass) return std::nullopt;
  return Refusal{path, "expected a mass in [" + fmt(kMinMass) + ", " + fmt(kMaxMass) +
                           "] kg (an electron to the observable universe), got " + approx(mass) + " kg"};
}

}  // namespace

BodyScale body_scale(const Body& body, const BodyModel& model) {
  BodyScale out;
  out.volume = model.volume;
  out.mass = body.mass ? *body.mass : body.density.value_or(0) * model.volume;
  for (const auto& v : model.mesh->vertices()) out.radius = std::max(out.radius, v.stableNorm());
  out.inradius = std::max(0.0, model.inradius);
  return out;
}

std::optional<Refusal> not_convex(const Scene& s, const Model& model) {
  if (!s.find_effect<Collisions>()) return std::nullopt;
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    if (!model.bodies[i].convex)
      return Refusal{body_path(i, "shape"), "expected a convex body, as the collisions effect needs (§2.4.2), got one that is " +
                                                model.bodies[i].not_convex};
  return std::nullopt;
}

std::optional<Refusal> over_sample_budget(const Scene& s) {
  const Limits& lim = s.limits;
  const double samples = s.duration / s.output_every;
  if (samples > lim.max_samples)
    return Refusal{"/output/every", "expected an interval giving at most " + fmt(lim.max_samples) +
                                        " samples (--max-samples raises it), got duration / every = " + approx(samples)};
  const double particles = static_cast<double>(particle_count(s)), bodies = static_cast<double>(s.bodies.size());
  const double bytes = (std::floor(samples) + 2) * (particles * kBytesPerParticleSample + bodies * kBytesPerBodySample);
  if (bytes > lim.max_memory_mb * 1e6)
    return Refusal{"/output/every", "expected an interval whose samples fit in " + fmt(lim.max_memory_mb) +
                                        " MB (--max-memory raises it), got " + approx(samples) + " samples of " +
                                        fmt(particles) + " particle(s) and " + fmt(bodies) + " body(ies), about " +
                                        approx(bytes / 1e6) + " MB"};
  return std::nullopt;
}

std::optional<Refusal> over_step_budget(const Scene& s, const Model& model) {
  const Limits& lim = s.limits;
  const double samples = s.duration / s.output_every;
  if (!is_adaptive(s.solver.method)) {
    // As OdeSolver::advance: every output interval in equal steps of at most dt.
    const double intervals = std::ceil(samples * (1 - 1e-12));
    const double steps = intervals * std::max(1.0, std::ceil(s.output_every / s.solver.dt * (1 - 1e-12)));
    if (steps > lim.max_steps)
      return Refusal{"/solver/dt", "expected a step giving at most " + fmt(lim.max_steps) +
                                       " steps (--max-steps raises it), got dt = " + fmt(s.solver.dt) + " s: " +
                                       approx(steps) + " steps over " + fmt(s.duration) + " s"};
  }
  const auto* c = s.find_effect<Collisions>();
  if (!c || s.bodies.empty()) return std::nullopt;
  const std::string step_path = "/effects/" + std::to_string(effect_index<Collisions>(s)) + "/step";
  std::vector<BodyScale> scale;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) scale.push_back(body_scale(s.bodies[i], model.bodies[i]));
  std::size_t thinnest = 0, fastest = 0;
  double v = 0;
  const double floor = floor_of(s, scale);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (scale[i].inradius < scale[thinnest].inradius) thinnest = i;
    if (s.bodies[i].is_static) continue;
    if (const double vi = top_speed(s, scale, i, floor); vi > v) v = vi, fastest = i;
  }
  // The collision loop lets no two bodies that may meet close on each other by
  // more than the thinner one's inradius in a step (Collider::crossing in
  // core/collision/collisions.hpp); at worst (two of the thinnest bodies
  // meeting head on, both at the top speed) that is a step of half the
  // smallest inradius at the top speed, the bound on steps below. A body
  // thinner than the penetration tolerance could be passed through before a
  // contact is deep enough to be searched.
  const double inradius = scale[thinnest].inradius;
  if (!(inradius > c->penetration_tolerance))
    return Refusal{body_path(thinnest, "shape"),
                   "expected a body thicker than the collisions' penetration tolerance (" +
                       fmt(c->penetration_tolerance) + " m), got one whose inradius is " + approx(inradius) +
                       " m: a contact may sink that deep, and so pass through it"};
  const double h_tunnel = v > 0 ? 0.5 * inradius / v : INFINITY;
  const double h = std::min(c->step, h_tunnel);
  const double steps = s.duration / h;
  if (steps > lim.max_steps) {
    if (c->step <= h_tunnel)
      return Refusal{step_path, "expected a collision step giving at most " + fmt(lim.max_steps) +
                                    " steps (--max-steps raises it), got step = " + fmt(c->step) + " s: " +
                                    approx(steps) + " steps over " + fmt(s.duration) + " s"};
    return Refusal{body_path(fastest, "velocity"),
                   "expected speeds the collision loop can follow in at most " + fmt(lim.max_steps) +
                       " steps (--max-steps raises it): at worst a step moves a body half the smallest inradius (" +
                       approx(inradius) + " m, body '" + s.bodies[thinnest].name + "'), and body '" +
                       s.bodies[fastest].name + "' may reach " + approx(v) + " m/s, so " + approx(steps) +
                       " steps over " + fmt(s.duration) + " s"};
  }
  return std::nullopt;
}

std::optional<Refusal> physically_absurd(const Scene& s, const Model& model) {
  const std::string c = "299792458 m/s";
  const auto too_fast = [&](double v, const std::string& what) {
    return what + " of " + approx(v) + " m/s, faster than light (" + c + "), where Newtonian mechanics means nothing";
  };
  const auto length = [&](double x, const std::string& what) -> std::optional<std::string> {
    if (x > kMaxLength)
      return "expected " + what + " of at most " + fmt(kMaxLength) + " m (the observable universe's radius is 4.4e26 m), got " + approx(x) + " m";
    return std::nullopt;
  };
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Particle& p = s.particles[i];
    const std::string at = "/particles/" + std::to_string(i);
    if (p.velocity.stableNorm() > kSpeedOfLight) return Refusal{at + "/velocity", "expected a speed below light's, got " + too_fast(p.velocity.stableNorm(), "a speed")};
    if (auto why = length(p.position.stableNorm(), "a distance from the origin")) return Refusal{at + "/position", *why};
    if (auto r = mass_out_of_range(at + "/mass", p.mass)) return r;
  }
  for (std::size_t i = 0; i < s.generators.size(); ++i) {
    const std::string at = "/generators/" + std::to_string(i);
    double mass = 0, reach = 0;  // reach: how far from the origin its last particle is, at most
    if (const auto* net = std::get_if<ParticleNet>(&s.generators[i]))
      mass = net->mass, reach = net->origin.stableNorm() + net->spacing * (net->rows + net->cols);
    if (const auto* chain = std::get_if<ParticleChain>(&s.generators[i]))
      mass = chain->mass, reach = chain->origin.stableNorm() + chain->spacing * chain->count;
    if (auto why = length(reach, "particles at a distance from the origin")) return Refusal{at + "/spacing", *why};
    if (auto r = mass_out_of_range(at + "/mass", mass)) return r;
  }
  const auto* gravity = s.find_effect<Gravity>();
  if (gravity && gravity->g.stableNorm() * s.duration > kSpeedOfLight)
    return Refusal{"/effects/" + std::to_string(effect_index<Gravity>(s)) + "/g",
                   "expected a gravity that keeps a falling body below light's speed over the duration (" +
                       fmt(s.duration) + " s), got |g| = " + approx(gravity->g.stableNorm()) + " m/s^2, " +
                       too_fast(gravity->g.stableNorm() * s.duration, "a speed")};
  std::vector<BodyScale> scale;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    scale.push_back(body_scale(b, model.bodies[i]));
    const BodyScale& sc = scale.back();
    if (sc.radius > kMaxLength || sc.radius < kMinLength)
      return Refusal{body_path(i, "shape"), "expected a body between " + fmt(kMinLength) + " m (a proton) and " +
                                                fmt(kMaxLength) + " m (the observable universe) from its centre to its farthest corner, got " +
                                                approx(sc.radius) + " m"};
    if (auto why = length(b.position.stableNorm(), "a distance from the origin")) return Refusal{body_path(i, "position"), *why};
    if (auto r = mass_out_of_range(body_path(i, b.mass ? "mass" : "density"), sc.mass)) return r;
    if (b.velocity.stableNorm() > kSpeedOfLight)
      return Refusal{body_path(i, "velocity"), "expected a speed below light's, got " + too_fast(b.velocity.stableNorm(), "a speed")};
    if (b.angular_velocity.stableNorm() * sc.radius > kSpeedOfLight)
      return Refusal{body_path(i, "angular_velocity"),
                     "expected a spin whose rim stays below light's speed, got |w| = " + approx(b.angular_velocity.stableNorm()) +
                         " rad/s at a radius of " + approx(sc.radius) + " m, " + too_fast(b.angular_velocity.stableNorm() * sc.radius, "a rim speed")};
  }
  if (const auto* a = s.find_effect<AppliedForces>())
    for (std::size_t k = 0; k < a->forces.size(); ++k) {
      const AppliedForce& f = a->forces[k];
      const auto it = std::find_if(s.bodies.begin(), s.bodies.end(), [&](const Body& b) { return b.name == f.body; });
      const auto i = static_cast<std::size_t>(it - s.bodies.begin());
      if (i >= s.bodies.size()) continue;
      const double dv = f.force.stableNorm() / scale[i].mass * std::max(0.0, std::min(f.until, s.duration) - f.from);
      if (dv > kSpeedOfLight)
        return Refusal{"/effects/" + std::to_string(effect_index<AppliedForces>(s)) + "/forces/" + std::to_string(k) + "/force",
                       "expected a force that keeps body '" + f.body + "' below light's speed while it acts, got |F| = " +
                           approx(f.force.stableNorm()) + " N on " + approx(scale[i].mass) + " kg, " + too_fast(dv, "a speed change")};
    }
  return std::nullopt;
}

}  // namespace gacompare::core
