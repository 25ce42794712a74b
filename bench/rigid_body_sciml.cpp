// The SciML "RigidBody" non-stiff benchmark (SciMLBenchmarks.jl,
// benchmarks/NonStiffODE/RigidBody_wpd.jmd; Hairer–Nørsett–Wanner I §II.10):
// Euler's equations of a free rigid body with a periodic torque,
//   y1' = −2 y2 y3,  y2' = 1.25 y1 y3,  y3' = −0.5 y1 y2 + 0.25 sin²(t),
// y(0) = (1, 0, 0.9), t in [0, 10], as a work-precision table of every
// embedded pair here (core/dynamics/tableaus.hpp), cash_karp45 and Boost.Odeint's
// steppers, on SciML's axes: reltol = 10^−k, abstol = 10^−(k+3), here k = 3…12
// (SciML sweeps k = 3…10).
//
// Two measurements per method and tolerance, each timed alone:
//   final: one advance() to t = 10 (SciML's save_everystep=false, error :final):
//          |y(10) − ref(10)|₂;
//   saved: the state at 100 save points t = 0.1, 0.2, …, 10 (SciML's saveat):
//          the L2 error sqrt(mean over points and components of the squared error).
// A method with dense output steps past a save point and interpolates; the
// others end a step on every save point.
// Time: each measurement repeated until 20 ms have passed, that total over the
// count is one sample; the median of 7 samples, with their min–max (--quick:
// 3 samples of 5 ms).
// The reference: vern9 at abs = rel = 1e-14, cross-checked against Odeint's
// Runge–Kutta–Fehlberg 7(8) at 1e-14 (the output states how far apart they are).
//
//   rigid_body_sciml [--quick]   (markdown on stdout, in parts "<!-- part: NAME -->"
//                                 that scripts/results.py --only integrators puts
//                                 into docs/results/integrators.md)
#include "core/dynamics/ode.hpp"

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {
using namespace gacompare;
using State = std::vector<double>;
namespace odeint = boost::numeric::odeint;

constexpr double kEnd = 10.0;
const State kStart{1.0, 0.0, 0.9};

void rigid(double t, std::span<const double> y, std::span<double> dy) {
  const double s = std::sin(t);
  dy[0] = -2.0 * y[1] * y[2];
  dy[1] = 1.25 * y[0] * y[2];
  dy[2] = -0.5 * y[0] * y[1] + 0.25 * s * s;
}

std::vector<double> save_times(bool saved) {
  if (!saved) return {kEnd};
  std::vector<double> t;
  for (int k = 1; k <= 100; ++k) t.push_back(kEnd * k / 100);
  return t;
}

struct Result {
  std::vector<State> states;  // at save_times
  std::uint64_t evaluations = 0;
};

// One of ours: a fresh solver, one advance() per save time.
Result ours(core::SolverMethod m, double abs_tol, double rel_tol, bool saved) {
  core::OdeSolver s({m, 1e-3, abs_tol, rel_tol, core::ErrorNorm::component}, 3);
  State y = kStart;
  double t = 0;
  core::Profile p;
  Result r;
  for (double te : save_times(saved)) {
    s.advance(rigid, t, te, y, p);
    r.states.push_back(y);
  }
  r.evaluations = s.stats().derivative_evaluations;
  return r;
}

// One of Odeint's: integrate_times over 0 and the save times.
template <class Stepper>
Result peer(Stepper stepper, bool saved) {
  State x = kStart;
  Result r;
  auto sys = [&](const State& y, State& dy, double t) {
    ++r.evaluations;
    rigid(t, y, dy);
  };
  std::vector<double> times{0.0};
  for (double t : save_times(saved)) times.push_back(t);
  odeint::integrate_times(stepper, sys, x, times.begin(), times.end(), 1e-3, [&](const State& y, double t) {
    if (t > 0) r.states.push_back(y);
  });
  return r;
}

struct Method {
  std::string name;
  bool dense;  // steps past a save point and interpolates
  std::function<Result(double abs_tol, double rel_tol, bool saved)> run;
};

std::vector<Method> methods() {
  std::vector<Method> out;
  for (auto m : {core::SolverMethod::bs3, core::SolverMethod::dopri5, core::SolverMethod::tsit5,
                 core::SolverMethod::vern6, core::SolverMethod::vern7, core::SolverMethod::vern8,
                 core::SolverMethod::vern9, core::SolverMethod::cash_karp45})
    out.push_back({std::string(core::to_string(m)), core::butcher_tableau(m) && core::butcher_tableau(m)->dense_degree > 0,
                   [m](double a, double r, bool saved) { return ours(m, a, r, saved); }});
  out.push_back({"odeint_cash_karp54", false, [](double a, double r, bool saved) {
                   return peer(odeint::make_controlled(a, r, odeint::runge_kutta_cash_karp54<State>()), saved);
                 }});
  out.push_back({"odeint_dopri5", true, [](double a, double r, bool saved) {
                   return peer(odeint::make_dense_output(a, r, odeint::runge_kutta_dopri5<State>()), saved);
                 }});
  out.push_back({"odeint_fehlberg78", false, [](double a, double r, bool saved) {
                   return peer(odeint::make_controlled(a, r, odeint::runge_kutta_fehlberg78<State>()), saved);
                 }});
  return out;
}

// Median and range of 7 samples, each the mean time of as many runs as fill 20 ms.
struct Timing {
  double median, lo, hi;
};
bool quick = false;
Timing time_of(const std::function<void()>& once) {
  using clock = std::chrono::steady_clock;
  std::vector<double> samples;
  const int count = quick ? 3 : 7;
  const double fill = quick ? 0.005 : 0.02;
  once();  // warm-up
  for (int s = 0; s < count; ++s) {
    long n = 0;
    const auto t0 = clock::now();
    double elapsed = 0;
    do {
      once();
      ++n;
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < fill);
    samples.push_back(elapsed / static_cast<double>(n));
  }
  std::sort(samples.begin(), samples.end());
  return {samples[samples.size() / 2], samples.front(), samples.back()};
}

double final_error(const Result& r, const Result& ref) {
  double s = 0;
  for (int i = 0; i < 3; ++i) s += std::pow(r.states.back()[i] - ref.states.back()[i], 2);
  return std::sqrt(s);
}
double l2_error(const Result& r, const Result& ref) {
  double s = 0;
  for (std::size_t k = 0; k < ref.states.size(); ++k)
    for (int i = 0; i < 3; ++i) s += std::pow(r.states[k][i] - ref.states[k][i], 2);
  return std::sqrt(s / static_cast<double>(3 * ref.states.size()));
}

struct Cell {
  std::string method;
  int k;
  double error;
  Timing time;
  std::uint64_t evaluations;
};

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}
std::string ms(const Timing& t) {
  return fmt("%.3g", 1e3 * t.median) + " (" + fmt("%.3g", 1e3 * t.lo) + "–" + fmt("%.3g", 1e3 * t.hi) + ")";
}

// A method's median time at error E: interpolated in log error – log time
// between its two tolerances whose errors bracket E; none outside its range.
std::optional<double> time_at(const std::vector<Cell>& cells, const std::string& method, double E) {
  std::optional<double> best;
  for (std::size_t i = 0; i + 1 < cells.size(); ++i) {
    const Cell &a = cells[i], &b = cells[i + 1];
    if (a.method != method || b.method != method) continue;
    const double lo = std::min(a.error, b.error), hi = std::max(a.error, b.error);
    if (!(lo <= E && E <= hi) || !(lo > 0)) continue;
    const double w = hi == lo ? 0 : (std::log(E) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    const double t = std::exp(std::log(a.time.median) + w * (std::log(b.time.median) - std::log(a.time.median)));
    best = best ? std::min(*best, t) : t;
  }
  return best;
}

void table(std::ostream& md, const std::vector<Cell>& cells, const char* error_name) {
  md << "| method | reltol | abstol | " << error_name << " | time, ms: median (min–max of " << (quick ? 3 : 7)
     << ") | f evaluations |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  for (const Cell& c : cells)
    md << "| " << c.method << " | 1e-" << c.k << " | 1e-" << c.k + 3 << " | " << fmt("%.2e", c.error) << " | "
       << ms(c.time) << " | " << c.evaluations << " |\n";
}

// The fastest method at each decade of error, and whether SciML's ordering
// holds there: tsit5 faster than dopri5, and the fastest of tsit5 and vern6–9
// faster than the fastest of dopri5 and bs3. Returns the decades where it
// holds and where it does not, as text.
std::pair<std::string, std::string> ranking(std::ostream& md, const std::vector<Cell>& cells,
                                            const std::vector<Method>& ms_) {
  std::string holds, fails;
  md << "| error E | fastest (ms at E) | then | tsit5 / dopri5 time | fastest of tsit5, vern6–9 | fastest of dopri5, "
        "bs3 | SciML order holds |\n"
     << "|---:|---|---|---:|---:|---:|:-:|\n";
  for (int e = 2; e <= 13; ++e) {
    const double E = std::pow(10.0, -e);
    std::vector<std::pair<double, std::string>> at;
    for (const Method& m : ms_)
      if (const auto t = time_at(cells, m.name, E)) at.emplace_back(*t, m.name);
    if (at.size() < 2) continue;
    std::sort(at.begin(), at.end());
    auto best_of = [&](std::initializer_list<const char*> names) -> std::optional<std::pair<double, std::string>> {
      for (const auto& p : at)
        for (const char* n : names)
          if (p.second == n) return p;
      return std::nullopt;
    };
    const auto mine = best_of({"tsit5", "vern6", "vern7", "vern8", "vern9"}), old = best_of({"dopri5", "bs3"});
    const auto tsit5 = best_of({"tsit5"}), dopri5 = best_of({"dopri5"});
    const bool both = mine && old, ratio = tsit5 && dopri5;
    const bool ok = both && mine->first < old->first && (!ratio || tsit5->first < dopri5->first);
    md << "| 1e-" << e << " | " << at[0].second << " (" << fmt("%.3g", 1e3 * at[0].first) << ") | " << at[1].second << " ("
       << fmt("%.3g", 1e3 * at[1].first) << ") | " << (ratio ? fmt("%.2f", tsit5->first / dopri5->first) : "–") << " | "
       << (mine ? mine->second + " " + fmt("%.3g", 1e3 * mine->first) : std::string("–")) << " | "
       << (old ? old->second + " " + fmt("%.3g", 1e3 * old->first) : std::string("–")) << " | "
       << (both ? (ok ? "yes" : "no") : "–") << " |\n";
    if (both) (ok ? holds : fails) += (ok ? holds : fails).empty() ? "1e-" + std::to_string(e) : ", 1e-" + std::to_string(e);
  }
  return {holds, fails};
}

std::string verdict(const std::pair<std::string, std::string>& r) {
  if (r.second.empty()) return "The ordering agrees with SciML's at every error level both groups reach (" + r.first + ").";
  return "The ordering agrees with SciML's at " + (r.first.empty() ? std::string("no error level") : r.first) +
         " and does not at " + r.second + ".";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && !std::strcmp(argv[1], "--quick")) {
    quick = true;
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: rigid_body_sciml [--quick]\n");
    return 2;
  }
  const Result ref_final = ours(core::SolverMethod::vern9, 1e-14, 1e-14, false);
  const Result ref_saved = ours(core::SolverMethod::vern9, 1e-14, 1e-14, true);
  const Result check = peer(odeint::make_controlled(1e-14, 1e-14, odeint::runge_kutta_fehlberg78<State>()), true);
  double apart = 0;
  for (std::size_t k = 0; k < check.states.size(); ++k)
    for (int i = 0; i < 3; ++i) apart = std::max(apart, std::abs(check.states[k][i] - ref_saved.states[k][i]));

  const auto all = methods();
  std::vector<Cell> finals, saved;
  for (const Method& m : all)
    for (int k = 3; k <= 12; ++k) {
      const double rel = std::pow(10.0, -k), abs = std::pow(10.0, -(k + 3));
      const Result f = m.run(abs, rel, false), s = m.run(abs, rel, true);
      finals.push_back({m.name, k, final_error(f, ref_final), time_of([&] { m.run(abs, rel, false); }), f.evaluations});
      saved.push_back({m.name, k, l2_error(s, ref_saved), time_of([&] { m.run(abs, rel, true); }), s.evaluations});
      std::fprintf(stderr, "%s 1e-%d\n", m.name.c_str(), k);
    }

  std::ostream& md = std::cout;
  md << "<!-- part: reference -->\n"
     << "Reference: vern9 at abs = rel = 1e-14; Odeint's Runge–Kutta–Fehlberg 7(8) at 1e-14 agrees with it to "
     << fmt("%.1e", apart) << " at the 100 save points.\n";
  md << "<!-- part: final -->\n";
  table(md, finals, "final error");
  md << "<!-- part: final-ranking -->\n";
  const auto final_order = ranking(md, finals, all);
  md << "\n" << verdict(final_order) << "\n";
  md << "<!-- part: saved -->\n";
  table(md, saved, "L2 error");
  md << "<!-- part: saved-ranking -->\n";
  const auto saved_order = ranking(md, saved, all);
  md << "\n" << verdict(saved_order) << "\n";
  return 0;
}
