#include "compare/summary.hpp"

#include "compare/results.hpp"

#include "compare/metrics.hpp"

#include <algorithm>
#include <cmath>

namespace gacompare::compare {

namespace {
using core::Stage;
using json = nlohmann::ordered_json;

const BackendResult* find_backend(const SceneResult& r, std::string_view name) {
  for (const auto& b : r.backends)
    if (b.run.backend == name) return &b;
  return nullptr;
}

std::vector<double> seconds_each_repeat(const BackendResult& b, Stage s) {
  std::vector<double> v;
  for (const auto& p : b.profiles) v.push_back(p[s].seconds);
  return v;
}

// What one unit of a stage's work is, and how many each run did (summary.hpp).
void set_work(StageTimes& st, const core::Run& num, const core::Run& den) {
  const auto from_counter = [&](const char* unit, const char* name) {
    st.unit = unit;
    st.numerator_work = num.count(name);
    st.denominator_work = den.count(name);
  };
  switch (st.stage) {
    case Stage::narrowphase: from_counter("narrowphase pair", "narrowphase_pairs"); break;
    case Stage::response: from_counter("impulse", "impulses"); break;
    case Stage::time_of_impact: from_counter("time-of-impact state", "impact_state_evaluations"); break;
    case Stage::integrate:
      st.unit = "solver step";
      st.numerator_work = num.solver.steps_accepted + num.solver.steps_rejected;
      st.denominator_work = den.solver.steps_accepted + den.solver.steps_rejected;
      break;
    default: break;
  }
  if (st.numerator_work == 0 || st.denominator_work == 0) {  // no such counter: the stage's own calls
    st.unit = st.stage == Stage::forces ? "derivative evaluation"
              : st.stage == Stage::broadphase ? "detection"
                                              : "call";
    st.numerator_work = num.profile[st.stage].calls;
    st.denominator_work = den.profile[st.stage].calls;
  }
}

// Keys named by the backends, so cga/traditional reads "traditional_seconds"
// and "cga_seconds" as it always has.
json interval_json(const Aggregate& a, BackendPair p) {
  return {{"ratio", a.ratio.ratio},
          {"ci95", json::array({a.ratio.lo, a.ratio.hi})},
          {"verdict", to_string(a.verdict, p.numerator)},
          {"scenes", a.scenes},
          {"parted_left_out", a.parted},
          {std::string(p.denominator) + "_seconds", a.denominator_seconds},
          {std::string(p.numerator) + "_seconds", a.numerator_seconds}};
}
}  // namespace

bool ran_both(const SceneResult& r, BackendPair p) {
  return find_backend(r, p.numerator) && find_backend(r, p.denominator);
}

std::vector<BackendPair> pairs_present(std::span<const SceneResult> results) {
  std::vector<BackendPair> out;
  for (const BackendPair p : kPairs)
    if (std::any_of(results.begin(), results.end(), [&](const SceneResult& r) { return ran_both(r, p); }))
      out.push_back(p);
  return out;
}

std::vector<std::string_view> backends_of(std::span<const BackendPair> pairs) {
  std::vector<std::string_view> out;
  for (const BackendPair p : pairs)
    for (const std::string_view b : {p.denominator, p.numerator})
      if (std::find(out.begin(), out.end(), b) == out.end()) out.push_back(b);
  const auto& order = known_backends();
  const auto rank = [&](std::string_view b) { return std::find(order.begin(), order.end(), b) - order.begin(); };
  std::stable_sort(out.begin(), out.end(), [&](std::string_view a, std::string_view b) { return rank(a) < rank(b); });
  return out;
}

std::string_view representation(std::string_view backend, const core::Scene& scene) {
  if (backend == "cga") return "rotor";
  if (backend == "pga") return "motor";
  if (backend == kTraditionalRepresentations[0]) return "matrix";
  if (backend == kTraditionalRepresentations[1]) return "quaternion";
  if (backend == "traditional") return scene.rigid_body.rotation == core::Rotation::matrix ? "matrix" : "quaternion";
  return "";
}

StateErrors pair_divergence(const SceneResult& r, BackendPair p) {
  StateErrors worst;
  const BackendResult* num = find_backend(r, p.numerator);
  const BackendResult* den = find_backend(r, p.denominator);
  if (!num || !den) return worst;
  const auto& a = den->run.samples;
  const auto& b = num->run.samples;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) worst.take(state_difference(a[k], b[k]));
  return worst;
}

const char* to_string(Category c) {
  switch (c) {
    case Category::particles: return "particles";
    case Category::rigid_bodies: return "rigid bodies";
    case Category::collisions: return "collisions";
  }
  return "?";
}

Category category_of(const core::Scene& scene) {
  if (scene.find_effect<core::Collisions>()) return Category::collisions;
  return scene.bodies.empty() ? Category::particles : Category::rigid_bodies;
}

Tolerance agreement_tolerance(const core::Scene& scene) {
  Tolerance t{scene.check.max_divergence, "check.max_divergence"};
  if (const auto* c = scene.find_effect<core::Collisions>(); c && c->penetration_tolerance < t.metres)
    t = {c->penetration_tolerance, "penetration tolerance"};
  return t;
}

const char* to_string(Trajectories t) {
  switch (t) {
    case Trajectories::identical: return "identical";
    case Trajectories::agree: return "within tolerance";
    case Trajectories::parted: return "parted (chaotic)";
    case Trajectories::own_settings: return "own settings (equal accuracy)";
    case Trajectories::not_compared: return "not compared";
  }
  return "?";
}

Trajectories classify(double position_divergence, double orientation_divergence, double tolerance_used) {
  if (position_divergence == 0 && orientation_divergence == 0) return Trajectories::identical;
  return tolerance_used <= 1 ? Trajectories::agree : Trajectories::parted;  // a NaN is not agreement
}

double tolerance_used(const SceneResult& r, BackendPair p, double d) {
  const BackendResult* num = find_backend(r, p.numerator);
  const BackendResult* den = find_backend(r, p.denominator);
  if (!num || !den) return 0;
  const std::vector<double> radii = body_radii(*r.model);
  const auto& a = den->run.samples;
  const auto& b = num->run.samples;
  double used = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    for (std::size_t i = 0; i < std::min(a[k].particles.size(), b[k].particles.size()); ++i)
      used = worse(used, particle_difference(a[k].particles[i], b[k].particles[i])[Measure::position] / d);
    for (std::size_t i = 0; i < std::min(a[k].bodies.size(), b[k].bodies.size()); ++i) {
      if (i < r.scene.bodies.size() && r.scene.bodies[i].is_static) continue;
      const StateErrors e = body_difference(a[k].bodies[i], b[k].bodies[i]);
      const double radius = i < radii.size() ? radii[i] : 0;
      used = worse(used, std::max(e[Measure::position], radius * e[Measure::orientation]) / d);
    }
  }
  return used;
}

SceneSummary summarise_scene(const SceneResult& r, BackendPair pair, bool own_settings) {
  SceneSummary s;
  s.pair = pair;
  s.name = r.scene.name;
  s.category = category_of(r.scene);
  s.tolerance = agreement_tolerance(r.scene);
  s.bodies = !r.scene.bodies.empty();
  if (s.bodies) s.numerator_form = representation(pair.numerator, r.scene), s.denominator_form = representation(pair.denominator, r.scene);
  const BackendResult* num = find_backend(r, pair.numerator);
  const BackendResult* den = find_backend(r, pair.denominator);
  s.ran = num && den;
  if (!s.ran) {
    s.not_compared_why = "needs both " + std::string(pair.denominator) + " and " + std::string(pair.numerator);
    return s;
  }
  const StateErrors apart = pair_divergence(r, pair);
  s.divergence = apart[Measure::position];
  s.orientation_divergence = apart[Measure::orientation];
  for (const auto* b : {den, num})
    if (b->run.error) s.not_compared_why = b->run.backend + " stopped early";
  s.tolerance_used = tolerance_used(r, pair, s.tolerance.metres);
  s.numerator_steps = num->run.solver.steps_accepted + num->run.solver.steps_rejected;
  s.denominator_steps = den->run.solver.steps_accepted + den->run.solver.steps_rejected;
  s.trajectories = !s.not_compared_why.empty() ? Trajectories::not_compared
                   : own_settings                ? Trajectories::own_settings
                                                 : classify(s.divergence, s.orientation_divergence, s.tolerance_used);
  for (int k = 0; k < core::kStageCount; ++k) {
    const auto stage = static_cast<Stage>(k);
    if (!den->run.profile.ran(stage) && !num->run.profile.ran(stage)) continue;
    StageTimes st;
    st.stage = stage;
    st.seconds = {seconds_each_repeat(*num, stage), seconds_each_repeat(*den, stage)};
    set_work(st, num->run, den->run);
    s.stages.push_back(std::move(st));
  }
  return s;
}

std::vector<PairSummaries> summarise(std::span<const SceneResult> results, bool own_settings) {
  std::vector<BackendPair> pairs = pairs_present(results);
  if (pairs.empty() || pairs.front() != kPairs[0]) pairs.insert(pairs.begin(), kPairs[0]);
  std::vector<PairSummaries> out;
  for (const BackendPair p : pairs) {
    PairSummaries ps{p, {}};
    for (const auto& r : results) ps.scenes.push_back(summarise_scene(r, p, own_settings));
    out.push_back(std::move(ps));
  }
  return out;
}

PairedRepeats per_unit_of_work(const StageTimes& s) {
  PairedRepeats out = s.seconds;
  if (s.numerator_work == 0 || s.denominator_work == 0) return out;
  const double scale = static_cast<double>(s.denominator_work) / static_cast<double>(s.numerator_work);
  for (auto& x : out.numerator) x *= scale;
  return out;
}

PairedRepeats compared_seconds(const SceneSummary& s, std::optional<core::Stage> stage, bool as_measured) {
  PairedRepeats out;
  if (s.trajectories == Trajectories::not_compared) return out;
  for (const auto& st : s.stages) {
    if (stage && st.stage != *stage) continue;
    const PairedRepeats p = s.trajectories == Trajectories::parted && !as_measured ? per_unit_of_work(st) : st.seconds;
    const std::size_t n = p.pairs();
    out.numerator.resize(std::max(out.numerator.size(), n));
    out.denominator.resize(std::max(out.denominator.size(), n));
    for (std::size_t i = 0; i < n; ++i) out.numerator[i] += p.numerator[i], out.denominator[i] += p.denominator[i];
  }
  return out;
}

namespace {
// bootstrap_ratio, with no interval below kMinRepeatsForInterval repeats.
RatioInterval interval(std::span<const PairedRepeats> data) {
  for (const auto& p : data)
    if (p.pairs() < kMinRepeatsForInterval) return {time_weighted_ratio(data), NAN, NAN};
  return bootstrap_ratio(data);
}
}  // namespace

RatioInterval scene_ratio(const SceneSummary& s, std::optional<core::Stage> stage, bool as_measured) {
  const PairedRepeats data[] = {compared_seconds(s, stage, as_measured)};
  return interval(data);
}

Aggregate aggregate(const std::vector<SceneSummary>& scenes, Category c, std::optional<core::Stage> stage) {
  Aggregate a;
  std::vector<PairedRepeats> data;
  for (const auto& s : scenes) {
    if (s.category != c) continue;
    if (s.trajectories == Trajectories::parted) {
      a.parted += !compared_seconds(s, stage).numerator.empty();
      continue;
    }
    PairedRepeats p = compared_seconds(s, stage);
    const std::size_t n = p.pairs();
    double sc = 0, st = 0;
    for (std::size_t i = 0; i < n; ++i) sc += p.numerator[i], st += p.denominator[i];
    if (n == 0 || st <= 0) continue;
    a.numerator_seconds += sc / static_cast<double>(n);
    a.denominator_seconds += st / static_cast<double>(n);
    ++a.scenes;
    data.push_back(std::move(p));
  }
  a.ratio = interval(data);
  a.verdict = speed_verdict(a.ratio);
  return a;
}

std::vector<std::string> parted_scenes(const std::vector<SceneSummary>& scenes, Category c) {
  std::vector<std::string> out;
  for (const auto& s : scenes)
    if (s.category == c && s.trajectories == Trajectories::parted) out.push_back(s.name);
  return out;
}

namespace {
// One pair's "scenes" and "categories" (summary.hpp).
json pair_json(const PairSummaries& ps) {
  const BackendPair p = ps.pair;
  json scene_list = json::array();
  for (const auto& s : ps.scenes) {
    json j = {{"name", s.name},
              {"category", to_string(s.category)},
              {"evidence", is_evidence(s.category)},
              {"trajectories", to_string(s.trajectories)},
              {"max_position_difference", s.divergence},
              {"tolerance_used", s.tolerance_used},
              {"tolerance", s.tolerance.metres},
              {"tolerance_source", s.tolerance.source}};
    if (s.bodies) {
      j["max_orientation_difference_rad"] = s.orientation_divergence;
      j["rotation"] = {{std::string(p.denominator), std::string(s.denominator_form)},
                       {std::string(p.numerator), std::string(s.numerator_form)}};
    }
    if (s.trajectories == Trajectories::not_compared) {
      j["not_compared"] = s.not_compared_why;
    } else {
      const bool parted = s.trajectories == Trajectories::parted;
      j["compared"] = parted ? "per unit of work" : "whole run";
      const RatioInterval r = scene_ratio(s, std::nullopt);
      j["ratio"] = r.ratio;
      j["ci95"] = json::array({r.lo, r.hi});
      j["verdict"] = to_string(speed_verdict(r), p.numerator);
      j["solver_steps"] = {{std::string(p.denominator), s.denominator_steps}, {std::string(p.numerator), s.numerator_steps}};
      if (parted) {
        const RatioInterval whole = scene_ratio(s, std::nullopt, true);
        j["whole_run_ratio"] = whole.ratio;
        j["whole_run_ci95"] = json::array({whole.lo, whole.hi});
        json work = json::object();
        for (const auto& st : s.stages)
          work[std::string(core::stage_name(st.stage))] = {{"unit", st.unit},
                                                           {std::string(p.denominator), st.denominator_work},
                                                           {std::string(p.numerator), st.numerator_work}};
        j["work"] = work;
      }
    }
    scene_list.push_back(j);
  }
  json categories = json::object();
  for (const Category c : kCategories) {
    const Aggregate overall = aggregate(ps.scenes, c, std::nullopt);
    if (overall.scenes == 0 && overall.parted == 0) continue;
    json names = json::array();
    for (const auto& s : ps.scenes)
      if (s.category == c && s.trajectories != Trajectories::parted) names.push_back(s.name);
    json stages = json::object();
    for (int k = 0; k < core::kStageCount; ++k) {
      const auto stage = static_cast<Stage>(k);
      const Aggregate a = aggregate(ps.scenes, c, stage);
      if (a.scenes > 0) stages[std::string(core::stage_name(stage))] = interval_json(a, p);
    }
    categories[to_string(c)] = {{"evidence", is_evidence(c)},
                                {"scenes", names},
                                {"parted", parted_scenes(ps.scenes, c)},
                                {"overall", interval_json(overall, p)},
                                {"stages", stages}};
  }
  return {{"scenes", scene_list}, {"categories", categories}};
}
}  // namespace

nlohmann::ordered_json summary_json(const std::vector<PairSummaries>& pairs, const MachineInfo& machine,
                                    int repeats, double equal_accuracy) {
  // cga/traditional at the top level, where its readers have always found it.
  json first = pair_json(PairSummaries{kPairs[0], {}});
  json others = json::array();
  for (const auto& ps : pairs) {
    if (ps.pair == kPairs[0]) {
      first = pair_json(ps);
      continue;
    }
    json j = {{"numerator", std::string(ps.pair.numerator)}, {"denominator", std::string(ps.pair.denominator)}};
    j.update(pair_json(ps));
    others.push_back(std::move(j));
  }
  return {{"tool", {{"name", "gacompare"}, {"version", tool_version()}}},
          {"machine", machine_json(machine)},
          {"repeats", repeats},
          {"equal_accuracy", equal_accuracy > 0 ? json(equal_accuracy) : json(nullptr)},
          {"method",
           {{"pairs",
             "\"scenes\" and \"categories\" compare cga with traditional (the rotation as the scene writes it, "
             "the matrix by default); each entry of \"pairs\" another pair that ran (cga/traditional-quaternion "
             "on rigid-body scenes, pga/traditional, pga/cga, ...), the same way"},
            {"ratio",
             "time-weighted numerator/denominator (cga/traditional): the sum over a category's scenes of the mean "
             "numerator seconds per repeat over the sum of the mean denominator seconds, over the scenes whose "
             "trajectories did not part; a parted scene is left out of its category (its backends did different "
             "work), and its own ratio scales each stage's numerator time to the denominator run's work (seconds x "
             "denominator units / numerator units)"},
            {"ci95",
             "95% bootstrap interval over paired repeats, resampled within each scene, numerator repeat i kept with "
             "denominator repeat i; expanded percentile interval (Hesterberg 2015): the k-th smallest and largest "
             "resampled ratio, k = floor(tail x resamples), tail = Phi(-sqrt(n/(n-1)) t(0.975, n-1)) for n repeats"},
            {"resamples", kBootstrapResamples},
            {"seed", kBootstrapSeed},
            {"tail", repeats >= static_cast<int>(kMinRepeatsForInterval) ? json(expanded_tail(repeats)) : json(nullptr)},
            {"min_repeats", kMinRepeatsForInterval},
            {"verdict",
             "\"within noise\" when ci95 contains 1, else the numerator's \"faster\" or \"slower\" (\"cga "
             "faster\")"},
            {"agreement",
             "every position within d and every moving body's orientation within d / r (r the body's radius), as "
             "check bounds them between backends; d the scene's check.max_divergence, and on a collision scene at "
             "most its penetration tolerance; parted otherwise"}}},
          {"scenes", first["scenes"]},
          {"categories", first["categories"]},
          {"pairs", others}};
}

}  // namespace gacompare::compare
