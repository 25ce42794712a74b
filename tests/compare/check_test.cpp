// `gacompare check` on hand-made runs: between backends and against a stored
// baseline it bounds position, orientation, velocity and angular velocity, each
// by the distance no point of a body may move (check.max_divergence between
// backends, check.baseline_tolerance against a baseline): d, d / r, d / Δt and
// d / (r Δt), r the body's radius about its centre of mass, Δt the output
// interval. Each case sits 10% inside and 10% outside its bound.
#include "compare/check.hpp"
#include "compare/metrics.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace {
using namespace gacompare;
using compare::CheckLine;
using core::Vec3;

constexpr double kDt = 0.01;

// A baseline as `check` reads it from its file (compare/stored.hpp).
compare::Baseline read_back(const nlohmann::ordered_json& stored) {
  return compare::parse_baseline(nlohmann::json::parse(stored.dump()), "baseline.json");
}

// A 0.2 m cube (r = √3 · 0.1 m) and a particle, both at rest, with a static slab
// that never moves; default check bounds (1e-6 m between backends, 1e-9 m from a baseline).
core::Scene scene() {
  core::Scene s;
  s.name = "hand";
  s.output_every = kDt;
  s.duration = 0.1;
  core::Body cube;
  cube.name = "cube";
  cube.shape = core::BoxShape{{0.2, 0.2, 0.2}};
  cube.mass = 1;
  core::Body slab = cube;
  slab.name = "slab";
  slab.shape = core::BoxShape{{2, 2, 0.2}};
  slab.is_static = true;
  s.bodies = {cube, slab};
  core::Particle p;
  p.name = "dot";
  p.mass = 1;
  s.particles = {p};
  return s;
}

using Change = std::function<void(core::Sample&)>;

core::Run run(const core::Scene& s, const std::string& backend, const Change& change = {}) {
  core::Run r;
  r.backend = backend;
  for (int k = 0; k <= 10; ++k) {
    core::Sample smp;
    smp.t = k * kDt;
    smp.particles.resize(1);
    smp.bodies.resize(s.bodies.size());
    if (change && k == 7) change(smp);  // one sample differs
    r.samples.push_back(smp);
  }
  return r;
}

compare::SceneResult result(const Change& cga_change, const Change& bullet_change = {}) {
  const core::Scene s = scene();
  compare::SceneResult r{s, {}, std::make_shared<const core::Model>(core::compile(s))};
  r.backends.push_back({run(s, "traditional"), {{}}, {1.0}, true});
  r.backends.push_back({run(s, "cga", cga_change), {{}}, {1.0}, true});
  if (bullet_change) r.backends.push_back({run(s, "bullet", bullet_change), {{}}, {1.0}, true});
  return r;
}

const CheckLine& line(const std::vector<CheckLine>& lines, const std::string& backend, const std::string& what) {
  for (const auto& l : lines)
    if (l.backend == backend && l.what == what) return l;
  static const CheckLine none{"", "", "missing", 0, 0, CheckLine::Verdict::fail, "no such line"};
  ADD_FAILURE() << "no line '" << what << "' for " << backend;
  return none;
}

Eigen::Vector4d turned(double angle) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized()));
  return {q.w(), q.x(), q.y(), q.z()};
}

const double kR = std::sqrt(3.0) * 0.1;

TEST(CheckBounds, BodyRadiusIsTheFarthestVertexFromTheCentreOfMass) {
  const auto radii = compare::body_radii(core::compile(scene()));
  ASSERT_EQ(radii.size(), 2u);
  EXPECT_NEAR(radii[0], kR, 1e-15);
  EXPECT_NEAR(radii[1], std::sqrt(1 + 1 + 0.01), 1e-15);
}

struct Case {
  const char* what;  // the line between backends
  double bound;      // its bound
  std::function<void(core::Sample&, double)> apply;
};

TEST(CheckBounds, BetweenBackendsEachMeasureHasItsBound) {
  const double d = 1e-6;
  const std::vector<Case> cases = {
      {"divergence between backends (m)", d, [](core::Sample& s, double x) { s.bodies[0].position.x() = x; }},
      {"divergence between backends (m)", d, [](core::Sample& s, double x) { s.particles[0].position.y() = x; }},
      {"orientation divergence between backends (rad)", d / kR,
       [](core::Sample& s, double x) { s.bodies[0].orientation = turned(x); }},
      {"velocity divergence between backends (m/s)", d / kDt,
       [](core::Sample& s, double x) { s.bodies[0].velocity.z() = x; }},
      {"velocity divergence between backends (m/s)", d / kDt,
       [](core::Sample& s, double x) { s.particles[0].velocity.z() = -x; }},
      {"angular velocity divergence between backends (rad/s)", d / (kR * kDt),
       [](core::Sample& s, double x) { s.bodies[0].angular_velocity = Vec3(0, x, 0); }},
  };
  for (const auto& c : cases) {
    for (const double f : {0.9, 1.1}) {
      const auto lines = compare::check_scene(result([&](core::Sample& s) { c.apply(s, f * c.bound); }), std::nullopt);
      const CheckLine& l = line(lines, "all", c.what);
      EXPECT_NEAR(l.value, f * c.bound, 1e-12 * c.bound) << c.what;
      EXPECT_NEAR(l.bound, c.bound, 1e-12 * c.bound) << c.what;
      EXPECT_EQ(l.verdict, f < 1 ? CheckLine::Verdict::pass : CheckLine::Verdict::fail) << c.what << " × " << f;
      EXPECT_NE(l.note.find("t = 0.07 s"), std::string::npos) << l.note;
    }
  }
  // The static slab is left out, and so is Bullet (another method: compare/metrics.hpp).
  const auto lines = compare::check_scene(
      result([](core::Sample& s) { s.bodies[1].orientation = turned(1); },
             [](core::Sample& s) { s.bodies[0].velocity.x() = 1; }),
      std::nullopt);
  EXPECT_EQ(line(lines, "all", "orientation divergence between backends (rad)").value, 0.0);
  EXPECT_EQ(line(lines, "all", "velocity divergence between backends (m/s)").value, 0.0);
  // A NaN is never agreement.
  const auto nan = compare::check_scene(result([](core::Sample& s) { s.bodies[0].angular_velocity.x() = NAN; }),
                                        std::nullopt);
  EXPECT_EQ(line(nan, "all", "angular velocity divergence between backends (rad/s)").verdict, CheckLine::Verdict::fail);
}

TEST(CheckBounds, AgainstTheBaselineEachMeasureHasItsBound) {
  const compare::SceneResult r = result({});
  const nlohmann::json stored = compare::baseline_json(r);
  const double d = r.scene.check.baseline_tolerance;
  for (const auto& l : compare::check_scene(r, read_back(stored))) EXPECT_NE(l.verdict, CheckLine::Verdict::fail) << l.what;

  struct Doctor {
    const char* what;
    double bound;
    std::function<void(nlohmann::json& cube, double)> apply;
  };
  const std::vector<Doctor> doctors = {
      {"distance from baseline, final state (m)", d, [](nlohmann::json& c, double x) { c["position"][2] = x; }},
      {"orientation from baseline, final state (rad)", d / kR,
       [](nlohmann::json& c, double x) {
         const auto q = turned(x);
         c["orientation"] = {q[0], q[1], q[2], q[3]};
       }},
      {"velocity from baseline, final state (m/s)", d / kDt, [](nlohmann::json& c, double x) { c["velocity"][0] = x; }},
      {"angular velocity from baseline, final state (rad/s)", d / (kR * kDt),
       [](nlohmann::json& c, double x) { c["angular_velocity"][1] = x; }},
  };
  for (const auto& doc : doctors) {
    for (const double f : {0.9, 1.1}) {
      nlohmann::json b = stored;
      doc.apply(b["runs"][1]["final"]["bodies"]["cube"], f * doc.bound);
      const auto lines = compare::check_scene(r, read_back(b));
      const CheckLine& l = line(lines, "cga", doc.what);
      EXPECT_NEAR(l.value, f * doc.bound, 1e-12 * doc.bound) << doc.what;
      EXPECT_EQ(l.verdict, f < 1 ? CheckLine::Verdict::pass : CheckLine::Verdict::fail) << doc.what << " × " << f;
      EXPECT_EQ(line(lines, "traditional", doc.what).verdict, CheckLine::Verdict::pass);
    }
  }
}

// Baselines stored before velocities were (a particle as its position alone, a
// body without velocities) still read: positions and orientations are checked,
// the velocities are an info line asking for --update.
TEST(CheckBounds, ABaselineWithoutVelocitiesStillReads) {
  const compare::SceneResult r = result({});
  nlohmann::json old = compare::baseline_json(r);
  for (auto& run : old["runs"]) {
    auto& fin = run["final"];
    fin["particles"]["dot"] = fin["particles"]["dot"]["position"];
    for (auto& [name, body] : fin["bodies"].items()) {
      body.erase("velocity");
      body.erase("angular_velocity");
    }
  }
  old["runs"][0]["final"]["bodies"]["cube"]["orientation"] = {std::cos(1e-9), std::sin(1e-9), 0, 0};  // 2e-9 rad
  const auto lines = compare::check_scene(r, read_back(old));
  EXPECT_EQ(line(lines, "traditional", "orientation from baseline, final state (rad)").verdict, CheckLine::Verdict::pass);
  EXPECT_NEAR(line(lines, "traditional", "orientation from baseline, final state (rad)").value, 2e-9, 1e-22);
  EXPECT_EQ(line(lines, "cga", "velocities from baseline").verdict, CheckLine::Verdict::info);
  for (const auto& l : lines) EXPECT_EQ(l.what.find("velocity from baseline"), std::string::npos) << l.what;
}

}  // namespace
