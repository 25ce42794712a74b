#pragma once
// results.json: everything a comparison produced, machine readable.
#include "compare/machine.hpp"
#include "compare/metrics.hpp"  // the divergence and energy measures results.json reports
#include "compare/runner.hpp"

#include <nlohmann/json.hpp>

namespace gacompare::compare {

// The schema: {"tool", "scene", "machine", "repeats", "runs": [...]}.
// "scene" also carries what the replay draws and `diff` needs
// (docs/using-gacompare.md, "results.json"): duration, output_every, check tolerances, the particles'
// names, each body's mesh about its centre of mass, radius and static flag,
// and the constraints.
nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats);

// results.json's "scene" record (a scene with its generators expanded).
nlohmann::ordered_json scene_json(const core::Scene& scene, const core::Model& model);

// The "machine" record of results.json and summary.json: CPU, CPUs, load
// averages at the start and end, compiler, build type and flags, the git
// commit and dirty flag of the build (null when unknown), and the date.
nlohmann::ordered_json machine_json(const MachineInfo& machine);

}  // namespace gacompare::compare
