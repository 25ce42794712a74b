// `compare --accuracy` (compare/accuracy.hpp): the ladder + log-space bisection
// search on synthetic monotone error functions with a known answer, and the
// whole search on the spinning top cut to 0.5 s: the setting found reaches the
// target (checked by running it again against an independent reference), and a
// second search reads the cache instead of running anything.
#include "compare/accuracy.hpp"

#include "compare/runner.hpp"
#include "core/model/generators.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace gacompare::compare {
namespace {

// error = c · tol^p: reaches E at tol* = (E / c)^(1/p). The ladder's decades
// bracket tol*, four bisections narrow the bracket to a factor 10^(1/16), and
// the setting kept is the loosest that reaches E: in (tol*/10^(1/16), tol*].
TEST(SearchLadder, FindsTheLoosestToleranceThatReachesTheTarget) {
  for (const double c : {1.0, 37.0, 0.01})
    for (const double target : {1e-5, 3e-7, 2e-9}) {
      const double p = 0.9;
      const double star = std::pow(target / c, 1 / p);
      const SearchResult r = search_ladder(tolerance_ladder(), [&](double t) { return c * std::pow(t, p); }, target, 4);
      ASSERT_TRUE(r.found) << c << " " << target;
      EXPECT_LE(r.error, target);
      EXPECT_LE(r.setting, star * (1 + 1e-12));
      EXPECT_GT(r.setting, star / std::pow(10.0, 1.0 / 16) * (1 - 1e-12));
      // The trials: decades up to the first that reaches, then exactly four bisections.
      const std::size_t rungs = static_cast<std::size_t>(std::ceil(-std::log10(star) - 1e-12)) - 2;
      EXPECT_EQ(r.trials.size(), rungs + 4) << c << " " << target;
    }
}

TEST(SearchLadder, HalvesTheStepAndRefusesWhatItCannotReach) {
  // Second order in dt: error = dt^2 reaches 1e-8 at dt = 1e-4; from 1e-2, halvings
  // bracket it between 1.5625e-4 and 7.8125e-5.
  const SearchResult r = search_ladder(step_ladder(1e-2), [](double dt) { return dt * dt; }, 1e-8, 4);
  ASSERT_TRUE(r.found);
  EXPECT_LE(r.error, 1e-8);
  EXPECT_LE(r.setting, 1e-4 * (1 + 1e-12));
  EXPECT_GT(r.setting, 1e-4 / std::pow(2.0, 1.0 / 16));
  EXPECT_EQ(step_ladder(1e-2).size(), 17u);
  EXPECT_DOUBLE_EQ(step_ladder(1e-2).back(), 1e-2 / 65536);
  // A floor above the target: every rung tried, none found.
  const SearchResult never = search_ladder(step_ladder(1e-2), [](double dt) { return 1e-6 + dt; }, 1e-8, 4);
  EXPECT_FALSE(never.found);
  EXPECT_EQ(never.trials.size(), 17u);
  // NaN (a failed run) is never "reached"; the first rung already reaching stops at once.
  const SearchResult nan = search_ladder(tolerance_ladder(), [](double) { return NAN; }, 1, 4);
  EXPECT_FALSE(nan.found);
  const SearchResult first = search_ladder(tolerance_ladder(), [](double) { return 0.0; }, 1e-9, 4);
  ASSERT_TRUE(first.found);
  EXPECT_EQ(first.setting, 1e-3);
  EXPECT_EQ(first.trials.size(), 1u);
}

TEST(EqualAccuracy, SpinningTopReachesTheTargetAndReusesTheCache) {
  core::Scene scene = core::load_scene(std::string(GACOMPARE_DATA_DIR) + "/scenes/spinning_top.json");
  scene.duration = 0.5;
  const double target = 1e-6;  // rad
  const auto dir = std::filesystem::temp_directory_path() / ("gacompare-accuracy-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto cache = dir / "accuracy.json";

  const AccuracyPlan plan = find_equal_accuracy(scene, target, {"traditional", "cga"}, cache);
  EXPECT_FALSE(plan.reused);
  EXPECT_EQ(plan.measure, Measure::orientation);
  ASSERT_EQ(plan.backends.size(), 2u);
  ASSERT_TRUE(std::filesystem::exists(cache));

  // Independently: run each setting found and measure against a reference at
  // 1e-14 computed here.
  core::Scene ref_scene = accuracy_scene(scene);
  ref_scene.solver.abs_tol = ref_scene.solver.rel_tol = 1e-14;
  const core::Run ref = run_backend(ref_scene, "traditional");
  for (const auto& s : plan.backends) {
    EXPECT_LE(s.error, target) << s.backend;
    EXPECT_GT(s.spec.abs_tol, 1e-13) << s.backend;
    EXPECT_GT(s.steps, 0u) << s.backend;
    core::Scene run_scene = accuracy_scene(scene);
    run_scene.solver = s.spec;
    const core::Run run = run_backend(run_scene, s.backend);
    const double e = state_difference(run.samples.back(), ref.samples.back())[Measure::orientation];
    EXPECT_LE(e, target) << s.backend;
    EXPECT_DOUBLE_EQ(e, s.error) << s.backend;
    EXPECT_EQ(run.solver.steps_accepted, s.steps) << s.backend;
  }

  // Rerun: read from the cache, the same settings.
  const auto written = std::filesystem::last_write_time(cache);
  const AccuracyPlan again = find_equal_accuracy(scene, target, {"traditional", "cga"}, cache);
  EXPECT_TRUE(again.reused);
  ASSERT_EQ(again.backends.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(again.backends[k].spec.abs_tol, plan.backends[k].spec.abs_tol);
    EXPECT_EQ(again.backends[k].error, plan.backends[k].error);
    EXPECT_EQ(again.backends[k].steps, plan.backends[k].steps);
  }
  EXPECT_EQ(std::filesystem::last_write_time(cache), written);
  // Another target is another search.
  EXPECT_FALSE(find_equal_accuracy(scene, 1e-4, {"traditional"}, cache).reused);

  // Timed at the settings found, with the section saying the settings differ.
  const SceneResult timed = compare_at_accuracy(scene, plan, 1);
  const std::string md = accuracy_section_md(plan, timed);
  EXPECT_NE(md.find("settings differ per backend"), std::string::npos) << md;
  EXPECT_NE(md.find("| cga |"), std::string::npos) << md;
  std::filesystem::remove_all(dir);
}

// The Lie-group methods are searched like the others: rkmk45 over its
// tolerances, rkmk4 and crouch_grossman4 over halved steps, in every backend,
// and each setting found reaches the target.
TEST(EqualAccuracy, LieGroupMethodsReachTheTarget) {
  const auto dir = std::filesystem::temp_directory_path() / ("gacompare-accuracy-lie-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  for (const auto method : {core::SolverMethod::rkmk45, core::SolverMethod::rkmk4, core::SolverMethod::crouch_grossman4}) {
    core::Scene scene = core::load_scene(std::string(GACOMPARE_DATA_DIR) + "/scenes/spinning_top.json");
    scene.duration = 0.5;
    scene.solver.method = method;
    const double target = 1e-9;  // rad: past the first rung of both ladders (1e-3, the scene's dt), so searched
    std::string file(core::to_string(method));
    file += ".json";
    const AccuracyPlan plan = find_equal_accuracy(scene, target, {"traditional", "cga", "pga"}, dir / file);
    EXPECT_EQ(plan.adaptive, method == core::SolverMethod::rkmk45);
    ASSERT_EQ(plan.backends.size(), 3u);
    for (const auto& s : plan.backends) {
      EXPECT_EQ(s.spec.method, method) << s.backend;
      EXPECT_LE(s.error, target) << core::to_string(method) << " " << s.backend;
      EXPECT_GT(s.steps, 0u) << s.backend;
      std::printf("%s %s: dt %.3g, tol %.3g, error %.2e in %llu steps\n", core::to_string(method).data(),
                  s.backend.c_str(), s.spec.dt, s.spec.abs_tol, s.error, static_cast<unsigned long long>(s.steps));
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(EqualAccuracy, RefusesASceneWithCollisions) {
  const core::Scene scene = core::load_scene(std::string(GACOMPARE_DATA_DIR) + "/scenes/cube_drop_flat.json");
  EXPECT_NE(accuracy_refusal(scene).find("collisions"), std::string::npos);
  EXPECT_THROW(find_equal_accuracy(scene, 1e-6, {"traditional"}, "/nonexistent/accuracy.json"), Error);
}

}  // namespace
}  // namespace gacompare::compare
