#pragma once
// `gacompare check`: regression checks between backends and against stored
// results. A scene fails when its backends diverge beyond its bound, an
// invariant drifts past a bound the scene states, a run stops early, or a final
// state moves from the stored baseline. Divergence and baseline are measured in
// position, orientation, velocity and angular velocity, each bounded by the
// scene's distance (max_divergence, baseline_tolerance) as check.cpp derives it. Timing against the baseline is reported
// as a ratio and fails only with --max-time-ratio (check_scene): these machines are noisy.
#include "compare/metrics.hpp"
#include "compare/runner.hpp"
#include "compare/stored.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace gacompare::compare {

struct CheckLine {
  std::string scene, backend, what;
  double value = 0, bound = 0;
  enum class Verdict { pass, fail, info } verdict = Verdict::pass;
  std::string note;  // why it failed, or what an info line means
};

// StateObjects (compare/stored.hpp) of a scene.
StateObjects state_objects(const core::Scene& scene, const core::Model& model);

// "No point of a body moves by more than d" as a bound on each measure: the
// position by d; the orientation by d / r (a turn by θ moves a point at r from
// the centre of mass by 2r sin(θ/2) ≤ rθ, r the body's farthest vertex); the
// velocity by d / Δt and the angular velocity by d / (r Δt), Δt the scene's
// output interval: the speed difference that would part the two states by d
// within one interval. Static bodies never move and are left out. add() takes
// pairs of samples; line() is the worst ratio of a difference to its bound
// over every object and pair, and where it was (nothing where no object has
// that measure). Between backends (check), against a baseline (check) and
// between two runs (diff).
class StateBounds {
 public:
  StateBounds(StateObjects objects, double d) : objects_(std::move(objects)), d_(d) {}
  void add(const core::Sample& a, const core::Sample& b);
  std::optional<CheckLine> line(Measure m, const std::string& backend, const std::string& what,
                                const std::string& d_name) const;

 private:
  struct Worst {
    double value = 0, bound = INFINITY, ratio = 0;
    std::string where;
  };
  double allowed(Measure m, double r) const;
  void take(Measure m, double value, double limit, const std::string& who, double t);
  StateObjects objects_;
  double d_;
  std::array<Worst, 4> worst_;
};

// A time ratio, after / before, of the medians, with its 95% interval (bootstrap_unpaired_ratio)
// in the note and "within noise" when it holds 1. Held to `max_ratio` when one
// is given: it fails when the interval lies wholly above it or when there is
// none (`why_none` says why, else "fewer than 2 repeats"); without one it is an
// info line.
CheckLine time_ratio_line(const std::string& scene, const std::string& backend, const std::string& what,
                          std::span<const double> before, std::span<const double> after,
                          std::optional<double> max_ratio, const std::string& why_none = "");

// What --update stores for a scene: its hash, and per backend the final sample
// (particle positions and velocities; body positions, orientations, velocities
// and angular velocities), the median wall time and each repeat's. check_scene also reads the
// first format (a particle as its position alone, bodies without velocities).
nlohmann::ordered_json baseline_json(const SceneResult& r);

// The checks of one scene; `baseline` is the stored baseline (nullopt: none kept).
// Time against the baseline is an info line, unless `max_time_ratio` R is
// given: then it fails when the 95% interval of time / baseline time (median
// wall time per repeat, bootstrap_unpaired_ratio: the baseline's repeats and these
// did not run side by side) lies above R, or when there is no interval (one
// repeat, or a baseline stored without its repeats' times).
std::vector<CheckLine> check_scene(const SceneResult& r, const std::optional<Baseline>& baseline,
                                   std::optional<double> max_time_ratio = std::nullopt);

// DIR/<scene name>.json
std::filesystem::path baseline_path(const std::filesystem::path& dir, const std::string& scene);

// The lines as a markdown table.
std::string check_table(const std::vector<CheckLine>& lines);

}  // namespace gacompare::compare
