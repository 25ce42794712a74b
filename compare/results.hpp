#pragma once
// results.json: everything a comparison produced, machine readable.
#include "compare/machine.hpp"
#include "compare/runner.hpp"

#include <nlohmann/json.hpp>

namespace gacompare::compare {

// The issue #2 schema: {"tool", "scene", "machine", "repeats", "runs": [...]}.
nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats);

// Between two samples of the same scene: the largest distance between their
// particle and body positions, and the largest angle (rad) between their body
// orientations, 2 acos |q1·q2|. The divergence measures below and the report's
// divergence figures are built on these.
double position_difference(const core::Sample& a, const core::Sample& b);
double orientation_difference(const core::Sample& a, const core::Sample& b);

// Largest distance between the backends' particle and body positions over all
// samples (0 with fewer than two backends): the divergence between backends.
double max_divergence(const SceneResult& r);
// Largest angle (rad) between the backends' body orientations over all samples.
double max_orientation_divergence(const SceneResult& r);

// max over samples of |E(t) − E(0)|, relative to the largest of |E(0)|, the
// kinetic and the potential energy seen in the run (E(0) alone can be 0): the
// energy drift, or the energy dissipated where drag acts.
double energy_drift(const core::Run& run);

}  // namespace gacompare::compare
