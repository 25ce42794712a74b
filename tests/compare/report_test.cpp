// The report's tables and figures (compare/report.cpp, report_html.cpp) on
// real runs: a stage a backend has not got reads "–", not "0 (0–0) 0%"; lines
// that coincide are said to; the stage bars carry min–max error bars; every
// pair of backends that ran gets its ratios, and only those.
#include "compare/plot.hpp"
#include "compare/report.hpp"
#include "compare/summary.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

using namespace gacompare;
using namespace gacompare::compare;

namespace {

const std::string kScenes = std::string(GACOMPARE_DATA_DIR) + "/scenes/";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The line of `text` that starts with `start` ("" when none does).
std::string line_of(const std::string& text, const std::string& start) {
  const auto at = text.find("\n" + start);
  return at == std::string::npos ? "" : text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

// Three backends on a rigid-body and a collision scene, once each: runs of a
// few milliseconds.
std::vector<SceneResult> three_backends(const std::vector<std::string>& backends) {
  std::vector<SceneResult> out;
  for (const char* scene : {"tumbling_box.json", "elastic_pair.json"})
    out.push_back(compare_scene(core::load_scene(kScenes + scene), backends, 1, Selection::exactly));
  return out;
}

}  // namespace

TEST(Report, AStageABackendHasNotGotIsADash) {
  // Bullet steps whole (its contacts inside its step, timed as integrate): no
  // narrowphase, broadphase, time of impact or response of its own.
  const SceneResult r =
      compare_scene(core::load_scene(kScenes + "cube_drop_flat.json"), {"traditional", "cga", "bullet"}, 1);
  const std::string md = scene_report_md(r, machine_info(), 1);
  EXPECT_NE(md.find("| `narrowphase` |"), std::string::npos) << md;
  const auto row = md.substr(md.find("| `narrowphase` |"), md.find('\n', md.find("| `narrowphase` |")) - md.find("| `narrowphase` |"));
  EXPECT_NE(row.find("| – | – | – |"), std::string::npos) << row;  // bullet's three cells
  EXPECT_EQ(md.find("0 (0–0)"), std::string::npos) << md;
  EXPECT_NE(md.find("A dash: the backend has no such stage"), std::string::npos);
}

TEST(Report, LinesThatCoincideAreSaidTo) {
  // Particles run the same formulas in both backends: bit-identical samples,
  // so every traditional and cga line of the pendulum's figures is one line.
  const SceneResult same = compare_scene(core::load_scene(kScenes + "pendulum.json"), {"traditional", "cga"}, 1);
  const std::string html = scene_report_html(same, machine_info(), 1);
  EXPECT_GE(count(html, "cga coincides with traditional at every point (drawn dashed over it)."), 2u);  // energy, constraint
  EXPECT_NE(html.find("cga (= traditional)"), std::string::npos);  // in the legend too
  // A tumbling box's rotor and matrix differ at rounding: no line coincides.
  const SceneResult apart = compare_scene(core::load_scene(kScenes + "tumbling_box.json"), {"traditional", "cga"}, 1);
  EXPECT_EQ(scene_report_html(apart, machine_info(), 1).find("coincides"), std::string::npos);
}

TEST(Report, StageBarsCarryErrorBars) {
  // The same bars with and without min–max: gnuplot draws each error bar as
  // a path of its own, so three bars with error bars add paths.
  Plot bars{"t", "stage", "s", false, false, {Series{"a", {0, 1, 2}, {1, 2, 3}, false}}, {"x", "y", "z"}};
  const std::string plain = render_svg(bars);
  bars.series[0].lo = {0.5, 1.5, 2.5};
  bars.series[0].hi = {1.5, 2.5, 3.5};
  const std::string with = render_svg(bars);
  EXPECT_GT(count(with, "<path"), count(plain, "<path"));
}

TEST(Report, EveryPairThatRanHasItsRatios) {
  const std::vector<SceneResult> results = three_backends({"traditional", "cga", "pga"});
  const std::string scene = scene_report_md(results[1], machine_info(), 1);
  EXPECT_NE(scene.find("ratios are cga/traditional, pga/traditional and pga/cga over paired repeats"),
            std::string::npos) << scene;
  const std::string head = line_of(scene, "| stage |");
  EXPECT_NE(head.find("| cga / traditional | pga / traditional | pga / cga |"), std::string::npos) << head;
  // Each row: the stage, three cells per backend, one per pair (the cells hold no '|').
  const std::string all = line_of(scene, "| **all stages** |");
  EXPECT_EQ(count(all, "|"), 1u + 1 + 3 * 3 + 3) << all;
  EXPECT_NE(scene.find("Largest distance between the cga and pga positions"), std::string::npos);

  const std::string md = summary_report_md(results, machine_info(), 1);
  for (const char* section : {"## cga / traditional by category and stage", "## pga / traditional by category and stage",
                              "## pga / cga by category and stage"})
    EXPECT_EQ(count(md, section), 1u) << section;
  EXPECT_NE(md.find("| category | stage | scenes | cga | pga | pga / cga [95% CI] | verdict |"), std::string::npos);
  // One column per backend in the times and energy tables; one row per scene and pair below them.
  EXPECT_EQ(count(md, "| scene | category | tolerance d (m) | traditional | cga | pga |"), 2u) << md;
  EXPECT_NE(md.find("| scene | pair | ratio [95% CI] | apart (m) | apart (rad) | trajectories |"), std::string::npos);
  for (const char* pair : {"| cga / traditional", "| pga / traditional", "| pga / cga"})
    EXPECT_GE(count(md, pair), results.size()) << pair;
  EXPECT_NE(md.find("Trajectories of pga against cga: "), std::string::npos);
  EXPECT_NE(md.find("compare `traditional/`, `cga/` and `pga/` side by side"), std::string::npos);

  // summary.json: pga over each of the others, with the ratio of the runs' own
  // totals (one repeat: the ratio is that of the repeat's times).
  const auto j = summary_json(summarise(results), machine_info(), 1);
  ASSERT_EQ(j["pairs"].size(), 2u);
  EXPECT_EQ(j["pairs"][1]["numerator"], "pga");
  EXPECT_EQ(j["pairs"][1]["denominator"], "cga");
  const auto total = [&](std::size_t scene, const char* backend) {
    for (const auto& b : results[scene].backends)
      if (b.run.backend == backend) return b.profiles.at(0).total_seconds();
    return 0.0;
  };
  for (std::size_t k = 0; k < results.size(); ++k) {
    const auto& s = j["pairs"][1]["scenes"][k];
    ASSERT_TRUE(s.contains("ratio")) << s;  // compared: the two algebras agree on these scenes
    EXPECT_NEAR(s["ratio"].get<double>(), total(k, "pga") / total(k, "cga"), 1e-12) << s;
    EXPECT_NEAR(j["scenes"][k]["ratio"].get<double>(), total(k, "cga") / total(k, "traditional"), 1e-12);
  }
  EXPECT_GT(j["pairs"][0]["categories"]["collisions"]["overall"]["pga_seconds"].get<double>(), 0);
}

TEST(Report, APairThatDidNotRunHasNoColumn) {
  const std::vector<SceneResult> two = three_backends({"traditional", "cga"});
  const std::string scene = scene_report_md(two[0], machine_info(), 1);
  EXPECT_NE(scene.find("ratios are cga/traditional over paired repeats"), std::string::npos) << scene;
  EXPECT_EQ(scene.find("pga"), std::string::npos) << scene;
  EXPECT_TRUE(summary_json(summarise(two), machine_info(), 1)["pairs"].empty());

  // Without cga, cga / traditional stays in summary.json's top level, not compared.
  const std::vector<SceneResult> no_cga = three_backends({"traditional", "pga"});
  const auto j = summary_json(summarise(no_cga), machine_info(), 1);
  EXPECT_EQ(j["scenes"][0]["not_compared"], "needs both traditional and cga");
  ASSERT_EQ(j["pairs"].size(), 1u);
  EXPECT_EQ(j["pairs"][0]["numerator"], "pga");
  EXPECT_EQ(j["pairs"][0]["scenes"][0]["trajectories"], "within tolerance");
  const std::string md = summary_report_md(no_cga, machine_info(), 1);
  EXPECT_EQ(md.find("## pga / cga"), std::string::npos);
  EXPECT_NE(md.find("## pga / traditional by category and stage"), std::string::npos);
}

// A rigid-body scene runs the traditional backend as a matrix and as a
// quaternion without a key in the scene; the verdict says which
// representations each ratio compares, and why each ratio is what it is: the
// product of the solver steps' ratio and the time per step's (read back from
// the runs' own counters).
TEST(Report, TheRigidBodyVerdictNamesItsRepresentationsAndItsReasons) {
  const core::Scene top = core::load_scene(kScenes + "spinning_top.json");
  std::vector<SceneResult> results = {compare_scene(top, {"traditional", "cga"}, 5)};
  ASSERT_EQ(results[0].backends.size(), 3u);
  EXPECT_EQ(results[0].backends[1].run.backend, "traditional-quaternion");
  const std::string md = summary_report_md(results, machine_info(), 5);
  EXPECT_NE(md.find("rotor against matrix (cga / traditional) "), std::string::npos) << md;
  EXPECT_NE(md.find("rotor against quaternion (cga / traditional-quaternion) "), std::string::npos) << md;
  const std::string why = line_of(md, "- rotor against quaternion (cga / traditional-quaternion): ");
  ASSERT_FALSE(why.empty()) << md;
  const auto steps = [&](const char* backend) {
    for (const auto& b : results[0].backends)
      if (b.run.backend == backend) return b.run.solver.steps_accepted + b.run.solver.steps_rejected;
    return std::uint64_t{0};
  };
  EXPECT_NE(why.find(std::to_string(steps("cga")) + " solver steps against " + std::to_string(steps("traditional-quaternion"))),
            std::string::npos) << why;
  // summary.json keeps the representations and the steps with each scene.
  const auto j = summary_json(summarise(results), machine_info(), 5);
  EXPECT_EQ(j["scenes"][0]["rotation"]["traditional"], "matrix");
  EXPECT_EQ(j["scenes"][0]["rotation"]["cga"], "rotor");
  ASSERT_EQ(j["pairs"][0]["denominator"], "traditional-quaternion");
  EXPECT_EQ(j["pairs"][0]["scenes"][0]["rotation"]["traditional-quaternion"], "quaternion");
  EXPECT_EQ(j["pairs"][0]["scenes"][0]["solver_steps"]["cga"], steps("cga"));
  // The twin is the traditional backend with the quaternion state: 13 numbers a body, not 18.
  const core::Run q = run_backend(top, "traditional-quaternion");
  EXPECT_EQ(q.backend, "traditional-quaternion");
  EXPECT_EQ(q.samples.back().bodies.size(), 1u);
  // Named exactly, no twin is added.
  EXPECT_EQ(compare_scene(top, {"traditional", "cga"}, 1, Selection::exactly).backends.size(), 2u);
}
