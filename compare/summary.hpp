#pragma once
// The multi-scene summary's numbers (DIR/summary.json, and the verdict of the
// summary report.md/.html): for each pair of backends that ran (cga/traditional,
// pga/traditional, pga/cga), their ratio per category and stage, weighted by
// time, with a bootstrap interval over paired repeats (compare/stats.hpp); each
// scene's agreement against its own tolerance; runs whose trajectories part
// compared per call.
#include "compare/machine.hpp"
#include "compare/metrics.hpp"
#include "compare/runner.hpp"
#include "compare/stats.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gacompare::compare {

// Two backends compared: the numerator's time over the denominator's.
struct BackendPair {
  std::string_view numerator, denominator;
  std::string label() const { return std::string(numerator) + " / " + std::string(denominator); }
  friend bool operator==(const BackendPair&, const BackendPair&) = default;
};
// Every pair reported, in this order: each algebra against traditional (as
// the scene writes its rotation, the matrix unless it says otherwise), each
// algebra against the traditional backend's other representation (the
// quaternion, the rotor's algebraic twin, run beside it on rigid-body scenes:
// compare/runner.hpp), then the two algebras against each other.
// cga/traditional, the first, is the project's question and summary.json's
// top level.
inline constexpr BackendPair kPairs[] = {
    {"cga", "traditional"}, {"cga", "traditional-quaternion"}, {"cga", "traditional-matrix"},
    {"pga", "traditional"}, {"pga", "traditional-quaternion"}, {"pga", "traditional-matrix"},
    {"pga", "cga"}};
// What a backend stores a rotation as on `scene`: "matrix", "quaternion",
// "rotor" or "motor"; "" for bullet.
std::string_view representation(std::string_view backend, const core::Scene& scene);
bool ran_both(const SceneResult& r, BackendPair p);
// The pairs of kPairs both of whose backends ran in one of `results` at least.
std::vector<BackendPair> pairs_present(std::span<const SceneResult> results);
// The backends of `pairs`, each once, in known_backends() order.
std::vector<std::string_view> backends_of(std::span<const BackendPair> pairs);
// Largest state_difference between the pair's samples (0 unless both ran).
StateErrors pair_divergence(const SceneResult& r, BackendPair p);

// particles: scenes with no bodies. Every backend runs the same formulas,
// written once over an algebra policy (a vector of each algebra is a
// 3-vector), with bit-identical trajectories: reported, not counted as evidence either way.
// rigid_bodies: bodies, without the collisions effect. collisions: the effect listed.
enum class Category { particles, rigid_bodies, collisions };
inline constexpr Category kCategories[] = {Category::rigid_bodies, Category::collisions, Category::particles};
const char* to_string(Category c);
Category category_of(const core::Scene& scene);
inline bool is_evidence(Category c) { return c != Category::particles; }

// The largest distance between the backends' positions the summary may call
// agreement: the scene's check.max_divergence, and on a collision scene no more
// than its penetration tolerance (further apart, the backends resolve different
// contacts: a check allowance set wider, like bodies_in_box's 1.3 m "bounded by
// the box", bounds how far they may part, not how well they agree).
struct Tolerance {
  double metres = 0;
  std::string source;  // "check.max_divergence" or "penetration tolerance"
};
Tolerance agreement_tolerance(const core::Scene& scene);

// identical: every sampled position and orientation equal, bit for bit;
// agree ("within tolerance"): every position within the tolerance d and every
// moving body's orientation within d / r (tolerance_used ≤ 1); parted ("parted
// (chaotic)"): further apart (chaos amplifies the backends' different
// rounding, as in bodies_in_box: the runs then do different work, are left
// out of their category's ratios and compared on their own per unit of
// work); not_compared: not both backends of the pair ran to the end;
// own_settings: each backend ran at its own solver setting
// (`compare --accuracy`), so they differ by design, are neither classified
// nor compared per unit of work. NaN (a blown-up run) is parted.
enum class Trajectories { identical, agree, parted, own_settings, not_compared };
const char* to_string(Trajectories t);
Trajectories classify(double position_divergence, double orientation_divergence, double tolerance_used);

// How much of the tolerance d the pair's parting used: the largest over the
// two backends' samples of each particle's |Δx| / d and each moving body's
// max(|Δx|, r θ) / d, θ the angle between the orientations and r the body's
// radius (compare/metrics.hpp): the bounds `check` applies between backends,
// position by d and orientation by d / r. 0 without both backends.
double tolerance_used(const SceneResult& r, BackendPair p, double d);

// One stage of one scene: seconds per repeat of the pair's two backends, and
// what one unit of its work is, counted in each backend's run: "narrowphase pair"
// (counter narrowphase_pairs), "impulse" (impulses), "time-of-impact state"
// (impact_state_evaluations), "solver step" (steps accepted + rejected) for
// integrate, else the stage's own calls (a derivative evaluation for forces, a
// detection for broadphase).
struct StageTimes {
  core::Stage stage{};
  PairedRepeats seconds;
  std::string unit;
  std::uint64_t numerator_work = 0, denominator_work = 0;
};

// One scene as one pair of its backends saw it.
struct SceneSummary {
  BackendPair pair = kPairs[0];
  std::string name;
  Category category{};
  Tolerance tolerance;
  double divergence = 0, orientation_divergence = 0;  // m, rad: between the pair, largest over samples
  double tolerance_used = 0;                          // tolerance_used(r, tolerance.metres)
  bool bodies = false;
  // What each side stores a rotation as (representation()), where the scene has bodies.
  std::string_view numerator_form, denominator_form;
  // Solver steps (accepted and rejected) of each side's first repeat.
  std::uint64_t numerator_steps = 0, denominator_steps = 0;
  Trajectories trajectories = Trajectories::not_compared;
  bool ran = false;  // both backends of the pair ran on the scene (to its end or not)
  std::string not_compared_why;  // set when trajectories == not_compared
  std::vector<StageTimes> stages;  // every stage either backend ran
};
// `own_settings`: the backends ran at different solver settings (`compare --accuracy`).
SceneSummary summarise_scene(const SceneResult& r, BackendPair pair = kPairs[0], bool own_settings = false);

// One pair's summaries, one per scene, in the results' order.
struct PairSummaries {
  BackendPair pair;
  std::vector<SceneSummary> scenes;
};
// cga/traditional always (where a backend is missing its scenes are not
// compared, as summary.json's top level has always said), then each other pair
// of kPairs that ran in one scene at least.
std::vector<PairSummaries> summarise(std::span<const SceneResult> results, bool own_settings = false);

// The numerator's time scaled to the denominator run's work: seconds ×
// denominator_work / numerator_work, i.e. the time per unit of work compared.
// Unscaled when either count is 0.
PairedRepeats per_unit_of_work(const StageTimes& s);
// The times the summary compares for one stage (every stage when `stage` is
// empty, summed per repeat): as measured, or per unit of work where the
// trajectories parted (unless `as_measured`). Empty when the scene is not
// compared or lacks the stage.
PairedRepeats compared_seconds(const SceneSummary& s, std::optional<core::Stage> stage, bool as_measured = false);

// The fewest paired repeats for an interval, and so for a verdict: with 5 the
// expanded interval held the true ratio 91% of the time in the simulation of
// compare/stats.hpp, with 4 87%, with 3 74%; fewer leave the ratio alone.
inline constexpr std::size_t kMinRepeatsForInterval = 5;

// One scene's ratio of compared_seconds with its interval.
RatioInterval scene_ratio(const SceneSummary& s, std::optional<core::Stage> stage, bool as_measured = false);

// One category's ratio at one stage (or all stages), over the compared scenes
// of one pair whose backends followed one trajectory. A parted scene is left
// out and counted: its backends did different work, and no count of work
// makes two piles the same work. Per unit of work, bodies_in_box_unsearched
// read cga / traditional 1.24 at one commit and 0.98 at the next, after a
// change of rounding that moved neither backend's cost per operation; the two
// boxes were nine tenths of the collision scenes' time, so the category's
// verdict turned from "cga slower" to "cga faster" with them. Each parted
// scene keeps its own ratio, per unit of work, in its own row.
struct Aggregate {
  int scenes = 0;
  int parted = 0;  // the category's parted scenes, left out
  // Σ over the scenes in the ratio of the mean seconds per repeat
  double numerator_seconds = 0, denominator_seconds = 0;
  RatioInterval ratio;
  Speed verdict = Speed::unknown;
};
Aggregate aggregate(const std::vector<SceneSummary>& scenes, Category c, std::optional<core::Stage> stage);
// The names of category c's scenes whose backends parted, in order: those
// aggregate leaves out.
std::vector<std::string> parted_scenes(const std::vector<SceneSummary>& scenes, Category c);

// DIR/summary.json: {"tool", "machine", "repeats", "method": {how the ratios
// and intervals are computed}, "scenes": [...], "categories": {name: {"evidence",
// "scenes" (those in the ratio), "parted" (those left out), "overall":
// {"ratio", "ci95", "verdict", "scenes", "parted_left_out",
// "traditional_seconds", "cga_seconds"}, "stages": {...}}}, "pairs": [...]}:
// "scenes" and "categories" are cga/traditional; "pairs" holds each other pair
// of `pairs` as {"numerator", "denominator", "scenes", "categories"}, the same
// shape with the seconds and work keys named by its backends ("pga_seconds").
// `equal_accuracy` > 0: the runs were timed at that accuracy (`compare --accuracy`).
nlohmann::ordered_json summary_json(const std::vector<PairSummaries>& pairs, const MachineInfo& machine, int repeats,
                                    double equal_accuracy = 0);

}  // namespace gacompare::compare
