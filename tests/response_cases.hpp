#pragma once
// Collision response cases (§2.5) run through a backend on the
// bundled scenes (data/scenes), checked against analytic answers: bounce
// heights falling by ε², rest, conservation across an elastic impact, an
// edge–edge impulse along the edges' common normal, no tunnelling among 27
// bodies in a box, the scene rejected when bodies start overlapping.
// Instantiated by tests/{traditional,cga}/response_test.cpp.
#include "core/dynamics/simulator.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace gacompare::testing {

inline core::Scene bundled(const std::string& name) {
  return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
}
inline const core::BodySample& body(const core::Sample& s, std::size_t b) { return s.bodies[b]; }

// Apex heights (local maxima of z where v_z turns from + to −) of body b.
inline std::vector<double> apexes(const core::Run& run, std::size_t b) {
  std::vector<double> out;
  for (std::size_t k = 1; k < run.samples.size(); ++k)
    if (body(run.samples[k - 1], b).velocity.z() > 0 && body(run.samples[k], b).velocity.z() <= 0)
      out.push_back(std::max(body(run.samples[k - 1], b).position.z(), body(run.samples[k], b).position.z()));
  return out;
}

template <class Backend>
class ResponseCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(ResponseCases);

// A cube dropped flat on a static slab, ε = 0.5: the speed after each bounce
// is ε times the speed before, so each apex above the resting height is ε² =
// 0.25 of the one before. Tolerance 1%: an impact is resolved anywhere within
// the penetration tolerance (1e-4 m of a 0.25 m rise: 4e-4 relative), the
// apex is read from samples 2 ms apart (½ g dt² = 2e-5 m), and RK4 is exact
// for free flight. Then it rests: on the slab within the tolerance, at rest
// to 1e-6 m/s, and stays there for the last second (no sinking, no creep).
TYPED_TEST_P(ResponseCases, FlatDropBouncesByEpsilonSquaredAndRests) {
  const auto scene = bundled("cube_drop_flat");
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error) << *run.error;
  const double rest = 0.1;  // slab top 0 + half the cube
  const auto up = apexes(run, 1);
  ASSERT_GE(up.size(), 3u);
  EXPECT_NEAR((up[0] - rest) / (1.1 - rest), 0.25, 0.0025);
  EXPECT_NEAR((up[1] - rest) / (up[0] - rest), 0.25, 0.0025);
  EXPECT_NEAR((up[2] - rest) / (up[1] - rest), 0.25, 0.0025);
  const double tol = 1e-4;
  for (const auto& s : run.samples) {
    EXPECT_GT(body(s, 1).position.z(), rest - tol) << "sank at t=" << s.t;
    if (s.t < scene.duration - 1.0) continue;
    EXPECT_LT(std::abs(body(s, 1).position.z() - rest), tol) << s.t;
    EXPECT_LT(body(s, 1).velocity.norm(), 1e-6) << s.t;
  }
  EXPECT_EQ(run.counters.at("impact_searches_unresolved"), 0u);
}

// Edge and corner first: the cube bounces, tips and comes to rest flat, one
// face down: centre 0.1 above the slab within the tolerance, no vertical
// motion, one body axis vertical (1e-6 rad). The response is frictionless
// (eq. 47–53), so the horizontal velocity and the spin about the vertical
// that the impacts left stay: they are checked constant over the last second.
TYPED_TEST_P(ResponseCases, EdgeAndCornerDropsComeToRestFlat) {
  for (const char* name : {"cube_drop_edge", "cube_drop_corner"}) {
    const auto scene = bundled(name);
    const core::Run run = core::simulate<TypeParam>(scene);
    ASSERT_FALSE(run.error) << name << ": " << *run.error;
    const core::Sample* settled = nullptr;
    for (const auto& s : run.samples) {
      EXPECT_GT(body(s, 1).position.z(), 0.1 - 1e-4) << name << " sank at " << s.t;
      if (s.t < scene.duration - 1.0) continue;
      if (!settled) settled = &s;
      const auto& b = body(s, 1);
      EXPECT_NEAR(b.position.z(), 0.1, 1e-4) << name << " t=" << s.t;
      EXPECT_LT(std::abs(b.velocity.z()), 1e-6) << name << " t=" << s.t;
      const Eigen::Matrix3d r =
          Eigen::Quaterniond(b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]).toRotationMatrix();
      // Level within the tolerance: the corners of the bottom face may rest at
      // different depths in [0, tol], so the tilt is at most tol / (face diagonal).
      const double tilt = std::acos(std::min(1.0, r.row(2).cwiseAbs().maxCoeff()));
      EXPECT_LT(tilt, 1e-4 / (0.2 * std::sqrt(2.0))) << name << " t=" << s.t;
      // The impulses are solved to 1e-6 m/s (core/collision/collisions.hpp), which at the
      // cube's half width is 1e-5 rad/s of rocking at most.
      EXPECT_LT((b.velocity - body(*settled, 1).velocity).norm(), 1e-6) << name << " t=" << s.t;
      EXPECT_LT((b.angular_velocity - body(*settled, 1).angular_velocity).norm(), 1e-5) << name << " t=" << s.t;
      EXPECT_LT(std::hypot(b.angular_velocity.x(), b.angular_velocity.y()), 1e-5) << name << " t=" << s.t;
    }
  }
}

// Two free bodies, ε = 1: the impulses are equal and opposite at one point, so
// linear and angular momentum are conserved exactly but for rounding, and the
// kinetic energy by the choice of ε. Compared between the last sample before
// and the first after the contact; 1e-9 relative covers RK4's rotation error
// over the 2 ms between them (measured ~1e-12) and leaves the impulse's own
// error (rounding, ~1e-15) far inside it.
TYPED_TEST_P(ResponseCases, ElasticImpactConservesEnergyAndMomenta) {
  const core::Run run = core::simulate<TypeParam>(bundled("elastic_pair"));
  ASSERT_FALSE(run.error) << *run.error;
  ASSERT_GT(run.counters.at("contacts"), 0u);
  // The impact: the first sample where the plate's velocity has changed.
  std::size_t k = 1;
  while (k < run.samples.size() && (body(run.samples[k], 1).velocity - body(run.samples[0], 1).velocity).norm() < 1e-9) ++k;
  ASSERT_LT(k, run.samples.size()) << "no impact";
  const auto& before = run.samples[k - 1];
  const auto& after = run.samples[k];
  EXPECT_NEAR(after.kinetic / before.kinetic - 1, 0, 1e-9);
  EXPECT_LT((after.linear_momentum - before.linear_momentum).norm() / before.linear_momentum.norm(), 1e-9);
  EXPECT_LT((after.angular_momentum - before.angular_momentum).norm() / before.angular_momentum.norm(), 1e-9);
  // And over the whole run (several contacts may follow).
  const auto& last = run.samples.back();
  EXPECT_NEAR(last.kinetic / run.samples[0].kinetic - 1, 0, 1e-9);
  EXPECT_LT((last.linear_momentum - run.samples[0].linear_momentum).norm() / run.samples[0].linear_momentum.norm(), 1e-9);
}

// Edge through edge (fig. 10): a's edge runs along x, b's along y, so the
// common normal is z and the impulse changes only the z velocities: x and y
// velocities stay as they were (to rounding), momentum is conserved, and the
// two boxes part (b above a moving up relative to it).
TYPED_TEST_P(ResponseCases, EdgeEdgeImpulseAlongTheCommonNormal) {
  const core::Run run = core::simulate<TypeParam>(bundled("box_edge_edge"));
  ASSERT_FALSE(run.error) << *run.error;
  const auto& first = run.samples.front();
  const auto& last = run.samples.back();
  EXPECT_GT(run.counters.at("contacts"), 0u);
  for (std::size_t b = 0; b < 2; ++b) {
    EXPECT_NEAR(body(last, b).velocity.x(), body(first, b).velocity.x(), 1e-12);
    EXPECT_NEAR(body(last, b).velocity.y(), body(first, b).velocity.y(), 1e-12);
  }
  EXPECT_GT(body(last, 1).velocity.z() - body(last, 0).velocity.z(), 0);
  EXPECT_LT((last.linear_momentum - first.linear_momentum).norm(), 1e-12);
}

// Fig. 8: pushed into the pyramid's point, the cube comes back (+x) spinning.
TYPED_TEST_P(ResponseCases, CubeBouncesOffThePyramidsPoint) {
  const core::Run run = core::simulate<TypeParam>(bundled("cube_pyramid_point"));
  ASSERT_FALSE(run.error) << *run.error;
  const auto& last = body(run.samples.back(), 1);
  EXPECT_GT(last.velocity.x(), 0);
  EXPECT_GT(last.angular_velocity.norm(), 0.1);
  // The apex (0.3, 0, 0) never gets deeper into the cube than the tolerance:
  // the cube's centre stays at least its inradius (0.1) minus 1e-4 from it.
  for (const auto& s : run.samples)
    EXPECT_GT((body(s, 1).position - Eigen::Vector3d(0.3, 0, 0)).norm(), 0.1 - 1e-4) << s.t;
}

// 27 bodies in a closed box: no NaN, and every centre stays inside the walls
// (inner faces at ±0.6) at every sample: nothing tunnels or escapes. The
// traditional backend runs the whole 10 s (about 6 s of CPU); the cga backend,
// three times slower here, the first 3 s (the bodies are thrown at up to
// 3.5 m/s and spinning; by 3 s most lie on the floor), to keep the suite fast.
// `gacompare check` (CI) runs both for the whole 10 s.
TYPED_TEST_P(ResponseCases, BodiesInABoxStayInside) {
  auto scene = bundled("bodies_in_box");
  if (TypeParam::name != "traditional") scene.duration = 3.0;
  const core::Run run = core::simulate<TypeParam>(scene);
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_DOUBLE_EQ(run.samples.back().t, scene.duration);
  for (const auto& s : run.samples)
    for (std::size_t b = 6; b < s.bodies.size(); ++b)
      EXPECT_LT(body(s, b).position.cwiseAbs().maxCoeff(), 0.6) << scene.bodies[b].name << " at t=" << s.t;
  EXPECT_GT(run.counters.at("contacts"), 100u);
}

// fn 28: bodies overlapping at t = 0 are refused, naming the pair.
TYPED_TEST_P(ResponseCases, OverlapAtTheStartIsRefusedByName) {
  auto scene = bundled("cube_drop_flat");
  scene.bodies[1].position.z() = 0.05;
  try {
    core::simulate<TypeParam>(scene);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    const std::string what = e.what();
    EXPECT_NE(what.find("'slab' and 'cube' overlap at t = 0"), std::string::npos) << what;
  }
}

// The two time-of-impact searches find impacts in the band; Illinois on the
// separating-axis depth needs fewer state evaluations than bisection.
TYPED_TEST_P(ResponseCases, IllinoisNeedsFewerEvaluationsThanBisection) {
  auto scene = bundled("cube_drop_corner");
  scene.duration = 1.2;  // the impacts before it settles
  for (auto& e : scene.effects)
    if (auto* c = std::get_if<core::Collisions>(&e)) c->penetration_tolerance = 1e-7;
  std::map<core::TimeOfImpact, core::Run> runs;
  for (const auto m : {core::TimeOfImpact::bisection, core::TimeOfImpact::illinois}) {
    for (auto& e : scene.effects)
      if (auto* c = std::get_if<core::Collisions>(&e)) c->time_of_impact = m;
    runs[m] = core::simulate<TypeParam>(scene);
    ASSERT_FALSE(runs[m].error) << *runs[m].error;
    EXPECT_GT(runs[m].counters.at("impact_searches"), 0u);
    EXPECT_EQ(runs[m].counters.at("impact_searches_unresolved"), 0u);
  }
  const auto per_search = [](const core::Run& r) {
    return double(r.counters.at("impact_iterations")) / double(r.counters.at("impact_searches"));
  };
  EXPECT_LT(per_search(runs[core::TimeOfImpact::illinois]), per_search(runs[core::TimeOfImpact::bisection]));
}

// Every time-of-impact search (core/collision/time_of_impact.hpp) with either motion
// gives the flat drop's bounces: apexes falling by ε² to 1 % (as
// FlatDropBouncesByEpsilonSquaredAndRests says why), no unresolved search, no
// sinking below the tolerance. Either motion integrates the island once per
// search found (to the time found; fixed-step RK4 moves the pair's bodies
// alone as in the island, so the check there never misses), and the
// interpolated motion integrates no body for most of its trials: with
// bisection or golden section it integrates fewer bodies per search.
TYPED_TEST_P(ResponseCases, EveryImpactSearchAndMotionGivesTheFlatDropsBounces) {
  auto scene = bundled("cube_drop_flat");
  scene.duration = 1.5;
  std::map<std::pair<core::TimeOfImpact, core::ImpactMotion>, double> per_search;
  for (const auto m : {core::TimeOfImpact::bisection, core::TimeOfImpact::illinois, core::TimeOfImpact::golden_section,
                       core::TimeOfImpact::conservative_advancement})
    for (const auto motion : {core::ImpactMotion::integrate, core::ImpactMotion::interpolate}) {
      for (auto& e : scene.effects)
        if (auto* c = std::get_if<core::Collisions>(&e)) c->time_of_impact = m, c->impact_motion = motion;
      const core::Run run = core::simulate<TypeParam>(scene);
      const std::string what = std::to_string(static_cast<int>(m)) + "/" + std::to_string(static_cast<int>(motion));
      ASSERT_FALSE(run.error) << what << ": " << *run.error;
      const auto up = apexes(run, 1);
      ASSERT_GE(up.size(), 2u) << what;
      EXPECT_NEAR((up[0] - 0.1) / (1.1 - 0.1), 0.25, 0.0025) << what;
      EXPECT_NEAR((up[1] - 0.1) / (up[0] - 0.1), 0.25, 0.0025) << what;
      for (const auto& smp : run.samples) EXPECT_GT(body(smp, 1).position.z(), 0.1 - 1e-4) << what << " t=" << smp.t;
      EXPECT_GT(run.counters.at("impact_searches"), 0u) << what;
      EXPECT_EQ(run.counters.at("impact_searches_unresolved"), 0u) << what;
      EXPECT_EQ(run.counters.at("impact_island_misses"), 0u) << what;
      EXPECT_EQ(run.counters.at("impact_state_evaluations"), run.counters.at("impact_searches")) << what;
      per_search[{m, motion}] =
          double(run.counters.at("impact_bodies_integrated")) / double(run.counters.at("impact_searches"));
      if (motion == core::ImpactMotion::interpolate) {
        EXPECT_GT(run.counters.at("impact_interpolated_evaluations"), 0u) << what;
      }
    }
  for (const auto m : {core::TimeOfImpact::bisection, core::TimeOfImpact::golden_section})
    EXPECT_LT(per_search[std::pair(m, core::ImpactMotion::interpolate)],
              per_search[std::pair(m, core::ImpactMotion::integrate)]);
  // Two bodies (the cube and the slab) once per search, and at most a check
  // of the interpolated time on the pair's own motion.
  EXPECT_LE(per_search[std::pair(core::TimeOfImpact::bisection, core::ImpactMotion::interpolate)], 4.0);
}

// Far from the origin: the same scene moved by D along
// (1, 1, 1), D = 1e3 … 1e9 m. A coordinate of size D is stored to D·1.1e-16,
// so moving a scene perturbs every position update by that much.
// - The flat drop is not sensitive to such perturbations: it follows its
//   trajectory at the origin, relative to the slab, to 1e-13·D (450 ulps of D:
//   1e-4 m at 1e9, measured 2.4e-5 m in both backends; 1e-10 m at 1e3,
//   measured 6e-13).
// - The corner drop tips over an edge, which amplifies any perturbation (the
//   two backends' rounding differences alone grow to 2e-9 m at the origin):
//   its trajectory is not the test; that it lands, never sinks deeper than the
//   penetration tolerance and comes to rest flat on the slab at every D is.
// Before, the cga broadphase held conformal spheres in world coordinates
// (½|c|² beside c) and from 1e5 m the cube fell through the slab.
TYPED_TEST_P(ResponseCases, FarFromTheOriginGivesTheAnswersAtTheOrigin) {
  const double tol = 1e-4, rest = 0.1;  // the scenes' penetration tolerance; slab top 0 + half the cube
  for (const char* name : {"cube_drop_flat", "cube_drop_corner"}) {
    const auto scene = bundled(name);
    const bool follows = std::string(name) == "cube_drop_flat";
    const core::Run at_origin = core::simulate<TypeParam>(scene);
    ASSERT_FALSE(at_origin.error) << *at_origin.error;
    for (const double d : {1e3, 1e5, 1e7, 1e9}) {
      core::Scene moved = scene;
      for (auto& b : moved.bodies) b.position += Eigen::Vector3d::Constant(d);
      const core::Run run = core::simulate<TypeParam>(moved);
      ASSERT_FALSE(run.error) << name << " at " << d << ": " << *run.error;
      ASSERT_EQ(run.samples.size(), at_origin.samples.size());
      double worst = 0;
      for (std::size_t k = 0; k < run.samples.size(); ++k) {
        const auto &a = run.samples[k], &o = at_origin.samples[k];
        const Eigen::Vector3d rel = body(a, 1).position - body(a, 0).position;
        worst = std::max(worst, (rel - (body(o, 1).position - body(o, 0).position)).norm());
        // The slab's top is at z = 0 relative to its centre + 0.1; the cube's
        // lowest point is at least its centre − 0.1·√3 (a corner).
        EXPECT_GT(rel.z() + 0.1, -tol - 0.1 * std::sqrt(3.0)) << name << " moved " << d << " fell through at t=" << a.t;
      }
      if (follows) {
        EXPECT_LT(worst, 1e-13 * d) << name << " moved " << d << " m";
      }
      const auto& end = run.samples.back();
      const Eigen::Vector3d rel = body(end, 1).position - body(end, 0).position;
      EXPECT_NEAR(rel.z() - 0.1, rest, tol) << name << " moved " << d << " m: not resting on the slab";
      EXPECT_LT(body(end, 1).velocity.norm(), 1e-6) << name << " moved " << d << " m: not at rest";
    }
  }
}

// Every broadphase (core/collision/broadphase.hpp: sort and sweep, the AABB
// tree, the sphere tree) finds the same pairs, so gives the same run, number
// for number: the 27 bodies in a box for 0.5 s (chaotic: any difference in a
// pair would part the runs), and the flat drop 1e7 m from the origin, where
// the frame the trees keep matters. Only the counters differ: the sweep
// inserts nothing, the trees insert every body once and then only those that
// left their fat volumes.
TYPED_TEST_P(ResponseCases, EveryBroadphaseGivesTheSameRun) {
  for (const auto& [name, offset] : {std::pair{"bodies_in_box", 0.0}, std::pair{"cube_drop_flat", 1e7}}) {
    auto scene = bundled(name);
    scene.duration = 0.5;
    for (auto& b : scene.bodies) b.position += Eigen::Vector3d::Constant(offset);
    std::vector<core::Run> runs;
    for (const auto m : {core::BroadphaseMethod::sweep, core::BroadphaseMethod::aabb_tree,
                         core::BroadphaseMethod::sphere_tree}) {
      auto with = scene;
      for (auto& e : with.effects)
        if (auto* c = std::get_if<core::Collisions>(&e)) c->broadphase = m;
      runs.push_back(core::simulate<TypeParam>(with));
      ASSERT_FALSE(runs.back().error) << *runs.back().error;
    }
    const auto& sweep = runs[0];
    EXPECT_EQ(sweep.counters.at("broadphase_tree_updates"), 0u);
    for (std::size_t k = 1; k < runs.size(); ++k) {
      const auto& r = runs[k];
      ASSERT_EQ(r.samples.size(), sweep.samples.size());
      for (std::size_t i = 0; i < r.samples.size(); ++i)
        for (std::size_t b = 0; b < r.samples[i].bodies.size(); ++b) {
          const auto &x = body(r.samples[i], b), &y = body(sweep.samples[i], b);
          ASSERT_TRUE(x.position == y.position && x.orientation == y.orientation && x.velocity == y.velocity &&
                      x.angular_velocity == y.angular_velocity)
              << name << " method " << k << " body " << b << " t=" << r.samples[i].t;
        }
      EXPECT_EQ(r.counters.at("narrowphase_pairs"), sweep.counters.at("narrowphase_pairs")) << name;
      EXPECT_GE(r.counters.at("broadphase_tree_updates"), scene.bodies.size()) << name;
      EXPECT_LT(r.counters.at("broadphase_tree_updates"), r.counters.at("collision_steps") * scene.bodies.size() / 2)
          << name;
    }
  }
}

REGISTER_TYPED_TEST_SUITE_P(ResponseCases, FlatDropBouncesByEpsilonSquaredAndRests, EdgeAndCornerDropsComeToRestFlat,
                            ElasticImpactConservesEnergyAndMomenta, EdgeEdgeImpulseAlongTheCommonNormal,
                            CubeBouncesOffThePyramidsPoint, BodiesInABoxStayInside, OverlapAtTheStartIsRefusedByName,
                            IllinoisNeedsFewerEvaluationsThanBisection, EveryImpactSearchAndMotionGivesTheFlatDropsBounces,
                            FarFromTheOriginGivesTheAnswersAtTheOrigin, EveryBroadphaseGivesTheSameRun);

}  // namespace gacompare::testing
