// What accuracy costs in time (issue #4): every solver × tolerance (adaptive) or
// step (fixed) × backend on the given scenes, plus Boost.Odeint's controlled
// Cash–Karp 5(4) as a peer, each cell's error against a reference run and its time.
//
//   work_precision [--repeats N] [--max-duration S] [--plot-dir DIR] SCENE.json...
//
// With --plot-dir, each scene's work-precision diagram is drawn by gnuplot to
// DIR/<scene>_work_precision.svg in the field's convention (SciML's benchmarks):
// x the error at the end, y the time, both logarithmic, a line with markers per
// solver and backend, the Pareto front in bold.
//
// Reference: the traditional backend with cash_karp45 at abs = rel = 1e-13 (the
// tightest tolerance at which these scenes still run in seconds); errors of
// cells tighter than ~1e-11 therefore measure the reference as much as the cell.
// Error: largest particle position difference at the final time, and the RMS
// over all samples. Time: one warm-up, then the median (min–max) of N runs of
// the whole simulation, both backends interleaved per repeat. The Pareto front
// (no other cell of the scene is both more accurate and faster) is marked ★;
// a cell whose final error exceeds that of not simulating at all
// (the largest distance anything gets from its start in the reference run) has
// diverged and is never on it. Samples are taken 50 times a run (not at the
// scene's output interval), because adaptive steps never cross a sample time and
// a fine sampling would cap every tolerance at the same step.
#include "cga/backend.hpp"
#include "compare/plot.hpp"
#include "core/error.hpp"
#include "core/generators.hpp"
#include "core/simulator.hpp"
#include "traditional/backend.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace {
using namespace gacompare;

struct Cell {
  Cell(std::string m, std::string b, std::string p) : method(std::move(m)), backend(std::move(b)), param(std::move(p)) {}
  std::string method, backend, param;
  double error_final = 0, error_rms = 0;
  std::vector<double> seconds;
  std::uint64_t steps = 0, evaluations = 0;
  std::string failure;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

void errors(const core::Run& run, const core::Run& ref, Cell& c) {
  double sum = 0, last = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < std::min(run.samples.size(), ref.samples.size()); ++k) {
    double worst = 0;
    for (std::size_t i = 0; i < ref.samples[k].particles.size(); ++i) {
      const double d = (run.samples[k].particles[i].position - ref.samples[k].particles[i].position).norm();
      worst = std::max(worst, d);
      sum += d * d;
      ++n;
    }
    last = worst;
  }
  c.error_final = run.samples.size() == ref.samples.size() ? last : INFINITY;
  c.error_rms = n ? std::sqrt(sum / static_cast<double>(n)) : INFINITY;
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
core::Run odeint_run(const core::Scene& s, double tol, std::vector<double>& seconds, std::uint64_t& evals) {
  namespace odeint = boost::numeric::odeint;
  using B = traditional::Backend;
  const auto t0 = std::chrono::steady_clock::now();
  const auto model = B::build(s);
  std::vector<double> x(B::state_size(model));
  B::initial_state(model, x);
  core::Run run;
  evals = 0;
  auto sys = [&](const std::vector<double>& y, std::vector<double>& dy, double t) {
    ++evals;
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

void plot(const std::string& scene, const std::vector<Cell>& cells, double nothing, const std::string& dir) {
  compare::Plot p{scene + ": what accuracy costs in time", "error at the end (m)", "time (s), median", true, true, {}};
  std::vector<std::pair<double, double>> usable;  // (error, time) of cells that did not diverge
  for (const auto& c : cells) {  // one series per solver and backend, in the cells' order
    const std::string title = c.method + " (" + c.backend + ")";
    auto it = std::find_if(p.series.begin(), p.series.end(), [&](const auto& s) { return s.title == title; });
    if (it == p.series.end()) it = p.series.insert(p.series.end(), compare::Series{title, {}, {}, false});
    if (!c.failure.empty() || !(c.error_final < nothing) || c.error_final <= 0) continue;
    it->x.push_back(c.error_final);
    it->y.push_back(median(c.seconds));
    usable.emplace_back(c.error_final, median(c.seconds));
  }
  std::erase_if(p.series, [](const compare::Series& s) { return s.x.empty(); });
  std::sort(usable.begin(), usable.end());
  compare::Series front{"Pareto front", {}, {}, true};
  double best = INFINITY;  // walking from the most accurate: keep each cell faster than all more accurate ones
  for (const auto& [e, t] : usable)
    if (t < best) {
      front.x.push_back(e);
      front.y.push_back(t);
      best = t;
    }
  if (!front.x.empty()) p.series.push_back(front);
  compare::write_svg(p, std::filesystem::path(dir) / (scene + "_work_precision.svg"));
}

void sweep(const core::Scene& base, int repeats, const std::string& plot_dir) {
  core::Scene ref_scene = base;
  ref_scene.solver = {core::SolverMethod::cash_karp45, base.solver.dt, 1e-13, 1e-13};
  const core::Run ref = core::simulate<traditional::Backend>(ref_scene);
  if (ref.error) throw run_error(base.name + ": reference run failed: " + *ref.error);

  std::vector<std::pair<core::SolverSpec, std::string>> specs;
  for (auto m : {core::SolverMethod::rk4_doubling, core::SolverMethod::cash_karp45})
    for (int e = 3; e <= 12; ++e) {
      const double tol = std::pow(10.0, -e);
      char p[32];
      std::snprintf(p, sizeof p, "tol %.0e", tol);
      specs.push_back({{m, base.solver.dt, tol, tol}, p});
    }
  for (auto m : {core::SolverMethod::euler, core::SolverMethod::symplectic_euler, core::SolverMethod::rk4,
                 core::SolverMethod::velocity_verlet})
    for (double dt = 1e-2; dt >= 1e-2 / 16 * 0.99; dt /= 2) {
      char p[32];
      std::snprintf(p, sizeof p, "dt %.4g", dt);
      specs.push_back({{m, dt, 1e-9, 1e-9}, p});
    }

  // The error of not simulating at all: how far anything ever gets from its start
  // (the end alone would do for a projectile, not for an orbit that closes).
  double nothing = 0;
  for (const auto& smp : ref.samples)
    for (std::size_t i = 0; i < smp.particles.size(); ++i)
      nothing = std::max(nothing, (smp.particles[i].position - ref.samples.front().particles[i].position).norm());

  std::vector<Cell> cells;
  for (const auto& [spec, param] : specs) {
    core::Scene s = base;
    s.solver = spec;
    Cell tc(std::string(core::to_string(spec.method)), "traditional", param), cc = tc;
    cc.backend = "cga";
    std::vector<double> warm;
    try {
      core::Run rt = timed<traditional::Backend>(s, warm), rc = timed<cga::Backend>(s, warm);
      for (int r = 0; r < repeats; ++r) {  // interleaved, alternating who goes first
        if (r % 2 == 0) {
          rt = timed<traditional::Backend>(s, tc.seconds);
          rc = timed<cga::Backend>(s, cc.seconds);
        } else {
          rc = timed<cga::Backend>(s, cc.seconds);
          rt = timed<traditional::Backend>(s, tc.seconds);
        }
      }
      for (auto [c, run] : {std::pair{&tc, &rt}, std::pair{&cc, &rc}}) {
        errors(*run, ref, *c);
        c->steps = run->solver.steps_accepted;
        c->evaluations = run->solver.derivative_evaluations;
        if (run->error) c->failure = *run->error;
      }
    } catch (const Error& e) {
      tc.failure = cc.failure = e.what();
    }
    cells.push_back(tc);
    cells.push_back(cc);
  }
  if (base.constraint_solver.drift != core::Drift::projection) {
    for (int e = 3; e <= 12; ++e) {
      const double tol = std::pow(10.0, -e);
      char p[32];
      std::snprintf(p, sizeof p, "tol %.0e", tol);
      Cell c("odeint cash_karp54", "traditional", p);
      std::vector<double> warm;
      odeint_run(base, tol, warm, c.evaluations);
      core::Run run;
      for (int r = 0; r < repeats; ++r) run = odeint_run(base, tol, c.seconds, c.evaluations);
      errors(run, ref, c);
      cells.push_back(c);
    }
  }

  std::printf("\n### %s\n\nReference: traditional, cash_karp45 at 1e-13. %d timed repeats per cell.\n\n", base.name.c_str(),
              repeats);
  std::printf("| method | backend | setting | error at end (m) | RMS error (m) | time median (min–max) | steps | f evals | |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---|\n");
  for (const auto& c : cells) {
    const double t = median(c.seconds);
    bool pareto = c.failure.empty() && c.error_final < nothing;
    for (const auto& o : cells)
      if (&o != &c && o.failure.empty() && o.error_final < c.error_final && median(o.seconds) < t) pareto = false;
    const auto [mn, mx] = c.seconds.empty() ? std::pair{0.0, 0.0} : std::pair{*std::min_element(c.seconds.begin(), c.seconds.end()), *std::max_element(c.seconds.begin(), c.seconds.end())};
    if (!c.failure.empty()) {
      std::printf("| %s | %s | %s | failed: %s | | | | | |\n", c.method.c_str(), c.backend.c_str(), c.param.c_str(),
                  c.failure.c_str());
      continue;
    }
    const std::string steps = c.steps ? std::to_string(c.steps) : "–";
    std::printf("| %s | %s | %s | %.2e | %.2e | %.3g ms (%.3g–%.3g) | %s | %llu | %s |\n", c.method.c_str(),
                c.backend.c_str(), c.param.c_str(), c.error_final, c.error_rms, 1e3 * t, 1e3 * mn, 1e3 * mx,
                steps.c_str(), static_cast<unsigned long long>(c.evaluations), pareto ? "★" : "");
  }
  std::fflush(stdout);
  if (!plot_dir.empty()) plot(base.name, cells, nothing, plot_dir);
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 3;
  double max_duration = 0;
  std::string plot_dir;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--max-duration") && i + 1 < argc) {
      max_duration = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--plot-dir") && i + 1 < argc) {
      plot_dir = argv[++i];
    } else if (argv[i][0] == '-') {
      std::fprintf(stderr, "work_precision: unknown option %s\nusage: work_precision [--repeats N] [--max-duration S] [--plot-dir DIR] SCENE.json...\n", argv[i]);
      return 2;
    } else {
      files.push_back(argv[i]);
    }
  }
  if (files.empty() || repeats < 1) {
    std::fprintf(stderr, "usage: work_precision [--repeats N] [--max-duration S] [--plot-dir DIR] SCENE.json...\n");
    return 2;
  }
  try {
    for (const auto& f : files) {
      core::Scene s = core::expand_generators(core::load_scene(f));
      if (max_duration > 0 && s.duration > max_duration) {
        s.duration = max_duration;
        std::printf("\n(%s cut to %g s)\n", s.name.c_str(), max_duration);
      }
      s.output_every = s.duration / 50;
      sweep(s, repeats, plot_dir);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "work_precision: %s\n", e.what());
    return e.kind() == ErrorKind::input ? 2 : 1;
  }
  return 0;
}
