#include "compare/results.hpp"

#include "compare/stats.hpp"

#include <cmath>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json vec(const Eigen::Vector4d& v) { return json::array({v[0], v[1], v[2], v[3]}); }

json sample_json(const core::Scene& scene, const core::Sample& s) {
  json particles = json::object();
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    particles[scene.particles[i].name] = {{"position", vec(s.particles[i].position)},
                                          {"velocity", vec(s.particles[i].velocity)}};
  json bodies = json::object();
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    bodies[scene.bodies[i].name] = {{"position", vec(s.bodies[i].position)},
                                    {"orientation", vec(s.bodies[i].orientation)},
                                    {"velocity", vec(s.bodies[i].velocity)},
                                    {"angular_velocity", vec(s.bodies[i].angular_velocity)}};
  return {{"t", s.t},
          {"particles", particles},
          {"bodies", bodies},
          {"energy", {{"kinetic", s.kinetic}, {"potential", s.potential}}},
          {"linear_momentum", vec(s.linear_momentum)},
          {"angular_momentum", vec(s.angular_momentum)},
          {"constraint_violation", s.constraint_violation},
          {"rotation_drift", s.rotation_drift}};
}

json spread_json(const Spread& s) { return {{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

json run_json(const core::Scene& scene, const BackendResult& b) {
  const core::Run& run = b.run;
  json samples = json::array();
  for (const auto& s : run.samples) samples.push_back(sample_json(scene, s));
  json stages = json::object();
  for (int k = 0; k < core::kStageCount; ++k) {
    const auto stage = static_cast<core::Stage>(k);
    if (!run.profile.ran(stage)) continue;
    std::vector<double> secs;
    for (const auto& p : b.profiles) secs.push_back(p[stage].seconds);
    const Spread sp = spread(secs);
    stages[std::string(core::stage_name(stage))] = {{"seconds", sp.median},
                                                    {"seconds_min", sp.min},
                                                    {"seconds_max", sp.max},
                                                    {"seconds_each_repeat", secs},
                                                    {"calls", run.profile[stage].calls}};
  }
  json j = {{"backend", run.backend},
            {"samples", samples},
            {"stages", stages},
            {"wall_seconds", spread_json(spread(b.wall_seconds))},
            {"solver",
             {{"method", core::to_string(scene.solver.method)},
              {"steps_accepted", run.solver.steps_accepted},
              {"steps_rejected", run.solver.steps_rejected},
              {"derivative_evaluations", run.solver.derivative_evaluations},
              {"min_step", run.solver.steps_accepted ? run.solver.min_step : 0.0},
              {"max_step", run.solver.max_step}}},
            {"counters", run.counters},
            {"metrics", run.metrics},
            {"deterministic", b.deterministic}};
  if (run.error) j["error"] = *run.error;
  return j;
}
}  // namespace

double energy_drift(const core::Run& run) {
  if (run.samples.empty()) return 0;
  const double e0 = run.samples.front().kinetic + run.samples.front().potential;
  double worst = 0, scale = std::abs(e0);
  for (const auto& s : run.samples) {
    worst = std::max(worst, std::abs(s.kinetic + s.potential - e0));
    scale = std::max({scale, std::abs(s.kinetic), std::abs(s.potential)});
  }
  return scale > 0 ? worst / scale : 0.0;
}

double position_difference(const core::Sample& a, const core::Sample& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.particles.size(); ++i)
    worst = std::max(worst, (a.particles[i].position - b.particles[i].position).norm());
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    worst = std::max(worst, (a.bodies[i].position - b.bodies[i].position).norm());
  return worst;
}

double orientation_difference(const core::Sample& a, const core::Sample& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    worst = std::max(worst, 2 * std::acos(std::min(1.0, std::abs(a.bodies[i].orientation.dot(b.bodies[i].orientation)))));
  return worst;
}

namespace {
// The largest `diff` between the first backend and each other one, over all
// samples. Bullet is left out: it is a reference with another integrator and
// contact model, not a third algebra (its agreement is the report's Bullet
// table), and the divergence is what `check` bounds between our backends.
double max_over_runs(const SceneResult& r, double (*diff)(const core::Sample&, const core::Sample&)) {
  double worst = 0;
  for (std::size_t b = 1; b < r.backends.size(); ++b) {
    if (r.backends[b].run.backend == "bullet") continue;
    const auto& a = r.backends[0].run.samples;
    const auto& c = r.backends[b].run.samples;
    for (std::size_t k = 0; k < std::min(a.size(), c.size()); ++k) worst = std::max(worst, diff(a[k], c[k]));
  }
  return worst;
}
}  // namespace

double max_divergence(const SceneResult& r) { return max_over_runs(r, position_difference); }
double max_orientation_divergence(const SceneResult& r) { return max_over_runs(r, orientation_difference); }

nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats) {
  json runs = json::array();
  for (const auto& b : r.backends) runs.push_back(run_json(r.scene, b));
  return {{"tool", {{"name", "gacompare"}, {"version", tool_version()}}},
          {"scene",
           {{"name", r.scene.name},
            {"description", r.scene.description},
            {"file", r.scene.file.string()},
            {"sha256", r.scene.sha256}}},
          {"machine",
           {{"cpu", machine.cpu}, {"compiler", machine.compiler}, {"date", machine.date},
            {"build_type", machine.build_type}}},
          {"repeats", repeats},
          {"runs", runs},
          {"divergence",
           {{"max_position_difference", max_divergence(r)},
            {"max_orientation_difference_rad", max_orientation_divergence(r)}}}};
}

}  // namespace gacompare::compare
