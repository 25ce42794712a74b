#include "compare/results.hpp"

#include "compare/stats.hpp"
#include "core/parallel.hpp"
#include "core/model/model.hpp"

#include <cmath>

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json vec(const Eigen::Vector4d& v) { return json::array({v[0], v[1], v[2], v[3]}); }

// Appends key: value to an object whose keys are known to differ (the
// scene's names, unique by load): ordered_json's operator[] searches the keys
// one by one, which made a sample of N bodies cost N² string compares (a
// fifth of an 8,000-body run, most of a 100,000-body one).
void append_unique(json& object, const std::string& key, json value) {
  std::vector<std::pair<const std::string, json>>& items = object.get_ref<json::object_t&>();
  items.emplace_back(key, std::move(value));
}

json sample_json(const core::Scene& scene, const core::Sample& s) {
  json particles = json::object();
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    append_unique(particles, scene.particles[i].name,
                  {{"position", vec(s.particles[i].position)}, {"velocity", vec(s.particles[i].velocity)}});
  json bodies = json::object();
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    append_unique(bodies, scene.bodies[i].name,
                  {{"position", vec(s.bodies[i].position)},
                   {"orientation", vec(s.bodies[i].orientation)},
                   {"velocity", vec(s.bodies[i].velocity)},
                   {"angular_velocity", vec(s.bodies[i].angular_velocity)}});
  return {{"t", s.t},
          {"particles", particles},
          {"bodies", bodies},
          {"energy", {{"kinetic", s.kinetic}, {"potential", s.potential}}},
          {"linear_momentum", vec(s.linear_momentum)},
          {"angular_momentum", vec(s.angular_momentum)},
          {"constraint_violation", s.constraint_violation},
          {"rotation_drift", s.rotation_drift}};
}

// What the replay draws and `diff` bounds, beside the samples: each body's
// mesh in body coordinates (about its centre of mass, as its samples' position
// and orientation place it: world = R(q) v + x), its radius and whether it is
// static; the particles in sample order; the constraints with their geometry.
json bodies_json(const core::Scene& scene, const core::Model& model) {
  json bodies = json::array();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const core::Body& b = scene.bodies[i];
    const core::Mesh& mesh = *model.bodies[i].mesh;  // about the centre of mass
    json vertices = json::array(), triangles = json::array();
    for (const core::Vec3& v : mesh.vertices()) vertices.push_back(vec(v));
    for (const auto& t : mesh.triangles()) triangles.push_back({t[0], t[1], t[2]});
    bodies.push_back({{"name", b.name}, {"static", b.is_static}, {"radius", model.bodies[i].radius}, {"vertices", vertices},
                      {"triangles", triangles}});
  }
  return bodies;
}

json constraints_json(const core::Scene& scene) {
  json out = json::array();
  for (const auto& c : scene.constraints) {
    json j = {{"type", std::string(core::constraint_name(c))}};
    std::visit(
        [&](const auto& k) {
          using K = std::decay_t<decltype(k)>;
          if constexpr (std::is_same_v<K, core::DistanceBetween>) {
            j["particles"] = {k.a, k.b};
            j["length"] = k.length;
          } else {
            j["particles"] = {k.particle};
            if constexpr (std::is_same_v<K, core::DistanceToPoint>) j["point"] = vec(k.point), j["length"] = k.length;
            if constexpr (std::is_same_v<K, core::OnPlane>) j["point"] = vec(k.point), j["normal"] = vec(k.normal);
            if constexpr (std::is_same_v<K, core::OnLine>) j["point"] = vec(k.point), j["direction"] = vec(k.direction);
            if constexpr (std::is_same_v<K, core::OnCircle>)
              j["center"] = vec(k.center), j["normal"] = vec(k.normal), j["radius"] = k.radius;
            if constexpr (std::is_same_v<K, core::OnHelix>)
              j["center"] = vec(k.center), j["axis"] = vec(k.axis), j["radius"] = k.radius, j["pitch"] = k.pitch;
          }
        },
        c);
    out.push_back(j);
  }
  return out;
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
            {"deterministic", b.deterministic},
            {"state_hash", core::state_hash(run)}};
  if (run.error) j["error"] = *run.error;
  return j;
}
}  // namespace

nlohmann::ordered_json scene_json(const core::Scene& scene, const core::Model& model) {
  json particles = json::array();
  for (const auto& p : scene.particles) particles.push_back(p.name);
  return {{"name", scene.name},
          {"description", scene.description},
          {"file", scene.file.string()},
          {"sha256", scene.sha256},
          {"duration", scene.duration},
          {"output_every", scene.output_every},
          {"check", {{"max_divergence", scene.check.max_divergence}, {"baseline_tolerance", scene.check.baseline_tolerance}}},
          {"particles", particles},
          {"bodies", bodies_json(scene, model)},
          {"constraints", constraints_json(scene)}};
}

nlohmann::ordered_json machine_json(const MachineInfo& m) {
  const auto dirty = m.build.dirty == "yes" ? json(true) : m.build.dirty == "no" ? json(false) : json(nullptr);
  return {{"cpu", m.cpu},
          {"logical_cpus", m.logical_cpus},
          {"usable_cpus", m.usable_cpus},
          {"threads", core::threads()},
          {"load_average", {{"start", m.load_average}, {"end", m.load_average_end}}},
          {"compiler", m.compiler},
          {"build_type", m.build_type},
          {"flags", m.flags},
          {"allocator", m.allocator},
          {"git", {{"commit", m.build.commit}, {"dirty", dirty}}},
          {"date", m.date}};
}

nlohmann::ordered_json results_json(const SceneResult& r, const MachineInfo& machine, int repeats) {
  json runs = json::array();
  for (const auto& b : r.backends) runs.push_back(run_json(r.scene, b));
  return {{"tool", {{"name", "gacompare"}, {"version", tool_version()}}},
          {"scene", scene_json(r.scene, *r.model)},
          {"machine", machine_json(machine)},
          {"repeats", repeats},
          {"runs", runs},
          {"divergence",
           {{"max_position_difference", max_divergence(r)},
            {"max_orientation_difference_rad", max_orientation_divergence(r)}}}};
}

}  // namespace gacompare::compare
