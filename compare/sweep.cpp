#include "compare/sweep.hpp"

#include "cga/backend.hpp"
#include "compare/machine.hpp"
#include "compare/plot.hpp"
#include "compare/report.hpp"
#include "compare/stats.hpp"
#include "core/error.hpp"
#include "core/generators.hpp"
#include "core/simulator.hpp"
#include "traditional/backend.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

std::string fmt(const char* f, double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

// Largest position distance at the final time, and the RMS over all samples.
std::pair<double, double> errors(const core::Run& run, const core::Run& ref) {
  double sum = 0, last = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < std::min(run.samples.size(), ref.samples.size()); ++k) {
    double worst = 0;
    auto add = [&](const core::Vec3& a, const core::Vec3& b) {
      const double d = (a - b).norm();
      worst = std::max(worst, d);
      sum += d * d;
      ++n;
    };
    for (std::size_t i = 0; i < ref.samples[k].particles.size(); ++i)
      add(run.samples[k].particles[i].position, ref.samples[k].particles[i].position);
    for (std::size_t i = 0; i < ref.samples[k].bodies.size(); ++i)
      add(run.samples[k].bodies[i].position, ref.samples[k].bodies[i].position);
    last = worst;
  }
  const bool complete = run.samples.size() == ref.samples.size() && !run.error;
  return {complete ? last : INFINITY, complete && n ? std::sqrt(sum / static_cast<double>(n)) : INFINITY};
}

// The error of not simulating at all: how far anything ever gets from its start
// (the end alone would do for a projectile, not for an orbit that closes). A cell
// worse than this has diverged and is never on the Pareto front.
double error_of_nothing(const core::Run& ref) {
  double worst = 0;
  for (const auto& s : ref.samples) {
    for (std::size_t i = 0; i < s.particles.size(); ++i)
      worst = std::max(worst, (s.particles[i].position - ref.samples.front().particles[i].position).norm());
    for (std::size_t i = 0; i < s.bodies.size(); ++i)
      worst = std::max(worst, (s.bodies[i].position - ref.samples.front().bodies[i].position).norm());
  }
  return worst;
}

template <class B>
core::Run timed(const core::Scene& s, std::vector<double>& seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  core::Run r = core::simulate<B>(s);
  seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return r;
}

// Boost.Odeint's controlled Cash–Karp on the traditional backend's derivative,
// observed at the same output times. Its error norm is its own (max over
// components of |err| / (abs + rel·(|x| + h|dx/dt|))), close to ours but not equal.
core::Run odeint_run(const core::Scene& s, double tol, std::vector<double>& seconds) {
  namespace odeint = boost::numeric::odeint;
  using B = traditional::Backend;
  const auto t0 = std::chrono::steady_clock::now();
  const auto model = B::build(s);
  std::vector<double> x(B::state_size(model));
  B::initial_state(model, x);
  core::Run run;
  auto sys = [&](const std::vector<double>& y, std::vector<double>& dy, double t) {
    ++run.solver.derivative_evaluations;
    B::derivative(model, t, y, dy, run.profile);
  };
  const auto times = core::output_times(s);
  auto observe = [&](const std::vector<double>& y, double t) {
    core::Sample smp;
    smp.t = t;
    B::observe(model, y, smp);
    run.samples.push_back(std::move(smp));
  };
  odeint::integrate_times(odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<std::vector<double>>()),
                          sys, x, times.begin(), times.end(), s.solver.dt, observe);
  seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return run;
}

json cell(const std::string& backend, const core::Run& run, const core::Run& ref, const std::vector<double>& secs) {
  const auto [final_error, rms] = errors(run, ref);
  json c = {{"backend", backend},
            {"error_final", std::isfinite(final_error) ? json(final_error) : json(nullptr)},
            {"error_rms", std::isfinite(rms) ? json(rms) : json(nullptr)},
            {"seconds", secs},
            {"steps", run.solver.steps_accepted},
            {"derivative_evaluations", run.solver.derivative_evaluations}};
  if (run.error) c["failure"] = *run.error;
  return c;
}

bool projection(const core::Scene& s) { return s.constraint_solver.drift == core::Drift::projection && !s.constraints.empty(); }
}  // namespace

core::Scene swept_scene(const core::Scene& scene, const SweepSpec& spec) {
  core::Scene s = core::expand_generators(scene);
  if (spec.max_duration > 0 && s.duration > spec.max_duration) s.duration = spec.max_duration;
  s.output_every = s.duration / 50;
  return s;
}

std::vector<Unit> sweep_units(const SweepSpec& spec, const core::Scene& scene) {
  std::vector<Unit> units;
  for (auto m : spec.solvers) {
    const std::string name(core::to_string(m));
    if (core::is_adaptive(m)) {
      for (int e = spec.tol_from; e <= spec.tol_to; ++e) {
        const double tol = std::pow(10.0, -e);
        units.push_back({name + "-tol1e-" + std::to_string(e), name, fmt("tol %.0e", tol), {m, scene.solver.dt, tol, tol}});
      }
    } else {
      double dt = spec.dt_from;
      for (int k = 0; k <= spec.dt_halvings; ++k, dt /= 2)
        units.push_back({name + "-dt" + fmt("%.6g", dt), name, fmt("dt %.6g", dt), {m, dt, 1e-9, 1e-9}});
    }
  }
  if (spec.peer && !projection(scene))
    for (int e = spec.tol_from; e <= spec.tol_to; ++e) {
      const double tol = std::pow(10.0, -e);
      units.push_back({"odeint_cash_karp54-tol1e-" + std::to_string(e), "odeint_cash_karp54", fmt("tol %.0e", tol),
                       {core::SolverMethod::cash_karp45, scene.solver.dt, tol, tol}});
    }
  return units;
}

core::Run sweep_reference(const core::Scene& swept) {
  core::Scene s = swept;
  s.solver = {core::SolverMethod::cash_karp45, swept.solver.dt, 1e-13, 1e-13};
  core::Run ref = core::simulate<traditional::Backend>(s);
  if (ref.error) throw run_error(swept.name + ": the sweep's reference run failed: " + *ref.error);
  return ref;
}

json run_unit(const Unit& unit, const core::Scene& swept, const core::Run& ref, const SweepSpec& spec) {
  core::Scene s = swept;
  s.solver = unit.spec;
  json cells = json::array();
  if (unit.solver == "odeint_cash_karp54") {
    std::vector<double> warm, secs;
    odeint_run(s, unit.spec.abs_tol, warm);
    core::Run run;
    for (int r = 0; r < spec.repeats; ++r) run = odeint_run(s, unit.spec.abs_tol, secs);
    cells.push_back(cell("traditional", run, ref, secs));
  } else {
    std::vector<double> warm, st, sc;
    try {
      timed<traditional::Backend>(s, warm);
      timed<cga::Backend>(s, warm);
      core::Run rt, rc;
      for (int r = 0; r < spec.repeats; ++r) {  // interleaved, alternating who goes first
        if (r % 2 == 0) {
          rt = timed<traditional::Backend>(s, st);
          rc = timed<cga::Backend>(s, sc);
        } else {
          rc = timed<cga::Backend>(s, sc);
          rt = timed<traditional::Backend>(s, st);
        }
      }
      cells.push_back(cell("traditional", rt, ref, st));
      cells.push_back(cell("cga", rc, ref, sc));
    } catch (const Error& e) {  // a setting this scene refuses (a split solver with bodies)
      for (const char* b : {"traditional", "cga"})
        cells.push_back({{"backend", b}, {"error_final", nullptr}, {"error_rms", nullptr}, {"seconds", json::array()},
                         {"steps", 0}, {"derivative_evaluations", 0}, {"failure", e.what()}});
    }
  }
  return {{"unit", unit.id}, {"solver", unit.solver}, {"setting", unit.setting}, {"scene_sha256", swept.sha256},
          {"error_of_nothing", error_of_nothing(ref)}, {"cells", cells}};
}

void write_sweep_report(const std::filesystem::path& dir, const core::Scene& scene,
                        const std::vector<nlohmann::json>& units, const SweepSpec& spec) {
  struct Row {
    std::string solver, backend, setting, failure;
    double error = INFINITY, rms = INFINITY, time = 0;
    Spread secs;
    std::uint64_t steps = 0, evals = 0;
  };
  std::vector<Row> rows;
  double nothing = INFINITY;
  for (const auto& u : units) {
    nothing = u.value("error_of_nothing", INFINITY);
    for (const auto& c : u.at("cells")) {
      Row r;
      r.solver = u.at("solver");
      r.backend = c.at("backend");
      r.setting = u.at("setting");
      r.failure = c.value("failure", "");
      if (!c.at("error_final").is_null()) r.error = c.at("error_final").get<double>();
      if (!c.at("error_rms").is_null()) r.rms = c.at("error_rms").get<double>();
      r.secs = spread(c.at("seconds").get<std::vector<double>>());
      r.time = r.secs.median;
      r.steps = c.at("steps");
      r.evals = c.at("derivative_evaluations");
      rows.push_back(r);
    }
  }
  auto usable = [&](const Row& r) { return r.failure.empty() && r.error < nothing && r.error > 0; };
  auto pareto = [&](const Row& r) {
    if (!usable(r)) return false;
    for (const auto& o : rows)
      if (&o != &r && usable(o) && o.error < r.error && o.time < r.time) return false;
    return true;
  };

  std::ostringstream md, csv;
  md << "# " << scene.name << ": what accuracy costs in time\n\nReference: traditional, cash_karp45 at 1e-13. "
     << spec.repeats << " timed repeats per cell after one warm-up, backends interleaved; the Pareto front marked ★.\n\n"
     << "| method | backend | setting | error at end (m) | RMS error (m) | time median (min–max) | steps | f evals | |\n"
     << "|---|---|---|---:|---:|---:|---:|---:|---|\n";
  csv << "method,backend,setting,error_final_m,error_rms_m,seconds_median,seconds_min,seconds_max,steps,evaluations,failure\n";
  for (const auto& r : rows) {
    if (!r.failure.empty()) {
      md << "| " << r.solver << " | " << r.backend << " | " << r.setting << " | failed: " << r.failure << " | | | | | |\n";
    } else {
      md << "| " << r.solver << " | " << r.backend << " | " << r.setting << " | " << fmt("%.2e", r.error) << " | "
         << fmt("%.2e", r.rms) << " | " << fmt("%.3g", 1e3 * r.time) << " ms (" << fmt("%.3g", 1e3 * r.secs.min) << "–"
         << fmt("%.3g", 1e3 * r.secs.max) << ") | " << (r.steps ? std::to_string(r.steps) : "–") << " | " << r.evals
         << " | " << (pareto(r) ? "★" : "") << " |\n";
    }
    std::string failure = r.failure;
    std::replace(failure.begin(), failure.end(), ',', ';');
    csv << r.solver << "," << r.backend << "," << r.setting << "," << fmt("%.9g", r.error) << "," << fmt("%.9g", r.rms)
        << "," << fmt("%.9g", r.time) << "," << fmt("%.9g", r.secs.min) << "," << fmt("%.9g", r.secs.max) << ","
        << r.steps << "," << r.evals << "," << failure << "\n";
  }
  write_file_atomically(dir / "sweep.md", md.str());
  write_file_atomically(dir / "sweep.csv", csv.str());

  // The diagram in the field's convention (SciML's benchmarks): x the error, y the
  // time, both logarithmic, a line with markers per solver and backend.
  Plot p{scene.name + ": what accuracy costs in time", "error at the end (m)", "time (s), median", true, true, {}, {}};
  std::vector<std::pair<double, double>> front;
  for (const auto& r : rows) {
    const std::string title = r.solver + " (" + r.backend + ")";
    auto it = std::find_if(p.series.begin(), p.series.end(), [&](const Series& s) { return s.title == title; });
    if (it == p.series.end()) it = p.series.insert(p.series.end(), Series{title, {}, {}, false});
    if (!usable(r)) continue;
    it->x.push_back(r.error);
    it->y.push_back(r.time);
    if (pareto(r)) front.emplace_back(r.error, r.time);
  }
  std::erase_if(p.series, [](const Series& s) { return s.x.empty(); });
  std::sort(front.begin(), front.end());
  if (!front.empty()) {
    Series f{"Pareto front", {}, {}, true};
    for (const auto& [e, t] : front) f.x.push_back(e), f.y.push_back(t);
    p.series.push_back(f);
  }
  std::string figure;
  if (!p.series.empty()) {
    figure = render_svg(p);
    write_file_atomically(dir / (scene.name + "_work_precision.svg"), figure);
    figure = "<figure>" + figure.substr(std::min(figure.size(), figure.find("<svg"))) + "</figure>\n";
  }
  write_file_atomically(dir / "sweep.html", html_page(scene.name + " — what accuracy costs in time",
                                                      markdown_to_html(md.str()) + figure));
}

}  // namespace gacompare::compare
