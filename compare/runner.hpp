#pragma once
// Runs scenes through the backends: one run, or a comparison with repeats
// interleaved so that the machine's drift hits every backend alike.
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/run.hpp"

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace gacompare::compare {

// The backends that can run a scene, in report order: traditional, cga, pga
// and "bullet", the whole-simulation reference (compare/bullet_world.hpp).
const std::vector<std::string>& backend_names();

// The traditional backend in one rotation representation, whatever the scene
// writes: "traditional-matrix" (Ṙ = ω̂ R, 9 numbers) and
// "traditional-quaternion" (q̇ = ½ ω q, 4 numbers). Plain "traditional" runs
// the representation the scene writes (rigid_body.rotation, matrix unless it
// says otherwise). The quaternion is the rotor's algebraic twin, so "cga
// against traditional" on rigid bodies compares the rotor with the matrix;
// the rotor against the quaternion needs the twin run beside it.
inline constexpr std::string_view kTraditionalRepresentations[] = {"traditional-matrix", "traditional-quaternion"};
// The twin of a scene's "traditional": the representation it does not write.
std::string_view representation_twin(const core::Scene& scene);
// backend_names() and the two representations: what --backend and --backends accept.
const std::vector<std::string>& known_backends();

// How a list of backends is read.
enum class Selection {
  // The list, less bullet on the scenes it does not suit: bullet runs only on
  // scenes that list the collisions effect and that Bullet can simulate
  // (bullet_unsupported() == ""), and is left out silently elsewhere. On a
  // rigid-body scene (bodies, no collisions) "traditional" is followed by its
  // representation_twin, so the rotor meets both the matrix and the quaternion
  // with no key in the scene. The CLI's default (compare without --backends)
  // is backend_names() read this way.
  where_supported,
  // The list as given (the CLI's --backends, even naming all three, and run
  // --backend): bullet on a scene Bullet cannot run is an input_error, raised
  // before anything runs.
  exactly,
};

// The backends compare_scene runs for `requested`, read as `selection` says.
// With the scene's compiled model where there is one (bullet_unsupported reads it).
std::vector<std::string> backends_for(const core::Scene& scene, const std::vector<std::string>& requested,
                                      Selection selection = Selection::where_supported,
                                      const core::Model* model = nullptr);

// One simulation through the named backend, reading the scene's compiled
// model; the scene's generators must be expanded. Throws input_error for an
// unknown backend or a scene the backend cannot simulate. Without a model, it
// compiles one for this run.
core::Run run_backend(const core::Scene& scene, std::shared_ptr<const core::Model> model, std::string_view backend);
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
  std::vector<BackendResult> backends;  // in the order of backends_for(scene, requested, selection)
  std::shared_ptr<const core::Model> model;  // compiled once; every backend's run read it
};

// Called after each round of repeats (every backend once), with the round
// (1-based), the number of rounds and the result so far (each backend's
// wall_seconds holds one time per round done): the command line's progress.
using Progress = std::function<void(int round, int rounds, const SceneResult& so_far)>;

// Runs every backend of backends_for(scene, requested, selection) `repeats`
// times, alternating which goes first in each round (ABBA…) so none always runs
// on a warm or a cold machine.
// `model` is the scene's compiled model (core::load_compiled), compiled here when absent.
SceneResult compare_scene(const core::Scene& scene, std::shared_ptr<const core::Model> model,
                          const std::vector<std::string>& requested, int repeats,
                          Selection selection = Selection::where_supported, const Progress& progress = {});
SceneResult compare_scene(const core::Scene& scene, const std::vector<std::string>& requested, int repeats,
                          Selection selection = Selection::where_supported, const Progress& progress = {});

}  // namespace gacompare::compare
