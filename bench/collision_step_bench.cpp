// One collision step of a real pile, timed alone: the broadphase, the
// narrowphase and the response of a scene's world after it has run for a
// while, repeated on the same two steps. The scale series times whole runs,
// whose wall time moves by 20 % between identical runs on a shared machine;
// a change to a stage worth a few per cent needs this instead.
//
//   python3 bench/scale/box_scene.py --bodies 10000 --seed 1 --duration 1 --time-of-impact none > box.json
//   build/ci/bench/collision_step_bench --scene box.json [--settle 0.5]
//
// Before timing, the scene runs for --settle simulated seconds (default 0.5:
// the 10,000-body box's pile is forming), then two more collision steps, whose
// states before and after their integration are kept. Each benchmark
// iteration resolves one of the two steps again from its integrated state
// (core/collision/collision_step.hpp CollisionStep::resolve), the two in
// turn, so that the broadphase sees its bodies move by a step's travel. The
// collision state (trees, pair memories, kept contacts, warm starts) carries
// on from one iteration to the next as it does from step to step. The
// world's integration is not timed: it is the same work at every step and
// `gacompare`'s stage table times it.
//
// Comparing two versions of a stage: on a shared machine the same build's
// step time drifts by tens of per cent over minutes, so two builds run one
// after the other compare the drift. Two ways that held: alternate the two
// versions within one process (a switch the stage reads, for the experiment
// only, flipped every other iteration, each version with its own Profile:
// the repetitions' ratios then agree to a per cent or two), or run the two
// builds at once with --benchmark_filter=threads:1, one per core (taskset),
// and again with the cores swapped, since the cores' speeds differ too. A
// third needs no change to the code: alternate the two builds in many short
// runs (six or more each) on a scene restarted near the phase to time
// (bench/scale/restart_scene.py), with a short --settle (0.08 s on the
// 10,000-body pile restarted at 0.9 s: long enough for the kept contacts'
// refusals and waits, which start empty, to reach their steady share), and
// take the median of the paired ratios.
//
// Benchmarks BM_step/<backend>/threads:<n>. Counters, per step: each stage's
// milliseconds (from the run's own stage profile), the milliseconds between
// them (the step's own bookkeeping, which no stage times), and the step's
// work: the narrowphase's pairs (all, and the islands' own), the world's
// pairs decided apart beyond reach and by their remembered axis, the kept
// contacts measured again, the contacts responded to, the push-out's
// detections and the islands.
#include "cga/backend.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"
#include "traditional/backend.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

namespace {

using namespace gacompare;

std::string g_scene;
double g_settle = 0.5;

// A scene's world after `settle` seconds and the two steps that follow it.
template <core::Backend B>
struct Pile {
  core::Scene scene;
  typename B::Model model;
  typename B::Data data;
  std::vector<double> before[2], integrated[2];  // each step's state at its start, and after its integration
  double t0[2] = {0, 0}, t1[2] = {0, 0};

  explicit Pile(core::Scene s) : scene(std::move(s)), model(B::build(scene)), data(B::data(model)) {
    std::vector<double> y(B::state_size(model));
    B::initial_state(model, y);
    core::OdeSolver solver = core::solver_for<B>(scene, model, y.size());
    core::Profile profile;
    auto after = [&](std::vector<double>& yy) { return B::after_step(model, yy, profile); };
    auto f = [&](double t, std::span<const double> yy, std::span<double> dy) { B::derivative(model, t, yy, dy, profile); };
    double t = 0;
    B::advance(model, data, solver, f, t, g_settle, y, profile, after);
    const double h = model.collisions->setup.settings.step;
    for (int k = 0; k < 2; ++k) {
      before[k] = y, t0[k] = t, t1[k] = t + h;
      solver.advance(f, t, t1[k], y, profile, after);  // the world's integration alone
      integrated[k] = y;
      resolve(k, y, profile);
    }
  }

  // Step k's collisions resolved again from its integrated state; y is left
  // holding the result.
  void resolve(int k, std::vector<double>& y, core::Profile& profile) {
    const auto bodies = [&](std::vector<double>& v) { return std::span<double>(v).subspan(model.offset); };
    const core::CollisionStep<typename B::Contacts> step(*model.collisions, model.bodies, *data.collisions);
    step.resolve(bodies(y), std::span<const double>(before[k]).subspan(model.offset), t0[k], t1[k], profile);
  }
};

// Settled on two threads (the run is the same on any number: core/parallel.hpp).
template <core::Backend B>
Pile<B>& pile() {
  static Pile<B> p = [] {
    core::set_threads(2);
    return Pile<B>(core::load_scene(g_scene));
  }();
  return p;
}

template <core::Backend B>
void step(benchmark::State& st, int threads) {
  Pile<B>* settled = nullptr;
  try {
    settled = &pile<B>();
  } catch (const std::exception& e) {  // the run failed while it settled: its reason, no time
    st.SkipWithError(e.what());
    return;
  }
  Pile<B>& p = *settled;
  core::set_threads(threads);
  core::Profile profile;
  std::vector<double> y;
  std::map<std::string, std::uint64_t> before, after;
  p.data.collisions->counters.add_to(before);
  double resolving = 0;  // seconds in resolve(), timed here as the stages are (core/stage.hpp)
  int k = 0;
  for (auto _ : st) {
    st.PauseTiming();
    y = p.integrated[k];
    st.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    p.resolve(k, y, profile);
    resolving += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(y.data());
    k ^= 1;
  }
  const double n = static_cast<double>(st.iterations());
  double staged = 0;
  for (const core::Stage s : {core::Stage::broadphase, core::Stage::narrowphase, core::Stage::time_of_impact,
                              core::Stage::response})
    if (profile.ran(s)) {
      st.counters[std::string(core::stage_name(s)) + "_ms"] = 1e3 * profile[s].seconds / n;
      staged += profile[s].seconds;
    }
  // The step's own work between the stages (islands, their subsystems and
  // bookkeeping, a push-out's own loops): what no stage's timer holds.
  st.counters["between_stages_ms"] = 1e3 * (resolving - staged) / n;
  // What a step does, per step: the pairs tested (all, and those within the
  // islands' own detections: push-outs and steps alone), how the world's were
  // decided, the contacts responded to and the push-out's detections.
  p.data.collisions->counters.add_to(after);
  for (const char* name : {"narrowphase_pairs", "island_narrowphase_pairs", "links_apart", "narrowphase_axes_kept",
                           "narrowphase_contacts_kept", "contacts", "push_out_detections", "islands"})
    st.counters[name] = static_cast<double>(after[name] - before[name]) / n;
  core::set_threads(1);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene" && i + 1 < argc) g_scene = argv[++i];
    else if (a == "--settle" && i + 1 < argc) g_settle = std::atof(argv[++i]);
    else {
      std::fprintf(stderr, "collision_step_bench: unknown argument '%s' (--scene FILE [--settle SECONDS])\n", a.c_str());
      return 2;
    }
  }
  if (g_scene.empty()) {
    std::fprintf(stderr, "collision_step_bench: --scene FILE is required (a scene with the collisions effect)\n");
    return 2;
  }
  if (!(g_settle >= 0)) {
    std::fprintf(stderr, "collision_step_bench: --settle must be a number of seconds, at least 0\n");
    return 2;
  }
  try {
    // Load once here so that a bad file stops the run with its reason
    // before any benchmark starts.
    if (!core::load_scene(g_scene).find_effect<core::Collisions>())
      throw std::runtime_error(g_scene + ": the scene lists no collisions effect");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "collision_step_bench: %s\n", e.what());
    return 2;
  }
  for (const int threads : {1, 2}) {
    benchmark::RegisterBenchmark(("BM_step/traditional/threads:" + std::to_string(threads)).c_str(),
                                 [threads](benchmark::State& st) { step<traditional::Backend>(st, threads); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("BM_step/cga/threads:" + std::to_string(threads)).c_str(),
                                 [threads](benchmark::State& st) { step<cga::Backend>(st, threads); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
