#pragma once
// Runs scenes through the backends: one run, or a comparison with repeats
// interleaved so that the machine's drift hits every backend alike.
#include "core/run.hpp"
#include "core/scene.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace gacompare::compare {

// The backends that can run a scene, in report order.
const std::vector<std::string>& backend_names();

// One simulation through the named backend; the scene's generators must be expanded. Throws input_error for an unknown
// backend or a scene the backend cannot simulate.
core::Run run_backend(const core::Scene& scene, std::string_view backend);

// All repeats of one backend on one scene. The samples kept are the first
// repeat's; every repeat's stage times and wall time are kept for the spread.
struct BackendResult {
  core::Run run;                        // first repeat, with samples
  std::vector<core::Profile> profiles;  // one per repeat
  std::vector<double> wall_seconds;     // one per repeat
  bool deterministic = true;            // every repeat ended in the same final sample
};

struct SceneResult {
  core::Scene scene;  // with its generators expanded: particles match the samples
  std::vector<BackendResult> backends;  // in backend_names() order
};

// Runs every backend `repeats` times, alternating which goes first in each round
// (ABBA…) so neither always runs on a warm or a cold machine.
SceneResult compare_scene(const core::Scene& scene, const std::vector<std::string>& backends, int repeats);

}  // namespace gacompare::compare
