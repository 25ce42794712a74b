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
