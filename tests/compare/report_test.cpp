// The report's tables and figures (compare/report.cpp, report_html.cpp) on
// real runs: a stage a backend has not got reads "–", not "0 (0–0) 0%"; lines
// that coincide are said to; the stage bars carry min–max error bars.
#include "compare/plot.hpp"
#include "compare/report.hpp"
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
