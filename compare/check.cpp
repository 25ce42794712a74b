#include "compare/check.hpp"

#include "compare/escape.hpp"
#include "compare/files.hpp"
#include "compare/machine.hpp"
#include "compare/metrics.hpp"
#include "compare/results.hpp"
#include "compare/sanity.hpp"
#include "compare/stats.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <cstdio>
#include <sstream>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json vec(const Eigen::Vector4d& v) { return json::array({v[0], v[1], v[2], v[3]}); }

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

CheckLine bound(const std::string& scene, const std::string& backend, const std::string& what, double value,
                double limit) {
  CheckLine l{scene, backend, what, value, limit, value <= limit ? CheckLine::Verdict::pass : CheckLine::Verdict::fail, ""};
  if (!std::isfinite(value)) l.verdict = CheckLine::Verdict::fail;
  return l;
}

// "orientation divergence between backends (rad)"; position keeps its first name.
std::string line_name(Measure m, const char* position_name, const char* rest) {
  if (m == Measure::position) return position_name;
  return std::string(measure_words(m)) + rest + " (" + std::string(measure_unit(m)) + ")";
}

}  // namespace

CheckLine time_ratio_line(const std::string& scene, const std::string& backend, const std::string& what,
                          std::span<const double> before, std::span<const double> after,
                          std::optional<double> max_ratio, const std::string& why_none) {
  const RatioInterval r = bootstrap_unpaired_ratio(before, after);
  CheckLine l{scene, backend, what, r.ratio, max_ratio.value_or(0),
              max_ratio ? CheckLine::Verdict::pass : CheckLine::Verdict::info, ""};
  if (std::isnan(r.lo)) {
    l.note = "no interval: " + (why_none.empty() ? std::string("fewer than 2 repeats") : why_none);
    if (max_ratio) l.verdict = CheckLine::Verdict::fail;
    return l;
  }
  l.note = "95% interval [" + fmt(r.lo) + ", " + fmt(r.hi) + "], " +
           (r.lo <= 1 && 1 <= r.hi ? "within noise" : r.lo > 1 ? "slower" : "faster");
  if (max_ratio && r.lo > *max_ratio) {
    l.verdict = CheckLine::Verdict::fail;
    l.note += "; the whole interval lies above " + fmt(*max_ratio);
  }
  if (!max_ratio) l.note += "; reported, not checked (--max-time-ratio R checks it)";
  return l;
}

StateObjects state_objects(const core::Scene& scene, const core::Model& model) {
  StateObjects o{scene.name, scene.output_every, {}, {}};
  for (const auto& p : scene.particles) o.particles.push_back(p.name);
  const std::vector<double> radii = body_radii(model);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    o.bodies.push_back({scene.bodies[i].name, radii[i], scene.bodies[i].is_static});
  return o;
}

void StateBounds::add(const core::Sample& a, const core::Sample& b) {
  for (std::size_t i = 0; i < std::min({a.particles.size(), b.particles.size(), objects_.particles.size()}); ++i) {
    const StateErrors e = particle_difference(a.particles[i], b.particles[i]);
    const std::string who = "particle '" + objects_.particles[i] + "'";
    for (const Measure m : {Measure::position, Measure::velocity}) take(m, e[m], allowed(m, 1), who, a.t);
  }
  for (std::size_t i = 0; i < std::min({a.bodies.size(), b.bodies.size(), objects_.bodies.size()}); ++i) {
    const auto& body = objects_.bodies[i];
    if (body.is_static) continue;
    const StateErrors e = body_difference(a.bodies[i], b.bodies[i]);
    const std::string who = "body '" + body.name + "' (r = " + fmt(body.radius) + " m)";
    for (const Measure m : kMeasures) take(m, e[m], allowed(m, body.radius), who, a.t);
  }
}

std::optional<CheckLine> StateBounds::line(Measure m, const std::string& backend, const std::string& what,
                                           const std::string& d_name) const {
  const Worst& w = worst_[static_cast<std::size_t>(m)];
  if (w.where.empty()) return std::nullopt;
  static constexpr const char* rule[] = {"", " / r", " / Δt", " / (r Δt)"};
  CheckLine l = bound(objects_.scene, backend, what, w.value, w.bound);
  l.note = (w.value == 0 ? std::string("equal everywhere") : "worst: " + w.where) + "; bound " + d_name +
           rule[static_cast<std::size_t>(m)];
  return l;
}

double StateBounds::allowed(Measure m, double r) const {
  const double dt = objects_.output_every;
  switch (m) {
    case Measure::position: return d_;
    case Measure::orientation: return d_ / r;
    case Measure::velocity: return d_ / dt;
    case Measure::angular_velocity: return d_ / (r * dt);
  }
  return d_;
}

void StateBounds::take(Measure m, double value, double limit, const std::string& who, double t) {
  Worst& w = worst_[static_cast<std::size_t>(m)];
  const double ratio = value / limit;
  // The first object, then a larger ratio; a NaN (a diverged run) wins and stays.
  if (!w.where.empty() && (std::isnan(w.ratio) || !(std::isnan(ratio) || ratio > w.ratio))) return;
  w = {value, limit, ratio, who + " at t = " + fmt(t) + " s"};
}

namespace {

// A baseline run's final sample as a Sample of `scene`; nullopt when its
// particles or bodies are not the scene's.
std::optional<core::Sample> baseline_sample(const core::Scene& scene, const BaselineRun& base) {
  if (base.particles.size() != scene.particles.size() || base.bodies.size() != scene.bodies.size()) return std::nullopt;
  core::Sample s;
  s.t = base.t;
  for (const auto& p : scene.particles) {
    const auto it = base.particles.find(p.name);
    if (it == base.particles.end()) return std::nullopt;
    s.particles.push_back(it->second);
  }
  for (const auto& b : scene.bodies) {
    const auto it = base.bodies.find(b.name);
    if (it == base.bodies.end()) return std::nullopt;
    s.bodies.push_back(it->second);
  }
  return s;
}
}  // namespace

std::filesystem::path baseline_path(const std::filesystem::path& dir, const std::string& scene) {
  return dir / (file_name_for(scene) + ".json");  // compare/files.hpp: a name is never a path
}

json baseline_json(const SceneResult& r) {
  json runs = json::array();
  for (const auto& b : r.backends) {
    json particles = json::object(), bodies = json::object();
    if (!b.run.samples.empty()) {
      const auto& last = b.run.samples.back();
      for (std::size_t i = 0; i < last.particles.size(); ++i)
        particles[r.scene.particles[i].name] = {{"position", vec(last.particles[i].position)},
                                                {"velocity", vec(last.particles[i].velocity)}};
      for (std::size_t i = 0; i < last.bodies.size(); ++i)
        bodies[r.scene.bodies[i].name] = {{"position", vec(last.bodies[i].position)},
                                          {"orientation", vec(last.bodies[i].orientation)},
                                          {"velocity", vec(last.bodies[i].velocity)},
                                          {"angular_velocity", vec(last.bodies[i].angular_velocity)}};
    }
    runs.push_back({{"backend", b.run.backend},
                    {"final", {{"t", b.run.samples.empty() ? 0.0 : b.run.samples.back().t},
                               {"particles", particles},
                               {"bodies", bodies}}},
                    {"wall_seconds", spread(b.wall_seconds).median},
                    {"wall_seconds_each_repeat", b.wall_seconds}});
  }
  return {{"scene", r.scene.name},
          {"sha256", r.scene.sha256},
          {"tool", {{"version", tool_version()}}},
          {"machine", machine_json(machine_info())},
          {"runs", runs}};
}

std::vector<CheckLine> check_scene(const SceneResult& r, const std::optional<Baseline>& baseline,
                                   std::optional<double> max_time_ratio) {
  std::vector<CheckLine> out;
  const auto& spec = r.scene.check;
  const std::string& name = r.scene.name;
  for (const auto& b : r.backends) {
    const auto& run = b.run;
    if (run.error) {
      out.push_back({name, run.backend, "run", 0, 0, CheckLine::Verdict::fail, *run.error});
      continue;
    }
    if (spec.max_energy_drift) out.push_back(bound(name, run.backend, "energy drift", energy_drift(run), *spec.max_energy_drift));
    double violation = 0, drift = 0;
    for (const auto& s : run.samples) {
      violation = std::max(violation, s.constraint_violation);
      drift = std::max(drift, s.rotation_drift);
    }
    if (spec.max_constraint_violation)
      out.push_back(bound(name, run.backend, "constraint violation (m)", violation, *spec.max_constraint_violation));
    if (spec.max_rotation_drift) out.push_back(bound(name, run.backend, "rotation drift", drift, *spec.max_rotation_drift));
    // Where the scene says its bodies come to rest: the farthest each is from
    // its rest position at any sample from `after` on.
    for (const auto& rest : spec.rest) {
      const auto body = std::find_if(r.scene.bodies.begin(), r.scene.bodies.end(),
                                     [&](const core::Body& b) { return b.name == rest.body; });
      const auto k = static_cast<std::size_t>(body - r.scene.bodies.begin());
      double farthest = 0;
      bool seen = false;
      for (const auto& s : run.samples)
        if (s.t >= spec.rest_after && k < s.bodies.size())
          farthest = std::max(farthest, (s.bodies[k].position - rest.position).norm()), seen = true;
      if (!seen) farthest = INFINITY;  // a run that never reached `after` has not come to rest
      std::string what = "rest of ";
      what += rest.body;
      what += " (m)";
      out.push_back(bound(name, run.backend, what, farthest, spec.rest_tolerance));
    }
    // Physical sanity (compare/sanity.hpp): what agreement between backends and
    // with a baseline cannot see, since both may be wrong the same way.
    for (auto& l : sanity_checks(r.scene, *r.model, run)) out.push_back(std::move(l));
  }
  if (r.backends.size() > 1) {  // the first backend against each other one but Bullet (compare/metrics.hpp says why)
    StateBounds between(state_objects(r.scene, *r.model), spec.max_divergence);
    for (std::size_t b = 1; b < r.backends.size(); ++b) {
      if (r.backends[b].run.backend == "bullet") continue;
      const auto& x = r.backends[0].run.samples;
      const auto& y = r.backends[b].run.samples;
      for (std::size_t k = 0; k < std::min(x.size(), y.size()); ++k) between.add(x[k], y[k]);
    }
    for (const Measure m : kMeasures) {
      const auto what = line_name(m, "divergence between backends (m)", " divergence between backends");
      if (auto l = between.line(m, "all", what, "max_divergence")) out.push_back(*l);
    }
  }

  if (!baseline) return out;
  if (baseline->sha256 != r.scene.sha256 || baseline->scene != r.scene.name) {
    out.push_back({name, "all", "baseline", 0, 0, CheckLine::Verdict::fail,
                   baseline->scene != r.scene.name
                       ? "the baseline is of another scene (" + baseline->scene + "); refresh it with --update"
                       : "the scene file changed since its baseline was stored (sha256 differs); refresh it with --update"});
    return out;
  }
  for (const auto& b : r.backends) {
    const BaselineRun* base = nullptr;
    for (const auto& run : baseline->runs)
      if (run.backend == b.run.backend) base = &run;
    if (!base) {  // a baseline that lacks a backend checks less than it should: never a pass by omission
      out.push_back({name, b.run.backend, "baseline", 0, 0, CheckLine::Verdict::fail,
                     "the baseline stores no run of this backend; store one with --update"});
      continue;
    }
    if (b.run.error || b.run.samples.empty()) continue;
    // The same scene samples at the same times: a final time that differs is
    // another run's state (relative 1e-12: a time is k · every, computed alike).
    const double now_t = b.run.samples.back().t;
    if (!(std::abs(base->t - now_t) <= 1e-12 * std::max(1.0, std::abs(now_t)))) {
      out.push_back({name, b.run.backend, "baseline", 0, 0, CheckLine::Verdict::fail,
                     "the baseline's final state is at t = " + fmt(base->t) + " s, this run's at t = " + fmt(now_t) +
                         " s; refresh it with --update"});
      continue;
    }
    const bool velocities = base->velocities;
    const auto stored = baseline_sample(r.scene, *base);
    if (!stored) {
      out.push_back({name, b.run.backend, "distance from baseline, final state (m)", INFINITY, spec.baseline_tolerance,
                     CheckLine::Verdict::fail, "the scene's particles or bodies differ from the baseline's"});
      continue;
    }
    StateBounds from(state_objects(r.scene, *r.model), spec.baseline_tolerance);
    from.add(b.run.samples.back(), *stored);
    for (const Measure m : kMeasures) {
      const auto what = line_name(m, "distance from baseline, final state (m)", " from baseline, final state");
      if (!velocities && (m == Measure::velocity || m == Measure::angular_velocity)) continue;
      if (auto l = from.line(m, b.run.backend, what, "baseline_tolerance")) out.push_back(*l);
    }
    if (!velocities)
      out.push_back({name, b.run.backend, "velocities from baseline", 0, 0, CheckLine::Verdict::info,
                     "not checked: this baseline stores no velocities (stored before they were); refresh it with --update"});
    const double then = base->wall_seconds, now = spread(b.wall_seconds).median;
    if (!max_time_ratio) {
      if (then > 0)
        out.push_back({name, b.run.backend, "time / baseline time", now / then, 0, CheckLine::Verdict::info,
                       "reported, not checked (--max-time-ratio R checks it)"});
      continue;
    }
    const std::vector<double>& before = base->wall_seconds_each_repeat;
    out.push_back(time_ratio_line(name, b.run.backend, "time / baseline time", before, b.wall_seconds,
                                  max_time_ratio,
                                  before.size() < 2 ? "this baseline stores no repeats' times; refresh it with --update"
                                                    : ""));
  }
  return out;
}

std::string check_table(const std::vector<CheckLine>& lines) {
  std::ostringstream o;
  o << "| scene | backend | check | value | bound | result |\n|---|---|---|---:|---:|---|\n";
  for (const auto& l : lines) {
    const char* v = l.verdict == CheckLine::Verdict::pass ? "pass" : l.verdict == CheckLine::Verdict::fail ? "**FAIL**" : "info";
    o << "| " << md_text(l.scene) << " | " << md_text(l.backend) << " | " << md_text(l.what) << " | "
      << (l.verdict == CheckLine::Verdict::info && l.value == 0 ? std::string("–") : fmt(l.value)) << " | "
      << (l.verdict == CheckLine::Verdict::info ? std::string("–") : l.what == "run" || l.what == "baseline" ? std::string("–") : fmt(l.bound))
      << " | " << v << (l.note.empty() ? "" : ": " + md_text(l.note)) << " |\n";
  }
  return o.str();
}

}  // namespace gacompare::compare
