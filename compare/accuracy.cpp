#include "compare/accuracy.hpp"

#include "compare/machine.hpp"
#include "compare/stats.hpp"
#include "compare/stored.hpp"
#include "compare/sweep.hpp"
#include "core/error.hpp"
#include "core/model/generators.hpp"
#include "core/read_file.hpp"
#include "core/dynamics/ode.hpp"
#include "core/dynamics/simulator.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

namespace gacompare::compare {

namespace {
using json = nlohmann::json;

bool reaches(double error, double target) { return !std::isnan(error) && error <= target; }

double setting_of(const core::SolverSpec& s, bool adaptive) { return adaptive ? s.abs_tol : s.dt; }

core::SolverSpec with_setting(core::SolverSpec s, bool adaptive, double x) {
  if (adaptive) s.abs_tol = s.rel_tol = x;
  else s.dt = x;
  return s;
}

std::string setting_text(bool adaptive, double x) { return (adaptive ? "tol " : "dt ") + format_number("%.3g", x); }

// The final error of `run` against `ref` in `m`; infinite where the run stopped early.
double final_error(const core::Run& run, const core::Run& ref, Measure m) {
  if (run.error || run.samples.empty() || run.samples.size() != ref.samples.size()) return INFINITY;
  return state_difference(run.samples.back(), ref.samples.back())[m];
}

json plan_json(const AccuracyPlan& p) {
  json b = json::object();
  for (const auto& s : p.backends)
    b[s.backend] = {{"setting", setting_of(s.spec, p.adaptive)}, {"error", s.error}, {"steps", s.steps},
                    {"trials", s.trials}};
  return {{"sha256", p.sha256}, {"duration", p.duration}, {"target", p.target},
          {"measure", std::string(measure_name(p.measure))}, {"adaptive", p.adaptive},
          {"reference", "traditional, cash_karp45 at 1e-14"}, {"backends", b}};
}

json read_cache(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(file, ec))) return json::object();
  json j = parse_stored(core::read_file(file, "accuracy cache"), file.string());
  return j.is_object() ? j : json::object();
}

// A cached backend's setting, checked before it is trusted: the setting where
// the search itself can land (a tolerance from 1e-13 to 1e-3, a step from dt /
// 2^16 to dt; 1e-12 relative slack for rounding) and within the step budget,
// its error in [0, target], its steps and trials counts within what a search
// runs. Throws input_error naming the cache and the JSON path otherwise.
AccuracySetting cached_setting(const Field& e, const std::string& backend, const core::Scene& scene, bool adaptive,
                               double target) {
  const double lo = adaptive ? tolerance_ladder().back() : step_ladder(scene.solver.dt).back();
  const double hi = adaptive ? tolerance_ladder().front() : scene.solver.dt;
  const double x = e["setting"].number(lo * (1 - 1e-12), hi * (1 + 1e-12));
  if (!adaptive && scene.duration / x > scene.limits.max_steps)
    e["setting"].fail("a step giving at most " + format_number("%g", scene.limits.max_steps) + " steps");
  return {backend, with_setting(scene.solver, adaptive, x), e["error"].number(0, target),
          e["steps"].whole(0, static_cast<std::uint64_t>(scene.limits.max_steps)),
          static_cast<int>(e["trials"].whole(1, 100))};
}
}  // namespace

SearchResult search_ladder(const std::vector<double>& ladder, const std::function<double(double)>& error_of,
                           double target, int bisections) {
  SearchResult r;
  auto eval = [&](double x) {
    const double e = error_of(x);
    r.trials.push_back({x, e});
    return e;
  };
  std::size_t k = 0;
  for (; k < ladder.size(); ++k) {
    const double e = eval(ladder[k]);
    if (reaches(e, target)) {
      r.found = true, r.setting = ladder[k], r.error = e;
      break;
    }
  }
  if (!r.found || k == 0) return r;
  double loose = ladder[k - 1];  // misses the target
  for (int i = 0; i < bisections; ++i) {
    const double mid = std::sqrt(loose * r.setting);
    const double e = eval(mid);
    if (reaches(e, target)) r.setting = mid, r.error = e;
    else loose = mid;
  }
  return r;
}

std::vector<double> tolerance_ladder() {
  std::vector<double> v;
  for (int e = 3; e <= 13; ++e) v.push_back(std::pow(10.0, -e));
  return v;
}

std::vector<double> step_ladder(double dt) {
  std::vector<double> v;
  for (int k = 0; k <= 16; ++k) v.push_back(std::ldexp(dt, -k));
  return v;
}

core::Scene accuracy_scene(const core::Scene& scene) { return swept_scene(scene, SweepSpec{}); }

std::string accuracy_refusal(const core::Scene& scene) {
  if (scene.find_effect<core::Collisions>())
    return scene.name + ": --accuracy cannot search a scene with collisions: the time of impact makes the error "
                        "jump with the tolerance (not smooth), so no setting reaches an error reliably";
  return "";
}

AccuracyPlan find_equal_accuracy(const core::Scene& written, double target, const std::vector<std::string>& backends,
                                 const std::filesystem::path& cache, bool quiet) {
  if (const auto why = accuracy_refusal(written); !why.empty()) throw input_error(why);
  const core::Scene scene = accuracy_scene(written);
  // One model for every trial: they change the solver's settings only.
  const auto model = core::compiled_model(scene);
  AccuracyPlan plan;
  plan.scene = scene.name;
  plan.sha256 = scene.sha256;
  plan.duration = scene.duration;
  plan.target = target;
  plan.measure = default_error(scene);
  plan.adaptive = core::is_adaptive(scene.solver.method);
  const std::string method(core::to_string(scene.solver.method));

  // The cache: {"format": 1, "scenes": {name: {..., "method", "backends": {b: {...}}}}}.
  json all = read_cache(cache);
  const bool format_1 = all.contains("format") && all["format"] == 1 && all.contains("scenes") && all["scenes"].is_object();
  if (format_1 && all["scenes"].contains(scene.name) && all["scenes"][scene.name].is_object()) {
    const json& c = all["scenes"][scene.name];
    const auto is = [&](const char* key, const json& v) { return c.contains(key) && c[key] == v; };
    bool ok = is("sha256", plan.sha256) && is("duration", plan.duration) && is("target", target) &&
              is("measure", std::string(measure_name(plan.measure))) && is("method", method) && c.contains("backends") &&
              c["backends"].is_object();
    for (const auto& b : backends) ok = ok && c["backends"].contains(b);
    if (ok) {
      const Field entry(cache.string(), c, "/scenes/" + scene.name);
      try {
        for (const auto& b : backends)
          plan.backends.push_back(cached_setting(entry["backends"][b], b, scene, plan.adaptive, target));
        plan.reused = true;
        return plan;
      } catch (const Error& e) {  // a setting out of range is not trusted: searched again
        plan.backends.clear();
        if (!quiet) std::cerr << "gacompare: " << e.what() << "; searching again\n";
      }
    }
  }

  core::Scene ref_scene = scene;
  ref_scene.solver = {core::SolverMethod::cash_karp45, scene.solver.dt, kReferenceTolerance, kReferenceTolerance,
                      scene.solver.error_norm};
  const core::Run ref = run_backend(ref_scene, model, "traditional");
  if (ref.error) throw run_error(scene.name + ": the reference run (cash_karp45 at 1e-14) failed: " + *ref.error);

  for (const auto& b : backends) {
    AccuracySetting s{b, scene.solver, 0, 0, 0};
    std::uint64_t steps_of_found = 0;
    std::vector<std::pair<double, std::uint64_t>> steps;  // setting → steps
    auto error_of = [&](double x) {
      core::Scene s2 = scene;
      s2.solver = with_setting(scene.solver, plan.adaptive, x);
      const core::Run run = run_backend(s2, model, b);
      steps.emplace_back(x, run.solver.steps_accepted);
      const double e = final_error(run, ref, plan.measure);
      if (!quiet)
        std::cerr << "gacompare: " << scene.name << ": " << b << " " << setting_text(plan.adaptive, x) << ": "
                  << measure_words(plan.measure) << " error " << format_number("%.3g", e) << " " << measure_unit(plan.measure)
                  << "\n";
      return e;
    };
    const SearchResult r = search_ladder(plan.adaptive ? tolerance_ladder() : step_ladder(scene.solver.dt), error_of,
                                         target);
    if (!r.found) {
      const std::string unit(measure_unit(plan.measure));
      double best = INFINITY;
      for (const auto& t : r.trials)
        if (t.error < best) best = t.error;
      throw input_error(scene.name + ": --accuracy " + format_number("%g", target) + " " + unit + " is out of reach for " + b +
                        (plan.adaptive ? " down to tolerance 1e-13" : " with the step halved to 2^-16 of dt") +
                        " (best " + format_number("%.3g", best) + " " + unit +
                        ")");
    }
    for (const auto& [x, n] : steps)
      if (x == r.setting) steps_of_found = n;
    s.spec = with_setting(scene.solver, plan.adaptive, r.setting);
    s.error = r.error;
    s.steps = steps_of_found;
    s.trials = static_cast<int>(r.trials.size());
    plan.backends.push_back(s);
  }

  json entry = plan_json(plan);
  entry["method"] = method;
  if (!format_1) all = {{"format", 1}, {"scenes", json::object()}};
  all["scenes"][scene.name] = entry;
  if (cache.has_parent_path()) std::filesystem::create_directories(cache.parent_path());
  write_file_atomically(cache, all.dump(1) + "\n");
  return plan;
}

SceneResult compare_at_accuracy(const core::Scene& written, const AccuracyPlan& plan, int repeats,
                                const Progress& progress) {
  const core::Scene scene = accuracy_scene(written);
  SceneResult result{scene, std::vector<BackendResult>(plan.backends.size()),
                     core::compiled_model(scene)};
  const std::size_t n = plan.backends.size();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t b = (r % 2 == 0) ? k : n - 1 - k;  // alternating who goes first
      core::Scene s = scene;
      s.solver = plan.backends[b].spec;
      core::Run run = run_backend(s, result.model, plan.backends[b].backend);
      auto& br = result.backends[b];
      br.profiles.push_back(run.profile);
      br.wall_seconds.push_back(run.wall_seconds);
      if (r == 0) br.run = std::move(run);
      else if (run.samples.empty() || br.run.samples.empty() ||
               state_difference(run.samples.back(), br.run.samples.back()).value != StateErrors{}.value)
        br.deterministic = false;
    }
    if (progress) progress(r + 1, repeats, result);
  }
  return result;
}

std::string accuracy_section_md(const AccuracyPlan& plan, const SceneResult& result) {
  const std::string unit(measure_unit(plan.measure)), words(measure_words(plan.measure));
  std::ostringstream md;
  md << "\n## Time at equal accuracy\n\n**The settings differ per backend**: each backend runs at the "
     << (plan.adaptive ? "tolerance" : "step") << " at which its " << words << " error at t = " << plan.duration
     << " s (50 output samples, as in `sweep`: an adaptive step never crosses a sample time, so the scene's own "
     << "sampling would cap every loose tolerance at the same step), against the traditional backend with "
     << "cash_karp45 at 1e-14, is at most **" << format_number("%g", plan.target) << " "
     << unit << "** (`--accuracy`), found by a ladder of " << (plan.adaptive ? "decades" : "halvings")
     << " and log-space bisection" << (plan.reused ? ", read from accuracy.json" : "")
     << ". This table is the headline; the tables below are these same runs, each backend at its own setting.\n\n"
     << "| backend | setting | " << words << " error (" << unit
     << ") | steps | time median (min–max) |";
  // Each backend's time over that of each form of the traditional backend
  // that ran (the matrix, and on a rigid-body scene the quaternion twin:
  // compare/runner.hpp), over paired repeats.
  std::vector<const BackendResult*> refs;
  std::vector<std::string> ref_names;
  for (const std::string_view name : {std::string_view("traditional"), kTraditionalRepresentations[0],
                                      kTraditionalRepresentations[1]})
    for (std::size_t k = 0; k < plan.backends.size() && k < result.backends.size(); ++k)
      if (plan.backends[k].backend == name) refs.push_back(&result.backends[k]), ref_names.emplace_back(name);
  for (const auto& name : ref_names) md << " time / " << name << " |";
  md << "\n|---|---|---:|---:|---:|";
  for (std::size_t k = 0; k < refs.size(); ++k) md << "---:|";
  md << "\n";
  for (std::size_t k = 0; k < plan.backends.size() && k < result.backends.size(); ++k) {
    const auto& s = plan.backends[k];
    const auto& br = result.backends[k];
    const Spread t = spread(br.wall_seconds);
    md << "| " << s.backend << " | " << setting_text(plan.adaptive, setting_of(s.spec, plan.adaptive)) << " | "
       << format_number("%.2e", s.error) << " | " << s.steps << " | " << format_number("%.3g", 1e3 * t.median) << " ms ("
       << format_number("%.3g", 1e3 * t.min) << "–" << format_number("%.3g", 1e3 * t.max) << ") |";
    for (const BackendResult* ref : refs) {
      std::string ratio = "–";
      if (ref == &br) {
        ratio = "1";
      } else if (ref->wall_seconds.size() == br.wall_seconds.size()) {
        std::vector<double> q;
        for (std::size_t i = 0; i < br.wall_seconds.size(); ++i) q.push_back(br.wall_seconds[i] / ref->wall_seconds[i]);
        const Spread qs = spread(q);
        ratio = format_number("%.2f", qs.median) + " (" + format_number("%.2f", qs.min) + "–" + format_number("%.2f", qs.max) + ")";
      }
      md << " " << ratio << " |";
    }
    md << "\n";
  }
  return md.str();
}

void insert_section(const std::filesystem::path& report_md, const std::string& section) {
  std::string text = core::read_file(report_md, "report");
  const auto eol = text.find('\n');
  if (eol == std::string::npos) text += "\n" + section;
  else text.insert(eol + 1, section);
  write_file_atomically(report_md, text);
}

}  // namespace gacompare::compare
