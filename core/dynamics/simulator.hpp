#pragma once
// The simulator loop, a template over a backend (docs/architecture.md "Data flow"): no
// virtual call sits inside a per-particle or per-vertex loop, so timings compare
// the mathematics, not the dispatch. Each backend packs its own state into a flat
// vector of doubles; the loop integrates it, samples it at the output times and
// measures invariants from the backend-neutral sample.
#include "core/model/generators.hpp"
#include "core/model/model.hpp"
#include "core/dynamics/invariants.hpp"
#include "core/dynamics/ode.hpp"
#include "core/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <concepts>
#include <memory>
#include <span>
#include <sstream>
#include <string>

namespace gacompare::core {

template <class B>
concept Backend = requires(const Scene& scene, std::shared_ptr<const Model> compiled, const typename B::Model& m,
                           double t, std::span<const double> y, std::span<double> out, std::vector<double>& state,
                           Profile& profile, Sample& sample) {
  { B::name } -> std::convertible_to<std::string_view>;
  // The backend's state layout and view of the compiled model, once: only the
  // listed effects get an object. Throws input_error for what it cannot simulate.
  { B::build(scene, compiled) } -> std::same_as<typename B::Model>;
  { B::state_size(m) } -> std::same_as<std::size_t>;
  { B::initial_state(m, out) };
  // For the split solvers: velocity index of each position component, −1 for velocities.
  { B::velocity_of(m) } -> std::same_as<std::vector<int>>;
  { B::derivative(m, t, y, out, profile) };
  // After each accepted step (constraint projection); true when it changed the state.
  { B::after_step(m, state, profile) } -> std::same_as<bool>;
  // What a run changes besides its state vector (the collision stages' state),
  // fresh for each run, and the counters read from the model and it.
  { B::data(m) } -> std::same_as<typename B::Data>;
  { B::counters(m, B::data(m)) } -> std::same_as<std::map<std::string, std::uint64_t>>;
  // The compiled model it was built from, for the invariants.
  { *m.compiled } -> std::convertible_to<const Model&>;
  { B::metrics(m) } -> std::same_as<std::map<std::string, double>>;
  // Fills sample.particles / sample.bodies in world terms.
  { B::observe(m, y, sample) };
  // "" when every component is finite, else what holds the bad value: "particle 'bob'".
  { B::first_nonfinite(m, y) } -> std::same_as<std::string>;
  // The physical error norm of an adaptive step (core/model/scene.hpp ErrorNorm).
  { B::error_ratio(m, scene.solver, y, y, y) } -> std::same_as<double>;
  // A Lie-group method's step of h from (t, y) into out (and the embedded
  // pair's difference into err): core/dynamics/ode.hpp set_group_step.
  { B::group_step(m, scene.solver.method, t, t, y, out, out) };
  // B::advance(model, data, solver, f, t, t_end, y, profile, after): integrates to
  // t_end (with collision handling when the model has it; core/dynamics/simulation.hpp).
};

// "" when every component of y is finite; else "<what> '<name>'" for the first
// non-finite one, where entity k owns components [k·stride, (k+1)·stride).
std::string first_nonfinite(std::span<const double> y, std::size_t stride, const std::vector<std::string>& names,
                            std::string_view what);

// Throws input_error naming the first thing in the scene that no backend can
// simulate yet (and the issue that adds it): never a silent partial simulation.
void check_implemented(const Scene& scene);

// An error from building a backend's model ("bodies 'a' and 'b' overlap at
// t = 0 ...") with the scene file and the JSON path of the first body it
// names in front, as the loader's own errors have them; unchanged when it
// names the file already.
Error located(const Scene& scene, const Error& e);

// The scene's model, compiled once for every run that reads it (both backends,
// Bullet, every repeat and solver setting: it holds no solver or rotation
// choice); an error is located as above.
std::shared_ptr<const Model> compiled_model(const Scene& scene);

// velocity_of for a state of particles [x (3), v (3)] each.
std::vector<int> particle_layout(std::size_t particles);

// The output times: every `every` seconds from 0, and `duration` itself.
std::vector<double> output_times(const Scene& scene);

// The scene's solver with the backend's physical error norm (core/model/scene.hpp
// ErrorNorm) and, for a Lie-group method, its group step (set_group_step_of,
// core/dynamics/ode.hpp). Both refer to `model`, which must outlive the solver.
template <Backend B>
OdeSolver solver_for(const Scene& scene, const typename B::Model& model, std::size_t n) {
  OdeSolver solver(scene.solver, n, B::velocity_of(model));
  solver.set_error_norm([&scene, &model](std::span<const double> y0, std::span<const double> y1,
                                         std::span<const double> err) {
    return B::error_ratio(model, scene.solver, y0, y1, err);
  });
  solver.set_step_budget(scene.limits.max_steps);
  set_group_step_of<B>(solver, model);
  // Component i's owner, by the backend's own naming of a non-finite state
  // (only asked once a run has failed).
  solver.set_describe([&model, n](std::size_t i) {
    std::vector<double> y(n, 0.0);
    y[i] = NAN;
    return B::first_nonfinite(model, y);
  });
  return solver;
}

// Which stage a non-finite state came from, found only once a run has failed
// (no check costs anything while it runs): the failed output interval is
// replayed from the last sample's state with a fresh solver, checking every
// derivative. A finite state whose derivative is not finite is the derivative's
// stage (`forces`, or `forces or constraints` where the scene has constraints:
// both are inside one derivative); finite derivatives and a non-finite state
// are the solver's combination, `integrate`. A scene with collisions names its
// own stages as it goes (core/dynamics/simulation.hpp), so it is not replayed: its
// collider's counters and contact cache would count the interval twice.
template <Backend B>
std::string nonfinite_stage(const Scene& scene, const typename B::Model& model, double t0, double t1,
                            const std::vector<double>& y0) {
  if (scene.find_effect<Collisions>()) return "integrate";
  struct Found {};
  const char* stage = "integrate";
  std::vector<double> y = y0;
  OdeSolver solver = solver_for<B>(scene, model, y.size());
  Profile scratch;
  const auto finite = [](std::span<const double> v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  auto f = [&](double t, std::span<const double> yy, std::span<double> dy) {
    B::derivative(model, t, yy, dy, scratch);
    if (finite(yy) && !finite(dy)) {
      stage = scene.constraints.empty() ? "forces" : "forces or constraints";
      throw Found{};
    }
  };
  auto after = [&](std::vector<double>& yy) { return B::after_step(model, yy, scratch); };
  double t = t0;
  try {
    solver.advance(f, t, t1, y, scratch, after);
  } catch (const Found&) {
  } catch (const Error&) {
  }
  return stage;
}

// Runs a scene with its compiled model (core/model/model.hpp, shared by every
// backend that runs it); generators must have been expanded
// (expand_generators), so that the samples' particles match scene.particles.
template <Backend B>
Run simulate(const Scene& scene, std::shared_ptr<const Model> compiled) {
  Run run;
  run.backend = std::string(B::name);
  check_implemented(scene);
  const auto model = [&] {
    try {
      return B::build(scene, std::move(compiled));
    } catch (const Error& e) {
      throw located(scene, e);
    }
  }();
  std::vector<double> y(B::state_size(model));
  B::initial_state(model, y);
  auto data = B::data(model);
  OdeSolver solver = solver_for<B>(scene, model, y.size());
  auto after = [&](std::vector<double>& yy) { return B::after_step(model, yy, run.profile); };
  auto f = [&](double t, std::span<const double> yy, std::span<double> dy) {
    B::derivative(model, t, yy, dy, run.profile);
  };
  auto record = [&](double t) {
    Sample s;
    s.t = t;
    B::observe(model, y, s);
    fill_invariants(scene, *model.compiled, s);
    run.samples.push_back(std::move(s));
  };

  const auto times = output_times(scene);
  run.samples.reserve(times.size());
  const auto start = std::chrono::steady_clock::now();
  double t = 0;
  record(t);
  std::vector<double> y_last = y;  // the state at the last sample: where a failed interval is replayed from
  for (std::size_t k = 1; k < times.size(); ++k) {
    try {
      B::advance(model, data, solver, f, t, times[k], y, run.profile, after);
    } catch (const Error& e) {
      // Every stop names its time; those that cannot (the constraint solve)
      // get the output interval they stopped in.
      run.error = std::string(e.what());
      if (run.error->find("t=") == std::string::npos) {
        std::ostringstream when;
        when << ", between t=" << times[k - 1] << " and t=" << times[k];
        *run.error += when.str();
      }
      break;
    }
    if (auto bad = B::first_nonfinite(model, y); !bad.empty()) {
      std::ostringstream msg;
      msg << "non-finite state: " << bad << ", stage "
          << nonfinite_stage<B>(scene, model, times[k - 1], times[k], y_last) << ", between t=" << times[k - 1]
          << " and t=" << t;
      run.error = msg.str();
      break;
    }
    record(t);
    y_last = y;
  }
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.solver = solver.stats();
  run.counters = B::counters(model, data);
  run.metrics = B::metrics(model);
  return run;
}
// The same, compiling the scene's model for this run alone.
template <Backend B>
Run simulate(const Scene& scene) {
  return simulate<B>(scene, compiled_model(scene));
}

}  // namespace gacompare::core
