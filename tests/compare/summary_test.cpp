// The summary's rules (compare/summary.hpp) against answers computed by hand:
// categories, agreement tolerances, runs compared per unit of work, the
// time-weighted aggregate per category, the pairs of backends compared and
// summary.json.
#include "compare/summary.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace gacompare;
using namespace gacompare::compare;

namespace {

// Times are sums and quotients of a few doubles: 1e-12 relative covers their rounding.
constexpr double kRounding = 1e-12;

}  // namespace

TEST(Summary, CategoriesFromTheScene) {
  core::Scene s;
  EXPECT_EQ(category_of(s), Category::particles);
  s.bodies.push_back({});
  EXPECT_EQ(category_of(s), Category::rigid_bodies);
  s.effects.push_back(core::Collisions{});
  EXPECT_EQ(category_of(s), Category::collisions);
  EXPECT_FALSE(is_evidence(Category::particles));
  EXPECT_TRUE(is_evidence(Category::rigid_bodies));
}

TEST(Summary, AgreementToleranceIsTheCheckCappedByThePenetrationTolerance) {
  core::Scene s;
  EXPECT_EQ(agreement_tolerance(s).metres, 1e-6);  // CheckSpec's default
  s.check.max_divergence = 1.3;                     // bodies_in_box: "bounded by the box"
  EXPECT_EQ(agreement_tolerance(s).metres, 1.3);    // no contacts: the check is the tolerance
  core::Collisions c;
  c.penetration_tolerance = 1e-4;
  s.effects.push_back(c);
  EXPECT_EQ(agreement_tolerance(s).metres, 1e-4);
  EXPECT_EQ(agreement_tolerance(s).source, "penetration tolerance");
  s.check.max_divergence = 1e-6;
  EXPECT_EQ(agreement_tolerance(s).metres, 1e-6);
  EXPECT_EQ(agreement_tolerance(s).source, "check.max_divergence");
}

TEST(Summary, TrajectoriesAgainstTheTolerance) {
  EXPECT_EQ(classify(0, 0, 0), Trajectories::identical);
  EXPECT_EQ(classify(0, 1e-9, 0.2), Trajectories::agree);
  EXPECT_EQ(classify(1e-4, 0, 1.0), Trajectories::agree);
  EXPECT_EQ(classify(1.19, 3.1, 1e4), Trajectories::parted);
  EXPECT_EQ(classify(NAN, 0, NAN), Trajectories::parted);
  EXPECT_STREQ(to_string(Trajectories::parted), "parted (chaotic)");
  EXPECT_STREQ(to_string(Trajectories::agree), "within tolerance");
}

TEST(Summary, ToleranceUsedBoundsPositionsAndOrientationsAsCheckDoes) {
  // A particle and a 2 × 2 × 2 m box (radius √3 m, its corners) and a static
  // slab. Sample 1: the particle 3e-7 m apart, the box turned by 4e-7 rad
  // about z in cga (r θ = 6.93e-7 m), its centre 1e-7 m apart; sample 2: the
  // slab's orientation wildly apart (static bodies are left out, as in check).
  // Used: max(3e-7, max(1e-7, √3 · 4e-7)) / 1e-6 = 0.6928.
  SceneResult r;
  r.scene.particles.push_back({});
  core::Body box, slab;
  box.shape = core::BoxShape{{2, 2, 2}};
  slab.shape = core::BoxShape{{4, 4, 1}};
  slab.is_static = true;
  box.mass = slab.mass = 1;
  r.scene.bodies = {box, slab};
  r.model = std::make_shared<const core::Model>(core::compile(r.scene));
  core::Sample a;
  a.particles.resize(1);
  a.bodies.resize(2);
  core::Sample b = a;
  b.particles[0].position.x() = 3e-7;
  b.bodies[0].position.y() = 1e-7;
  const double half = 2e-7;  // half the angle
  b.bodies[0].orientation = {std::cos(half), 0, 0, std::sin(half)};
  core::Sample c = a, d = a;
  d.bodies[1].orientation = {0, 1, 0, 0};
  for (const char* name : {"traditional", "cga"}) {
    BackendResult br;
    br.run.backend = name;
    br.run.samples = name == std::string("cga") ? std::vector<core::Sample>{b, d} : std::vector<core::Sample>{a, c};
    r.backends.push_back(br);
  }
  // Tolerance: the rotation angle is exact to ~1e-16 rad (compare/metrics.hpp).
  EXPECT_NEAR(tolerance_used(r, kPairs[0], 1e-6), std::sqrt(3.0) * 4e-7 / 1e-6, 1e-9);
  r.backends[1].run.samples[0].bodies[0].orientation = {1, 0, 0, 0};
  EXPECT_NEAR(tolerance_used(r, kPairs[0], 1e-6), 0.3, 1e-9);  // the particle's 3e-7 m
  EXPECT_EQ(tolerance_used(r, {"pga", "traditional"}, 1e-6), 0);  // no pga run
}

namespace {
// A collision scene at two stages, two repeats (too few for an interval: the
// ratios below have none): narrowphase (trad 100 pairs,
// cga 200) and response (trad 10 impulses, cga 5).
SceneSummary two_stage_scene(Trajectories t) {
  SceneSummary s;
  s.name = "box";
  s.category = Category::collisions;
  s.trajectories = t;
  s.stages.push_back({core::Stage::narrowphase, {{4, 4}, {1, 1}}, "narrowphase pair", 200, 100});
  s.stages.push_back({core::Stage::response, {{1, 5}, {2, 2}}, "impulse", 5, 10});
  return s;
}
}  // namespace

TEST(Summary, PartedRunsAreComparedPerUnitOfWork) {
  // Per unit of work: narrowphase cga 4 s × 100/200 = 2 s against 1 s (2);
  // response cga (1, 5) × 10/5 = (2, 10) against 2 s (mean 6 over 2: 3). All
  // stages: cga (4, 12) against (3, 3): 8/3. As measured: narrowphase 4,
  // response 3/2, all stages (5, 9) against (3, 3): 7/3.
  const SceneSummary parted = two_stage_scene(Trajectories::parted);
  EXPECT_EQ(per_unit_of_work(parted.stages[0]).numerator, (std::vector<double>{2, 2}));
  EXPECT_NEAR(scene_ratio(parted, core::Stage::narrowphase).ratio, 2.0, kRounding);
  EXPECT_NEAR(scene_ratio(parted, core::Stage::response).ratio, 3.0, kRounding);
  EXPECT_EQ(compared_seconds(parted, std::nullopt).numerator, (std::vector<double>{4, 12}));
  EXPECT_NEAR(scene_ratio(parted, std::nullopt).ratio, 8.0 / 3.0, kRounding);
  EXPECT_NEAR(scene_ratio(parted, std::nullopt, true).ratio, 7.0 / 3.0, kRounding);  // as measured

  const SceneSummary agreed = two_stage_scene(Trajectories::agree);
  EXPECT_NEAR(scene_ratio(agreed, core::Stage::narrowphase).ratio, 4.0, kRounding);
  EXPECT_NEAR(scene_ratio(agreed, core::Stage::response).ratio, 1.5, kRounding);
  EXPECT_EQ(compared_seconds(agreed, std::nullopt).numerator, (std::vector<double>{5, 9}));
  EXPECT_NEAR(scene_ratio(agreed, std::nullopt).ratio, 7.0 / 3.0, kRounding);

  EXPECT_TRUE(std::isnan(scene_ratio(parted, std::nullopt).lo));  // 2 repeats: no interval
  EXPECT_EQ(speed_verdict(scene_ratio(parted, std::nullopt)), Speed::unknown);

  // At equal accuracy (compare --accuracy) the work differs by design: as measured.
  const SceneSummary own = two_stage_scene(Trajectories::own_settings);
  EXPECT_NEAR(scene_ratio(own, std::nullopt).ratio, 7.0 / 3.0, kRounding);

  SceneSummary unrun = two_stage_scene(Trajectories::not_compared);
  EXPECT_EQ(compared_seconds(unrun, std::nullopt).pairs(), 0u);
}

TEST(Summary, AggregateIsPerCategoryAndTimeWeighted) {
  // Two collision scenes and a particle scene: the collision aggregate at all
  // stages is the mean cga (5 + 9)/2 + 1 = 8 over 3 + 1 = 4: 2, where the
  // scenes' own ratios are 7/3 and 1; the particle scene stays out.
  std::vector<SceneSummary> scenes = {two_stage_scene(Trajectories::agree), two_stage_scene(Trajectories::agree)};
  scenes[1].stages = {{core::Stage::narrowphase, {{1, 1}, {1, 1}}, "narrowphase pair", 1, 1}};
  SceneSummary particles;
  particles.category = Category::particles;
  particles.trajectories = Trajectories::identical;
  particles.stages = {{core::Stage::forces, {{50, 50}, {1, 1}}, "derivative evaluation", 1, 1}};
  scenes.push_back(particles);
  const Aggregate a = aggregate(scenes, Category::collisions, std::nullopt);
  EXPECT_EQ(a.scenes, 2);
  EXPECT_NEAR(a.numerator_seconds, 8.0, kRounding);
  EXPECT_NEAR(a.denominator_seconds, 4.0, kRounding);
  EXPECT_NEAR(a.ratio.ratio, 2.0, kRounding);
  const Aggregate n = aggregate(scenes, Category::collisions, core::Stage::narrowphase);
  EXPECT_NEAR(n.ratio.ratio, 5.0 / 2.0, kRounding);  // (4 + 1) over (1 + 1)
  EXPECT_EQ(aggregate(scenes, Category::rigid_bodies, std::nullopt).scenes, 0);
  EXPECT_EQ(aggregate(scenes, Category::particles, std::nullopt).verdict, Speed::unknown);  // 2 repeats

  const nlohmann::ordered_json j = summary_json({{kPairs[0], scenes}}, MachineInfo{}, 2);
  EXPECT_EQ(j["method"]["resamples"], kBootstrapResamples);
  EXPECT_NEAR(j["categories"]["collisions"]["overall"]["ratio"].get<double>(), 2.0, kRounding);
  EXPECT_EQ(j["categories"]["collisions"]["overall"]["ci95"].size(), 2u);  // [null, null]: 2 repeats
  EXPECT_EQ(j["categories"]["collisions"]["overall"]["verdict"], "no verdict");
  EXPECT_TRUE(j["categories"]["collisions"]["evidence"].get<bool>());
  EXPECT_FALSE(j["categories"]["particles"]["evidence"].get<bool>());
  EXPECT_FALSE(j["categories"].contains("rigid bodies"));
  EXPECT_NEAR(j["categories"]["collisions"]["overall"]["cga_seconds"].get<double>(), 8.0, kRounding);
  EXPECT_NEAR(j["categories"]["collisions"]["overall"]["traditional_seconds"].get<double>(), 4.0, kRounding);
  EXPECT_TRUE(j["pairs"].empty());  // cga / traditional alone
}

TEST(Summary, APartedSceneIsLeftOutOfItsCategory) {
  // A scene that agreed (ratio 7/3 as measured) and one that parted: the
  // category's ratio is the agreeing scene's alone, at every stage, and the
  // parted one is counted and named as left out, keeping its own ratio.
  std::vector<SceneSummary> scenes = {two_stage_scene(Trajectories::agree), two_stage_scene(Trajectories::parted)};
  scenes[1].name = "pile";
  for (auto& st : scenes[1].stages)
    for (double& x : st.seconds.numerator) x *= 10;  // a pile ten times dearer changes nothing
  const Aggregate a = aggregate(scenes, Category::collisions, std::nullopt);
  EXPECT_EQ(a.scenes, 1);
  EXPECT_EQ(a.parted, 1);
  EXPECT_NEAR(a.ratio.ratio, 7.0 / 3.0, kRounding);
  EXPECT_NEAR(aggregate(scenes, Category::collisions, core::Stage::narrowphase).ratio.ratio, 4.0, kRounding);
  EXPECT_NEAR(scene_ratio(scenes[1], std::nullopt).ratio, 80.0 / 3.0, kRounding);  // its own, per unit of work

  const nlohmann::ordered_json j = summary_json({{kPairs[0], scenes}}, MachineInfo{}, 2);
  const auto& c = j["categories"]["collisions"];
  EXPECT_EQ(c["scenes"], nlohmann::ordered_json::array({"box"}));
  EXPECT_EQ(c["parted"], nlohmann::ordered_json::array({"pile"}));
  EXPECT_EQ(c["overall"]["scenes"], 1);
  EXPECT_EQ(c["overall"]["parted_left_out"], 1);
  EXPECT_NEAR(c["overall"]["ratio"].get<double>(), 7.0 / 3.0, kRounding);

  // Every scene parted: no ratio and no verdict, and the category still says why.
  const std::vector<SceneSummary> only = {scenes[1]};
  const Aggregate none = aggregate(only, Category::collisions, std::nullopt);
  EXPECT_EQ(none.scenes, 0);
  EXPECT_EQ(none.parted, 1);
  EXPECT_EQ(none.verdict, Speed::unknown);
  const nlohmann::ordered_json k = summary_json({{kPairs[0], only}}, MachineInfo{}, 2);
  EXPECT_EQ(k["categories"]["collisions"]["overall"]["scenes"], 0);
  EXPECT_EQ(k["categories"]["collisions"]["parted"], nlohmann::ordered_json::array({"pile"}));
}

TEST(Summary, AnIntervalFromFiveRepeats) {
  // Five repeats at ratio 2 exactly: interval [2, 2], "cga slower". Four: none.
  SceneSummary s;
  s.category = Category::rigid_bodies;
  s.trajectories = Trajectories::agree;
  s.stages = {{core::Stage::forces, {{2, 4, 6, 8, 10}, {1, 2, 3, 4, 5}}, "derivative evaluation", 1, 1}};
  EXPECT_EQ(scene_ratio(s, std::nullopt).lo, 2.0);
  EXPECT_EQ(aggregate({s}, Category::rigid_bodies, std::nullopt).verdict, Speed::slower);
  s.stages[0].seconds.numerator.pop_back();
  EXPECT_TRUE(std::isnan(scene_ratio(s, std::nullopt).hi));
  EXPECT_EQ(aggregate({s}, Category::rigid_bodies, std::nullopt).verdict, Speed::unknown);
}

TEST(Summary, EveryPairHasTheShapeOfCgaOverTraditional) {
  // pga / traditional over the five repeats above at ratio 3, and the box
  // parted: its work keys and seconds keys name pga and traditional, its
  // verdict pga's. cga / traditional stays at the top level, its keys as ever.
  SceneSummary fast;
  fast.category = Category::rigid_bodies;
  fast.trajectories = Trajectories::agree;
  fast.stages = {{core::Stage::forces, {{2, 4, 6, 8, 10}, {1, 2, 3, 4, 5}}, "derivative evaluation", 1, 1}};
  const BackendPair pga{"pga", "traditional"};
  SceneSummary slow = fast;
  slow.pair = pga;
  for (double& x : slow.stages[0].seconds.numerator) x *= 1.5;
  SceneSummary parted = two_stage_scene(Trajectories::parted);
  parted.pair = pga;
  const nlohmann::ordered_json j =
      summary_json({{pga, {slow, parted}}, {kPairs[0], {fast, two_stage_scene(Trajectories::agree)}}}, MachineInfo{}, 5);
  EXPECT_EQ(j["categories"]["rigid bodies"]["overall"]["verdict"], "cga slower");  // the top level: cga, wherever given
  EXPECT_TRUE(j["categories"]["rigid bodies"]["overall"].contains("cga_seconds"));
  ASSERT_EQ(j["pairs"].size(), 1u);
  const auto& p = j["pairs"][0];
  EXPECT_EQ(p["numerator"], "pga");
  EXPECT_EQ(p["denominator"], "traditional");
  const auto& overall = p["categories"]["rigid bodies"]["overall"];
  EXPECT_NEAR(overall["ratio"].get<double>(), 3.0, kRounding);
  EXPECT_EQ(overall["verdict"], "pga slower");
  EXPECT_NEAR(overall["pga_seconds"].get<double>(), 9.0, kRounding);  // mean of 3, 6, 9, 12, 15
  EXPECT_NEAR(overall["traditional_seconds"].get<double>(), 3.0, kRounding);
  EXPECT_FALSE(overall.contains("cga_seconds"));
  ASSERT_EQ(p["scenes"].size(), 2u);
  EXPECT_EQ(p["scenes"][1]["compared"], "per unit of work");
  EXPECT_EQ(p["scenes"][1]["work"]["narrowphase"]["pga"], 200);
  EXPECT_EQ(p["scenes"][1]["work"]["narrowphase"]["traditional"], 100);
  EXPECT_NEAR(p["scenes"][1]["ratio"].get<double>(), 8.0 / 3.0, kRounding);  // as for cga above
}

TEST(Summary, PairsThatRan) {
  // Which pairs a set of results holds, and their backends in order.
  const auto ran = [](std::initializer_list<const char*> names) {
    SceneResult r;
    for (const char* name : names) {
      r.backends.emplace_back();
      r.backends.back().run.backend = name;
    }
    return r;
  };
  const SceneResult two = ran({"traditional", "cga"}), three = ran({"traditional", "pga", "bullet"});
  const BackendPair pga_trad{"pga", "traditional"}, pga_cga{"pga", "cga"};
  EXPECT_EQ(pairs_present(std::span(&two, 1)), (std::vector<BackendPair>{kPairs[0]}));
  EXPECT_EQ(pairs_present(std::span(&three, 1)), (std::vector<BackendPair>{pga_trad}));
  const std::vector<SceneResult> both = {two, three};
  EXPECT_EQ(pairs_present(both), (std::vector<BackendPair>{kPairs[0], pga_trad}));  // pga and cga never met
  // In known_backends() order, each representation of the traditional backend beside it.
  EXPECT_EQ(backends_of(kPairs), (std::vector<std::string_view>{"traditional", "traditional-matrix",
                                                                 "traditional-quaternion", "cga", "pga"}));
  const std::vector<SceneResult> twin = {ran({"traditional", "traditional-quaternion", "cga"})};
  EXPECT_EQ(pairs_present(twin), (std::vector<BackendPair>{kPairs[0], {"cga", "traditional-quaternion"}}));
  EXPECT_EQ(pga_cga.label(), "pga / cga");
}
