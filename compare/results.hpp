#pragma once
// results.json: everything a comparison produced, machine readable.
#include "compare/machine.hpp"
#include "compare/metrics.hpp"  // the divergence and energy measures results.json reports
#include "compare/runner.hpp"

#include <nlohmann/json.hpp>

namespace gacompare::compare {

// The issue #2 schema: {"tool", "scene", "machine", "repeats", "runs": [...]}.
nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats);

}  // namespace gacompare::compare
