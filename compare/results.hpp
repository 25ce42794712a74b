#pragma once
// results.json: everything a comparison produced, machine readable.
#include "compare/machine.hpp"
#include "compare/runner.hpp"

#include <nlohmann/json.hpp>

namespace gacompare::compare {

// The issue #2 schema: {"tool", "scene", "machine", "repeats", "runs": [...]}.
nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats);

// Largest distance between the backends' particle positions over all samples
// (0 with fewer than two backends): the divergence between backends.
double max_divergence(const SceneResult& r);

// max over samples of |E(t) − E(0)| / max(|E(0)|, tiny): the energy drift.
double energy_drift(const core::Run& run);

}  // namespace gacompare::compare
