#include "compare/sweep.hpp"

#include "cga/backend.hpp"
#include "pga/backend.hpp"
#include "compare/escape.hpp"
#include "compare/files.hpp"
#include "compare/machine.hpp"
#include "compare/metrics.hpp"
#include "compare/plot.hpp"
#include "compare/report.hpp"
#include "compare/stats.hpp"
#include "core/error.hpp"
#include "core/model/generators.hpp"
#include "core/dynamics/simulator.hpp"
#include "traditional/backend.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <tuple>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

// Per measure, the largest error over particles and bodies at the final time and
// the RMS over every sample and moving object (a static body, never moved, would
// only dilute it); infinite where the run stopped early.
struct Errors {
  StateErrors final, rms;
};

Errors errors(const core::Scene& scene, const core::Run& run, const core::Run& ref) {
  StateErrors sum, count;
  Errors e;
  auto add = [&](const StateErrors& d, bool body) {
    for (const Measure m : kMeasures)
      if (body || !body_only(m)) sum[m] += d[m] * d[m], count[m] += 1;
  };
  const std::size_t n = std::min(run.samples.size(), ref.samples.size());
  for (std::size_t k = 0; k < n; ++k) {
    const auto &a = run.samples[k], &b = ref.samples[k];
    for (std::size_t i = 0; i < std::min(a.particles.size(), b.particles.size()); ++i)
      add(particle_difference(a.particles[i], b.particles[i]), false);
    for (std::size_t i = 0; i < std::min(a.bodies.size(), b.bodies.size()); ++i)
      if (!scene.bodies[i].is_static) add(body_difference(a.bodies[i], b.bodies[i]), true);
    if (k + 1 == n) e.final = state_difference(a, b);
  }
  const bool complete = run.samples.size() == ref.samples.size() && !run.error;
  for (const Measure m : kMeasures) {
    e.rms[m] = complete && count[m] > 0 ? std::sqrt(sum[m] / count[m]) : INFINITY;
    if (!complete) e.final[m] = INFINITY;
  }
  return e;
}

// The error of not simulating at all: how far anything ever gets from its start,
// per measure (the end alone would do for a projectile, not for an orbit that
// closes). A cell worse than this has diverged and is never on the Pareto front.
StateErrors error_of_nothing(const core::Run& ref) {
  StateErrors worst;
  for (const auto& s : ref.samples) worst.take(state_difference(s, ref.samples.front()));
  return worst;
}

// The measures a scene has: orientation and angular velocity need a body.
std::vector<Measure> measures_of(const core::Scene& s) {
  std::vector<Measure> out;
  for (const Measure m : kMeasures)
    if (!body_only(m) || !s.bodies.empty()) out.push_back(m);
  return out;
}

json number_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// One run, timed without compiling its model (compiled once per scene).
template <class B>
core::Run timed(const core::Scene& s, const std::shared_ptr<const core::Model>& model, std::vector<double>& seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  core::Run r = core::simulate<B>(s, model);
  seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return r;
}

// The Boost.Odeint peers on the traditional backend's derivative, observed at
// the same output times: odeint_cash_karp54, its controlled Cash–Karp, which
// clips its steps at the output times as ours do; odeint_dopri5, its
// Dormand–Prince with dense output (make_dense_output), which steps past them
// and interpolates as our dopri5 does. Their error norm is their own (max over
// components of |err| / (abs + rel·(|x| + h|dx/dt|))), close to ours but not equal.
core::Run odeint_run(const core::Scene& s, const std::string& peer, double tol, std::vector<double>& seconds) {
  namespace odeint = boost::numeric::odeint;
  using B = traditional::Backend;
  using State = std::vector<double>;
  const auto t0 = std::chrono::steady_clock::now();
  const auto model = B::build(s);
  State x(B::state_size(model));
  B::initial_state(model, x);
  core::Run run;
  auto sys = [&](const State& y, State& dy, double t) {
    ++run.solver.derivative_evaluations;
    B::derivative(model, t, y, dy, run.profile);
  };
  const auto times = core::output_times(s);
  auto observe = [&](const State& y, double t) {
    core::Sample smp;
    smp.t = t;
    B::observe(model, y, smp);
    run.samples.push_back(std::move(smp));
  };
  if (peer == "odeint_dopri5")
    odeint::integrate_times(odeint::make_dense_output(tol, tol, odeint::runge_kutta_dopri5<State>()), sys, x,
                            times.begin(), times.end(), s.solver.dt, observe);
  else
    odeint::integrate_times(odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<State>()), sys, x,
                            times.begin(), times.end(), s.solver.dt, observe);
  seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return run;
}
bool is_peer(const std::string& solver) { return solver.starts_with("odeint_"); }

json cell(const std::string& backend, const core::Scene& scene, const core::Run& run, const core::Run& ref,
          const std::vector<double>& secs) {
  const Errors e = errors(scene, run, ref);
  json errs = json::object();
  for (const Measure m : measures_of(scene))
    errs[std::string(measure_name(m))] = {{"final", number_or_null(e.final[m])}, {"rms", number_or_null(e.rms[m])}};
  json c = {{"backend", backend},
            {"errors", errs},
            {"seconds", secs},
            {"steps", run.solver.steps_accepted},
            {"derivative_evaluations", run.solver.derivative_evaluations}};
  if (run.error) c["failure"] = *run.error;
  return c;
}

// One cell of the report: a backend at one setting of one solver.
struct Row {
  std::string solver, backend, setting, failure;
  StateErrors final, rms;  // NaN: not measured (a failed cell, or a body measure of a scene without bodies)
  double error = INFINITY, time = 0;  // the diagram's measure at the end
  Spread secs;
  std::uint64_t steps = 0, evals = 0;
};

// Time at equal accuracy: equal tolerance is not equal accuracy,
// so per solver each backend's time and steps are read off its own cells at
// common error levels — every decade inside the range all the solver's
// backends reach — and compared with the traditional backend's at that level.
template <class Usable>
void write_equal_accuracy(std::ostringstream& md, const std::vector<Row>& rows, Usable usable, Measure x) {
  std::vector<std::string> solvers, backends;
  for (const auto& r : rows) {
    if (std::find(solvers.begin(), solvers.end(), r.solver) == solvers.end()) solvers.push_back(r.solver);
    if (std::find(backends.begin(), backends.end(), r.backend) == backends.end()) backends.push_back(r.backend);
  }
  std::ostringstream table;
  int lines = 0;
  for (const auto& solver : solvers) {
    if (is_peer(solver)) continue;  // a peer has one backend: nothing to compare at equal error
    std::vector<std::pair<std::string, std::vector<EqualAccuracyPoint>>> lines_of;
    double lo = 0, hi = INFINITY;
    for (const auto& b : backends) {
      std::vector<EqualAccuracyPoint> cells;
      for (const auto& r : rows)
        if (r.solver == solver && r.backend == b && usable(r))
          cells.push_back({r.error, r.time, static_cast<double>(r.steps)});
      if (cells.empty()) continue;
      double mn = INFINITY, mx = 0;
      for (const auto& c : cells) mn = std::min(mn, c.error), mx = std::max(mx, c.error);
      lo = std::max(lo, mn), hi = std::min(hi, mx);
      lines_of.emplace_back(b, std::move(cells));
    }
    if (lines_of.size() < 2 || !(lo > 0) || !(lo <= hi)) continue;
    for (int e = static_cast<int>(std::floor(std::log10(hi))); e >= static_cast<int>(std::ceil(std::log10(lo))); --e) {
      const double level = std::pow(10.0, e);
      std::optional<EqualAccuracyPoint> base;
      for (const auto& [b, cells] : lines_of)
        if (b == "traditional") base = cost_at_error(cells, level);
      for (const auto& [b, cells] : lines_of) {
        const auto at = cost_at_error(cells, level);
        if (!at) continue;
        table << "| " << solver << " | " << format_number("%.0e", level) << " | " << b << " | "
              << format_number("%.3g", 1e3 * at->time) << " ms | " << format_number("%.0f", at->steps) << " | "
              << (base ? format_number("%.2f", at->time / base->time) : "–") << " | "
              << (base ? format_number("%.2f", at->steps / base->steps) : "–") << " |\n";
        ++lines;
      }
    }
  }
  md << "\n## Time at equal accuracy\n\n";
  if (lines == 0) {
    md << "No error level is reached by two backends of one solver inside both their ranges: nothing to compare.\n";
    return;
  }
  md << "Each backend's median time and steps to reach a " << measure_words(x) << " error E at the end, read off its "
     << "own cells above (the cells that are faster than every more accurate one, interpolated in log error – log "
     << "time; never extrapolated), at every decade E inside the range all the solver's backends reach. Ratios are "
     << "to the traditional backend at the same E: **the settings differ per backend**, the accuracy does not.\n\n"
     << "| method | E (" << measure_unit(x) << ") | backend | time at E | steps at E | time / traditional | steps / traditional |\n"
     << "|---|---:|---|---:|---:|---:|---:|\n"
     << table.str();
}

// Method against method on one state, the traditional backend's, which the
// Boost.Odeint peers integrate too: at every decade E a peer reaches, each
// method's time and derivative evaluations at E, and its time over each
// peer's (the same interpolation as above).
template <class Usable>
void write_methods_against_peers(std::ostringstream& md, const std::vector<Row>& rows, Usable usable, Measure x) {
  std::vector<std::string> methods, peers;
  std::vector<std::vector<EqualAccuracyPoint>> cells;
  for (const auto& r : rows) {
    if (r.backend != "traditional" || !usable(r)) continue;
    auto it = std::find(methods.begin(), methods.end(), r.solver);
    if (it == methods.end()) {
      methods.push_back(r.solver), cells.emplace_back();
      if (is_peer(r.solver)) peers.push_back(r.solver);
      it = methods.end() - 1;
    }
    // Derivative evaluations, not steps: the peers count only those, and
    // they are the work a method's steps cost.
    cells[static_cast<std::size_t>(it - methods.begin())].push_back({r.error, r.time, static_cast<double>(r.evals)});
  }
  if (peers.empty() || methods.size() < 2) return;
  double lo = INFINITY, hi = 0;
  for (std::size_t k = 0; k < methods.size(); ++k)
    if (is_peer(methods[k]))
      for (const auto& c : cells[k]) lo = std::min(lo, c.error), hi = std::max(hi, c.error);
  if (!(lo > 0) || !(lo <= hi)) return;
  std::ostringstream table;
  int lines = 0;
  for (int e = static_cast<int>(std::floor(std::log10(hi))); e >= static_cast<int>(std::ceil(std::log10(lo))); --e) {
    const double level = std::pow(10.0, e);
    std::vector<std::optional<EqualAccuracyPoint>> peer_at;
    for (const auto& p : peers)
      peer_at.push_back(cost_at_error(cells[static_cast<std::size_t>(std::find(methods.begin(), methods.end(), p) - methods.begin())], level));
    for (std::size_t k = 0; k < methods.size(); ++k) {
      const auto at = cost_at_error(cells[k], level);
      if (!at) continue;
      table << "| " << format_number("%.0e", level) << " | " << methods[k] << " | " << format_number("%.3g", 1e3 * at->time)
            << " ms | " << format_number("%.0f", at->steps) << " |";
      for (const auto& p : peer_at) table << " " << (p ? format_number("%.2f", at->time / p->time) : "–") << " |";
      table << "\n";
      ++lines;
    }
  }
  if (lines == 0) return;
  md << "\n## Method against method\n\nOn the traditional backend's state, which Boost.Odeint's steppers integrate "
        "too: each method's median time and derivative evaluations to reach a "
     << measure_words(x) << " error E at the end (interpolated as above), and its time over each peer's at the same E, "
        "at every decade a peer reaches. The methods' own settings differ; the accuracy does not.\n\n| E ("
     << measure_unit(x) << ") | method | time at E | f evals at E |";
  for (const auto& p : peers) md << " time / " << p << " |";
  md << "\n|---:|---|---:|---:|";
  for (std::size_t k = 0; k < peers.size(); ++k) md << "---:|";
  md << "\n" << table.str();
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
        units.push_back({name + "-tol1e-" + std::to_string(e), name, format_number("tol %.0e", tol), {m, scene.solver.dt, tol, tol}});
      }
    } else {
      double dt = spec.dt_from;
      for (int k = 0; k <= spec.dt_halvings; ++k, dt /= 2)
        units.push_back({name + "-dt" + format_number("%.6g", dt), name, format_number("dt %.6g", dt), {m, dt, 1e-9, 1e-9}});
    }
  }
  if (spec.peer && !projection(scene))
    for (const auto& [peer, ours] : {std::pair{"odeint_cash_karp54", core::SolverMethod::cash_karp45},
                                     std::pair{"odeint_dopri5", core::SolverMethod::dopri5}})
      for (int e = spec.tol_from; e <= spec.tol_to; ++e) {
        const double tol = std::pow(10.0, -e);
        units.push_back({std::string(peer) + "-tol1e-" + std::to_string(e), peer, format_number("tol %.0e", tol),
                         {ours, scene.solver.dt, tol, tol}});
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
  if (is_peer(unit.solver)) {
    std::vector<double> warm, secs;
    odeint_run(s, unit.solver, unit.spec.abs_tol, warm);
    core::Run run;
    for (int r = 0; r < spec.repeats; ++r) run = odeint_run(s, unit.solver, unit.spec.abs_tol, secs);
    cells.push_back(cell("traditional", s, run, ref, secs));
  } else {
    // Every variant in turn, the order rotated each repeat so drift hits them
    // alike: the three backends, and for a scene of bodies the traditional
    // backend with its other rotation representation too (matrix, quaternion,
    // rotor and motor in one diagram).
    struct Variant {
      std::string label;
      core::Scene scene;
      std::string backend;
      std::vector<double> secs;
      core::Run run;
    };
    std::vector<Variant> variants = {{"traditional", s, "traditional", {}, {}}, {"cga", s, "cga", {}, {}},
                                     {"pga", s, "pga", {}, {}}};
    if (!s.bodies.empty()) {
      core::Scene other = s;
      other.rigid_body.rotation =
          s.rigid_body.rotation == core::Rotation::matrix ? core::Rotation::quaternion : core::Rotation::matrix;
      variants.insert(variants.begin() + 1,
                      {std::string("traditional-") + (other.rigid_body.rotation == core::Rotation::matrix ? "matrix" : "quaternion"),
                       other, "traditional", {}, {}});
    }
    try {
      const auto model = core::compiled_model(swept);
      auto run_one = [&model](Variant& v, std::vector<double>& secs) {
        if (v.backend == "cga") return timed<cga::Backend>(v.scene, model, secs);
        if (v.backend == "pga") return timed<pga::Backend>(v.scene, model, secs);
        return timed<traditional::Backend>(v.scene, model, secs);
      };
      std::vector<double> warm;
      for (auto& v : variants) run_one(v, warm);
      for (int r = 0; r < spec.repeats; ++r)
        for (std::size_t k = 0; k < variants.size(); ++k) {
          Variant& v = variants[(k + static_cast<std::size_t>(r)) % variants.size()];
          v.run = run_one(v, v.secs);
        }
      for (const auto& v : variants) cells.push_back(cell(v.label, v.scene, v.run, ref, v.secs));
    } catch (const Error& e) {  // a setting this scene refuses (a split solver with bodies)
      for (const auto& v : variants)
        cells.push_back({{"backend", v.label}, {"errors", json::object()}, {"seconds", json::array()},
                         {"steps", 0}, {"derivative_evaluations", 0}, {"failure", e.what()}});
    }
  }
  json nothing = json::object();
  const StateErrors n = error_of_nothing(ref);
  for (const Measure m : measures_of(swept)) nothing[std::string(measure_name(m))] = n[m];
  return {{"format", kSweepCellFormat}, {"unit", unit.id}, {"solver", unit.solver}, {"setting", unit.setting},
          {"key", cell_key(swept, spec)}, {"error_of_nothing", nothing}, {"cells", cells}};
}

std::string format_number(const char* printf_format, double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, printf_format, x);
  return buf;
}

Measure default_error(const core::Scene& scene) {
  return !scene.bodies.empty() && scene.particles.empty() ? Measure::orientation : Measure::position;
}

std::optional<EqualAccuracyPoint> cost_at_error(std::vector<EqualAccuracyPoint> cells, double error) {
  std::erase_if(cells, [](const EqualAccuracyPoint& c) { return !(c.error > 0 && c.time > 0 && c.steps > 0); });
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  std::vector<EqualAccuracyPoint> front;
  for (const auto& c : cells)
    if (front.empty() || c.error < front.back().error) front.push_back(c);
  if (front.empty() || !(error > 0)) return std::nullopt;
  // front: time rising, error falling.
  if (error > front.front().error || error < front.back().error) return std::nullopt;
  for (std::size_t k = 0; k + 1 < front.size(); ++k) {
    const auto &a = front[k], &b = front[k + 1];
    if (error <= a.error && error >= b.error) {
      const double w = std::log(a.error / error) / std::log(a.error / b.error);
      return EqualAccuracyPoint{error, std::exp(std::log(a.time) + w * std::log(b.time / a.time)),
                                std::exp(std::log(a.steps) + w * std::log(b.steps / a.steps))};
    }
  }
  return front.front();  // a front of one cell, asked at exactly its error
}

nlohmann::ordered_json cell_key(const core::Scene& swept, const SweepSpec& spec) {
  return {{"scene_sha256", swept.sha256}, {"duration", swept.duration}, {"output_every", swept.output_every},
          {"repeats", spec.repeats}, {"build", spec.build}};
}

bool cell_is_current(const SweepCell& cell, const nlohmann::json& key) {
  // Compared as unordered JSON: a record read back from a file keeps no order.
  return cell.format == kSweepCellFormat && cell.key == nlohmann::json(key);
}

std::vector<SweepCell> run_units(const core::Scene& swept, const SweepSpec& spec) {
  const core::Run ref = sweep_reference(swept);
  std::vector<SweepCell> out;
  for (const Unit& u : sweep_units(spec, swept))
    out.push_back(parse_cell(run_unit(u, swept, ref, spec).dump(), "(in memory)", u.id));
  return out;
}

std::string_view method_family(std::string_view solver) {
  using core::SolverMethod;
  const auto m = core::solver_method_from_string(solver);
  if (!m) return "Odeint";
  switch (*m) {
    case SolverMethod::euler: case SolverMethod::rk4: case SolverMethod::rk4_doubling: case SolverMethod::cash_karp45:
      return "classical";
    case SolverMethod::symplectic_euler: case SolverMethod::velocity_verlet:
      return "symplectic";
    case SolverMethod::rkmk4: case SolverMethod::rkmk45: case SolverMethod::crouch_grossman4:
      return "Lie group";
    default:
      return "PI pairs";
  }
}

void write_sweep_report(const std::filesystem::path& dir, const core::Scene& scene,
                        const std::vector<SweepCell>& units, const SweepSpec& spec) {
  const Measure x = spec.error.value_or(default_error(scene));
  const auto measures = measures_of(scene);
  const std::string unit(measure_unit(x)), words(measure_words(x));
  std::vector<Row> rows;
  double nothing = INFINITY;
  for (const auto& u : units) {
    const auto n = u.error_of_nothing.find(std::string(measure_name(x)));
    nothing = n == u.error_of_nothing.end() ? INFINITY : n->second;
    for (const auto& c : u.cells) {
      Row r;
      r.solver = u.solver;
      r.backend = c.backend;
      r.setting = u.setting;
      r.failure = c.failure;
      for (const Measure m : kMeasures) {
        r.final[m] = r.rms[m] = NAN;
        const auto it = c.errors.find(std::string(measure_name(m)));
        if (it == c.errors.end()) continue;
        std::tie(r.final[m], r.rms[m]) = it->second;
      }
      if (std::isfinite(r.final[x])) r.error = r.final[x];
      r.secs = spread(c.seconds);
      r.time = r.secs.median;
      r.steps = c.steps;
      r.evals = c.evaluations;
      rows.push_back(r);
    }
  }
  auto usable = [&](const Row& r) { return r.failure.empty() && r.error < nothing && r.error > 0; };
  auto pareto = [&](const Row& r) {
    if (!usable(r)) return false;
    for (const auto& o : rows)
      if (&o != &r && usable(o) && o.error <= r.error && o.time <= r.time && (o.error < r.error || o.time < r.time))
        return false;  // dominated (two variants with the same error: only the faster is on the front)
    return true;
  };

  auto why = [&] {
    if (spec.error) return std::string("chosen with --error");
    if (x == Measure::orientation)
      return std::string("the default for a scene of bodies: rotation is where the backends' algebras differ, while a "
                         "centre of mass moves by the same formulas in both; --error position|velocity|angular_velocity "
                         "draws another");
    return std::string("the default for a scene with particles; --error chooses another");
  };
  std::ostringstream md, csv;
  md << "# " << md_text(scene.name) << ": what accuracy costs in time\n\nReference: traditional, cash_karp45 at 1e-13. "
     << spec.repeats << " timed repeats per cell after one warm-up, backends interleaved. Errors against the reference "
     << "at the final time, the largest over particles and bodies: position |x − x_ref| (m), orientation (rad: the "
     << "angle of q_ref⁻¹ q, accurate to rounding), velocity |v − v_ref| (m/s) and angular velocity |ω − ω_ref| "
     << "(rad/s, world frame); the RMS is over every sample and moving object. **The diagram's x-axis and the Pareto front (★): "
     << words << " error at the end (" << unit << ")**, " << why() << ".\n\n"
     << "| method | backend | setting |";
  for (const Measure m : measures) md << " " << measure_words(m) << " (" << measure_unit(m) << ") |";
  md << " RMS " << words << " (" << unit << ") | time median (min–max) | steps | f evals | |\n|---|---|---|";
  for (std::size_t k = 0; k < measures.size(); ++k) md << "---:|";
  md << "---:|---:|---:|---:|---|\n";
  csv << "method,backend,setting";
  for (const Measure m : kMeasures) csv << "," << measure_name(m) << "_error";
  for (const Measure m : kMeasures) csv << "," << measure_name(m) << "_error_rms";
  csv << ",seconds_median,seconds_min,seconds_max,steps,evaluations,failure\n";
  // In the CSV a measure not measured (the scene has no object for it, or the
  // setting was refused) is an empty field; a run that stopped early reads inf.
  auto csv_number = [](double v) { return std::isnan(v) ? std::string() : format_number("%.9g", v); };
  for (const auto& r : rows) {
    md << "| " << md_text(r.solver) << " | " << md_text(r.backend) << " | " << md_text(r.setting) << " |";
    if (!r.failure.empty()) {
      md << " failed: " << md_text(r.failure) << " |";
      for (std::size_t k = 0; k < measures.size() + 4; ++k) md << " |";
      md << "\n";
    } else {
      for (const Measure m : measures) md << " " << format_number("%.2e", r.final[m]) << " |";
      md << " " << format_number("%.2e", r.rms[x]) << " | " << format_number("%.3g", 1e3 * r.time) << " ms (" << format_number("%.3g", 1e3 * r.secs.min)
         << "–" << format_number("%.3g", 1e3 * r.secs.max) << ") | " << (r.steps ? std::to_string(r.steps) : "–") << " | "
         << r.evals << " | " << (pareto(r) ? "★" : "") << " |\n";
    }
    csv << csv_field(r.solver) << "," << csv_field(r.backend) << "," << csv_field(r.setting);
    for (const Measure m : kMeasures) csv << "," << csv_number(r.final[m]);
    for (const Measure m : kMeasures) csv << "," << csv_number(r.rms[m]);
    csv << "," << format_number("%.9g", r.time) << "," << format_number("%.9g", r.secs.min) << "," << format_number("%.9g", r.secs.max) << ","
        << r.steps << "," << r.evals << "," << csv_field(r.failure) << "\n";
  }
  write_equal_accuracy(md, rows, usable, x);
  write_methods_against_peers(md, rows, usable, x);
  if (std::none_of(rows.begin(), rows.end(), usable))
    md << "\nNo cell has a " << words << " error above 0 and below the error of not simulating at all ("
       << format_number("%.2e", nothing) << " " << unit << "): there is no diagram to draw.\n";
  write_file_atomically(dir / "sweep.md", md.str());
  write_file_atomically(dir / "sweep.csv", csv.str());

  // The diagram in the field's convention (SciML's benchmarks): x the error, y the
  // time, both logarithmic, a line with markers per solver and backend.
  Plot p{scene.name + ": what accuracy costs in time", words + " error at the end (" + unit + ")", "time (s), median",
         true, true, {}, {}};
  // Colour by backend (and representation), marker by method; the key says
  // what each colour and each marker means, not every combination of them.
  std::vector<std::pair<double, double>> front;
  std::vector<std::string> methods, backends;
  // By family: a curve's methods are its family's, its cells the ones no
  // cell of the same backend and family beats in both error and time.
  const auto group = [&](const Row& r) { return spec.by_family ? std::string(method_family(r.solver)) : r.solver; };
  const auto best_of_group = [&](const Row& r) {
    for (const auto& o : rows)
      if (&o != &r && usable(o) && o.backend == r.backend && group(o) == group(r) && o.error <= r.error &&
          o.time <= r.time && (o.error < r.error || o.time < r.time))
        return false;
    return true;
  };
  for (const auto& r : rows) {  // methods: the curves' methods, or families
    if (!usable(r)) continue;
    if (std::find(methods.begin(), methods.end(), group(r)) == methods.end()) methods.push_back(group(r));
    if (std::find(backends.begin(), backends.end(), r.backend) == backends.end()) backends.push_back(r.backend);
  }
  for (const auto& r : rows) {
    const std::string title = group(r) + " (" + r.backend + ")";
    auto it = std::find_if(p.series.begin(), p.series.end(), [&](const Series& s) { return s.title == title; });
    if (it == p.series.end()) {
      Series s{title, {}, {}, false};
      s.colour = backend_colour(r.backend);
      s.marker = method_marker(static_cast<std::size_t>(std::find(methods.begin(), methods.end(), group(r)) - methods.begin()));
      s.in_key = false;
      it = p.series.insert(p.series.end(), s);
    }
    if (!usable(r) || (spec.by_family && !best_of_group(r))) continue;
    it->x.push_back(r.error);
    it->y.push_back(r.time);
    if (pareto(r)) front.emplace_back(r.error, r.time);
  }
  std::erase_if(p.series, [](const Series& s) { return s.x.empty(); });
  if (spec.by_family)  // a family's cells come from several methods: along the error
    for (auto& s : p.series) {
      std::vector<std::pair<double, double>> xy;
      for (std::size_t k = 0; k < s.x.size(); ++k) xy.emplace_back(s.x[k], s.y[k]);
      std::sort(xy.begin(), xy.end());
      for (std::size_t k = 0; k < xy.size(); ++k) s.x[k] = xy[k].first, s.y[k] = xy[k].second;
    }
  for (const auto& b : backends) {
    Series k{b, {}, {}, false};
    k.colour = backend_colour(b), k.key_only = true;
    p.series.push_back(k);
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    Series k{methods[m], {}, {}, false};
    k.marker = method_marker(m), k.key_only = true;
    p.series.push_back(k);
  }
  std::sort(front.begin(), front.end());
  if (!front.empty()) {
    Series f{"Pareto front", {}, {}, true};
    f.colour = "#000000";  // not a backend's colour
    for (const auto& [e, t] : front) f.x.push_back(e), f.y.push_back(t);
    p.series.push_back(f);
  }
  std::string figure;
  std::error_code gone;
  std::filesystem::remove(dir / (file_name_for(scene.name) + "_work_precision.svg"), gone);  // a stale one, drawn by another --error
  if (std::any_of(p.series.begin(), p.series.end(), [](const Series& s) { return !s.key_only; })) {
    figure = render_svg(p);
    write_file_atomically(dir / (file_name_for(scene.name) + "_work_precision.svg"), figure);
    figure = "<figure>" + figure.substr(std::min(figure.size(), figure.find("<svg"))) + "</figure>\n";
  }
  write_file_atomically(dir / "sweep.html", html_page(scene.name + " — what accuracy costs in time",
                                                      markdown_to_html(md.str()) + figure));
}

}  // namespace gacompare::compare
