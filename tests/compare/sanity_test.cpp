// The physical-sanity rules (compare/sanity.hpp) on runs built by hand: a clean
// run passes every rule, and each way of breaking physics fails its rule (and
// only where it should: a slope, a wall and a stack are not failures).
#include "compare/check.hpp"
#include "compare/machine.hpp"
#include "compare/report.hpp"
#include "compare/sanity.hpp"
#include "core/dynamics/invariants.hpp"
#include "core/dynamics/rigid_body.hpp"
#include "core/collision/separating_axis.hpp"
#include "core/model/model.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>

namespace {
using namespace gacompare;
using compare::CheckLine;
using core::Vec3;

constexpr double kTol = 1e-4, kG = 9.81, kDt = 0.01;

core::Body box(const std::string& name, const Vec3& size, double mass, const Vec3& at, bool fixed = false) {
  core::Body b;
  b.name = name;
  b.shape = core::BoxShape{size};
  b.mass = mass;
  b.position = at;
  b.is_static = fixed;
  return b;
}

// A 2 × 2 × 0.2 slab with its top face at z = 0 and a 0.2 m cube of 1 kg on it,
// gravity −z, the bundled collision settings.
core::Scene slab_scene() {
  core::Scene s;
  s.name = "hand";
  s.effects = {core::Gravity{{0, 0, -kG}}, core::Collisions{0.5, kTol, 1e-3, core::TimeOfImpact::bisection}};
  s.bodies = {box("slab", {2, 2, 0.2}, 100, {0, 0, -0.1}, true), box("cube", {0.2, 0.2, 0.2}, 1, {0, 0, 0.1})};
  return s;
}

// Pose of body b at time t: position, velocity (orientation: the scene's).
struct State {
  Vec3 x, v;
};
using Motion = std::function<State(std::size_t body, double t)>;

// A run sampled every kDt over [0, duration], energies filled by the code the
// backends use (core/dynamics/invariants.hpp); static bodies stay where the scene puts them.
core::Run make_run(const core::Scene& scene, double duration, const Motion& motion,
                   const std::string& backend = "traditional") {
  core::Run run;
  run.backend = backend;
  run.counters["unresolved_impacts"] = 0;
  const core::Model model = core::compile(scene);
  const int n = static_cast<int>(std::lround(duration / kDt));
  for (int k = 0; k <= n; ++k) {
    core::Sample s;
    s.t = k * kDt;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      core::BodySample bs;
      bs.orientation = scene.bodies[b].orientation;
      bs.position = scene.bodies[b].position;
      if (!scene.bodies[b].is_static) {
        const State st = motion(b, s.t);
        bs.position = st.x, bs.velocity = st.v;
      }
      s.bodies.push_back(bs);
    }
    core::fill_invariants(scene, model, s);
    run.samples.push_back(s);
  }
  return run;
}

// The cube resting 5e-5 m deep in the slab, sliding along x at 0.1 m/s: what a
// frictionless floor allows.
State sliding(double t) { return {{-0.5 + 0.1 * t, 0.2, 0.1 - 5e-5}, {0.1, 0, 0}}; }

const CheckLine& find(const std::vector<CheckLine>& lines, const std::string& what_starts) {
  for (const auto& l : lines)
    if (l.what.rfind(what_starts, 0) == 0) return l;
  static const CheckLine none{"", "", "missing", 0, 0, CheckLine::Verdict::fail, "no such line"};
  ADD_FAILURE() << "no line " << what_starts;
  return none;
}
bool passes(const CheckLine& l) { return l.verdict == CheckLine::Verdict::pass; }
bool fails(const CheckLine& l) { return l.verdict == CheckLine::Verdict::fail; }

TEST(Sanity, ACleanRunPassesEveryRule) {
  const auto scene = slab_scene();
  const auto run = make_run(scene, 1.0, [](std::size_t, double t) { return sliding(t); });
  const auto lines = compare::sanity_checks(scene, run);
  ASSERT_EQ(lines.size(), 7u);
  for (const auto& l : lines)
    if (l.what.rfind("sanity: overlap", 0) != 0) {
      EXPECT_TRUE(passes(l)) << l.what << ": " << l.note;
    }
  // One moving body: nothing to overlap, said so rather than passed.
  EXPECT_EQ(find(lines, "sanity: overlap").verdict, CheckLine::Verdict::info);
  EXPECT_NE(find(lines, "sanity: overlap").note.find("fewer than two moving bodies"), std::string::npos);
  EXPECT_NEAR(find(lines, "sanity: penetration").value, 5e-5, 1e-12);
  EXPECT_NE(find(lines, "sanity: lateral drift").note.find("1 stretch"), std::string::npos);
  EXPECT_TRUE(compare::sanity_warnings(lines).empty());
}

TEST(Sanity, OnlyCollisionScenesAndFinishedRunsAreChecked) {
  auto scene = slab_scene();
  auto run = make_run(scene, 0.1, [](std::size_t, double t) { return sliding(t); });
  run.error = "stopped";
  EXPECT_TRUE(compare::sanity_checks(scene, run).empty());  // the error already fails
  run.error.reset();
  scene.effects.pop_back();
  EXPECT_TRUE(compare::sanity_checks(scene, run).empty());
}

TEST(Sanity, EnergyRisingFailsNamingTheTimes) {
  const auto scene = slab_scene();
  // Lifted by 5 mm at t = 0.5 s, still resting: 49 mJ from nowhere.
  const auto run = make_run(scene, 1.0, [](std::size_t, double t) {
    State s = sliding(t);
    if (t > 0.5 - 1e-9) s.x.z() += 5e-3;
    return s;
  });
  const CheckLine l = compare::energy_rise_check(scene, run);
  EXPECT_TRUE(fails(l)) << l.note;
  EXPECT_NEAR(l.value, 1 * kG * 5e-3, 1e-9);
  EXPECT_NEAR(l.bound, 1 * kG * kTol, 1e-7);  // one cube on a static body: lifted by one tolerance at most
  EXPECT_NE(l.note.find("to t = 0.5 s"), std::string::npos) << l.note;
}

TEST(Sanity, PositionalCorrectionWithinTheToleranceIsNotARise) {
  const auto scene = slab_scene();
  const auto run = make_run(scene, 1.0, [](std::size_t, double t) {
    State s = sliding(t);
    if (t > 0.5 - 1e-9) s.x.z() += 0.9 * kTol;  // corrected from depth ~tol to ~0
    return s;
  });
  EXPECT_TRUE(passes(compare::energy_rise_check(scene, run)));
}

TEST(Sanity, AStackMayBeLiftedOneToleranceALevel) {
  auto scene = slab_scene();
  scene.bodies.push_back(box("top", {0.2, 0.2, 0.2}, 1, {0, 0, 0.3}));
  // Both corrected at t = 0.5: the cube by one tolerance, the one on it by two.
  const auto lifted = [](double by) {
    return [by](std::size_t b, double t) {
      const double up = t > 0.5 - 1e-9 ? (b == 2 ? 2 * by : by) : 0.0;
      return State{{0, 0, (b == 2 ? 0.3 : 0.1) - 2e-5 + up}, {0, 0, 0}};
    };
  };
  const CheckLine ok = compare::energy_rise_check(scene, make_run(scene, 1.0, lifted(0.95 * kTol)));
  EXPECT_TRUE(passes(ok)) << ok.value << " " << ok.bound;
  EXPECT_NEAR(ok.bound, 3 * kG * kTol, 1e-7);  // levels 1 + 2, and 1e-9 of the energies for rounding
  EXPECT_TRUE(fails(compare::energy_rise_check(scene, make_run(scene, 1.0, lifted(1.5 * kTol)))));
}

TEST(Sanity, EnergyIsNotCheckedWhereSomethingDoesWork) {
  auto scene = slab_scene();
  scene.effects.push_back(core::AppliedForces{{{"cube", {0, 0, 0}, {1, 0, 0}, 0, 1}}});
  const auto run = make_run(scene, 0.2, [](std::size_t, double t) { return sliding(t); });
  const CheckLine l = compare::energy_rise_check(scene, run);
  EXPECT_EQ(l.verdict, CheckLine::Verdict::info);
  EXPECT_NE(l.note.find("applied forces"), std::string::npos);
}

TEST(Sanity, ABodyUnderTheSlabFails) {
  const auto scene = slab_scene();
  // 5 mm deep from t = 0.3 s (50 tolerances), then through: centre of mass inside.
  const auto run = make_run(scene, 1.0, [](std::size_t, double t) {
    State s = sliding(t);
    if (t > 0.3 - 1e-9) s.x.z() = 0.1 - 5e-3;
    if (t > 0.6 - 1e-9) s.x.z() = -0.05;
    return s;
  });
  const CheckLine l = compare::penetration_check(scene, run);
  EXPECT_TRUE(fails(l));
  EXPECT_NEAR(l.bound, 10 * kTol, 1e-15);
  EXPECT_NE(l.note.find("cube is"), std::string::npos) << l.note;
  EXPECT_NE(l.note.find("deep in slab"), std::string::npos) << l.note;
  EXPECT_NE(l.note.find("cube's centre of mass is inside slab at t = 0.6 s"), std::string::npos) << l.note;
}

// A round body is judged by its own surface, not by the polyhedron inscribed
// in it (core/model/mesh.hpp: the proxy's 26 vertices lie on the sphere, so between
// them the sphere reaches further, by up to r (1 − cos 27.3°) = 11 mm for
// r = 0.1 m): a ball turned so that its body direction farthest from every
// proxy vertex points down, 5 mm into the slab (50 tolerances, the proxy's
// lowest vertex still 6 mm above the slab top), must fail.
TEST(Sanity, ARoundBodyIsJudgedByItsOwnSurface) {
  auto scene = slab_scene();
  scene.bodies[1].shape = core::SphereShape{0.1};
  const auto turn = Eigen::Quaterniond::FromTwoVectors(Vec3(0.35185, 0.88867, 0.29404), -Vec3::UnitZ());
  scene.bodies[1].orientation = {turn.w(), turn.x(), turn.y(), turn.z()};
  const auto run = make_run(scene, 0.1, [](std::size_t, double) { return State{{0, 0, 0.1 - 5e-3}, {0, 0, 0}}; });
  const CheckLine l = compare::penetration_check(scene, run);
  EXPECT_TRUE(fails(l)) << l.note;
  EXPECT_NEAR(l.value, 5e-3, 1e-9) << l.note;
}

TEST(Sanity, AFixedStepBackendMayDipOneStepsTravel) {
  const auto scene = slab_scene();
  // 3 mm deep at 4 m/s: a 1 ms fixed step's travel (Bullet's), not a tunnel.
  auto run = make_run(
      scene, 0.1, [](std::size_t, double t) { return State{{0, 0, 0.1 - (t > 0.05 ? 3e-3 : 0.0)}, {0, 0, -4}}; },
      "bullet");
  EXPECT_TRUE(fails(compare::penetration_check(scene, run)));
  run.metrics["bullet_fixed_step_s"] = 1e-3;
  const CheckLine l = compare::penetration_check(scene, run);
  EXPECT_TRUE(passes(l)) << l.note;
  EXPECT_NEAR(l.bound, 10 * kTol + 4e-3, 1e-12);
}

// The same dip in our own run: allowed only where the scene asks for no
// impact search (time_of_impact "none"), by its collision step's travel.
TEST(Sanity, ARunWithoutASearchMayDipOneCollisionStepsTravel) {
  auto scene = slab_scene();
  const auto dip = [](std::size_t, double t) { return State{{0, 0, 0.1 - (t > 0.05 ? 3e-3 : 0.0)}, {0, 0, -4}}; };
  EXPECT_TRUE(fails(compare::penetration_check(scene, make_run(scene, 0.1, dip))));
  std::get<core::Collisions>(scene.effects[1]).time_of_impact = core::TimeOfImpact::none;
  const CheckLine l = compare::penetration_check(scene, make_run(scene, 0.1, dip));
  EXPECT_TRUE(passes(l)) << l.note;
  EXPECT_NEAR(l.bound, 10 * kTol + 4e-3, 1e-12);
  EXPECT_NE(l.note.find("without a time of impact"), std::string::npos) << l.note;
  // Twice that is not a step's travel.
  const CheckLine deeper = compare::penetration_check(
      scene, make_run(scene, 0.1, [](std::size_t, double t) { return State{{0, 0, 0.1 - (t > 0.05 ? 6e-3 : 0.0)}, {0, 0, -4}}; }));
  EXPECT_TRUE(fails(deeper)) << deeper.note;
}

TEST(Sanity, ARestingBodyDriftingSidewaysFails) {
  const auto scene = slab_scene();
  // Moved sideways by 1 µm per sample with zero velocity: a teleport.
  const auto teleported = make_run(scene, 1.0, [](std::size_t, double t) {
    return State{{1e-4 * t, 0, 0.1 - 5e-5}, {0, 0, 0}};
  });
  const auto lines = compare::lateral_drift_checks(scene, teleported);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(passes(lines[0])) << lines[0].note;  // the velocity did not change
  EXPECT_TRUE(fails(lines[1]));
  EXPECT_NEAR(lines[1].value, 1e-4, 1e-12);
  EXPECT_NE(lines[1].note.find("cube at rest from t = 0 to 1 s"), std::string::npos) << lines[1].note;

  // Accelerated sideways at 1e-4 m/s², position consistent with it: starting to slide on a level floor.
  const auto accelerated = make_run(scene, 1.0, [](std::size_t, double t) {
    return State{{0.5e-4 * t * t, 0, 0.1 - 5e-5}, {1e-4 * t, 0, 0}};
  });
  const auto acc = compare::lateral_drift_checks(scene, accelerated);
  EXPECT_TRUE(fails(acc[0]));
  EXPECT_NEAR(acc[0].value, 1e-4, 1e-12);
  EXPECT_TRUE(passes(acc[1])) << acc[1].value;
}

TEST(Sanity, SlidingDownASlopeIsNotDrift) {
  auto scene = slab_scene();
  const double theta = 0.2;  // rad, about y
  const Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Vec3::UnitY()));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  for (auto& b : scene.bodies) b.orientation = {q.w(), q.x(), q.y(), q.z()};
  const Vec3 rest = scene.bodies[0].position + r * Vec3(0, 0, 0.2 - 5e-5);
  const Vec3 down = r * Vec3(1, 0, 0);  // down the slope: the rotation about +y lowers +x
  ASSERT_LT(down.z(), 0);
  const double a = kG * std::sin(theta);
  const auto run = make_run(scene, 0.3, [&](std::size_t, double t) {
    return State{rest + 0.5 * a * t * t * down, a * t * down};
  });
  for (const auto& l : compare::sanity_checks(scene, run)) EXPECT_FALSE(fails(l)) << l.what << ": " << l.note;
  EXPECT_EQ(compare::lateral_drift_checks(scene, run)[0].verdict, CheckLine::Verdict::info);
}

// Friction slows a sliding body on a level floor: rule 3 leaves
// the pair out. The same run without friction fails it.
TEST(Sanity, SlowingByFrictionIsNotDrift) {
  auto scene = slab_scene();
  const double decel = 0.5 * kG;
  const auto run = make_run(scene, 0.3, [&](std::size_t, double t) {
    const double v = std::max(0.0, 1.0 - decel * t), x = (1.0 - v * v) / (2 * decel);
    return State{{x, 0, 0.1 - 5e-5}, {v, 0, 0}};
  });
  EXPECT_TRUE(fails(compare::lateral_drift_checks(scene, run)[0]));
  for (auto& b : scene.bodies) b.friction = 0.5;
  for (const auto& l : compare::sanity_checks(scene, run)) EXPECT_FALSE(fails(l)) << l.what << ": " << l.note;
  EXPECT_EQ(compare::lateral_drift_checks(scene, run)[0].verdict, CheckLine::Verdict::info);
}

TEST(Sanity, BouncingOffAWallIsNotDrift) {
  auto scene = slab_scene();
  scene.bodies.push_back(box("wall", {0.1, 2, 1}, 100, {0.65, 0, 0.5}, true));
  // Sliding at 0.5 m/s into the wall (face at x = 0.6), back at 0.25 m/s from t = 0.505 s.
  const auto run = make_run(scene, 1.0, [](std::size_t, double t) {
    const double tc = 0.505, x = t < tc ? 0.2475 + 0.5 * t : 0.5 - 0.25 * (t - tc);
    return State{{x, 0, 0.1 - 5e-5}, {t < tc ? 0.5 : -0.25, 0, 0}};
  });
  const auto lines = compare::lateral_drift_checks(scene, run);
  for (const auto& l : lines) EXPECT_TRUE(passes(l)) << l.what << ": " << l.note;
  EXPECT_NE(lines[0].note.find("2 stretch"), std::string::npos) << lines[0].note;  // before and after the wall
}

// A body that could reach a resting one within a sample's interval leaves
// that interval unchecked, though their bounding spheres are apart at both
// samples: a cube crossing beside the resting one at 40 m/s, 0.5 m from it
// (spheres 0.15 m apart, faces 0.3 m, its reach in 0.01 s 0.4 m). The rule
// finds such partners by growing each sphere by its own reach; without the
// growth the resting cube's rest would be one stretch, not two.
TEST(Sanity, ABodyThatCouldReachARestingOneLeavesItUnchecked) {
  auto scene = slab_scene();
  scene.bodies.push_back(box("crossing", {0.2, 0.2, 0.2}, 1, {0.5, -2, 0.1}));
  const auto run = make_run(scene, 0.1, [](std::size_t b, double t) {
    if (b == 1) return State{{0, 0, 0.1 - 5e-5}, {0, 0, 0}};
    return State{{0.5, 40 * (t - 0.05), 0.1 - 5e-5}, {0, 40, 0}};
  });
  const auto lines = compare::lateral_drift_checks(scene, run);
  for (const auto& l : lines) EXPECT_TRUE(passes(l)) << l.what << ": " << l.note;
  EXPECT_NE(lines[0].note.find("4 stretch"), std::string::npos) << lines[0].note;  // each cube: before and after
}

// Rule 5. The cube slower than the resting speed (0.064 m/s here) and
// speeding up steadily at 1e-3 m/s² for 2 s, as the top of a tilted column
// did: the rise over a second (1e-3 m/s) is ten times the bound.
TEST(Sanity, ARestingBodyThatKeepsSpeedingUpFails) {
  const auto scene = slab_scene();
  const double a = 1e-3;
  const auto run = make_run(scene, 2.0, [&](std::size_t, double t) {
    return State{{0.5 * a * t * t, 0, 0.1 - 5e-5}, {a * t, 0, 0}};
  });
  const CheckLine l = compare::resting_acceleration_check(scene, run);
  EXPECT_TRUE(fails(l)) << l.note;
  EXPECT_NEAR(l.value, a * 1.0, 0.05 * a);  // one second's rise
  EXPECT_NE(l.note.find("cube"), std::string::npos) << l.note;
}

// Sliding at a constant 1 mm/s, or nudged once to 0.5 mm/s and sliding on:
// no second of steady speeding up, so no failure.
TEST(Sanity, SlidingOnOrANudgeIsNotASpeedUp) {
  const auto scene = slab_scene();
  const auto steady = make_run(scene, 2.0, [](std::size_t, double t) { return State{{1e-3 * t, 0, 0.1 - 5e-5}, {1e-3, 0, 0}}; });
  EXPECT_TRUE(passes(compare::resting_acceleration_check(scene, steady)));
  const auto nudged = make_run(scene, 2.0, [](std::size_t, double t) {
    const double v = t < 0.5 ? 0.0 : 5e-4;
    return State{{v * (t - 0.5), 0, 0.1 - 5e-5}, {v, 0, 0}};
  });
  const CheckLine l = compare::resting_acceleration_check(scene, nudged);
  EXPECT_TRUE(passes(l)) << l.value << " " << l.note;
}

// The same steady speed-up while a second cube moves faster than v_rest: the
// scene is not at rest (a neighbour may be pushing), so the rule holds back;
// once the second cube is at rest too, the speed-up fails again.
TEST(Sanity, ASpeedUpCountsOnlyWhileTheWholeSceneRests) {
  auto scene = slab_scene();
  scene.bodies.push_back(box("other", {0.2, 0.2, 0.2}, 1, {1, 0, 0.1}));
  const double a = 1e-3;
  const auto with_other = [&](double other_speed) {
    return make_run(scene, 2.0, [&, other_speed](std::size_t b, double t) {
      if (b == 2) return State{{1 + other_speed * t, 0, 0.1 - 5e-5}, {other_speed, 0, 0}};
      return State{{0.5 * a * t * t, 0, 0.1 - 5e-5}, {a * t, 0, 0}};
    });
  };
  const double v_rest = core::compile(scene).resting_speed;
  const CheckLine moving = compare::resting_acceleration_check(scene, with_other(2 * v_rest));
  EXPECT_TRUE(passes(moving)) << moving.value << " " << moving.note;
  const CheckLine resting = compare::resting_acceleration_check(scene, with_other(0));
  EXPECT_TRUE(fails(resting)) << resting.note;
}

TEST(Sanity, UnresolvedImpactsFailAndAnAbsentCounterIsNotMeasured) {
  const auto scene = slab_scene();
  auto run = make_run(scene, 0.1, [](std::size_t, double t) { return sliding(t); });
  EXPECT_TRUE(passes(compare::unresolved_impacts_check(scene, run)));
  run.counters["unresolved_impacts"] = 3;
  const CheckLine l = compare::unresolved_impacts_check(scene, run);
  EXPECT_TRUE(fails(l));
  EXPECT_EQ(l.value, 3);
  run.counters.erase("unresolved_impacts");
  EXPECT_EQ(compare::unresolved_impacts_check(scene, run).verdict, CheckLine::Verdict::info);
}

// A scene's stated rest positions (check.rest): check fails on a body farther
// than the tolerance from its rest after the time given, and only there.
TEST(Sanity, CheckHoldsBodiesToTheRestTheSceneStates) {
  auto scene = slab_scene();
  scene.check.rest = {{"cube", Vec3(0, 0, 0.1)}};
  scene.check.rest_after = 0.5;
  scene.check.rest_tolerance = 1e-3;
  const auto check = [&](const Motion& m) {
    compare::SceneResult r{scene, {}, std::make_shared<const core::Model>(core::compile(scene))};
    r.backends.push_back({make_run(scene, 1.0, m), {{}}, {1.0}, true});
    return find(compare::check_scene(r, std::nullopt), "rest of cube");
  };
  // Sinking 5e-5 and falling in from 1 cm above before 0.5 s: at rest in time.
  const CheckLine settled = check([](std::size_t, double t) {
    return State{{0, 0, 0.1 - 5e-5 + (t < 0.4 ? 0.01 : 0.0)}, {0, 0, 0}};
  });
  EXPECT_TRUE(passes(settled)) << settled.value;
  EXPECT_NEAR(settled.value, 5e-5, 1e-12);
  // Sliding off at 1 cm/s: 5 mm away by the end.
  const CheckLine slid = check([](std::size_t, double t) { return State{{0.01 * t, 0, 0.1}, {0.01, 0, 0}}; });
  EXPECT_TRUE(fails(slid));
  EXPECT_NEAR(slid.value, 0.01, 1e-12);
}

TEST(Sanity, CheckFailsOnASanityRuleAndCarriesABulletRun) {
  const auto scene = slab_scene();
  const Motion lifted = [](std::size_t, double t) {
    State s = sliding(t);
    if (t > 0.5 - 1e-9) s.x.z() += 5e-3;
    return s;
  };
  compare::SceneResult r{scene, {}, std::make_shared<const core::Model>(core::compile(scene))};
  for (const char* b : {"traditional", "cga"}) r.backends.push_back({make_run(scene, 1.0, lifted, b), {{}}, {1.0}, true});
  auto bullet = make_run(scene, 1.0, [](std::size_t, double t) { return State{{0.3, 0.1 * t, 0.1}, {0, 0.1, 0}}; }, "bullet");
  bullet.counters.clear();  // Bullet publishes no unresolved_impacts
  r.backends.push_back({bullet, {{}}, {1.0}, true});

  const auto lines = compare::check_scene(r, std::nullopt);
  int sanity_failures = 0;
  for (const auto& l : lines) {
    if (l.what.rfind("sanity:", 0) == 0 && fails(l)) {
      ++sanity_failures;
      EXPECT_NE(l.backend, "bullet") << l.what;
    }
    if (l.what == "divergence between backends (m)") {
      EXPECT_TRUE(passes(l));  // Bullet stays out of it
    }
  }
  EXPECT_EQ(sanity_failures, 2);  // energy, traditional and cga
  EXPECT_EQ(find(lines, "sanity: unresolved").verdict, CheckLine::Verdict::pass);

  const std::string md = compare::scene_report_md(r, compare::MachineInfo{"cpu", "cc", "today", "Release"}, 1);
  EXPECT_NE(md.find("**WARNING, physical sanity:** traditional: energy rise"), std::string::npos) << md;
  EXPECT_NE(md.find("## Physical sanity"), std::string::npos);
  EXPECT_NE(md.find("| hand | bullet | sanity: unresolved impacts |"), std::string::npos);
}

// Rule 6. A heavy cube on a light one on the slab: resting 5e-5 m into each
// other passes; sunk 5 mm (50 tolerances) from t = 0.4 s fails, naming both.
core::Scene two_cube_stack() {
  auto scene = slab_scene();
  scene.bodies.push_back(box("heavy", {0.2, 0.2, 0.2}, 100, {0, 0, 0.3}));
  return scene;
}

TEST(Sanity, AHeavyBoxSinkingIntoALightOneFails) {
  const auto scene = two_cube_stack();
  const auto stack = [](double sunk) {
    return [sunk](std::size_t b, double t) {
      const double z = b == 1 ? 0.1 - 5e-5 : 0.3 - 1e-4 - (t > 0.4 - 1e-9 ? sunk : 0.0);
      return State{{0, 0, z}, {0, 0, 0}};
    };
  };
  const CheckLine resting = compare::overlap_check(scene, make_run(scene, 1.0, stack(0)));
  EXPECT_TRUE(passes(resting)) << resting.note;
  EXPECT_NEAR(resting.value, 5e-5, 1e-12);
  EXPECT_NEAR(resting.bound, 10 * kTol, 1e-15);
  const CheckLine sunk = compare::overlap_check(scene, make_run(scene, 1.0, stack(5e-3)));
  EXPECT_TRUE(fails(sunk)) << sunk.note;
  EXPECT_NEAR(sunk.value, 5e-3 + 5e-5, 1e-12);
  EXPECT_NE(sunk.note.find("cube and heavy overlap by"), std::string::npos) << sunk.note;
  EXPECT_NE(sunk.note.find("at t = 0.4 s"), std::string::npos) << sunk.note;
  // The whole rule set carries it: check and compare fail the run.
  const auto lines = compare::sanity_checks(scene, make_run(scene, 1.0, stack(5e-3)));
  EXPECT_TRUE(fails(find(lines, "sanity: overlap")));
  EXPECT_EQ(compare::sanity_warnings(lines).size(), 1u);
}

// Without a time of impact the pair may overlap by one step's travel at both
// bodies' highest speeds, no more.
TEST(Sanity, AnOverlapWithoutASearchMayReachOneStepsTravelOfBoth) {
  auto scene = two_cube_stack();
  std::get<core::Collisions>(scene.effects[1]).time_of_impact = core::TimeOfImpact::none;
  const auto closing = [](double sunk) {
    return [sunk](std::size_t b, double) {
      return b == 1 ? State{{0, 0, 0.1}, {0, 0, 1}} : State{{0, 0, 0.3 - sunk}, {0, 0, -3}};
    };
  };
  const CheckLine l = compare::overlap_check(scene, make_run(scene, 0.1, closing(4e-3)));
  EXPECT_TRUE(passes(l)) << l.note;
  EXPECT_NEAR(l.bound, 10 * kTol + 1e-3 * (1 + 3), 1e-12);
  EXPECT_NE(l.note.find("without a time of impact"), std::string::npos) << l.note;
  EXPECT_TRUE(fails(compare::overlap_check(scene, make_run(scene, 0.1, closing(6e-3)))));
}

TEST(Sanity, ANonFinitePositionOrAMissingBodyFailsTheOverlapRule) {
  const auto scene = two_cube_stack();
  const auto run = make_run(scene, 0.1, [](std::size_t b, double t) {
    return State{{0, 0, b == 2 && t > 0.05 ? std::nan("") : 0.1 + 0.2 * (b - 1)}, {0, 0, 0}};
  });
  const CheckLine l = compare::overlap_check(scene, run);
  EXPECT_TRUE(fails(l));
  EXPECT_NE(l.note.find("heavy's position is not finite at t = 0.06 s"), std::string::npos) << l.note;
  // A sample short of a body (a results file cut short) fails too, not skipped.
  auto cut = make_run(scene, 0.1, [](std::size_t b, double) { return State{{0, 0, 0.1 + 0.2 * (b - 1)}, {0, 0, 0}}; });
  cut.samples[3].bodies.pop_back();
  const CheckLine short_sample = compare::overlap_check(scene, cut);
  EXPECT_TRUE(fails(short_sample));
  EXPECT_NE(short_sample.note.find("the sample at t = 0.03 s has 2 bodies, the scene 3"), std::string::npos)
      << short_sample.note;
}

// The grid finds what every pair finds: 300 turned boxes of sizes 0.02 to
// 0.3 m crowded into a 1.5 m cube, and a clump of three a billion metres out
// (cells clamped there), against the exact depth of all 45,000 pairs.
TEST(Sanity, TheOverlapRuleFindsTheDeepestPairAsBruteForceDoes) {
  core::Scene scene = slab_scene();
  scene.bodies.resize(1);
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> at;
  for (int i = 0; i < 303; ++i) {
    const Vec3 size(0.02 + 0.28 * u(rng), 0.02 + 0.28 * u(rng), 0.02 + 0.28 * u(rng));
    const Vec3 x = i < 300 ? Vec3(1.5 * u(rng), 1.5 * u(rng), 1 + 1.5 * u(rng)) : Vec3(1e9 + 0.1 * (i - 300), 0, 5);
    std::string name = "b";
    name += std::to_string(i);  // (gcc 12 at -O3 warns falsely on "b" + std::to_string)
    auto b = box(name, size, 1, x);
    std::normal_distribution<double> n(0, 1);
    const Eigen::Vector4d q = Eigen::Vector4d(n(rng), n(rng), n(rng), n(rng)).normalized();
    b.orientation = q;
    scene.bodies.push_back(b);
    at.push_back(x);
  }
  const auto run = make_run(scene, 0.0, [&](std::size_t b, double) { return State{at[b - 1], {0, 0, 0}}; });
  const core::Model model = core::compile(scene);
  double deepest = 0, deepest_far = 0;
  for (std::size_t i = 1; i < scene.bodies.size(); ++i)
    for (std::size_t j = i + 1; j < scene.bodies.size(); ++j) {
      const auto placed = [&](std::size_t k) {
        return collision::Placed{model.bodies[k].mesh.get(),
                                 {core::rotation_matrix(scene.bodies[k].orientation), run.samples[0].bodies[k].position}};
      };
      const double d = std::max(0.0, collision::sat_reference(placed(i), placed(j)).depth);
      deepest = std::max(deepest, d);
      if (i > 300) deepest_far = std::max(deepest_far, d);
    }
  ASSERT_GT(deepest, 0.05);  // crowded: the case has deep pairs to find
  const CheckLine l = compare::overlap_check(scene, run);
  EXPECT_TRUE(fails(l));
  EXPECT_EQ(l.value, deepest);  // the same depth of the same pair, not a near one
  // Far out alone: the clump's own deepest pair.
  core::Scene far = scene;
  far.bodies.erase(far.bodies.begin() + 1, far.bodies.begin() + 301);
  at.erase(at.begin(), at.begin() + 300);
  ASSERT_GT(deepest_far, 0);
  EXPECT_EQ(compare::overlap_check(far, make_run(far, 0.0, [&](std::size_t b, double) { return State{at[b - 1], {0, 0, 0}}; })).value,
            deepest_far);
}

// Two rods end to end, 1 cm into each other, their centres 0.99 m apart
// (nearly the sum of their bounding radii, 1.02 m): the grid must still put
// them in neighbouring cells, so its cell is the largest diameter, not less.
TEST(Sanity, TwoLongBodiesTouchingAtTheirEndsAreFound) {
  core::Scene scene = slab_scene();
  scene.bodies.resize(1);
  scene.bodies.push_back(box("left", {1, 0.1, 0.1}, 1, {0.3, 0, 1}));
  scene.bodies.push_back(box("right", {1, 0.1, 0.1}, 1, {1.29, 0, 1}));
  scene.bodies.push_back(box("pebble", {0.01, 0.01, 0.01}, 1, {0, 0.5, 1}));
  const auto run = make_run(scene, 0.0, [&](std::size_t b, double) { return State{scene.bodies[b].position, {0, 0, 0}}; });
  const CheckLine l = compare::overlap_check(scene, run);
  EXPECT_TRUE(fails(l)) << l.note;
  EXPECT_NEAR(l.value, 0.01, 1e-12);
  EXPECT_NE(l.note.find("left and right"), std::string::npos) << l.note;
}

// With bounds that differ per body (no search: each body's top speed), the
// line still reports the deepest pair, not the one closest to its bound: a
// shallow resting pair of slow bodies is nearer its bound than a pair of fast
// ones 4 mm into each other, and reporting it read as "overlap 5e-05 m".
// The same for the walls: a fast body 3 mm into the slab, a slow one 5e-5 m.
TEST(Sanity, WithBoundsPerBodyTheDeepestPairIsReported) {
  auto scene = two_cube_stack();
  std::get<core::Collisions>(scene.effects[1]).time_of_impact = core::TimeOfImpact::none;
  scene.bodies.push_back(box("low", {0.2, 0.2, 0.2}, 1, {0.6, 0, 0.1}));
  scene.bodies.push_back(box("high", {0.2, 0.2, 0.2}, 1, {0.6, 0, 0.3}));
  const auto run = make_run(scene, 0.1, [](std::size_t b, double) {
    switch (b) {
      case 1: return State{{0, 0, 0.1 - 3e-3}, {0, 0, -3}};   // fast, 3 mm into the slab
      case 2: return State{{0, 0, 0.3 - 7e-3}, {0, 0, -3}};   // fast, 4 mm into the cube
      case 3: return State{{0.6, 0, 0.1 - 5e-5}, {0, 0, 0}};  // slow, 5e-5 m into the slab
      default: return State{{0.6, 0, 0.3 - 1e-4}, {0, 0, 0}}; // slow, 5e-5 m into low
    }
  });
  const CheckLine pair = compare::overlap_check(scene, run);
  EXPECT_TRUE(passes(pair)) << pair.note;
  EXPECT_NEAR(pair.value, 4e-3, 1e-12);
  EXPECT_NEAR(pair.bound, 10 * kTol + 1e-3 * (3 + 3), 1e-12);
  EXPECT_NE(pair.note.find("cube and heavy overlap by"), std::string::npos) << pair.note;
  const CheckLine wall = compare::penetration_check(scene, run);
  EXPECT_TRUE(passes(wall)) << wall.note;
  EXPECT_NEAR(wall.value, 3e-3, 1e-12);
  EXPECT_NEAR(wall.bound, 10 * kTol + 1e-3 * 3, 1e-12);
}

// The pairs every pairwise rule looks at (compare::SphereGrid), against every
// pair tested: the same set, each pair once and (i < j), and each body's
// partners the same set, over seeded crowds with a floor a hundred times their
// size, bodies flung fast (grown a metre), boulders among pebbles, a body at
// NaN or of NaN size, bodies a billion metres out (the grid's clamped cells),
// and a subset of the bodies asked for.
// A query stops where its visitor says so.
TEST(Sanity, NearPairsAreThePairsEveryPairTestFinds) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> u(0, 1);
  for (int round = 0; round < 20; ++round) {
    const std::size_t n = 50 + 40 * static_cast<std::size_t>(round);
    std::vector<Vec3> c(n);
    std::vector<double> r(n), grow(n);
    for (std::size_t i = 0; i < n; ++i) {
      c[i] = Vec3(2 * u(rng), 2 * u(rng), 2 * u(rng));
      r[i] = 0.02 + 0.2 * u(rng);
      grow[i] = round % 2 ? 0.0 : 0.02 * u(rng);
    }
    r[0] = 10, c[0] = Vec3(1, 1, -10);  // a floor
    grow[1] = 1.0, grow[2] = 0.5;       // flung fast
    if (round % 3 == 2)                 // boulders among pebbles: half the bodies ten times the others
      for (std::size_t i = 6; i < n; i += 2) r[i] *= 10;
    if (round % 6 == 1) grow[6] = std::nan("");  // a size not known: it meets everything
    c[3] = Vec3(1e9, 0, 0), c[4] = Vec3(1e9 + 0.05, 0, 0);  // far out, touching
    if (round % 3 == 0) c[5] = Vec3(std::nan(""), 0, 0);     // lost: it meets everything
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < n; ++i)
      if (round % 4 != 1 || i % 3 != 0) which.push_back(i);
    const std::vector<double> grown = round % 5 == 4 ? std::vector<double>{} : grow;
    const compare::SphereGrid grid(c, r, which, grown);
    const auto got = grid.pairs();
    std::vector<std::pair<std::size_t, std::size_t>> want;
    for (std::size_t a = 0; a < which.size(); ++a)
      for (std::size_t b = a + 1; b < which.size(); ++b) {
        const std::size_t i = which[a], j = which[b];
        const double g = round % 5 == 4 ? 0.0 : grow[i] + grow[j];
        if (!((c[i] - c[j]).norm() - r[i] - r[j] >= g)) want.emplace_back(std::min(i, j), std::max(i, j));
      }
    auto sorted = got;
    std::sort(sorted.begin(), sorted.end());
    std::sort(want.begin(), want.end());
    ASSERT_GT(want.size(), n / 2) << round;  // crowded: the case has pairs to find
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << round << ": a pair twice";
    EXPECT_EQ(sorted, want) << round;
    for (const auto& [i, j] : got) EXPECT_LT(i, j) << round;
    for (const std::size_t i : which) {
      std::vector<std::size_t> mine, theirs;
      grid.near(i, [&](std::size_t j) { return mine.push_back(j), true; });
      for (const auto& [a, b] : want)
        if (a == i || b == i) theirs.push_back(a == i ? b : a);
      std::sort(mine.begin(), mine.end());
      ASSERT_EQ(mine, theirs) << round << " body " << i;
      if (theirs.size() < 2) continue;
      int asked = 0;
      EXPECT_FALSE(grid.near(i, [&](std::size_t) { return ++asked < 2; })) << round;
      EXPECT_EQ(asked, 2) << round;  // stopped at the visitor's word
    }
  }
}

}  // namespace
