#pragma once
// `gacompare check`: regression checks between backends and against stored
// results. A scene fails when its backends diverge beyond its bound, an
// invariant drifts past a bound the scene states, a run stops early, or a final
// state moves from the stored baseline. Divergence and baseline are measured in
// position, orientation, velocity and angular velocity, each bounded by the
// scene's distance (max_divergence, baseline_tolerance) as check.cpp derives it. Timing against the baseline is reported
// as a ratio and never fails: these machines are noisy.
#include "compare/runner.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace gacompare::compare {

struct CheckLine {
  std::string scene, backend, what;
  double value = 0, bound = 0;
  enum class Verdict { pass, fail, info } verdict = Verdict::pass;
  std::string note;  // why it failed, or what an info line means
};

// What --update stores for a scene: its hash, and per backend the final sample
// (particle positions and velocities; body positions, orientations, velocities
// and angular velocities) and the median wall time. check_scene also reads the
// first format (a particle as its position alone, bodies without velocities).
nlohmann::ordered_json baseline_json(const SceneResult& r);

// The checks of one scene; `baseline` is the stored baseline (nullopt: none kept).
std::vector<CheckLine> check_scene(const SceneResult& r, const std::optional<nlohmann::json>& baseline);

// DIR/<scene name>.json
std::filesystem::path baseline_path(const std::filesystem::path& dir, const std::string& scene);

// The lines as a markdown table.
std::string check_table(const std::vector<CheckLine>& lines);

}  // namespace gacompare::compare
