#pragma once
// `gacompare compare --accuracy E`: time at equal accuracy.
// Equal tolerance is not equal accuracy (the backends' states differ), so for
// each backend this finds the tolerance (adaptive solver) or step (fixed-step
// solver) at which its final error against a reference reaches E, and times
// each backend at its own setting.
//
// Reference: the same scene through the traditional backend with cash_karp45 at
// abs = rel = 1e-14, once per scene. Error: the scene's default measure
// (default_error: orientation in rad for bodies without particles, position in
// m otherwise) at the final sample, the largest over particles and bodies.
// Search: a geometric ladder (tolerances 1e-3 … 1e-13 by decades; steps the
// scene's dt halved up to 16 times) up to the first rung whose error is ≤ E,
// then bisection in log-space between that rung and the one before, keeping the
// loosest setting that reaches E. The settings found are cached in
// DIR/accuracy.json, keyed by the scene's sha256, duration, solver, E and
// measure, so a rerun reuses them.
#include "compare/metrics.hpp"
#include "compare/runner.hpp"
#include "core/model/scene.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace gacompare::compare {

// One evaluated setting of a search.
struct Trial {
  double setting = 0, error = 0;
};

struct SearchResult {
  bool found = false;
  double setting = 0;         // the loosest setting tried whose error is ≤ target (when found)
  double error = 0;           // its error
  std::vector<Trial> trials;  // every setting evaluated, in order
};

// Walks `ladder` (settings from loose to tight) to the first rung with
// error_of(rung) ≤ target, then bisects `bisections` times in log-space between
// it and the rung before (the geometric mean of the two), keeping the loosest
// setting that reaches the target. An error that is NaN counts as too large.
SearchResult search_ladder(const std::vector<double>& ladder, const std::function<double(double)>& error_of,
                           double target, int bisections = 4);

std::vector<double> tolerance_ladder();        // 1e-3, 1e-4, …, 1e-13
std::vector<double> step_ladder(double dt);    // dt, dt/2, …, dt/2^16
inline constexpr double kReferenceTolerance = 1e-14;

// A backend's setting at the target accuracy.
struct AccuracySetting {
  std::string backend;
  core::SolverSpec spec;  // the scene's solver with the tolerance or step found
  double error = 0;       // achieved final error (in the plan's measure)
  std::uint64_t steps = 0;
  int trials = 0;         // simulations the search ran
};

struct AccuracyPlan {
  std::string scene, sha256;
  double duration = 0, target = 0;
  Measure measure = Measure::orientation;
  bool adaptive = true;
  std::vector<AccuracySetting> backends;
  bool reused = false;  // read from the cache, nothing run
};

// The scene as searched and timed: generators expanded and 50 output samples,
// as in `sweep` (an adaptive step never crosses a sample time, so a fine
// sampling would cap every loose tolerance at the same step).
core::Scene accuracy_scene(const core::Scene& scene);

// "" when --accuracy can search this scene, else why not (collisions).
std::string accuracy_refusal(const core::Scene& scene);

// The settings at which each of `backends` (traditional, cga) reaches `target`
// on `scene` (generators expanded here), read from `cache` when it holds this
// search, else searched and stored there. Throws input_error for a scene with
// collisions, a fixed-step scene that halving cannot bring to the target within
// 2^-16 of its dt, or an adaptive one that 1e-13 does not.
AccuracyPlan find_equal_accuracy(const core::Scene& scene, double target, const std::vector<std::string>& backends,
                                 const std::filesystem::path& cache, bool quiet = true);

// Like compare_scene, on accuracy_scene(scene), but each backend runs with its
// plan's solver; the result's scene keeps the solver as written.
SceneResult compare_at_accuracy(const core::Scene& scene, const AccuracyPlan& plan, int repeats,
                                const Progress& progress = {});

// The report section: per backend the setting found, achieved error, steps,
// median time (min–max) and the cga/traditional ratio over paired repeats.
std::string accuracy_section_md(const AccuracyPlan& plan, const SceneResult& result);

// Inserts `section` after the first line (the title) of the markdown file.
void insert_section(const std::filesystem::path& report_md, const std::string& section);

}  // namespace gacompare::compare
