#pragma once
// A backend's whole state: particles (written once over the backend's vector
// algebra, core/dynamics/particle_system.hpp) followed by rigid bodies (in the backend's own
// algebra: traditional/rigid_body.hpp, cga/rigid_body.hpp). This composes the two
// into what the simulator needs (core::Backend); each backend is this template
// with its algebra and its name. Collide supplies the backend's narrowphase view
// of a body (Collide::Body) and its bounding-sphere algebra (Collide::Spheres);
// they are used only when the scene lists the collisions effect.
#include "core/collision/collision_step.hpp"
#include "core/collision/collisions.hpp"
#include "core/dynamics/lie_bodies.hpp"
#include "core/dynamics/particle_system.hpp"
#include "core/dynamics/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

namespace gacompare::core {

template <ParticleVectorOps ParticleOps, RigidBodies Bodies, CollisionAlgebra Collide>
struct Simulation {
  using Particles = ParticleSystem<ParticleOps>;
  using Contacts = Collider<Bodies, typename Collide::Body, typename Collide::Spheres>;
  struct Model {
    typename Particles::Model particles;
    typename Bodies::Model bodies;
    std::shared_ptr<const core::Model> compiled;  // the scene's bodies and effects, shared with every reader
    std::size_t offset = 0;  // where the bodies' state starts
    std::optional<Contacts> collisions;  // only when the scene lists the effect
    std::optional<typename Contacts::State> collisions_start;  // the collision stages' state a run starts from
    double bounding_seconds = 0;         // building the bounding spheres, once
    // Per-effect counters: each listed force effect with the particles and
    // moving bodies (applied forces: the forces) it acts on; every force
    // evaluation evaluates exactly these terms and no others, so
    // `effect_<type>_terms` = evaluations × targets. An effect the scene does
    // not list has no entry and no counter: nothing evaluates it.
    std::vector<std::pair<std::string, std::uint64_t>> effect_targets;
    mutable std::uint64_t force_evaluations = 0;
    // Of those, the sleeping bodies skipped and the applied forces on them
    // (core/collision/sleep.hpp): terms not evaluated.
    mutable std::uint64_t asleep_body_evaluations = 0, asleep_push_evaluations = 0;
  };

  // What a run changes as it goes, beside the state vector: the collision
  // stages' state (counters, persistent broadphase, pair memory, warm starts).
  struct Data {
    std::optional<typename Contacts::State> collisions;
    // The bodies in one block per thread, each integrated through the
    // world's step on one thread (integrate_in_blocks); built on first use.
    std::unique_ptr<BodyBlocks<Bodies>> blocks;
  };
  static Data data(const Model& m) { return Data{m.collisions_start, {}}; }

  static Model build(const Scene& scene, std::shared_ptr<const core::Model> compiled) {
    Model m{Particles::build(scene), {}, std::move(compiled), 0, std::nullopt, std::nullopt, 0, effect_targets(scene)};
    if (!scene.bodies.empty()) require_volumes(scene, *m.compiled);
    m.bodies = Bodies::build(scene, *m.compiled);
    m.offset = Particles::state_size(m.particles);
    if (scene.find_effect<Collisions>()) {
      Profile once;
      typename Contacts::State start;
      m.collisions = Contacts::build(scene, *m.compiled, m.bodies, start, once);
      m.collisions_start = std::move(start);
      m.bounding_seconds = once[Stage::bounding_volumes].seconds;
    }
    return m;
  }

  // The same, compiling the scene's model for this backend alone (tests, benchmarks).
  static Model build(const Scene& scene) { return build(scene, std::make_shared<const core::Model>(compile(scene))); }

  // The terms a force evaluation computes for each listed effect: every
  // particle (pinned ones too: their force is computed, their acceleration
  // zeroed), every moving body (static bodies are skipped), every pair of
  // particles for the mutual attraction, every applied force.
  static std::vector<std::pair<std::string, std::uint64_t>> effect_targets(const Scene& scene) {
    std::uint64_t moving = 0;
    for (const auto& b : scene.bodies) moving += b.is_static ? 0 : 1;
    const std::uint64_t particles = scene.particles.size();
    std::vector<std::pair<std::string, std::uint64_t>> out;
    for (const auto& e : scene.effects) {
      const std::string name(effect_name(e));
      if (std::holds_alternative<Collisions>(e)) continue;  // counted by the collision pipeline
      if (const auto* f = std::get_if<AppliedForces>(&e)) out.emplace_back(name, f->forces.size());
      else if (std::holds_alternative<AttractionBetweenParticles>(e))
        out.emplace_back(name, particles * (particles > 0 ? particles - 1 : 0) / 2);
      else if (std::holds_alternative<AttractionToPoint>(e)) out.emplace_back(name, particles);
      else out.emplace_back(name, particles + moving);  // gravity and the drags act on both
    }
    return out;
  }

  // Integrates from t to t_end: straight through without collisions, else in
  // collision steps: the whole world to the end of the step, then its islands'
  // contacts, time of impact and response (core/collision/collision_step.hpp).
  template <class F, class G>
  static void advance(const Model& m, Data& data, OdeSolver& solver, F& f, double& t, double t_end, std::vector<double>& y,
                      Profile& profile, G& after) {
    if (!m.collisions) return solver.advance(f, t, t_end, y, profile, after);
    const Contacts& c = *m.collisions;
    const auto bodies = [&](std::vector<double>& yy) { return std::span<double>(yy).subspan(m.offset); };
    auto& state = *data.collisions;
    const CollisionStep<Contacts> step(c, m.bodies, state);
    std::vector<double> y0;  // the last accepted state (§2.5.1's double buffer)
    while (t < t_end) {
      const double h = std::min(c.setup.settings.step, t_end - t);
      const double t0 = t, t1 = t_end - (t0 + h) <= 1e-9 * h ? t_end : t0 + h;
      if (!(t1 > t0)) {
        std::ostringstream msg;
        msg << "collisions: no progress at t=" << t0 << ": the step " << h
            << " s is below the resolution of t (stage integrate)";
        throw run_error(msg.str());
      }
      copy_on_threads(std::span<const double>(y), y0);
      step.wake_pushed(t0, t1);
      if (state.sleep.any()) {
        // Sleeping bodies do not move: their derivative is zero and not
        // computed (core/collision/sleep.hpp).
        // The terms skipped, counted once per step rather than per evaluation.
        std::uint64_t pushes_asleep = 0;
        for (const auto& push : m.compiled->effects.pushes) pushes_asleep += state.sleep.is_asleep(push.body);
        auto awake = [&](double tt, std::span<const double> yy, std::span<double> dy) {
          derivative(m, tt, yy, dy, profile, state.sleep.asleep);
          m.asleep_body_evaluations += state.sleep.sleeping;
          m.asleep_push_evaluations += pushes_asleep;
        };
        if (is_lie_group(solver.method())) {
          // A Lie-group method steps through its group step and never calls
          // f: the mask goes to the step for this collision step (it counts
          // the skipped terms alike), then the world's plain step is back.
          set_group_step_of<Simulation>(solver, m, std::span<const char>(state.sleep.asleep),
                                        static_cast<std::uint64_t>(state.sleep.sleeping), pushes_asleep);
          solver.advance(f, t, t1, y, profile, after);
          set_group_step_of<Simulation>(solver, m);
        } else {
          solver.advance(awake, t, t1, y, profile, after);
        }
      } else if (in_blocks(m, solver)) {
        integrate_in_blocks(m, data, solver, t, t1, y, profile);
      } else {
        solver.advance(f, t, t1, y, profile, after);
      }
      ++state.counters.steps;
      fail_if_nonfinite(m, y, "integrate", t);  // before the broadphase sorts on it
      step.resolve(bodies(y), bodies(y0), t0, t1, profile);
      t = t1;
    }
  }
  // Whether the world's step is integrated in blocks of bodies, one block per
  // thread (core/collision/subsystem.hpp BodyBlocks says why that is bit for
  // bit the whole world's step): rigid bodies alone, since a particle's
  // forces may read other particles (pairs, springs, constraints).
  static bool in_blocks(const Model& m, const OdeSolver& solver) {
    return m.offset == 0 && BodyBlocks<Bodies>::wanted(solver.method(), m.bodies.bodies.size());
  }
  static void integrate_in_blocks(const Model& m, Data& data, OdeSolver& solver, double& t, double t1,
                                  std::vector<double>& y, Profile& profile) {
    if (!data.blocks) data.blocks = std::make_unique<BodyBlocks<Bodies>>();
    const std::uint64_t before = solver.stats().derivative_evaluations;
    data.blocks->integrate(m.bodies, Bodies::state_size(m.bodies) / m.bodies.bodies.size(), solver, t, t1, y, profile);
    m.force_evaluations += solver.stats().derivative_evaluations - before;
    t = t1;
  }
  // A collision step names the stage a non-finite state came from (the
  // simulator cannot replay one: the collider's state moves on). One pass over
  // the bodies a step, next to the step limit's and the broadphase's own.
  static void fail_if_nonfinite(const Model& m, const std::vector<double>& y, const char* stage, double t) {
    const std::string bad = first_nonfinite(m, y);
    if (bad.empty()) return;
    std::ostringstream msg;
    msg << "non-finite state: " << bad << ", stage " << stage << ", at t=" << t;
    throw run_error(msg.str());
  }
  // The physical error norm of an adaptive step (core/model/scene.hpp ErrorNorm):
  // particles per component (their numbers are positions and velocities
  // already), each body by its backend.
  static double error_ratio(const Model& m, const SolverSpec& spec, std::span<const double> y,
                            std::span<const double> ynew, std::span<const double> err) {
    double worst = 0;
    for (std::size_t i = 0; i < m.offset; ++i) {
      const double r = std::abs(err[i]) / (spec.abs_tol + spec.rel_tol * std::max(std::abs(y[i]), std::abs(ynew[i])));
      if (std::isnan(r)) return r;
      worst = std::max(worst, r);
    }
    if (m.bodies.bodies.empty()) return worst;
    const double r = Bodies::error_ratio(m.bodies, y.subspan(m.offset), ynew.subspan(m.offset), err.subspan(m.offset),
                                         spec.abs_tol, spec.rel_tol);
    return std::isnan(r) ? r : std::max(worst, r);
  }
  static std::size_t state_size(const Model& m) { return m.offset + Bodies::state_size(m.bodies); }
  static void initial_state(const Model& m, std::span<double> y) {
    Particles::initial_state(m.particles, y.first(m.offset));
    Bodies::initial_state(m.bodies, y.subspan(m.offset));
  }
  // The split (symplectic) solvers need positions and velocities: particles only.
  static std::vector<int> velocity_of(const Model& m) {
    return m.bodies.bodies.empty() ? Particles::velocity_of(m.particles) : std::vector<int>{};
  }
  // `asleep`: empty, or a flag per body; a sleeping body's derivative is
  // zero and not computed (the caller counts the terms it skipped).
  static void derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                         Profile& profile, std::span<const char> asleep = {}) {
    ++m.force_evaluations;
    if (m.offset > 0) Particles::derivative(m.particles, t, y.first(m.offset), dydt.first(m.offset), profile);
    if (!m.bodies.bodies.empty()) {
      ScopedStage timed(profile, Stage::forces);
      Bodies::derivative(m.bodies, t, y.subspan(m.offset), dydt.subspan(m.offset), asleep);
    }
  }
  // A Lie-group method's step (core/dynamics/ode.hpp set_group_step): a state
  // of bodies only (lie_group_refusal keeps particles out), each body by its
  // backend. Its forces are evaluated inside the step, timed as `integrate`.
  // `asleep` as for derivative: the sleeping bodies stay where they are, and
  // their terms (`sleeping` bodies, `pushes_asleep` applied forces, counted
  // once per collision step by the caller) are counted as skipped at each of
  // the step's evaluations.
  static void group_step(const Model& m, SolverMethod method, double t, double h, std::span<const double> y,
                         std::span<double> out, std::span<double> err, std::span<const char> asleep = {},
                         std::uint64_t sleeping = 0, std::uint64_t pushes_asleep = 0) {
    if (m.offset > 0)
      throw input_error("solver.method '" + std::string(to_string(method)) +
                        "' steps rigid bodies on their rotation group and cannot integrate particles");
    const auto stages = static_cast<std::uint64_t>(lie::body_step_stages(group_method(method)));
    m.force_evaluations += stages;
    m.asleep_body_evaluations += stages * sleeping;
    m.asleep_push_evaluations += stages * pushes_asleep;
    Bodies::group_step(m.bodies, method, t, h, y, out, err, asleep);
  }
  static bool after_step(const Model& m, std::vector<double>& y, Profile& profile) {
    const bool projected = Particles::after_step(m.particles, y, profile);
    const bool renormalised = Bodies::renormalise(m.bodies, std::span<double>(y).subspan(m.offset));
    return projected || renormalised;
  }
  static void observe(const Model& m, std::span<const double> y, Sample& s) {
    Particles::observe(m.particles, y.first(m.offset), s);
    Bodies::observe(m.bodies, y.subspan(m.offset), s);
  }
  static std::string first_nonfinite(const Model& m, std::span<const double> y) {
    std::string bad = Particles::first_nonfinite(m.particles, y.first(m.offset));
    if (bad.empty() && !m.bodies.bodies.empty())
      bad = core::first_nonfinite(y.subspan(m.offset), Bodies::state_size(m.bodies) / m.bodies.bodies.size(),
                                  m.bodies.names, "body");
    return bad;
  }
  static std::map<std::string, std::uint64_t> counters(const Model& m, const Data& data) {
    auto out = Particles::counters(m.particles);
    if (data.collisions) data.collisions->counters.add_to(out);
    for (const auto& [name, targets] : m.effect_targets) {
      if (targets == 0) continue;
      // Gravity and the drags act on every moving body, applied forces on theirs: less the sleeping ones.
      const bool per_body = name != "attraction_between_particles" && name != "attraction_to_point";
      const std::uint64_t skipped = name == "applied_forces" ? m.asleep_push_evaluations
                                    : per_body             ? m.asleep_body_evaluations
                                                           : 0;
      out["effect_" + name + "_terms"] += m.force_evaluations * targets - skipped;
    }
    return out;
  }
  static std::map<std::string, double> metrics(const Model& m) {
    auto out = Particles::metrics(m.particles);
    if (m.collisions) out["bounding_volumes_seconds"] = m.bounding_seconds;
    if (!m.bodies.bodies.empty()) out["mass_properties_seconds"] = m.compiled->seconds;
    return out;
  }
};

}  // namespace gacompare::core
