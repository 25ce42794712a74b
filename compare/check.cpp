#include "compare/check.hpp"

#include "compare/machine.hpp"
#include "compare/results.hpp"
#include "compare/sanity.hpp"
#include "compare/stats.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json vec(const Eigen::Vector4d& v) { return json::array({v[0], v[1], v[2], v[3]}); }

Eigen::Vector3d vec3(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

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

// Largest distance between the final positions of a run and a baseline run.
double baseline_distance(const core::Scene& scene, const core::Sample& last, const nlohmann::json& base) {
  double worst = 0;
  const auto& ps = base.at("final").at("particles");
  if (ps.size() != last.particles.size()) return INFINITY;
  for (std::size_t i = 0; i < last.particles.size(); ++i)
    worst = std::max(worst, (last.particles[i].position - vec3(ps.at(scene.particles[i].name))).norm());
  const auto& bs = base.at("final").at("bodies");
  if (bs.size() != last.bodies.size()) return INFINITY;
  for (std::size_t i = 0; i < last.bodies.size(); ++i)
    worst = std::max(worst, (last.bodies[i].position - vec3(bs.at(scene.bodies[i].name).at("position"))).norm());
  return worst;
}
}  // namespace

std::filesystem::path baseline_path(const std::filesystem::path& dir, const std::string& scene) {
  return dir / (scene + ".json");
}

json baseline_json(const SceneResult& r) {
  json runs = json::array();
  for (const auto& b : r.backends) {
    json particles = json::object(), bodies = json::object();
    if (!b.run.samples.empty()) {
      const auto& last = b.run.samples.back();
      for (std::size_t i = 0; i < last.particles.size(); ++i)
        particles[r.scene.particles[i].name] = vec(last.particles[i].position);
      for (std::size_t i = 0; i < last.bodies.size(); ++i)
        bodies[r.scene.bodies[i].name] = {{"position", vec(last.bodies[i].position)},
                                          {"orientation", vec(last.bodies[i].orientation)}};
    }
    runs.push_back({{"backend", b.run.backend},
                    {"final", {{"t", b.run.samples.empty() ? 0.0 : b.run.samples.back().t},
                               {"particles", particles},
                               {"bodies", bodies}}},
                    {"wall_seconds", spread(b.wall_seconds).median}});
  }
  return {{"scene", r.scene.name},
          {"sha256", r.scene.sha256},
          {"tool", {{"version", tool_version()}}},
          {"machine", {{"cpu", machine_info().cpu}, {"compiler", machine_info().compiler}}},
          {"runs", runs}};
}

std::vector<CheckLine> check_scene(const SceneResult& r, const std::optional<nlohmann::json>& baseline) {
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
    // Physical sanity (compare/sanity.hpp): what agreement between backends and
    // with a baseline cannot see, since both may be wrong the same way.
    for (auto& l : sanity_checks(r.scene, run)) out.push_back(std::move(l));
  }
  if (r.backends.size() > 1) {
    out.push_back(bound(name, "all", "divergence between backends (m)", max_divergence(r), spec.max_divergence));
    const double angle = max_orientation_divergence(r);
    if (angle > 0)
      out.push_back({name, "all", "orientation divergence (rad)", angle, 0, CheckLine::Verdict::info,
                     "reported, not checked: the representations round differently and a rotation near an unstable axis amplifies it"});
  }

  if (!baseline) return out;
  if (baseline->value("sha256", "") != r.scene.sha256) {
    out.push_back({name, "all", "baseline", 0, 0, CheckLine::Verdict::fail,
                   "the scene file changed since its baseline was stored (sha256 differs); refresh it with --update"});
    return out;
  }
  for (const auto& b : r.backends) {
    const nlohmann::json* base = nullptr;
    for (const auto& run : baseline->at("runs"))
      if (run.at("backend") == b.run.backend) base = &run;
    if (!base) {
      out.push_back({name, b.run.backend, "baseline", 0, 0, CheckLine::Verdict::info, "no stored run for this backend"});
      continue;
    }
    if (b.run.error || b.run.samples.empty()) continue;
    const double d = baseline_distance(r.scene, b.run.samples.back(), *base);
    CheckLine l = bound(name, b.run.backend, "distance from baseline, final state (m)", d, spec.baseline_tolerance);
    if (!std::isfinite(d)) l.note = "the scene's particles or bodies differ from the baseline's";
    out.push_back(l);
    const double then = base->value("wall_seconds", 0.0), now = spread(b.wall_seconds).median;
    if (then > 0)
      out.push_back({name, b.run.backend, "time / baseline time", now / then, 0, CheckLine::Verdict::info,
                     "timing is reported, never checked"});
  }
  return out;
}

std::string check_table(const std::vector<CheckLine>& lines) {
  std::ostringstream o;
  o << "| scene | backend | check | value | bound | result |\n|---|---|---|---:|---:|---|\n";
  for (const auto& l : lines) {
    const char* v = l.verdict == CheckLine::Verdict::pass ? "pass" : l.verdict == CheckLine::Verdict::fail ? "**FAIL**" : "info";
    o << "| " << l.scene << " | " << l.backend << " | " << l.what << " | "
      << (l.verdict == CheckLine::Verdict::info && l.value == 0 ? std::string("–") : fmt(l.value)) << " | "
      << (l.verdict == CheckLine::Verdict::info ? std::string("–") : l.what == "run" || l.what == "baseline" ? std::string("–") : fmt(l.bound))
      << " | " << v << (l.note.empty() ? "" : ": " + l.note) << " |\n";
  }
  return o.str();
}

}  // namespace gacompare::compare
